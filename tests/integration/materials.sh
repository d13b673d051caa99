#!/usr/bin/env bash
# materials.sh - an intruder of another material (docs/model.md, "Units and the paper's
# values"): intruder_density sets the intruder's mass and moment of inertia and nothing
# else, its default gives the bits of a run without it, and a bad value is refused with
# its file, line, key and range. A particle file's masses (docs/inputs.md, "Particle
# masses"): its mass or density column agrees with the scene's mass model or is refused
# with its line (particle_mass = scene), or is used (particle_mass = file); never
# ignored. (A particle file's several intruders: intruders.sh.)
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

# the tiny bed, shaken 0.2 s (whole datasets to compare: h5diff cannot compare empty ones)
PREP=("${FAST[@]}" "${GENTLE[@]}")
# mass FILE SPECIES : the masses of /particles/bed's disks of that species, one a line
mass() { paste -d' ' <(h5vals "$1" /particles/bed/species) <(h5vals "$1" /particles/bed/mass) | awk -v k="$2" '$1 == k { print $2 }'; }

shake_run d1.log "${PREP[@]}" output="$TMP/d1.h5" && shake_run d3.log "${PREP[@]}" intruder_density=3 output="$TMP/d3.h5" &&
	shake_run dx.log "${PREP[@]}" intruder_density=1 output="$TMP/dx.h5"
rc=$?
if [ "$rc" -ne 0 ]; then
	fail runs "exit $rc: $(head -c 300 d1.log d3.log dx.log)"
	finish
fi
# the tiny bed's intruder has R = 2 cm (radius_ratio 2, mean grain radius 1 cm): its mass is
# mass_factor rho R^2 = 2 pi 3 4 g at intruder_density 3, 2 pi 4 g at the default
m1=$(mass d1.h5 1) m3=$(mass d3.h5 1)
awk -v a="$m1" -v b="$m3" 'BEGIN { pi = 3.141592653589793; exit !(a == 2 * pi * 4 && (b - 2 * pi * 12) ^ 2 < (1e-14 * b) ^ 2) }' &&
	ok intruder_mass || fail intruder_mass "intruder masses $m1 (default) and $m3 (intruder_density 3), expected 8 pi and 24 pi g"
# the grains keep theirs: the same masses, in the same order
[ -n "$(mass d1.h5 0)" ] && [ "$(mass d1.h5 0)" = "$(mass d3.h5 0)" ] && ok grains_unchanged ||
	fail grains_unchanged "the grains' masses change with intruder_density"
h5param d3.h5 intruder_density | grep -qx 3 && ok recorded || fail recorded "/parameters/intruder_density is '$(h5param d3.h5 intruder_density)', expected 3"
# intruder_density = density is the default's run, bit for bit (datasets and every attribute
# but the parameter itself)
same_output d1.h5 dx.h5 output intruder_density && ok default_bits || fail default_bits "intruder_density = 1 differs from the default 0"
# a heavier intruder settles into another bed: the run differs (the key has teeth)
same_output d1.h5 d3.h5 output intruder_density 2>/dev/null && fail teeth "intruder_density 3 gives the run of the default" || ok teeth

# refused: a negative density, with file, line, key and range; and the dt guard sees a
# light intruder (the lightest disk sets the stability limit)
printf 'n_grains = 60\nintruder_density = -1\n' >neg.ini
shake_run neg.log neg.ini "${PREP[@]}" output="$TMP/neg.h5"
rc=$?
[ "$rc" -eq 1 ] && contains neg.log "neg.ini:2:" && contains neg.log "intruder_density" && contains neg.log "[0, 1e+06]" &&
	[ ! -e neg.h5 ] && ok refused.range || fail refused.range "exit $rc: $(head -c 300 neg.log)"
# (d1 and d3 ran at the default dt; an intruder a million times lighter than the grains
# is beyond the guard at the same dt)
shake_run light.log "${PREP[@]}" intruder_density=1e-6 output="$TMP/light.h5"
rc=$?
[ "$rc" -eq 1 ] && contains light.log "stability limit" && [ ! -e light.h5 ] && ok refused.dt_guard_light ||
	fail refused.dt_guard_light "exit $rc: $(head -c 300 light.log)"

# --- particle files: a bed prepared with an intruder twice as dense, in both formats ---
shake_run w.log "${FAST[@]}" duration=0 intruder_density=2 write_particles="$TMP/P.txt" write_lammps="$TMP/P.data" output=none
rc=$?
if [ "$rc" -ne 0 ] || [ ! -s P.txt ] || [ ! -s P.data ]; then
	fail pfile.write "exit $rc: $(head -c 300 w.log)"
	finish
