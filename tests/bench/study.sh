#!/usr/bin/env bash
# study.sh - what a study costs (run by `make bench-study`; not part of `make check`).
#
# The questions of the paper's claims answered twice in one invocation, from fresh runs:
#   grid  the fixed-grid way of the shipped campaigns (every replicate at every grid point
#         for the whole duration);
#   skip  the same question with the engine's stop rules (stop = flux, stop = risen), the
#         driver's adaptive onset search ([onset]) and replicates = auto, whose target is
#         the interval width the grid reached at the same point in this invocation (so
#         the skip way's interval is at most as wide, or it ran out of max_replicates:
#         the table says which).
# The campaign templates are tests/bench/study/*.campaign.in (their @X@ are filled here).
#
#   claim 1  onset frequency of the flux, no intruder    bin/onset --threshold 2 | [onset] flux
#   claim 2  mean flux through mid-bed with/without R=4  auto twin mean_flux     | stop=flux + auto
#   claim 3  ring force ratio with/without intruder       bin/ring (paper preset) | bin/ring (fast, stop=risen)
#   claim 4  median waiting time per radius ratio        auto twin median_wait   | stop=risen + auto
#   claim 5  onset of the rise near onset, one depth     auto twin rise_fraction | [onset] rise
#
# The full shipped grids (~270 000 simulated s) do not fit one sitting: each claim runs a
# stated subset (fewer grid points or groups, the shipped duration; the subsets are
# described with the settings below), both ways. The full grids' cost is then COMPUTED from the CPU seconds
# per simulated second measured here times their planned simulated seconds (from
# `bin/study expand` of campaigns/claim*.campaign), and so is the skip way of all five
# claims at 16 replicates per point; both are labelled as computed.
#
# Answers come from the tools: bin/onset, the driver's auto_point / onset_group tables
# (a grid is evaluated by its replicates = auto twin: the same name and scene with
# batch = max_replicates = its seeds, which asks for exactly the grid's runs - the same
# ids - and runs nothing new), sqlite3 on the database. CPU seconds: user + system of
# `study run` (driver, GNU parallel, settling, every engine) from /usr/bin/time; "engine s"
# is the engine's own loop time (runs.wall_seconds) plus the packing cache's settling.
#
# stdout: the report (also build/bench-study/report.txt); stderr: progress;
# build/bench-study/costs.tsv, answers.tsv: the numbers; runs/study.db there: everything.
#
# Knobs:
#   STUDY_QUICK=1      a few-minute version (short runs, few seeds and points: the
#                      pipeline, not the figures)
#   JOBS=2             runs at a time
#   STUDY_NICE=5       nice level of the runs
#   STUDY_DIR=DIR      work directory (default build/bench-study; emptied first)
#   STUDY_CLAIMS="3 5 1 4 2"   which claims to run, in this order (the costly and
#                      decisive claim 5 early, so that a bench cut short still has it)
set -uo pipefail

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
cd "$root" || exit 1

QUICK=${STUDY_QUICK:-0}
JOBS=${JOBS:-2}
NICE=${STUDY_NICE:-5}
W=${STUDY_DIR:-build/bench-study}
CLAIMS=${STUDY_CLAIMS:-3 5 1 4 2}
STUDY=$root/bin/study
ONSET=$root/bin/onset
RING=$root/bin/ring
TPL=$here/study
R=$W/runs
DB=$R/study.db
REPORT=$W/report.txt
COSTS=$W/costs.tsv
ANS=$W/answers.tsv
T0=$(date +%s)

for b in "$STUDY" "$ONSET" "$RING" "$root/bin/shake"; do
	[ -x "$b" ] || { echo "study.sh: $b missing (run make)" >&2; exit 1; }
done
command -v sqlite3 >/dev/null || { echo "study.sh: sqlite3 missing (make deps)" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "study.sh: /usr/bin/time missing (apt-get install time)" >&2; exit 1; }

