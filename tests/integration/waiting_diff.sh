#!/usr/bin/env bash
# waiting_diff.sh - bin/waiting --diff KEY on run files whose waiting times are set by
# hand (build/fuzz/h5mut), so that the answer is known: a tiny campaign at four
# frequencies (6 runs each) becomes a reference (20 Hz: risen at 1..6 s, median 3), the
# same times (21 Hz: difference 0, 0 inside its interval), later times (22 Hz: 10..15 s,
# median 12, difference 9, 0 excluded) and a curve that never reaches 1/2 (23 Hz: two risen,
# four censored at 5 s: a censored median, reported as the bound >2, never as a
# number). Then the reference made censored too (a bound the other way; both censored:
# none), --boot 1 (no interval) and the usage error of a KEY that is no grouping key.
# The campaign is run by the release engine (lib.sh's data_driver_setup: the tool is
# under test, the engine only makes the files whose times are then set by hand).
# tier: slow: a campaign of 24 tiny runs
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
data_driver_setup
H5MUT="${H5MUT:-$REPO/build/fuzz/h5mut}"
[ -x "$H5MUT" ] || { fail setup "$H5MUT is not an executable (run make tests)"; finish; }
cd "$TMP" || exit 1

printf '[campaign]\nname = w\nseed = 5\nreplicates = 6\n[scene]\nn_grains = 40\nwidth = 16\ndepth = 0\nsettle_ke = 1
settle_min = 0.1\npreset = fast\namplitude = 0.05\nradius_ratio = 1.5\nduration = 0.3\n[grid]
frequency = 20, 21, 22, 23\n' >w.campaign
"$DATA_STUDY" run w.campaign --runs R --jobs 2 --no-progress >setup.log 2>&1 &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'")" = 24 ] && ok wdiff.setup.campaign ||
	{ fail wdiff.setup.campaign "$(tail -c 400 setup.log)"; finish; }

# each run's rise by frequency and replicate (1..6)
# times set by hand: longer than the runs, so their duration is made 20 s in file and
# database alike (a waiting time after the run's end is refused: docs/inputs.md, "Run
# files"), and each new file's seal is recorded, as the driver would have; the rows'
# own seals are written again once after each batch (reseal_rows reads every row: once
# per run it was a Python start and a pass over the database for each of 30 runs)
# times ID RISEN WAIT: run ID's file says so
times() {
	"$H5MUT" "R/w/$1.h5" "R/w/$1.new" --attr / risen "$2" --attr / waiting_time "$3" --attr /parameters duration 20 &&
		mv "R/w/$1.new" "R/w/$1.h5" &&
		q R/study.db "UPDATE result SET file_seal = '$(head -c 64 "R/w/$1.h5" | sed -n 's/^fnv1a64w //p')' WHERE run = '$1';
			UPDATE param SET value = 20 WHERE run = '$1' AND key = 'duration'"
}
bad=0
while IFS='|' read -r id rep f; do
	case "${f%.0}" in
	20 | 21) r=1 w=$rep ;;
	22) r=1 w=$((rep + 9)) ;;
	23) if [ "$rep" -le 2 ]; then r=1 w=$rep; else r=0 w=5; fi ;;
	esac
	times "$id" "$r" "$w" || bad=1
done < <(q R/study.db "SELECT r.id, r.replicate, p.value FROM run r JOIN param p ON p.run = r.id AND p.key = 'frequency'")
reseal_rows R/study.db || bad=1
[ "$bad" = 0 ] && ok wdiff.setup.times || { fail wdiff.setup.times "h5mut failed"; finish; }

"$BINDIR/waiting" w --runs R --no-plot --boot 400 --seed 3 --diff frequency >w.out 2>w.err
rc=$?
A=R/w/analysis
[ "$rc" = 0 ] && [ ! -s w.err ] && ok wdiff.exit || fail wdiff.exit "exit $rc: $(cat w.err)"
# row FREQ: waiting_diff.csv's row of the group at FREQ against 20 Hz
row() { awk -F, -v f="$1" 'NR > 1 && $4 + 0 == f' $A/waiting_diff.csv; }
col() { row "$1" | cut -d, -f"$2"; }
[ "$(tail -n +2 $A/waiting_diff.csv | wc -l)" = 3 ] && [ "$(col 21 3)" = 20 ] &&
	ok wdiff.csv.three_pairs || fail wdiff.csv.three_pairs "$(cat $A/waiting_diff.csv)"
