#!/usr/bin/env bash
# reproduce.sh - `make reproduce`: the paper's claims from one command. Runs the
# campaigns of campaigns/reproduce/ (stop rules, the adaptive onset search, 16 replicates
# per point; study run resumes, so a second call with nothing changed simulates nothing),
# runs the analysis tools on them, and writes REPRODUCTION.md and its figures from the
# database - every number, interval and verdict is computed here, none is typed in.
#
# Knobs (environment):
#   REPRODUCE_QUICK=1   a few-minute pipeline check: the same campaigns cut down (2
#                       replicates, short runs, coarse searches) under build/reproduce-quick;
#                       its REPRODUCTION.md goes there too, never over the real one
#   JOBS=2              runs at a time;  REPRODUCE_NICE=5  their nice level
#   REPRODUCE_RUNS=DIR  where the runs and study.db go (default runs/reproduce)
#   REPRODUCE_WORK=DIR  QUICK only: the work directory (default build/reproduce-quick)
#   REPRODUCE_CLAIMS="1 2 3 4 5"   which claims to run and report
#   REPRODUCE_QUESTIONS="1 2 3 4 5"   which open questions to run and report (default all;
#                       none with REPRODUCE_QUICK unless given)
#   REPRODUCE_REPORT_ONLY=1   write REPRODUCTION.md from what the database and the tools'
#                       last outputs hold, running no campaign and no tool
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root" || exit 1

QUICK=${REPRODUCE_QUICK:-0}
JOBS=${JOBS:-2}
NICE=${REPRODUCE_NICE:-5}
CLAIMS=${REPRODUCE_CLAIMS:-1 2 3 4 5}
REPORT_ONLY=${REPRODUCE_REPORT_ONLY:-0}
# the questions the paper left open (scripts/reproduce_questions.sh); none in QUICK mode
# unless asked for
if [ "$QUICK" = 1 ]; then QUESTIONS=${REPRODUCE_QUESTIONS:-}; else QUESTIONS=${REPRODUCE_QUESTIONS-1 2 3 4 5}; fi
if [ "$QUICK" = 1 ]; then
	W=${REPRODUCE_WORK:-build/reproduce-quick}
	RUNS=${REPRODUCE_RUNS:-$W/runs}
	OUT=$W/REPRODUCTION.md
	FIG=$W/figures
else
	W=build/reproduce
	RUNS=${REPRODUCE_RUNS:-runs/reproduce}
	OUT=REPRODUCTION.md
	FIG=docs/reproduction
fi
DB=$RUNS/study.db
ANA=$W/analysis
STUDY=$root/bin/study
for b in study shake onset hysteresis waiting figures rolls ring whale convect; do
	[ -x "bin/$b" ] || { echo "reproduce: bin/$b missing (make)" >&2; exit 1; }
done
mkdir -p "$W/campaigns" "$ANA" "$FIG" "$RUNS" || exit 1
T0=$(date +%s)
log() { printf '[reproduce %5ss] %s\n' "$(( $(date +%s) - T0 ))" "$*" >&2; }
q() { sqlite3 -batch -noheader -separator $'\t' "$DB" "$@" 2>/dev/null; }

# --- the campaigns ------------------------------------------------------------------------
# campaign FILE : the file to run - the shipped one, or for QUICK its cut-down copy
campaign() {
	local src=campaigns/reproduce/$1
	[ "$QUICK" = 1 ] || { printf '%s\n' "$src"; return; }
	local dst=$W/campaigns/$1
	# fewer replicates, short runs, a coarse search; a separate name, so that a quick
	# database is never mistaken for the real one
	# (claim 1's slow ramp, 516 s, becomes 16 s: twice the fast ramp's 8 s)
	sed -E -e 's/^(replicates *= *)[0-9]+/\12/' -e 's/^(duration *= *)[0-9]+ *, *[0-9]+/\18, 16/' \
		-e 's/^(duration *= *)516$/\1@SLOW@/' \
		-e 's/^(duration *= *)[0-9]+([^,0-9]|$)/\18\2/' \
		-e 's/^(name *= *)(.*)/\1q\2/' -e 's/^(tolerance *= *).*/\10.2/' -e 's/^(stop_skip *= *).*/\12/' \
		-e 's/^(stop_after *= *).*/\11/' -e 's/^(field_periods *= *).*/\15/' \
		-e 's/@SLOW@/16/' -e 's|^scene *= *\.\./\.\./|scene = '"$root"'/|' "$src" >"$dst"
	printf '%s\n' "$dst"
}
cname() { awk -F'=' '/^name[ \t]*=/ { gsub(/[ \t]|#.*/, "", $2); print $2; exit }' "$1"; }

declare -A FILE NAME
for c in claim1_onset claim1_hysteresis claim1_hysteresis_slow claim2_rolls claim3_ring claim4_waiting claim5_depth; do
	FILE[$c]=$(campaign "$c.campaign")
	NAME[$c]=$(cname "${FILE[$c]}")
