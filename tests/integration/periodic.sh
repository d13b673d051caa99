#!/usr/bin/env bash
# periodic.sh - sides = periodic end to end (docs/model.md, "Periodic side boundaries"):
# a short shaken scene with flux and field writes a valid file (h5dump reads it, the
# H5MD boxes say periodic in x, the walls are one bottom row closing on itself, the
# disks stay within a skin of [0, width), the observables are there); the
# sanitizer build and every kernel path of the release build give the same bits; a run stopped by SIGTERM and
# resumed from its checkpoint ends as the uninterrupted one; a LAMMPS data file of it
# has the period as its x box; too narrow a period and too wide an intruder are refused
# naming the keys; runs from the particle files (text, LAMMPS) written after settling
# are the run that settled.
# tier: slow: a shaken scene on every kernel path, stopped and resumed
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

W=24
tiny_bed n_grains=150 width=$W
SCENE=("${BEDARGS[@]}" duration=3
	"${GENTLE[@]}" sides=periodic flux=yes field=yes field_periods=4 snapshots=yes traj_rate=100 progress=no)

shake_run p.log "${SCENE[@]}" output=p.h5 write_lammps=p.data write_particles=p.txt
rc=$?
if [ $rc != 0 ]; then
	fail periodic.run "exit $rc: $(tail -n 3 p.log)"
	finish
fi
ok periodic.run
h5dump -H p.h5 >/dev/null 2>&1 && ok periodic.h5dump_reads || fail periodic.h5dump_reads "h5dump -H p.h5 failed"
[ "$(h5param p.h5 sides)" = periodic ] && ok periodic.parameter_echoed ||
	fail periodic.parameter_echoed "/parameters/sides = '$(h5param p.h5 sides)'"

# boundary attribute of each particle group's box: periodic for x, none for y
boundary() { h5dump -a "$2/box/boundary" "$1" 2>/dev/null | awk '/\(0\):/ { sub(/.*\(0\): */, ""); gsub(/[" ]/, ""); print; exit }'; }
for g in /particles/bed /particles/intruder /particles/walls; do
	b=$(boundary p.h5 $g)
	[ "$b" = periodic,none ] && ok "periodic.boundary$g" || fail "periodic.boundary$g" "boundary '$b', want periodic,none"
done
b=$(boundary p.h5 /particles/bed_xyz)
[ "$b" = periodic,none,none ] && ok periodic.boundary.bed_xyz || fail periodic.boundary.bed_xyz "boundary '$b'"
edges=$(h5vals p.h5 /particles/bed/box/edges | head -n 1)
[ "$edges" = "$W" ] && ok periodic.box_edges || fail periodic.box_edges "edges x '$edges', want $W"

# the walls: one bottom row (no side columns) spaced evenly round the period
h5vals p.h5 /particles/walls/position | paste -d' ' - - | awk -v W=$W '
	{ x[NR] = $1; if ($2 != -1) side++ } END {
		n = NR; d = W / n; bad = 0
		for (k = 1; k <= n; k++) if ((x[k] - (k - 0.5) * d)^2 > 1e-20) bad++
		if (side || bad || d > 2) { printf "FAIL periodic.walls_bottom_row: %d walls, %d off the floor, %d misplaced, spacing %g\n", n, side, bad, d; exit }
		printf "ok periodic.walls_bottom_row\n" }'

# every snapshot position within a skin (0.5 cm) of [0, W): wrapped at list builds
h5vals p.h5 /particles/bed/position/value | paste -d' ' - - | awk -v W=$W '
	$1 < lo || NR == 1 { lo = $1 } $1 > hi || NR == 1 { hi = $1 }
	END { if (lo > -0.5 && hi < W + 0.5) print "ok periodic.positions_in_period"
	      else printf "FAIL periodic.positions_in_period: x in [%g, %g]\n", lo, hi }'
# and the bed really crossed the seam: some disk is on either edge
h5vals p.h5 /final/x | awk -v W=$W '$1 < 2 { l++ } $1 > W - 2 { r++ } END {
	if (l && r) print "ok periodic.both_edges_occupied"; else printf "FAIL periodic.both_edges_occupied: %d left, %d right\n", l, r }'

