#!/usr/bin/env bash
# analysis_pool.sh - analysis across campaigns: three tiny campaigns at one amplitude
# each (two in one runs directory, one in its own), pooled by bin/onset into groups by
# amplitude (a key no campaign sweeps but that differs between them), each group naming
# its campaign; difference intervals between every pair of amplitudes (--diff; --ref one
# against the others; --where a selection), a power-law fit
# against the amplitude with the Gamma and v exponents judged (--fit), a figure against
# Gamma (--axis gamma); waiting pools too; and the usage errors (a campaign not in its
# database, a --diff key that is no grouping key, a bad --axis).
# tier: slow: three small campaigns
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
cd "$TMP" || exit 1
S="$(tiny_scene n_grains=40 width=16 radius_ratio=-)
flux = yes
radius_ratio = 0
duration = 1"
camp() { printf '[campaign]\nname = %s\nseed = %s\nreplicates = 2\n[scene]\n%s\namplitude = %s\n[grid]\nfrequency = %s\n' "$1" "$2" "$S" "$3" "$4" >"$1.campaign"; }
camp a 3 0.5 '4, 6, 8'
camp b 4 1 '3, 5, 7'
camp c 5 2 '2, 3.5, 5'
# run by the release engine (lib.sh's data_driver_setup): the pooling tools are under test,
# the engine only makes the files they read
data_driver_setup
"$DATA_STUDY" run a.campaign --runs R --jobs 2 --no-progress >a.log 2>&1 &&
	"$DATA_STUDY" run b.campaign --runs R --jobs 2 --no-progress >b.log 2>&1 &&
	"$DATA_STUDY" run c.campaign --runs R2 --jobs 2 --no-progress >c.log 2>&1 &&
	ok pool.setup || { fail pool.setup "$(tail -c 300 a.log b.log c.log)"; finish; }

"$BINDIR/onset" a b R2/c --runs R --boot 100 --diff amplitude --fit amplitude --axis gamma >o.out 2>o.err
rc=$?
[ "$rc" -eq 0 ] && [ ! -s o.err ] && ok pool.onset_exit || fail pool.onset_exit "exit $rc: $(cat o.err)"
# three groups by amplitude, each from its campaign, the key said to differ between them
grep -q '^radius_ratio=0 depth=1 amplitude=0.5 ' o.out && grep -q '^radius_ratio=0 depth=1 amplitude=2 ' o.out &&
	grep -q '^# 3 campaigns pooled.*: a (R/study.db), b (R/study.db), c (R2/study.db)' o.out &&
	grep -q '^# grouped also by amplitude: it differs between the campaigns' o.out &&
	grep -Eq '^# radius_ratio=0 depth=1 amplitude=2 +c$' o.out && ok pool.groups_by_parameters ||
	fail pool.groups_by_parameters "$(cat o.out)"
A=R/a+b+c/analysis
[ "$(tail -n +2 $A/onset_runs.csv | wc -l)" = 18 ] && ok pool.all_runs || fail pool.all_runs "$(ls $A)"
# the seeds of different campaigns are different bootstrap units: 2 per group
[ "$(sqlite3 R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 'a+b+c' AND key = 'seeds' AND value = 2")" = 3 ] &&
	ok pool.stored_in_first_database || fail pool.stored_in_first_database "$(sqlite3 R/study.db "SELECT grp, key, value FROM analysis WHERE key = 'seeds'")"
# --diff: every pair (1 - 0.5, 2 - 0.5, 2 - 1) per estimate, each with an interval and a verdict on 0
[ "$(grep -Ec '(inside|excluded)$' o.out)" -ge 3 ] && [ "$(tail -n +2 $A/onset_diff.csv | wc -l)" = 6 ] &&
	[ "$(awk -F, 'NR > 1 && $5 == "threshold_f" { print $3 "-" $4 }' $A/onset_diff.csv | sort | tr '\n' ' ')" = "0.5-1 0.5-2 1-2 " ] &&
	[ "$(sqlite3 R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 'a+b+c' AND key = 'diff_threshold_f'")" = 3 ] &&
	ok pool.diff_every_pair || fail pool.diff_every_pair "$(cat o.out; cat $A/onset_diff.csv)"