rm -rf "$W"
mkdir -p "$W/campaigns" "$W/time" "$W/analysis" "$W/bin" || exit 1
# the binaries of this invocation, copied first: a rebuild while the bench runs cannot mix
# two engines or drivers (study exec runs the shake beside it)
cp "$STUDY" "$root/bin/shake" "$ONSET" "$RING" "$W/bin/" || exit 1
STUDY=$(cd "$W/bin" && pwd)/study ONSET=$(cd "$W/bin" && pwd)/onset RING=$(cd "$W/bin" && pwd)/ring
: >"$REPORT"
printf 'claim\tway\tcampaign\truns\tsim_s\tcpu_s\tengine_s\twall_s\n' >"$COSTS"
printf 'claim\tpoint\tway\testimate\tlo\thi\twidth\treplicates\tstate\n' >"$ANS"

log() { printf '[bench-study %5ss] %s\n' "$(( $(date +%s) - T0 ))" "$*" >&2; }
out() { printf '%s\n' "$*" | tee -a "$REPORT"; }
outf() { local f=$1; shift; # shellcheck disable=SC2059
	printf "$f" "$@" | tee -a "$REPORT"; }
q() { sqlite3 -separator $'\t' "$DB" "$@"; }
calc() { awk "BEGIN { printf \"%.6g\", $1 }"; }

# --- the settings of each mode -----------------------------------------------------------
# Presets: fast (verlet, 2e-4) where make bench-accuracy found the observable
# indistinguishable from the paper preset (flux, waiting times, the ring's ratios: claims
# 1, 2, 4, 5 both ways); claim 3's grid way uses paper (as the shipped campaign), its skip
# way fast: the preset is one of the things that way skips.
if [ "$QUICK" = 1 ]; then
	C1=(SEEDS=2 DUR=40 FREQS=2.5:3.2:0.1 FROM=2.5 TO=3.2 TOL=0.1 MAXREP=6 STOPSKIP=8)
	C2=(SEEDS=4 DUR=60 FREQS=2.8 BATCH=4 MAXREP=8 STOPSKIP=12)
	C3=(SEEDS=2 DUR=10 FREQS=2.8)
	C4=(SEEDS=6 DUR=60 RATIOS="3, 4" BATCH=2 MAXREP=8)
	C5=(SEEDS=6 DUR=60 FREQS=2.7:3.0:0.15 RATIO=4 DEPTH=2 FROM=2.55 TO=3.15 TOL=0.15 BATCH=6 MAXREP=6)
else
	# Sized for about an hour of a shared 2-core machine. Each way runs the same subset:
	# claim 1: 2.625-2.775 Hz at the shipped 0.025 Hz spacing (7 of its 29 frequencies,
	#   around the onset), 4 seeds as shipped; the search over the same range to 0.02 Hz;
	# claim 2: 2.8 Hz (1 of 3 frequencies: where the claim's difference is, and where the
	#   rolls run, so that stop = flux saves least), both systems, 6 seeds (shipped 8);
	# claim 3: 2.8 Hz (1 of make reproduce's 2 frequencies), both systems, 8 seeds (16);
	# claim 4: R = 3 and 4 (the waiting and the rising regime, 2 of 12 ratios), 6 seeds
	#   (shipped 10); claim 5: R = 4, depth 2 (1 of 8 groups), 2.7, 2.85, 3.0 Hz (3 of 7
	#   frequencies), 6 seeds (shipped 12); the search over 2.55-3.15 Hz to 0.15 Hz, whose
	#   midpoints are the grid's frequencies.
	C1=(SEEDS=4 DUR=120 FREQS=2.625:2.775:0.025 FROM=2.625 TO=2.775 TOL=0.02 MAXREP=6 STOPSKIP=24)
	C2=(SEEDS=6 DUR=200 FREQS=2.8 BATCH=3 MAXREP=9 STOPSKIP=40)
	C3=(SEEDS=8 DUR=60 FREQS=2.8)
	C4=(SEEDS=6 DUR=180 RATIOS="3, 4" BATCH=2 MAXREP=8)
	C5=(SEEDS=6 DUR=300 FREQS=2.7:3.0:0.15 RATIO=4 DEPTH=2 FROM=2.55 TO=3.15 TOL=0.15 BATCH=6 MAXREP=6)
fi
P_FLUX=fast P_RING=paper   # claim 3's grid way; its skip way uses fast (see claim_3)

