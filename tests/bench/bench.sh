#!/usr/bin/env bash
# bench.sh - speed benchmark of shakebox (run by `make bench`, after bin/shake is built).
#
#  1. paper scene (950 grains, radius ratio 4, 60 cm box, f = 3.2 Hz): settle once, then time
#     1 simulated second (20000 steps) of shakebox and of LAMMPS gran/hooke (lammps_time.sh) on
#     the same settled state, BENCH_REPS times each, interleaved (shake, lammps, shake, ...).
#     Target: LAMMPS / shakebox >= 6 on one core, on every path (1b).
#     1c: the same scene with shear history, shakebox tangential = spring against LAMMPS
#     gran/hooke/history (the deck's history variable), BENCH_PATH_REPS times each, interleaved.
#  2. scaling: N = 1e3, 1e4, 1e5 grains, box width 60 cm * N/950 (same bed height), settled once
#     each, then a short run timed BENCH_SCALE_REPS times, the sizes taking turns.  Target: ns
#     per particle-step within 1.5x of the N = 1e3 figure.
#  3. peak memory (maximum RSS from /usr/bin/time -v of the timed runs) per N.  Target: marginal
#     memory < 1 KiB per particle.
#
# stdout: the report (also saved as build/bench/report.txt); stderr: progress lines;
# build/bench/bench.tsv: the numbers (section, N, metric, value, unit);
# build/bench/runs.tsv: every single timed run.
# Exit status: 0 when every command worked (targets missed or not), 1 when one failed.
#
# Environment knobs:
#   BENCH_REPS=9         interleaved repetitions of the paper-scene comparison
#   BENCH_SCALE_REPS=5   repetitions of each scaling run
#   BENCH_QUICK=1        skip N = 1e5 (the marginal memory figure then uses 1e4 - 1e3)
#   BENCH_NO_LAMMPS=1    skip LAMMPS (no speed-up figure)
#   BENCH_REUSE=1        reuse the settled states already in build/bench/ (skip preparation)
#   BENCH_SETTLE_KE=1    settle_ke (erg) for preparing the scaling beds (the paper scene
#                        always uses the default 0.01)
#   BENCH_TASKSET=CPU    pin every timed run to this CPU with taskset (default: the last CPU,
#                        so that no run migrates between cores - on the 2-core CI machines CPU 0
#                        also takes the interrupts and its times spread twice as far; "none":
#                        no pinning)
#   BENCH_PATH_REPS=3    repetitions of the paper scene on every other kernel path this CPU runs
#   NATIVE=path          a build of the same tree for this CPU only (make bench builds it with
#                        MARCH=-march=native into build/native): timed against the dispatched
#                        binary on the paper scene (BENCH_PATH_REPS each, interleaved); unset: skipped
#   SHAKE=path           binary to time (default bin/shake; copied to build/bench/ first so a
#                        rebuild during the benchmark cannot mix two engines)
#   LMP=path             LAMMPS binary (passed to lammps_time.sh; default lmp)
set -uo pipefail

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
cd "$root" || exit 1

REPS=${BENCH_REPS:-9}
PREPS=${BENCH_PATH_REPS:-3}
SREPS=${BENCH_SCALE_REPS:-5}
QUICK=${BENCH_QUICK:-0}
NO_LAMMPS=${BENCH_NO_LAMMPS:-0}
REUSE=${BENCH_REUSE:-0}
if [ -z "${BENCH_TASKSET:-}" ] && command -v taskset >/dev/null 2>&1; then
	PIN=$(( $(nproc) - 1 ))
else
	PIN=${BENCH_TASKSET:-}
fi
[ "$PIN" = none ] && PIN=
SHAKE_SRC=${SHAKE:-bin/shake}
W=build/bench
REPORT=$W/report.txt
TSV=$W/bench.tsv
RUNS=$W/runs.tsv
T0=$(date +%s)

# --- scene parameters ---------------------------------------------------------------
FREQ=3.2
PAPER_STEPS=20000            # duration=1 at dt = 5e-5
SCALE_NS=(1000 10000 100000)
# duration of the timed scaling runs (dt = 5e-5 s -> 0.1 s = 2000 steps)
declare -A SCALE_DUR=([1000]=0.1 [10000]=0.1 [100000]=0.1)
# Settling the scaling beds.  With the default criterion (settle_ke = 0.01 erg per disk) the
# wide beds take long to calm down (N = 1e4: 8.2 simulated s, ~2 min; N = 1e5: far longer), so
# all scaling beds settle to settle_ke = 1 erg (grain speeds ~0.5 cm/s, against ~40 cm/s once
# the box shakes) - the same criterion for every N, so the beds are alike.  settle_min must stay
# at its default 1 s: with 0.5 s the still-falling bed slams down (overlap > 0.3 at N = 1e4).
SETTLE_KE=${BENCH_SETTLE_KE:-1}
declare -A SCALE_SETTLE=([1000]="settle_ke=$SETTLE_KE" [10000]="settle_ke=$SETTLE_KE" [100000]="settle_ke=$SETTLE_KE")
RUN_FLAGS=(settle=no progress=no max_overlap=0.9 snapshots=no --profile)

