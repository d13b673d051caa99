#!/usr/bin/env bash
# dump_lammps.sh - scripts/dump_lammps.sh writes a run's snapshots as a LAMMPS text dump
# that a real reader opens: LAMMPS's read_dump reads a frame of it, and the positions it
# writes back are the run's snapshot (/particles/bed/position, then the walls of
# /particles/walls) to 1e-12 cm; one frame per snapshot, every disk in each, its step the
# engine's.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1
command -v lmp >/dev/null || { fail setup "lmp (Debian package lammps) is not installed: make deps"; finish; }
shake_run s.log "${FAST[@]}" "${GENTLE[@]}" duration=1 snapshots=yes output=s.h5 || fail run "exit $?"
bash "$REPO/scripts/dump_lammps.sh" s.h5 >s.dump 2>d.err || fail convert "$(cat d.err)"
nf=$(grep -c '^ITEM: TIMESTEP' s.dump)
ns=$(dims s.h5 /particles/bed/position/step)
[ "$nf" = "$ns" ] && [ "$nf" -ge 4 ] && ok frames || fail frames "$nf frames for $ns snapshots"
# the third frame, read by LAMMPS and written back
step=$(awk '/^ITEM: TIMESTEP/ { getline; if (++k == 3) { print; exit } }' s.dump)
read -r xlo xhi ylo yhi < <(awk '/^ITEM: BOX BOUNDS/ { getline a; getline b; print a, b; exit }' s.dump)
cat >in.read <<IN
units cgs
dimension 2
atom_style sphere
boundary f f p
region box block $xlo $xhi $ylo $yhi -0.5 0.5
create_box 3 box
read_dump s.dump $step x y box yes add yes
write_dump all custom back.dump id type x y modify format float %.17g sort id
IN
lmp -in in.read -log none -screen none >lmp.out 2>&1 || { fail lammps_reads "$(tail -n 3 lmp.out)"; finish; }
[ "$step" = "$(h5vals s.h5 /particles/bed/position/step | sed -n 3p)" ] && ok frame_step_is_engine_step ||
	fail frame_step_is_engine_step "frame 3 has step $step"
# the frame as the run file has it: snapshot 3's x, y of the mobile disks, then the walls
n=$(( $(dims s.h5 /particles/bed/id) + $(dims s.h5 /particles/walls/id) ))
{ h5snap s.h5 0 | sed -n 3p | tr ' ' '\n'; h5vals s.h5 /particles/walls/position | awk 'NR % 2 == 1'; } >x3
{ h5snap s.h5 1 | sed -n 3p | tr ' ' '\n'; h5vals s.h5 /particles/walls/position | awk 'NR % 2 == 0'; } >y3
worst=$(paste <(awk 'NR > 9 { print $3, $4 }' back.dump) x3 y3 | awk '{ d = $1 - $3; e = $2 - $4; d = d < 0 ? -d : d; e = e < 0 ? -e : e;
	w = d > w ? d : w; w = e > w ? e : w; k++ } END { print k, w + 0 }')
read -r k w <<<"$worst"
[ "$k" = "$n" ] && awk -v w="$w" 'BEGIN { exit !(w < 1e-12) }' && ok lammps_reads_the_frame ||
	fail lammps_reads_the_frame "$k of $n atoms, largest difference $w cm"
bash "$REPO/scripts/dump_lammps.sh" nosuch.h5 >/dev/null 2>e1 && fail missing_file "exit 0" || grep -q 'cannot read' e1 && ok missing_file || fail missing_file "$(cat e1)"
finish
