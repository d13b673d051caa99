#!/usr/bin/env bash
# lammps_collisions.sh - the three contact laws (docs/model.md "Contact law", "Normal law",
# "Restitution") checked against LAMMPS on single two-disk collisions (`make
# validate-collisions`; docs/validate_lammps.md, "Two-disk collisions").
#
# Laws: hooke (LAMMPS gran/hooke, dampflag 1, Kt 0), restitution (gran/hooke with the
# pair's damping 2 zeta sqrt(Y m_eff) from e, and both codes' e of two mobile disks checked
# against the input e), hertz (LAMMPS gran/hertz/history, Kt ~ 0, see deck()). Cases, gravity off, relative approach speed 50 cm/s:
#   equal     two unit disks head-on
#   intruder  a unit grain head-on against the intruder of radius 4
#   oblique   two unit disks without spin, impact parameter (R_i + R_j)/2: the rebound spin
#   sliding   the same with gamma_s = 1e4 s^-1, so that the shear force reaches mu |F_N|
#             (hertz: against pair_style granular, spin tolerance SPIN_TOL_LEVER, see deck())
#   wall      a unit grain onto a wall disk of radius 1 (LAMMPS: an atom that is not
#             integrated; its mass enters m_eff as the engine's wall_mass = disk)
# The engine's side is tests/bench/lammps_collision.c (its own force and verlet code);
# LAMMPS gets the law's values and the masses that program prints (m = mass_factor rho R^2,
# docs/model.md "Units", given to LAMMPS with `set atom N mass`). Both sides' trajectories,
# every step, go through one analysis: the contact starts and ends where the overlap
# xi = R_i + R_j - d changes sign (linear interpolation between steps), e = the normal
# relative speed after / before (each along the normal of its crossing), spin = omega of
# disk 0 after the contact (rad/s, counter-clockwise).
#
# Tolerances: relative 1e-3 on e, t_c and the spin (absolute 1e-6 rad/s where both spins are
# ~0, the head-on cases). Both codes integrate with velocity Verlet at DT; the engine's
# column "conv" is the largest relative change of e, t_c and spin from DT to DT/2, which must
# be below 1e-4 for the comparison to mean anything (checked too): what is left beyond that
# is a difference of the laws. Measured: the two codes agree to the last printed digit
# (docs/validate_lammps.md, "Two-disk collisions").
#
# Knobs: COLL_DT (5e-6 s), LMP (lmp), COLL_BIN (the engine's program),
# COLL_ENGINE_ARGS ("KEY=VALUE ...", applied to the engine only: shows that a difference in
# a law is caught, e.g. COLL_ENGINE_ARGS=gamma_n=101 must fail), COLL_LAWS, COLL_CASES.
# Exit 0: all agree; 1: some disagree; 2: a run failed.
set -euo pipefail
REPO=$(cd "$(dirname "$0")/../.." && pwd)
BIN=${COLL_BIN:-$REPO/build/rel/tests/bench/lammps_collision}
LMP=${LMP:-lmp}
DT=${COLL_DT:-1e-6}
ENGINE_ARGS=${COLL_ENGINE_ARGS:-}
LAWS=${COLL_LAWS:-hooke restitution hertz}
CASES=${COLL_CASES:-equal intruder oblique sliding wall}
TOL=1e-3 TOL_W_ABS=1e-6 TOL_CONV=1e-4
# hertz sliding against pair_style granular (see deck()): the lever R_i - xi/2 against the
# engine's R_i is up to xi_max / 2R = 2 % shorter (xi_max = 0.04 cm at 43 cm/s), so the
# spin may differ by about 1 %; e and t_c feel it only through the shear force's work
SPIN_TOL_LEVER=1e-2

