#!/usr/bin/env bash
# materials.sh - an intruder of another material (docs/model.md, "Units and the paper's
# values"): intruder_density sets the intruder's mass and moment of inertia and nothing
# else, its default gives the bits of a run without it, and a bad value is refused with
# its file, line, key and range.
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
finish
