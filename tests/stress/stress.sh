#!/usr/bin/env bash
# stress.sh - numerical-stability stress tests (`make stress`).
# Prints "ok ID" / "FAIL ID: why" per check and writes tables to
# build/stress/report.txt and a plot build/stress/dt_max.png:
#  (i)   the largest stable dt of each integrator for stiffness Y = 3e5 .. 3e8 (bisection
#        in log dt on a short shaken run), against the contact time t_c, and a guard rule;
#  (ii)  a settled paper bed left without vibration for 1e7 steps (kinetic energy, creep
#        of the intruder and of the mean height, heating);
#  (iii) wide beds up to 1e5 grains (width scaled with N): the largest overlap settled and
#        shaken, plus a deep column (N = 3000 in the paper's 60 cm box);
#  (iv)  violent driving (f up to 30 Hz), large intruders (R up to 12), zero damping,
#        zero friction: each ends as a valid run or a clear blow-up, never with NaN.
# Knobs: STRESS_QUICK=1 (a few minutes: fewer Y, 1e6 rest steps, N <= 1e4), JOBS (2).
set -u
cd "$(dirname "$0")/../.."
REPO=$PWD
SHAKE=${SHAKE:-$REPO/bin/shake}
OVL=${STRESS_OVL:-$REPO/build/rel/tests/stress/maxoverlap}
QUICK=${STRESS_QUICK:-0}
JOBS=${JOBS:-2}
OUT=${STRESS_OUT:-$REPO/build/stress}
. "$REPO/tests/stress/lib.sh"
mkdir -p "$OUT"
cd "$OUT" || exit 2
REPORT=$OUT/report.txt
export SHAKE OVL OUT
NOK=0 NFAIL=0
ok() { echo "ok $1"; NOK=$((NOK + 1)); }
fail() { echo "FAIL $1: $2"; NFAIL=$((NFAIL + 1)); }

if [ "$QUICK" = 1 ]; then
	YS="3e5 3e6 3e7 3e8" REST_STEPS=1000000 DEEP_N="1000 10000" COLUMN_N="" BISECT=5
else
	YS="3e5 1e6 3e6 1e7 3e7 1e8 3e8" REST_STEPS=10000000 DEEP_N="1000 10000 100000" COLUMN_N=3000 BISECT=7
fi
{
	echo "shakebox stress tests  $(date '+%Y-%m-%d %H:%M:%S')"
	echo "  engine $SHAKE ($("$SHAKE" --version 2>/dev/null | head -n 1)); STRESS_QUICK=$QUICK JOBS=$JOBS"
	echo "  load average at start $(cut -d' ' -f1-3 /proc/loadavg)"
	echo
} >"$REPORT"

# contact time of the stiffest pair (two r_min = 0.85 cm grains, m = 2 pi rho R^2):
# t_c = pi / sqrt(Y / m_eff - (gamma_N / 2)^2)
tc_of() { awk -v Y="$1" 'BEGIN { m = 2 * 3.141592653589793 * 0.85 * 0.85; me = m / 2
	printf "%.6g\n", 3.141592653589793 / sqrt(Y / me - 2500) }'; }
export -f tc_of

