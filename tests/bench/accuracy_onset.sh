#!/usr/bin/env bash
# accuracy_onset.sh - part (e) of `make bench-accuracy` (tests/bench/accuracy.sh runs it
# after (d); `ACC_PARTS=e make bench-accuracy` runs it alone): is `preset = fast` (verlet,
# dt 2e-4) good enough near the onset of convection, where a small change of the dynamics
# moves the answer most? Both presets on the same settled beds (settled once with the
# paper preset, then `settle = no`), paired bed by bed:
#  (e1) the onset of convection of each bed, by the `[onset]` search's own definition
#       (docs/campaigns.md, "Adaptive onset search"): claim 1's search (observable flux,
#       threshold 2 particles/period through the band 0.4-0.6, 2.5-3.2 Hz, tolerance
#       0.02 Hz, stop = flux), no intruder, one replicate per group and the groups
#       bed x preset: each bed's onset is the midpoint of its final bracket. Run through
#       `bin/study run` (ACC_OUT/onset/runs, campaign acc_onset); the beds lie in the
#       campaign's directory because a run's relative `particles` path is read from there.
#       Paired difference fast - paper over the beds (`bin/dumpflux stats paired`: the
#       mean with its Student-t interval, the exact sign-flip p, the difference a paired
#       t-test detects with 80 % power); the interval and the detectable difference are
#       never narrower than the tolerance (a bed's onset is only known to its bracket).
#  (e2) Phi(D) at 2.6 and 2.8 Hz with and without the intruder (R = 4, depth 1):
#       ACC_PHI_BEDS beds each way (the flat ones are (e1)'s first beds), runs of DUR s,
#       periods after the first 20 % averaged (`bin/dumpflux run`). Per group (frequency x
#       intruder): the profiles compared line by line (`bin/dumpflux compare`: lines whose
#       paired difference's interval excludes 0, chi^2 per line and its exact sign-flip
#       p) and the mid-bed |Phi| (the mean over the lines in 0.4-0.6 of the surface
#       height, bin/onset's Phi of a run) paired as in (e1).
# Verdict per comparison: "differ" when a paired test gives p < 0.05 (e1: sign-flip;
# e2: sign-flip of mid-bed |Phi| or of the profile's chi^2), else "indistinguishable
# within" the detectable difference it states. Writes ACC_OUT/onset/section.md (the
# subsection of docs/benchmarks.md), summary.txt (one line per comparison), the rows
# acc-e-onset and acc-e-phiFF-{flat,r4} of docs/preset_evidence.tsv (not with ACC_QUICK=1:
# scripts/preset_evidence.sh) and appends the tables to the report.
#
# Knobs (environment): ACC_QUICK=1 (3 beds, a coarse search and short runs: a pipeline
# check of a few minutes; its numbers mean nothing), ACC_ONSET_BEDS (e1 beds, default 12),
# ACC_PHI_BEDS (e2 beds per intruder case, default 8, at most ACC_ONSET_BEDS), JOBS (default
# 2), ACC_OUT (default build/bench/accuracy), ACC_REPORT (the report to append to; default
# ACC_OUT/onset/report.txt, written fresh), ACC_ONSET_KEEP=1 (keep the runs of an earlier
# invocation: the driver resumes the search, finished e2 runs are not run again).
# Exit: 0 done (whatever the verdict), 1 bad state (a binary or tool missing, bin/study
# failing, runs failed, unreadable output).
# Full size: about 210 runs, about 1600 CPU s on a Zen 5 core (two quiet cores: 15 minutes;
# measured: 208 runs, 1601 CPU s).
set -u
if [ "${1:-}" = --help ] || [ "${1:-}" = -h ]; then
	sed -n '2,/^set -u/p' "$0" | sed '$d; s/^# \{0,1\}//'
	exit 0
fi
HERE=$(cd "$(dirname "$0")" && pwd)
REPO=$(cd "$HERE/../.." && pwd)
SHAKE=$REPO/bin/shake
STUDY=$REPO/bin/study
DUMPFLUX=$REPO/bin/dumpflux
SCENE=$REPO/scenes/paper.scene
QUICK=${ACC_QUICK:-0}
JOBS=${JOBS:-2}
OUT=${ACC_OUT:-$REPO/build/bench/accuracy}
DIR=$OUT/onset
RUNS=$DIR/runs
NAME=acc_onset
CDIR=$RUNS/$NAME
DB=$RUNS/study.db
PRESETS="paper fast"

