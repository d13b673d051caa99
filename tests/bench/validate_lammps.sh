#!/usr/bin/env bash
# validate_lammps.sh - `make validate-lammps` (issue #16, point 4; "verdicts a referee can
# check", part 6): the engine against LAMMPS gran/hooke, a code no one here wrote, on the
# SAME settled beds in both codes, where the paper's claims are most sensitive.
#
#   A. Phi(D) at VALIDATE_FREQ (3.0) Hz without intruder: the profile of the flux,
#      compared line by line over the beds (the engine in the paper preset, gear5).
#   B. The onset of convection without intruder: per bed, Phi through the band
#      0.4-0.6 of the surface height at each frequency of a grid around this model's
#      onset; a run convects when Phi >= 2 particles per period (the study's
#      threshold); per bed the onset is the midpoint between the highest
#      non-convecting and the lowest convecting frequency; the two codes' onsets
#      paired bed by bed.
#   C. Claim 5: the intruder R = 4 at depth 0 and depth 1 (rows beneath it; "one row
#      lower" is depth - 1) at 2.7 Hz: risen or not within the run, by the engine's rule
#      in both codes; Fisher's test of the depths in each code, McNemar's of the codes
#      at each depth, and the power of the latter.
#   D. Claim 4: R = 4 at the claim-4 campaign's frequency and depth: the waiting time
#      per bed in each code, paired, and the fraction rising within 5 s.
#
# How (every part):
#   1. settled beds prepared by the engine (bin/shake duration=0) and written as
#      LAMMPS data files (write_lammps; the wall disks' velocity there is the drive's at
#      t = 0, so a bed is written once per frequency it is shaken at);
#   2. each bed shaken in both codes: bin/shake from that data file, and LAMMPS with
#      tests/bench/lammps/vibrated_box.in (the deck whose physics
#      tests/integration/lammps_agreement.sh checks against the engine: Y, gamma_N,
#      gamma_S, mu, g, the wall disks' masses, velocity Verlet) with a fragment inserted
#      around its `run ${steps}` line that only adds output: validate_strobe.in (A, B:
#      every atom at the engine's stroboscopic steps) or validate_rise.in (C, D: the
#      engine's rise rule on every step, the run stopped at the rise). In B, C and D the
#      engine runs with the deck's integrator and step (integrator = verlet, dt read
#      from the deck), so that a difference is the code's, not the integrator's; A keeps
#      the paper preset (gear5) it has always compared;
#   3. the flux of a LAMMPS run is counted from its dump by the engine's own crossing
#      code (bin/dumpflux dump: core/model/crossing.c, the lines of the engine's run of the
#      same bed, the box offset A sin(2 pi f t) taken off); the rise by the engine's rule
#      (validate_rise.in) against the engine's own `risen` / `waiting_time`;
#   4. the statistics (bin/dumpflux compare, bin/dumpflux stats: analysis/measure/pairdiff.c,
#      analysis/measure/twocode.c, exact small-sample tests) and one Markdown fragment, a
#      section per part (`## A.` ... `## D.`, each with a `**Result:**` line), a summary
#      table at the top, figures for A and B (PNG and PDF).
#
# All runs of all parts go into one queue, longest first, JOBS at a time. Each prep and
# run records its wall and CPU seconds; the fragment states them per part, with the
# CPU model and the date.
#
# Knobs (environment):
#   VALIDATE_PARTS       parts to run, default "A B C D"; the fragment holds every part
#                        found in the run directory, each saying when it ran
#   VALIDATE_QUICK=1     every part at a tiny size (2 beds, a few seconds, two onset
#                        frequencies): checks the pipeline, says nothing about agreement
#   A: VALIDATE_BEDS (10), VALIDATE_DURATION (80 s), VALIDATE_SKIP (0.2 of the periods),
#      VALIDATE_FREQ (3.0 Hz)
#   B: VALIDATE_ONSET_BEDS (3), VALIDATE_ONSET_FREQS ("2.55 2.60 2.65 2.70 2.75 2.80
#      2.85"), VALIDATE_ONSET_DURATION (48 s), VALIDATE_ONSET_SKIP (0.5: the first half
#      of the periods, as the study's flux stop rule skips 24 of 48 s)
#   C: VALIDATE_C_BEDS (6 per depth), VALIDATE_C_DURATION (120 s), VALIDATE_C_FREQ (2.7)
#   D: VALIDATE_D_BEDS (12), VALIDATE_D_DURATION (30 s); frequency and depth from
#      campaigns/reproduce/claim4_waiting.campaign and its scene (VALIDATE_D_FREQ,
#      VALIDATE_D_DEPTH override)
#   E: part D with shear history on in both codes (not in the default parts: the
#      engine's `tangential = spring`, LAMMPS `gran/hooke/history`, both k_t = 2/7 of
#      the normal stiffness), on D's beds (the same seeds) and settings
#   VALIDATE_CHEAP_FIRST=1 (the runs cheapest first, not longest first: for a validation
#   spread over sessions), JOBS (parallel runs, default 2), VALIDATE_WORK (run directory, default
#   build/validate[-quick]), VALIDATE_OUT (where the .md and the figures go: docs for the
#   full run, the run directory for the quick one), VALIDATE_REPORT=1 (the statistics
#   and the fragment only, from the runs already in the run directory), VALIDATE_FRESH=1
#   (start the parts over; without it a run that finished before is not run again: an
#   interrupted validation resumes, more beds add only theirs, with the binaries and
#   settings of the first start, other settings refused).
# The defaults are sized for 50 minutes on 2 idle cores even if no intruder rose (about
# 43 minutes when they rise as in the engine; measured rates and the sum in
# docs/benchmarks.md, "Sizing make validate-lammps"); the fragment states the power that leaves. The runs
# are started under nice -n 5 here; run the script (or make) without nice.
# Exit status: 0 done (whatever the verdicts: the fragment states them), 1 a step failed.
set -euo pipefail
REPO=$(cd "$(dirname "$0")/../.." && pwd)
cd "$REPO"
QUICK=${VALIDATE_QUICK:-0}
read -r -a PARTS_LIST <<<"${VALIDATE_PARTS:-A B C D}"
PARTS="${PARTS_LIST[*]}" # one space apart
if [ "$QUICK" = 1 ]; then
	A_BEDS=${VALIDATE_BEDS:-2} A_DUR=${VALIDATE_DURATION:-6}
	B_BEDS=${VALIDATE_ONSET_BEDS:-2} B_FREQS=${VALIDATE_ONSET_FREQS:-2.60 2.80} B_DUR=${VALIDATE_ONSET_DURATION:-4}
	C_BEDS=${VALIDATE_C_BEDS:-2} C_DUR=${VALIDATE_C_DURATION:-4}
	D_BEDS=${VALIDATE_D_BEDS:-2} D_DUR=${VALIDATE_D_DURATION:-4}
	WORK=${VALIDATE_WORK:-build/validate-quick}
	OUT=${VALIDATE_OUT:-$WORK}
else
	A_BEDS=${VALIDATE_BEDS:-10} A_DUR=${VALIDATE_DURATION:-80}
	B_BEDS=${VALIDATE_ONSET_BEDS:-3} B_FREQS=${VALIDATE_ONSET_FREQS:-2.55 2.60 2.65 2.70 2.75 2.80 2.85} B_DUR=${VALIDATE_ONSET_DURATION:-48}
	C_BEDS=${VALIDATE_C_BEDS:-6} C_DUR=${VALIDATE_C_DURATION:-120}
	D_BEDS=${VALIDATE_D_BEDS:-12} D_DUR=${VALIDATE_D_DURATION:-30}
	WORK=${VALIDATE_WORK:-build/validate}
	OUT=${VALIDATE_OUT:-docs}
fi
A_FREQ=${VALIDATE_FREQ:-3.0}
A_SKIP=${VALIDATE_SKIP:-0.2}
B_SKIP=${VALIDATE_ONSET_SKIP:-0.5}
B_THR=2          # particles per period: the study's "convecting" (docs/model.md, "How a claim is judged")
C_FREQ=${VALIDATE_C_FREQ:-2.7}
C_R=4            # radius_ratio of parts C and D
D_FAST=5         # s: "rises at once" (claim 4a's bound)
AMP=2            # the paper's amplitude (cm)
JOBS=${JOBS:-2}
SHAKE=${VALIDATE_SHAKE:-$REPO/bin/shake}
DUMPFLUX=${VALIDATE_DUMPFLUX:-$REPO/bin/dumpflux}
DECK=$REPO/tests/bench/lammps/vibrated_box.in
STROBE=$REPO/tests/bench/lammps/validate_strobe.in
RISE=$REPO/tests/bench/lammps/validate_rise.in
D_CAMPAIGN=campaigns/reproduce/claim4_waiting.campaign
LMP=${LMP:-lmp}
REPORT=${VALIDATE_REPORT:-0}
FRESH=${VALIDATE_FRESH:-0}
T0=$(date +%s)

die() { echo "validate_lammps: $*" >&2; exit 1; }
command -v "$LMP" >/dev/null || die "$LMP (LAMMPS) not found: make deps installs the Debian package lammps"
command -v gnuplot >/dev/null || die "gnuplot not found: make deps"
command -v h5dump >/dev/null || die "h5dump not found: make deps (hdf5-tools)"
if [ ! -x "$SHAKE" ] || [ ! -x "$DUMPFLUX" ]; then die "build first: $SHAKE, $DUMPFLUX"; fi
for p in $PARTS; do
	case $p in A | B | C | D | E) ;; *) die "VALIDATE_PARTS: '$p' is not a part (A B C D E)" ;; esac
done

# a key of an INI file: the first `key = value` in [section] (or at the top when the
# section is empty), comments (;) and blanks stripped
ini_get() { # FILE SECTION KEY
	awk -v want="$2" -v k="$3" '/^[ \t]*\[/ { s = $0; gsub(/[][ \t]/, "", s); next }
		{ line = $0; sub(/;.*/, "", line); n = index(line, "="); if (!n) next
		  key = substr(line, 1, n - 1); v = substr(line, n + 1); gsub(/[ \t\r]/, "", key); gsub(/[ \t\r]/, "", v)
		  if (key == k && (s == want || (want == "" && s == ""))) { print v; exit } }' "$1"
}
# part D: the claim-4 campaign's setting (its [scene], else its scene file's)
D_SCENE=$(realpath -m --relative-to="$REPO" "$(dirname "$D_CAMPAIGN")/$(ini_get "$D_CAMPAIGN" campaign scene)")
scene_key() { # KEY: the campaign's [scene] value, else the scene file's ([scene] or top level)
	local v
	v=$(ini_get "$D_CAMPAIGN" scene "$1")
	[ -n "$v" ] || v=$(ini_get "$D_SCENE" scene "$1")
	[ -n "$v" ] || v=$(ini_get "$D_SCENE" "" "$1")
	echo "$v"
}
D_FREQ=${VALIDATE_D_FREQ:-$(scene_key frequency)}
D_DEPTH=${VALIDATE_D_DEPTH:-$(scene_key depth)}
if [ -z "$D_FREQ" ] || [ -z "$D_DEPTH" ]; then
	die "no frequency or depth in $D_CAMPAIGN or $D_SCENE (VALIDATE_D_FREQ, VALIDATE_D_DEPTH)"
fi

