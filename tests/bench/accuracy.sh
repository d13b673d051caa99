#!/usr/bin/env bash
# accuracy.sh - run time against error for every integrator (
# `make bench-accuracy`). Three measurements, one table each, a work-precision plot and
# a conclusion in build/bench/accuracy/report.txt:
#  (a) two-disk collisions (disk-disk, disk-wall; head-on, oblique) against the analytic
#      spring-dashpot solution: tests/bench/accuracy_collision.c;
#  (b) the paper scene over a short horizon T before chaos separates trajectories,
#      against a gear5 run at dt = 5e-5 / 16; T is chosen where two references
#      (dt / 16 and dt / 32) still agree ten times better than the paper setting does
#      with the reference (measured: T = 0.05 s; the table prints the floor);
#  (c) ensemble observables the study uses: Phi(D) at 3.0 Hz (mean over periods after
#      a transient, 80 lines) and the intruder's waiting time at 3.2 Hz (restricted mean
#      of min(W, run length), censored runs count with the run length), over ACC_SEEDS
#      beds, against a gear5 ensemble at dt = 1.25e-5 on the same beds. A setting is
#      accurate when both are statistically indistinguishable from the reference
#      (|z| < 2 on the means, unpaired standard errors, and chi^2 / n of the Phi(D)
#      profile below its 95 % point); the cheapest accurate setting is the proposed
#      `fast` preset;
#  (d) the ring observables of claim 3 (contact forces around the intruder), preset fast
#      against preset paper on the claim's own campaign: tests/bench/accuracy_ring.sh;
#  (e) near the onset, preset fast against paper on the same beds: each bed's onset of
#      convection by claim 1's search, and Phi(D) at 2.6 and 2.8 Hz with and without the
#      intruder: tests/bench/accuracy_onset.sh.
# Cost is CPU seconds (user + sys of the whole process, from /usr/bin/time) per
# simulated second: robust when another job shares the machine, unlike wall time.
# Knobs: ACC_QUICK=1 (a few minutes), ACC_SEEDS, JOBS (default 2), ACC_OUT, ACC_PARTS (the
# parts to run, default "a b c d e"; e.g. ACC_PARTS=d), ACC_RING_REPS (replicates of (d)),
# ACC_ONSET_BEDS and ACC_PHI_BEDS (beds of (e)).
set -u
cd "$(dirname "$0")/../.."
REPO=$PWD
SHAKE=${SHAKE:-$REPO/bin/shake}
ACC_COLL=${ACC_COLL:-$REPO/build/rel/tests/bench/accuracy_collision}
QUICK=${ACC_QUICK:-0}
JOBS=${JOBS:-2}
OUT=${ACC_OUT:-$REPO/build/bench/accuracy}
PARTS=${ACC_PARTS:-a b c d e}
part() { case " $PARTS " in *" $1 "*) return 0 ;; esac; return 1; }
for p in $PARTS; do case $p in a | b | c | d | e) ;; *) echo "ACC_PARTS: unknown part '$p' (a b c d e)" >&2; exit 1 ;; esac; done
. "$REPO/tests/stress/lib.sh"
mkdir -p "$OUT/runs" "$OUT/beds"
cd "$OUT" || exit 2
REPORT=$OUT/report.txt
export SHAKE OUT

if [ "$QUICK" = 1 ]; then
	SEEDS=${ACC_SEEDS:-3}
	DUR_W=10 DUR_F=10 SKIP_F=3
	CSET="gear5:5e-5 gear5:1e-4 gear4:1e-4 verlet:1e-4 verlet:2e-4"
	BDTS="1e-5 5e-5 1e-4 2e-4 5e-4"
	COLL_ARG=quick
else
	SEEDS=${ACC_SEEDS:-6}
	DUR_W=20 DUR_F=15 SKIP_F=5
	CSET="gear5:5e-5 gear5:1e-4 gear5:2e-4 gear4:1e-4 gear4:2e-4 verlet:1e-4 verlet:1.5e-4 verlet:2e-4 verlet:3e-4"
	BDTS="1e-5 2e-5 5e-5 1e-4 1.5e-4 2e-4 3e-4 5e-4 7e-4 1e-3"
	COLL_ARG=
fi
REF_C=gear5:1.25e-5
HORIZON=0.05
REF_B=3.125e-6 REF_B2=1.5625e-6