die() { echo "lammps_collisions.sh: $*" >&2; exit 2; }
[ -x "$BIN" ] || die "no $BIN: build it with 'make $(realpath --relative-to="$REPO" "$BIN" 2>/dev/null || echo "$BIN")'"
command -v "$LMP" >/dev/null || die "no LAMMPS binary '$LMP' (Debian: apt-get install lammps; or set LMP)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# the analysis of one trajectory ("step x0 y0 vx0 vy0 w0 x1 y1 vx1 vy1 w1", '#' lines skipped):
# prints "e tc spin", or "fail REASON"
analyse() { # FILE R0 R1 DT
	awk -v r0="$2" -v r1="$3" -v dt="$4" '
	function nrm(k, f,  dx, dy, d) { # unit normal (r0 - r1)/d at step k-1+f
		dx = (1 - f) * (px0 - px1) + f * ($2 - $7); dy = (1 - f) * (py0 - py1) + f * ($3 - $8)
		d = sqrt(dx * dx + dy * dy); nx = dx / d; ny = dy / d }
	/^#/ { next }
	{
		xi = rs - sqrt(($2 - $7) ^ 2 + ($3 - $8) ^ 2)
		if (NR > 1 && !started && pxi <= 0 && xi > 0) {
			f = -pxi / (xi - pxi); ts = ($1 - 1 + f) * dt; started = 1
			nrm($1, f); vb = -((v0x - v1x) * nx + (v0y - v1y) * ny)
		} else if (started && !ended && pxi > 0 && xi <= 0) {
			f = pxi / (pxi - xi); te = ($1 - 1 + f) * dt; ended = 1
			nrm($1, f); enx = nx; eny = ny
		}
		if (NR == 1 || !started) { v0x = $4; v0y = $5; v1x = $9; v1y = $10 }
		pxi = xi; px0 = $2; py0 = $3; px1 = $7; py1 = $8; last = $0
	}
	BEGIN { rs = r0 + r1 }
	END {
		if (!started) { print "fail no_contact"; exit }
		if (!ended) { print "fail contact_did_not_end"; exit }
		split(last, L, " ")
		va = (L[4] - L[9]) * enx + (L[5] - L[10]) * eny
		printf "%.12g %.12g %.12g\n", va / vb, te - ts, L[6]
	}' "$1"
}

# one key of the engine's header line
hdr() { sed -n '1s/.* '"$2"'=\([^ ]*\).*/\1/p' "$1"; }

# the LAMMPS deck of one case, from the engine's header (law values before any override)
deck() { # LAW CASE HEADER DUMP
	local law=$1 cs=$2 h=$3 dump=$4
	local Y gn gs mu K e r0 r1 m0 m1 wall gap v
	Y=$(hdr "$h" stiffness) gn=$(hdr "$h" gamma_n) gs=$(hdr "$h" gamma_s) mu=$(hdr "$h" mu)
	K=$(hdr "$h" hertz_stiffness) e=$(hdr "$h" restitution) r0=$(hdr "$h" r0) r1=$(hdr "$h" r1)
	m0=$(hdr "$h" m0) m1=$(hdr "$h" m1) wall=$(hdr "$h" wall) gap=$(hdr "$h" gap) v=$(hdr "$h" v)
	[ "$cs" = sliding ] && gs=1e4
	local b=0 x1 y1 vx0 vy0 vx1
	[ "$cs" = oblique ] || [ "$cs" = sliding ] && b=$(awk -v a="$r0" -v c="$r1" 'BEGIN{print 0.5*(a+c)}')
	local pair
	case $law in
	hooke) pair="pair_style gran/hooke $Y 0.0 $gn $gs $mu 1
pair_coeff * *" ;;
	hertz)
		# Kt: LAMMPS's history styles divide by Kt when a contact slides (Kt = 0 gives NaN),
		# so Kt = 1e-6: its spring force, Kt sqrt(xi R_eff) |shear| < 1e-7 dyn, is ~1e-11 of
		# the shear force here
		pair="pair_style gran/hertz/history $K 1e-6 $gn $gs $mu 1
pair_coeff * *"
		# Sliding: gran/hertz/history's slip branch rescales the shear history so that the
		# spring Kt*shear holds the force beyond mu |F_N|, whatever Kt is: a memory the
		# engine's law has not. pair_style granular has the law without history (hertz:
		# K sqrt(xi R_eff) xi; damping viscoelastic: gamma_n sqrt(xi R_eff) m_eff;
		# linear_nohistory: x_gamma,t times that, x_gamma,t = gamma_s / gamma_n), but applies
		# the shear force at the contact point, R_i - xi/2 from the centre: SPIN_TOL_LEVER.
		[ "$cs" = sliding ] && pair="pair_style granular
