#!/usr/bin/env bash
# hostile_input.sh - input that is in range key by key but asks for the impossible, or
# that is not what it looks like, is refused at once: exit code 1 and a message naming
# the file, the line and the key (or the limit), within seconds, never a hang, a silent
# misreading or a physics failure later. Sizes computed from keys (lattice columns,
# wall disks, masses) are checked before they are used; a long line or a NUL byte in a
# scene or particle file is an error, never cut in pieces; particle files are regular
# files of sane disks (radii, places, overlaps, LAMMPS ids, style and box). Every field
# of a line is read, numbers in one strict decimal reading, and a byte-order mark or a
# CRLF is read alike by the scene, campaign and particle readers. SIGTERM ends a long
# preparation within seconds.
# tier: slow: runs that must end by themselves within a time limit
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

OUT="$TMP/out.h5"
LIMIT=20 # seconds before timeout(1) sends SIGTERM (and SIGKILL 5 s later)
PROMPT=10 # seconds: "at once", with room for the sanitizer build on a busy machine

# refused ID "needle|needle..." args... : bin/shake ends within PROMPT s with exit code
# 1, its stderr has every needle, and no output file is left behind
refused() {
	local id=$1 needles=$2
	shift 2
	rm -f "$OUT" "$TMP/out.xmf" "$OUT.journal" "$OUT.ckpt"
	local log="$TMP/$id.log" t0=$SECONDS
	timeout -k 5 "$LIMIT" "$SHAKE" "$@" output="$OUT" progress=no >"$log" 2>&1
	local rc=$? why="" took=$((SECONDS - t0))
	if [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then
		why="still running after $LIMIT s (exit $rc from timeout)"
	elif [ "$rc" -ne 1 ]; then
		why="exit code $rc, expected 1"
	elif [ "$took" -gt "$PROMPT" ]; then
		why="took $took s"
	fi
	local IFS='|' n
	for n in $needles; do
		[ -z "$why" ] && ! contains "$log" "$n" && why="message lacks '$n'"
	done
	unset IFS
	for f in "$OUT" "$TMP/out.xmf" "$OUT.journal" "$OUT.ckpt"; do
		[ -z "$why" ] && [ -e "$f" ] && why="left $(basename "$f") behind"
	done
	if [ -z "$why" ]; then ok "$id"; else fail "$id" "$why; stderr: $(head -c 400 "$log" | tr '\n' ' ')"; fi
}

# runs ID args... : bin/shake ends within LIMIT s with exit code 0 (log in ID.log)
runs() {
	local id=$1
	shift
	timeout -k 5 "$LIMIT" "$SHAKE" "$@" output="$TMP/$id.h5" progress=no >"$TMP/$id.log" 2>&1
	local rc=$?
	[ "$rc" -eq 0 ] && return 0
	fail "$id" "exit $rc: $(head -c 300 "$TMP/$id.log" | tr '\n' ' ')"
	return 1
}

# sigterm_within ID SECONDS_BEFORE SECONDS_AFTER args... : SIGTERM after SECONDS_BEFORE
# ends bin/shake within SECONDS_AFTER (exit code in $STOP_RC, log in ID.log; STOP_ALIVE
# is 1 when the process was still running to receive the signal)
sigterm_within() {
	local id=$1 before=$2 after=$3
	shift 3
	"$SHAKE" "$@" progress=no >"$TMP/$id.log" 2>&1 &
	local pid=$! k
	sleep "$before"
	# STOP_ALIVE=1: the signal reached a running process
	STOP_ALIVE=0
	kill -TERM "$pid" 2>/dev/null && STOP_ALIVE=1
	for ((k = 0; k < after * 10; k++)); do
		kill -0 "$pid" 2>/dev/null || break
		sleep 0.1
	done
	if kill -0 "$pid" 2>/dev/null; then
		kill -KILL "$pid" 2>/dev/null
		wait "$pid" 2>/dev/null
		STOP_RC=killed
		return 1
	fi
	wait "$pid"
	STOP_RC=$?
	return 0
}

# ==== 1. sizes computed from keys in range, and SIGTERM ====
# width / (2.2 r_max) lattice columns overflowed int: no grain was placed, and the
# placement loop ran for ever, deaf to SIGTERM
refused sizes.lattice_columns "command line: width|r_max|lattice sites|at most 10000000" \
	duration=0 n_grains=5 width=1e7 r_min=1e-3 r_max=1e-3 dt=1e-7 radius_ratio=0
refused sizes.lattice_columns.tiny_radii "width|r_max|at most 10000000" \
	duration=0 n_grains=5 r_min=1e-300 r_max=1e-300 width=10 radius_ratio=0
# the bottom wall's disk count overflowed int: no bottom wall, a failure much later
refused sizes.walls.bottom "wall_spacing|width|wall disks|at most 1000000" \
	duration=0 n_grains=5 radius_ratio=0 width=1e7 wall_spacing=1e-3 wall_radius=1e-3
refused sizes.step_count "duration / dt|at most 1e15" dt=1e-300 dt_guard=off duration=1 output=steps.h5
refused sizes.settle_step_count "settle_max / dt|at most 1e15" dt=1e-300 dt_guard=off duration=0
refused sizes.depth_beyond_the_grains "depth 50000 rows|n_grains 150|at most" n_grains=150 depth=50000 duration=0.02
refused sizes.walls.tall "wall_spacing|wall_height|at most 1000000" n_grains=150 wall_height=5000000 duration=0.02
refused sizes.walls.sides "wall_spacing|wall_height|wall disks|at most 1000000" \
	duration=0 n_grains=5 radius_ratio=0 width=20 wall_height=1e7 wall_spacing=1e-3 wall_radius=1e-3
# every key in range, the mass m = mass_factor rho R^2 underflows to 0 (1/m = inf)
refused sizes.mass_underflow "mass_factor|density|positive and finite" \
	"${FAST[@]}" duration=0 mass_factor=1e-300 density=1e-300 dt_guard=off

# SIGTERM while a bed settles for far longer than the test waits (a bed 2 10^4 cm wide,
# every key in range, at a step of 10^-7 s: minutes of settling) ends the process with
# exit 7 and its word; the process must still be running when the signal comes, or the
# check would say nothing
if sigterm_within stop.sigterm.long_settling 1 5 duration=0 n_grains=5 width=2e4 r_min=1e-3 r_max=1e-3 \
	dt=1e-7 radius_ratio=0 output="$TMP/sig1.h5"; then
	if [ "$STOP_ALIVE" != 1 ]; then
		fail stop.sigterm.long_settling "the run had ended before the SIGTERM (exit $STOP_RC): $(tail -n 1 "$TMP/stop.sigterm.long_settling.log")"
	elif [ "$STOP_RC" = 7 ] && grep -q 'interrupted' "$TMP/stop.sigterm.long_settling.log"; then
		ok stop.sigterm.long_settling
	else
		fail stop.sigterm.long_settling "exit $STOP_RC, want 7 and 'interrupted': $(tail -n 1 "$TMP/stop.sigterm.long_settling.log")"
	fi
else
	fail stop.sigterm.long_settling "still running 5 s after SIGTERM"
fi
# SIGTERM while a 2 10^5-atom LAMMPS file is read (velocities listed last to first): the
# reading took seconds per 10^5 atoms, deaf to SIGTERM
awk -v nx=400 -v ny=500 'BEGIN {
	p = 2.2; W = nx * p; H = 2 * ny * p; nb = int(W / 2) + 2; ns = int(H / 2) + 1
	printf "# a bed of %d grains\n\n%d atoms\n3 atom types\n\n", nx * ny, nx * ny + nb + 2 * ns
	printf "-3 %g xlo xhi\n-3 %g ylo yhi\n-0.5 0.5 zlo zhi\n\nAtoms # sphere\n\n", W + 3, H + 3
	for (j = 0; j < ny; j++) for (i = 0; i < nx; i++)
		printf "%d 1 2 0.477 %.6f %.6f 0\n", ++id, (i + 0.5) * p, (j + 0.5) * p
	for (k = 0; k < nb; k++) printf "%d 3 2 0.477 %.6f -1 0\n", ++id, -1 + (W + 2) * k / (nb - 1)
	for (k = 1; k <= ns; k++) {
		printf "%d 3 2 0.477 -1 %.6f 0\n", ++id, -1 + H * k / ns
		printf "%d 3 2 0.477 %.6f %.6f 0\n", ++id, W + 1, -1 + H * k / ns
	}
	printf "\nVelocities\n\n"
	for (k = id; k >= 1; k--) printf "%d 0 0 0 0 0 0\n", k
}' >big.data
if sigterm_within stop.sigterm.reading 1.5 4 particles="$TMP/big.data" particle_mass=file settle=no duration=1000 snapshots=no \
	traj_rate=0 output="$TMP/sig2.h5"; then
	[ "$STOP_RC" -eq 7 ] && ok stop.sigterm.reading ||
		fail stop.sigterm.reading "exit $STOP_RC, expected 7: $(head -c 300 stop.sigterm.reading.log)"