done
want() { case " $CLAIMS " in *" $1 "*) return 0 ;; esac; return 1; }
campaigns_of() {
	case $1 in
	1) echo claim1_onset claim1_hysteresis ;; 2) echo claim2_rolls ;;
	3) echo claim3_ring ;; 4) echo claim4_waiting ;; 5) echo claim5_depth ;;
	esac
}

done_runs() { q "SELECT COUNT(*) FROM run WHERE state IN ('done', 'failed')"; }
n0=$(done_runs); n0=${n0:-0}
declare -A WALL
# run_campaign LABEL KEY FILE: study run (resumes), its wall time into WALL[KEY]
run_campaign() {
	local t
	t=$(date +%s)
	log "$1: study run $3"
	nice -n "$NICE" "$STUDY" run "$3" --runs "$RUNS" --jobs "$JOBS" --no-progress >>"$W/study.log" 2>&1 ||
		log "$1: study run $3 exited $? (see $W/study.log)"
	WALL[$2]=$(( $(date +%s) - t ))
}
tool() { # TOOL CAMPAIGN OPTIONS... : a tool's figures and CSVs under $ANA/CAMPAIGN
	local t=$1 n=$2; shift 2
	[ "$REPORT_ONLY" = 1 ] && return 0
	nice -n "$NICE" "bin/$t" "$n" --db "$DB" --runs "$RUNS" --out "$ANA/$n" "$@" >"$ANA/$n.$t.txt" 2>&1 ||
		log "bin/$t $n: exit $? (see $ANA/$n.$t.txt)"
}
has_runs() { [ "$(q "SELECT COUNT(*) FROM run WHERE campaign = '$1' AND current")" -gt 0 ] 2>/dev/null; }
# The slow ramp answers only one question: is a split of the branches a lag of the bed
# behind the ramp (halves at half the speed) or hysteresis (stays)? Without a split
# (the fast ramp's up - down interval holds 0) there is nothing to tell apart: it runs
# when the fast ramp splits, or when an earlier invocation started it.
slow_needed() {
	has_runs "${NAME[claim1_hysteresis_slow]}" && return 0
	tool hysteresis "${NAME[claim1_hysteresis]}" && HYST_DONE=1
	local lo hi
	read -r _ lo hi _ <<<"$(q "SELECT value, lo, hi, n FROM analysis WHERE campaign = '${NAME[claim1_hysteresis]}'
		AND tool = 'hysteresis' AND key = 'diff_threshold' LIMIT 1" | tr '\t' ' ')"
	[ -n "${lo:-}" ] && [ -n "${hi:-}" ] || { log "claim 1: no up - down interval of the fast ramp; the slow ramp runs"; return 0; }
	awk -v l="$lo" -v h="$hi" 'BEGIN { exit !(l > 0 || h < 0) }' &&
		{ log "claim 1: the fast ramp splits (up - down in [$lo, $hi] Hz): the slow ramp runs"; return 0; }
	log "claim 1: the fast ramp does not split (up - down in [$lo, $hi] Hz): no slow ramp"
	return 1
}
for k in $CLAIMS; do
	[ "$REPORT_ONLY" = 1 ] && break
	for c in $(campaigns_of "$k"); do
		run_campaign "claim $k" "$c" "${FILE[$c]}"
	done
	[ "$k" = 1 ] && slow_needed && run_campaign "claim 1" claim1_hysteresis_slow "${FILE[claim1_hysteresis_slow]}"
done
# shellcheck source=scripts/reproduce_questions.sh
. "$root/scripts/reproduce_questions.sh"
[ "$REPORT_ONLY" = 1 ] || questions_run
n1=$(done_runs); n1=${n1:-0}
T_RUN=$(( $(date +%s) - T0 ))

# --- the analysis -------------------------------------------------------------------------
want 1 && { tool onset "${NAME[claim1_onset]}"; [ "${HYST_DONE:-0}" = 1 ] || tool hysteresis "${NAME[claim1_hysteresis]}"
	has_runs "${NAME[claim1_hysteresis_slow]}" && tool hysteresis "${NAME[claim1_hysteresis_slow]}"; }
want 2 && { tool onset "${NAME[claim2_rolls]}" --by radius_ratio,frequency; tool figures "${NAME[claim2_rolls]}"
	tool rolls "${NAME[claim2_rolls]}"; }
want 3 && tool ring "${NAME[claim3_ring]}"
want 4 && { tool waiting "${NAME[claim4_waiting]}"; tool figures "${NAME[claim4_waiting]}"; }
want 5 && tool waiting "${NAME[claim5_depth]}"
questions_tools
T_ALL=$(( $(date +%s) - T0 ))