pair_coeff * * hertz $K $gn damping viscoelastic tangential linear_nohistory $(awk -v a="$gs" -v b="$gn" 'BEGIN{printf "%.17g", a/b}') $mu" ;;
	restitution)
		# the law's damping for this pair, gamma_N m_eff = 2 zeta sqrt(Y m_eff), given to
		# gran/hooke as gamma_n = 2 zeta sqrt(Y / m_eff): LAMMPS then computes the engine's
		# forces by its own code, the engine sets its damping from e by its own code. (LAMMPS
		# pair_style granular's `damping coeff_restitution` is the same normal law, but its
		# tangential force acts at the contact point, R_i - xi/2 from the centre, not at R_i:
		# docs/validate_lammps.md "Two-disk collisions"; the Debian LAMMPS of 29 Sep 2021 lacks it.)
		local g
		g=$(awk -v Y="$Y" -v e="$e" -v a="$m0" -v c="$m1" 'BEGIN {
			m = a * c / (a + c); l = -log(e); z = l / sqrt(3.141592653589793^2 + l * l)
			printf "%.17g", 2 * z * sqrt(Y / m) }')
		pair="pair_style gran/hooke $Y 0.0 $g $gs $mu 1
pair_coeff * *" ;;
	esac
	if [ "$wall" = 1 ]; then
		x1=0 y1=0 vx0=0 vy0=-$v vx1=0
		local y0; y0=$(awk -v a="$r0" -v c="$r1" -v g="$gap" 'BEGIN{printf "%.17g", a+c+g}')
		local x0=0
	else
		x1=$(awk -v s="$r0" -v t="$r1" -v g="$gap" -v b="$b" 'BEGIN{d=s+t+g; printf "%.17g", sqrt(d*d-b*b)}')
		y1=-$b x0=0 y0=0 vy0=0
		vx0=$(awk -v v="$v" -v a="$m0" -v c="$m1" 'BEGIN{printf "%.17g", v*c/(a+c)}')
		vx1=$(awk -v v="$v" -v a="$m0" -v c="$m1" 'BEGIN{printf "%.17g", -v*a/(a+c)}')
	fi
	local steps; steps=$(awk -v dt="$DT" 'BEGIN{printf "%d", 0.012/dt+0.5}')
	cat <<EOD
units cgs
dimension 2
atom_style sphere
boundary f f p
comm_modify vel yes
region box block -20 20 -20 20 -0.5 0.5
create_box 2 box
create_atoms 1 single $x0 $y0 0
create_atoms 2 single $x1 $y1 0
set atom 1 diameter $(awk -v r="$r0" 'BEGIN{print 2*r}')
set atom 2 diameter $(awk -v r="$r1" 'BEGIN{print 2*r}')
set atom 1 mass $m0
set atom 2 mass $m1
velocity all set 0 0 0
set atom 1 vx $vx0 vy $vy0
set atom 2 vx $vx1
$pair
neighbor 0.5 bin
neigh_modify every 1 delay 0 check yes
timestep $DT
group moving $( [ "$wall" = 1 ] && echo "id 1" || echo "id 1 2")
fix integ moving nve/sphere disc
fix twod all enforce2d
dump d all custom 1 $dump id x y vx vy omegaz
dump_modify d sort id format float %.17g
thermo $steps
run $steps
EOD
}

# a LAMMPS dump of 2 atoms -> the engine's columns
dump2cols() {
	awk '/^ITEM: TIMESTEP/ { getline; s = $1; next }
	     /^ITEM: ATOMS/ { getline; a = $2" "$3" "$4" "$5" "$6; getline; print s, a, $2, $3, $4, $5, $6 }' "$1"
}

half=$(awk -v d="$DT" 'BEGIN{printf "%.17g", d/2}')
printf '# two-disk collisions, dt = %s s%s\n' "$DT" "${ENGINE_ARGS:+, engine only: $ENGINE_ARGS}"
printf '%-11s %-9s %12s %12s %9s %12s %12s %9s %12s %12s %9s %9s %s\n' law case e_shake e_lammps rel_e \
	tc_shake_ms tc_lammps_ms rel_tc spin_shake spin_lammps rel_spin conv verdict