# ---------------------------------------------------------------- (i) largest stable dt
# bed per Y: 240 grains, 2x intruder, 30 cm box, settled with dt = t_c / 60
STAB_BED=(n_grains=240 width=30 radius_ratio=2 depth=1)
# stable_run Y INTEG DT NAME : 0 when stable (exit 0, kinetic energy per disk at the end
# within 5x and the largest overlap within max(2x, +0.1) of the run at t_c / 60)
stable_run() {
	local Y=$1 ig=$2 dt=$3 name=$4 d=$OUT/dt/Y$1
	# dt_guard = off: this bisection is what measures the limits the guard enforces
	"$SHAKE" particles="$d/bed.txt" settle=no stiffness="$Y" integrator="$ig" dt="$dt" duration=0.5 \
		max_overlap=0.9 snapshots=no traj_rate=0 progress=no dt_guard=off output="$d/$name.h5" >"$d/$name.log" 2>&1
	local rc=$?
	[ "$rc" -eq 0 ] || return 1
	no_nonfinite "$d/$name.h5" || return 1
	local ke ov
	read -r _ ke _ _ <<<"$(final_stats "$d/$name.h5")"
	ov=$("$OVL" "$d/$name.h5" | awk '{ print $2 }')
	echo "$ke $ov" >"$d/$name.sane"
	[ "$name" = "safe_$ig" ] && return 0
	read -r ke0 ov0 <"$d/safe_$ig.sane"
	awk -v k="$ke" -v o="$ov" -v k0="$ke0" -v o0="$ov0" 'BEGIN {
		lim = 2 * o0; if (o0 + 0.1 > lim) lim = o0 + 0.1
		exit !(k <= 5 * k0 + 1e-3 && o <= lim) }'
}
bisect_dt() { # Y INTEG -> "Y integ t_c dt_max ratio note"
	local Y=$1 ig=$2 tc lo hi mid note=""
	tc=$(tc_of "$Y")
	lo=$(awk -v t="$tc" 'BEGIN { printf "%.6g", t / 60 }')
	hi=$(awk -v t="$tc" 'BEGIN { printf "%.6g", t * 2 }')
	if ! stable_run "$Y" "$ig" "$lo" "safe_$ig"; then
		echo "$Y $ig $tc 0 0 unstable_at_tc/60"
		return
	fi
	if stable_run "$Y" "$ig" "$hi" "hi_$ig"; then
		echo "$Y $ig $tc $hi $(awk -v a="$hi" -v t="$tc" 'BEGIN { printf "%.4f", a / t }') stable_at_2tc"
		return
	fi
	for k in $(seq 1 "$BISECT"); do
		mid=$(awk -v a="$lo" -v b="$hi" 'BEGIN { printf "%.6g", sqrt(a * b) }')
		if stable_run "$Y" "$ig" "$mid" "b${k}_$ig"; then lo=$mid; else hi=$mid; fi
	done
	echo "$Y $ig $tc $lo $(awk -v a="$lo" -v t="$tc" 'BEGIN { printf "%.4f", a / t }') first_unstable=$hi"
}
export -f stable_run bisect_dt no_nonfinite final_stats h5col
export BISECT
echo "(i) largest stable dt, Y = $YS" >&2
settle_y() {
	local Y=$1 d=$OUT/dt/Y$1 dt
	mkdir -p "$d"
	dt=$(awk -v t="$(tc_of "$Y")" 'BEGIN { printf "%.6g", t / 60 }')
	[ -s "$d/bed.txt" ] || "$SHAKE" n_grains=240 width=30 radius_ratio=2 depth=1 stiffness="$Y" dt="$dt" \
		duration=0 max_overlap=0.9 write_particles="$d/bed.txt" output="$d/prep.h5" progress=no >"$d/prep.log" 2>&1
}
export -f settle_y
printf '%s\n' $YS | parallel -j "$JOBS" settle_y
for Y in $YS; do for ig in gear5 gear4 verlet; do echo "$Y $ig"; done; done |
	parallel -j "$JOBS" -k --colsep ' ' bisect_dt {1} {2} >dtmax.tsv
{
	echo "(i) Largest stable dt (bisection in log dt, $BISECT halvings, bracket [t_c/60, 2 t_c]) on a 240-grain bed"
	echo "    (2x intruder, 30 cm box) settled at each Y, shaken 0.5 s at 3.2 Hz, A = 2 cm. Stable = exit 0, no"
	echo "    NaN, kinetic energy at the end <= 5x and largest overlap <= max(2x, +0.1) of the run at t_c / 60."
	echo "    t_c = pi / sqrt(Y / m_eff - (gamma_N/2)^2) for the stiffest pair (two r_min = 0.85 cm grains)."
	printf "    %-8s %-7s %11s %11s %8s  %s\n" Y integ t_c dt_max dt/t_c note
	awk '{ printf "    %-8s %-7s %11s %11s %8s  %s\n", $1, $2, $3, $4, $5, $6 }' dtmax.tsv
	awk '{ r[$2] = (r[$2] == "" || $5 < r[$2]) ? $5 : r[$2] } END {
		printf "    guard (smallest dt_max / t_c over Y):"; for (i in r) printf " %s %.3f;", i, r[i]; printf "\n" }' dtmax.tsv
	echo
} >>"$REPORT"
for ig in gear5 gear4 verlet; do
	n=$(awk -v i="$ig" '$2 == i && $4 > 0' dtmax.tsv | wc -l)
	[ "$n" -gt 0 ] && ok "stress.dt_max.$ig.found" || fail "stress.dt_max.$ig.found" "no stable dt found"
	# the paper's dt must be stable at the paper's stiffness
	awk -v i="$ig" '$1 == "3e6" && $2 == i { exit !($4 >= 5e-5) }' dtmax.tsv && ok "stress.dt_max.$ig.paper_dt_stable" ||
		fail "stress.dt_max.$ig.paper_dt_stable" "dt_max at Y = 3e6 below 5e-5"
