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
#   REPRODUCE_QUESTIONS="1 2 3 4 5 6"   which open questions to run and report (default all;
#                       none with REPRODUCE_QUICK unless given)
#   REPRODUCE_REPORT_ONLY=1   write REPRODUCTION.md from what the database and the tools'
#                       last outputs hold, running no campaign and no tool
#   REPRODUCE_CROSSCODE=1   rewrite only what REPRODUCTION.md takes from
#                       docs/validate_lammps.md (each claim's "Cross-checked in LAMMPS" lines,
#                       claim 5's sentence across the codes, the validation section, and the
#                       integrator lines' evidence from docs/preset_evidence.tsv), by the
#                       same code as a full report, in the REPRODUCTION.md there is: after
#                       `make validate-lammps` on a machine that does not hold the runs
#   REPRODUCE_VALIDATION=FILE   the validation fragment to read (default docs/validate_lammps.md)
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root" || exit 1

QUICK=${REPRODUCE_QUICK:-0}
JOBS=${JOBS:-2}
NICE=${REPRODUCE_NICE:-5}
CLAIMS=${REPRODUCE_CLAIMS:-1 2 3 4 5}
REPORT_ONLY=${REPRODUCE_REPORT_ONLY:-0}
CROSSCODE=${REPRODUCE_CROSSCODE:-0}
[ "$CROSSCODE" = 1 ] && REPORT_ONLY=1 # runs nothing
# the questions the paper left open (scripts/reproduce_questions.sh); none in QUICK mode
# unless asked for
if [ "$QUICK" = 1 ]; then QUESTIONS=${REPRODUCE_QUESTIONS:-}; else QUESTIONS=${REPRODUCE_QUESTIONS-1 2 3 4 5 6}; fi
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
# every program of the build (the Makefile's one list of them)
tools=$(make -s --no-print-directory -C "$root" print-tools) && [ -n "$tools" ] ||
	{ echo "reproduce: make print-tools gave no list of the programs" >&2; exit 1; }
for b in $tools; do
	[ -x "bin/$b" ] || { echo "reproduce: bin/$b missing (make)" >&2; exit 1; }
done
mkdir -p "$W/campaigns" "$ANA" "$FIG" "$RUNS" || exit 1
T0=$(date +%s)
log() { printf '[reproduce %5ss] %s\n' "$(( $(date +%s) - T0 ))" "$*" >&2; }
q() { sqlite3 -batch -noheader -separator $'\t' "$DB" "$@" 2>/dev/null; }
# the verdicts' rules, and val / iv / csv_mean over the same database
# shellcheck source=scripts/verdicts.sh
. "$root/scripts/verdicts.sh"
VDB=$DB

# --- the campaigns ------------------------------------------------------------------------
# a campaign file copied out of campaigns/reproduce/ keeps its scene: the sed expression
# that turns the scene's ../../ into the repository's path (every copy below uses it)
SCENE_ABS='s|^scene *= *\.\./\.\./|scene = '"$root"'/|'
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
		-e 's/@SLOW@/16/' -e "$SCENE_ABS" "$src" >"$dst"
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