else
	fail stop.sigterm.reading "still running 4 s after SIGTERM: $(head -c 300 stop.sigterm.reading.log)"
fi
# and while settling (a bed that settles for at least 100 s)
if sigterm_within stop.sigterm.settling 1.5 4 "${FAST[@]}" settle_min=100 settle_max=200 output="$TMP/sig3.h5"; then
	[ "$STOP_RC" -eq 7 ] && contains stop.sigterm.settling.log "interrupted while settling" &&
		ok stop.sigterm.settling ||
		fail stop.sigterm.settling "exit $STOP_RC: $(head -c 300 stop.sigterm.settling.log)"
else
	fail stop.sigterm.settling "still running 4 s after SIGTERM"
fi

# ==== 2. long lines and NUL bytes ====
ys() { printf "%${1}s" "" | tr ' ' "${2:-y}"; }
# inih reads 199 characters a line: the tail of a long comment was read as a line of its own
printf '; %s frequency = 7.5\n' "$(ys 197)" >long_comment.scene
refused scene.long_comment "long_comment.scene:1:|line too long|199" long_comment.scene "${FAST[@]}" duration=0
printf 'seed = 3\noutput = %s.h5\n' "$(ys 250 a)" >long_value.scene
refused scene.long_key_line "long_value.scene:2:|line too long|199" long_value.scene "${FAST[@]}" duration=0
# a line of exactly 199 characters is read whole
printf ';%s\nfrequency = 3\n' "$(ys 198)" >at_limit.scene
runs scene.line_at_limit at_limit.scene "${FAST[@]}" duration=0 && ok scene.line_at_limit
# the bytes after a NUL vanished
printf 'seed = 3\0frequency = 7.5\nduration = 0\n' >nul.scene
refused scene.nul "nul.scene:1:|NUL byte" nul.scene "${FAST[@]}"
printf 'seed = 3\n; \0\n' >nul_comment.scene
refused scene.nul_in_comment "nul_comment.scene:2:|NUL byte" nul_comment.scene "${FAST[@]}" duration=0
# a scene that is no regular file is refused at once: a pipe could be endless, a FIFO
# without a writer blocked the open for good; a regular one is bounded in lines
refused scene.pipe "not a regular file" <(yes '; a comment') "${FAST[@]}" duration=0
mkfifo "$TMP/scene.fifo"
refused scene.fifo "scene.fifo|not a regular file" "$TMP/scene.fifo" "${FAST[@]}" duration=0
yes '; a comment' | head -n 100001 >long.scene
refused scene.too_many_lines "long.scene:100001:|more than 100000 lines" long.scene "${FAST[@]}" duration=0