# --ref 1: each against amplitude 1 (0.5 - 1 and 2 - 1); --where: only the runs at amplitude 0.5 and 1
"$BINDIR/onset" a b R2/c --runs R --boot 50 --no-store --no-plot --diff amplitude --ref 1 >r.out 2>r.err &&
	[ "$(awk -F, 'NR > 1 && $5 == "threshold_f" { print $3 "-" $4 }' $A/onset_diff.csv | sort | tr '\n' ' ')" = "1-0.5 1-2 " ] &&
	grep -q "minus at amplitude = 1 (--ref" r.out && ok pool.diff_ref || fail pool.diff_ref "$(cat r.out r.err; cat $A/onset_diff.csv)"
"$BINDIR/onset" a b R2/c --runs R --boot 50 --no-store --no-plot --diff amplitude --ref 3 >r3.out 2>r3.err &&
	grep -q "# no group with usable runs at amplitude = 3 (--ref)" r3.out && ok pool.diff_ref_absent ||
	fail pool.diff_ref_absent "$(cat r3.out r3.err)"
"$BINDIR/onset" a b --runs R --boot 50 --no-store --no-plot --where amplitude=1 >wh.out 2>wh.err &&
	[ "$(tail -n +2 R/a+b/analysis/onset_runs.csv | wc -l)" = 6 ] && ! grep -q '^radius_ratio=0 depth=1 amplitude=0.5 ' wh.out &&
	ok pool.where || fail pool.where "$(cat wh.out wh.err)"
"$BINDIR/onset" a --runs R --no-store --where nosuchkey=1 >wm.out 2>wm.err
[ $? -eq 1 ] && grep -q "where: 'nosuchkey' is not a parameter of campaign 'a'" wm.err && ok pool.where_unknown ||
	fail pool.where_unknown "$(cat wm.err)"
"$BINDIR/onset" a --runs R --no-store --where mu=1 >wn.out 2>wn.err
[ $? -eq 1 ] && grep -q "no finished fixed-frequency run with flux = yes in R/study.db with mu = 1" wn.err && ok pool.where_none ||
	fail pool.where_none "$(cat wn.err)"
"$BINDIR/onset" a --runs R --no-store --ref 1 >rf.out 2>rf.err
[ $? -eq 1 ] && grep -q -- "--ref: only with --diff KEY" rf.err && ok pool.ref_without_diff || fail pool.ref_without_diff "$(cat rf.err)"
# --fit: p of the threshold crossing over 3 points, with the two reference exponents judged
grep -Eq '^radius_ratio=0 depth=1 +threshold_f +3 .*Γ const \(p = -1/2\) (excluded|inside), v const \(p = -1\) (excluded|inside)' o.out &&
	[ "$(sqlite3 R/study.db "SELECT COUNT(*) FROM analysis WHERE key = 'fit_p_threshold_f' AND n = 3 AND value < 0")" = 1 ] &&
	ok pool.fit || fail pool.fit "$(cat o.out; cat $A/onset_fit.csv)"
grep -q "set xlabel 'peak acceleration Γ'" $A/onset.gp && [ -s $A/onset.png ] && ok pool.axis_gamma ||
	fail pool.axis_gamma "$(grep xlabel $A/onset.gp)"

"$BINDIR/waiting" a b --runs R >w.out 2>w.err
grep -q "campaigns a+b: no finished run with an intruder" w.err && ok pool.waiting_pools ||
	fail pool.waiting_pools "$(cat w.err)"
"$BINDIR/onset" a R2/nope --runs R --no-store >e1.out 2>e1.err
[ $? -eq 1 ] && grep -q "campaign 'nope' is not in R2/study.db" e1.err && ok pool.unknown_campaign ||
	fail pool.unknown_campaign "$(cat e1.err)"
"$BINDIR/onset" a b --runs R --no-store --boot 20 --diff mu >e2.out 2>e2.err
[ $? -eq 1 ] && grep -q "'mu' is not a grouping key (they are: radius_ratio, depth, amplitude" e2.err &&
	ok pool.diff_not_a_key || fail pool.diff_not_a_key "$(cat e2.err)"
"$BINDIR/onset" a --runs R --no-store --axis speed >e3.out 2>e3.err
[ $? -eq 1 ] && grep -q "expected one of frequency|gamma|velocity, got 'speed'" e3.err && ok pool.bad_axis ||
	fail pool.bad_axis "$(cat e3.err)"
finish