done
gnuplot <<EOF 2>/dev/null
set terminal pngcairo size 900,600 font ',11'
set output '$OUT/dt_max.png'
set logscale xy
set grid
set key top left
set xlabel 'contact time t_c [s] (stiffest pair)'
set ylabel 'largest stable dt [s]'
set title 'Largest stable time step against contact time (Y = 3e5 .. 3e8)'
plot for [ig in 'gear5 gear4 verlet'] '$OUT/dtmax.tsv' using (strcol(2) eq ig ? \$3 : 1/0):(\$4 > 0 ? \$4 : 1/0) with linespoints pt 7 title ig, \
     x / 10 with lines dt 2 lc rgb 'gray' title 'dt = t_c / 10', x / 20 with lines dt 3 lc rgb 'gray' title 'dt = t_c / 20'
EOF

# ---------------------------------------------------------------- (ii) long rest
echo "(ii) rest, $REST_STEPS steps" >&2
[ -s bed_paper.txt ] || "$SHAKE" duration=0 write_particles=bed_paper.txt output=bed_paper.h5 progress=no >bed_paper.log 2>&1
rest_run() { # integ
	local dur
	dur=$(awk -v n="$REST_STEPS" 'BEGIN { printf "%.10g", n * 5e-5 }')
	# amplitude 0: no vibration; frequency sets only the snapshot period (10 snapshots)
	"$SHAKE" particles="$OUT/bed_paper.txt" settle=no amplitude=0 frequency="$(awk -v d="$dur" 'BEGIN { printf "%.10g", 10 / d }')" \
		integrator="$1" dt=5e-5 duration="$dur" traj_rate="$(awk -v d="$dur" 'BEGIN { printf "%.10g", 200 / d }')" \
		max_overlap=0.9 progress=no output="$OUT/rest_$1.h5" >"$OUT/rest_$1.log" 2>&1
	echo $? >"$OUT/rest_$1.rc"
}
export -f rest_run
export REST_STEPS
printf '%s\n' gear5 gear4 verlet | parallel -j "$JOBS" rest_run
{
	echo "(ii) Settled paper bed (950 grains + R = 4 intruder, settled below 0.01 erg per disk) left without"
	echo "     vibration (amplitude = 0) for $REST_STEPS steps at dt = 5e-5 ($(awk -v n="$REST_STEPS" 'BEGIN { print n * 5e-5 }') s)."
	echo "     ke = kinetic energy per disk at the end; mean height of the grains at the 10 snapshots (first -> last,"
	echo "     largest step between snapshots after the first interval, which still holds the last
     compaction below the settle criterion); intruder height range over the run and its largest speed."
	printf "     %-7s %4s %11s %13s %13s %11s %11s %11s %9s\n" integ exit ke_end_erg y_first y_last max_step_cm intr_range intr_vmax cpu_s
} >>"$REPORT"
for ig in gear5 gear4 verlet; do
	rc=$(cat "rest_$ig.rc")
	if [ "$rc" != 0 ]; then
		fail "stress.rest.$ig.runs" "exit $rc: $(head -c 300 "rest_$ig.log")"
		continue
	fi
	ok "stress.rest.$ig.runs"
	read -r n ke ybar vmax <<<"$(final_stats "rest_$ig.h5")"
	read -r y1 yl step <<<"$(snap_mobile_y "rest_$ig.h5" | awk -v n="$n" '
		{ s += $1; c++; if (c == n) { m[k++] = s / n; s = c = 0 } }
		END { for (i = 2; i < k; i++) { d = m[i] - m[i - 1]; if (d < 0) d = -d; if (d > mx) mx = d }
		      printf "%.9f %.9f %.3e\n", m[0], m[k - 1], mx }')"
	read -r irange ivmax <<<"$(intruder_rows "rest_$ig.h5" | awk '{ c = (NR - 1) % 6; v[c] = $1
		if (c == 5) { if (!k++) lo = hi = v[2]; if (v[2] < lo) lo = v[2]; if (v[2] > hi) hi = v[2]
		s = sqrt(v[3] * v[3] + v[4] * v[4]); if (s > vm) vm = s } } END { printf "%.3e %.3e\n", hi - lo, vm }')"
	cpu=$(attr_val "rest_$ig.h5" provenance/loop_seconds)
	[ -z "$cpu" ] && cpu=$(h5dump -a /provenance/loop_seconds "rest_$ig.h5" 2>/dev/null | awk '/\(0\)/ { print $2 }')
	printf "     %-7s %4s %11s %13s %13s %11s %11s %11s %9s\n" "$ig" "$rc" "$ke" "$y1" "$yl" "$step" "$irange" "$ivmax" "$cpu" >>"$REPORT"
	awk -v k="$ke" 'BEGIN { exit !(k < 1e-3) }' && ok "stress.rest.$ig.no_heating" ||
		fail "stress.rest.$ig.no_heating" "kinetic energy per disk $ke erg >= 1e-3 at the end"
	awk -v s="$step" 'BEGIN { exit !(s < 1e-3) }' && ok "stress.rest.$ig.no_creep.mean_height" ||
		fail "stress.rest.$ig.no_creep.mean_height" "mean height moved $step cm between snapshots"
	awk -v d="$irange" 'BEGIN { exit !(d < 1e-2) }' && ok "stress.rest.$ig.no_creep.intruder" ||
		fail "stress.rest.$ig.no_creep.intruder" "intruder height range $irange cm"
