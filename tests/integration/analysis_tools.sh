#!/usr/bin/env bash
# analysis_tools.sh - the analysis tools end to end: a tiny campaign (with and
# without intruder, three frequencies, two seeds, flux and field on) and a tiny ramp
# campaign run by bin/study, then onset, waiting, figures and hysteresis on them:
# exit codes, nothing on stderr, tables, CSV and PNG files, the rows stored in the `analysis` table,
# reproducible bootstrap intervals on a second run, and the error paths.
# The campaigns are run by the release engine (lib.sh's data_driver_setup: the tools are
# what is tested).
# tier: slow: campaigns for every analysis tool
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
data_driver_setup
cd "$TMP" || exit 1
png_ok() { [ -s "$1" ] && [ "$(head -c 4 "$1" | od -An -c | tr -d ' ')" = '211PNG' ]; }

SCENE="$(tiny_scene radius_ratio=-)
amplitude = 1
traj_rate = 100
flux = yes"
printf '[campaign]\nname = t\nseed = 3\nreplicates = 2\n[scene]\n%s\nduration = 1\nfield = yes\nfield_periods = 2\n[grid]\nradius_ratio = 0, 2\nfrequency = 3, 5, 7\n' "$SCENE" >t.campaign
printf '[campaign]\nname = h\nseed = 4\nreplicates = 2\n[scene]\n%s\nduration = 2.5\nramp = updown\nramp_from = 3\nramp_to = 7\n[grid]\nradius_ratio = 2\n' "$SCENE" >h.campaign
t0=$SECONDS
"$DATA_STUDY" run t.campaign --runs "$TMP/R" --jobs 2 --no-progress >study_t.log 2>&1 &&
	"$DATA_STUDY" run h.campaign --runs "$TMP/R" --jobs 2 --no-progress >study_h.log 2>&1
