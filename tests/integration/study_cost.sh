#!/usr/bin/env bash
# study_cost.sh - the cost before the start (docs/campaigns.md, "Cost before the
# start"): study run --dry-run prints the runs, simulated seconds and CPU time and runs
# and records nothing; the engine's rate is measured once into RUNS/.calibration and
# reused; study expand prints the same summary on stderr and keeps its table; a search
# is an upper bound; and the estimate meets the CPU the real run takes within a factor
# of 2 either way.
# tier: alone: compares a measured CPU time with an estimate
# tier: slow: a campaign run for real, its CPU measured, and the engine calibrated
. "$(dirname "$0")/lib.sh"
study_setup
[ -x /usr/bin/time ] || { fail setup "/usr/bin/time is needed to measure the run's CPU"; finish; }
cd "$TMP" || exit 1

# the paper bed without intruder, fast preset: the engine's work dominates the driver's
cat >c.campaign <<'E'
[campaign]
name = c
seed = 5
replicates = 2
[scene]
radius_ratio = 0
preset = fast
duration = 12
snapshots = no
traj_rate = 0
[grid]
frequency = 3
E
"$STUDY" run --dry-run c.campaign --runs R >dry.out 2>dry.err
rc=$?
[ "$rc" -eq 0 ] && grep -q '^  total: 2 runs, 24 s of simulated shaking, 2 packings to settle, CPU ' dry.err &&
	grep -q 'verlet, calibration measured now in [0-9.]* s on this machine' dry.err && ok dry.summary || fail dry.summary "exit $rc: $(cat dry.err)"
# nothing run, nothing recorded: only the calibration in the runs directory
[ ! -e R/study.db ] && [ ! -e R/c ] && [ "$(ls -A R)" = .calibration ] && [ ! -s dry.out ] &&
	[ "$(ls R/.calibration)" = "$(ls R/.calibration | grep -E '^[0-9a-f]{16}\.verlet\.txt$')" ] &&
	ok dry.nothing_run || fail dry.nothing_run "$(find R)"
"$STUDY" run --dry-run c.campaign --runs R 2>dry2.err
grep -Eq 'verlet, calibration measured 20[0-9:TZ-]* \([0-9]+ s ago\) on this machine' dry2.err && ok dry.cached || fail dry.cached "$(cat dry2.err)"
# how busy the machine was when it was measured: said, and a busy one named as such
grep -Eq 'verlet, calibration measured now in [0-9.]+ s on this machine, at load [0-9.]+ on [0-9]+ cores' dry.err &&
	grep -Eq 'verlet, calibration measured 20[^ ]* \([^)]*\) on this machine, at load [0-9.]+ on [0-9]+ cores' dry2.err && ok dry.load_said ||
	fail dry.load_said "$(grep rate: dry.err dry2.err)"
