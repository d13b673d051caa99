#!/usr/bin/env bash
# regress.sh - the regression scenes and how their outputs are reduced to text. Sourced by
# tests/integration/regression.sh (compare) and run by hand to write the references:
#     bash tests/reference/regress.sh write      (after a deliberate change of the physics
#                                                  or of the order of a floating-point sum)
# Each scene is small and short (a shaken 150-grain bed with an intruder, 0.5 s, every
# integrator), so the comparison is exact: the engine's arithmetic is fixed (no FMA
# contraction, no reassociation, no threads), and any difference in the %.17g text is a
# change of the physics, of the recipe or of the order in which forces are summed.
set -u
REGRESS_SCENE=(n_grains=150 width=24 radius_ratio=2.5 depth=1 settle_ke=1 settle_min=0.2
	duration=0.5 frequency=4 amplitude=1 traj_rate=100 snapshots=no progress=no seed=11)
REGRESS_CASES=(gear5 gear4 verlet)

# regress_reduce FILE.h5 : the final state of every disk and the intruder trajectory, as text
# (the trajectory as rows t x y vx vy omega, the layout of the references, gathered from
# the H5MD group /particles/intruder)
regress_reduce() {
	local f=$1 d
	for d in /final/x /final/y /final/vx /final/vy /final/omega /final/theta; do
		echo "# $d"
		regress_vals "$f" "$d"
	done
	echo "# /intruder/trajectory"
	local g=/particles/intruder
	paste -d' ' <(regress_vals "$f" $g/position/time) <(regress_vals "$f" $g/position/value | paste -d' ' - -) \
		<(regress_vals "$f" $g/velocity/value | paste -d' ' - -) <(regress_vals "$f" $g/angular_velocity/value) |
		tr ' ' '\n'
}

# regress_vals FILE DATASET : its values, one per line, %.17g
regress_vals() {
	h5dump -m %.17g -d "$2" -y -w 100000 "$1" | awk '/^ *DATA \{/ && !done { on = 1; next } on && /^ *\}/ { on = 0; done = 1 } on' |
		tr ',' '\n' | sed 's/^ *//; /^$/d'
}

# regress_run SHAKE CASE OUT.h5 : run one case (integrator CASE at its own preset dt)
regress_run() {
	local shake=$1 c=$2 out=$3
	local dt=5e-5
	[ "$c" = verlet ] && dt=1e-4
	"$shake" "${REGRESS_SCENE[@]}" integrator="$c" dt="$dt" output="$out"
}

if [ "${BASH_SOURCE[0]}" = "$0" ] && [ "${1:-}" = write ]; then
	cd "$(dirname "$0")/../.." || exit 1
	tmp=$(mktemp -d)
	trap 'rm -rf "$tmp"' EXIT
	for c in "${REGRESS_CASES[@]}"; do
		regress_run bin/shake "$c" "$tmp/$c.h5" || exit 1
		regress_reduce "$tmp/$c.h5" >"tests/reference/$c.txt" || exit 1
		echo "wrote tests/reference/$c.txt ($(wc -l <"tests/reference/$c.txt") lines)"
	done
fi