# --- helpers ------------------------------------------------------------------------
elapsed() { echo $(( $(date +%s) - T0 )); }
log() { printf '[bench %4ss] %s\n' "$(elapsed)" "$*" >&2; }
die() {
	printf '[bench %4ss] ERROR: %s\n' "$(elapsed)" "$*" >&2
	printf 'bench: FAILED: %s\n' "$*"
	exit 1
}
rep() { printf '%s\n' "$*" >>"$REPORT"; }
repf() { # printf-style
	local fmt=$1; shift
	# shellcheck disable=SC2059
	printf "$fmt" "$@" >>"$REPORT"
}
tsv() { printf '%s\t%s\t%s\t%s\t%s\n' "$1" "$2" "$3" "$4" "$5" >>"$TSV"; }
is_uint() { [[ $1 =~ ^[1-9][0-9]*$ ]]; }
# stats V1 V2 ... -> "median min max"
stats() {
	printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 }
		END { if (NR == 0) { print "nan nan nan"; exit }
		      m = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
		      printf "%.6g %.6g %.6g\n", m, v[1], v[NR] }'
}
calc() { awk "BEGIN { printf \"%.6g\", $1 }"; }
verdict() { # verdict CONDITION-AS-AWK-EXPR -> "target met" / "target missed"
	awk "BEGIN { exit !($1) }" && echo "target met" || echo "target missed"
}
secs() { if [ "$1" = reused ]; then echo "(reused, BENCH_REUSE=1)"; else echo "$1 s"; fi; }
why() { # the engine's exit codes (shake --help)
	case $1 in
	1) echo " (bad input)" ;; 2) echo " (I/O error)" ;; 3) echo " (NaN/Inf)" ;;
	4) echo " (overlap beyond max_overlap)" ;; 5) echo " (a disk left the box)" ;;
	6) echo " (settling did not converge: raise settle_max or BENCH_SETTLE_KE)" ;;
	7) echo " (interrupted)" ;;
	esac
}
pin() { if [ -n "$PIN" ]; then taskset -c "$PIN" "$@"; else "$@"; fi; }

# run_shake TAG ARGS... : run the engine under /usr/bin/time -v; on success sets
#   R_LOOP R_STEPS R_MOBILE R_WALLS R_RSS (KiB); on failure stops the benchmark.
run_shake() {
	local tag=$1; shift
	local err=$W/log/$tag.err tim=$W/log/$tag.time rc
	pin "$TIMEBIN" -v -o "$tim" "$SHAKE" "$@" >"$W/log/$tag.out" 2>"$err"
	rc=$?
	if [ $rc -ne 0 ]; then
		{
			echo "---- last lines of $err:"
			tail -n 15 "$err"
		} >&2
		die "$tag: '$SHAKE $*' exited with status $rc$(why "$rc")"
	fi
	local line
	line=$(grep '^profile loop_seconds=' "$err" | tail -n 1)
	[ -n "$line" ] || die "$tag: no 'profile loop_seconds=' line on stderr of '$SHAKE $*' (see $err)"
	read -r R_LOOP R_STEPS R_MOBILE R_WALLS < <(echo "$line" |
		sed -E 's/.*loop_seconds=([^ ]+) steps=([^ ]+) mobile=([^ ]+) walls=([^ ]+).*/\1 \2 \3 \4/')
	R_RSS=$(awk -F': ' '/Maximum resident set size/ { print $2 }' "$tim")
	[[ $R_LOOP =~ ^[0-9.eE+-]+$ && $R_STEPS =~ ^[0-9]+$ && $R_MOBILE =~ ^[0-9]+$ && $R_WALLS =~ ^[0-9]+$ ]] ||
		die "$tag: cannot parse '$line'"
	[ "$R_STEPS" -gt 0 ] || die "$tag: the run made 0 steps ('$line')"
	[[ $R_RSS =~ ^[0-9]+$ ]] || die "$tag: no maximum RSS in $tim"
	printf '%s\tshake\t%s\t%s\t%s\t%s\t%s\n' "$tag" "$R_LOOP" "$R_STEPS" "$R_MOBILE" "$R_WALLS" "$R_RSS" >>"$RUNS"
}