# particle files: a state written by the engine, then altered
if ! runs prep "${FAST[@]}" duration=0 write_particles="$TMP/bed.txt" write_lammps="$TMP/bed.data"; then
	finish
fi
RUN=(settle=no duration=0.01 "${GENTLE[@]}")
nl=$(wc -l <bed.txt)
{ cat bed.txt; printf '# %s 5.5 30 1 grain\n' "$(ys 1030)"; } >long_comment.txt
refused particles.long_comment "long_comment.txt:$((nl + 1)):|line too long|1023" particles=long_comment.txt "${RUN[@]}"
{ cat bed.txt; printf '5.5 30 1 grain%s 0 0 0\n' "$(ys 1030 ' ')"; } >long_line.txt
refused particles.long_line "long_line.txt:$((nl + 1)):|line too long|1023" particles=long_line.txt "${RUN[@]}"
{ cat bed.txt; printf '# two more grains\0 5.5 30 1 grain\n'; } >nul_comment.txt
refused particles.nul_in_comment "nul_comment.txt:$((nl + 1)):|NUL byte" particles=nul_comment.txt "${RUN[@]}"
{ head -n 3 bed.txt; printf '5.5 30 1 grain\0 0 0 0 garbage\n'; tail -n +4 bed.txt; } >nul_line.txt
refused particles.nul "nul_line.txt:4:|NUL byte" particles=nul_line.txt "${RUN[@]}"
awk -v l="$(ys 1100)" '/^Atoms/ { print "# " l } { print }' bed.data >long_line.data
refused particles.lammps_long_line "long_line.data:|line too long|1023" particles=long_line.data "${RUN[@]}"