# What the campaigns cost a quiet machine: the engine's CPU seconds per step of the
# paper's bed (950 grains), measured here for each integrator as the difference of two
# runs (so settling drops out), kept in $W/calibration for later invocations (a second
# call simulates nothing); a run's cost is then its steps times that, scaled with its
# grains. The engine loop's wall time (the table's) counts the waiting for a busy CPU too.
calibrate() { # INTEGRATOR-PRESET -> CPU seconds per step of the paper's bed
	local cpu d out=$W/calibration.$1
	[ -s "$out" ] && { cat "$out"; return; }
	for d in 0.5 2.5; do
		/usr/bin/time -f '%U %S' -o "$W/calib.time" bin/shake scenes/paper.scene preset="$1" radius_ratio=0 \
			duration=$d snapshots=no traj_rate=0 output="$W/calib.h5" >/dev/null 2>&1 || return
		cpu[${d%.*}]=$(awk '{ print $1 + $2 }' "$W/calib.time")
	done
	rm -f "$W/calib.h5" "$W/calib.xmf" "$W/calib.time"
	awk -v a="${cpu[0]}" -v b="${cpu[2]}" -v dt="$([ "$1" = fast ] && echo 2e-4 || echo 5e-5)" \
		'BEGIN { printf "%.4g\n", (b - a) / (2 / dt) }' | tee "$out"
}
C_FAST=$(calibrate fast) C_PAPER=$(calibrate paper)