done
echo >>"$REPORT"

# ---------------------------------------------------------------- (iii) deep / wide beds
echo "(iii) beds N = $DEEP_N ${COLUMN_N:+, column $COLUMN_N}" >&2
deep_run() { # N WIDTH TAG
	local n=$1 w=$2 tag=$3
	/usr/bin/time -f '%e' -o "$OUT/deep_$tag.settle_time" "$SHAKE" n_grains="$n" width="$w" duration=0 \
		max_overlap=0.9 settle_max=120 snapshots=no write_particles="$OUT/deep_$tag.txt" \
		output="$OUT/deep_${tag}_settled.h5" progress=no >"$OUT/deep_$tag.log" 2>&1
	echo $? >"$OUT/deep_$tag.rc0"
	"$SHAKE" particles="$OUT/deep_$tag.txt" settle=no duration=1.25 max_overlap=0.9 snapshots=yes traj_rate=0 \
		output="$OUT/deep_${tag}_shaken.h5" progress=no >>"$OUT/deep_$tag.log" 2>&1
	echo $? >"$OUT/deep_$tag.rc1"
}
export -f deep_run
{
	for n in $DEEP_N; do echo "$n $(awk -v n="$n" 'BEGIN { printf "%.6g", 60 * n / 950 }') wide$n"; done
	for n in $COLUMN_N; do echo "$n 60 column$n"; done
} | parallel -j "$JOBS" --colsep ' ' deep_run {1} {2} {3}
{
	echo "(iii) Largest overlap / smaller radius (maxoverlap over the recorded states: settled = the state at"
	echo "      the start of shaking; shaken = /final and 4 stroboscopic snapshots of 1.25 s at 3.2 Hz, A = 2 cm)."
	echo "      Runs with max_overlap = 0.9 (the engine would stop at 0.6 by default). hydrostatic = the"
	echo "      overlap of a bottom contact carrying its column's weight, W / (2 cos 30 Y), / r_min."
	printf "      %-12s %8s %8s %6s %9s %9s %9s %11s %s\n" bed N width exit settled shaken_fin shaken_snap hydrostatic settle_wall_s
} >>"$REPORT"
for tag in $(for n in $DEEP_N; do echo "wide$n"; done) $(for n in $COLUMN_N; do echo "column$n"; done); do
	rc0=$(cat "deep_$tag.rc0") rc1=$(cat "deep_$tag.rc1")
	s0=- f1=- s1=-
	[ "$rc0" = 0 ] && s0=$("$OVL" "deep_${tag}_settled.h5" | awk '{ print $2 }')
	[ -s "deep_${tag}_shaken.h5" ] && read -r f1 s1 <<<"$("$OVL" "deep_${tag}_shaken.h5" | awk '{ print $2, $4 }')"
	n=$(attr_val "deep_${tag}_settled.h5" parameters/n_grains) w=$(attr_val "deep_${tag}_settled.h5" parameters/width)
	# The load decides how far soft disks overlap: the bottom contacts of a column of
	# height h carry its weight, W = (2 phi h / (pi R)) m g per column one diameter wide
	# (area fraction phi = 0.82, mean radius R), on two contacts at 30 deg from the
	# vertical: xi = W / (2 cos 30 Y). Force chains carry up to about five times the
	# mean load (the exponential tail of the contact-force distribution; measured here
	# 3.2 - 4.8 times), so the settled bed's largest overlap must stay below
	# max(0.3, 5 xi / r_min); shaken, below the engine's default stop (0.6).
	hyd=$(awk -v h="$(attr_val "deep_${tag}_settled.h5" surface_height)" \
		-v Y="$(attr_val "deep_${tag}_settled.h5" parameters/stiffness)" -v g="$(attr_val "deep_${tag}_settled.h5" parameters/gravity)" \
		-v a="$(attr_val "deep_${tag}_settled.h5" parameters/r_min)" -v b="$(attr_val "deep_${tag}_settled.h5" parameters/r_max)" \
		-v mf="$(attr_val "deep_${tag}_settled.h5" parameters/mass_factor)" -v rho="$(attr_val "deep_${tag}_settled.h5" parameters/density)" \
		'BEGIN { R = (a + b) / 2; m = mf * rho * (a * a + a * b + b * b) / 3
			 W = 2 * 0.82 * h / (3.141592653589793 * R) * m * g
			 printf "%.4f", W / (2 * cos(3.141592653589793 / 6) * Y) / a }')
	printf "      %-12s %8s %8s %6s %9s %9s %9s %11s %s\n" "$tag" "$n" "$w" "$rc0/$rc1" "$s0" "$f1" "$s1" "$hyd" "$(cat "deep_$tag.settle_time" 2>/dev/null)" >>"$REPORT"
	[ "$rc0" = 0 ] && [ "$rc1" = 0 ] && ok "stress.deep.$tag.runs" || fail "stress.deep.$tag.runs" "exit $rc0 (settle) / $rc1 (shake)"
	awk -v a="$s0" -v b="$f1" -v c="$s1" -v hy="$hyd" 'BEGIN { lim = 5 * hy > 0.3 ? 5 * hy : 0.3
		exit !(a + 0 < lim && b + 0 < 0.6 && c + 0 < 0.6 && a != "-") }' &&
		ok "stress.deep.$tag.overlap_small" ||
		fail "stress.deep.$tag.overlap_small" "largest overlap settled $s0 (limit max(0.3, 5 x hydrostatic $hyd)), shaken $f1 / $s1 of the radius"