{
	echo "shakebox accuracy benchmark  $(date '+%Y-%m-%d %H:%M:%S')"
	echo "  engine   $SHAKE ($("$SHAKE" --version 2>/dev/null | head -n 1))"
	echo "  machine  $(nproc) cores; load average at start $(cut -d' ' -f1-3 /proc/loadavg)"
	echo "  settings ACC_QUICK=$QUICK seeds=$SEEDS JOBS=$JOBS parts=$PARTS"
	echo
} >"$REPORT"

# ---------------------------------------------------------------- (a) collisions
if part a; then
echo "(a) two-disk collisions" >&2
"$ACC_COLL" $COLL_ARG >collision.tsv || { echo "accuracy_collision failed" >&2; exit 1; }
{
	echo "(a) Two-disk collisions, V0 = 50 cm/s, unit disks, paper contact law (t_c = 3.22 ms disk-disk,"
	echo "    4.55 ms disk-wall). Error = max(|de/e|, |dt_c/t_c|) over the four cases (head-on against"
	echo "    the analytic solution, oblique 45 deg against gear5 at dt 1e-7); 'broken' = blew up or"
	echo "    the contact never ended. Steps = steps per disk-disk contact; us = wall time of one contact."
	grep '^# reference' collision.tsv | sed 's/^# /    /; s/; /;\n      /g'
	awk -F'\t' 'NR > 2 && !/^#/ {
		k = $1 SUBSEP $2
		if (!(k in seen)) { seen[k] = 1; order[n++] = k }
		if ($13 != "ok") bad[k] = 1
		else { m = $10 > $11 ? $10 : $11; if (m > err[k]) err[k] = m; if ($10 > ee[k]) ee[k] = $10; if ($11 > et[k]) et[k] = $11 }
		if ($3 == "disk_disk_head_on") { st[k] = $4; us[k] = $5 }
	} END {
		printf "    %-8s %-8s %6s %9s %11s %11s %11s\n", "integ", "dt", "steps", "us", "max|de/e|", "max|dtc/tc|", "error"
		for (i = 0; i < n; i++) { split(order[i], a, SUBSEP)
			if (bad[order[i]]) printf "    %-8s %-8s %6s %9.2f %11s %11s %11s\n", a[1], a[2], st[order[i]], us[order[i]], "-", "-", "broken"
			else printf "    %-8s %-8s %6s %9.2f %11.3e %11.3e %11.3e\n", a[1], a[2], st[order[i]], us[order[i]], ee[order[i]], et[order[i]], err[order[i]] }
	}' collision.tsv
	echo
} >>"$REPORT"
awk -F'\t' 'NR > 2 && !/^#/ { k = $1 "\t" $2; if ($13 != "ok") bad[k] = 1; else { m = $10 > $11 ? $10 : $11; if (m > e[k]) e[k] = m }
	if ($3 == "disk_disk_head_on") s[k] = $4 }
	END { for (k in s) if (!bad[k]) print k "\t" s[k] "\t" e[k] }' collision.tsv | sort -k1,1 -k2,2g >collision_wp.tsv
fi

# ---------------------------------------------------------------- beds
if part b || part c; then
echo "settling $SEEDS beds" >&2
settle_bed() { # seed
	local b=$OUT/beds/seed$1.txt
	[ -s "$b" ] && return 0
	"$SHAKE" seed="$1" duration=0 write_particles="$b" output="$OUT/beds/seed$1.h5" progress=no >"$OUT/beds/seed$1.log" 2>&1
}
export -f settle_bed
seq 1 "$SEEDS" | parallel -j "$JOBS" settle_bed
for s in $(seq 1 "$SEEDS"); do [ -s "beds/seed$s.txt" ] || { echo "settling seed $s failed" >&2; exit 1; }; done
fi

# run_one NAME INTEG DT args... : runs, records "exit cpu_seconds" in runs/NAME.res
run_one() {
	local name=$1 ig=$2 dt=$3
	shift 3
	[ -s "$OUT/runs/$name.res" ] && return 0
	# dt_guard = off: the curves go on to where each integrator breaks down
	/usr/bin/time -f '%U %S' -o "$OUT/runs/$name.time" "$SHAKE" integrator="$ig" dt="$dt" progress=no \
		snapshots=no dt_guard=off output="$OUT/runs/$name.h5" "$@" >"$OUT/runs/$name.log" 2>&1
	local rc=$?
	echo "$rc $(awk '{ print $1 + $2 }' "$OUT/runs/$name.time" | tail -n 1)" >"$OUT/runs/$name.res"
}
export -f run_one