# --- REPRODUCTION.md ----------------------------------------------------------------------
# a value from the analysis table: VAL CAMPAIGN TOOL KEY [WHERE] -> "value lo hi n"
# (a missing value or bound is "-": none was computed, e.g. a median never reached)
num() { printf "CASE WHEN %s IS NULL THEN '-' ELSE printf('%%.4g', %s) END" "$1" "$1"; }
val() { q "SELECT $(num value), $(num lo), $(num hi), COALESCE(n, '-') FROM analysis
	   WHERE campaign = '$1' AND tool = '$2' AND key = '$3' ${4:+AND $4} LIMIT 1"; }
iv() { # "value lo hi n" -> "value [lo, hi]"
	set -- $1
	case "${1:-}" in "") printf 'not computed'; return ;; -) printf 'none'; return ;; esac
	if [ "${2:--}" != - ] && [ "${3:--}" != - ]; then printf '%s [%s, %s]' "$1" "$2" "$3"; else printf '%s (no interval)' "$1"; fi
}
fig() { # SRC NAME : copy a tool's figure next to REPRODUCTION.md, print its link
	[ -f "$1" ] || { printf '(figure missing: %s)' "$(basename "$1")"; return; }
	cp "$1" "$FIG/$2" && cp "${1%.png}.pdf" "$FIG/${2%.png}.pdf" 2>/dev/null
	printf '![%s](%s)' "${2%.png}" "$(realpath --relative-to="$(dirname "$OUT")" "$FIG/$2")"
}
counts() { # CAMPAIGN -> "N runs: D done, F failed (reasons)"
	local n d f why
	read -r n d f <<<"$(q "SELECT COUNT(*), SUM(state = 'done'), SUM(state = 'failed') FROM run WHERE campaign = '$1' AND current" | tr '\t' ' ')"
	why=$(q "SELECT GROUP_CONCAT(s || ' ' || c, ', ') FROM (SELECT status AS s, COUNT(*) AS c FROM runs
		 WHERE campaign = '$1' AND state = 'failed' GROUP BY status)")
	printf '%s runs: %s done, %s failed%s' "${n:-0}" "${d:-0}" "${f:-0}" "${why:+ ($why)}"
}
verdict() { printf '**Verdict: %s.** %s' "$1" "$2"; }
# the mean of column COL of a tool's per-run CSV over the rows whose columns match
# "k=v k=v", with a Student-t 95 % interval: "mean lo hi n"
csv_mean() {
	local f=$1 col=$2 where=$3
	[ -f "$f" ] || { echo "- - - 0"; return; }
	awk -F, -v col="$col" -v where="$where" '
		NR == 1 { for (i = 1; i <= NF; i++) { h = $i; gsub(/"/, "", h); c[h] = i }
			  nw = split(where, w, " "); next }
		{ ok = 1
		  for (j = 1; j <= nw; j++) { split(w[j], kv, "=")
			if (!(kv[1] in c)) { # a grouping key the CSV has only in its group label
				gl = " " $c["group"] " "; gsub(/"/, "", gl)
				if (index(gl, " " w[j] " ") == 0) ok = 0
				continue }
			v = $c[kv[1]]; gsub(/"/, "", v)
			num = v ~ /^[-+.0-9eE]+$/ && kv[2] ~ /^[-+.0-9eE]+$/
			if (v != kv[2] && !(num && v + 0 == kv[2] + 0)) ok = 0 }
		  x = $c[col]; if (ok && x != "" && x != "nan") { n++; s += x; ss += x * x } }
		END { if (n < 2) { printf "%s - - %d\n", n ? s : "-", n; exit }
		      split("12.706 4.303 3.182 2.776 2.571 2.447 2.365 2.306 2.262 2.228 2.201 2.179 2.160 2.145 " \
			    "2.131 2.120 2.110 2.101 2.093 2.086 2.080 2.074 2.069 2.064 2.060 2.056 2.052 2.048 2.045 2.042", tq, " ")
		      m = s / n; sd = sqrt((ss - n * m * m) / (n - 1)); t = n - 1 <= 30 ? tq[n - 1] : 1.96
		      printf "%.4g %.4g %.4g %d\n", m, m - t * sd / sqrt(n), m + t * sd / sqrt(n), n }' "$f"
}
# runs_phi CAMPAIGN FREQUENCY RADIUS_RATIO : mean [95 % t interval] of the runs' Phi through
# mid-bed (bin/onset's onset_runs.csv), and how many runs
runs_phi() {
	[ -f "$ANA/$1/onset_runs.csv" ] || { printf 'not computed'; return; }
	set -- $(csv_mean "$ANA/$1/onset_runs.csv" phi "frequency=$2 radius_ratio=$3")
	[ "${4:-0}" -ge 2 ] && printf '%s [%s, %s] (%s runs)' "$1" "$2" "$3" "$4" || printf '%s run(s)' "${4:-0}"
}

{
	echo "# Reproduction of Pöschel & Herrmann, \"Size segregation and convection\" (1995)"
	echo
	echo "Written by \`make reproduce\` (scripts/reproduce.sh) on $(date -u +%Y-%m-%d) from the database"
	echo "\`$DB\`: every number below is computed from the runs, none is typed in. The paper's"
	echo "statements are those of docs/model.md, \"The paper's claims\"."
	[ "$QUICK" = 1 ] && echo && echo "**QUICK MODE: 2 replicates, 8 s runs - a check of the pipeline, not of the physics.**"
	missing=$(for k in 1 2 3 4 5; do want "$k" || printf '%s ' "$k"; done)
	[ -n "$missing" ] && echo && echo "**Not in this report: claim(s) ${missing% } (their campaigns have not been run to the end; \`make reproduce\` resumes them).**"
	echo
	echo "| | |"
	echo "|---|---|"
	echo "| this invocation | $T_ALL s wall on $(nproc) cores ($T_RUN s running campaigns), $((n1 - n0)) runs simulated |"
	echo "| runs in the database | $(q "SELECT COUNT(*) FROM run WHERE current") ($(q "SELECT COUNT(*) FROM run WHERE current AND state = 'failed'") failed) |"
	echo "| simulated time | $(q "SELECT printf('%.0f', TOTAL(status_time)) FROM runs") s; engine loop $(q "SELECT printf('%.0f', TOTAL(wall_seconds)) FROM runs") s |"
	echo "| engine | $(q "SELECT DISTINCT git_hash FROM runs LIMIT 3" | tr '\n' ' ') |"
	echo
	if want 1; then
		n=${NAME[claim1_onset]} h=${NAME[claim1_hysteresis]} hs=${NAME[claim1_hysteresis_slow]}
		ramps=$h; has_runs "$hs" && ramps="$h $hs"
		echo "## Claim 1: a sharp onset of convection, without hysteresis"
		echo
		echo "*Paper:* without the intruder, convection rolls exist only above an onset frequency; runs"
		echo "differ by less than 0.05 Hz, and the onset is the same when the frequency rises as when it falls."
		echo
		search=$(q "SELECT $(num estimate), $(num ci_lo), $(num ci_hi), replicates, runs, state FROM onset_group WHERE campaign = '$n' LIMIT 1")
		read -r se slo shi srep sruns sstate <<<"$(echo "$search" | tr '\t' ' ')"
		thr=$(val "$n" onset threshold_f); sd=$(val "$n" onset threshold_seed_sd); sig=$(val "$n" onset sigmoid_f0)
		# a ramp campaign's duration and its range (one of each per campaign)
		ramp_of() { q "SELECT printf('%g %g-%g', MIN(duration), MIN(ramp_from), MIN(ramp_to)) FROM runs WHERE campaign = '$1' AND current"; }
		echo "| quantity | ours (95 % interval) | test |"
		echo "|---|---|---|"
		echo "| onset, adaptive search (bisection per replicate, flux ≥ 2 particles/period through 0.4–0.6 of the bed) | $(iv "${se:-} ${slo:-} ${shi:-}") Hz, ${srep:-0} replicates, ${sruns:-0} runs (${sstate:-not run}) | order statistics of the replicates' onsets |"
		echo "| onset, threshold crossing of the mean flux (bin/onset) | $(iv "$thr") Hz | bootstrap over seeds |"
		echo "| onset, sigmoid midpoint | $(iv "$sig") Hz | nonlinear least squares, bootstrap |"
		echo "| spread of the replicates' onsets (sd) | $(iv "$sd") Hz | |"
		for r in $ramps; do
			read -r d range <<<"$(ramp_of "$r")"
			echo "| ramp $range Hz over $d s, up: onset | $(iv "$(val "$r" hysteresis up_threshold_f)") Hz | bin/hysteresis |"
			echo "| ramp $range Hz over $d s, down: onset | $(iv "$(val "$r" hysteresis down_threshold_f)") Hz | |"
			echo "| ramp $range Hz over $d s, up − down | $(iv "$(val "$r" hysteresis diff_threshold)") Hz | bootstrap over seeds |"
		done
		echo
		echo "Runs: onset search $(counts "$n"); ramps $(counts "$h")$(has_runs "$hs" && printf '; slow ramps %s' "$(counts "$hs")")."
		has_runs "$hs" || { echo; echo "The ramp twice as slow did not run: it is needed only when the up − down interval excludes 0 (a lag of the bed behind the ramp halves with the speed, hysteresis does not; both make up > down, so without a split there is neither)."; }
		echo
		read -r sdv _ <<<"$sd"
		sharp=$(awk -v s="${sdv:--}" 'BEGIN { print (s + 0 == s && s < 0.05) ? 1 : 0 }')
		# no hysteresis: at the slowest ramp the branches agree (the difference's interval
		# holds 0), or the difference is a lag of the bed behind the ramp: it scales with
		# the ramp speed (the slow ramp's interval holds the fast ramp's difference times
		# the speed ratio)
		slowest=${ramps##* }
		read -r dfast _ <<<"$(ramp_of "$h")"; read -r dslow _ <<<"$(ramp_of "$slowest")"
		read -r fv _ _ _ <<<"$(val "$h" hysteresis diff_threshold)"
		read -r sv slo shi _ <<<"$(val "$slowest" hysteresis diff_threshold)"
		nohyst=$(awk -v l="${slo:--}" -v h="${shi:--}" -v f="${fv:--}" -v a="${dfast:-0}" -v b="${dslow:-0}" 'BEGIN {
			if (!(l + 0 == l)) { print 0; exit }
			if (l <= 0 && h >= 0) { print 1; exit }
			lag = (f + 0 == f && b > a) ? f * a / b : "x"
			print (lag != "x" && l <= lag && h >= lag) ? 2 : 0 }')
		why0="the up − down interval of the $([ "$slowest" = "$h" ] && echo ramp || echo "slower ramp") ($dslow s) contains 0"
		why2="the branches differ by a lag of the bed behind the ramp: the difference shrinks with the ramp speed as a lag does (slow ramp [$slo, $shi] Hz holds the fast ramp's ${fv:-?} Hz × $dfast/$dslow)"
		why=$([ "$nohyst" = 1 ] && echo "$why0" || echo "$why2")
		if [ "$sharp" = 1 ] && [ "$nohyst" != 0 ]; then verdict reproduced "The replicates' onsets spread by less than 0.05 Hz, and $why."
		elif [ "$sharp" = 1 ] || [ "$nohyst" != 0 ]; then verdict partly "Sharp (spread < 0.05 Hz): $([ "$sharp" = 1 ] && echo yes || echo "no (${sdv:-?} Hz)"); no hysteresis: $([ "$nohyst" != 0 ] && echo "yes, $why" || echo "no (slowest ramp: [${slo:-?}, ${shi:-?}] Hz, fastest: ${fv:-?} Hz)")."
		else verdict "not reproduced" "The replicates' onsets spread by ${sdv:-?} Hz (≥ 0.05), and the slowest ramp's up − down interval [${slo:-?}, ${shi:-?}] Hz neither holds 0 nor scales like a lag."; fi
		echo
		echo
		echo "$(fig "$ANA/$n/onset.png" claim1_onset.png) $(fig "$ANA/$h/hysteresis.png" claim1_hysteresis.png)$(has_runs "$hs" && printf ' %s' "$(fig "$ANA/$hs/hysteresis.png" claim1_hysteresis_slow.png)")"
		echo
	fi
	if want 2; then
		n=${NAME[claim2_rolls]}
		echo "## Claim 2: the intruder drags the rolls deeper at 2.8 Hz"
		echo
		echo "*Paper:* at 2.8 Hz Φ(D) extends further down with the intruder than without; at 2.6 Hz both"
		echo "beds only fluctuate, at 3.0 Hz both convect alike."
		echo
		echo "| frequency | Φ through mid-bed without | with 𝓡 = 4 |"
		echo "|---|---|---|"
		for f in $(q "SELECT DISTINCT frequency FROM runs WHERE campaign = '$n' AND current ORDER BY frequency"); do
			printf '| %s Hz | %s | %s |\n' "$f" "$(runs_phi "$n" "$f" 0)" "$(runs_phi "$n" "$f" 4)"
		done
		echo
		echo "Runs: $(counts "$n")."
		echo
		echo "How deep the rolls reach (bin/rolls: the lowest height where the run's |Φ(D)| is a"
		echo "fraction of its maximum; the difference with − without, > 0: deeper with the intruder):"
		echo
		echo "| frequency | reach without | reach with 𝓡 = 4 | difference | lines whose Φ differs |"
		echo "|---|---|---|---|---|"
		for f in $(q "SELECT DISTINCT frequency FROM runs WHERE campaign = '$n' AND current ORDER BY frequency"); do
			g="frequency = $f"
			printf '| %s Hz | %s cm | %s cm | %s cm | %s |\n' "$f" "$(iv "$(val "$n" rolls reach "$g AND radius_ratio = 0")")" \
				"$(iv "$(val "$n" rolls reach "$g AND radius_ratio = 4")")" "$(iv "$(val "$n" rolls reach_diff "$g AND radius_ratio = 4")")" \
				"$(val "$n" rolls lines_differ "$g AND radius_ratio = 4" | cut -f1)"
		done
		echo
		read -r _ dlo dhi _ <<<"$(val "$n" rolls reach_diff "frequency = 2.8 AND radius_ratio = 4")"
		read -r _ l30 h30 _ <<<"$(val "$n" rolls reach_diff "frequency = 3.0 AND radius_ratio = 4")"
		deeper=$(awk -v l="${dlo:--}" 'BEGIN { print (l + 0 == l && l > 0) ? 1 : 0 }')
		alike=$(awk -v l="${l30:--}" -v h="${h30:--}" 'BEGIN { print (l + 0 == l && l <= 0 && h >= 0) ? 1 : 0 }')
		if [ "$deeper" = 1 ] && [ "$alike" = 1 ]; then verdict reproduced "At 2.8 Hz the rolls reach deeper with the intruder (the difference's interval lies above 0); at 3.0 Hz its interval contains 0."
		elif [ "$deeper" = 1 ] || [ "$alike" = 1 ]; then verdict partly "Deeper with the intruder at 2.8 Hz: $([ "$deeper" = 1 ] && echo yes || echo "no (difference ${dlo:-?} … ${dhi:-?} cm)"); alike at 3.0 Hz: $([ "$alike" = 1 ] && echo yes || echo "no (${l30:-?} … ${h30:-?} cm)")."
		else verdict "not reproduced" "At 2.8 Hz the difference's interval (${dlo:-?} … ${dhi:-?} cm) does not lie above 0, and at 3.0 Hz (${l30:-?} … ${h30:-?} cm) it excludes 0."; fi
		echo
		echo
		echo "$(fig "$ANA/$n/rolls.png" claim2_rolls.png) $(fig "$ANA/$n/fig3.png" claim2_fig3.png) $(fig "$ANA/$n/fig1.png" claim2_fig1.png)"
		echo
	fi
	if want 3; then
		n=${NAME[claim3_ring]}
		echo "## Claim 3: larger forces around the intruder"
		echo
		echo "*Paper:* in the 4.5–8 cm ring the mean force on small grains is about 15 % larger with the"
		echo "intruder at 2.8 Hz (about 5 % at 2.6 Hz), while the granular temperature is about the same."
		echo
		echo "Ratios with/without the intruder of the ring's means before the rise (bin/ring; bootstrap"
		echo "percentile intervals, the two systems resampled apart):"
		echo
		echo "| frequency | Σ\|F\| per grain | net force \|ΣF + mg\| | granular temperature |"
		echo "|---|---|---|---|"
		for f in $(q "SELECT DISTINCT frequency FROM runs WHERE campaign = '$n' AND current ORDER BY frequency"); do
			g="frequency = $f AND radius_ratio = 4"
			printf '| %s Hz | %s | %s | %s |\n' "$f" "$(iv "$(val "$n" ring ratio_force "$g")")" \
				"$(iv "$(val "$n" ring ratio_net_force "$g")")" "$(iv "$(val "$n" ring ratio_temperature "$g")")"
		done
		echo
		echo "Runs: $(counts "$n")."
		echo
		# the paper's numbers: +15 % at 2.8 Hz, +5 % at 2.6 Hz (the force ratio's interval
		# must hold them)
		read -r _ rlo rhi _ <<<"$(val "$n" ring ratio_force "frequency = 2.8 AND radius_ratio = 4")"
		read -r _ slo shi _ <<<"$(val "$n" ring ratio_force "frequency = 2.6 AND radius_ratio = 4")"
		in15=$(awk -v l="${rlo:--}" -v h="${rhi:--}" 'BEGIN { print (l + 0 == l && l <= 1.15 && h >= 1.15) ? 1 : 0 }')
		in5=$(awk -v l="${slo:--}" -v h="${shi:--}" 'BEGIN { print (l + 0 == l && l <= 1.05 && h >= 1.05) ? 1 : 0 }')
		what="force ratio at 2.8 Hz [${rlo:-?}, ${rhi:-?}] (paper 1.15), at 2.6 Hz [${slo:-?}, ${shi:-?}] (paper 1.05)"
		if [ "$in15" = 1 ] && [ "$in5" = 1 ]; then verdict reproduced "Both intervals hold the paper's numbers: $what."
		elif [ "$in15" = 1 ] || [ "$in5" = 1 ]; then verdict partly "One interval holds the paper's number: $what."
		else verdict "not reproduced" "Neither interval holds the paper's number: $what."; fi
		echo
		echo
		echo "$(fig "$ANA/$n/ring.png" claim3_ring.png)"
		echo
	fi
	if want 4; then
		n=${NAME[claim4_waiting]}
		echo "## Claim 4: the waiting time at 3.2 Hz"
		echo
		echo "*Paper:* 𝓡 = 4 rises at once; 𝓡 = 2 … 3.5 first wait about 30 s (hardly depending on 𝓡), then"
		echo "rise fast and afterwards go up and down at the top (whale effect)."
		echo
		echo "| 𝓡 | runs | risen | median wait (one diameter) | median wait (half way to the surface) |"
		echo "|---|---|---|---|---|"
		for r in $(q "SELECT DISTINCT radius_ratio FROM runs WHERE campaign = '$n' AND current ORDER BY radius_ratio"); do
			w="radius_ratio = $r"
			printf '| %s | %s | %s | %s s | %s s |\n' "$r" "$(val "$n" waiting runs "$w" | cut -f1)" \
				"$(val "$n" waiting risen "$w" | cut -f1)" "$(iv "$(val "$n" waiting median "$w")")" \
				"$(iv "$(val "$n" waiting way_median "$w")")"
		done
		echo
		lr=$(q "SELECT printf('%.3g', value) FROM analysis WHERE campaign = '$n' AND tool = 'waiting' AND key = 'logrank_p' LIMIT 1")
		lw=$(q "SELECT printf('%.3g', value) FROM analysis WHERE campaign = '$n' AND tool = 'waiting' AND key = 'way_logrank_p' LIMIT 1")
		echo "Log-rank test of equal waiting-time distributions across 𝓡: p = ${lr:-not computed} (one diameter), ${lw:-not computed} (half way)."
		echo "Runs: $(counts "$n")."
		echo
		m4=$(val "$n" waiting median "radius_ratio = 4" | cut -f1)
		msm=$(q "SELECT printf('%.4g', MIN(value)), printf('%.4g', MAX(value)) FROM analysis WHERE campaign = '$n' AND tool = 'waiting' AND key = 'median' AND radius_ratio < 4")
		read -r mlo mhi <<<"$(echo "$msm" | tr '\t' ' ')"
		ok4=$(awk -v m="${m4:-nan}" 'BEGIN { print (m + 0 == m && m < 5) ? 1 : 0 }')
		ok30=$(awk -v a="${mlo:-nan}" -v b="${mhi:-nan}" 'BEGIN { print (a + 0 == a && a >= 10 && b <= 60) ? 1 : 0 }')
		if [ "$ok4" = 1 ] && [ "$ok30" = 1 ]; then verdict reproduced "𝓡 = 4 rises within 5 s (median $m4 s); the medians of 𝓡 < 4 lie between 10 and 60 s ($mlo … $mhi s)."
		elif [ "$ok4" = 1 ] || [ "$ok30" = 1 ]; then verdict partly "𝓡 = 4 within 5 s: $([ "$ok4" = 1 ] && echo yes || echo "no (median ${m4:-?} s)"); medians of 𝓡 < 4 in 10–60 s: $([ "$ok30" = 1 ] && echo yes || echo "no (${mlo:-?} … ${mhi:-?} s)")."
		else verdict "not reproduced" "𝓡 = 4 median ${m4:-?} s; 𝓡 < 4 medians ${mlo:-?} … ${mhi:-?} s."; fi
		echo
		echo
		echo "$(fig "$ANA/$n/waiting_km.png" claim4_km.png) $(fig "$ANA/$n/fig4.png" claim4_fig4.png)"
		echo
	fi
	if want 5; then
		n=${NAME[claim5_depth]}
		echo "## Claim 5: close to onset, one row deeper can prevent the rise"
		echo
		echo "*Paper:* close to the onset, starting the intruder one row lower can prevent the rise altogether."
		echo
		echo "| frequency | depth (rows) | runs | risen | fraction risen | median wait |"
		echo "|---|---|---|---|---|---|"
		q "SELECT DISTINCT frequency, depth FROM runs WHERE campaign = '$n' AND current ORDER BY frequency, depth" |
			while IFS=$'\t' read -r f d; do
				w="frequency = $f AND depth = $d"
				printf '| %s Hz | %s | %s | %s | %s | %s s |\n' "$f" "$d" "$(val "$n" waiting runs "$w" | cut -f1)" \
					"$(val "$n" waiting risen "$w" | cut -f1)" "$(iv "$(val "$n" waiting fraction_risen "$w")")" \
					"$(iv "$(val "$n" waiting median "$w")")"
			done
		echo
		lr=$(q "SELECT printf('%.3g', value) FROM analysis WHERE campaign = '$n' AND tool = 'waiting' AND key = 'logrank_p' LIMIT 1")
		echo "Log-rank test across the groups: p = ${lr:-not computed}. Runs: $(counts "$n")."
		echo
		# the claim: at some frequency a deeper start lowers the fraction risen, beyond the
		# intervals (the deeper group's upper bound below the shallower group's lower bound)
		pairs() { # CONDITION on a (one depth) and b (one row deeper): the pairs, as "f Hz: a/b"
			q "SELECT GROUP_CONCAT(a.frequency || ' Hz, depth ' || a.depth || ' → ' || b.depth || ': '
				  || printf('%.2f', a.value) || ' → ' || printf('%.2f', b.value), '; ')
			   FROM analysis a JOIN analysis b ON a.campaign = b.campaign AND a.tool = b.tool AND a.key = b.key
			   AND a.frequency = b.frequency AND b.depth = a.depth + 1
			   WHERE a.campaign = '$n' AND a.tool = 'waiting' AND a.key = 'fraction_risen' AND $1"
		}
		drop=$(pairs "b.hi < a.lo") more=$(pairs "b.lo > a.hi")
		echo "Fraction risen: Clopper–Pearson 95 % intervals; two neighbouring depths differ when their intervals separate."
		echo
		if [ -n "$drop" ]; then verdict reproduced "One row deeper lowers the fraction risen beyond both intervals at: $drop.${more:+ But at $more a deeper start rises more often.}"
		elif [ -n "$more" ]; then verdict "not reproduced" "The opposite: one row deeper *raises* the fraction risen beyond both intervals at $more; nowhere does it lower it beyond the intervals."
		else verdict "not reproduced" "No pair of neighbouring depths at one frequency has fraction-risen intervals that separate."; fi
		echo
		echo
		echo "$(fig "$ANA/$n/waiting_km.png" claim5_km.png)"
		echo
	fi
	echo "## Validation against LAMMPS"
	echo
	if [ -f docs/validate_lammps.md ]; then
		# the result as make validate-lammps wrote it (its own run: about 50 minutes)
		echo "From \`make validate-lammps\` ($(sed -n 's/^Generated \([0-9-]* [0-9:]* UTC\).*/\1/p' docs/validate_lammps.md); the setup, statistics and per-bed table"
		echo "are in [docs/validate_lammps.md](docs/validate_lammps.md)): Φ(D) at 3.0 Hz without intruder over"
		echo "the same settled beds shaken by shakebox and by LAMMPS \`gran/hooke\`, counted by the engine's own flux code."
		echo
		awk '/^\*\*Result/ { on = 1 } on && /^!\[/ { exit } on' docs/validate_lammps.md
		echo "![Φ(D), shakebox and LAMMPS](docs/validate_lammps.png)"
	else
		echo "*Not run: \`make validate-lammps\` writes docs/validate_lammps.md.*"
	fi
	echo
	questions_report
	echo "## What this run cost"
	echo
	echo "CPU seconds a quiet core spends: each run's steps × the engine's CPU time per step of the paper's"
	echo "bed measured at the start (fast preset ${C_FAST:-?} s, paper preset ${C_PAPER:-?} s per step of 950 grains),"
	echo "scaled with the run's grains; settling and the tools are not in it. The engine loop's wall time"
	echo "also counts the waiting for a busy CPU."
	echo
	echo "| campaign | runs | simulated s | CPU s (estimate) | engine loop wall s | wall s of this invocation |"
	echo "|---|---|---|---|---|---|"
	local_cpu() { # CAMPAIGN -> the estimate
		q "SELECT printf('%.0f', TOTAL(steps * n_grains / 950.0 * CASE WHEN integrator = 'verlet' THEN ${C_FAST:-0}
			ELSE ${C_PAPER:-0} END)) FROM runs WHERE campaign = '$1' AND current"
	}
	cost_row() { # CAMPAIGN-NAME KEY
		printf '| %s | %s | %s | %s | %s | %s |\n' "$1" "$(q "SELECT COUNT(*) FROM runs WHERE campaign = '$1' AND current")" \
			"$(q "SELECT printf('%.0f', TOTAL(status_time)) FROM runs WHERE campaign = '$1' AND current")" \
			"$(local_cpu "$1")" \
			"$(q "SELECT printf('%.0f', TOTAL(wall_seconds)) FROM runs WHERE campaign = '$1' AND current")" "${WALL[$2]:-0}"
	}
	tot_c=0 tot_q=0
	for k in $CLAIMS; do
		for c in $(campaigns_of "$k"); do cost_row "${NAME[$c]}" "$c"; tot_c=$((tot_c + $(local_cpu "${NAME[$c]}"))); done
	done
	for k in $QUESTIONS; do
		for c in $(campaigns_of_question "$k"); do cost_row "${QNAME[$c]}" "$c"; tot_q=$((tot_q + $(local_cpu "${QNAME[$c]}"))); done
	done
	echo
	echo "On $(nproc) quiet cores: the claims about $((tot_c / 60 / $(nproc))) min of CPU, the open questions about $((tot_q / 60 / $(nproc))) min (estimates as above, without settling and tools)."
} >"$OUT.tmp" && mv "$OUT.tmp" "$OUT"
log "wrote $OUT ($((n1 - n0)) runs simulated, $T_ALL s)"