cal=$(ls R/.calibration/*.verlet.txt)
cp "$cal" cal.keep
awk -v n="$(nproc)" 'NR == 1 { $4 = n * 3 } { print }' cal.keep >"$cal"
"$STUDY" run --dry-run c.campaign --runs R 2>dry3.err
grep -q 'a busy machine: the rate may be slow (remove the file to measure again)' dry3.err && ok dry.busy_said ||
	fail dry.busy_said "$(grep rate: dry3.err)"
cp cal.keep "$cal"

# study expand: its table unchanged on stdout, the same summary on stderr
"$STUDY" expand c.campaign --runs R >exp.out 2>exp.err
[ "$(head -n 1 exp.out)" = "$(printf 'id\tcache_key\treplicate\tseed\tfrequency')" ] && [ "$(wc -l <exp.out)" = 3 ] &&
	ok expand.table || fail expand.table "$(cat exp.out)"
[ "$(grep '^  total' exp.err)" = "$(grep '^  total' dry2.err)" ] && ok expand.summary ||
	fail expand.summary "$(cat exp.err)"
# expand measures nothing: in a runs directory without the rate it says so and writes nothing
"$STUDY" expand c.campaign --runs fresh >exp2.out 2>exp2.err
grep -q '^  total: .*CPU not known yet' exp2.err && grep -q 'not measured on this machine yet' exp2.err && [ ! -e fresh ] &&
	ok expand.measures_nothing || fail expand.measures_nothing "$(cat exp2.err; ls -a fresh 2>&1)"

# a search: bounds, said so (2 replicates x a chain of at most 8 runs over [2.5, 3.2] to 0.02)
cat >o.campaign <<'E'
[campaign]
name = o
seed = 1
[scene]
radius_ratio = 0
preset = fast
duration = 60
flux = yes
traj_rate = 0
snapshots = no
[onset]
observable = flux
from = 2.5
to = 3.2
tolerance = 0.02
threshold = 2
band = 0.4:0.6
replicates = 2
E
"$STUDY" run --dry-run o.campaign --runs R 2>o.err
grep -q '^  total: at most 16 runs, at most 16 min of simulated shaking, at most 2 packings to settle, CPU at most ' o.err &&
	ok search.upper_bound || fail search.upper_bound "$(cat o.err)"
# a stop rule: the grid's 2 runs at their full 12 s at most, at stop_skip = 5 s at least
sed 's/^duration = 12$/duration = 12\nstop = flux\nflux = yes\nstop_skip = 5\nstop_flux_threshold = 1/' c.campaign >s.campaign
"$STUDY" run --dry-run s.campaign --runs R 2>s.err
grep -q '^  total: 2 runs, at most 24 s of simulated shaking (a stop rule may end runs earlier), 2 packings to settle, CPU at most ' s.err &&
	grep -q '^         (at least 2 runs, 10 s of simulated shaking, CPU [0-9.e+]* s, if no run fails)$' s.err &&
	ok stop.both_ends || fail stop.both_ends "$(cat s.err)"
# ... and the other end: 2 replicates x 6 bisections (no ends), no stop rule: 60 s each
grep -q '^         (at least 12 runs, 12 min of simulated shaking, CPU [0-9.e+]* [a-z]*, if no run fails)$' o.err &&
	ok search.lower_bound || fail search.lower_bound "$(cat o.err)"
[ ! -e R/o ] && [ ! -e R/study.db ] && ok search.nothing_run || fail search.nothing_run "$(find R)"
# a search where the rate is not known: no bound claimed on a CPU time it cannot give
"$STUDY" expand o.campaign --runs fresh >/dev/null 2>o2.err
grep -q '^  total: at most 16 runs, .*, CPU not known yet$' o2.err && ok search.cpu_unknown ||
	fail search.cpu_unknown "$(cat o2.err)"

# the real run: its CPU (engine, driver and GNU parallel) against the estimate
est=$(sed -n 's/^  total: .*CPU \([0-9.e+]*\) s$/\1/p' dry2.err)
/usr/bin/time -f '%U %S' -o cpu.txt "$STUDY" run c.campaign --runs R --jobs 1 >run.log 2>&1
rc=$?
cpu=$(awk '{ print $1 + $2 }' cpu.txt)
[ "$rc" -eq 0 ] && ok run.exit || fail run.exit "exit $rc: $(tail -c 400 run.log)"
echo "# estimated CPU ${est:-?} s, measured $cpu s"
awk -v e="${est:-0}" -v m="$cpu" 'BEGIN { exit !(e > 0 && m / e >= 0.5 && m / e <= 2) }' &&
	ok run.within_factor_2 || fail run.within_factor_2 "estimated ${est:-none} s, measured $cpu s CPU"
# --dry-run of what is done: nothing remains; of the campaign extended: only the new runs
"$STUDY" run --dry-run c.campaign --runs R 2>dd.err
grep -q "^study: c: 2 of 2 runs are done already" dd.err && grep -q "^study: c: nothing remains to run" dd.err &&
	! grep -q 'total:' dd.err && ok dry.nothing_remains || fail dry.nothing_remains "$(cat dd.err)"
sed 's/^frequency = 3$/frequency = 3, 3.5/' c.campaign >cx.campaign
"$STUDY" run --dry-run cx.campaign --runs R 2>dx.err
grep -q "^study: c: 2 of 4 runs are done already (their files are in R/c): the cost below is of the 2 that remain" dx.err &&
	grep -q '^  total: 2 runs, 24 s of simulated shaking' dx.err && ok dry.what_remains || fail dry.what_remains "$(cat dx.err)"
# ... at the rate its 2 finished runs measured, not the calibration's: their CPU less
# their own settling at the calibration's settling rate (each replicate has its own
# packing: no run started from the cache), over their grains x steps, from the database
settle=$(awk 'NR == 1 { print $2 }' "$cal")
want=$(q R/study.db "SELECT TOTAL(a.cpu_seconds) FROM attempt a WHERE a.campaign = 'c'")' '$(q R/study.db "SELECT
	TOTAL((SELECT value FROM param WHERE campaign = 'c' AND run = s.run AND key = 'n_grains') * s.status_time /
	(SELECT value FROM param WHERE campaign = 'c' AND run = s.run AND key = 'dt')), SUM(r.from_cache) FROM result s
	JOIN run r ON r.campaign = s.campaign AND r.id = s.run WHERE s.campaign = 'c'")
want=$(awk -v w="$want" -v k="$settle" 'BEGIN { split(w, a, "[ |]"); if (a[3] != 0) exit; printf "%.3g", (a[1] - 2 * 950 * k) / a[2] }')
grep -q "^  rate: $want CPU s per grain-step, [0-9.e+-]* CPU s per grain settled; verlet, rate from 2 finished runs of this campaign (their CPU per grain-step, in R/study.db); settling at the rate of the calibration measured 20" dx.err &&
	ok dry.rate_from_runs || fail dry.rate_from_runs "want $want: $(grep rate: dx.err)"
# study status's ETA over a made-up search (beside c, in the database its run made): one run done in 60 s, one pending; the chain
# over [0, 1] to 0.25 takes at most 4 runs; replicate 1 has 2 (its pending one included),
# and the group may get 2 more replicates: 1 + (4 - 2) + 2 x 4 = 11 runs, 11 min at most
sqlite3 R/study.db "INSERT INTO campaign(name, description) VALUES ('f', 'made up');
INSERT INTO run(campaign, id, state, started) VALUES ('f', 'a', 'done', '2026-01-01T00:00:00Z'), ('f', 'b', 'pending', NULL);
INSERT INTO attempt(campaign, run, n, status, finished) VALUES ('f', 'a', 1, 'ok', '2026-01-01T00:01:00Z');
INSERT INTO onset_search(campaign, freq_from, freq_to, tolerance, replicates, max_replicates, state)
	VALUES ('f', 0, 1, 0.25, 'auto', 4, 'searching');
INSERT INTO onset_group(campaign, grp, point, replicates, runs, state) VALUES ('f', 'all', 0, 2, 3, 'searching');
INSERT INTO onset_replicate(campaign, grp, replicate, state, runs) VALUES ('f', 'all', 1, 'searching', 2), ('f', 'all', 2, 'found', 1);" 2>sql.err
"$STUDY" status f --runs R >st.out 2>&1
grep -q '^  ETA: at most 11.0 min for the whole campaign (at most 11 runs to go) at the pace of the last runs' st.out &&
	ok eta.whole_search || fail eta.whole_search "$(cat sql.err st.out)"
# the same runs without a search: only what is pending, no bound claimed
sqlite3 R/study.db "DELETE FROM onset_search; DELETE FROM onset_group; DELETE FROM onset_replicate"
"$STUDY" status f --runs R >st2.out 2>&1
grep -q '^  ETA: about 60 s at the pace of the last runs' st2.out && ! grep -q 'at most' st2.out &&
	ok eta.grid_unchanged || fail eta.grid_unchanged "$(cat st2.out)"
# an attempt of b that was interrupted after 6 s is no run finished: the pace stays one
# run a minute (counted, it would promise 30 s)
sqlite3 R/study.db "UPDATE run SET started = '2026-01-01T00:00:00Z' WHERE campaign = 'f' AND id = 'b';
INSERT INTO attempt(campaign, run, n, status, finished) VALUES ('f', 'b', 1, 'interrupted', '2026-01-01T00:00:06Z')"
"$STUDY" status f --runs R >st2i.out 2>&1
grep -q '^  ETA: about 60 s at the pace of the last runs' st2i.out && ok eta.interrupted_not_finished ||
	fail eta.interrupted_not_finished "$(grep ETA st2i.out)"
# the progress line's (status --watch) ETA of a made-up search covers the search, not the
# round: one run of 30 s done at 1 simulated s per s (loop and span), one pending (this
# round: 30 s); replicate 1's bracket [0, 1] to 0.25 needs ceil(log2(4)) - 1 = 1 bisection
# after this round's run (30 s more, expected); at most (4 - 2) + 2 chains x 4 = 10 runs
# in 10 rounds, one at a time: 30 + 10 x 30 s = 5.5 min
sqlite3 R/study.db "INSERT INTO campaign(name, description) VALUES ('g', 'made up');
INSERT INTO run(campaign, id, state, started, finished) VALUES ('g', 'a', 'done', '2026-01-01T00:00:00Z', '2026-01-01T00:00:30Z'),
	('g', 'b', 'pending', NULL, NULL);
INSERT INTO param(campaign, run, key, value) VALUES ('g', 'a', 'duration', 30.0), ('g', 'b', 'duration', 30.0);
INSERT INTO result(campaign, run, status_time, wall_seconds) VALUES ('g', 'a', 30, 30);
INSERT INTO onset_search(campaign, freq_from, freq_to, tolerance, replicates, max_replicates, state)
	VALUES ('g', 0, 1, 0.25, 'auto', 4, 'searching');
INSERT INTO onset_group(campaign, grp, point, replicates, runs, state) VALUES ('g', 'all', 0, 2, 3, 'searching');
INSERT INTO onset_replicate(campaign, grp, replicate, state, runs) VALUES ('g', 'all', 1, 'searching', 2), ('g', 'all', 2, 'found', 1)" 2>sqlg.err
"$STUDY" status g --runs R --watch --interval 0.1 >w.out 2>&1
grep -q '^g: 1/2 finished (50%): .*; ETA this round: 30 s; search: about 60 s (1 more round expected, 1 more run, 1 at a time), at most 5.5 min (10 more runs) at 1 simulated s per s from the last runs to finish$' w.out &&
	ok watch.eta_whole_search || fail watch.eta_whole_search "$(cat sqlg.err w.out)"
# a bracket already at the tolerance after this round's run: no more rounds expected
sqlite3 R/study.db "UPDATE onset_replicate SET lo = 0.5, hi = 0.75 WHERE campaign = 'g' AND replicate = 1"
"$STUDY" status g --runs R --watch --interval 0.1 >w2.out 2>&1
grep -q 'ETA this round: 30 s; search: about 30 s (0 more rounds expected, 0 more runs, 1 at a time), at most 5.5 min' w2.out &&
	ok watch.eta_search_last_round || fail watch.eta_search_last_round "$(cat w2.out)"
# replicates = auto: whether a batch more is needed the intervals say: only the bound
# (2 of at most 4 replicates in batches of 3: up to 1 more round of 2 runs, one at a time: 30 + 2 x 30 s)
sqlite3 R/study.db "DELETE FROM onset_search WHERE campaign = 'g'; INSERT INTO auto_point(campaign, point, grp, replicates,
	max_replicates, batch, state) VALUES ('g', 0, 'all', 2, 4, 3, 'running')"
"$STUDY" status g --runs R --watch --interval 0.1 >w3.out 2>&1
grep -q 'ETA this round: 30 s; search: at most 90 s (up to 1 more round, 2 more runs, if the intervals need them; 1 at a time) at 1 simulated s per s' w3.out &&
	ok watch.eta_auto_bound || fail watch.eta_auto_bound "$(cat w3.out)"
# replicates = auto: a point with 2 of at most 5 replicates: 1 pending + 3 = 4 runs
sqlite3 R/study.db "INSERT INTO auto_point(campaign, point, grp, replicates, max_replicates, state)
	VALUES ('f', 0, 'all', 2, 5, 'running')"
"$STUDY" status f --runs R >st3.out 2>&1
grep -q '^  ETA: at most 4.0 min for the whole campaign (at most 4 runs to go)' st3.out &&
	ok eta.whole_auto || fail eta.whole_auto "$(cat st3.out)"
finish