rc=$?
echo "# campaigns: $((SECONDS - t0)) s"
[ "$rc" -eq 0 ] && [ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'")" = 14 ] && ok setup.campaigns ||
	{ fail setup.campaigns "study exit $rc: $(tail -c 300 study_t.log study_h.log)"; finish; }

# tool NAME CAMPAIGN [ARGS...]: runs it with stdout in NAME.out, stderr in NAME.err; returns its exit code
tool() {
	local n=$1
	shift
	"$BINDIR/$n" "$@" >"$n.out" 2>"$n.err"
}

# ---- onset ----
tool onset t --runs R --boot 60 --seed 7
rc=$?
A=R/t/analysis
[ "$rc" -eq 0 ] && ok onset.exit || fail onset.exit "exit $rc: $(cat onset.err)"
[ ! -s onset.err ] && ok onset.quiet || fail onset.quiet "$(head -c 300 onset.err)"
grep -q '^group .*sigmoid f0' onset.out && grep -q '^radius_ratio=0 depth=1 .* no ' onset.out &&
	grep -q '^radius_ratio=2 depth=1 .* yes ' onset.out && ok onset.table || fail onset.table "$(cat onset.out)"
[ "$(tail -n +2 $A/onset_runs.csv | wc -l)" = 12 ] && [ -s $A/onset_summary.csv ] && [ -s $A/onset_seeds.csv ] &&
	ok onset.csv || fail onset.csv "$(ls $A)"
png_ok $A/onset.png && ok onset.png || fail onset.png "no PNG"
[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 't' AND tool = 'onset' AND key IN ('sigmoid_f0', 'threshold_f')
	AND version = '3' AND n = 6 AND created LIKE '20%'")" = 4 ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE tool = 'onset' AND key = 'seeds' AND value = 2")" = 2 ] &&
	ok onset.db_rows || fail onset.db_rows "$(q R/study.db "SELECT * FROM analysis WHERE tool = 'onset'")"
# the threshold estimate lies inside the sampled frequencies and its interval around it
[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE tool = 'onset' AND key = 'threshold_f' AND value IS NOT NULL
	AND (value BETWEEN 3 AND 7) AND (lo IS NULL OR lo <= value + 1e-9) AND (hi IS NULL OR hi >= value - 1e-9)")" -ge 1 ] &&
	ok onset.threshold_range || fail onset.threshold_range "$(q R/study.db "SELECT grp, value, lo, hi FROM analysis WHERE key = 'threshold_f'")"
q R/study.db "SELECT grp, key, value, lo, hi FROM analysis WHERE tool = 'onset' ORDER BY grp, key" >onset.rows1
tool onset t --runs R --boot 60 --seed 7 --no-plot
q R/study.db "SELECT grp, key, value, lo, hi FROM analysis WHERE tool = 'onset' ORDER BY grp, key" >onset.rows2
# 7 keys of the estimates and 8 of the accounting per group
cmp -s onset.rows1 onset.rows2 && [ "$(wc -l <onset.rows1)" = 30 ] && ok onset.rerun_reproducible_no_duplicates ||
	fail onset.rerun_reproducible_no_duplicates "$(diff onset.rows1 onset.rows2 | head -n 4)"
# the database path and the output convention can be given explicitly
tool onset t --db R/study.db --out "$TMP/o2" --boot 20 --no-store && [ -s o2/onset_runs.csv ] && png_ok o2/onset.png &&
	ok onset.db_and_out_options || fail onset.db_and_out_options "$(cat onset.err)"

# ---- waiting ----
tool waiting t --runs R
rc=$?
[ "$rc" -eq 0 ] && ok waiting.exit || fail waiting.exit "exit $rc: $(cat waiting.err)"
[ ! -s waiting.err ] && ok waiting.quiet || fail waiting.quiet "$(head -c 300 waiting.err)"
# runs without intruder have no waiting time: three groups (R = 2 at 3 frequencies)
[ "$(sed '/^$/q' waiting.out | grep -c '^radius_ratio=2 frequency=')" = 3 ] && ! grep -q '^radius_ratio=0' waiting.out &&
	ok waiting.table || fail waiting.table "$(cat waiting.out)"
[ "$(tail -n +2 $A/waiting_runs.csv | wc -l)" = 6 ] && [ -s $A/waiting_km.csv ] && [ -s $A/waiting_hist.csv ] &&
	ok waiting.csv || fail waiting.csv "$(ls $A)"
# the log-rank test across the three groups, printed with the runs it rests on and
# stored once - or, when no intruder rose (these short runs), said to be impossible
lr=$(grep '^# log-rank' waiting.out)
nlr=$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE tool = 'waiting' AND grp = 'all groups' AND key IN ('logrank_chi2', 'logrank_p', 'logrank_df') AND n = 6")
case "$lr" in
"# log-rank test of equal waiting-time distributions across the 3 groups (6 runs"*"df = 2, p = "*) [ "$nlr" = 3 ] ;;
"# log-rank test across the 3 groups (6 runs): no test, no intruder rose") [ "$nlr" = 0 ] ;;
*) false ;;
esac && ok waiting.logrank || fail waiting.logrank "'$lr', $nlr stored rows"
png_ok $A/waiting_km.png && png_ok $A/waiting_hist.png && ok waiting.png || fail waiting.png "missing PNG"
# each run's pair (waiting_time, risen) is the one in its output file
id=$(q R/study.db "SELECT id FROM runs WHERE radius_ratio = 2 ORDER BY id LIMIT 1")
line=$(grep ",$id," $A/waiting_runs.csv)
[ -n "$line" ] && [ "$(echo "$line" | awk -F, '{print $7}')" = "$(attr R/t/$id.h5 /risen)" ] &&
	awk -v a="$(echo "$line" | awk -F, '{print $6}')" -v b="$(attr R/t/$id.h5 /waiting_time)" 'BEGIN { exit !(a == b) }' &&
	ok waiting.matches_output || fail waiting.matches_output "csv '$line' vs file risen=$(attr R/t/$id.h5 /risen)"
[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 't' AND tool = 'waiting' AND key = 'fraction_risen'
	AND value BETWEEN 0 AND 1 AND n = 2")" = 3 ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE tool = 'waiting' AND key = 'median'")" = 3 ] &&
	ok waiting.db_rows || fail waiting.db_rows "$(q R/study.db "SELECT * FROM analysis WHERE tool = 'waiting'")"