# Claims 2, 3 and 5 again at the same distance from this model's onset f_on (claim 1's
# search) as the paper's frequencies are from the paper's onset: the paper puts it at
# 2.8 Hz ("at the onset of segregation (f = 2.8)"), so its 2.6 / 2.8 / 3.0 Hz are
# f_on - 0.2, f_on, f_on + 0.2 here (docs/model.md, "The paper's claims"). Each is the
# claim's campaign with those frequencies (rounded to 0.01 Hz) and 8 replicates; claim 5,
# "close to the onset", runs at f_on. Written once claim 1's search is done.
PAPER_ONSET=2.8
F_ON=
declare -A REL_F
rel_setup() {
	F_ON=$(q "SELECT printf('%.4g', estimate) FROM onset_group WHERE campaign = '${NAME[claim1_onset]}' AND state = 'done'
		AND estimate IS NOT NULL")
	[ -n "$F_ON" ] || return 1
	local c off fs
	for c in claim2_rolls claim3_ring claim5_depth; do
		case $c in claim2_rolls) off="-0.2 0 0.2" ;; claim3_ring) off="-0.2 0" ;; claim5_depth) off="0" ;; esac
		fs=$(for o in $off; do awk -v f="$F_ON" -v o="$o" 'BEGIN { printf "%.2f\n", f + o }'; done | paste -sd, | sed 's/,/, /g')
		REL_F[$c]=${fs//,/}
		FILE[${c}_on]=$W/campaigns/${c}_on.campaign
		sed -E -e 's/^(name *= *)([^ #]*)(.*)/\1\2_on\3/' \
			-e 's/^(description *= *)(.*)/\1\2, at f_on offsets/' \
			-e "s/^(replicates *= *)16/\18/" \
			-e "$SCENE_ABS" \
			-e "/^\[grid\]/,/^\[/ s/^frequency *=.*/frequency = $fs/" "${FILE[$c]}" >"${FILE[${c}_on]}.tmp" &&
			mv "${FILE[${c}_on]}.tmp" "${FILE[${c}_on]}"
		NAME[${c}_on]=$(cname "${FILE[${c}_on]}")
	done
}
if [ "$REPORT_ONLY" != 1 ] && rel_setup; then
	log "this model's onset f_on = $F_ON Hz: claims 2, 3 and 5 at its offsets"
	for c in claim2_rolls claim3_ring claim5_depth; do
		want "${c:5:1}" && run_campaign "claim ${c:5:1} at f_on" "${c}_on" "${FILE[${c}_on]}"
	done
else
	rel_setup
fi
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
if [ -n "$F_ON" ]; then
	want 2 && { tool onset "${NAME[claim2_rolls_on]}" --by radius_ratio,frequency; tool rolls "${NAME[claim2_rolls_on]}"; }
	want 3 && tool ring "${NAME[claim3_ring_on]}"
	want 5 && tool waiting "${NAME[claim5_depth_on]}"
fi
want 4 && { tool waiting "${NAME[claim4_waiting]}"; tool figures "${NAME[claim4_waiting]}"; }
want 5 && tool waiting "${NAME[claim5_depth]}"
questions_tools
T_ALL=$(( $(date +%s) - T0 ))

# What the campaigns cost a quiet machine: the engine's CPU seconds per step of the
# paper's bed (950 grains), the rate bin/study measures once per engine build, CPU and
# integrator for its cost before the start and keeps in RUNS/.calibration (study/report/
# calib.c; docs/campaigns.md, "Cost before the start": --dry-run measures it or reads it
# back); a run's cost is then its steps times that, scaled with its grains. The engine
# loop's wall time (the table's) counts the waiting for a busy CPU too.
# The dry run is of a copy of the campaign under another name in a run directory of its
# own, whose runs are all still to do: the dry run of a finished campaign has nothing to
# cost and names no rate (a report's cost table once said "?" and 0 CPU s for every
# paper-preset campaign that way). The copy shares RUNS's calibration cache.
calibrate() { # CAMPAIGN (its preset's integrator) -> CPU seconds per step of the paper's bed
	local f d=$W/calibrate c
	c=$d/$(basename "$1")
	mkdir -p "$d/runs" "$RUNS/.calibration" && ln -sfn "$(realpath "$RUNS/.calibration")" "$d/runs/.calibration" &&
		sed -E -e 's/^(name *= *)(.*)/\1calibrate_\2/' -e "$SCENE_ABS" "$1" >"$c" || return 1
	f=$("$STUDY" run "$c" --dry-run --runs "$d/runs" 2>&1 |
		sed -n 's/^  rate: .*(\(.*\.calibration\/[0-9a-f]*\.[a-z0-9]*\.txt\))$/\1/p' | head -n 1)
	[ -s "$f" ] && awk 'NR == 1 { printf "%.4g\n", $1 * 950 }' "$f"
}
C_FAST="" C_PAPER=""
if [ "$CROSSCODE" != 1 ]; then # that mode writes no cost table
	C_FAST=$(calibrate campaigns/reproduce/claim1_onset.campaign) C_PAPER=$(calibrate campaigns/reproduce/claim3_ring.campaign)
fi