# the same times: difference 0, the interval holds 0 and has a width
awk -F, '{ exit !($10 == 0 && $11 < 0 && $12 > 0 && $13 == 400 && $16 == 1) }' <<<"$(row 21)" &&
	grep -qE ' 21 +20 +0\.000 \[-[0-9.]+, [0-9.]+\] .* inside$' w.out &&
	ok wdiff.same.zero_inside || fail wdiff.same.zero_inside "$(row 21); $(grep -A5 '^# differences' w.out)"
# later times: difference 9 (median 12 against 3), 0 excluded
awk -F, '{ exit !($10 == 9 && $11 > 0 && $12 >= $10 && $16 == 0) }' <<<"$(row 22)" &&
	grep -qE ' 22 +20 +9\.000 \[[0-9.]+, [0-9.]+\] .* excluded$' w.out &&
	ok wdiff.later.zero_excluded || fail wdiff.later.zero_excluded "$(row 22); $(grep -A5 '^# differences' w.out)"
# a censored median: no number, the bound >2 (its longest observation 5 less 3), said censored
awk -F, '{ exit !($6 == "nan" && $9 == "b" && $10 == "nan" && $14 == 0 && $15 > 0) }' <<<"$(row 23)" &&
	grep -qE ' 23 +20 +>2\.000 \[[-0-9.]+, \+inf\] +b ' w.out &&
	ok wdiff.censored.bound || fail wdiff.censored.bound "$(row 23); $(grep -A5 '^# differences' w.out)"
# stored: one diff_median per pair, the censored one without a value, grp naming both
[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE tool = 'waiting' AND key = 'diff_median'")" = 3 ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE key = 'diff_median' AND frequency = 23 AND value IS NULL
		AND hi IS NULL AND grp LIKE '%23% - %20%'")" = 1 ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE key = 'diff_median' AND frequency = 22 AND value = 9 AND lo > 0")" = 1 ] &&
	ok wdiff.stored || fail wdiff.stored "$(q R/study.db "SELECT grp, value, lo, hi, n FROM analysis WHERE key = 'diff_median'")"
# the same seed, the same intervals
cp $A/waiting_diff.csv first.csv
"$BINDIR/waiting" w --runs R --no-plot --no-store --boot 400 --seed 3 --diff frequency >w2.out 2>&1 &&
	cmp -s first.csv $A/waiting_diff.csv && ok wdiff.reproducible || fail wdiff.reproducible "$(diff first.csv $A/waiting_diff.csv)"

# no interval without replicates
"$BINDIR/waiting" w --runs R --no-plot --no-store --boot 1 --diff frequency >b.out 2>&1 &&
	awk -F, 'NR > 1 && $13 != 0 { bad = 1 } END { exit bad }' $A/waiting_diff.csv &&
	grep -q ' 22 .* 9\.000 \[-, -\] ' b.out && grep -q '^# differences.*no interval (--boot below 2)' b.out &&
	ok wdiff.no_boot || fail wdiff.no_boot "$(cat b.out)"

# the reference censored too (20 Hz made like 23 Hz): against it a reached median is an
# upper bound (21 Hz: <-2, 3 less its longest observation 5) and two censored medians
# give no number at all
while IFS='|' read -r id rep; do
	[ "$rep" -le 2 ] && r=1 w=$rep || r=0 w=5
	times "$id" "$r" "$w"
done < <(q R/study.db "SELECT r.id, r.replicate FROM run r JOIN param p ON p.run = r.id AND p.key = 'frequency' AND p.value = 20")
reseal_rows R/study.db
"$BINDIR/waiting" w --runs R --no-plot --no-store --boot 200 --diff frequency >c.out 2>c.err
awk -F, '{ exit !($5 == "nan" && $9 == "a" && $10 == "nan" && $11 == "-inf") }' <<<"$(row 21)" &&
	grep -qE ' 21 +20 +<-2\.000 \[-inf, ' c.out && ok wdiff.censored.reference ||
	fail wdiff.censored.reference "$(cat c.err; row 21; grep -A5 '^# differences' c.out)"
awk -F, '{ exit !($9 == "both" && $10 == "nan" && $11 == "-inf" && $12 == "inf" && $16 == 1) }' <<<"$(row 23)" &&
	grep -qE ' 23 +20 +censored \[-inf, \+inf\] +both ' c.out && ok wdiff.censored.both ||
	fail wdiff.censored.both "$(row 23; grep -A5 '^# differences' c.out)"

# a KEY that is no grouping key is a usage error
"$BINDIR/waiting" w --runs R --no-plot --no-store --diff mu >e.out 2>e.err
rc=$?
[ "$rc" = 1 ] && grep -q 'mu' e.err && grep -q 'frequency' e.err && ok wdiff.not_a_key ||
	fail wdiff.not_a_key "exit $rc: $(cat e.err)"
finish