# ---------------------------------------------------------------- (b) short horizon
if part b; then
echo "(b) paper scene, horizon $HORIZON s" >&2
{
	echo "b_ref gear5 $REF_B particles=$OUT/beds/seed1.txt settle=no duration=$HORIZON traj_rate=2000"
	echo "b_ref2 gear5 $REF_B2 particles=$OUT/beds/seed1.txt settle=no duration=$HORIZON traj_rate=2000"
	for ig in gear5 gear4 verlet; do for dt in $BDTS; do
		echo "b_${ig}_$dt $ig $dt particles=$OUT/beds/seed1.txt settle=no duration=$HORIZON traj_rate=2000 max_overlap=0.9"
	done; done
} | parallel -j "$JOBS" --colsep ' ' run_one {}

# positions of the mobile disks at the horizon (lab frame), "x y kind" per line
mobile_xy() { paste <(h5col "$1" /final/x) <(h5col "$1" /final/y) <(h5col "$1" /final/species) | awk '$3 != 2'; }
# bdiff A B : "rms_all max_all intruder" position differences (cm)
bdiff() {
	paste <(mobile_xy "$1") <(mobile_xy "$2") | awk '{ dx = $1 - $4; dy = $2 - $5; d2 = dx * dx + dy * dy; s += d2; n++
		if (d2 > m) m = d2; if ($3 == 1) di = sqrt(d2) } END { printf "%.3e %.3e %.3e\n", sqrt(s / n), sqrt(m), di }'
}
read -r fl_rms fl_max fl_int <<<"$(bdiff runs/b_ref.h5 runs/b_ref2.h5)"
: >scene_wp.tsv
{
	echo "(b) Paper scene (seed 1 bed, f = 3.2 Hz) at the horizon T = $HORIZON s, against gear5 at dt = $REF_B (= 5e-5/16)."
	echo "    Horizon: the intruder positions of the two references (dt/16 and dt/32) differ by 4e-7 cm at"
	echo "    0.05 s, 9e-6 cm at 0.1 s, 3e-2 cm at 0.25 s and O(0.3 cm) (saturated) from 0.3 s on; gear5 at"
	echo "    5e-5 differs from the reference 10x more than the references differ among themselves up"
	echo "    to ~0.05-0.1 s, so integration error dominates there; beyond, chaos amplifies any error."
	echo "    Floor (ref dt/16 vs dt/32) at T: rms over all grains $fl_rms cm, max $fl_max cm, intruder $fl_int cm."
	echo "    Errors below ~2x the floor are not resolved. loop_s = wall seconds of the stepping loop (/provenance)."
	printf "    %-8s %-8s %5s %10s %10s %10s %10s\n" integ dt exit rms_all max_all intruder loop_s
	for ig in gear5 gear4 verlet; do for dt in $BDTS; do
		n=b_${ig}_$dt
		read -r rc cpu <"runs/$n.res"
		if [ "$rc" = 0 ]; then
			read -r a b c <<<"$(bdiff runs/b_ref.h5 "runs/$n.h5")"
			cpu=$(attr_val "runs/$n.h5" provenance/loop_seconds)
			printf "    %-8s %-8s %5s %10s %10s %10s %10s\n" "$ig" "$dt" "$rc" "$a" "$b" "$c" "$cpu"
			echo "$ig $dt $a $b $c $cpu" >>scene_wp.tsv
		else
			printf "    %-8s %-8s %5s %10s %10s %10s %10s  (%s)\n" "$ig" "$dt" "$rc" - - - "$cpu" \
				"$(grep -o 'shake: .*' "runs/$n.log" | head -c 90)"
		fi
	done; done
	echo
} >>"$REPORT"
fi