# --- REPRODUCTION.md ----------------------------------------------------------------------
# claim 1's onset search: its threshold, band and skip (what "convecting" means everywhere
# below) and the onset f_on, this report's one onset
read -r THR BAND SKIP <<<"$(q "SELECT printf('%g', threshold), printf('%g–%g', band_lo, band_hi), printf('%g', skip)
	FROM onset_search WHERE campaign = '${NAME[claim1_onset]}'" | tr '\t' ' ')"
THR=${THR:-2} BAND=${BAND:-0.4–0.6} SKIP=${SKIP:-0.2}
# ONSET_DEF: that definition in words, the one every onset of this report is by
ONSET_DEF="the first frequency at which a bed's mean flux through $BAND of its height, the first $SKIP of its periods left out, is at least $THR particles per period in magnitude"
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
# integrator CAMPAIGN FILE : the preset, integrator and time step of the campaign's runs, the
# campaign file's word on its preset (its "# preset:" paragraph) and the measured evidence
# it names ("# preset evidence:", the rows of docs/preset_evidence.tsv: scripts/preset_evidence.sh)
integrator() {
	local what why ev
	what=$(q "SELECT GROUP_CONCAT(x, '; ') FROM (SELECT DISTINCT 'preset ' || COALESCE(preset, 'none') || ' ('
		|| integrator || ', Δt = ' || printf('%g', dt) || ' s)' AS x FROM runs WHERE campaign = '$1' AND current)")
	why=$(awk '/^# preset:/ { on = 1; sub(/^# preset: */, ""); printf "%s", $0; next }
		on && /^#   / { sub(/^# */, " "); printf "%s", $0; next } { on = 0 }' "$2")
	ev=$(bash "$root/scripts/preset_evidence.sh" line "$2")
	printf '*Integrator* (%s): %s. The campaign file on the preset: "%s" Evidence (docs/preset_evidence.tsv): %s.\n' \
		"$1" "${what:-no runs yet}" "$why" "$ev"
}
# lammps PART : make validate-lammps's row for a part (docs/validate_lammps.md's summary
# table) as "*Cross-checked in LAMMPS* (part X): evidence: result."
VAL=${REPRODUCE_VALIDATION:-docs/validate_lammps.md}
lammps() {
	[ -f "$VAL" ] || { echo "*Cross-checked in LAMMPS:* not run (\`make validate-lammps\`)."; return; }
	awk -F' [|] ' -v p="$1" '$1 == "| " p { printf "*Cross-checked in LAMMPS* (make validate-lammps, part %s, same beds in both codes): %s — %s.\n", p, $3, $4; f = 1 }
		END { if (!f) printf "*Cross-checked in LAMMPS:* not yet: `make validate-lammps` part %s has not been run (docs/validate_lammps.md holds no part %s).\n", p, p }' "$VAL"
}
# crosscode_c : claim 5's lines across the codes (part C of docs/validate_lammps.md): its
# row, each code's own depth comparison, and the one sentence across the codes
crosscode_c() {
	local both across pfs pfl pm
	lammps C
	# each code's own depth comparison: does the claim's verdict differ between the codes?
	both=""
	[ -f "$VAL" ] && both=$(sed -n '/^## C\./,/^## D\./p' "$VAL" | grep -m1 '^shakebox: .*LAMMPS: ')
	if [ -n "$both" ]; then
		echo "Each code alone, depth 1 against one row lower: $both"
		# the one sentence across the codes, generated from the numbers
		# (bin/dumpflux stats verdict; tests/analysis/twocode.c holds each wording):
		# the fragment's own, or from an older fragment's p-values
		across=$(sed -n '/^## C\./,/^## D\./s/^Across the codes: //p' "$VAL" | head -n 1)
		if [ -z "$across" ]; then
			pfs=$(sed -n 's/^shakebox: .*Fisher p = \([0-9.e+-]*\) (.*LAMMPS: .*/\1/p' <<<"$both")
			pfl=$(sed -n 's/.*LAMMPS: .*Fisher p = \([0-9.e+-]*\) (.*/\1/p' <<<"$both")
			pm=$(sed -n '/^## C\./,/^## D\./p' "$VAL" | grep -m1 -A2 '^\*\*Result:\*\*' | tr '\n' ' ' |
				grep -o 'McNemar p = [0-9.e+-]*\|, p = [0-9.e+-]* at depth 1' | grep -o '[0-9][0-9.e+-]*' | head -n 2 |
				sort -g | head -n 1)
			[ -n "$pfs" ] && [ -n "$pfl" ] && [ -n "$pm" ] &&
				across=$("$root/bin/dumpflux" stats verdict "$pfs" "$pfl" "$pm" "the depth effect" 2>/dev/null)
		fi
		[ -z "$across" ] || echo "Across the codes: $across"
	fi
}
# validation_section : the section on make validate-lammps, from docs/validate_lammps.md
validation_section() {
	echo "## Validation against LAMMPS"
	echo
	if [ -f "$VAL" ]; then
		# the result as make validate-lammps wrote it (its own run, about 45 minutes)
		echo "From \`make validate-lammps\` ($(sed -n 's/^Generated \([0-9-]* [0-9:]* UTC\).*/\1/p' "$VAL")): the same settled beds shaken"
		echo "by shakebox and by LAMMPS \`gran/hooke\`, a code nobody here wrote, with the engine's own definitions applied"
		echo "to LAMMPS's output (its crossing code for the flux, its rise rule for the waiting time). The setup,"
		echo "statistics and per-bed tables are in [docs/validate_lammps.md](docs/validate_lammps.md)."
		echo
		if grep -q '^| part | question' "$VAL"; then
			awk '/^\| part \| question/ { on = 1 } on && !/^\|/ { exit } on' "$VAL"
		else # a fragment from before the parts: Phi(D) at 3.0 Hz alone
			echo "Φ(D) at 3.0 Hz without intruder (the onset and claims 4 and 5 are not in this fragment):"
			echo
			awk '/^\*\*Result/ { on = 1 } on && /^!\[/ { exit } on' "$VAL"
		fi
		echo
		echo "![Φ(D), shakebox and LAMMPS](docs/validate_lammps.png)$([ -f docs/validate_lammps_onset.png ] && echo " ![the onset in both codes](docs/validate_lammps_onset.png)")"
	else
		echo "*Not run: \`make validate-lammps\` writes docs/validate_lammps.md.*"
	fi
}
# render : the verdict lines of scripts/verdicts.sh as a table of parts and the verdict
render() {
	awk -F'\t' 'function e(x) { gsub(/\|/, "\\|", x); return x }
		BEGIN { print "| part | the paper | ours | holds? |"; print "|---|---|---|---|" }
		$1 == "part" { printf "| %s | %s | %s | %s |\n", $2, e($4), e($5), $3 }
		$1 == "claim" { v = $2; t = $3 }
		END { printf "\n**Verdict: %s** (%s).\n", v, t }'
}
# runs_phi CAMPAIGN FREQUENCY RADIUS_RATIO : mean [95 % t interval] of the runs' Phi through
# mid-bed (bin/onset's onset_runs.csv), and how many runs
runs_phi() {
	[ -f "$ANA/$1/onset_runs.csv" ] || { printf 'not computed'; return; }
	set -- $(csv_mean "$ANA/$1/onset_runs.csv" phi "frequency=$2 radius_ratio=$3")
	[ "${4:-0}" -ge 2 ] && printf '%s [%s, %s] (%s runs)' "$1" "$2" "$3" "$4" || printf '%s run(s)' "${4:-0}"
}

# REPRODUCE_CROSSCODE=1: the cross-code pieces put in place in the existing report, each
# exactly once (a report without one of the places is refused, not patched)
if [ "$CROSSCODE" = 1 ]; then
	[ -s "$OUT" ] || { echo "reproduce: REPRODUCE_CROSSCODE=1 needs $OUT (make reproduce writes it)" >&2; exit 1; }
	[ -f "$VAL" ] || { echo "reproduce: REPRODUCE_CROSSCODE=1 needs $VAL (make validate-lammps writes it)" >&2; exit 1; }
	cc=$W/crosscode
	mkdir -p "$cc" || exit 1
	lammps B >"$cc/B" && lammps D >"$cc/D" && crosscode_c >"$cc/C" && validation_section >"$cc/V" || exit 1
	# the integrator lines' evidence: docs/preset_evidence.tsv's rows as they are now (the
	# validation may have written one), per campaign name, and per NAME_on (rel_setup's
	# copies at the onset's offsets carry their campaign's preset lines)
	for f in campaigns/reproduce/*.campaign; do
		ev=$(bash "$root/scripts/preset_evidence.sh" line "$f") || exit 1
		printf '%s\t%s\n%s_on\t%s\n' "$(cname "$f")" "$ev" "$(cname "$f")" "$ev"
	done >"$cc/E" || exit 1
	when=$(sed -n 's/^Written by `make reproduce` (scripts\/reproduce.sh) on \([0-9-]*\).*/\1/p' "$OUT" | head -n 1)
	awk -v dir="$cc" -v when="${when:-an earlier day}" -v now="$(date -u +%Y-%m-%d)" -v mark="Evidence (docs/preset_evidence.tsv): " '
		function put(f,   l) { while ((getline l < (dir "/" f)) > 0) print l; close(dir "/" f); done[f]++ }
		BEGIN { while ((getline l < (dir "/E")) > 0) { t = index(l, "\t"); ev[substr(l, 1, t - 1)] = substr(l, t + 1) } }
		/^\*Integrator\* \(/ && index($0, mark) {
			nm = substr($0, 15); nm = substr(nm, 1, index(nm, ")") - 1)
			if (ev[nm] != "") { print substr($0, 1, index($0, mark) + length(mark) - 1) ev[nm] "."; next }
		}
		skip && /^(Each code alone|Across the codes:)/ { next }
		skipsec && /^## / { skipsec = 0 }
		skipsec { next }
		{ skip = 0 }
		/^\| cross-code lines \|/ { next }
		/^\| this invocation \|/ { print; printf "| cross-code lines | refreshed on %s from docs/validate_lammps.md (REPRODUCE_CROSSCODE=1); the rest as written on %s |\n", now, when; next }
		/^\*Cross-checked in LAMMPS[*:]/ && /part B[ ,]/ { put("B"); next }
		/^\*Cross-checked in LAMMPS[*:]/ && /part D[ ,]/ { put("D"); next }
		/^\*Cross-checked in LAMMPS[*:]/ && /part C[ ,]/ { put("C"); skip = 1; next }
		/^## Validation against LAMMPS$/ { put("V"); print ""; skipsec = 1; next }
		{ print }
		END { for (f in want) if (done[f] != 1) { printf "reproduce: %d places for the cross-code piece %s in the report, want 1\n", done[f], f > "/dev/stderr"; bad = 1 }
			exit bad }
		BEGIN { want["B"]; want["C"]; want["D"]; want["V"] }' "$OUT" >"$OUT.tmp" || { rm -f "$OUT.tmp"; exit 1; }
	mv "$OUT.tmp" "$OUT" && log "wrote $OUT: the cross-code lines from $VAL, the rest unchanged"
	exit 0
fi

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
	if [ "$REPORT_ONLY" = 1 ]; then echo "| this invocation | report only (REPRODUCE_REPORT_ONLY=1): no campaign and no tool ran; the runs' own times are in the cost section |"
	else echo "| this invocation | $T_ALL s wall on $(nproc) cores ($T_RUN s running campaigns), $((n1 - n0)) runs simulated |"; fi
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
		integrator "$n" "${FILE[claim1_onset]}"
		integrator "$h" "${FILE[claim1_hysteresis]}"
		echo
		search=$(q "SELECT $(num estimate), $(num ci_lo), $(num ci_hi), replicates, runs, state FROM onset_group WHERE campaign = '$n' LIMIT 1")
		read -r se slo shi srep sruns sstate <<<"$(echo "$search" | tr '\t' ' ')"
		# a ramp campaign's duration and its range (one of each per campaign)
		ramp_of() { q "SELECT printf('%g %g-%g', MIN(duration), MIN(ramp_from), MIN(ramp_to)) FROM runs WHERE campaign = '$1' AND current"; }
		echo "| quantity | ours (95 % interval) | test |"
		echo "|---|---|---|"
		echo "| onset f_on (the [onset] search: bisection per replicate, the median of the replicates' onsets) | $(iv "${se:-} ${slo:-} ${shi:-}") Hz, ${srep:-0} replicates, ${sruns:-0} runs (${sstate:-not run}) | order statistics of the replicates' onsets |"
		# bin/onset on the same runs by the same definition (its default on an [onset]
		# campaign): the threshold crossing of the mean flux per frequency
		read -r tf tlo thi _ <<<"$(val "$n" onset threshold_f)"
		agree=$(awk -v a="${slo:--}" -v b="${shi:--}" -v c="${tlo:--}" -v d="${thi:--}" 'BEGIN {
			if (a + 0 != a || b + 0 != b || c + 0 != c || d + 0 != d) print "not decided"
			else print (a <= d && c <= b) ? "agrees with f_on (the intervals overlap)" : "differs from f_on (the intervals do not overlap)" }')
		echo "| the same onset by bin/onset (the crossing of the mean flux per frequency, same runs) | $(iv "${tf:-} ${tlo:-} ${thi:-}") Hz | $agree |"
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
		verdict_claim1 "$n" "$h" "$(ramp_of "$h" | cut -d' ' -f1)" "${ramps##* }" "$(ramp_of "${ramps##* }" | cut -d' ' -f1)" |
			verdict_combine | render
		echo
		lammps B
		echo
		echo "**The onset** is $ONSET_DEF (docs/model.md, \"The onset of convection\"); f_on is"
		echo "the adaptive search's estimate of it, and claims 2, 3 and 5 are evaluated again at the same distance"
		echo "from it as the paper's frequencies are from the paper's onset. The runs' stop rule, bin/onset and its"
		echo "figure use the same definition (the figure's dashed line; its fitted sigmoid's midpoint f₀ is"
		echo "labelled as such, not a second onset), and no interval is narrower than the runs resolve"
		echo "(docs/analysis.md, \"Intervals and the data's resolution\")."
		echo
		echo "$(fig "$ANA/$n/onset.png" claim1_onset.png) $(fig "$ANA/$h/hysteresis.png" claim1_hysteresis.png)$(has_runs "$hs" && printf ' %s' "$(fig "$ANA/$hs/hysteresis.png" claim1_hysteresis_slow.png)")"
		echo
	fi
	# at_onset CLAIM-KEY : the lead-in of a claim's evaluation at f_on's offsets
	at_onset() {
		echo "### At the same distance from this model's onset"
		echo
		if [ -z "$F_ON" ]; then echo "*Not evaluated: claim 1's onset search is not done.*"; echo; return 1; fi
		if ! has_runs "${NAME[$1_on]}"; then echo "*Not run yet* (\`make reproduce\` runs ${NAME[$1_on]} at ${REL_F[$1]} Hz)."; echo; return 1; fi
		echo "f_on = $F_ON Hz here, $PAPER_ONSET Hz in the paper: the paper's frequencies shifted by f_on − $PAPER_ONSET Hz,"
		echo "${REL_F[$1]// /, } Hz, with $(q "SELECT MAX(replicate) FROM run WHERE campaign = '${NAME[$1_on]}' AND current") replicates."
		echo
		integrator "${NAME[$1_on]}" "${FILE[$1_on]}"
		echo
		return 0
	}
	claim2_tables() { # CAMPAIGN
		local n=$1 f g
		echo "| frequency | Φ through mid-bed without | with 𝓡 = 4 | reach without | reach with 𝓡 = 4 | reach with − without | lines whose Φ differs |"
		echo "|---|---|---|---|---|---|---|"
		for f in $(q "SELECT DISTINCT frequency FROM runs WHERE campaign = '$n' AND current ORDER BY frequency"); do
			g="frequency = $f"
			printf '| %s Hz | %s | %s | %s cm | %s cm | %s cm | %s |\n' "$f" "$(runs_phi "$n" "$f" 0)" "$(runs_phi "$n" "$f" 4)" \
				"$(iv "$(val "$n" rolls reach "$g AND radius_ratio = 0")")" "$(iv "$(val "$n" rolls reach "$g AND radius_ratio = 4")")" \
				"$(iv "$(val "$n" rolls reach_diff "$g AND radius_ratio = 4")")" "$(val "$n" rolls lines_differ "$g AND radius_ratio = 4" | cut -f1)"
		done
		echo
		echo "Runs: $(counts "$n")."
		echo
	}
	if want 2; then
		n=${NAME[claim2_rolls]}
		echo "## Claim 2: the intruder drags the rolls deeper close to the onset"
		echo
		echo "*Paper:* at 2.8 Hz Φ(D) extends further down with the intruder than without; at 2.6 Hz both"
		echo "beds only fluctuate, at 3.0 Hz both convect alike."
		echo
		integrator "$n" "${FILE[claim2_rolls]}"
		echo
		echo "Φ through mid-bed: particles per period through $BAND of the bed (bin/onset), a bed convects"
		echo "above $THR. How deep the rolls reach (bin/rolls): the lowest height where the run's |Φ(D)| is"
		echo "a fraction of its maximum; with − without > 0: deeper with the intruder. 95 % intervals."
		echo
		claim2_tables "$n"
		verdict_claim2 "$n" "$ANA/$n/onset_runs.csv" "$THR" 2.6 2.8 3.0 | verdict_combine | render
		echo
		if at_onset claim2_rolls; then
			claim2_tables "${NAME[claim2_rolls_on]}"
			verdict_claim2 "${NAME[claim2_rolls_on]}" "$ANA/${NAME[claim2_rolls_on]}/onset_runs.csv" "$THR" ${REL_F[claim2_rolls]} |
				verdict_combine | render
			echo
		fi
		echo "$(fig "$ANA/$n/rolls.png" claim2_rolls.png) $(fig "$ANA/$n/fig3.png" claim2_fig3.png) $(fig "$ANA/$n/fig1.png" claim2_fig1.png)"
		echo
	fi
	claim3_table() { # CAMPAIGN
		local n=$1 f g
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
	}
	if want 3; then
		n=${NAME[claim3_ring]}
		echo "## Claim 3: larger forces around the intruder"
		echo
		echo "*Paper:* in the 4.5–8 cm ring the mean force on small grains is about 15 % larger with the"
		echo "intruder at 2.8 Hz (about 5 % at 2.6 Hz), while the granular temperature is about the same."
		echo
		integrator "$n" "${FILE[claim3_ring]}"
		echo
		echo "Ratios with/without the intruder of the ring's means before the rise (bin/ring; bootstrap"
		echo "percentile intervals, the two systems resampled apart):"
		echo
		claim3_table "$n"
		verdict_claim3 "$n" 2.8 2.6 | verdict_combine | render
		echo
		if at_onset claim3_ring; then
			set -- ${REL_F[claim3_ring]}
			claim3_table "${NAME[claim3_ring_on]}"
			verdict_claim3 "${NAME[claim3_ring_on]}" "$2" "$1" | verdict_combine | render
			echo
		fi
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
		integrator "$n" "${FILE[claim4_waiting]}"
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
		echo "Runs: $(counts "$n"). The whale effect (part 4d) is open question 5's long runs."
		echo
		wq=; qwant 5 && wq=${QNAME[q5_long]}
		verdict_claim4 "$n" "$wq" | verdict_combine | render
		echo
		lammps D
		echo
		echo "$(fig "$ANA/$n/waiting_km.png" claim4_km.png) $(fig "$ANA/$n/fig4.png" claim4_fig4.png)"
		echo
	fi
	claim5_table() { # CAMPAIGN
		local n=$1 f d w
		echo "| frequency | depth (rows beneath) | runs | risen | fraction risen | median wait | one row lower: Δ fraction risen | Fisher p |"
		echo "|---|---|---|---|---|---|---|---|"
		q "SELECT DISTINCT frequency, depth FROM runs WHERE campaign = '$n' AND current ORDER BY frequency, depth" |
			while IFS=$'\t' read -r f d; do
				w="frequency = $f AND depth = $d"
				printf '| %s Hz | %s | %s | %s | %s | %s s | %s | %s |\n' "$f" "$d" "$(val "$n" waiting runs "$w" | cut -f1)" \
					"$(val "$n" waiting risen "$w" | cut -f1)" "$(iv "$(val "$n" waiting fraction_risen "$w")")" \
					"$(iv "$(val "$n" waiting median "$w")")" "$(val "$n" waiting lower_fraction_diff "$w" | cut -f1)" \
					"$(val "$n" waiting lower_fisher_p "$w" | cut -f1)"
			done
		echo
		echo "Runs: $(counts "$n")."
		echo
	}
	if want 5; then
		n=${NAME[claim5_depth]}
		echo "## Claim 5: close to the onset, one row lower can prevent the rise"
		echo
		echo "*Paper:* close to the onset, starting the intruder one row lower can prevent the rise altogether."
		echo
		integrator "$n" "${FILE[claim5_depth]}"
		echo
		echo "\`depth\` counts the full grain rows beneath the intruder (0: on the floor; docs/model.md), so"
		echo "one row lower is depth − 1. Fraction risen: Clopper–Pearson 95 % intervals; one row lower:"
		echo "the fraction risen from depth − 1 minus that from this depth, and Fisher's exact test of the"
		echo "two counts (bin/waiting)."
		echo
		claim5_table "$n"
		verdict_claim5 "$n" | verdict_combine | render
		echo
		crosscode_c
		echo
		if at_onset claim5_depth; then
			claim5_table "${NAME[claim5_depth_on]}"
			verdict_claim5 "${NAME[claim5_depth_on]}" | verdict_combine | render
			echo
		fi
		echo "$(fig "$ANA/$n/waiting_km.png" claim5_km.png)"
		echo
	fi
	validation_section
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
	local_cpu() { # CAMPAIGN -> the estimate, or "?" where a rate it needs was not measured
		local nf np
		read -r nf np <<<"$(q "SELECT TOTAL(integrator = 'verlet'), TOTAL(integrator <> 'verlet') FROM runs
			WHERE campaign = '$1' AND current" | tr '\t' ' ')"
		if { [ "${nf%.*}" != 0 ] && [ -z "$C_FAST" ]; } || { [ "${np%.*}" != 0 ] && [ -z "$C_PAPER" ]; }; then
			echo "?"
			return
		fi
		q "SELECT printf('%.0f', TOTAL(steps * n_grains / 950.0 * CASE WHEN integrator = 'verlet' THEN ${C_FAST:-0}
			ELSE ${C_PAPER:-0} END)) FROM runs WHERE campaign = '$1' AND current"
	}
	add_cpu() { # VAR CAMPAIGN : its estimate added to VAR; an unknown one counted in UNKNOWN
		local v
		v=$(local_cpu "$2")
		if [ "$v" = "?" ]; then UNKNOWN=$((UNKNOWN + 1)); else printf -v "$1" '%s' $((${!1} + v)); fi
	}
	cost_row() { # CAMPAIGN-NAME KEY
		printf '| %s | %s | %s | %s | %s | %s |\n' "$1" "$(q "SELECT COUNT(*) FROM runs WHERE campaign = '$1' AND current")" \
			"$(q "SELECT printf('%.0f', TOTAL(status_time)) FROM runs WHERE campaign = '$1' AND current")" \
			"$(local_cpu "$1")" \
			"$(q "SELECT printf('%.0f', TOTAL(wall_seconds)) FROM runs WHERE campaign = '$1' AND current")" "${WALL[$2]:-0}"
	}
	tot_c=0 tot_q=0 UNKNOWN=0
	for k in $CLAIMS; do
		for c in $(campaigns_of "$k"); do cost_row "${NAME[$c]}" "$c"; add_cpu tot_c "${NAME[$c]}"; done
	done
	for c in claim2_rolls_on claim3_ring_on claim5_depth_on; do
		[ -n "${NAME[$c]:-}" ] && has_runs "${NAME[$c]}" || continue
		cost_row "${NAME[$c]}" "$c"; add_cpu tot_c "${NAME[$c]}"
	done
	for k in $QUESTIONS; do
		for c in $(campaigns_of_question "$k"); do cost_row "${QNAME[$c]}" "$c"; add_cpu tot_q "${QNAME[$c]}"; done
	done
	echo
	echo "On $(nproc) quiet cores: the claims about $((tot_c / 60 / $(nproc))) min of CPU, the open questions about $((tot_q / 60 / $(nproc))) min (estimates as above, without settling and tools)."
	[ "$UNKNOWN" = 0 ] || echo "The estimates leave out $UNKNOWN campaign(s) marked ? (their preset's rate was not measured): the sums are lower bounds."
} >"$OUT.tmp" && mv "$OUT.tmp" "$OUT"
log "wrote $OUT ($((n1 - n0)) runs simulated, $T_ALL s)"