# ==== 7. what a scene path or a particle file is ====
mkdir -p adir
refused scene.directory "adir|is a directory" adir "${FAST[@]}" duration=0
refused particles.directory "adir|is a directory" particles=adir "${RUN[@]}"
refused particles.dev_zero "/dev/zero|not a regular file" particles=/dev/zero "${RUN[@]}"
mkfifo fifo
refused particles.fifo "fifo|not a regular file" particles="$TMP/fifo" "${RUN[@]}"

g=$(awk '$4 == "grain" { print; exit }' bed.txt)
gl=$(awk '$4 == "grain" { print NR; exit }' bed.txt)
set -- $g
{ cat bed.txt; echo "$g"; } >twin.txt
refused particles.coincident "twin.txt:$((nl + 1)):|coincides|line $gl" particles=twin.txt "${RUN[@]}"
{ cat bed.txt; echo "$1 $(awk -v y="$2" -v r="$3" 'BEGIN { printf "%.17g", y + 0.3 * r }') $3 grain"; } >deep.txt
refused particles.deep_overlap "deep.txt:$((nl + 1)):|line $gl|max_overlap" particles=deep.txt "${RUN[@]}"
{ cat bed.txt; echo "5 60 1e-300 grain"; } >tiny.txt
refused particles.radius_tiny "tiny.txt:$((nl + 1)):|radius|[0.0001, 10000]" particles=tiny.txt "${RUN[@]}"
{ cat bed.txt; echo "5 60 1e6 grain"; } >huge.txt
refused particles.radius_huge "huge.txt:$((nl + 1)):|radius|[0.0001, 10000]" particles=huge.txt "${RUN[@]}"
# a grain a million cm above a box of tens of cm (a slip of units); one just outside
# the box is the run's to find (blowup.sh)
{ cat bed.txt; echo "10 1e6 1 grain"; } >high.txt
refused particles.far_outside_box "high.txt:$((nl + 1)):|outside the box of the walls" particles=high.txt "${RUN[@]}"
# without walls there is no box: a grain 10^12 cm away is measured against the origin
printf '10 5 1 grain\n1e12 5 1 grain\n' >far.txt
refused particles.far_from_origin "far.txt:2:|from the origin" particles=far.txt "${RUN[@]}"
# no walls at all: legal (a free fall), warned
printf '10 5 1 grain\n14 5 2 intruder\n' >nowall.txt
runs particles.no_walls_warned particles=nowall.txt "${RUN[@]}" &&
	{ contains particles.no_walls_warned.log "warning" && contains particles.no_walls_warned.log "no walls" &&
		ok particles.no_walls_warned || fail particles.no_walls_warned "no warning: $(head -c 200 particles.no_walls_warned.log)"; }