# ---------------------------------------------------------------- (c) ensembles
if part c; then
echo "(c) ensembles: $SEEDS seeds x ($REF_C $CSET)" >&2
{
	for s in $(seq 1 "$SEEDS"); do for st in $REF_C $CSET; do
		ig=${st%%:*} dt=${st#*:}
		echo "w_${ig}_${dt}_s$s $ig $dt particles=$OUT/beds/seed$s.txt settle=no frequency=3.2 duration=$DUR_W traj_rate=0 max_overlap=0.9"
		echo "f_${ig}_${dt}_s$s $ig $dt particles=$OUT/beds/seed$s.txt settle=no frequency=3.0 duration=$DUR_F traj_rate=0 flux=yes max_overlap=0.9"
	done; done
} | parallel -j "$JOBS" --colsep ' ' run_one {}

# per run: waiting time (restricted) and the period-averaged Phi(D) profile
skip_periods=$(awk -v s="$SKIP_F" 'BEGIN { printf "%d", s * 3.0 + 0.5 }')
: >ens_runs.tsv
for st in $REF_C $CSET; do
	ig=${st%%:*} dt=${st#*:}
	for s in $(seq 1 "$SEEDS"); do
		w=runs/w_${ig}_${dt}_s$s f=runs/f_${ig}_${dt}_s$s
		read -r rcw cpuw <"$w.res"
		read -r rcf cpuf <"$f.res"
		wt=NA risen=NA prof=NA
		if [ "$rcw" = 0 ]; then wt=$(attr_val "$w.h5" waiting_time); risen=$(attr_val "$w.h5" risen); fi
		if [ "$rcf" = 0 ]; then
			prof=$(h5col "$f.h5" /observables/flux/phi/value | awk -v L=80 -v skip="$skip_periods" '
				{ p = int((NR - 1) / L); l = (NR - 1) % L; if (p >= skip) { s[l] += $1; if (l == 0) np++ } }
				END { for (l = 0; l < L; l++) printf "%s%.6g", l ? "," : "", s[l] / np }')
		fi
		echo "$ig $dt $s $rcw $cpuw $wt $risen $rcf $cpuf $prof" >>ens_runs.tsv
	done
done
REF_IG=${REF_C%%:*} REF_DT=${REF_C#*:}
awk -v rig="$REF_IG" -v rdt="$REF_DT" -v dw="$DUR_W" -v df="$DUR_F" -v pw="$OUT/ensemble_wp.tsv" '
	function key(a, b) { return a " " b }
	{ k = key($1, $2); if (!(k in seen)) { seen[k] = 1; ord[n++] = k }
	  if ($4 == 0) { nw[k]++; w = $6; sw[k] += w; sw2[k] += w * w; cw[k] += $5 / dw; if ($7 == 0) cens[k]++ } else failw[k]++
	  if ($8 == 0) { nf[k]++; cf[k] += $9 / df; L = split($10, v, ","); nl = L; m = 0
	      for (l = 1; l <= L; l++) { sp[k, l] += v[l]; sp2[k, l] += v[l] * v[l]; m += v[l] / L }
	      sm[k] += m; sm2[k] += m * m } else failf[k]++ }
	function mean(s, c) { return c ? s / c : 0 }
	function se(s, s2, c,    vv) { if (c < 2) return 0; vv = (s2 - s * s / c) / (c - 1); return sqrt((vv > 0 ? vv : 0) / c) }
	END {
		r = key(rig, rdt)
		rw = mean(sw[r], nw[r]); rsw = se(sw[r], sw2[r], nw[r])
		rm = mean(sm[r], nf[r]); rsm = se(sm[r], sm2[r], nf[r])
		# chi^2 95 % point of nl degrees of freedom (Wilson-Hilferty)
		z = 1.645; c95 = nl * (1 - 2 / (9 * nl) + z * sqrt(2 / (9 * nl))) ^ 3
		printf "    reference %s dt %s: W = %.3f +- %.3f s, mean Phi = %.4f +- %.4f particles/period/line\n", rig, rdt, rw, rsw, rm, rsm
		printf "    %-8s %-8s %4s %9s %17s %6s %19s %6s %9s %7s %8s %s\n", "integ", "dt", "runs", "cpu/s_sim", "W [s]", "z_W", "mean Phi", "z_Phi", "chi2/n", "speedup", "cens", "verdict"
		for (i = 0; i < n; i++) { k = ord[i]; split(k, a, " ")
			w = mean(sw[k], nw[k]); sew = se(sw[k], sw2[k], nw[k])
			m = mean(sm[k], nf[k]); sem = se(sm[k], sm2[k], nf[k])
			zw = (w - rw) / sqrt(sew * sew + rsw * rsw + 1e-30); zm = (m - rm) / sqrt(sem * sem + rsm * rsm + 1e-30)
			chi = 0
			for (l = 1; l <= nl; l++) { a1 = mean(sp[k, l], nf[k]); a2 = mean(sp[r, l], nf[r])
				s1 = se(sp[k, l], sp2[k, l], nf[k]); s2 = se(sp[r, l], sp2[r, l], nf[r])
				if (s1 * s1 + s2 * s2 > 0) chi += (a1 - a2) ^ 2 / (s1 * s1 + s2 * s2) }
			cpu = (mean(cw[k], nw[k]) + mean(cf[k], nf[k])) / 2
			if (a[1] == "gear5" && a[2] == "5e-5") paper = cpu
			cpuk[k] = cpu
			ok = (k != r) && nw[k] == nw[r] && nf[k] == nf[r] && !failw[k] && !failf[k] && zw < 2 && zw > -2 && zm < 2 && zm > -2 && chi < c95
			verdict[k] = k == r ? "reference" : (ok ? "indistinguishable" : "DIFFERENT")
			row[k] = sprintf("%-8s %-8s %4d %9.3f %8.3f +- %5.3f %6.2f %8.4f +- %7.4f %6.2f %9.2f", a[1], a[2], nw[k] + nf[k], cpu, w, sew, zw, m, sem, zm, chi / nl)
			if (k == "verlet 2e-4") # the fast preset: its evidence rows (below)
				printf "FAST %d %.3f %.3f %.3f %.3f %.3f %.3f %.3f %.3f %.2f %.2f %.2f %d %d\n", nw[k], w, sew, rw, rsw, m, sem, rm, rsm, zw, zm, chi / nl, c95 / nl, failw[k] + failf[k] > (pw ".fast")
			relw = rw ? (w - rw) / rw : 0; relm = rm ? (m - rm) / rm : 0
			printf "%s %s %.5g %.5g %.5g %.5g %.5g %s\n", a[1], a[2], cpu, relw, sew / (rw ? rw : 1), relm, sem / (rm ? rm : 1), verdict[k] > pw
		}
		for (i = 0; i < n; i++) { k = ord[i]
			printf "    %s %7.2f %8d %s%s\n", row[k], paper ? paper / cpuk[k] : 0, cens[k], verdict[k], (failw[k] || failf[k]) ? sprintf(" (%d+%d runs failed)", failw[k], failf[k]) : "" }
		printf "    chi2/n: the Phi(D) profile difference over %d lines; 95 %% point %.3f (lines are correlated: indicative)\n", nl, c95 / nl
		best = ""; bc = 1e30
		for (i = 0; i < n; i++) { k = ord[i]; if (verdict[k] == "indistinguishable" && cpuk[k] < bc) { bc = cpuk[k]; best = k } }
		if (best != "") printf "BEST %s %.4f %.3f\n", best, bc, paper / bc; else print "BEST none"
	}' ens_runs.tsv >ensemble.txt
{
	echo "(c) Ensembles over $SEEDS beds (seeds 1..$SEEDS, settled once with gear5 at 5e-5, shared by every setting):"
	echo "    waiting time W at 3.2 Hz (R = 4, $DUR_W s runs; restricted mean of min(W, $DUR_W s); cens = runs that never rose)"
	echo "    and Phi(D) at 3.0 Hz ($DUR_F s runs, periods after ${SKIP_F} s averaged; 'mean Phi' = mean over the 80 lines)."
	echo "    +- are standard errors over seeds; z = difference to the reference / combined standard error."
	echo "    cpu/s_sim = CPU seconds per simulated second (mean of both observables' runs); speedup vs gear5 at 5e-5."
	grep -v '^BEST' ensemble.txt
	echo
} >>"$REPORT"
# the fast preset's evidence rows (scripts/preset_evidence.sh): the waiting time and
# Phi(D), each indistinguishable when |z| < 2 (and, for Phi, chi^2 below its 95 % point)
if [ "$QUICK" != 1 ] && [ -s "$OUT/ensemble_wp.tsv.fast" ]; then
	read -r _ nb w sew rw rsw m sem rm rsm zw zm chil c95l nfail <"$OUT/ensemble_wp.tsv.fast"
	src="make bench-accuracy (c), $(date +%Y-%m-%d), $(git rev-parse --short HEAD 2>/dev/null)"
	vw=$(awk -v z="$zw" -v f="$nfail" 'BEGIN { print (z < 2 && z > -2 && !f) ? "indistinguishable" : "differ" }')
	vm=$(awk -v z="$zm" -v c="$chil" -v c95="$c95l" -v f="$nfail" 'BEGIN { print (z < 2 && z > -2 && c < c95 && !f) ? "indistinguishable" : "differ" }')
	bash "$REPO/scripts/preset_evidence.sh" set acc-c-wait32 "$vw" "$src" \
		"the waiting time of 𝓡 = 4 at 3.2 Hz over $nb beds against a $REF_C ensemble on the same beds: $w ± $sew s against $rw ± $rsw s (z = $zw; resolves about two standard errors of $nb beds)"
	bash "$REPO/scripts/preset_evidence.sh" set acc-c-phi30 "$vm" "$src" \
		"Φ(D) at 3.0 Hz over $nb beds against a $REF_C ensemble on the same beds: mean Φ $m ± $sem against $rm ± $rsm particles/period (z = $zm), χ²/line of the profile $chil against its 95 % point $c95l; resolves about two standard errors of $nb beds"
fi
fi

# ---------------------------------------------------------------- plot + conclusion
if part c; then
gnuplot <<EOF 2>/dev/null
set terminal pngcairo size 1500,480 font ',10'
set output '$OUT/work_precision.png'
set multiplot layout 1,3 title 'shakebox work-precision: error against cost, one curve per integrator'
set logscale xy
set grid
set key top right
set title '(a) two-disk collisions'
set xlabel 'steps per disk-disk contact'
set ylabel 'max relative error (e, t_c)'
plot for [ig in 'gear5 gear4 verlet'] '$OUT/collision_wp.tsv' using (strcol(1) eq ig ? \$3 : 1/0):4 with linespoints title ig
set title '(b) paper scene at T = $HORIZON s vs dt/16 reference'
set xlabel 'wall seconds of the stepping loop'
set ylabel 'rms grain position error [cm]'
plot for [ig in 'gear5 gear4 verlet'] '$OUT/scene_wp.tsv' using (strcol(1) eq ig ? \$6 : 1/0):3 with linespoints title ig, \
     $fl_rms with lines dt 2 lc rgb 'gray' title 'reference floor'
set title '(c) ensembles: |rel. difference| to reference'
set xlabel 'CPU seconds per simulated second'
set ylabel '|relative difference| (bars: 1 s.e.)'
set yrange [1e-3:*]
plot for [ig in 'gear5 gear4 verlet'] '$OUT/ensemble_wp.tsv' using (strcol(1) eq ig ? \$3 : 1/0):(abs(\$4)+1e-3):5 with yerrorlines title ig.' W', \
     for [ig in 'gear5 gear4 verlet'] '$OUT/ensemble_wp.tsv' using (strcol(1) eq ig ? \$3 : 1/0):(abs(\$6)+1e-3):7 with yerrorlines dt 2 title ig.' Phi'
unset multiplot
EOF
{
	echo "Conclusion"
	best=$(grep '^BEST' ensemble.txt)
	if [ "$best" = "BEST none" ] || [ -z "$best" ]; then
		echo "    no setting cheaper than the reference was statistically indistinguishable from it on (c)."
	else
		read -r _ big bdt bcpu bsp <<<"$best"
		echo "    cheapest setting indistinguishable from the reference ensemble on (c): integrator = $big, dt = $bdt"
		echo "    ($bcpu CPU s per simulated second, ${bsp}x cheaper than gear5 at dt = 5e-5; target >= 3x:"\
			"$(awk -v s="$bsp" 'BEGIN { print (s >= 3 ? "met" : "missed") }'))."
		echo "    Proposed 'fast' preset: integrator = $big, dt = $bdt (everything else as 'paper')."
	fi
	echo "    The ensemble test only resolves differences larger than ~2 standard errors of $SEEDS seeds; see the"
	echo "    z columns for how close each setting is. Plot: $OUT/work_precision.png"
} >>"$REPORT"
fi

# ---------------------------------------------------------------- (d) ring force
if part d; then
	echo "(d) ring force: preset fast against paper (tests/bench/accuracy_ring.sh)" >&2
	ACC_QUICK=$QUICK JOBS=$JOBS ACC_OUT=$PWD ACC_REPORT=$REPORT bash "$REPO/tests/bench/accuracy_ring.sh" ||
		{ cat "$REPORT"; echo "accuracy: (d) ring force failed" >&2; exit 1; }
fi

# ---------------------------------------------------------------- (e) near the onset
if part e; then
	echo "(e) near the onset: preset fast against paper on the same beds (tests/bench/accuracy_onset.sh)" >&2
	ACC_QUICK=$QUICK JOBS=$JOBS ACC_OUT=$OUT ACC_REPORT=$REPORT bash "$REPO/tests/bench/accuracy_onset.sh" ||
		{ cat "$REPORT"; echo "accuracy: (e) near the onset failed" >&2; exit 1; }
fi
cat "$REPORT"