# run_lammps TAG DATA STEPS : sets L_LOOP L_STEPS L_ATOMS
run_lammps() { # TAG DATAFILE STEPS [lmp args...]
	local tag=$1 data=$2 steps=$3 out rc
	shift 3
	out=$(pin bash "$here/lammps_time.sh" "$data" "$steps" "$FREQ" "$@" 2>"$W/log/$tag.err")
	rc=$?
	if [ $rc -ne 0 ]; then
		cat "$W/log/$tag.err" >&2
		die "$tag: lammps_time.sh exited with status $rc (BENCH_NO_LAMMPS=1 skips LAMMPS)"
	fi
	read -r L_LOOP L_STEPS L_ATOMS < <(echo "$out" |
		sed -E 's/.*lammps_loop_seconds=([^ ]+) steps=([^ ]+) atoms=([^ ]+).*/\1 \2 \3/')
	[[ ${L_LOOP:-} =~ ^[0-9.eE+-]+$ && ${L_STEPS:-} =~ ^[0-9]+$ ]] || die "$tag: cannot parse lammps_time.sh output '$out'"
	[ "$L_STEPS" -eq "$steps" ] || die "$tag: LAMMPS ran $L_STEPS steps, expected $steps"
	printf '%s\tlammps\t%s\t%s\t%s\t\t\n' "$tag" "$L_LOOP" "$L_STEPS" "$L_ATOMS" >>"$RUNS"
}