# LAMMPS files
sed 's/^Atoms # sphere/Atoms # full/' bed.data >full.data
refused particles.lammps_atom_style "full.data:|atom_style full|sphere" particles=full.data "${RUN[@]}"
a=$(grep -n '^Atoms' bed.data | cut -d: -f1)
awk -v a="$a" 'NR == a + 3 { $1 = 1 } { print }' bed.data >dupid.data
refused particles.lammps_duplicate_id "dupid.data:$((a + 3)):|duplicate atom id 1|first at line $((a + 2))" \
	particles=dupid.data "${RUN[@]}"
v=$(grep -n '^Velocities' bed.data | cut -d: -f1)
awk -v v="$v" 'NR == v + 3 { $1 = 1 } { print }' bed.data >twicev.data
refused particles.lammps_velocity_twice "twicev.data:$((v + 3)):|atom id 1|line $((v + 2))" particles=twicev.data "${RUN[@]}"
awk -v a="$a" 'NR == a + 4 { $6 = 1e6 } { print }' bed.data >outbox.data
refused particles.lammps_outside_box "outbox.data:$((a + 4)):|outside the box|ylo yhi" particles=outbox.data "${RUN[@]}"
sed 's/^[0-9]* atoms$/30000000 atoms/' bed.data >many.data
refused particles.lammps_atom_count "many.data:|30000000 atoms|at most" particles=many.data "${RUN[@]}"