done
echo >>"$REPORT"

# ---------------------------------------------------------------- (iv) violent and degenerate
echo "(iv) violent and degenerate cases" >&2
[ -s bed_tall.txt ] || "$SHAKE" duration=0 wall_height=400 write_particles=bed_tall.txt output=bed_tall.h5 progress=no >bed_tall.log 2>&1
for R in 8 12; do
	[ -s "bed_R$R.txt" ] || "$SHAKE" n_grains=2000 width=120 radius_ratio=$R duration=0 write_particles="bed_R$R.txt" \
		output="bed_R$R.h5" progress=no >"bed_R$R.log" 2>&1
done
violent_run() { # NAME INTEG DT args...
	local name=$1 ig=$2 dt=$3
	shift 3
	"$SHAKE" integrator="$ig" dt="$dt" progress=no traj_rate=100 snapshots=yes dt_guard=warn \
		output="$OUT/v/$name.h5" "$@" >"$OUT/v/$name.log" 2>&1
	echo $? >"$OUT/v/$name.rc"
}
export -f violent_run
mkdir -p v
CASES=(
	"f10_G8 particles=$OUT/bed_tall.txt settle=no frequency=10 amplitude=2 duration=2"
	"f20_G32 particles=$OUT/bed_tall.txt settle=no frequency=20 amplitude=2 duration=2"
	"f30_G72 particles=$OUT/bed_tall.txt settle=no frequency=30 amplitude=2 duration=2"
	"f30_G72_lowwalls particles=$OUT/bed_paper.txt settle=no frequency=30 amplitude=2 duration=2"
	"f30_A0.5_G18 particles=$OUT/bed_tall.txt settle=no frequency=30 amplitude=0.5 duration=2"
	"R8 particles=$OUT/bed_R8.txt settle=no frequency=3.2 duration=3"
	"R12 particles=$OUT/bed_R12.txt settle=no frequency=3.2 duration=3"
	"no_damping particles=$OUT/bed_paper.txt settle=no gamma_n=0 gamma_s=0 duration=5"
	"no_friction particles=$OUT/bed_paper.txt settle=no mu=0 duration=5"
	"no_damping_no_friction particles=$OUT/bed_paper.txt settle=no gamma_n=0 gamma_s=0 mu=0 duration=5"
)
SETS="gear5:5e-5 gear4:5e-5 verlet:5e-5 gear5:1e-4 verlet:1e-4"
for c in "${CASES[@]}"; do
	set -- $c
	name=$1
	shift
	for st in $SETS; do echo "${name}__${st%%:*}_${st#*:} ${st%%:*} ${st#*:} $*"; done