# the deck's time step is the one the dumps' steps are counted in, and the engine's in B-D
DT=$(awk '$1 == "timestep" { print $2; exit }' "$DECK")
[ -n "$DT" ] || die "no timestep line in $DECK"
steps_of() { # DURATION -> steps of DT, or fail when not a whole number
	awk -v d="$1" -v dt="$DT" 'BEGIN { s = d / dt; r = int(s + 0.5); if (s - r > 1e-6 || r - s > 1e-6) exit 1; print r }'
}
for v in A_DUR B_DUR C_DUR D_DUR; do
	steps_of "${!v}" >/dev/null || die "$v = ${!v} s is not a whole number of steps of $DT s"
done
for v in A_BEDS B_BEDS C_BEDS D_BEDS; do
	if ! [[ ${!v} =~ ^[0-9]+$ ]] || [ "${!v}" -lt 2 ] || [ "${!v}" -gt 99 ]; then die "$v = ${!v}: expected 2 to 99 beds"; fi
done
for f in $B_FREQS; do
	awk -v f="$f" 'BEGIN { exit !(f + 0 > 0 && f ~ /^[0-9.]+$/) }' || die "VALIDATE_ONSET_FREQS: '$f' is not a frequency"
done
[ "$(echo "$B_FREQS" | wc -w)" -ge 2 ] || die "VALIDATE_ONSET_FREQS: two frequencies at least"

# seeds: each part its own beds (C: depth 0 and depth 1 apart)
seeds() { # PART [DEPTH]
	case $1 in
	A) seq 101 $((100 + A_BEDS)) ;;
	B) seq 201 $((200 + B_BEDS)) ;;
	C) seq $((301 + 100 * $2)) $((300 + 100 * $2 + C_BEDS)) ;;
	D | E) seq 501 $((500 + D_BEDS)) ;; # E: D's beds, with shear history
	esac
}
tags() { # PART: the runs of a part, one name each
	local s f d
	case $1 in
	A | D | E) seeds "$1" ;;
	B) for s in $(seeds B); do for f in $B_FREQS; do echo "${s}_$f"; done; done ;;
	C) for d in 0 1; do for s in $(seeds C $d); do echo "d${d}_$s"; done; done ;;
	esac
}

mkdir -p "$WORK/bin" "$OUT"
WORK=$(cd "$WORK" && pwd)
# Resuming: a run that finished (its .ok file) is not run again, so an interrupted
# validation (a session's end) goes on where it stopped, and more beds (a larger
# VALIDATE_C_BEDS) add only their own runs. What the runs share must then be what they
# were made with: the binaries are those of the first start (kept in WORK/bin), and
# every setting but the numbers of beds is held to the recorded one (WORK/settings).
# VALIDATE_FRESH=1 starts every part of PARTS over.
settings="DT=$DT AMP=$AMP A_FREQ=$A_FREQ A_DUR=$A_DUR B_FREQS=$B_FREQS B_DUR=$B_DUR C_FREQ=$C_FREQ C_DUR=$C_DUR C_R=$C_R D_FREQ=$D_FREQ D_DUR=$D_DUR D_DEPTH=$D_DEPTH QUICK=$QUICK"
done_runs=$(find "$WORK" -mindepth 2 -maxdepth 2 -name '*.ok' 2>/dev/null | wc -l)
if [ "$REPORT" != 1 ] && [ "$FRESH" != 1 ] && [ "$done_runs" -gt 0 ]; then
	[ "$(cat "$WORK/settings" 2>/dev/null)" = "$settings" ] ||
		die "$WORK holds $done_runs finished runs made with other settings ($(cat "$WORK/settings" 2>/dev/null || echo none recorded)); VALIDATE_FRESH=1 starts over"
	echo "validate_lammps: resuming in $WORK: $done_runs runs already finished, with the binaries of the first start" >&2
elif [ "$REPORT" != 1 ]; then
	# the binaries copied first: others may rebuild bin/ while the runs go on; a report
	# from recorded runs reads their files with the binaries they were made with
	cp "$SHAKE" "$WORK/bin/shake" || die "cannot copy $SHAKE"
	cp "$DUMPFLUX" "$WORK/bin/dumpflux" || die "cannot copy $DUMPFLUX"
	echo "$settings" >"$WORK/settings"
fi
[ -x "$WORK/bin/dumpflux" ] || die "no $WORK/bin/dumpflux"
VSHAKE=$SHAKE # the engine this invocation was given (a part's own copy: part_bin)
SHAKE=$WORK/bin/shake DUMPFLUX=$WORK/bin/dumpflux
# A part whose runs began with another engine than the first start's (part E needs the
# shear spring, which an older validation's binary lacks) keeps its own in WORK/P/bin:
# copied when the part starts with no run finished, used for all its runs after that
part_bin() { # PART NAME
	if [ -x "$WORK/$1/bin/$2" ]; then echo "$WORK/$1/bin/$2"; else echo "$WORK/bin/$2"; fi
}
export -f part_bin

# the LAMMPS inputs: the deck with a fragment's lines before its one `run ${steps}` line
# (those after a `#@after run` line of the fragment just after it)
insert() { # FRAGMENT OUT
	awk 'FNR == NR { if ($0 ~ /^#@after run/) { after = 1; next } if (after) post = post $0 "\n"; else pre = pre $0 "\n"; next }
		/^run \$\{steps\}[ \t]*$/ { printf "%s", pre; print; printf "%s", post; n++; next } { print }
		END { if (n != 1) exit 1 }' "$1" "$DECK" >"$2" ||
		die "$DECK: expected exactly one 'run \${steps}' line to insert $1 at"
}
insert "$STROBE" "$WORK/strobe.in"
insert "$RISE" "$WORK/rise.in"
# part E: the same deck with shear history (its `history` variable: Kt NULL, 2/7 Kn, the
# engine's default shear_stiffness), set to yes by a first line (an index variable keeps its
# first value), or no part E
grep -q '^variable history index no' "$WORK/rise.in" ||
	die "$DECK: no 'variable history index no' line: part E cannot switch history on"
{ echo 'variable history index yes'; cat "$WORK/rise.in"; } >"$WORK/rise_history.in"

# (the readers read to the end: a writer killed by SIGPIPE would fail the pipeline)
CPU_MODEL=$(lscpu 2>/dev/null | awk -F: '/^Model name/ && !m { m = $2; sub(/^[ \t]+/, "", m) } END { print m }') || CPU_MODEL="?"
LMP_VERSION=$("$LMP" -h 2>/dev/null | awk 'NF && !v { v = $0; sub(/^ +/, "", v) } END { print v }') || LMP_VERSION="?"
COMMIT="$(git rev-parse --short HEAD 2>/dev/null || echo '?')$(git diff --quiet HEAD -- core analysis tests/bench 2>/dev/null || echo ' (with uncommitted changes)')"
cmd="make validate-lammps"
[ "$QUICK" = 1 ] && cmd="$cmd VALIDATE_QUICK=1"
[ "$PARTS" = "A B C D" ] || cmd="$cmd VALIDATE_PARTS=\"$PARTS\""
[ "$QUICK" = 1 ] && echo "validate_lammps: QUICK RUN: every part at a tiny size, a check of the pipeline only (no verdict means anything)" >&2
echo "validate_lammps: parts $PARTS in $WORK, $JOBS jobs; A: $A_BEDS beds x $A_DUR s at $A_FREQ Hz; B: $B_BEDS beds x {$B_FREQS} Hz x $B_DUR s;" \
	"C: $C_BEDS beds x depth 0, 1 x $C_DUR s at $C_FREQ Hz; D: $D_BEDS beds x $D_DUR s at $D_FREQ Hz, depth $D_DEPTH" >&2

# ---------------------------------------------------------------- the runs
# job PART KIND TAG: KIND prep (the bed), shake or lmp; each records "wall user sys"
job() {
	local part=$1 kind=$2 tag=$3 rc=0 TIMEFORMAT='%R %U %S'
	local dir=$WORK/$part freq dur seed depth rr=0 where=()
	case $part in
	A) freq=$A_FREQ dur=$A_DUR seed=$tag ;;
	B) freq=${tag#*_} dur=$B_DUR seed=${tag%_*} ;;
	C) freq=$C_FREQ dur=$C_DUR seed=${tag#*_} depth=${tag%%_*} depth=${depth#d} rr=$C_R ;;
	D | E) freq=$D_FREQ dur=$D_DUR seed=$tag depth=$D_DEPTH rr=$C_R ;;
	esac
	[ -z "${depth:-}" ] || where=(depth="$depth") # the beds without intruder as they always were
	local steps
	steps=$(awk -v d="$dur" -v dt="$DT" 'BEGIN { printf "%d", d / dt + 0.5 }')
	local data=$dir/bed_$tag.data out=$dir/${kind}_$tag
	[ -e "$out.ok" ] && return 0 # finished before: resumed
	rm -f "$out".* # what an interrupted attempt left
	case $kind in
	prep)
		{ time nice -n 5 "$(part_bin "$part" shake)" radius_ratio=$rr "${where[@]}" seed="$seed" frequency="$freq" amplitude=$AMP duration=0 \
			progress=no write_lammps="$data" output="$dir/prep_$tag.h5" >"$out.log" 2>&1; } 2>"$out.sec" || rc=$? ;;
	shake | paper | fast)
		local how=()
		case $part/$kind in
		C/paper | C/fast) how=(radius_ratio="$rr" preset="$kind" stop=risen stop_after=0) ;; # the presets on the same beds
		A/*) how=(radius_ratio=0 flux=yes) ;; # the paper preset
		B/*) how=(radius_ratio=0 flux=yes integrator=verlet dt="$DT") ;;
		C/* | D/*) how=(radius_ratio="$rr" integrator=verlet dt="$DT" stop=risen stop_after=0) ;;
		E/*) how=(radius_ratio="$rr" integrator=verlet dt="$DT" stop=risen stop_after=0 tangential=spring) ;;
		esac
		{ time nice -n 5 "$(part_bin "$part" shake)" particles="$data" settle=no "${how[@]}" frequency="$freq" amplitude=$AMP \
			duration="$dur" snapshots=no traj_rate=0 progress=no output="$out.h5" >"$out.log" 2>&1; } 2>"$out.sec" || rc=$? ;;
	lmp)
		if [ "$part" = A ] || [ "$part" = B ]; then
			{ time OMP_NUM_THREADS=1 nice -n 5 "$LMP" -in "$WORK/strobe.in" -log none -screen none -nocite \
				-var data "$data" -var steps "$steps" -var freq "$freq" -var amp $AMP \
				-var strobe "$out.dump" >"$out.log" 2>&1; } 2>"$out.sec" || rc=$?
		else
			# the intruder (type 2): its settled height and diameter as the data file has them
			local y0 h
			read -r h y0 < <(awk '/^Atoms/ { on = 1; next } /^Velocities/ { exit } on && NF >= 6 && $2 == 2 { print $3, $6; exit }' "$data")
			local deck=$WORK/rise.in
			[ "$part" != E ] || deck=$WORK/rise_history.in
			{ time OMP_NUM_THREADS=1 nice -n 5 "$LMP" -in "$deck" -log "$out.lammps" -screen none -nocite \
				-var data "$data" -var steps "$steps" -var freq "$freq" -var amp $AMP \
				-var rise_y0 "$y0" -var rise_h "$h" -var rise_out "$out.rise" >"$out.log" 2>&1; } 2>"$out.sec" || rc=$?
		fi ;;
	esac
	[ "$kind" = prep ] ||
		echo "validate_lammps: $part $kind $tag: exit $rc, $(awk '{ printf "%.0f s (CPU %.0f s)", $1, $2 + $3 }' "$out.sec")" >&2
	[ "$rc" != 0 ] || touch "$out.ok"
	return $rc
}
export -f job
export WORK LMP SHAKE DT AMP A_FREQ A_DUR B_DUR C_FREQ C_DUR C_R D_FREQ D_DUR D_DEPTH

if [ "$REPORT" != 1 ]; then
	: >"$WORK/prep.jobs"
	: >"$WORK/run.jobs.est"
	for p in $PARTS; do
		[ "$FRESH" != 1 ] || rm -rf "${WORK:?}/$p"
		mkdir -p "$WORK/$p"
		if [ "$p" = E ] && [ -z "$(find "$WORK/$p" -maxdepth 1 -name '*.ok' -print -quit)" ]; then
			mkdir -p "$WORK/$p/bin" && cp "$VSHAKE" "$WORK/$p/bin/shake" || die "cannot copy $VSHAKE to $WORK/$p/bin"
		fi
		for t in $(tags "$p"); do
			echo "$p prep $t" >>"$WORK/prep.jobs"
			case $p in A) d=$A_DUR ;; B) d=$B_DUR ;; C) d=$C_DUR ;; D | E) d=$D_DUR ;; esac
			# longest first (LAMMPS costs about 6 times the engine's CPU per simulated second)
			echo "$((6 * d)) $p lmp $t" >>"$WORK/run.jobs.est"
			echo "$d $p shake $t" >>"$WORK/run.jobs.est"
			# C also with the engine's own presets on the same beds: paper (gear5, the
			# paper's step) and fast (verlet at 4 times it), for the presets at the onset
			[ "$p" != C ] || printf '%s\n' "$d $p paper $t" "$((d / 4)) $p fast $t" >>"$WORK/run.jobs.est"
		done
	done
	# VALIDATE_CHEAP_FIRST=1: the cheapest first instead, so that a validation spread over
	# sessions (resumed) has every engine run before the first LAMMPS run
	sort -k1,1n"$([ "${VALIDATE_CHEAP_FIRST:-0}" = 1 ] || echo r)" -s "$WORK/run.jobs.est" | cut -d' ' -f2- >"$WORK/run.jobs"
	# shellcheck disable=SC2016 # the jobs' words, expanded by the inner bash
	xargs -P "$JOBS" -L 1 bash -c 'job "$0" "$1" "$2"' <"$WORK/prep.jobs" ||
		die "a preparation failed (logs in $WORK/*/prep_*.log)"
	T1=$(date +%s)
	echo "validate_lammps: $(wc -l <"$WORK/prep.jobs") beds prepared in $((T1 - T0)) s; $(wc -l <"$WORK/run.jobs") runs" >&2
	# shellcheck disable=SC2016
	xargs -P "$JOBS" -L 1 bash -c 'job "$0" "$1" "$2"' <"$WORK/run.jobs" || die "a run failed (logs in $WORK/*/)"
	T2=$(date +%s)
	for p in $PARTS; do
		# what a part's section states about its runs: when, at which commit, with whom
		echo "$(date -u -d @"$T0" '+%Y-%m-%d %H:%M UTC')|$COMMIT|$PARTS|$JOBS|$QUICK|$CPU_MODEL" >"$WORK/$p/stamp"
	done
	echo "$((T1 - T0)) $((T2 - T1))" >"$WORK/times"