# ==== 8. every field read whole, with one reading of a number, in every reader ====
# (docs/inputs.md: "Numbers", "Lines")
# a fifth word on a text line is no velocity: the grain started at rest unasked
{ cat bed.txt; echo "5.5 30 1 grain garbage"; } >extra.txt
refused particles.text_extra_field "extra.txt:$((nl + 1)):|5 fields" particles=extra.txt "${RUN[@]}"
{ cat bed.txt; echo "5.5 30 1 grain 0 0 0 garbage"; } >extra8.txt
refused particles.text_bad_mass "extra8.txt:$((nl + 1)):|m: expected a finite decimal number|garbage" particles=extra8.txt "${RUN[@]}"
{ cat bed.txt; echo "5.5 30 1 grain 0 0 0 6.283185307179586 garbage"; } >extra9.txt
refused particles.text_extra_field_after_mass "extra9.txt:$((nl + 1)):|9 fields" particles=extra9.txt "${RUN[@]}"
{ cat bed.txt; echo "0x10 30 1 grain"; } >hex.txt
refused particles.text_hex "hex.txt:$((nl + 1)):|x|0x10" particles=hex.txt "${RUN[@]}"
# an atom type 1.5 was read as 1, and ".5" as the diameter: every column shifted
awk -v a="$a" 'NR == a + 2 { $2 = "1.5" } { print }' bed.data >type15.data
refused particles.lammps_type_fraction "type15.data:$((a + 2)):|type|1.5" particles=type15.data "${RUN[@]}"
awk -v a="$a" 'NR == a + 2 { $0 = $0 " garbage" } { print }' bed.data >trail.data
refused particles.lammps_atoms_trailing "trail.data:$((a + 2)):|8 fields" particles=trail.data "${RUN[@]}"
awk -v v="$v" 'NR == v + 2 { $0 = $0 " 7" } { print }' bed.data >trailv.data
refused particles.lammps_velocities_trailing "trailv.data:$((v + 2)):|8 fields" particles=trailv.data "${RUN[@]}"
sed 's/^\([0-9]*\) atoms$/\1 atoms junk/' bed.data >count_junk.data
refused particles.lammps_count_trailing "count_junk.data:|N atoms" particles=count_junk.data "${RUN[@]}"
# numbers: decimal only (0x10 was 16 Hz as a real, refused as an integer), and an
# integer key range-checked as an integer (2^53 + 1 equals 2^53 as a double)
printf 'frequency = 0x10\n' >hex.scene
refused scene.hex_real "hex.scene:1:|frequency|0x10" hex.scene "${FAST[@]}" duration=0
refused cmdline.hex_real "frequency|0x10" "${FAST[@]}" duration=0 frequency=0x10
refused cmdline.hex_int "n_grains|0x10" "${FAST[@]}" duration=0 n_grains=0x10
refused cmdline.int_past_double "seed|9007199254740993|9007199254740992" "${FAST[@]}" duration=0 seed=9007199254740993
runs cmdline.int_at_bound "${FAST[@]}" duration=0 seed=9007199254740992 && ok cmdline.int_at_bound
# a UTF-8 byte-order mark opens a file: dropped by all three readers alike (and a
# section after it is checked like any other); a CRLF line is measured without its CR
STUDY_BIN="$(dirname "$SHAKE")/study"
bom() { printf '\357\273\277'; cat "$1"; }
printf 'seed = 3\n' >plain.scene
bom plain.scene >bom.scene
runs scene.bom bom.scene "${FAST[@]}" duration=0 && ok scene.bom
printf '[bogus]\nseed = 3\n' >bogus.scene
bom bogus.scene >bom_bogus.scene
refused scene.bom_bad_section "bom_bogus.scene:1:|unknown section [bogus]" bom_bogus.scene "${FAST[@]}" duration=0
bom bed.txt >bom.txt
runs particles.bom_text particles=bom.txt "${RUN[@]}" && ok particles.bom_text
bom bed.data >bom.data
runs particles.bom_lammps particles=bom.data "${RUN[@]}" && ok particles.bom_lammps
printf '[campaign]\nname = b\nseed = 1\n[grid]\nfrequency = 3, 4\n' >plain.campaign
bom plain.campaign >bom.campaign
"$STUDY_BIN" expand bom.campaign >bom.campaign.out 2>bom.campaign.err && [ "$(awk -F "\t" 'NR > 1 { print $5 }' bom.campaign.out | tr "\n" " ")" = "3 4 " ] &&
	ok campaign.bom || fail campaign.bom "$(head -c 300 bom.campaign.out)"
{ printf '\357\273\277[camp]\n'; cat plain.campaign; } >bom_bad.campaign
"$STUDY_BIN" expand bom_bad.campaign >bom_bad.out 2>&1
[ $? -eq 1 ] && grep -q 'bom_bad.campaign:1: unknown section' bom_bad.out && ok campaign.bom_bad_section ||
	fail campaign.bom_bad_section "$(head -c 300 bom_bad.out)"
# the longest line a reader takes (199 characters, 1023 in a particle file), with CRLF
printf '; %s\r\nseed = 3\r\n' "$(ys 197)" >crlf.scene
runs scene.crlf_longest_line crlf.scene "${FAST[@]}" duration=0 && ok scene.crlf_longest_line
{ printf '[campaign]\r\nname = b\r\nseed = 1\r\n# %s\r\n[grid]\r\nfrequency = 3, 4\r\n' "$(ys 197)"; } >crlf.campaign
"$STUDY_BIN" expand crlf.campaign >crlf.campaign.out 2>&1 && ok campaign.crlf_longest_line ||
	fail campaign.crlf_longest_line "$(head -c 300 crlf.campaign.out)"
{ sed 's/$/\r/' bed.txt; printf '# %s\r\n' "$(ys 1021)"; } >crlf.txt
runs particles.crlf_longest_line particles=crlf.txt "${RUN[@]}" && ok particles.crlf_longest_line

# and the files the engine writes still read back (particles_io.sh has the round trips)
runs particles.own_files_read particles="$TMP/bed.txt" "${RUN[@]}" &&
	runs particles.own_files_read particles="$TMP/bed.data" "${RUN[@]}" && ok particles.own_files_read
finish