# prepare TAG DATAFILE ARGS... : settle a scene once and write it as a LAMMPS data file.
prepare() {
	local tag=$1 data=$2; shift 2
	if [ "$REUSE" = 1 ] && [ -s "$data" ]; then
		log "$tag: reusing $data (BENCH_REUSE=1)"
		P_SECS=reused
		return
	fi
	rm -f "$data"
	local t rc err=$W/log/$tag.err
	t=$(date +%s.%N)
	"$SHAKE" "$@" duration=0 write_lammps="$data" output="$W/$tag.h5" progress=no \
		>"$W/log/$tag.out" 2>"$err"
	rc=$?
	if [ $rc -ne 0 ]; then
		{
			echo "---- last lines of $err:"
			tail -n 15 "$err"
		} >&2
		die "$tag: preparation '$SHAKE $* duration=0 ...' exited with status $rc$(why "$rc")"
	fi
	[ -s "$data" ] || die "$tag: preparation did not write $data"
	P_SECS=$(awk -v a="$t" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
	rm -f "$W/$tag.h5" "$W/$tag.xmf"
}

# --- checks -------------------------------------------------------------------------
is_uint "$REPS" || die "BENCH_REPS must be a positive integer (got '$REPS')"
is_uint "$SREPS" || die "BENCH_SCALE_REPS must be a positive integer (got '$SREPS')"
[ -x "$SHAKE_SRC" ] || die "$SHAKE_SRC not found or not executable (run 'make' first, or 'make bench')"
TIMEBIN=/usr/bin/time
[ -x "$TIMEBIN" ] || die "$TIMEBIN not found (GNU time; apt-get install time) - needed for peak memory"
if [ "$NO_LAMMPS" != 1 ]; then
	command -v "${LMP:-lmp}" >/dev/null 2>&1 ||
		die "LAMMPS '${LMP:-lmp}' not found (make deps, or BENCH_NO_LAMMPS=1 to skip the comparison)"
fi
if [ -n "$PIN" ]; then
	command -v taskset >/dev/null 2>&1 || die "BENCH_TASKSET set but taskset not found"
	taskset -c "$PIN" true 2>/dev/null || die "BENCH_TASKSET=$PIN: taskset cannot pin to that CPU"
fi
[ "$QUICK" = 1 ] && SCALE_NS=(1000 10000)

mkdir -p "$W/log" || die "cannot create $W"
SHAKE=$W/shake
cp "$SHAKE_SRC" "$SHAKE" || die "cannot copy $SHAKE_SRC to $SHAKE"
if [ -n "${NATIVE:-}" ]; then
	cp "$NATIVE" "$W/shake-native" || die "cannot copy NATIVE=$NATIVE to $W/shake-native"
fi
: >"$REPORT"
printf 'section\tN\tmetric\tvalue\tunit\n' >"$TSV"
printf 'tag\tengine\tloop_seconds\tsteps\tmobile_or_atoms\twalls\tmax_rss_kib\n' >"$RUNS"

commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
dirty=$(git status --porcelain --untracked-files=no -- core Makefile 2>/dev/null | wc -l)
[ "$dirty" -gt 0 ] && commit="$commit+dirty($dirty files in core/ Makefile)"
cpu=$("$SHAKE" --version 2>/dev/null | sed -n 's/^cpu: //p')
kpath=$("$SHAKE" --version 2>/dev/null | sed -n 's/^kernel path: \([^ ]*\).*/\1/p')
isa=$(grep -m1 -ow -E 'avx512f|avx512vl|avx512dq|avx512bw|avx2|fma|bmi2|sse2|asimd' /proc/cpuinfo 2>/dev/null | sort -u | tr '\n' ' ')
lmpver=skipped
[ "$NO_LAMMPS" = 1 ] || lmpver=$("${LMP:-lmp}" -h 2>/dev/null | awk '/^Large-scale|LAMMPS \(/ { print; exit }')

rep "shakebox speed benchmark  $(date '+%Y-%m-%d %H:%M:%S')"
rep "  engine   $SHAKE_SRC  (commit $commit, md5 $(md5sum "$SHAKE" | cut -c1-12))"
rep "  machine  ${cpu:-unknown CPU}, $(nproc) cores; load average at start $(cut -d' ' -f1-3 /proc/loadavg)"
rep "  isa      ${isa:-unknown}"
rep "  kernel   path ${kpath:-unknown} (the widest this CPU runs; section 1b times the others)"
rep "  lammps   ${lmpver:-unknown}"
rep "  settings BENCH_REPS=$REPS BENCH_SCALE_REPS=$SREPS BENCH_QUICK=$QUICK${PIN:+ BENCH_TASKSET=$PIN}$([ "$NO_LAMMPS" = 1 ] && echo " BENCH_NO_LAMMPS=1")"
rep "  ns/particle-step = loop_seconds / (steps * particles) * 1e9; 'mobile' = grains + intruder,"
rep "  'all' also counts the wall disks. Every timed run: max_overlap=0.9 snapshots=no settle=no."
rep ""

# --- 1. paper scene: shakebox vs LAMMPS ---------------------------------------------
log "paper scene: settling (950 grains, radius_ratio 4, 60 cm, takes a few seconds)"
PAPER=$W/paper.data
prepare paper_prep "$PAPER"
log "paper scene: settled in $(secs "$P_SECS") -> $PAPER"
PAPER_PREP=$P_SECS

shake_t=() verlet_t=() lmp_t=() ratios=()
for ((i = 1; i <= REPS; i++)); do
	run_shake "paper_shake_$i" particles="$PAPER" duration=1 output="$W/run.h5" "${RUN_FLAGS[@]}"
	[ "$R_STEPS" -eq "$PAPER_STEPS" ] || die "paper_shake_$i: $R_STEPS steps, expected $PAPER_STEPS"
	shake_t+=("$R_LOOP")
	P_MOBILE=$R_MOBILE P_WALLS=$R_WALLS P_RSS=$R_RSS P_LOOP=$R_LOOP
	msg="paper rep $i/$REPS: shakebox ${R_LOOP}s"
	# the same scene with LAMMPS's own integrator (velocity Verlet) at the same dt
	run_shake "paper_verlet_$i" particles="$PAPER" duration=1 integrator=verlet dt=5e-5 \
		output="$W/run.h5" "${RUN_FLAGS[@]}"
	verlet_t+=("$R_LOOP")
	msg="$msg (verlet ${R_LOOP}s)"
	if [ "$NO_LAMMPS" != 1 ]; then
		run_lammps "paper_lammps_$i" "$PAPER" "$PAPER_STEPS"
		[ "$L_ATOMS" -eq $((P_MOBILE + P_WALLS)) ] ||
			die "LAMMPS has $L_ATOMS atoms, shakebox $P_MOBILE mobile + $P_WALLS walls"
		lmp_t+=("$L_LOOP")
		ratios+=("$(calc "$L_LOOP / $P_LOOP")")
		msg="$msg, LAMMPS ${L_LOOP}s"
	fi
	log "$msg"
done
rm -f "$W/run.h5" "$W/run.xmf"

read -r s_med s_min s_max < <(stats "${shake_t[@]}")
ns_m=$(calc "$s_med / ($PAPER_STEPS * $P_MOBILE) * 1e9")
ns_a=$(calc "$s_med / ($PAPER_STEPS * ($P_MOBILE + $P_WALLS)) * 1e9")
rep "1. Paper scene: $P_MOBILE mobile disks + $P_WALLS wall disks, f = $FREQ Hz, 1 simulated s = $PAPER_STEPS steps,"
rep "   settled once with the default criterion (settle_ke 0.01 erg) in $(secs "$PAPER_PREP") wall time;"
rep "   $REPS runs each, interleaved; loop wall time in seconds (median [min .. max])"
repf '   %-10s %9.4f s  [%.4f .. %.4f]   %6.1f ns/particle-step (mobile), %6.1f (all)\n' \
	shakebox "$s_med" "$s_min" "$s_max" "$ns_m" "$ns_a"
tsv paper "$P_MOBILE" shake_loop_median "$s_med" s
tsv paper "$P_MOBILE" shake_loop_min "$s_min" s
tsv paper "$P_MOBILE" shake_loop_max "$s_max" s
tsv paper "$P_MOBILE" shake_ns_per_mobile_step "$ns_m" ns
tsv paper "$P_MOBILE" shake_ns_per_all_step "$ns_a" ns
tsv paper "$P_MOBILE" shake_max_rss "$P_RSS" KiB
if [ "$NO_LAMMPS" != 1 ]; then
	read -r l_med l_min l_max < <(stats "${lmp_t[@]}")
	read -r r_med r_min r_max < <(stats "${ratios[@]}")
	lns_m=$(calc "$l_med / ($PAPER_STEPS * $P_MOBILE) * 1e9")
	lns_a=$(calc "$l_med / ($PAPER_STEPS * ($P_MOBILE + $P_WALLS)) * 1e9")
	speedup=$(calc "$l_med / $s_med")
	repf '   %-10s %9.4f s  [%.4f .. %.4f]   %6.1f ns/particle-step (mobile), %6.1f (all)\n' \
		LAMMPS "$l_med" "$l_min" "$l_max" "$lns_m" "$lns_a"
	best=$(calc "$l_min / $s_min")
	repf '   speed-up LAMMPS/shakebox = %.2fx (ratio of medians)   target >= 6x: %s\n' \
		"$speedup" "$(verdict "$speedup >= 6")"
	repf '   (this machine'"'"'s times come in bursts: ratio of the fastest runs %.2fx; of each\n' "$best"
	repf '   shakebox run and the LAMMPS run after it: median %.2fx, range %.2f .. %.2f)\n' "$r_med" "$r_min" "$r_max"
	read -r v_med v_min v_max < <(stats "${verlet_t[@]}")
	vspeed=$(calc "$l_med / $v_med")
	repf '   shakebox with LAMMPS'"'"'s integrator (integrator=verlet, same dt 5e-5; the paper'"'"'s gear5\n'
	repf '   integrates 6 instead of 3 values per coordinate):\n'
	repf '   %-10s %9.4f s  [%.4f .. %.4f]   %6.1f ns/particle-step (mobile); LAMMPS/this = %.2fx\n' \
		verlet "$v_med" "$v_min" "$v_max" "$(calc "$v_med / ($PAPER_STEPS * $P_MOBILE) * 1e9")" "$vspeed"
	tsv paper "$P_MOBILE" verlet_loop_median "$v_med" s
	tsv paper "$P_MOBILE" speedup_verlet "$vspeed" x
	tsv paper "$P_MOBILE" lammps_loop_median "$l_med" s
	tsv paper "$P_MOBILE" lammps_loop_min "$l_min" s
	tsv paper "$P_MOBILE" lammps_loop_max "$l_max" s
	tsv paper "$P_MOBILE" lammps_ns_per_mobile_step "$lns_m" ns
	tsv paper "$P_MOBILE" speedup "$speedup" x
	tsv paper "$P_MOBILE" speedup_fastest "$best" x
	tsv paper "$P_MOBILE" speedup_pair_median "$r_med" x
	tsv paper "$P_MOBILE" speedup_pair_min "$r_min" x
	tsv paper "$P_MOBILE" speedup_pair_max "$r_max" x
else
	rep "   LAMMPS skipped (BENCH_NO_LAMMPS=1): no speed-up figure"
fi
rep ""

# --- 1b. every kernel path this CPU runs, and the dispatched binary against a native build
rep "1b. The paper scene on every kernel path this CPU runs (SHAKEBOX_KERNEL; $PREPS runs each, interleaved;"
rep "    loop wall time, median [min .. max]; ratio: LAMMPS's median of section 1 / this median)"
declare -A PT
paths=()
while read -r path runs test needs; do
	if [ "$runs" != yes ]; then
		rep "    $(printf '%-8s' "$path") skipped: this CPU cannot run it (it needs $needs)"
	elif [ "$test" = test ]; then
		rep "    $(printf '%-8s' "$path") not timed: for tests only (eight lanes in plain code)"
	else
		paths+=("$path")
	fi
done < <("$SHAKE" --kernel-paths)
for ((i = 1; i <= PREPS; i++)); do
	for path in "${paths[@]}"; do
		SHAKEBOX_KERNEL=$path run_shake "path_${path}_$i" particles="$PAPER" duration=1 output="$W/run.h5" "${RUN_FLAGS[@]}"
		PT[$path]="${PT[$path]:-} $R_LOOP"
	done
	if [ -n "${NATIVE:-}" ]; then
		SHAKE_KEEP=$SHAKE SHAKE=$W/shake-native
		run_shake "native_$i" particles="$PAPER" duration=1 output="$W/run.h5" "${RUN_FLAGS[@]}"
		SHAKE=$SHAKE_KEEP
		PT[native]="${PT[native]:-} $R_LOOP"
		run_shake "dispatched_$i" particles="$PAPER" duration=1 output="$W/run.h5" "${RUN_FLAGS[@]}"
		PT[dispatched]="${PT[dispatched]:-} $R_LOOP"
	fi
	log "paths rep $i/$PREPS done"
done
for path in "${paths[@]}"; do
	# shellcheck disable=SC2086
	read -r m lo hi < <(stats ${PT[$path]})
	if [ "$NO_LAMMPS" != 1 ]; then
		repf '    %-8s %9.4f s  [%.4f .. %.4f]   %6.1f ns/particle-step (mobile)   LAMMPS/this = %.2fx\n' \
			"$path" "$m" "$lo" "$hi" "$(calc "$m / ($PAPER_STEPS * $P_MOBILE) * 1e9")" "$(calc "$l_med / $m")"
		tsv paths "$P_MOBILE" "speedup_$path" "$(calc "$l_med / $m")" x
	else
		repf '    %-8s %9.4f s  [%.4f .. %.4f]   %6.1f ns/particle-step (mobile)\n' \
			"$path" "$m" "$lo" "$hi" "$(calc "$m / ($PAPER_STEPS * $P_MOBILE) * 1e9")"
	fi
	tsv paths "$P_MOBILE" "loop_median_$path" "$m" s
done
if [ -n "${NATIVE:-}" ]; then
	# shellcheck disable=SC2086
	read -r nm nlo nhi < <(stats ${PT[native]})
	# shellcheck disable=SC2086
	read -r dm dlo dhi < <(stats ${PT[dispatched]})
	repf '    dispatched %.4f s [%.4f .. %.4f] against a build for this CPU only (MARCH=-march=native) %.4f s\n' \
		"$dm" "$dlo" "$dhi" "$nm"
	repf '    [%.4f .. %.4f]: the dispatched binary takes %+.1f %%   target within 5 %%: %s\n' "$nlo" "$nhi" \
		"$(calc "($dm / $nm - 1) * 100")" "$(verdict "$dm <= 1.05 * $nm")"
	tsv paths "$P_MOBILE" dispatched_over_native "$(calc "$dm / $nm")" x
else
	rep "    (the dispatched binary against a native build: skipped, NATIVE unset; make bench sets it)"
fi
rm -f "$W/run.h5" "$W/run.xmf"
rep ""

# --- 1c. shear history: tangential = spring against gran/hooke/history --------------
rep "1c. The paper scene with shear history: shakebox tangential = spring (dispatched path) against"
rep "    LAMMPS gran/hooke/history (vibrated_box.in -var history yes; both k_t = 2/7 Y); $PREPS runs each,"
rep "    interleaved; loop wall time, median [min .. max]"
spr_t=() hist_t=()
for ((i = 1; i <= PREPS; i++)); do
	run_shake "spring_$i" particles="$PAPER" duration=1 tangential=spring output="$W/run.h5" "${RUN_FLAGS[@]}"
	spr_t+=("$R_LOOP")
	msg="spring rep $i/$PREPS: shakebox ${R_LOOP}s"
	if [ "$NO_LAMMPS" != 1 ]; then
		run_lammps "history_lammps_$i" "$PAPER" "$PAPER_STEPS" -var history yes
		hist_t+=("$L_LOOP")
		msg="$msg, LAMMPS ${L_LOOP}s"
	fi
	log "$msg"
done
read -r m lo hi < <(stats "${spr_t[@]}")
repf '    %-10s %9.4f s  [%.4f .. %.4f]   %.2fx the default law'"'"'s time (section 1)\n' spring "$m" "$lo" "$hi" \
	"$(calc "$m / $s_med")"
tsv history "$P_MOBILE" spring_loop_median "$m" s
if [ "$NO_LAMMPS" != 1 ]; then
	read -r hm hlo hhi < <(stats "${hist_t[@]}")
	repf '    %-10s %9.4f s  [%.4f .. %.4f]   LAMMPS/shakebox = %.2fx (gran/hooke: %.2fx)\n' history "$hm" "$hlo" \
		"$hhi" "$(calc "$hm / $m")" "$speedup"
	tsv history "$P_MOBILE" lammps_history_loop_median "$hm" s
	tsv history "$P_MOBILE" speedup_history "$(calc "$hm / $m")" x
fi
rm -f "$W/run.h5" "$W/run.xmf"
rep ""

# --- 2. scaling + 3. memory ---------------------------------------------------------
declare -A S_STEPS S_MED S_NSM S_NSA S_RSS S_MOB S_WALLS S_PREP S_TS
for N in "${SCALE_NS[@]}"; do
	width=$(calc "60 * $N / 950")
	log "scaling N=$N: settling (width ${width} cm${SCALE_SETTLE[$N]:+, ${SCALE_SETTLE[$N]}})$([ "$N" -ge 100000 ] && echo ' - takes minutes')"
	# shellcheck disable=SC2086
	prepare "scale_prep_$N" "$W/scale_$N.data" n_grains="$N" width="$width" radius_ratio=4 frequency="$FREQ" ${SCALE_SETTLE[$N]}
	S_PREP[$N]=$P_SECS S_RSS[$N]=0
	log "scaling N=$N: settled in $(secs "$P_SECS")"
done
# The sizes take turns (1e3, 1e4, 1e5, 1e3, ...), as the two codes do above: a phase of
# the machine in which everything runs slower then shows in every size, not in one.
for ((i = 1; i <= SREPS; i++)); do
	for N in "${SCALE_NS[@]}"; do
		run_shake "scale_${N}_$i" particles="$W/scale_$N.data" duration="${SCALE_DUR[$N]}" frequency="$FREQ" \
			output="$W/run_$N.h5" "${RUN_FLAGS[@]}"
		S_TS[$N]="${S_TS[$N]:-} $R_LOOP"
		[ "$R_RSS" -gt "${S_RSS[$N]}" ] && S_RSS[$N]=$R_RSS
		S_STEPS[$N]=$R_STEPS S_MOB[$N]=$R_MOBILE S_WALLS[$N]=$R_WALLS
		log "scaling N=$N rep $i/$SREPS: ${R_LOOP}s for $R_STEPS steps, max RSS $R_RSS KiB"
	done
done
for N in "${SCALE_NS[@]}"; do
	rm -f "$W/run_$N.h5" "$W/run_$N.xmf"
	# shellcheck disable=SC2086
	read -r med _ _ < <(stats ${S_TS[$N]})
	S_MED[$N]=$med
	S_NSM[$N]=$(calc "$med / (${S_STEPS[$N]} * ${S_MOB[$N]}) * 1e9")
	S_NSA[$N]=$(calc "$med / (${S_STEPS[$N]} * (${S_MOB[$N]} + ${S_WALLS[$N]})) * 1e9")
done

N0=${SCALE_NS[0]}
rep "2. Scaling: box width 60 cm * N/950, radius_ratio 4, f = $FREQ Hz; median of $SREPS runs"
repf '   %7s %7s %6s %6s %10s %9s %9s %8s  %s\n' N mobile walls steps "loop [s]" "ns/p-st" "ns/p-st" "ratio" "target <= 1.5x"
repf '   %7s %7s %6s %6s %10s %9s %9s %8s\n' "" "" "" "" "" "(mobile)" "(all)" "to 1e3"
for N in "${SCALE_NS[@]}"; do
	ratio=$(calc "${S_NSM[$N]} / ${S_NSM[$N0]}")
	if [ "$N" = "$N0" ]; then v="(reference)"; else v=$(verdict "$ratio <= 1.5"); fi
	repf '   %7d %7d %6d %6d %10.4f %9.1f %9.1f %8.2f  %s\n' "$N" "${S_MOB[$N]}" "${S_WALLS[$N]}" \
		"${S_STEPS[$N]}" "${S_MED[$N]}" "${S_NSM[$N]}" "${S_NSA[$N]}" "$ratio" "$v"
	tsv scaling "$N" steps "${S_STEPS[$N]}" steps
	tsv scaling "$N" mobile "${S_MOB[$N]}" disks
	tsv scaling "$N" walls "${S_WALLS[$N]}" disks
	tsv scaling "$N" loop_median "${S_MED[$N]}" s
	tsv scaling "$N" ns_per_mobile_step "${S_NSM[$N]}" ns
	tsv scaling "$N" ns_per_all_step "${S_NSA[$N]}" ns
	tsv scaling "$N" ratio_to_1e3 "$ratio" x
	tsv scaling "$N" settle_seconds "${S_PREP[$N]/reused/NA}" s
done
prep_line="   settling (wall time, once each):"
for N in "${SCALE_NS[@]}"; do
	prep_line="$prep_line N=$N $(secs "${S_PREP[$N]}")${SCALE_SETTLE[$N]:+ (${SCALE_SETTLE[$N]})};"
done
rep "${prep_line%;}"
[ "$QUICK" = 1 ] && rep "   (BENCH_QUICK=1: N = 1e5 skipped)"
rep ""

NL=${SCALE_NS[-1]}
rep "3. Peak memory (maximum resident set size of the timed runs, /usr/bin/time -v)"
repf '   %7s %12s %14s %14s\n' N "RSS [KiB]" "KiB/particle" "KiB/particle"
repf '   %7s %12s %14s %14s\n' "" "" "(total/all)" "(total/mobile)"
for N in "${SCALE_NS[@]}"; do
	tot=$((S_MOB[$N] + S_WALLS[$N]))
	repf '   %7d %12d %14.3f %14.3f\n' "$N" "${S_RSS[$N]}" "$(calc "${S_RSS[$N]} / $tot")" \
		"$(calc "${S_RSS[$N]} / ${S_MOB[$N]}")"
	tsv memory "$N" max_rss "${S_RSS[$N]}" KiB
	tsv memory "$N" kib_per_particle_total "$(calc "${S_RSS[$N]} / $tot")" KiB
done
# marginal cost per added grain (the wall disks that come with the wider box are charged to
# the grains, so this is slightly pessimistic)
dparts=$((S_MOB[$NL] - S_MOB[$N0]))
marg=$(calc "(${S_RSS[$NL]} - ${S_RSS[$N0]}) / $dparts")
repf '   marginal (RSS(N=%d) - RSS(N=%d)) / %d more grains = %.3f KiB/particle (%.0f bytes)   target < 1 KiB: %s\n' \
	"$NL" "$N0" "$dparts" "$marg" "$(calc "$marg * 1024")" "$(verdict "$marg < 1")"
tsv memory "$N0-$NL" kib_per_particle_marginal "$marg" KiB
rep ""
# --- 4. what the observables cost --------------------------------------------------
# An observable that is off must cost nothing (it is decided at setup, not tested in
# the loop); one that is on costs what it measures. Same settled paper state, 1 s.
log "observables: off vs flux+field vs ring, interleaved"
obs_off=() obs_ff=() obs_ring=()
for ((i = 1; i <= REPS; i++)); do
	run_shake "obs_off_$i" particles="$PAPER" duration=1 output="$W/obs.h5" "${RUN_FLAGS[@]}"
	obs_off+=("$R_LOOP")
	run_shake "obs_ff_$i" particles="$PAPER" duration=1 output="$W/obs.h5" flux=yes field=yes "${RUN_FLAGS[@]}"
	obs_ff+=("$R_LOOP")
	run_shake "obs_ring_$i" particles="$PAPER" duration=1 output="$W/obs.h5" ring=yes "${RUN_FLAGS[@]}"
	obs_ring+=("$R_LOOP")
done
rm -f "$W/obs.h5" "$W/obs.xmf"
read -r o_off _ _ < <(stats "${obs_off[@]}")
read -r o_ff _ _ < <(stats "${obs_ff[@]}")
read -r o_ring _ _ < <(stats "${obs_ring[@]}")
rep "4. Observables on the paper scene, 1 simulated s, median of $REPS interleaved runs"
repf '   all off               %8.4f s\n' "$o_off"
repf '   flux + field on       %8.4f s   (%+.1f %%; they work once per period)\n' "$o_ff" "$(calc "($o_ff / $o_off - 1) * 100")"
repf '   ring on (every 10)    %8.4f s   (%+.1f %%; |F| kernel on 1 step in 10)\n' "$o_ring" "$(calc "($o_ring / $o_off - 1) * 100")"
repf '   (the paper-scene timing of section 1 is the "off" case: same code path)\n'
tsv observables "$P_MOBILE" off "$o_off" s
tsv observables "$P_MOBILE" flux_field "$o_ff" s
tsv observables "$P_MOBILE" ring "$o_ring" s
rep ""

rep "load average at end $(cut -d' ' -f1-3 /proc/loadavg); whole benchmark $(elapsed) s"
rep "numbers: $TSV   every run: $RUNS   logs: $W/log/"
tsv total - wall_seconds "$(elapsed)" s

log "done in $(elapsed)s"
cat "$REPORT"