die() {
	echo "accuracy_onset: $*" >&2
	exit 1
}

if [ "$QUICK" = 1 ]; then
	NB=${ACC_ONSET_BEDS:-3} NP=${ACC_PHI_BEDS:-2} TOL=0.1 ODUR=30 OSKIP=6 DUR=15
else
	NB=${ACC_ONSET_BEDS:-12} NP=${ACC_PHI_BEDS:-8} TOL=0.02 ODUR=120 OSKIP=24 DUR=60
fi
FROM=2.5 TO=3.2 THRESH=2 FREQS="2.6 2.8"
for v in NB NP JOBS; do
	case ${!v} in '' | *[!0-9]* | 0) die "$v: expected a positive integer, got '${!v}'" ;; esac
done
[ "$NB" -ge 3 ] && [ "$NB" -le 18 ] || die "ACC_ONSET_BEDS: expected 3 to 18 beds (a paired interval needs 3; one grid line holds 18), got $NB"
[ "$NP" -ge 2 ] && [ "$NP" -le "$NB" ] || die "ACC_PHI_BEDS: expected 2 to ACC_ONSET_BEDS ($NB), got $NP"
for b in "$SHAKE" "$STUDY" "$DUMPFLUX"; do
	[ -x "$b" ] || die "$b is missing or not executable: run make first"
done
for t in sqlite3 parallel awk sed sort; do
	command -v "$t" >/dev/null 2>&1 || die "$t is not installed"
