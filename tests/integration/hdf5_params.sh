#!/usr/bin/env bash
# hdf5_params.sh - the HDF5 output records the run: every scene parameter of
# `shake --params` is a root attribute of the right type whose value equals the input
# (reals exactly, compared at %.17g), /provenance is complete, status is ok, and the
# datasets and the XDMF sidecar have the shapes the run implies.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

"$SHAKE" --params >params.tsv 2>/dev/null
if [ "$(head -n 1 params.tsv | cut -f1,2,4)" != "$(printf 'name\ttype\tdefault')" ] || [ "$(wc -l <params.tsv)" -lt 30 ]; then
	fail params.table "shake --params does not give the name/type/unit/default TSV"
	finish
fi
ok params.table

# expected value of every parameter: the default, overridden by what the run was given
# expect_params TSV KEY=VALUE... > name<TAB>type<TAB>expected
expect_params() {
	local tsv=$1
	shift
	printf '%s\n' "$@" | awk -F'\t' -v OFS='\t' '
		FNR == NR { i = index($0, "="); set[substr($0, 1, i - 1)] = substr($0, i + 1); next }
		FNR == 1 { next }
		{ v = ($1 in set) ? set[$1] : $4; print $1, $2, v }' - "$tsv"
}

# compare_params ID FILE KEY=VALUE... : one check per parameter
compare_params() {
	local id=$1 f=$2
	shift 2
	local name type want got dt
	while IFS=$'\t' read -r name type want; do
		got=$(attr "$f" "/$name")
		dt=$(h5dump -a "/$name" "$f" 2>/dev/null | awk '/DATATYPE/ { print $2; exit }')
		case "$type" in
		real)
			want=$(awk -v x="$want" 'BEGIN { printf "%.17g", x + 0 }')
			got=$(awk -v x="$got" 'BEGIN { if (x == "") print ""; else printf "%.17g", x + 0 }')
			[ "$dt" = H5T_IEEE_F64LE ] || { fail "$id.$name" "type $dt, expected H5T_IEEE_F64LE"; continue; } ;;
		int) [ "$dt" = H5T_STD_I64LE ] || { fail "$id.$name" "type $dt, expected H5T_STD_I64LE"; continue; } ;;
		*) [ "$dt" = H5T_STRING ] || { fail "$id.$name" "type $dt, expected H5T_STRING"; continue; } ;;
		esac
		if [ "$got" = "$want" ]; then ok "$id.$name"; else fail "$id.$name" "file has '$got', input was '$want'"; fi
	done < <(expect_params params.tsv "$@")
}

# --- run 1: placement and settling, many non-default values of every type ---
RUN1=(n_grains=60 width=20.5 radius_ratio=2 depth=1 settle_ke=1 settle_min=0.2 settle_max=12.5
	settle=yes settle_drag=21.3 r_min=0.9 r_max=1.1 seed=12345 density=1.1 mass_factor=6.3
	wall_radius=0.95 wall_spacing=1.9 gamma_s=2.7 gamma_n=99.9 mu=0.45 gravity=980.665
	stiffness=3.1e6 clip_attractive=yes wall_mass=infinite integrator=verlet dt=4e-05
	skin=0.2 max_overlap=0.35 frequency=4 amplitude=1.1 duration=1 traj_rate=200 snapshots=yes
	checkpoint_every=0 checkpoint="$TMP/my.ckpt" restart=no write_particles="$TMP/p1.txt"
	write_lammps="$TMP/p1.data" progress=no output="$TMP/out1.h5")
log=$TMP/run1.log
shake_run "$log" "${RUN1[@]}"
rc=$?
if [ "$rc" -ne 0 ] || [ ! -s out1.h5 ]; then
	fail run1 "exit $rc: $(head -c 300 "$log")"
	finish
fi
ok run1
compare_params run1.param out1.h5 "${RUN1[@]}"

# --- run 2: from the particle file, other non-defaults (no recording) ---
RUN2=(particles="$TMP/p1.txt" settle=no integrator=gear4 dt=5e-05 duration=0.05 wall_height=30.5
	snapshots=no traj_rate=0 wall_mass=disk clip_attractive=no mu=0.6 frequency=2.7
	amplitude=0.5 output="$TMP/out2.h5" progress=yes restart=auto)
shake_run "$TMP/run2.log" "${RUN2[@]}"
rc=$?
if [ "$rc" -ne 0 ] || [ ! -s out2.h5 ]; then
	fail run2 "exit $rc: $(head -c 300 "$TMP/run2.log")"
else
	ok run2
	compare_params run2.param out2.h5 "${RUN2[@]}"
	d=$(dims out2.h5 /snapshots/x)
	[ "$d" = "0 61" ] && ok run2.no_snapshots || fail run2.no_snapshots "/snapshots/x is [$d], expected [0 61]"
	d=$(dims out2.h5 /intruder/trajectory)
	[ -z "$d" ] || [ "${d%% *}" = 0 ] && ok run2.no_trajectory || fail run2.no_trajectory "/intruder/trajectory is [$d] with traj_rate=0"
fi