# ---- figures ----
tool figures t --runs R
rc=$?
[ "$rc" -eq 0 ] && ok figures.exit || fail figures.exit "exit $rc: $(cat figures.err)"
[ ! -s figures.err ] && ok figures.quiet || fail figures.quiet "$(head -c 300 figures.err)"
png_ok $A/fig1.png && png_ok $A/fig3.png && png_ok $A/fig4.png && ok figures.png || fail figures.png "$(cat figures.out)"
[ "$(tail -n +2 $A/fig3_profile.csv | wc -l)" = $((6 * 80)) ] && [ -s $A/fig1_field.csv ] && [ -s $A/fig4_traj.csv ] &&
	ok figures.csv || fail figures.csv "$(wc -l $A/fig*.csv)"
grep -q '^5  *2  *2 ' figures.out && ok figures.table || fail figures.table "$(cat figures.out)"
[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 't' AND tool = 'figures' AND key = 'phi_max'")" = 6 ] &&
	ok figures.db_rows || fail figures.db_rows "$(q R/study.db "SELECT * FROM analysis WHERE tool = 'figures'")"
# the other tools' rows are untouched by this one
[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE tool = 'onset'")" = 30 ] && ok figures.keeps_other_tools ||
	fail figures.keeps_other_tools "onset rows changed"

# ---- hysteresis ----
tool hysteresis h --runs R --boot 40
rc=$?
H=R/h/analysis
[ "$rc" -eq 0 ] && ok hysteresis.exit || fail hysteresis.exit "exit $rc: $(cat hysteresis.err)"
[ ! -s hysteresis.err ] && ok hysteresis.quiet || fail hysteresis.quiet "$(head -c 300 hysteresis.err)"
grep -q '^radius_ratio=2 depth=1 ' hysteresis.out && ok hysteresis.table || fail hysteresis.table "$(cat hysteresis.out)"
# both branches present for both seeds, frequencies rising on the way up
[ "$(awk -F, 'NR > 1 { print $5 }' $H/hysteresis_periods.csv | sort -u | tr '\n' ' ')" = "down up " ] &&
	awk -F, 'NR > 1 && $5 == "up" { if (seen[$3] && $7 < last[$3]) bad = 1; seen[$3] = 1; last[$3] = $7 } END { exit bad }' $H/hysteresis_periods.csv &&
	ok hysteresis.branches || fail hysteresis.branches "$(head -n 5 $H/hysteresis_periods.csv)"
png_ok $H/hysteresis.png && [ -s $H/hysteresis_summary.csv ] && ok hysteresis.outputs || fail hysteresis.outputs "$(ls $H)"
[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 'h' AND tool = 'hysteresis'")" = 16 ] &&
	[ "$(q R/study.db "SELECT value FROM analysis WHERE campaign = 'h' AND key = 'seeds'")" = 2.0 ] &&
	ok hysteresis.db_rows || fail hysteresis.db_rows "$(q R/study.db "SELECT * FROM analysis WHERE tool = 'hysteresis'")"
# the fixed-frequency campaign has no ramps: a clear error, nothing stored
tool hysteresis t --runs R
rc=$?
[ "$rc" -eq 1 ] && grep -q 'no finished ramp run' hysteresis.err &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 't' AND tool = 'hysteresis'")" = 0 ] &&
	ok hysteresis.no_ramps || fail hysteresis.no_ramps "exit $rc: $(cat hysteresis.err)"

# ---- errors and help ----
for n in onset waiting figures hysteresis; do
	tool $n --help && grep -q "^usage: $n CAMPAIGN" $n.out && ok $n.help || fail $n.help "$(head -n 2 $n.out)"
	tool $n nosuch --runs R
	rc=$?
	[ "$rc" -eq 1 ] && grep -q "campaign 'nosuch'" $n.err && ok $n.unknown_campaign || fail $n.unknown_campaign "exit $rc: $(cat $n.err)"
	tool $n t --runs R --bogus 1
	[ $? -eq 1 ] && grep -q "^$n: --bogus: unknown option" $n.err && ok $n.bad_option || fail $n.bad_option "$(cat $n.err)"
done
tool onset t --db "$TMP/none/study.db"
rc=$?
[ "$rc" -eq 2 ] && grep -q 'cannot open database' onset.err && ok onset.missing_db || fail onset.missing_db "exit $rc: $(cat onset.err)"
tool onset t --runs R --band 0.7:0.2
[ $? -eq 1 ] && grep -q 'band' onset.err && ok onset.bad_band || fail onset.bad_band "$(cat onset.err)"
echo "# total: $((SECONDS - t0)) s"
finish