done
[ -x /usr/bin/time ] || die "/usr/bin/time is not installed (apt-get install time)"
[ -f "$SCENE" ] || die "$SCENE is missing"
case $DIR in /*/onset) ;; *) die "refusing to use '$DIR' (ACC_OUT must be an absolute path)" ;; esac
if [ "${ACC_ONSET_KEEP:-0}" != 1 ]; then rm -rf -- "$DIR" || die "cannot empty $DIR"; fi
mkdir -p "$CDIR/b" "$DIR/beds" "$DIR/e2" || die "cannot create $DIR"
REPORT=${ACC_REPORT:-$DIR/report.txt}
[ -n "${ACC_REPORT:-}" ] || : >"$REPORT"
export SHAKE DUMPFLUX DIR

echo "(e) near the onset: $NB beds for the onsets (2 presets x about $(awk -v a="$FROM" -v b="$TO" -v t="$TOL" 'BEGIN { print int(log((b - a) / t) / log(2) + 0.999) }') runs of up to $ODUR s each)," \
	"$NP + $NP beds x {$FREQS} Hz x 2 presets of $DUR s for Phi(D); $JOBS jobs" >&2

# ---------------------------------------------------------------- beds
# flat beds f1..fNB (seeds 1..NB) in the campaign's directory, intruder beds i1..iNP
# (seeds 101..) beside the e2 runs; settled with the scene's preset, paper
settle() { # NAME SEED RADIUS_RATIO OUTDIR
	local b=$4/$1.txt
	[ -s "$b" ] && return 0
	"$SHAKE" seed="$2" radius_ratio="$3" duration=0 write_particles="$b.tmp" output="$DIR/beds/$1.h5" \
		progress=no >"$DIR/beds/$1.log" 2>&1 && mv "$b.tmp" "$b"
}
export -f settle
{
	for s in $(seq 1 "$NB"); do echo "f$s $s 0 $CDIR/b"; done
	for s in $(seq 1 "$NP"); do echo "i$s $((100 + s)) 4 $DIR/beds"; done
} | parallel -j "$JOBS" --colsep ' ' settle {}
for s in $(seq 1 "$NB"); do [ -s "$CDIR/b/f$s.txt" ] || die "settling bed f$s failed ($DIR/beds/f$s.log)"; done
for s in $(seq 1 "$NP"); do [ -s "$DIR/beds/i$s.txt" ] || die "settling bed i$s failed ($DIR/beds/i$s.log)"; done

# ---------------------------------------------------------------- (e1) onsets
{
	echo "# accuracy_onset.sh (e1): the onset of each bed with both presets (generated)"
	echo "[campaign]"
	echo "name = $NAME"
	echo "description = the presets near the onset: each bed's onset of convection with paper and fast"
	echo "scene = $SCENE"
	echo "seed = 1700"
	echo "[scene]"
	echo "radius_ratio = 0"
	echo "settle = no"
	echo "duration = $ODUR"
	echo "flux = yes"
	echo "traj_rate = 0"
	echo "snapshots = no"
	echo "stop = flux"
	echo "stop_skip = $OSKIP"
	echo "stop_flux_se = 0.5"
	echo "[grid]"
	echo "particles = $(seq 1 "$NB" | sed 's|^|b/f|; s|$|.txt|' | paste -sd, | sed 's/,/, /g')"
	echo "preset = $(echo $PRESETS | sed 's/ /, /g')"
	echo "[onset]"
	echo "observable = flux"
	echo "from = $FROM"
	echo "to = $TO"
	echo "tolerance = $TOL"
	echo "threshold = $THRESH"
	echo "replicates = 1"
} >"$DIR/onset.campaign" || die "cannot write $DIR/onset.campaign"

echo "(e1) study run $DIR/onset.campaign" >&2
"$STUDY" run "$DIR/onset.campaign" --runs "$RUNS" --jobs "$JOBS" \
	--no-progress >"$DIR/study_e1.log" 2>&1
rc=$?
if [ "$rc" != 0 ]; then
	tail -n 15 "$DIR/study_e1.log" >&2
	[ "$rc" = 3 ] || die "bin/study run exited $rc (log: $DIR/study_e1.log)"
	echo "accuracy_onset: some runs of the search failed (exit 3): the table says which beds" >&2
fi
# the engine's CPU seconds per preset, as the driver recorded them for every attempt
cpu_of() { sqlite3 "$DB" "SELECT printf('%.0f', COALESCE(SUM(a.cpu_seconds), 0)) FROM attempt a JOIN param q
	ON q.campaign = a.campaign AND q.run = a.run AND q.key = 'preset' WHERE a.campaign = '$NAME' AND q.value = '$1'"; }
CPU1P=$(cpu_of paper) CPU1F=$(cpu_of fast)
CPU1=$((CPU1P + CPU1F))
# per group: the bed (particles) and the preset from the runs' parameters, the final bracket
sqlite3 -separator ' ' "$DB" "SELECT DISTINCT p.value, q.value, r.state, r.lo, r.hi, r.runs
	FROM onset_run o JOIN onset_replicate r ON r.campaign = o.campaign AND r.grp = o.grp AND r.replicate = o.replicate
	JOIN param p ON p.campaign = o.campaign AND p.run = o.run AND p.key = 'particles'
	JOIN param q ON q.campaign = o.campaign AND q.run = o.run AND q.key = 'preset'
	WHERE o.campaign = '$NAME'" >"$DIR/e1_groups.txt" 2>"$DIR/e1_sql.err" ||
	die "cannot read the search's brackets from $DB: $(cat "$DIR/e1_sql.err")"
[ -s "$DIR/e1_groups.txt" ] || die "no onset brackets in $DB for $NAME"
SIM1=$(sqlite3 "$DB" "SELECT printf('%.0f', SUM(status_time)) FROM runs WHERE campaign = '$NAME'")
NRUN1=$(sqlite3 "$DB" "SELECT COUNT(*) FROM runs WHERE campaign = '$NAME'")
# rows "bed paper_mid fast_mid" for the beds whose two searches both ended with a bracket
awk -v nb="$NB" '{ b = $1; sub(/^b\/f/, "", b); sub(/\.txt$/, "", b)
		if ($3 == "found") mid[b, $2] = ($4 + $5) / 2; else bad[b] = bad[b] " " $2 ": " $3 }
	END { for (b = 1; b <= nb; b++) {
		if ((b SUBSEP "paper") in mid && (b SUBSEP "fast") in mid) printf "%d %.6f %.6f\n", b, mid[b, "paper"], mid[b, "fast"]
		else printf "# bed f%d: no onset%s\n", b, bad[b] } }' "$DIR/e1_groups.txt" >"$DIR/e1_pairs.txt"
N1=$(grep -vc '^#' "$DIR/e1_pairs.txt")
MISS1=$(grep -c '^#' "$DIR/e1_pairs.txt")
[ "$N1" -ge 3 ] || die "(e1): only $N1 beds have an onset with both presets ($DIR/e1_pairs.txt)"
grep -v '^#' "$DIR/e1_pairs.txt" | awk '{ print $2, $3 }' >"$DIR/e1_paired.in"
"$DUMPFLUX" stats paired "$DIR/e1_paired.in" >"$DIR/e1_paired.txt" || die "dumpflux stats paired failed on (e1)"
kv() { awk -v k="$2" '$1 == "#" && $2 == k { print $3; exit }' "$1"; }
# the verdict of a paired comparison FILE, a value: differ when its sign-flip p < 0.05
decide() { awk -v p="$(kv "$1" p_flip)" 'BEGIN { print (p < 0.05 ? "differ" : "indistinguishable") }'; }
# the verdict line of a paired comparison: WHAT FILE FLOOR UNIT
verdict() {
	local f=$2 md hd det p
	md=$(kv "$f" mean_d) hd=$(kv "$f" half_d) det=$(kv "$f" detect80) p=$(kv "$f" p_flip)
	awk -v w="$1" -v md="$md" -v hd="$hd" -v det="$det" -v p="$p" -v fl="$3" -v u="$4" 'BEGIN {
		h = hd > fl ? hd : fl; d = det > fl ? det : fl
		printf "%s: fast - paper = %+.3g [%+.3g, %+.3g] %s (p = %.3g, exact sign-flip); ", w, md, md - h, md + h, u, p
		if (p < 0.05) printf "**differ**\n"
		else printf "**indistinguishable** within %.3g %s (80 %% power)\n", d, u }'
}
V1=$(verdict "onset of convection" "$DIR/e1_paired.txt" "$TOL" Hz)
D1=$(decide "$DIR/e1_paired.txt")

# ---------------------------------------------------------------- (e2) Phi(D)
e2_run() { # NAME BED PRESET FREQ DUR
	local o=$DIR/e2/$1
	case $(cat "$o.res" 2>/dev/null) in "0 "*) return 0 ;; esac # done by an earlier invocation
	/usr/bin/time -f '%U %S' -o "$o.time" "$SHAKE" particles="$2" settle=no preset="$3" frequency="$4" duration="$5" \
		flux=yes traj_rate=0 snapshots=no progress=no output="$o.h5" >"$o.log" 2>&1
	local rc=$?
	# 9: the run finished but its profile could not be read
	if [ "$rc" = 0 ] && ! "$DUMPFLUX" run "$o.h5" >"$o.tsv" 2>>"$o.log"; then rc=9; fi
	echo "$rc $(awk 'NF == 2 { print $1 + $2 }' "$o.time" | tail -n 1)" >"$o.res"
}
export -f e2_run
echo "(e2) $((4 * NP * 2)) runs of $DUR s" >&2
{
	for s in $(seq 1 "$NP"); do for f in $FREQS; do for p in $PRESETS; do
		echo "flat_${f}_${p}_$s $CDIR/b/f$s.txt $p $f $DUR"
		echo "r4_${f}_${p}_$s $DIR/beds/i$s.txt $p $f $DUR"
	done; done; done
} | parallel -j "$JOBS" --colsep ' ' e2_run {}
FAIL2=$(cat "$DIR"/e2/*.res | awk '$1 != 0' | wc -l)
[ "$FAIL2" = 0 ] || die "(e2): $FAIL2 runs failed ($(grep -l -v '^0 ' "$DIR"/e2/*.res | head -n 3 | tr '\n' ' '))"
CPU2=$(cat "$DIR"/e2/*.res | awk '{ c += $2 } END { printf "%.1f", c }')
# mid-bed |Phi| of a run: the mean over the lines in 0.4..0.6 of the surface height
midphi() { awk '/^# .*surface/ { for (i = 1; i <= NF; i++) if ($i == "surface") s = $(i + 1); next } /^#/ { next }
	s && $2 >= 0.4 * s && $2 <= 0.6 * s { t += $3; n++ } END { if (!n) exit 1; m = t / n; printf "%.6f\n", m < 0 ? -m : m }' "$1"; }
: >"$DIR/e2_table.txt"
V2=
declare -A D2 # the verdict of each group (its key: flat_2.6, r4_2.8, ...)
for f in $FREQS; do for k in flat r4; do
	g=${k}_$f
	a=() b=()
	: >"$DIR/e2_$g.in"
	for s in $(seq 1 "$NP"); do
		a+=("$DIR/e2/${k}_${f}_paper_$s.tsv") b+=("$DIR/e2/${k}_${f}_fast_$s.tsv")
		echo "$(midphi "$DIR/e2/${k}_${f}_paper_$s.tsv") $(midphi "$DIR/e2/${k}_${f}_fast_$s.tsv")" >>"$DIR/e2_$g.in" ||
			die "(e2): no lines in the band in $DIR/e2/${k}_${f}_*_$s.tsv"
	done
	"$DUMPFLUX" compare "${a[@]}" -- "${b[@]}" >"$DIR/e2_$g.cmp" || die "dumpflux compare failed on (e2) $g"
	"$DUMPFLUX" stats paired "$DIR/e2_$g.in" >"$DIR/e2_$g.paired" || die "dumpflux stats paired failed on (e2) $g"
	lab="$f Hz, $([ "$k" = flat ] && echo 'no intruder' || echo '𝓡 = 4')"
	# a profile that differs (chi^2's sign-flip p < 0.05) makes the group differ too
	pc=$(kv "$DIR/e2_$g.cmp" p_chi2)
	line=$(verdict "mid-bed |Phi|, $lab" "$DIR/e2_$g.paired" 0 "particles/period")
	D2[$g]=$(decide "$DIR/e2_$g.paired")
	if awk -v p="$pc" 'BEGIN { exit !(p < 0.05) }'; then
		line="${line%%\*\*indistinguishable*}**differ** (the profile: chi² p = $pc)"
		D2[$g]=differ
	fi
	V2="$V2$line"$'\n'
	echo "$f ${k} $(kv "$DIR/e2_$g.paired" mean_a) $(kv "$DIR/e2_$g.paired" mean_b) $(kv "$DIR/e2_$g.paired" mean_d) $(kv "$DIR/e2_$g.paired" half_d)" \
		"$(kv "$DIR/e2_$g.paired" detect80) $(kv "$DIR/e2_$g.paired" p_flip) $(kv "$DIR/e2_$g.cmp" disagree) $(kv "$DIR/e2_$g.cmp" lines)" \
		"$(kv "$DIR/e2_$g.cmp" chi2_per_line) $pc" >>"$DIR/e2_table.txt"
done; done

# ---------------------------------------------------------------- report
cpuinfo=$(awk -F': ' '/^model name/ { print $2; exit }' /proc/cpuinfo)
isa=$(grep -qw avx512f /proc/cpuinfo && echo AVX-512 || { grep -qw avx2 /proc/cpuinfo && echo AVX2 || echo SSE2; })
commit=$(git -C "$REPO" rev-parse --short HEAD 2>/dev/null || echo unknown)
{
	printf '%s\n' "$V1" | sed 's/\*\*//g'
	printf '%s' "$V2" | sed 's/\*\*//g'
} >"$DIR/summary.txt"
{
	echo "**(f) Near the onset: the onset and Φ(D) with both presets on the same beds** (\`make"
	echo "bench-accuracy\`, part (e), \`tests/bench/accuracy_onset.sh\`; $(date +%Y-%m-%d), commit $commit, $cpuinfo ($isa),"
	echo "$(nproc) cores$([ "$QUICK" = 1 ] && echo '; **ACC_QUICK=1: a pipeline check, the numbers mean nothing**')). Beds settled once with \`paper\`, then shaken with"
	echo "\`preset = paper\` (gear5, 5·10⁻⁵ s) and \`preset = fast\` (verlet, 2·10⁻⁴ s); paired bed by bed: the mean of"
	echo "fast − paper with its 95 % Student-t interval, the exact sign-flip test, and the difference a paired t-test"
	echo "detects with 80 % power (never below the data's resolution)."
	echo
	echo "(e1) **The onset of convection of each bed** by claim 1's \`[onset]\` search (flux through the band 0.4–0.6 of"
	echo "the surface height ≥ $THRESH particles/period, $FROM–$TO Hz, tolerance $TOL Hz, \`stop = flux\`), no intruder, one"
	echo "search per bed and preset; a bed's onset is the midpoint of its final bracket, known to ±$(awk -v t="$TOL" 'BEGIN { print t / 2 }') Hz. $N1 beds"
	[ "$MISS1" = 0 ] || echo "($MISS1 without an onset with both presets: $(grep '^#' "$DIR/e1_pairs.txt" | sed 's/^# //' | paste -sd';'))"
	echo "($NRUN1 runs, $SIM1 simulated s, $CPU1 CPU s: paper $CPU1P, fast $CPU1F): $V1"
	echo
	echo "| bed | paper onset (Hz) | fast onset (Hz) | fast − paper |"
	echo "|---:|---:|---:|---:|"
	grep -v '^#' "$DIR/e1_pairs.txt" | awk '{ printf "| f%d | %.3f | %.3f | %+.3f |\n", $1, $2, $3, $3 - $2 }'
	echo "| mean | $(kv "$DIR/e1_paired.txt" mean_a | xargs printf '%.3f') | $(kv "$DIR/e1_paired.txt" mean_b | xargs printf '%.3f') | $(kv "$DIR/e1_paired.txt" mean_d | xargs printf '%+.3f') |"
	echo
	echo "(e2) **Φ(D) at $(echo $FREQS | sed 's/ / and /') Hz** with and without the intruder (𝓡 = 4, depth 1), $NP beds each, $DUR s per run,"
	echo "the periods after the first 20 % averaged ($((8 * NP)) runs, $CPU2 CPU s). Mid-bed |Φ|: the mean over the"
	echo "lines in 0.4–0.6 of the surface height (\`bin/onset\`'s Φ of a run); profile: the paired differences line"
	echo "by line (\`bin/dumpflux compare\`), lines whose 95 % interval excludes 0, χ² per line and its exact"
	echo "sign-flip p over the beds."
	echo
	echo "| group | paper mid-bed \|Φ\| | fast | fast − paper (95 %) | detectable (80 %) | p | profile: lines differing | χ²/line (p) |"
	echo "|---|---:|---:|---:|---:|---:|---:|---:|"
	awk '{ printf "| %s Hz, %s | %.3f | %.3f | %+.3f ± %.3f | %.3f | %.3g | %d / %d | %.2f (%.3g) |\n", $1, ($2 == "flat" ? "no intruder" : "𝓡 = 4"), $3, $4, $5, $6, $7, $8, $9, $10, $11, $12 }' "$DIR/e2_table.txt"
	echo
	printf '%s' "$V2" | sed 's/^/- /'
} >"$DIR/section.md"
{
	echo "(e) Near the onset: the presets on the same beds (tests/bench/accuracy_onset.sh; $DIR/section.md)"
	sed 's/^/    /' "$DIR/summary.txt"
	echo
} >>"$REPORT"
cat "$DIR/summary.txt" >&2
# the evidence rows the campaigns' presets rest on (scripts/preset_evidence.sh): one per
# comparison, its verdict and its sentence; a quick run's numbers are not evidence
evidence() { # KEY VERDICT SUMMARY-LINE
	bash "$REPO/scripts/preset_evidence.sh" set "$1" "$2" "make bench-accuracy (e), $(date +%Y-%m-%d), $commit" "$3 ($NB beds for the onset, $NP per group for Φ)" ||
		die "cannot write docs/preset_evidence.tsv"
}
if [ "$QUICK" != 1 ]; then
	evidence acc-e-onset "$D1" "$(sed -n 1p "$DIR/summary.txt")"
	i=2
	for f in $FREQS; do for k in flat r4; do
		evidence "acc-e-phi$(echo "$f" | tr -d .)-$k" "${D2[${k}_$f]}" "$(sed -n "${i}p" "$DIR/summary.txt")"
		i=$((i + 1))
	done; done
fi
exit 0