fi
RUN=(settle=no "${GENTLE[@]}" duration=0.2 traj_rate=200 snapshots=yes progress=no)
il=$(grep -n ' intruder ' P.txt | cut -d: -f1)
al=$(awk '/^Atoms/ { a = 1 } a && $2 == 2 { print NR; exit }' P.data)
# read under the default material, both files are refused at the intruder's line, naming
# the key that would make it agree and the one that takes the file's masses
for f in P.txt:$il P.data:$al; do
	shake_run r.log particles="$TMP/${f%%:*}" "${RUN[@]}" output="$TMP/r.h5"
	rc=$?
	[ "$rc" -eq 1 ] && contains r.log "$f: intruder" && contains r.log "intruder_density" && contains r.log "particle_mass = file" &&
		[ ! -e r.h5 ] && ok "pfile.refused.${f%%:*}" || fail "pfile.refused.${f%%:*}" "exit $rc: $(head -c 300 r.log)"
done
# under the file's material it runs, and so does particle_mass = file; from the text file the
# two are the same run bit for bit (its m column is the scene's mass, printed exactly)
shake_run s.log particles="$TMP/P.txt" "${RUN[@]}" intruder_density=2 output="$TMP/s.h5" &&
	shake_run f.log particles="$TMP/P.txt" "${RUN[@]}" particle_mass=file output="$TMP/f.h5" &&
	shake_run g.log particles="$TMP/P.data" "${RUN[@]}" particle_mass=file output="$TMP/g.h5"
rc=$?
if [ "$rc" -ne 0 ]; then
	fail pfile.runs "exit $rc: $(head -c 300 s.log f.log g.log)"
	finish
fi
same_output s.h5 f.h5 output particle_mass intruder_density && ok pfile.file_is_scene ||
	fail pfile.file_is_scene "particle_mass = file differs from the scene's mass model with intruder_density = 2"
# the LAMMPS density column gives the masses to rounding: the intruder's 2 pi 2 4 g
awk -v a="$(mass g.h5 1)" -v b="$(mass s.h5 1)" 'BEGIN { pi = 3.141592653589793; exit !(b == 2 * pi * 8 && (a - b) ^ 2 < (1e-12 * b) ^ 2) }' &&
	ok pfile.lammps_mass || fail pfile.lammps_mass "intruder mass $(mass g.h5 1) from the LAMMPS file, $(mass s.h5 1) from the text, expected 16 pi g"
# particle_mass = file takes what the file says: an intruder of mass 100 g exactly
awk -v l="$il" 'NR == l { $8 = 100 } { print }' P.txt >P100.txt
shake_run h.log particles="$TMP/P100.txt" "${RUN[@]}" particle_mass=file duration=0 output="$TMP/h.h5"
[ "$(mass h.h5 1)" = 100 ] && ok pfile.file_mass || fail pfile.file_mass "intruder mass '$(mass h.h5 1)', expected 100: $(head -c 300 h.log)"
# a file without the column: the scene's masses (as before the column existed), but
# particle_mass = file is refused at its first line, and without any particle file
awk '!/^#/ { NF = 7 } { print }' P.txt >P7.txt
first=$(grep -vn '^#' P7.txt | head -n 1 | cut -d: -f1)
shake_run n.log particles="$TMP/P7.txt" "${RUN[@]}" duration=0 output=none && ok pfile.no_column_scene ||
	fail pfile.no_column_scene "$(head -c 300 n.log)"
shake_run n.log particles="$TMP/P7.txt" "${RUN[@]}" particle_mass=file duration=0 output="$TMP/n.h5"
rc=$?
[ "$rc" -eq 1 ] && contains n.log "P7.txt:$first:" && contains n.log "particle_mass = file (command line)" && contains n.log "no mass column" &&
	ok pfile.refused.no_column || fail pfile.refused.no_column "exit $rc: $(head -c 300 n.log)"
printf 'particle_mass = file\n' >pm.ini
shake_run n.log pm.ini "${FAST[@]}" duration=0 output=none
rc=$?
[ "$rc" -eq 1 ] && contains n.log "pm.ini:1" && contains n.log "no particle file" && ok pfile.refused.no_file ||
	fail pfile.refused.no_file "exit $rc: $(head -c 300 n.log)"
finish
