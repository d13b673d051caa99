#!/usr/bin/env bash
# lammps_agreement.sh - the engine and LAMMPS (gran/hooke, dampflag 1, nve/sphere disc;
# tests/bench/lammps/vibrated_box.in) integrate the same settled 200-grain bed for 200
# steps of shaking (f = 3.2 Hz, A = 2 cm, the paper's Y, gamma_N, gamma_S, mu, g, dt) with
# velocity Verlet and end in the same state; a run with other physics does not.
#
# Tolerances. The engine integrates in the box frame (walls at rest, g + a_box(t) on the
# grains), LAMMPS in the lab frame (walls moved by fix move): the two Verlet
# discretisations differ at O(dt^2) and stiff contacts (omega_0 = sqrt(Y/m) ~ 700/s)
# carry that into the state. Measured on this bed after 200 steps: max |dx|, |dy| ~ 5e-7
# cm, |dv| ~ 2e-4 cm/s, |d omega| ~ 4e-5 rad/s. We allow about 10x that:
TOL_POS=5e-6   # cm
TOL_VEL=2e-3   # cm/s   (speeds here are ~50 cm/s: 4e-5 relative)
TOL_OMEGA=5e-4 # rad/s
# and they must catch small physics changes: measured on the same bed, mu 0.5 -> 0.4
# moves omega by ~1.5e-3 rad/s (the Coulomb limit is rarely reached with gamma_S = 1,
# so only omega sees it), gamma_S 1 -> 1.5 by ~0.3 rad/s, Y +1 % positions by ~2e-3 cm.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

if ! command -v lmp >/dev/null 2>&1; then
	fail lammps.available "lmp not found (make deps installs the Debian package lammps)"
	finish
fi
DECK="$REPO/tests/bench/lammps/vibrated_box.in"
[ -f "$DECK" ] || { fail lammps.deck "$DECK missing"; finish; }

STEPS=200 FREQ=3.2 AMP=2
DUR=$(awk -v s=$STEPS 'BEGIN { printf "%.10g", s * 5e-5 }')

# a settled bed (default physics = what the deck hard-codes)
shake_run prep.log n_grains=200 width=30 radius_ratio=2 depth=1 duration=0 progress=no \
	write_lammps="$TMP/bed.data" output="$TMP/prep.h5"
rc=$?
if [ "$rc" -ne 0 ] || [ ! -s bed.data ]; then
	fail prepare "exit $rc: $(head -c 300 prep.log)"
	finish
fi
ok prepare

lmp -in "$DECK" -var data "$TMP/bed.data" -var steps $STEPS -var freq $FREQ -var amp $AMP \
	-var final "$TMP/lmp.dump" -log none -screen none >lmp.log 2>&1
rc=$?
if [ "$rc" -ne 0 ] || [ ! -s lmp.dump ]; then
	fail lammps.run "lmp exit $rc: $(tail -c 300 lmp.log)"
	finish
fi
ok lammps.run
awk '/^ITEM: ATOMS/ { on = 1; next } on' lmp.dump >lmp.rows # id type x y vx vy omegaz

h5col() { h5vals "$@"; } # lib.sh

# engine ID args... : run the engine from the bed, write ID.rows (kind x y vx vy omega)
engine() {
	local id=$1
	shift
	shake_run "$id.log" particles="$TMP/bed.data" settle=no integrator=verlet duration="$DUR" \
		frequency=$FREQ amplitude=$AMP traj_rate=0 snapshots=no progress=no "$@" output="$TMP/$id.h5"
	local rc=$?
	if [ "$rc" -ne 0 ]; then
		fail "$id.run" "exit $rc: $(head -c 300 "$id.log")"
		return 1
	fi
	[ "$(attr "$id.h5" /steps)" = $STEPS ] || { fail "$id.run" "ran $(attr "$id.h5" /steps) steps, expected $STEPS"; return 1; }
	paste -d' ' <(h5col "$id.h5" /final/species) <(h5col "$id.h5" /final/x) <(h5col "$id.h5" /final/y) \
		<(h5col "$id.h5" /final/vx) <(h5col "$id.h5" /final/vy) <(h5col "$id.h5" /final/omega) >"$id.rows"
}

# compare ID : max differences of ID.rows against LAMMPS, row i = atom id i; prints
# "n dpos dvel domega"; mobile disks in all columns, wall disks in position and velocity
compare() {
	paste -d' ' lmp.rows "$1.rows" | awk '
		function a(x) { return x < 0 ? -x : x }
		$1 != NR || $2 != $8 + 1 { print "row " NR ": id " $1 " type " $2 " vs kind " $8; exit 1 }
		{ p = a($3 - $9); if (a($4 - $10) > p) p = a($4 - $10)
		  v = a($5 - $11); if (a($6 - $12) > v) v = a($6 - $12)
		  w = ($2 == 3) ? 0 : a($7 - $13)
		  if (p > P) P = p; if (v > V) V = v; if (w > W) W = w; if ($2 != 3) nm++ }
		END { printf "%d %d %.3g %.3g %.3g\n", NR, nm, P, V, W }'
}
within() { # "n nm dpos dvel domega" -> true when all within the tolerances
	awk -v s="$1" -v tp=$TOL_POS -v tv=$TOL_VEL -v tw=$TOL_OMEGA 'BEGIN { split(s, f, " ")
		exit !(f[3] <= tp && f[4] <= tv && f[5] <= tw) }'
}

engine same || finish
natoms=$(wc -l <lmp.rows)
[ "$natoms" = "$(wc -l <same.rows)" ] && [ "$natoms" -gt 250 ] && ok atoms ||
	fail atoms "LAMMPS has $natoms atoms, the engine $(wc -l <same.rows)"
r=$(compare same) || { fail agree "$r"; finish; }
echo "# engine vs LAMMPS: atoms mobile max|dpos| max|dv| max|domega| = $r" >&2
if within "$r"; then ok agree; else
	fail agree "differences (atoms, mobile, pos cm, vel cm/s, omega rad/s) $r exceed $TOL_POS, $TOL_VEL, $TOL_OMEGA"; fi

# the check has teeth: other physics in the engine must fall outside the tolerances
for p in mu=0.4 gamma_s=1.5 stiffness=3.03e6; do
	id=teeth_${p%%=*}
	engine "$id" "$p" || continue
	r=$(compare "$id") || { fail "$id" "$r"; continue; }
	echo "# engine with $p vs LAMMPS: $r" >&2
	if within "$r"; then fail "$id" "engine with $p agrees with LAMMPS within the tolerances ($r): the check cannot see it"; else ok "$id"; fi
done
finish