# --- status and provenance of run 1 ---
f=out1.h5
[ "$(attr $f /status)" = ok ] && ok status.ok || fail status.ok "status = '$(attr $f /status)'"
[ "$(attr $f /exit_code)" = 0 ] && ok status.exit_code || fail status.exit_code "exit_code = '$(attr $f /exit_code)'"
[ "$(attr $f /format)" = shakebox-run-1 ] && ok format || fail format "format = '$(attr $f /format)'"
for a in git_hash compiler host start_time end_time; do
	v=$(attr $f /provenance/$a)
	[ -n "$v" ] && ok "provenance.$a" || fail "provenance.$a" "/provenance/$a missing or empty"
done
gh=$(attr $f /provenance/git_hash)
[[ "$gh" =~ ^[0-9a-f]{7,40}$ ]] && ok provenance.git_hash_form || fail provenance.git_hash_form "git_hash '$gh' is not a commit hash"
st=$(attr $f /provenance/start_time) en=$(attr $f /provenance/end_time)
[[ "$st" =~ ^[0-9]{4}-[0-9]{2}-[0-9]{2}T ]] && [[ ! "$en" < "$st" ]] && ok provenance.times ||
	fail provenance.times "start_time '$st', end_time '$en'"

# --- shapes of run 1: duration 1 s, f = 4 Hz -> 4 periods -> K = 5; 200 Hz -> 201 rows ---
nm=$(attr $f /n_mobile)
nw=$(attr $f /n_walls)
[ "$nm" = 61 ] && ok shape.n_mobile || fail shape.n_mobile "n_mobile = '$nm', expected 60 grains + 1 intruder"
[ -n "$nw" ] && [ "$nw" -gt 0 ] && ok shape.n_walls || fail shape.n_walls "n_walls = '$nw'"
d=$(dims $f /intruder/trajectory)
[ "$d" = "201 6" ] && ok shape.trajectory || fail shape.trajectory "/intruder/trajectory is [$d], expected [201 6]"
for c in x y theta; do
	d=$(dims $f /snapshots/$c)
	[ "$d" = "5 $nm" ] && ok "shape.snapshots_$c" || fail "shape.snapshots_$c" "/snapshots/$c is [$d], expected [5 $nm]"
done
d=$(dims $f /snapshots/time)
[ "$d" = 5 ] && ok shape.snapshot_time || fail shape.snapshot_time "/snapshots/time is [$d], expected [5]"
for c in x y vx vy omega theta; do
	d=$(dims $f /final/$c)
	[ "$d" = "$((nm + nw))" ] && ok "shape.final_$c" || fail "shape.final_$c" "/final/$c is [$d], expected [$((nm + nw))]"
done
for c in id kind radius mass; do
	d=$(dims $f /particles/$c)
	[ "$d" = "$((nm + nw))" ] && ok "shape.particles_$c" || fail "shape.particles_$c" "/particles/$c is [$d]"
done
# snapshot times are k / f (to within one step); trajectory rows run from t = 0 to duration
h5dump -m %.17g -d /snapshots/time -y -w 0 $f | awk '/^ *DATA/ { on = 1; next } on && /}/ { on = 0 }
	on { gsub(/,/, " "); for (i = 1; i <= NF; i++) print $i }' >times.txt
awk '{ if ($1 < 0.25 * (NR - 1) - 1e-12 || $1 > 0.25 * (NR - 1) + 4e-5 + 1e-12) bad = 1 } END { exit bad || NR != 5 }' times.txt &&
	ok shape.snapshot_times || fail shape.snapshot_times "/snapshots/time = $(tr '\n' ' ' <times.txt), expected 0 0.25 0.5 0.75 1"
h5dump -m %.17g -d /intruder/trajectory -y -w 0 $f | awk '/^ *DATA/ { on = 1; next } on && /}/ { on = 0 }
	on { gsub(/,/, " "); for (i = 1; i <= NF; i++) print $i }' | awk 'NR % 6 == 1' >traj_t.txt
awk 'NR == 1 && $1 != 0 { bad = 1 } { if ($1 < (NR - 1) * 0.005 - 1e-12 || $1 > (NR - 1) * 0.005 + 4e-5) bad = 1; last = $1 }
	END { exit bad || NR != 201 || last != 1 }' traj_t.txt && ok shape.trajectory_times ||
	fail shape.trajectory_times "trajectory t column is not 0, 0.005, ..., 1 ($(head -n 3 traj_t.txt | tr '\n' ' ')... $(tail -n 1 traj_t.txt))"

# --- XDMF sidecar ---
x=out1.xmf
if [ -s "$x" ]; then
	ok xdmf.exists
	contains $x 'out1.h5:/snapshots/x' && contains $x 'out1.h5:/snapshots/y' && ok xdmf.references_h5 ||
		fail xdmf.references_h5 "$x does not reference out1.h5:/snapshots/x and /y"
	n=$(grep -c '<Grid Name="t' $x)
	[ "$n" = 5 ] && ok xdmf.grids || fail xdmf.grids "$n time grids, expected 5"
	contains $x "NumberOfElements=\"$nm\"" && ok xdmf.elements || fail xdmf.elements "NumberOfElements is not $nm"
else
	fail xdmf.exists "no out1.xmf beside out1.h5"
fi
# no journal or checkpoint left after a successful run
[ ! -e out1.h5.journal ] && [ ! -e my.ckpt ] && ok cleanup || fail cleanup "journal or checkpoint left behind"
finish