bad=0
for law in $LAWS; do
	for cs in $CASES; do
		ecase=$cs extra=""
		[ "$cs" = sliding ] && ecase=oblique extra="gamma_s=1e4"
		# shellcheck disable=SC2086
		"$BIN" "$law" "$ecase" "$DT" $extra $ENGINE_ARGS >"$work/s.txt" || die "engine run $law $cs failed"
		# shellcheck disable=SC2086
		"$BIN" "$law" "$ecase" "$half" $extra $ENGINE_ARGS >"$work/s2.txt" || die "engine run $law $cs (dt/2) failed"
		# the LAMMPS side from an engine header without ENGINE_ARGS
		"$BIN" "$law" "$ecase" "$DT" >"$work/h.txt" || die "engine run $law $cs (header) failed"
		deck "$law" "$cs" "$work/h.txt" "$work/l.dump" >"$work/l.in"
		"$LMP" -in "$work/l.in" -log "$work/l.log" -screen none >/dev/null 2>&1 ||
			die "LAMMPS failed on $law $cs (deck and log: keep them with a copy of $work): $(tail -3 "$work/l.log")"
		dump2cols "$work/l.dump" >"$work/l.txt"
		r0=$(hdr "$work/h.txt" r0) r1=$(hdr "$work/h.txt" r1)
		read -r es ts ws < <(analyse "$work/s.txt" "$r0" "$r1" "$DT")
		read -r e2 t2 w2 < <(analyse "$work/s2.txt" "$r0" "$r1" "$half")
		read -r el tl wl < <(analyse "$work/l.txt" "$r0" "$r1" "$DT")
		case "$es $ts $ws $e2 $t2 $w2 $el $tl $wl" in
		*nan* | *inf* | *NAN* | *INF*) die "$law $cs: a run gave NaN/Inf (engine $es $ts $ws, dt/2 $e2 $t2 $w2, LAMMPS $el $tl $wl)" ;;
		esac
		for x in "$es" "$e2" "$el"; do
			[ "$x" = fail ] && die "$law $cs: a run's contact was not measured (engine $es $ts, dt/2 $e2 $t2, LAMMPS $el $tl)"
		done
		# restitution law, two mobile disks: e must be the input e (docs/model.md "Restitution")
		ein=0
		[ "$law" = restitution ] && { [ "$cs" = equal ] || [ "$cs" = intruder ]; } && ein=$(hdr "$work/h.txt" restitution)
		tolw=$TOL
		[ "$law $cs" = "hertz sliding" ] && tolw=$SPIN_TOL_LEVER
		line=$(awk -v tolw="$tolw" -v ein="$ein" -v es="$es" -v ts="$ts" -v ws="$ws" -v e2="$e2" -v t2="$t2" -v w2="$w2" \
			-v el="$el" -v tl="$tl" -v wl="$wl" -v tol="$TOL" -v wabs="$TOL_W_ABS" -v tconv="$TOL_CONV" '
			function a(x) { return x < 0 ? -x : x }
			function rel(x, y) { return a(x - y) / a(y) }
			function relw(x, y) { return a(x) < wabs && a(y) < wabs ? 0 : rel(x, y) }
			BEGIN {
				re = rel(es, el); rt = rel(ts, tl); rw = relw(ws, wl)
				c = rel(e2, es); if (rel(t2, ts) > c) c = rel(t2, ts); if (relw(w2, ws) > c) c = relw(w2, ws)
				v = "agree"
				if (c > tconv) v = "NOT-CONVERGED"
				else if (re > tol || rt > tol || rw > tolw) v = "DIFFER"
				else if (ein > 0 && (rel(es, ein) > tol || rel(el, ein) > tol)) v = "E-NOT-INPUT"
				printf "%12.6f %12.6f %9.1e %12.6f %12.6f %9.1e %12.6g %12.6g %9.1e %9.1e %s",
					es, el, re, ts * 1e3, tl * 1e3, rt, ws, wl, rw, c, v }')
		printf '%-11s %-9s %s\n' "$law" "$cs" "$line"
		case $line in *agree) ;; *) bad=1 ;; esac
	done
done
if [ $bad = 0 ]; then
	echo "lammps_collisions.sh: all agree (relative tolerance $TOL, converged to $TOL_CONV)"
else
	echo "lammps_collisions.sh: some collisions DIFFER or are not converged (above)" >&2
	exit 1
fi
