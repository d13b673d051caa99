#!/usr/bin/env bash
# whale.sh - bin/whale end to end on a tiny real campaign (100 grains, fast preset, 40 s
# at 4 Hz, 𝓡 = 0, 2.5, 3 with 3 seeds: about 3 s of CPU in the release build, which runs
# it: the tool is what is tested, lib.sh's data_driver_setup): the
# table, CSV files, figure and stored rows; the runs without intruder not considered;
# the runs that never rose listed and counted as the database says; and every
# analysed run's window, top level, dives and period recomputed here from its file
# with h5dump and awk (box frame, running mean over one period, GSL's quantile, the
# hysteresis), independently of analysis/measure/whale.c. Then the options: a skip longer than
# the runs (every risen run too short), --no-store, reproducibility, errors.
# tier: slow: a campaign of large beds
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
data_driver_setup
cd "$TMP" || exit 1
WHALE="$BINDIR/whale"
[ -x "$WHALE" ] || { fail setup "$WHALE is not an executable (run make)"; finish; }
png_ok() { [ -s "$1" ] && [ "$(head -c 4 "$1" | od -An -c | tr -d ' ')" = '211PNG' ]; }
pdf_ok() { [ -s "$1" ] && [ "$(head -c 4 "$1")" = '%PDF' ]; }
# rel A B TOL : |A - B| <= TOL |B| (both "nan" counts as equal)
rel() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { if (a == "nan" && b == "nan") exit 0; d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; exit !(a != "" && b != "" && d <= t * m + 1e-12) }'; }