# the observables: 12 periods of flux, 3 field blocks over ceil(W / cell) columns
nf=$(dims p.h5 /observables/flux/phi/value | cut -d' ' -f1)
[ "$nf" = 12 ] && ok periodic.flux_recorded || fail periodic.flux_recorded "flux rows '$nf', want 12"
fd=$(dims p.h5 /observables/field/count/value)
[ "$(echo "$fd" | cut -d' ' -f1)" = 3 ] && ok periodic.field_recorded || fail periodic.field_recorded "field dims '$fd'"
[ "$(attr p.h5 /status)" = ok ] && ok periodic.status_ok || fail periodic.status_ok "status '$(attr p.h5 /status)'"

# the LAMMPS data file: x box = the period, atoms inside it
awk -v W=$W '/xlo xhi/ { if ($1 == 0 && $2 == W) box = 1 } /^Atoms/ { on = 1; next } /^Velocities/ { on = 0 }
	on && NF == 7 { if ($5 < 0 || $5 >= W) out++ }
	END { if (box && !out) print "ok periodic.lammps_box"; else printf "FAIL periodic.lammps_box: box %d, %d atoms outside\n", box, out }' p.data
grep -q "boundary p f p" p.data && ok periodic.lammps_boundary_note || fail periodic.lammps_boundary_note "no 'boundary p f p' in the header"

# the same bits from every build
fin() { for d in /final/x /final/y /final/vx /final/omega /observables/flux/phi/value /observables/field/ux/value; do h5vals "$1" $d; done; }
fin p.h5 >ref.txt
[ "$(wc -l <ref.txt)" -gt 500 ] || fail periodic.compared_values "only $(wc -l <ref.txt) values to compare"
b="$REPO/bin/shake"
if [ -x "$b" ] && [ "$b" != "$SHAKE" ]; then
	while read -r path runs _ needs; do
		if [ "$runs" != yes ]; then
			echo "SKIP periodic.same_bits.release.$path: this CPU cannot run it (it needs $needs)"
		elif SHAKEBOX_KERNEL=$path "$b" "${SCENE[@]}" output=b.h5 >b.log 2>&1 && fin b.h5 >b.txt && cmp -s ref.txt b.txt; then
			ok "periodic.same_bits.release.$path"
		else
			fail "periodic.same_bits.release.$path" "$b on $path differs from $SHAKE ($(diff ref.txt b.txt | grep -c '^<') values)"
		fi
	done < <("$b" --kernel-paths)
fi

# a run from the particle files written after settling is the run that settled itself
for pf in p.txt p.data; do
	if "$SHAKE" "${SCENE[@]}" particles=$pf settle=no output=f.h5 >f.log 2>&1 && fin f.h5 >f.txt && cmp -s ref.txt f.txt; then
		ok "periodic.from_file.${pf#p.}"
	else
		fail "periodic.from_file.${pf#p.}" "differs from the run that settled ($(tail -n 1 f.log))"
	fi
done

# SIGTERM, then the same command resumes from the checkpoint and ends as p.h5
"$SHAKE" "${SCENE[@]}" checkpoint_every=0.25 output=r.h5 >r1.log 2>&1 &
pid=$!
for ((i = 0; i < 3000; i++)); do [ -e r.h5.ckpt ] || ! kill -0 $pid 2>/dev/null && break; sleep 0.005; done
kill -TERM $pid 2>/dev/null
wait $pid
rc=$?
if [ "$rc" -ne 7 ]; then
	fail periodic.resume.interrupted "exit $rc (want 7: the run ended before the signal?): $(tail -n 2 r1.log)"
elif "$SHAKE" "${SCENE[@]}" checkpoint_every=0.25 output=r.h5 >r2.log 2>&1; rc=$?; [ $rc != 0 ]; then
	fail periodic.resume.run "exit $rc: $(tail -n 2 r2.log)"
else
	fin r.h5 >r.txt
	cmp -s ref.txt r.txt && ok periodic.resume.same_end || fail periodic.resume.same_end "$(diff ref.txt r.txt | grep -c '^<') values differ"
fi

# refused: a period narrower than 4 r_max, an intruder wider than the period
shake_run n.log "${SCENE[@]}" width=4 output=n.h5
rc=$?
[ "$rc" -eq 1 ] && grep -q "width" n.log && grep -q "sides = periodic (command line)" n.log &&
	ok periodic.refused.narrow || fail periodic.refused.narrow "exit $rc: $(head -c 300 n.log)"
shake_run i.log "${SCENE[@]}" width=10 radius_ratio=5 output=i.h5
rc=$?
[ "$rc" -eq 1 ] && grep -q "radius_ratio" i.log && grep -q "own image" i.log &&
	ok periodic.refused.wide_intruder || fail periodic.refused.wide_intruder "exit $rc: $(head -c 300 i.log)"
finish