val() { # KEY ARRAY-ELEMENTS... -> the value of KEY
	local k=$1 kv; shift
	for kv in "$@"; do [ "${kv%%=*}" = "$k" ] && { printf '%s' "${kv#*=}"; return; }; done
}

# render TEMPLATE OUT KEY=VALUE... : fill @KEY@ (values may hold newlines)
render() {
	local t=$1 o=$2 kv; shift 2
	cp "$TPL/$t" "$o" || exit 1
	for kv in "$@"; do
		K=${kv%%=*} V=${kv#*=} perl -0pi -e 's/\@\Q$ENV{K}\E\@/$ENV{V}/g' "$o"
	done
	if grep -v "^[[:space:]]*#" "$o" | grep -q "@[A-Z]*@"; then
		echo "study.sh: $o: unfilled $(grep -o '@[A-Z]*@' "$o" | sort -u | tr '\n' ' ')" >&2
		exit 1
	fi
}

# run CLAIM WAY CAMPAIGN-FILE : study run under /usr/bin/time, costs into costs.tsv
run() {
	local claim=$1 way=$2 f=$3 name rc
	name=$(awk -F'=' '/^name[ \t]*=/ { gsub(/[ \t]|#.*/, "", $2); print $2; exit }' "$f")
	log "claim $claim $way: study run $(basename "$f")"
	/usr/bin/time -f '%e %U %S' -o "$W/time/$name" \
		nice -n "$NICE" "$STUDY" run "$f" --runs "$R" --jobs "$JOBS" --no-progress \
		>>"$W/study.log" 2>&1
	rc=$?
	[ $rc -eq 0 ] || log "claim $claim $way: study run exited $rc (see $W/study.log)"
	local wall usr sys
	read -r wall usr sys < <(tail -n 1 "$W/time/$name")
	# runs finished, simulated shaking seconds, engine loop seconds, settling of the caches
	local row
	row=$(q "SELECT COUNT(*), COALESCE(SUM(status_time), 0), COALESCE(SUM(wall_seconds), 0)
	         FROM runs WHERE campaign = '$name' AND current AND state IN ('done', 'failed')")
	local n sim loop settle
	IFS=$'\t' read -r n sim loop <<<"$row"
	settle=$(q "SELECT COALESCE(SUM(wall_seconds), 0) FROM cache WHERE campaign = '$name'")
	printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$claim" "$way" "$name" "$n" "$sim" \
		"$(calc "$usr + $sys")" "$(calc "$loop + $settle")" "$wall" >>"$COSTS"
	log "claim $claim $way: $n runs, $(calc "$sim") simulated s, $(calc "$usr + $sys") CPU s, $wall s wall"
}

# twin GRID-TEMPLATE OUT RESULT SEEDS KEY=VALUE... : a grid's replicates = auto twin
twin_lines() { printf 'replicates = auto\nresult = %s\nbatch = %s\nmax_replicates = %s\ntarget = 1e-9\nlevel = 0.95' "$1" "$2" "$2"; }

# evaluate CLAIM NAME TWIN-FILE : run the twin (nothing new runs) and store its points
evaluate() {
	local claim=$1 name=$2 f=$3 n0 n1
	n0=$(q "SELECT COUNT(*) FROM run WHERE campaign = '$name'")
	nice -n "$NICE" "$STUDY" run "$f" --runs "$R" --jobs "$JOBS" --no-progress >>"$W/study.log" 2>&1 ||
		log "claim $claim: the twin of $name exited $? (see $W/study.log)"
	n1=$(q "SELECT COUNT(*) FROM run WHERE campaign = '$name'")
	[ "$n0" = "$n1" ] || log "claim $claim: WARNING: the twin of $name added $((n1 - n0)) runs"
	q "SELECT '$claim', grp, 'grid', estimate, ci_lo, ci_hi, ci_hi - ci_lo, replicates, state
	   FROM auto_point WHERE campaign = '$name' ORDER BY point" >>"$ANS"
}

# point_lines 'a=1 b=2' -> 'a = 1\nb = 2' (a [grid] of one point)
point_lines() { printf '%s\n' "$1" | tr ' ' '\n' | sed 's/=/ = /'; }
slug() { printf '%s' "$1" | sed 's/ /_/g; s/=/-/g'; }

# skip_points CLAIM TEMPLATE RESULT PRESET SETTINGS... : one skip campaign per grid point,
# target = the grid's interval width there
skip_points() {
	local claim=$1 t=$2; shift 2
	local grp width target i=0
	while IFS=$'\t' read -r grp width; do
		i=$((i + 1))
		target=$width
		[ -n "$target" ] && awk "BEGIN { exit !($target > 0) }" || target=1e9
		local name=bench_c${claim}_skip_$(slug "$grp")
		render "$t" "$W/campaigns/$name.campaign" NAME="$name" TARGET="$(calc "$target")" \
			POINT="$(point_lines "$grp")" "$@"
		run "$claim" skip "$W/campaigns/$name.campaign"
		q "SELECT '$claim', grp, 'skip', estimate, ci_lo, ci_hi, ci_hi - ci_lo, replicates, state
		   FROM auto_point WHERE campaign = '$name'" >>"$ANS"
	done < <(q "SELECT grp, ci_hi - ci_lo FROM auto_point WHERE campaign = 'bench_c${claim}_grid' ORDER BY point")
}

onset_answer() { # CLAIM NAME WAY [onset options] : bin/onset's threshold crossing
	local claim=$1 name=$2 way=$3; shift 3
	nice -n "$NICE" "$ONSET" "$name" --db "$DB" --runs "$R" --out "$W/analysis/$name" --no-plot "$@" \
		>"$W/analysis/$name.onset.txt" 2>&1 || log "claim $claim: bin/onset $name failed (see $W/analysis/$name.onset.txt)"
	q "SELECT '$claim', grp, '$way', value, lo, hi, hi - lo,
	          (SELECT value FROM analysis b WHERE b.campaign = a.campaign AND b.tool = 'onset' AND b.grp = a.grp AND b.key = 'seeds'), 'bootstrap'
	   FROM analysis a WHERE campaign = '$name' AND tool = 'onset' AND key = 'threshold_f'" >>"$ANS"
}

log "work directory $W, JOBS=$JOBS, nice $NICE, quick=$QUICK; load $(cut -d' ' -f1-3 /proc/loadavg)"
LOAD0=$(cut -d' ' -f1-3 /proc/loadavg)

# --- claim 1: the onset frequency of convection without intruder --------------------------
claim_1() {
	render c1_grid.campaign.in "$W/campaigns/c1_grid.campaign" PRESET=$P_FLUX "${C1[@]}"
	run 1 grid "$W/campaigns/c1_grid.campaign"
	onset_answer 1 bench_c1_grid grid --threshold 2
	w=$(q "SELECT hi - lo FROM analysis WHERE campaign = 'bench_c1_grid' AND tool = 'onset' AND key = 'threshold_f'")
	[ -n "$w" ] && awk "BEGIN { exit !($w > 0) }" || w=$(val TOL "${C1[@]}")
	render c1_skip.campaign.in "$W/campaigns/c1_skip.campaign" PRESET=$P_FLUX TARGET="$(calc "$w")" "${C1[@]}"
	run 1 skip "$W/campaigns/c1_skip.campaign"
	q "SELECT '1', grp, 'skip', estimate, ci_lo, ci_hi, width, replicates, state
	   FROM onset_group WHERE campaign = 'bench_c1_skip'" >>"$ANS"
	# the grid's statistic on the search's runs, for a like-for-like look
	onset_answer 1 bench_c1_skip skip-onset --threshold 2
}

# --- claim 2: the flux through mid-bed with and without the intruder ----------------------
claim_2() {
	s=$(val SEEDS "${C2[@]}")
	render c2_grid.campaign.in "$W/campaigns/c2_grid.campaign" PRESET=$P_FLUX \
		REPLICATES="replicates = $s" "${C2[@]}"
	run 2 grid "$W/campaigns/c2_grid.campaign"
	render c2_grid.campaign.in "$W/campaigns/c2_grid_twin.campaign" PRESET=$P_FLUX \
		REPLICATES="$(twin_lines mean_flux "$s")" "${C2[@]}"
	evaluate 2 bench_c2_grid "$W/campaigns/c2_grid_twin.campaign"
	skip_points 2 c2_skip.campaign.in PRESET=$P_FLUX "${C2[@]}"
}

# --- claim 3: the ring force with/without the intruder -----------------------------------
# grid: the paper preset; skip: the fast preset (make bench-accuracy, part d) and the runs
# with the intruder ending at its rise. Answer: bin/ring's force ratio per frequency.
ring_answer() { # WAY NAME
	nice -n "$NICE" "$RING" "$2" --db "$DB" --runs "$R" --out "$W/analysis/$2" --no-plot --by radius_ratio,frequency \
		>"$W/analysis/$2.ring.txt" 2>&1 || log "claim 3: bin/ring $2 failed (see $W/analysis/$2.ring.txt)"
	q "SELECT '3', 'f=' || printf('%g', frequency), '$1', value, lo, hi, hi - lo, n, 'bootstrap'
	   FROM analysis WHERE campaign = '$2' AND tool = 'ring' AND key = 'ratio_force' ORDER BY frequency" >>"$ANS"
}
claim_3() {
	render c3_ring.campaign.in "$W/campaigns/c3_grid.campaign" NAME=bench_c3_grid WAY=grid \
		PRESET=$P_RING STOP="" ZIP="" "${C3[@]}"
	render c3_ring.campaign.in "$W/campaigns/c3_skip.campaign" NAME=bench_c3_skip WAY=skip \
		PRESET=$P_FLUX STOP="stop = none, risen" ZIP="zip = radius_ratio stop" "${C3[@]}"
	run 3 grid "$W/campaigns/c3_grid.campaign"
	ring_answer grid bench_c3_grid
	run 3 skip "$W/campaigns/c3_skip.campaign"
	ring_answer skip bench_c3_skip
}

# --- claim 4: the waiting time per radius ratio -----------------------------------------
claim_4() {
	s=$(val SEEDS "${C4[@]}")
	render c4_grid.campaign.in "$W/campaigns/c4_grid.campaign" PRESET=$P_FLUX \
		REPLICATES="replicates = $s" "${C4[@]}"
	run 4 grid "$W/campaigns/c4_grid.campaign"
	render c4_grid.campaign.in "$W/campaigns/c4_grid_twin.campaign" PRESET=$P_FLUX \
		REPLICATES="$(twin_lines median_wait "$s")" "${C4[@]}"
	evaluate 4 bench_c4_grid "$W/campaigns/c4_grid_twin.campaign"
	skip_points 4 c4_skip.campaign.in PRESET=$P_FLUX "${C4[@]}"
}

# --- claim 5: the rise near onset, one radius ratio and depth ----------------------------
claim_5() {
	s=$(val SEEDS "${C5[@]}")
	render c5_grid.campaign.in "$W/campaigns/c5_grid.campaign" PRESET=$P_FLUX \
		REPLICATES="replicates = $s" "${C5[@]}"
	run 5 grid "$W/campaigns/c5_grid.campaign"
	render c5_grid.campaign.in "$W/campaigns/c5_grid_twin.campaign" PRESET=$P_FLUX \
		REPLICATES="$(twin_lines rise_fraction "$s")" "${C5[@]}"
	evaluate 5 bench_c5_grid "$W/campaigns/c5_grid_twin.campaign"
	render c5_skip.campaign.in "$W/campaigns/c5_skip.campaign" PRESET=$P_FLUX "${C5[@]}"
	run 5 skip "$W/campaigns/c5_skip.campaign"
	q "SELECT '5', grp, 'skip', estimate, ci_lo, ci_hi, width, replicates, state
	   FROM onset_group WHERE campaign = 'bench_c5_skip'" >>"$ANS"
}

for c in $CLAIMS; do
	case $c in [1-5]) "claim_$c" ;; *) echo "study.sh: STUDY_CLAIMS: no claim '$c'" >&2; exit 1 ;; esac
done

LOAD1=$(cut -d' ' -f1-3 /proc/loadavg)
log "runs finished; load $LOAD1"

# --- the report --------------------------------------------------------------------------
bash "$TPL/report.sh" "$W" "$QUICK" "$JOBS" "$LOAD0" "$LOAD1" "$(( $(date +%s) - T0 ))" | tee -a "$REPORT"