done | parallel -j "$JOBS" --colsep ' ' violent_run {}
{
	echo "(iv) Violent and degenerate cases (paper bed unless said; 'tall' = side walls 400 cm high so that"
	echo "     flying grains stay in the box). exit: 0 ok, 3 NaN, 4 overlap > 0.6 R, 5 left the box."
	echo "     ovl = largest overlap / smaller radius in /final and the snapshots."
	printf "     %-24s" case
	for st in $SETS; do printf " %15s" "$st"; done
	echo
} >>"$REPORT"
for c in "${CASES[@]}"; do
	set -- $c
	name=$1
	printf "     %-24s" "$name" >>"$REPORT"
	for st in $SETS; do
		n=${name}__${st%%:*}_${st#*:} f=v/${name}__${st%%:*}_${st#*:}.h5
		rc=$(cat "v/$n.rc") stat=$(attr_val "$f" status)
		case "$rc:$stat" in
		0:ok | 3:nan | 4:overlap | 5:left_box) ok "stress.violent.$n.ends_cleanly" ;;
		*) fail "stress.violent.$n.ends_cleanly" "exit $rc status '$stat': $(head -c 200 "v/$n.log")" ;;
		esac
		if [ -s "$f" ] && no_nonfinite "$f"; then ok "stress.violent.$n.no_nan"; else fail "stress.violent.$n.no_nan" "NaN/Inf in (or no) $f"; fi
		ov=$("$OVL" "$f" 2>/dev/null | awk '{ printf "%.2f", ($2 > $4 ? $2 : $4) }')
		printf " %15s" "$rc ${ov:--}" >>"$REPORT"
	done
	echo >>"$REPORT"
done
echo >>"$REPORT"
cat "$REPORT"
echo "$NOK passed, $NFAIL failed"
[ "$NFAIL" -eq 0 ]