# The bed of ring.sh and observables_rise.sh: a 2.5-3x intruder rises within seconds
# to half a minute at 4 Hz, A = 2 cm, and moves up and down at the top of this shallow
# bed; the trajectory at 50 Hz.
printf '[campaign]\nname = wh\nseed = 5\nreplicates = 3\n[scene]\npreset = fast\n'"$(tiny_scene n_grains=100 width=24 radius_ratio=-)"'\namplitude = 2\nfrequency = 4\nduration = 40\ntraj_rate = 50\n[grid]\nradius_ratio = 0, 2.5, 3\n' >wh.campaign
t0=$SECONDS
"$DATA_STUDY" run wh.campaign --runs "$TMP/R" --jobs 2 --no-progress >study.log 2>&1
rc=$?
echo "# campaign: $((SECONDS - t0)) s"
[ "$rc" -eq 0 ] && [ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'")" = 9 ] && ok setup.campaign ||
	{ fail setup.campaign "study exit $rc: $(tail -c 300 study.log)"; finish; }

"$WHALE" wh --runs R --skip 2 --boot 300 --seed 4 >whale.out 2>whale.err
rc=$?
A=R/wh/analysis
[ "$rc" -eq 0 ] && ok whale.exit || fail whale.exit "exit $rc: $(cat whale.err)"
[ ! -s whale.err ] && ok whale.quiet || fail whale.quiet "$(head -c 300 whale.err)"
grep -q '^group .*period s \[CI\] (n)' whale.out && grep -q '^radius_ratio=2.5 ' whale.out &&
	grep -q '^radius_ratio=3 ' whale.out && ! grep -q '^radius_ratio=0 ' whale.out && ok whale.table ||
	fail whale.table "$(cat whale.out)"
# the runs with an intruder only: 6 considered, 2 groups
[ "$(tail -n +2 $A/whale_runs.csv | wc -l)" = 6 ] && [ "$(tail -n +2 $A/whale_accounting.csv | wc -l)" = 6 ] &&
	[ "$(tail -n +2 $A/whale_summary.csv | wc -l)" = 2 ] && [ "$(tail -n +2 $A/whale_points.csv | wc -l)" = 2 ] &&
	[ "$(tail -n +2 $A/whale_trend.csv | wc -l)" = 3 ] && ok whale.csv || fail whale.csv "$(wc -l $A/whale_*.csv)"
png_ok $A/whale.png && pdf_ok $A/whale.pdf && ok whale.figure || fail whale.figure "$(ls $A)"
grep -q 'median period' $A/whale.gp && grep -q "window opens" $A/whale.gp && ok whale.figure_text ||
	fail whale.figure_text "$(grep -c . $A/whale.gp) lines"
# a trace for every group that has an analysed run, of its representative run
nrep=$(awk -F, 'NR > 1 && $30 == 1' $A/whale_runs.csv | wc -l)
ntr=$(tail -n +2 $A/whale_traces.csv | cut -d, -f1 | sort -u | wc -l)
[ "$nrep" = "$ntr" ] && [ "$nrep" -ge 1 ] && ok whale.traces || fail whale.traces "$nrep representatives, $ntr traces"

# ---- the counts against the database ----
nr=$(q R/study.db "SELECT COUNT(*) FROM result s JOIN param p ON p.campaign = s.campaign AND p.run = s.run AND p.key = 'radius_ratio'
	WHERE s.campaign = 'wh' AND s.risen = 0 AND CAST(p.value AS REAL) > 0")
st() { q R/study.db "SELECT CAST(SUM(value) AS INT) FROM analysis WHERE campaign = 'wh' AND tool = 'whale' AND key = '$1'"; }
[ "$(st not_risen)" = "$nr" ] && [ "$(st runs)" = 6 ] &&
	[ "$(($(st not_risen) + $(st no_trajectory) + $(st too_short) + $(st analysed)))" = 6 ] &&
	[ "$(awk -F, 'NR > 1 && $11 == "not_risen"' $A/whale_runs.csv | wc -l)" = "$nr" ] && ok counts.not_risen ||
	fail counts.not_risen "stored not_risen $(st not_risen), database $nr; runs $(st runs)"
if [ "$nr" -gt 0 ]; then
	grep -q "^# $nr used runs\? never rose" whale.out && ok counts.not_risen_listed || fail counts.not_risen_listed "$(grep '^#' whale.out)"
fi
# every stored mean says how many runs it rests on: the period's n is the runs with >= 2 dives
np=$(awk -F, 'NR > 1 && $11 == "analysed" && $21 != "nan"' $A/whale_runs.csv | wc -l)
[ "$(q R/study.db "SELECT SUM(n) FROM analysis WHERE campaign = 'wh' AND tool = 'whale' AND key = 'period'")" = "$np" ] &&
	[ "$(st with_period)" = "$np" ] && ok counts.period_n || fail counts.period_n "$np runs with a period; stored $(q R/study.db "SELECT grp, n FROM analysis WHERE tool = 'whale' AND key = 'period'")"
[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 'wh' AND tool = 'whale' AND grp = 'trend over radius_ratio' AND key GLOB 'trend_*'")" = 6 ] &&
	ok store.trend_rows || fail store.trend_rows "$(q R/study.db "SELECT grp, key, value, n FROM analysis WHERE tool = 'whale' AND key GLOB 'trend*'")"
grep -q '^# trend of the rate against 𝓡' whale.out && ok print.trend || fail print.trend "$(grep '^#' whale.out)"

# ---- each analysed run recomputed from its file ----
A_=2 F_=4
nchk=0 bad=""
while IFS=, read -r run wt from samples dcm top dives period; do
	f=R/wh/$run.h5
	paste -d' ' <(h5vals "$f" /particles/intruder/position/time) <(h5vals "$f" /particles/intruder/position/value | paste -d' ' - -) |
		awk -v A=$A_ -v f=$F_ -v t0="$(awk -v w="$wt" 'BEGIN { printf "%.17g", w + 2 }')" '
		BEGIN { pi = atan2(0, -1) }
		$1 >= t0 { n++; t[n] = $1; y[n] = $3 - A * sin(2 * pi * f * $1) }
		END {
			w = 1 / f
			for (i = 1; i <= n; i++) { s = 0; k = 0
				for (j = i; j >= 1 && t[j] >= t[i] - w / 2; j--) { s += y[j]; k++ }
				for (j = i + 1; j <= n && t[j] <= t[i] + w / 2; j++) { s += y[j]; k++ }
				printf "%.17g %.17g\n", t[i], s / k }
		}' >sm.txt
	# GSL quantile 0.9 of the averaged heights: linear between order statistics
	tq=$(cut -d' ' -f2 sm.txt | sort -g | awk '{ v[NR] = $1 } END { x = 0.9 * (NR - 1); l = int(x); d = x - l; printf "%.17g", (1 - d) * v[l + 1] + d * v[l + 2] }')
	read -r n2 f2 d2 p2 <<<"$(awk -v top="$tq" -v D="$dcm" '
		{ n++; if (n == 1) first = $1
		  if (inn) { if ($2 >= top - D / 2) inn = 0 } else if ($2 < top - D) { nd++; s[nd] = $1; inn = 1 } }
		BEGIN { inn = 1 }
		END { p = (nd >= 2) ? sprintf("%.17g", (s[nd] - s[1]) / (nd - 1)) : "nan"; printf "%d %.17g %d %s\n", n, first, nd, p }' sm.txt)"
	nchk=$((nchk + 1))
	{ [ "$n2" = "$samples" ] && rel "$f2" "$from" 1e-12 && rel "$tq" "$top" 1e-9 && [ "$d2" = "$dives" ] && rel "$p2" "$period" 1e-9; } ||
		bad="$bad $run: samples $samples/$n2 from $from/$f2 top $top/$tq dives $dives/$d2 period $period/$p2;"
done < <(awk -F, 'NR > 1 && $11 == "analysed" { print $3 "," $10 "," $12 "," $14 "," $15 "," $16 "," $19 "," $21 }' $A/whale_runs.csv)
[ "$nchk" -ge 1 ] && [ -z "$bad" ] && ok recompute.runs_from_files || fail recompute.runs_from_files "$nchk runs checked:$bad"

# ---- options ----
q R/study.db "SELECT grp, key, value, lo, hi, n FROM analysis WHERE tool = 'whale' ORDER BY grp, key" >rows1
"$WHALE" wh --runs R --skip 2 --boot 300 --seed 4 --no-plot >/dev/null 2>&1
q R/study.db "SELECT grp, key, value, lo, hi, n FROM analysis WHERE tool = 'whale' ORDER BY grp, key" >rows2
cmp -s rows1 rows2 && ok whale.reproducible || fail whale.reproducible "$(diff rows1 rows2 | head -4)"
"$WHALE" wh --runs R --skip 1000 --no-store --out long >long.out 2>long.err
rc=$?
cmp -s rows1 <(q R/study.db "SELECT grp, key, value, lo, hi, n FROM analysis WHERE tool = 'whale' ORDER BY grp, key") &&
	[ "$rc" -eq 0 ] && ok whale.no_store || fail whale.no_store "exit $rc: $(cat long.err)"
risen=$((6 - nr))
[ "$(awk -F, 'NR > 1 && $11 == "too_short"' long/whale_runs.csv | wc -l)" = "$risen" ] &&
	grep -q "^# $risen risen runs\? with fewer than 10 drive periods" long.out && grep -q 'no run has one' long/whale.gp &&
	ok whale.skip_past_the_end || fail whale.skip_past_the_end "$(grep '^#' long.out)"
"$WHALE" --help | grep -q -- '--dive D' && ok cli.help || fail cli.help "no --dive in the help"
"$WHALE" wh --runs R --top 0 >/dev/null 2>e.txt
[ $? -eq 1 ] && grep -q -- '--top: expected a number' e.txt && ok cli.bad_value || fail cli.bad_value "$(cat e.txt)"
"$WHALE" wh --runs R --skpi 3 >/dev/null 2>e.txt
[ $? -eq 1 ] && grep -q 'did you mean --skip' e.txt && ok cli.misspelt || fail cli.misspelt "$(cat e.txt)"
"$WHALE" wh --runs R --by frequency >/dev/null 2>e.txt
[ $? -eq 1 ] && grep -q 'must include radius_ratio' e.txt && ok cli.by_needs_ratio || fail cli.by_needs_ratio "$(cat e.txt)"
"$WHALE" nosuch --runs R >/dev/null 2>e.txt
[ $? -eq 1 ] && grep -q "campaign 'nosuch' is not in" e.txt && ok cli.unknown_campaign || fail cli.unknown_campaign "$(cat e.txt)"
finish