else
	for p in $PARTS; do
		# a validation still under way (resumed over sessions) is reported from the runs
		# finished so far, said as such
		if [ ! -s "$WORK/$p/stamp" ] && ls "$WORK/$p"/*.ok >/dev/null 2>&1; then
			echo "$(date -u '+%Y-%m-%d %H:%M UTC') (in progress: the runs finished so far)|$COMMIT|$PARTS|$JOBS|$QUICK|$CPU_MODEL" >"$WORK/$p/stamp"
		fi
		[ -s "$WORK/$p/stamp" ] || die "VALIDATE_REPORT=1: no runs of part $p in $WORK/$p (run without it first)"
	done
	T2=$(date +%s)
fi

# ---------------------------------------------------------------- helpers of the reports
# per bed: the surface and Phi through the plane (mean over the lines at 0.4-0.6 of the
# surface height, as bin/onset's); plane6 to more digits for the threshold
plane() { awk -v s="$2" '!/^#/ && $2 >= 0.4 * s && $2 <= 0.6 * s { t += $3; n++ } END { printf "%.3f", n ? t / n : 0 }' "$1"; }
plane6() { awk -v s="$2" '!/^#/ && $2 >= 0.4 * s && $2 <= 0.6 * s { t += $3; n++ } END { printf "%.6f", n ? t / n : 0 }' "$1"; }
surface() { awk '/surface/ { for (i = 1; i <= NF; i++) if ($i == "surface") { print $(i + 1); exit } }' "$1"; }
# an attribute of a run file at full precision (strings without their quotes)
h5attr() { h5dump -m %.17g -a "/$2" "$1" 2>/dev/null | awk '/\(0\):/ && !n++ { v = $0; sub(/.*\(0\): */, "", v); gsub(/"/, "", v) } END { print v }'; }
# summed over a part's files of one kind: wall seconds, CPU seconds
sumsec() { cat "$1"/"$2"_*.sec 2>/dev/null | awk '{ t += $1 } END { printf "%.0f", t }'; }
sumcpu() { cat "$1"/"$2"_*.sec 2>/dev/null | awk '{ c += $2 + $3; if (NF < 3) u = 1 } END { if (u) printf "?"; else printf "%.0f", c }'; }
# k of n with its Clopper-Pearson interval: "k/n = f [lo, hi]"
cpint() { "$DUMPFLUX" stats binom "$1" "$2" | awk '{ printf "%d/%d = %.2f [%.2f, %.2f]", $1, $2, $3, $4, $5 }'; }
# a '# key value' of a stats output
key() { awk -v k="$1" '$1 == "#" && $2 == k { print $3; exit }' "$2"; }
fmtp() { awk -v p="$1" 'BEGIN { printf (p < 0.001 ? "%.1e" : "%.3g"), p }'; }
# the smallest differences McNemar's test detects with 80 % power from fraction P0 over N beds
# ("none": not even the largest difference possible that way reaches 80 %)
pwr() { "$DUMPFLUX" stats power "$1" "$2" | awk '{ printf "%s up, %s down", $1 == "nan" ? "none" : "+" $1, $2 == "nan" ? "none" : "−" $2 }'; }
quicknote() { if [ "$QUICK" = 1 ]; then echo "(Quick run: $1 check the pipeline only; the verdict means nothing.)"; fi; }
# a part's timing line: summed over its preparations and runs
part_times() { # PART
	local d=$WORK/$1
	local lw lc sw sc pw pc
	lw=$(sumsec "$d" lmp) lc=$(sumcpu "$d" lmp) sw=$(sumsec "$d" shake) sc=$(sumcpu "$d" shake) pw=$(sumsec "$d" prep) pc=$(sumcpu "$d" prep)
	local runs=("$d"/lmp_*.sec)
	echo "**Run time** (summed over this part's runs, ${#runs[@]} per code): LAMMPS $lw s of wall time ($lc s CPU), shakebox $sw s ($sc s CPU),"
	echo "the preparation of the beds $pw s ($pc s CPU)$(awk -v a="$lc" -v b="$sc" -v c="$pc" 'BEGIN { if (a != "?" && b != "?" && c != "?") printf ": %.0f CPU s in all, about %.1f min on 2 idle cores", a + b + c, (a + b + c) / 120 }')."
}
part_cpu() { local d=$WORK/$1; cat "$d"/*.sec | awk '{ c += $2 + $3 } END { printf "%.0f", c }'; }
part_wall() { local d=$WORK/$1; cat "$d"/*.sec | awk '{ c += $1 } END { printf "%.0f", c }'; }
stamp() { cut -d'|' -f"$2" "$WORK/$1/stamp"; }
part_header() { # PART: when and where this part's runs were made
	echo "Runs started $(stamp "$1" 1) at commit $(stamp "$1" 2) (parts $(stamp "$1" 3) together, $(stamp "$1" 4) at a time) on $(stamp "$1" 6)."
}
FIGBASE=validate_lammps
[ "$QUICK" = 1 ] && FIGBASE=validate_lammps_quick

# the frame check of a strobe dump's profile (dumpflux dump's '# frames' line): the
# walls moved by the drive's A sin(2 pi f t) (fix move wiggle), which dumpflux takes
# off the mobile disks; prints "wall_dev ybox"
frame_check() { # TSV DURATION FREQ
	local fr wd yb
	read -r fr wd yb < <(awk '/^# frames/ { print $3, $17, $13; exit }' "$1")
	[ "$fr" = "$(awk -v d="$2" -v f="$3" 'BEGIN { print int(d * f + 1e-9) + 1 }')" ] || die "$1: the dump has $fr frames"
	awk -v w="$wd" 'BEGIN { exit !(w < 1e-9) }' ||
		die "$1: the LAMMPS walls did not move as A sin(2 pi f t): deviation $wd cm (frame assumption broken)"
	echo "$wd $yb"
}

# ---------------------------------------------------------------- A. Phi(D)
report_A() {
	local d=$WORK/A s wall_dev=0 ybox=0 wd yb fc
	local SEEDS
	SEEDS=$(seeds A)
	for s in $SEEDS; do
		"$DUMPFLUX" run "$d/shake_$s.h5" --skip "$A_SKIP" >"$d/shake_$s.tsv" || die "dumpflux run shake_$s.h5 failed"
		"$DUMPFLUX" dump "$d/lmp_$s.dump" --like "$d/shake_$s.h5" --amplitude $AMP --frequency "$A_FREQ" \
			--dt "$DT" --skip "$A_SKIP" >"$d/lmp_$s.tsv" || die "dumpflux dump lmp_$s.dump failed"
		fc=$(frame_check "$d/lmp_$s.tsv" "$A_DUR" "$A_FREQ")
		read -r wd yb <<<"$fc"
		wall_dev=$(awk -v a="$wall_dev" -v b="$wd" 'BEGIN { print (b > a ? b : a) }')
		ybox=$(awk -v a="$ybox" -v b="$yb" 'BEGIN { print (b > a ? b : a) }')
	done
	# shellcheck disable=SC2046,SC2086 # one file per seed
	"$DUMPFLUX" compare $(printf "$d/shake_%s.tsv " $SEEDS) -- $(printf "$d/lmp_%s.tsv " $SEEDS) \
		>"$d/compare.tsv" || die "dumpflux compare failed"

	local FIG=$FIGBASE
	awk '!/^#/' "$d/compare.tsv" >"$d/plot.tsv"
	cat >"$d/plot.gp" <<GP
do for [fmt in "png pdf"] {
  if (fmt eq "png") { set terminal pngcairo size 900,900 font ",11"; set output "$OUT/$FIG.png" } \
  else { set terminal pdfcairo size 6.5in,6.5in font ",10"; set output "$OUT/$FIG.pdf" }
  set multiplot layout 2,1 title "Φ(D) at $A_FREQ Hz, A = $AMP cm, no intruder: the same $A_BEDS beds shaken by each code"
  set grid
  set key top left
  set ylabel "Φ (particles per period)"
  set format x ""
  set xlabel ""
  set lmargin 10
  set title "mean over the beds ± 95 % interval"
  plot "$d/plot.tsv" using (\$2-0.08):3:4 with yerrorbars pt 7 ps 0.5 lc rgb "#1f77b4" title "shakebox (gear5)", \
       "" using (\$2+0.08):5:6 with yerrorbars pt 5 ps 0.5 lc rgb "#d62728" title "LAMMPS gran/hooke"
  set format x "%g"
  set xlabel "D: height above the floor (cm)"
  set ylabel "ΔΦ (particles per period)"
  set title "paired difference shakebox − LAMMPS ± 95 % interval (filled: interval misses 0)"
  set key off
  plot "$d/plot.tsv" using 2:7:8 with yerrorbars pt 6 ps 0.5 lc rgb "#333333", \
       "" using 2:(\$10 == 0 ? \$7 : 1/0) with points pt 7 ps 0.8 lc rgb "#d62728", 0 with lines lc rgb "black" lw 1
  unset multiplot
}
GP
	gnuplot "$d/plot.gp" || die "gnuplot failed"
	if [ ! -s "$OUT/$FIG.png" ] || [ ! -s "$OUT/$FIG.pdf" ]; then die "the figure was not written"; fi

	val() { awk -v k="$1" '$1 == "#" && $2 == k { print $3; exit }' "$d/compare.tsv"; }
	local ndis nl nused maxt chi2 pmax pchi perms verdict dislines
	ndis=$(val disagree) nl=$(val lines) nused=$(val lines_with_crossings)
	maxt=$(val max_abs_t) chi2=$(val chi2_per_line) pmax=$(val p_max_abs_t) pchi=$(val p_chi2)
	perms=$(awk '$1 == "#" && $2 == "perms" { $1 = $2 = ""; sub(/^ +/, ""); print; exit }' "$d/compare.tsv")
	# the verdict: the lines' own intervals (at 95 % about 5 % of them miss 0 by chance) and
	# the family-wise sign-flip tests (p < 0.05: the profiles differ beyond their intervals)
	verdict=$(awk -v pm="$pmax" -v pc="$pchi" 'BEGIN { print (pm < 0.05 || pc < 0.05) ? "disagree" : "agree" }')
	dislines=$(awk '!/^#/ && $10 == 0 { printf "%s%d (%.1f cm, t = %s)", n++ ? ", " : "", $1, $2, $9 }' "$d/compare.tsv")
	printf '%s\t%s\t%s\n' "Φ(D) at $A_FREQ Hz, no intruder: the flux profile line by line" \
		"$A_BEDS beds × $A_DUR s; sign-flip tests over the $nl lines: max \\|t\\| p = $pmax, χ²/L p = $pchi" "the profiles **$verdict**" >"$d/summary"
	{
		echo "## A. Φ(D) at $A_FREQ Hz over an ensemble of beds"
		echo
		part_header A
		part_times A
		echo
		echo "**Setup.** $A_BEDS settled beds without intruder (seeds $(seeds A | awk 'NR == 1')…$(seeds A | awk 'END { print }'); 950 grains, width 60 cm, the paper's"
		echo "contact law), prepared by the engine and written as LAMMPS data files (\`write_lammps\`); each"
		echo "shaken for $A_DUR s at f = $A_FREQ Hz, A = $AMP cm (Γ = $(awk -v f="$A_FREQ" -v a=$AMP 'BEGIN { printf "%.2f", a * (2 * 3.14159265358979 * f) ^ 2 / 981 }'))"
		echo "by **shakebox** (\`bin/shake\`, paper preset: gear5, Δt = 5·10⁻⁵ s, box frame) and by **LAMMPS**"
		echo "\`gran/hooke\` (\`tests/bench/lammps/vibrated_box.in\`: the same Y, γ_N, γ_S, μ, g, masses and wall"
		echo "disks; velocity Verlet \`nve/sphere disc\` at Δt = $DT s; walls moved by \`fix move wiggle\` in the lab"
		echo "frame). LAMMPS dumps every atom at the engine's stroboscopic steps (sample k at the first step at"
		echo "or after k/f; \`tests/bench/lammps/validate_strobe.in\`); \`bin/dumpflux\` reads the dump and counts the"
		echo "crossings with the engine's own code (\`core/model/crossing.c\`, which \`core/model/observe.c\` calls during a run)"
		echo "on the lines of the engine's run of the same bed, after taking the box offset A sin(2πft) off the"
		echo "heights (at most $(awk -v y="$ybox" 'BEGIN { printf "%.2g", y }') cm at a phase-0 step; the LAMMPS wall disks moved by exactly that, to"
		echo "$(awk -v y="$wall_dev" 'BEGIN { printf "%.1g", y }') cm, so lab and box frame are told apart correctly). Φ(D) per bed and code is the time"
		echo "mean over the periods after the first $(awk -v s="$A_SKIP" 'BEGIN { print s * 100 }') % of them ($(awk -v d="$A_DUR" -v f="$A_FREQ" -v s="$A_SKIP" 'BEGIN { p = int(d * f + 1e-9); k = int(s * p); printf "%d of %d periods, %.0f s", p - k, p, (p - k) / f }'))."
		echo
		echo "**Statistics.** Per line: each code's mean over the beds ± the 95 % Student-t half-width; the"
		echo "paired difference shakebox − LAMMPS (bed by bed; the pairs are independent in practice, the"
		echo "trajectories decorrelate within seconds) with its interval and t = mean/(s/√n); *agree* = the"
		echo "difference's interval holds 0. With $nl lines about 5 % miss 0 by chance, and neighbouring lines"
		echo "are strongly correlated, so the verdict rests on two statistics over all lines with crossings"
		echo "($nused): max |t| and χ²/L = mean of t², whose null distributions come from the sign-flip test"
		echo "(each bed's difference as likely to have either sign if the codes agree; $perms, with the lines' correlations)."
		echo
		echo "**Result: the profiles $verdict.** Lines whose difference interval misses 0: $ndis of $nl${dislines:+ — $dislines}."
		echo "max |t| = $maxt (sign-flip p = $pmax); χ²/L = $chi2 (p = $pchi)."
		if [ "$verdict" = agree ]; then
			echo "Neither family-wise statistic is beyond what sign noise over $A_BEDS beds gives (p ≥ 0.05): Φ(D) from"
			echo "LAMMPS and from shakebox agree within their intervals."
		else
			echo "At least one family-wise statistic is beyond what sign noise over $A_BEDS beds gives (p < 0.05): Φ(D)"
			echo "from LAMMPS and from shakebox **differ** beyond their intervals (see the lines above and the figure)."
		fi
		# more lines outside than chance gives (binomial mean + 2 sd): say where and how large
		awk -v L="$nl" '!/^#/ && $10 == 0 { d += $7; b += $5; n++; if (!lo) lo = $2; hi = $2 }
			END { e = 0.05 * L + 2 * sqrt(0.05 * 0.95 * L); if (n > e && b != 0)
				printf "Note: %d lines outside is more than chance alone gives (about %.0f at most, for independent lines); they lie together, %.1f–%.1f cm, where the mean difference is %+.2f particles per period, %+.1f %% of LAMMPS'"'"'s Φ there. Lines are correlated (a bed with a stronger roll is stronger at every height), which the sign-flip p-values above account for; the difference is of the size of the per-line intervals and not significant over the profile with these beds, but it is systematic in sign: more beds would tell whether it is real.\n", n, e, lo, hi, d / n, 100 * d / b }' "$d/compare.tsv"
		quicknote "$A_BEDS beds of $A_DUR s"
		echo
		echo "![Φ(D), shakebox and LAMMPS]($FIG.png) ([PDF]($FIG.pdf))"
		echo
		echo "Per bed: free-surface height and Φ through the plane (mean over the lines at 0.4–0.6 of the surface height)."
		echo
		echo "| seed | surface (cm) | Φ plane shakebox | Φ plane LAMMPS | shakebox run, wall (s) | LAMMPS run, wall (s) |"
		echo "|---:|---:|---:|---:|---:|---:|"
		local sf
		for s in $SEEDS; do
			sf=$(surface "$d/shake_$s.tsv")
			echo "| $s | $(printf '%.2f' "$sf") | $(plane "$d/shake_$s.tsv" "$sf") | $(plane "$d/lmp_$s.tsv" "$sf") | $(awk '{ printf "%.0f", $1 }' "$d/shake_$s.sec") | $(awk '{ printf "%.0f", $1 }' "$d/lmp_$s.sec") |"
		done
		echo
		echo "Per line (D: mean height over the beds; Φ in particles per period; ± the 95 % half-width):"
		echo
		echo "| line | D (cm) | Φ shakebox | Φ LAMMPS | difference | t | agree |"
		echo "|---:|---:|---:|---:|---:|---:|:---:|"
		awk '!/^#/ { printf "| %d | %.2f | %.3f ± %.3f | %.3f ± %.3f | %+.3f ± %.3f | %.2f | %s |\n", $1, $2, $3, $4, $5, $6, $7, $8, $9, $10 ? "yes" : "**no**" }' "$d/compare.tsv"
	} >"$d/section.md"
	echo "validate_lammps: A: the profiles $verdict ($ndis of $nl lines outside; max |t| $maxt, p $pmax; chi2/L $chi2, p $pchi)" >&2
}

# ---------------------------------------------------------------- B. the onset
report_B() {
	local d=$WORK/B s f t sf wd yb fc wall_dev=0 nn ks kl so lo2 c
	: >"$d/phi.tsv"
	for s in $(seeds B); do
		for f in $B_FREQS; do
			t=${s}_$f
			"$DUMPFLUX" run "$d/shake_$t.h5" --skip "$B_SKIP" >"$d/shake_$t.tsv" || die "dumpflux run shake_$t.h5 failed"
			"$DUMPFLUX" dump "$d/lmp_$t.dump" --like "$d/shake_$t.h5" --amplitude $AMP --frequency "$f" \
				--dt "$DT" --skip "$B_SKIP" >"$d/lmp_$t.tsv" || die "dumpflux dump lmp_$t.dump failed"
			fc=$(frame_check "$d/lmp_$t.tsv" "$B_DUR" "$f")
			read -r wd yb <<<"$fc"
			wall_dev=$(awk -v a="$wall_dev" -v b="$wd" 'BEGIN { print (b > a ? b : a) }')
			sf=$(surface "$d/shake_$t.tsv")
			printf '%s\t%s\t%s\t%s\t%s\n' "$s" "$f" "$(plane6 "$d/shake_$t.tsv" "$sf")" "$(plane6 "$d/lmp_$t.tsv" "$sf")" "$sf" >>"$d/phi.tsv"
		done
		# the same bed at every frequency: the data files' atoms are identical (only the
		# walls' velocity at t = 0, the drive's, differs)
		local ref="" a
		for f in $B_FREQS; do
			a=$(awk '/^Atoms/ { on = 1 } /^Velocities/ { exit } on' "$d/bed_${s}_$f.data" | md5sum)
			[ -z "$ref" ] || [ "$a" = "$ref" ] || die "bed $s: the settled bed differs between frequencies"
			ref=$a
		done
	done
	# the grid and its spacing
	local grid dmin dmax n=$B_BEDS
	# shellcheck disable=SC2086 # the frequencies, one a word
	grid=$(printf '%s\n' $B_FREQS | sort -g | tr '\n' ' ')
	# shellcheck disable=SC2086
	read -r dmin dmax < <(printf '%s\n' $grid | awk 'NR > 1 { s = $1 - p; if (!n++ || s < lo) lo = s; if (s > hi) hi = s } { p = $1 } END { printf "%.4g %.4g\n", lo, hi }')
	local spacing="$dmin Hz"
	awk -v a="$dmin" -v b="$dmax" 'BEGIN { exit !(b - a > 1e-9) }' && spacing="$dmin–$dmax Hz (not uniform)"
	# per bed and code: the onset, censored when every or no frequency convects, and
	# whether the bed is monotone (no non-convecting frequency above a convecting one)
	awk -v thr=$B_THR -v h="$dmin" -F'\t' '
		{ s = $1; if (!(s in seen)) { seen[s] = 1; order[++ns] = s } f = $2 + 0
		  for (c = 0; c < 2; c++) { conv = $(3 + c) >= thr
		    if (conv) { if (!((s, c) in lo) || f < lo[s, c]) lo[s, c] = f }
		    else if (!((s, c) in hn) || f > hn[s, c]) hn[s, c] = f }
		  if (!(s in fmin) || f < fmin[s]) fmin[s] = f; if (!(s in fmax) || f > fmax[s]) fmax[s] = f }
		END { for (k = 1; k <= ns; k++) { s = order[k]; printf "%s", s
		  for (c = 0; c < 2; c++) {
		    if (!((s, c) in lo)) { o = fmax[s] + h / 2; cen = ">"; nm = 0 }
		    else if (!((s, c) in hn)) { o = fmin[s] - h / 2; cen = "<"; nm = 0 }
		    else { o = (hn[s, c] + lo[s, c]) / 2; cen = "="; nm = hn[s, c] > lo[s, c] }
		    printf "\t%.4f\t%s\t%d", o, cen, nm }
		  printf "\n" } }' "$d/phi.tsv" >"$d/onsets.tsv"
	awk -F'\t' '{ print $2, $5 }' "$d/onsets.tsv" >"$d/onsets.pairs"
	"$DUMPFLUX" stats paired "$d/onsets.pairs" >"$d/onsets.stats" || die "dumpflux stats paired (onsets) failed"
	local st=$d/onsets.stats
	local ms hs ml hl md hd pf ps det nms nml cs cl
	ms=$(key mean_a "$st") hs=$(key half_a "$st") ml=$(key mean_b "$st") hl=$(key half_b "$st")
	md=$(key mean_d "$st") hd=$(key half_d "$st") pf=$(key p_flip "$st") ps=$(key p_sign "$st") det=$(key detect80 "$st")
	nms=$(awk -F'\t' '$4 { n++ } END { print n + 0 }' "$d/onsets.tsv") nml=$(awk -F'\t' '$7 { n++ } END { print n + 0 }' "$d/onsets.tsv")
	cs=$(awk -F'\t' '$3 != "=" { n++ } END { print n + 0 }' "$d/onsets.tsv") cl=$(awk -F'\t' '$6 != "=" { n++ } END { print n + 0 }' "$d/onsets.tsv")
	# the interval of the paired difference, never narrower than the grid resolves: each
	# bed's onset is known to half a spacing
	local lo hi minp verdict
	read -r lo hi < <(awk -v m="$md" -v h="$hd" -v g="$dmin" 'BEGIN { if (h != h || h < g / 2) h = g / 2; printf "%+.3f %+.3f\n", m - h, m + h }')
	minp=$(awk -v n="$n" 'BEGIN { printf "%.3g", 2 / 2 ^ n }')
	# with beds enough for the exact test to reach 0.05 it decides, the interval only
	# flags what it cannot confirm; with fewer the interval decides alone
	verdict=$(awk -v p="$pf" -v lo="$lo" -v hi="$hi" -v m="$minp" 'BEGIN { out = lo > 0 || hi < 0
		if (m >= 0.05) print out ? "differ" : "agree"; else if (p < 0.05) print "differ"; else print out ? "undecided" : "agree" }')
	# per frequency: beds convecting in each code, discordant beds, McNemar
	: >"$d/freq.tsv"
	for f in $grid; do
		awk -v f="$f" -v thr=$B_THR -F'\t' '$2 + 0 == f + 0 { n++; a = $3 >= thr; b = $4 >= thr; ks += a; kl += b; if (a && !b) so++; if (b && !a) lo++ }
			END { printf "%s\t%d\t%d\t%d\t%d\t%d\n", f, n, ks, kl, so, lo }' "$d/phi.tsv" >>"$d/freq.tsv"
	done
	# the figure: fraction convecting against frequency, both codes
	local FIG=${FIGBASE}_onset
	while IFS=$'\t' read -r f nn ks kl so lo2; do
		printf '%s\t%s\t%s\n' "$f" "$("$DUMPFLUX" stats binom "$ks" "$nn" | cut -f3-5)" "$("$DUMPFLUX" stats binom "$kl" "$nn" | cut -f3-5)"
	done <"$d/freq.tsv" >"$d/frac.tsv"
	cat >"$d/plot.gp" <<GP
do for [fmt in "png pdf"] {
  if (fmt eq "png") { set terminal pngcairo size 900,560 font ",11"; set output "$OUT/$FIG.png" } \
  else { set terminal pdfcairo size 6.5in,4in font ",10"; set output "$OUT/$FIG.pdf" }
  set title "Onset of convection, no intruder: the same $n beds in each code, $B_DUR s per run (bars: Clopper–Pearson 95 %)"
  set grid
  set key bottom right
  set xlabel "f (Hz)"
  set ylabel "fraction of beds convecting (Φ ≥ $B_THR per period)"
  set yrange [-0.05:1.05]
  set offsets $dmin/2, $dmin/2, 0, 0
  set arrow 1 from $ms, graph 0 to $ms, graph 1 nohead dt 2 lc rgb "#1f77b4"
  set arrow 2 from $ml, graph 0 to $ml, graph 1 nohead dt 3 lc rgb "#d62728"
  plot "$d/frac.tsv" using (\$1-$dmin*0.06):2:3:4 with yerrorlines pt 7 ps 0.8 lc rgb "#1f77b4" title "shakebox (verlet, Δt = $DT s); dashed: mean onset", \
       "" using (\$1+$dmin*0.06):5:6:7 with yerrorlines pt 5 ps 0.8 lc rgb "#d62728" title "LAMMPS gran/hooke; dotted: mean onset"
}
GP
	gnuplot "$d/plot.gp" || die "gnuplot failed (part B)"
	if [ ! -s "$OUT/$FIG.png" ] || [ ! -s "$OUT/$FIG.pdf" ]; then die "the figure of part B was not written"; fi

	local word
	case $verdict in
	agree) word="the onsets **agree**" ;;
	differ) word="the onsets **differ**" ;;
	*) word="**undecided**" ;;
	esac
	if awk -v m="$minp" 'BEGIN { exit !(m >= 0.05) }'; then word="$word (by the interval alone: $n beds are too few for the exact test)"; fi
	printf '%s\t%s\t%s\n' "the onset of convection, no intruder: per bed the midpoint between the highest non-convecting and the lowest convecting frequency" \
		"$n beds × $(echo "$grid" | wc -w) frequencies × $B_DUR s; onset LAMMPS − shakebox = $(printf '%+.3f' "$md") [$lo, $hi] Hz (grid $spacing), exact paired p = $(fmtp "$pf")" "$word" >"$d/summary"
	{
		echo "## B. The onset of convection"
		echo
		part_header B
		part_times B
		echo
		echo "**Setup.** $n settled beds without intruder (seeds $(seeds B | awk "NR == 1")…$(seeds B | awk "END { print }")), each shaken at every frequency of the grid"
		echo "$(echo "$grid" | sed 's/ *$//; s/ /, /g') Hz (spacing $spacing; A = $AMP cm) for $B_DUR s in both codes, from the same data file"
		echo "(the beds' atoms are checked identical at every frequency; only the walls' velocity at t = 0, the drive's, differs)."
		echo "shakebox runs with the LAMMPS deck's integrator and step (\`integrator = verlet\`, Δt = $DT s), so that a"
		echo "difference is the code's, not the integrator's. Φ per run is the flux through the band 0.4–0.6 of the"
		echo "settled surface height (the mean over the lines there, as \`bin/onset\`'s plane), averaged over the periods"
		echo "after the first $(awk -v s="$B_SKIP" 'BEGIN { print s * 100 }') % of them ($(awk -v s="$B_SKIP" -v d="$B_DUR" 'BEGIN { printf "%g of %g s", s * d, d }') skipped, as the study's flux stop rule skips its transient); LAMMPS's"
		echo "from its stroboscopic dump by the engine's crossing code, on the engine's lines (walls moved as the drive"
		echo "to $(awk -v y="$wall_dev" 'BEGIN { printf "%.1g", y }') cm). A run **convects** when Φ ≥ $B_THR particles per period (the study's threshold). Per bed and"
		echo "code the **onset** is the midpoint between the highest non-convecting and the lowest convecting frequency;"
		echo "when every frequency convects it is set half a spacing below the grid (<), when none does half a"
		echo "spacing above (>) — censored, counted below. A bed is *non-monotone* when some non-convecting"
		echo "frequency lies above a convecting one (its onset is still that midpoint)."
		echo
		echo "**Statistics.** Fractions: Clopper–Pearson 95 % intervals; per frequency the beds where the codes"
		echo "disagree and McNemar's exact test. Onsets: each code's mean over the beds with its Student-t"
		echo "interval; the paired difference LAMMPS − shakebox per bed, its mean with the t interval widened to at"
		echo "least ± half the grid spacing (each bed's onset is known only to that), the sign test and the exact"
		echo "sign-flip test of the mean difference (all 2^$n sign patterns; with $n beds its smallest possible"
		echo "p is $minp). *differ* = exact p < 0.05; *agree* = p ≥ 0.05 and the interval holds 0; *undecided* ="
		echo "p ≥ 0.05 but the interval misses 0. When the beds are too few for the exact test to reach 0.05 at all"
		echo "(5 or fewer), the interval decides alone: *differ* when it misses 0, else *agree*."
		echo
		echo "**Result:** $word — onset LAMMPS − shakebox = $(printf '%+.3f' "$md") Hz, interval [$lo, $hi] Hz (grid spacing $spacing;"
		echo "t half-width $(printf '%.3f' "$hd") Hz), sign test p = $(fmtp "$ps"), exact paired p = $(fmtp "$pf") over $n beds."
		echo "Mean onset: shakebox $(printf '%.3f' "$ms") ± $(printf '%.3f' "$hs") Hz, LAMMPS $(printf '%.3f' "$ml") ± $(printf '%.3f' "$hl") Hz; non-monotone beds: shakebox $nms, LAMMPS $nml of $n;"
		echo "censored onsets: shakebox $cs, LAMMPS $cl. Power: at this spread of the differences a paired t-test at 5 %"
		echo "detects a mean difference of $(awk -v x="$det" 'BEGIN { if (x != x || x == 0) printf "(no spread: not estimable)"; else printf "%.3f Hz", x }') with 80 % power$(awk -v p="$minp" 'BEGIN { if (p >= 0.05) printf "; no exact paired test over these beds can reach p < 0.05" }')."
		quicknote "$n beds of $B_DUR s at $(echo "$grid" | wc -w) frequencies"
		echo
		echo "![fraction of beds convecting against frequency, shakebox and LAMMPS]($FIG.png) ([PDF]($FIG.pdf))"
		echo
		echo "Per frequency (fraction of beds convecting, Clopper–Pearson 95 %; discordant beds: convecting in one code only):"
		echo
		echo "| f (Hz) | shakebox | LAMMPS | shakebox only | LAMMPS only | McNemar p |"
		echo "|---:|---:|---:|---:|---:|---:|"
		while IFS=$'\t' read -r f nn ks kl so lo2; do
			echo "| $f | $(cpint "$ks" "$nn") | $(cpint "$kl" "$nn") | $so | $lo2 | $(fmtp "$("$DUMPFLUX" stats sign "$((so < lo2 ? so : lo2))" "$((so + lo2))")") |"
		done <"$d/freq.tsv"
		echo
		echo "Per bed: Φ through the plane (particles per period; **bold**: convecting) and the onset (Hz; <, >: censored; *: non-monotone):"
		echo
		printf '| seed | code |'
		for f in $grid; do printf ' %s Hz |' "$f"; done
		printf ' onset |\n|---:|:---|'
		for f in $grid; do printf -- '---:|'; done
		printf -- '---:|\n'
		for s in $(seeds B); do
			for c in 0 1; do
				printf '| %s | %s |' "$s" "$([ $c = 0 ] && echo shakebox || echo LAMMPS)"
				for f in $grid; do
					awk -v s="$s" -v f="$f" -v c=$c -v thr=$B_THR -F'\t' '$1 == s && $2 + 0 == f + 0 { v = $(3 + c); printf (v >= thr ? " **%.2f** |" : " %.2f |"), v }' "$d/phi.tsv"
				done
				awk -v s="$s" -v c=$c -F'\t' '$1 == s { o = $(2 + 3 * c); k = $(3 + 3 * c); m = $(4 + 3 * c)
					printf " %s%.3f%s |\n", k == "=" ? "" : k, o, m ? "*" : "" }' "$d/onsets.tsv"
			done
		done
	} >"$d/section.md"
	echo "validate_lammps: B: $verdict (onset LAMMPS - shakebox $md [$lo, $hi] Hz, exact p $pf)" >&2
}

# ---------------------------------------------------------------- C and D: the rise
# one line per bed: "tag risen_shake wait_shake risen_lmp wait_lmp" from the engine's run
# file and LAMMPS's rise line, with their checks
rise_table() { # PART DURATION TAGS...
	local part=$1 dur=$2 d=$WORK/$1 t
	shift 2
	local steps
	steps=$(steps_of "$dur")
	for t in "$@"; do
		local f=$d/shake_$t.h5 st rs ws y0s y0 line
		st=$(h5attr "$f" status)
		[ "$st" = ok ] || die "$part: shake_$t.h5: status '$st'"
		rs=$(h5attr "$f" risen) ws=$(h5attr "$f" waiting_time) y0s=$(h5attr "$f" intruder_settled_y)
		y0=$(awk '/^Atoms/ { on = 1; next } /^Velocities/ { exit } on && NF >= 6 && $2 == 2 { print $6; exit }' "$d/bed_$t.data")
		awk -v a="$y0s" -v b="$y0" 'BEGIN { exit !(a - b < 1e-12 && b - a < 1e-12) }' ||
			die "$part: bed $t: the engine's settled intruder height $y0s is not the data file's $y0"
		line=$(cat "$d/lmp_$t.rise" 2>/dev/null) || die "$part: no LAMMPS result for bed $t (lmp_$t.rise)"
		awk -v steps="$steps" -v dt="$DT" -v t="$t" '{ s = $3; hb = $5; h = $7; w = $9 }
			END { if (w < 0) w = -w
			  if (w > 1e-9) { print "walls off the drive by " w " cm"; exit 1 }
			  if (hb > h && s > steps) { print "rose after the end"; exit 1 }
			  if (!(hb > h) && s != steps) { print "stopped at step " s " without a rise"; exit 1 } }' <<<"$line" >"$d/check_$t" ||
			die "$part: bed $t: LAMMPS: $(cat "$d/check_$t")"
		awk -v t="$t" -v rs="$rs" -v ws="$ws" -v dt="$DT" '{ r = $5 > $7; printf "%s\t%d\t%.6f\t%d\t%.6f\n", t, rs, ws, r, $3 * dt }' <<<"$line"
	done
}

# C: the engine's presets on the same beds (paper: gear5 at the paper's step; fast:
# verlet at 4 times it) beside the verlet run at LAMMPS's step: per bed "depth tag
# risen_paper risen_fast risen_verlet", or nothing when a preset's runs are missing
preset_table() {
	local d=$WORK/C dep t f k r
	for dep in 0 1; do
		for t in $(seeds C "$dep" | sed "s/^/d${dep}_/"); do
			local line="$dep $t"
			for k in paper fast shake; do
				f=$d/${k}_$t.h5
				[ -e "$d/${k}_$t.ok" ] || return 1
				[ "$(h5attr "$f" status)" = ok ] || die "C: ${k}_$t.h5: status '$(h5attr "$f" status)'"
				r=$(h5attr "$f" risen)
				line="$line $r"
			done
			echo "$line"
		done
	done
}

# The presets at the onset (issue of the fast preset near the onset): per depth, the
# fraction risen with paper and with fast, paired bed by bed (McNemar), the smallest
# difference the test detects with 80 % power; the depth effect (claim 5) with each;
# paper against verlet at LAMMPS's step (the integrator and step alone). Appends a
# subsection to section.md and writes presets.summary (one line, for REPRODUCTION.md).
presets_C() {
	local d=$WORK/C n=$C_BEDS
	if ! preset_table >"$d/presets.tsv"; then
		rm -f "$d/presets.tsv" "$d/presets.summary"
		{ echo; echo "### The engine's presets on these beds"; echo
		  echo "Not run: the \`paper\` and \`fast\` runs of some beds are missing (they run with part C)."; } >>"$d/section.md"
		return 0
	fi
	# counts k[preset][depth]; discordant pairs (a, b) per depth: a risen only in the
	# first, b only in the second
	cnt() { awk -v dep="$1" -v c="$2" '$1 == dep { k += $c } END { print k + 0 }' "$d/presets.tsv"; }
	disc2() { awk -v dep="$1" -v x="$2" -v y="$3" '(dep == "all" || $1 == dep) { if ($x && !$y) a++; if ($y && !$x) b++ } END { print a + 0, b + 0 }' "$d/presets.tsv"; }
	local kp0 kp1 kf0 kf1 kv0 kv1
	kp0=$(cnt 0 3) kp1=$(cnt 1 3) kf0=$(cnt 0 4) kf1=$(cnt 1 4) kv0=$(cnt 0 5) kv1=$(cnt 1 5)
	local a0 b0 a1 b1 aa ba av0 bv0 av1 bv1 m0 m1 ma mv0 mv1 pw0 pw1 pwa fp ff fv
	read -r a0 b0 < <(disc2 0 3 4)
	read -r a1 b1 < <(disc2 1 3 4)
	read -r aa ba < <(disc2 all 3 4)
	read -r av0 bv0 < <(disc2 0 3 5)
	read -r av1 bv1 < <(disc2 1 3 5)
	mc() { "$DUMPFLUX" stats sign "$(($1 < $2 ? $1 : $2))" "$(($1 + $2))"; }
	m0=$(mc "$a0" "$b0") m1=$(mc "$a1" "$b1") ma=$(mc "$aa" "$ba") mv0=$(mc "$av0" "$bv0") mv1=$(mc "$av1" "$bv1")
	pw0=$(pwr "$n" "$(awk -v k="$kp0" -v n="$n" 'BEGIN { print k / n }')")
	pw1=$(pwr "$n" "$(awk -v k="$kp1" -v n="$n" 'BEGIN { print k / n }')")
	pwa=$(pwr "$((2 * n))" "$(awk -v k="$((kp0 + kp1))" -v n="$((2 * n))" 'BEGIN { print k / n }')")
	fp=$("$DUMPFLUX" stats fisher "$kp0" "$n" "$kp1" "$n") ff=$("$DUMPFLUX" stats fisher "$kf0" "$n" "$kf1" "$n")
	fv=$("$DUMPFLUX" stats fisher "$kv0" "$n" "$kv1" "$n")
	# the verdict: differ (a test at 5 %); indistinguishable only where the pooled test
	# could have seen a difference (its detectable difference exists), else undecided
	local word raw
	raw=$("$DUMPFLUX" stats power "$((2 * n))" "$(awk -v k="$((kp0 + kp1))" -v n="$((2 * n))" 'BEGIN { print k / n }')")
	word=$(awk -v a="$m0" -v b="$m1" -v c="$ma" -v r="$raw" 'BEGIN { split(r, w, " ")
		if (a < 0.05 || b < 0.05 || c < 0.05) print "differ"
		else if (w[1] == "nan" && w[2] == "nan") print "undecided (too few beds to detect any difference)"
		else print "indistinguishable (within the detectable difference)" }')
	printf '%s
' "fast against paper on the same $n beds per depth at $C_FREQ Hz (risen within $C_DUR s, 𝓡 = $C_R): depth 0 $kf0/$n against $kp0/$n, depth 1 $kf1/$n against $kp1/$n; McNemar p = $(fmtp "$m0") / $(fmtp "$m1"), pooled $(fmtp "$ma"); 80 % power only for differences of $pw0 / $pw1 (pooled $pwa): **$word**" >"$d/presets.summary"
	{
		echo
		echo "### The engine's presets on these beds: is the fast preset good enough at the onset?"
		echo
		echo "The same $n beds per depth shaken by shakebox three ways, each until the rise or for $C_DUR s: \`preset = paper\`"
		echo "(gear5, Δt = 5·10⁻⁵ s: the paper's integrator), \`preset = fast\` (verlet, Δt = 2·10⁻⁴ s: what the claims' campaigns"
		echo "run) and verlet at LAMMPS's step (Δt = $DT s, the runs above). 2.7 Hz is just above this model's onset, where"
		echo "a small change of the dynamics moves the answer most. Paired bed by bed: McNemar's exact test on the beds"
		echo "risen with one only; the power as above (from paper's fraction)."
		echo
		echo "**Result:** fast and paper are **$word** here — McNemar p = $(fmtp "$m0") at depth 0 ($a0 beds risen with paper only,"
		echo "$b0 with fast only), $(fmtp "$m1") at depth 1 ($a1, $b1), pooled $(fmtp "$ma"). With $n beds per depth the test detects with 80 % power"
		echo "a difference of fast's fraction from paper's of at least $pw0 at depth 0, $pw1 at depth 1 (pooled over the $((2 * n)) beds: $pwa)."
		echo "The depth effect (claim 5, Fisher's test of depth 1 against depth 0): paper p = $(fmtp "$fp"), fast p = $(fmtp "$ff"),"
		echo "verlet at LAMMPS's step p = $(fmtp "$fv"). Paper against verlet at LAMMPS's step (the integrator alone): McNemar"
		echo "p = $(fmtp "$mv0") at depth 0 ($av0, $bv0), $(fmtp "$mv1") at depth 1 ($av1, $bv1)."
		quicknote "$n beds per depth of $C_DUR s"
		echo
		echo "| depth | paper risen | fast risen | verlet Δt = $DT s risen | paper only / fast only | McNemar p (paper, fast) |"
		echo "|---:|---:|---:|---:|---:|---:|"
		echo "| 0 | $(cpint "$kp0" "$n") | $(cpint "$kf0" "$n") | $(cpint "$kv0" "$n") | $a0 / $b0 | $(fmtp "$m0") |"
		echo "| 1 | $(cpint "$kp1" "$n") | $(cpint "$kf1" "$n") | $(cpint "$kv1" "$n") | $a1 / $b1 | $(fmtp "$m1") |"
		echo "| Fisher p, 1 vs 0 | $(fmtp "$fp") | $(fmtp "$ff") | $(fmtp "$fv") | | |"
		echo
		echo "Run time of these runs: paper $(sumsec "$d" paper) s of wall time ($(sumcpu "$d" paper) s CPU), fast $(sumsec "$d" fast) s ($(sumcpu "$d" fast) s CPU)."
	} >>"$d/section.md"
	echo "validate_lammps: C presets: fast $word from paper (McNemar p $m0 at depth 0, $m1 at depth 1)" >&2
	# the evidence claim 5's preset rests on (scripts/preset_evidence.sh): the fractions
	# may agree while the claim's answer, the depth effect, does not
	local ev
	ev=$(awk -v w="$word" -v a="$fp" -v b="$ff" 'BEGIN { if (w == "differ") print "differ"
		else if ((a < 0.05) != (b < 0.05)) print "answer_differs"; else print "indistinguishable" }')
	[ "$QUICK" = 1 ] || bash "$REPO/scripts/preset_evidence.sh" set val-C-presets "$ev" \
		"make validate-lammps, part C, runs of $(stamp C 1 | cut -c1-10) at $(stamp C 2 | cut -c1-7)" \
		"claim 5 at $C_FREQ Hz on the same $n beds per depth: risen with fast $kf0/$n and $kf1/$n against paper's $kp0/$n and $kp1/$n at depth 0 and 1 (McNemar p = $(fmtp "$m0"), $(fmtp "$m1"); detectable with 80 % power $pw0, $pw1); the depth effect: Fisher p = $(fmtp "$fp") with paper, $(fmtp "$ff") with fast" ||
		die "C: cannot write docs/preset_evidence.tsv"
}

report_C() {
	local d=$WORK/C dep n=$C_BEDS
	# LAMMPS's runs come last in a validation spread over sessions (VALIDATE_CHEAP_FIRST):
	# until every one is there, the part says how far it got and reports the engine's
	# presets alone
	local nl
	nl=$(find "$d" -maxdepth 1 -name 'lmp_d*.ok' | wc -l)
	if [ "$nl" -lt $((2 * n)) ]; then
		printf '%s\t%s\t%s\n' "claim 5: 𝓡 = $C_R at depth 0 and 1, $C_FREQ Hz: risen within $C_DUR s (depth 0 is one row lower)" \
			"$n beds per depth; LAMMPS: $nl of $((2 * n)) runs so far" "**in progress**: the codes not yet compared" >"$d/summary"
		{
			echo "## C. Claim 5: one row lower, close to the onset"
			echo
			part_header C
			echo
			echo "**In progress:** $nl of LAMMPS's $((2 * n)) runs are finished (a validation spread over sessions: \`VALIDATE_CHEAP_FIRST=1\`"
			echo "runs the engine's runs first and resumes where it stopped); the codes are compared when all are."
		} >"$d/section.md"
		echo "validate_lammps: C: in progress ($nl of $((2 * n)) LAMMPS runs)" >&2
		presets_C
		return 0
	fi
	: >"$d/rise.tsv"
	for dep in 0 1; do
		# shellcheck disable=SC2046
		rise_table C "$C_DUR" $(seeds C $dep | sed "s/^/d${dep}_/") | sed "s/^/$dep\t/" >>"$d/rise.tsv"
	done
	# counts: k[code][depth]
	local k00 k01 k10 k11
	k00=$(awk -F'\t' '$1 == 0 { k += $3 } END { print k + 0 }' "$d/rise.tsv") k01=$(awk -F'\t' '$1 == 1 { k += $3 } END { print k + 0 }' "$d/rise.tsv")
	k10=$(awk -F'\t' '$1 == 0 { k += $5 } END { print k + 0 }' "$d/rise.tsv") k11=$(awk -F'\t' '$1 == 1 { k += $5 } END { print k + 0 }' "$d/rise.tsv")
	local fs fl
	fs=$("$DUMPFLUX" stats fisher "$k00" "$n" "$k01" "$n") fl=$("$DUMPFLUX" stats fisher "$k10" "$n" "$k11" "$n")
	# per depth: discordant beds and McNemar; pooled over the depths too
	disc() { awk -F'\t' -v dep="$1" '(dep == "all" || $1 == dep) { if ($3 && !$5) b++; if ($5 && !$3) c++; n++ } END { printf "%d %d %d\n", b, c, n }' "$d/rise.tsv"; }
	local b0 c0 b1 c1 ba ca na m0 m1 ma pw0 pw1 pwa
	read -r b0 c0 _ < <(disc 0)
	read -r b1 c1 _ < <(disc 1)
	read -r ba ca na < <(disc all)
	m0=$("$DUMPFLUX" stats sign "$((b0 < c0 ? b0 : c0))" "$((b0 + c0))") m1=$("$DUMPFLUX" stats sign "$((b1 < c1 ? b1 : c1))" "$((b1 + c1))")
	ma=$("$DUMPFLUX" stats sign "$((ba < ca ? ba : ca))" "$((ba + ca))")
	# the power: from shakebox's fraction at each depth (pooled: over both), the smallest
	# difference of LAMMPS's fraction McNemar's test detects with 80 % power
	pw0=$(pwr "$n" "$(awk -v k="$k00" -v n="$n" 'BEGIN { print k / n }')")
	pw1=$(pwr "$n" "$(awk -v k="$k01" -v n="$n" 'BEGIN { print k / n }')")
	pwa=$(pwr "$na" "$(awk -v k="$((k00 + k01))" -v n="$na" 'BEGIN { print k / n }')")
	local verdict dirs dirl word
	verdict=$(awk -v a="$m0" -v b="$m1" 'BEGIN { print (a < 0.05 || b < 0.05) ? "differ" : "agree" }')
	# the claim, read in each code: depth 0 (one row lower than depth 1) rises less
	claimread() { # K0 K1 P
		awk -v a="$1" -v b="$2" -v p="$3" -v n="$n" 'BEGIN {
			s = a < b ? "depth 0 rises less than depth 1 (the claim'"'"'s direction)" : a > b ? "depth 0 rises more than depth 1 (the opposite of the claim)" : "both depths rise alike"
			printf "%s, %d/%d against %d/%d, Fisher p = %s%s", s, a, n, b, n, (p < 0.001 ? sprintf("%.1e", p) : sprintf("%.3g", p)), p < 0.05 ? " (significant)" : " (not significant)" }'
	}
	dirs=$(claimread "$k00" "$k01" "$fs") dirl=$(claimread "$k10" "$k11" "$fl")
	# the one sentence across the codes (tc_verdict_text): each code's Fisher p of the
	# depths, the smaller McNemar p of the two depths
	local across
	across=$("$DUMPFLUX" stats verdict "$fs" "$fl" "$(awk -v a="$m0" -v b="$m1" 'BEGIN { print a < b ? a : b }')" "the depth effect")
	case $across in
	"The codes differ"*) word="the codes **differ**" ;;
	"The codes agree"*"each shows"*) word="the codes **agree**, and each shows the depth effect" ;;
	"The codes agree"*) word="the codes **agree**, and neither can decide" ;;
	*) word="**undecided**: the codes are not told apart, but one alone shows the depth effect" ;;
	esac
	printf '%s\t%s\t%s\n' "claim 5: 𝓡 = $C_R at depth 0 and 1, $C_FREQ Hz: risen within $C_DUR s (depth 0 is one row lower)" \
		"$n beds per depth; risen at depth 0 / 1: shakebox $k00/$k01, LAMMPS $k10/$k11 of $n; codes paired, McNemar p = $(fmtp "$m0") / $(fmtp "$m1"); 80 % power only for differences of $pw0 / $pw1" "$word" >"$d/summary"
	{
		echo "## C. Claim 5: one row lower, close to the onset"
		echo
		part_header C
		part_times C
		echo
		echo "**Setup.** The intruder 𝓡 = $C_R (\`radius_ratio = $C_R\`) at depth 0 and at depth 1 (\`depth\`: full rows of grains"
		echo "beneath it, docs/model.md \"Preparation\"; the paper's \"one row lower\" than depth 1 is depth 0), $n settled"
		echo "beds per depth (seeds $(seeds C 0 | awk "NR == 1")…$(seeds C 0 | awk "END { print }") at depth 0, $(seeds C 1 | awk "NR == 1")…$(seeds C 1 | awk "END { print }") at depth 1: independent beds), each shaken at"
		echo "$C_FREQ Hz (A = $AMP cm) for up to $C_DUR s in both codes from the same data file, shakebox with the deck's"
		echo "integrator and step (\`integrator = verlet\`, Δt = $DT s). **Risen** is the engine's rule (docs/model.md,"
		echo "\"Waiting time\"): the intruder's centre more than one intruder diameter above its settled height, in the"
		echo "box frame, checked on every step. shakebox: its own \`risen\` (\`stop = risen\`, \`stop_after = 0\`). LAMMPS:"
		echo "\`tests/bench/lammps/validate_rise.in\` evaluates the same rule at the end of every step (positions x(nΔt),"
		echo "walls at A sin(2πfnΔt)) with \`fix halt\`, which ends the run at the rise; the intruder is the data"
		echo "file's one atom of type 2, its settled height the file's (the engine's \`intruder_settled_y\`, checked"
		echo "equal), the walls checked to follow the drive."
		echo
		echo "**Statistics.** Fractions: Clopper–Pearson 95 % intervals. Per code, depth 1 against depth 0: Fisher's"
		echo "exact test (two-sided). Per depth, the codes paired bed by bed: McNemar's exact test on the discordant"
		echo "beds (risen in one code only) and the number of beds where they agree. *agree* = McNemar p ≥ 0.05 at"
		echo "both depths. Power: outcomes taken independent between the codes given the bed (a shared bed that makes"
		echo "them agree more only adds power), exactly over the discordant counts (\`bin/dumpflux stats power\`)."
		echo
		echo "Across the codes: $across"
		echo
		echo "**Result:** $word — McNemar p = $(fmtp "$m0") at depth 0 ($b0 beds risen in shakebox only, $c0 in LAMMPS only;"
		echo "agree on $((n - b0 - c0)) of $n), p = $(fmtp "$m1") at depth 1 ($b1, $c1; agree on $((n - b1 - c1)) of $n); pooled over both depths"
		echo "p = $(fmtp "$ma") (agree on $((na - ba - ca)) of $na)."
		echo "shakebox: $dirs. LAMMPS: $dirl."
		echo "Power: with $n beds per depth McNemar's test at 5 % detects with 80 % power a difference of LAMMPS's"
		echo "fraction risen from shakebox's of at least $pw0 at depth 0, $pw1 at depth 1 (none: not even"
		echo "the largest difference possible that way); pooled over the $na beds, $pwa.$(awk -v n="$n" 'BEGIN { if (2 / 2 ^ n >= 0.05) printf " With %d beds per depth McNemar'"'"'s test cannot reach p < 0.05 at one depth at all.", n }')"
		quicknote "$n beds per depth of $C_DUR s"
		echo
		echo "| depth | shakebox risen | LAMMPS risen | shakebox only | LAMMPS only | agree | McNemar p |"
		echo "|---:|---:|---:|---:|---:|---:|---:|"
		echo "| 0 | $(cpint "$k00" "$n") | $(cpint "$k10" "$n") | $b0 | $c0 | $((n - b0 - c0))/$n | $(fmtp "$m0") |"
		echo "| 1 | $(cpint "$k01" "$n") | $(cpint "$k11" "$n") | $b1 | $c1 | $((n - b1 - c1))/$n | $(fmtp "$m1") |"
		echo "| Fisher p, 1 vs 0 | $(fmtp "$fs") | $(fmtp "$fl") | | | | |"
		echo
		echo "Per bed (waiting time in s; censored runs: — at the run's end):"
		echo
		echo "| depth | seed | shakebox | LAMMPS |"
		echo "|---:|---:|---:|---:|"
		awk -F'\t' -v D="$C_DUR" '{ seed = $2; sub(/^d[0-9]+_/, "", seed)
			printf "| %s | %s | %s | %s |\n", $1, seed, $3 ? sprintf("%.2f", $4) : "— (" D ")", $5 ? sprintf("%.2f", $6) : "— (" D ")" }' "$d/rise.tsv"
	} >"$d/section.md"
	echo "validate_lammps: C: $verdict (McNemar p $m0 at depth 0, $m1 at depth 1; Fisher p shakebox $fs, LAMMPS $fl)" >&2
	presets_C
}

# report_rise PART: claim 4's waiting times in both codes, part D (the deck's law) or E
# (the same beds with shear history on in both codes)
report_rise() {
	local P=$1 d=$WORK/$1 n=$D_BEDS hist="" title="Claim 4: 𝓡 = $C_R rises at once"
	[ "$P" != E ] || { hist=" with shear history"; title="Claim 4 with shear history on in both codes"; }
	# shellcheck disable=SC2046
	rise_table "$P" "$D_DUR" $(seeds "$P") >"$d/rise.tsv"
	awk -F'\t' '{ print $3, $5 }' "$d/rise.tsv" >"$d/wait.pairs"
	"$DUMPFLUX" stats paired "$d/wait.pairs" >"$d/wait.stats" || die "dumpflux stats paired (waiting times) failed"
	local st=$d/wait.stats
	local meds medl medd ps pw pos neg ks kl b c m5 cens_s cens_l rs rl
	meds=$(key median_a "$st") medl=$(key median_b "$st") medd=$(key median_d "$st")
	ps=$(key p_sign "$st") pw=$(key p_wilcoxon "$st") pos=$(key pos "$st") neg=$(key neg "$st")
	rs=$(awk -F'\t' '{ k += $2 } END { print k + 0 }' "$d/rise.tsv") rl=$(awk -F'\t' '{ k += $4 } END { print k + 0 }' "$d/rise.tsv")
	cens_s=$((n - rs)) cens_l=$((n - rl))
	ks=$(awk -F'\t' -v f=$D_FAST '$2 && $3 <= f { k++ } END { print k + 0 }' "$d/rise.tsv")
	kl=$(awk -F'\t' -v f=$D_FAST '$4 && $5 <= f { k++ } END { print k + 0 }' "$d/rise.tsv")
	read -r b c < <(awk -F'\t' -v f=$D_FAST '{ a = $2 && $3 <= f; l = $4 && $5 <= f; if (a && !l) b++; if (l && !a) c++ } END { print b + 0, c + 0 }' "$d/rise.tsv")
	m5=$("$DUMPFLUX" stats sign "$((b < c ? b : c))" "$((b + c))")
	# a median that falls on a censored run is only a lower bound
	med() { # VALUE CENSORED
		awk -v m="$1" -v c="$2" -v n="$n" -v D="$D_DUR" 'BEGIN { if (2 * c >= n && m >= D - 1e-9) printf "> %g s", D; else printf "%.2f s", m }'
	}
	local verdict word
	verdict=$(awk -v a="$ps" -v b="$pw" -v c="$m5" 'BEGIN { print (a < 0.05 || b < 0.05 || c < 0.05) ? "differ" : "agree" }')
	[ "$verdict" = agree ] && word="the codes **agree**" || word="the codes **differ**"
	printf '%s\t%s\t%s\n' "claim 4$hist: 𝓡 = $C_R at $D_FREQ Hz (depth $D_DEPTH) \"rises at once\": the waiting time per bed" \
		"$n beds × up to $D_DUR s; median shakebox $(med "$meds" "$cens_s"), LAMMPS $(med "$medl" "$cens_l"); within $D_FAST s: $ks and $kl of $n; paired: sign test p = $(fmtp "$ps"), Wilcoxon p = $(fmtp "$pw")" "$word" >"$d/summary"
	{
		echo "## $P. $title"
		echo
		part_header "$P"
		part_times "$P"
		echo
		echo "**Setup.** The claim-4 campaign's setting (\`$D_CAMPAIGN\` on its scene \`$D_SCENE\`): 𝓡 = $C_R at $D_FREQ Hz,"
		echo "depth $D_DEPTH, A = $AMP cm; $n settled beds (seeds $(seeds "$P" | awk "NR == 1")…$(seeds "$P" | awk "END { print }")), each shaken in both codes from the same data"
		echo "file until the intruder rises or for $D_DUR s, shakebox with the deck's integrator and step (\`integrator ="
		echo "verlet\`, Δt = $DT s; the campaign runs the fast preset). The waiting time by the engine's rule in both codes,"
		echo "as in part C (shakebox's \`waiting_time\`; LAMMPS: \`validate_rise.in\`, the step at which \`fix halt\` ended"
		echo "the run × Δt). A run without a rise is censored at $D_DUR s."
		[ "$P" != E ] || { echo; echo "**Shear history.** Part D's beds and settings with Cundall–Strack's shear spring on in both codes: shakebox"
			echo "\`tangential = spring\` (docs/model.md, \"Tangential law\"), LAMMPS \`pair_style gran/hooke/history\` (\`rise_history.in\`: the"
			echo "deck with its \`history\` variable yes: Kt = NULL), both with k_t = 2/7 of the normal stiffness, the same γ_S and μ."; }
		echo
		echo "**Statistics.** Medians per code (a median on a censored run is only a lower bound); the paired"
		echo "difference LAMMPS − shakebox per bed: the sign test (valid with censoring: a censored run's difference"
		echo "has a known sign; two censored runs tie) and the exact Wilcoxon signed-rank test (censored waits taken"
		echo "as $D_DUR s); the fraction of beds rising within $D_FAST s per code (Clopper–Pearson 95 %) and McNemar's exact"
		echo "test of it. *agree* = all three p ≥ 0.05."
		echo
		echo "**Result:** $word — median waiting time shakebox $(med "$meds" "$cens_s"), LAMMPS $(med "$medl" "$cens_l") (median"
		echo "difference $(printf '%+.2f' "$medd") s; LAMMPS later in $pos beds, earlier in $neg); sign test p = $(fmtp "$ps"), Wilcoxon"
		echo "p = $(fmtp "$pw"). Risen within $D_FAST s: shakebox $(cpint "$ks" "$n"), LAMMPS $(cpint "$kl" "$n") (McNemar p = $(fmtp "$m5"))."
		echo "Censored (not risen within $D_DUR s): shakebox $cens_s, LAMMPS $cens_l of $n."
		echo "Power: at this spread of the differences a paired t-test at 5 % detects a mean difference of $(awk -v x="$(key detect80 "$st")" 'BEGIN { if (x != x || x == 0) printf "(no spread: not estimable)"; else printf "%.1f s", x }')"
		echo "with 80 % power; McNemar's test of the fraction within $D_FAST s detects $(pwr "$n" "$(awk -v k="$ks" -v n="$n" 'BEGIN { print k / n }')") from shakebox's fraction."
		quicknote "$n beds of $D_DUR s"
		echo
		echo "| seed | shakebox (s) | LAMMPS (s) | LAMMPS − shakebox (s) |"
		echo "|---:|---:|---:|---:|"
		# a censored wait is a lower bound, and so is (or bounds) the difference
		awk -F'\t' -v D="$D_DUR" '{ d = sprintf("%+.2f", $5 - $3); if (!$2 && !$4) d = "— (both censored)"; else if (!$2) d = "≤ " d; else if (!$4) d = "≥ " d
			printf "| %s | %s | %s | %s |\n", $1, $2 ? sprintf("%.2f", $3) : "> " D, $4 ? sprintf("%.2f", $5) : "> " D, d }' "$d/rise.tsv"
	} >"$d/section.md"
	echo "validate_lammps: $P: $verdict (medians $meds / $medl s; sign p $ps, Wilcoxon p $pw; within $D_FAST s $ks / $kl of $n)" >&2
}

report_D() { report_rise D; }
report_E() { report_rise E; }

for p in $PARTS; do
	"report_$p"
done
T3=$(date +%s)

# ---------------------------------------------------------------- the fragment
FRAG=$OUT/$FIGBASE.md
read -r PREP_S RUNS_S <"$WORK/times" || true
# A part whose runs are not in this run directory (another machine ran it, or a session
# whose run directory is gone) keeps its row and section from the fragment as it was:
# a run of part C alone must not drop A, B, D and E from the document.
OLDFRAG=$WORK/fragment.before
if [ -s "$FRAG" ]; then cp "$FRAG" "$OLDFRAG"; else : >"$OLDFRAG"; fi
old_row() { awk -F' [|] ' -v p="$1" '$1 == "| " p && $3 !~ /^not run/ { print; exit }' "$OLDFRAG"; }
old_section() {
	awk -v h="## $1." 'index($0, h) == 1 { on = 1; print; next } on && (/^## / || /^<!-- /) { exit } on' "$OLDFRAG" |
		sed -e :a -e '/^\n*$/{$d;N;ba' -e '}'
}
{
	echo "<!-- generated by tests/bench/validate_lammps.sh ($cmd); do not edit -->"
	echo "# Validation against LAMMPS: the same beds in two codes"
	echo
	echo "Generated $(date -u '+%Y-%m-%d %H:%M UTC') at commit $COMMIT by \`$cmd\`"
	if [ "$REPORT" = 1 ]; then
		echo "from the runs already recorded (VALIDATE_REPORT=1; analysis $((T3 - T2)) s)."
	else
		echo "(parts $PARTS run now: preparation ${PREP_S:-?} s, the runs ${RUNS_S:-?} s with $JOBS at a time, analysis $((T3 - T2)) s;"
		echo "**$((T3 - T0)) s of wall time** ($(((T3 - T0) / 60)) min) on $(nproc) cores of $CPU_MODEL, $(uptime | sed 's/.*load average: *\([^,]*\).*/load average \1 at the end/'))."
	fi
	echo "LAMMPS: $LMP_VERSION. Each part below says when its runs were made; parts not run now are from"
	echo "earlier runs in the run directory, or, where that holds none, kept as the previous fragment had them."
	[ "$QUICK" = 1 ] && { echo; echo "**Quick run (VALIDATE_QUICK=1): every part at a tiny size checks the pipeline only; no verdict below means anything.**"; }
	echo
	echo "What a referee checks: the engine's claims recomputed from a code nobody here wrote (LAMMPS \`gran/hooke\`,"
	echo "the deck \`tests/bench/lammps/vibrated_box.in\`), on the same settled beds, with the engine's own"
	echo "definitions applied to LAMMPS's output (its crossing code for the flux, its rise rule for the waiting time)."
	echo
	echo "| part | question | evidence | result | CPU s | runs started |"
	echo "|---|---|---|---|---:|---|"
	for p in A B C D E; do
		if [ -s "$WORK/$p/summary" ] && [ -s "$WORK/$p/section.md" ]; then
			IFS=$'\t' read -r q ev res <"$WORK/$p/summary"
			echo "| $p | $q | $ev | $res | $(part_cpu "$p") | $(stamp "$p" 1)$([ "$(stamp "$p" 5)" = 1 ] && echo ' (quick)') |"
		elif [ -n "$(old_row "$p")" ] && [ -n "$(old_section "$p")" ]; then
			old_row "$p"
		else
			echo "| $p | — | not run (VALIDATE_PARTS) | — | — | — |"
		fi
	done
	echo
	for p in A B C D E; do
		if [ -s "$WORK/$p/section.md" ]; then
			cat "$WORK/$p/section.md"
			echo
		elif [ -n "$(old_row "$p")" ] && [ -n "$(old_section "$p")" ]; then
			old_section "$p"
			echo
		fi
	done
	# the contact laws on two-disk collisions: `make validate-collisions` writes this section
	if [ -s "$REPO/docs/validate_lammps_collisions.md" ]; then
		cat "$REPO/docs/validate_lammps_collisions.md"
	else
		echo "## Two-disk collisions: the contact laws"
		echo
		echo "Not run: \`make validate-collisions\` writes this section."
	fi
} >"$FRAG.new"
mv "$FRAG.new" "$FRAG"
# the summary table on the terminal too
awk '/^\| part \|/ { on = 1 } on && !/^\|/ { exit } on' "$FRAG" >&2
echo "validate_lammps: wrote $FRAG and its figures in $(($(date +%s) - T0)) s" >&2
