#!/usr/bin/env bash
# study_slurm_search.sh - an [onset] search through `study submit --slurm` on a real
# one-node Slurm (lib.sh's slurm_cluster_up): each round one job array, the next round
# submitted by a planning job that depends on it (docs/cluster.md, "Searches on Slurm").
# The first round is held and cancelled: its planning job finds that the round finished
# no run and stops (exit 7, said in its log, nothing submitted); `study submit` again goes
# on, and the planning jobs carry the search to its end with no process on the login
# node. The onset, every replicate's bracket and chain, and the export equal those of
# `study run` on the same campaign, the run files bit-identical.
# tier: slow: a one-node Slurm cluster started, a search of several rounds as job arrays
. "$(dirname "$0")/lib.sh"
study_setup
T0=$SECONDS
slurm_cluster_up
cd "$TMP" || exit 1

# jobs of this user still known to the scheduler (array tasks and planning jobs)
queued() { squeue --noheader --array --format=%i 2>/dev/null; }
idle() { [ -z "$(queued)" ]; }

# The search of study_adaptive.sh with two replicates: 60 grains, an intruder of 1.5 mean
# radii, 2 s of the fast preset ended at the rise (its trajectory kept: the files are
# compared); 5 to 9 Hz to 0.5 Hz: a few rounds
NAME=so
cat >s.campaign <<C
[campaign]
name = $NAME
seed = 11
[scene]
preset = fast
$(tiny_scene width=16 radius_ratio=1.5 depth=-)
amplitude = 1
duration = 2
stop = risen
traj_rate = 20
snapshots = no
[onset]
observable = rise
from = 5
to = 9
tolerance = 0.5
replicates = 2
C

# --- the reference: study run, here ---
t=$SECONDS
"$STUDY" run s.campaign --runs "$TMP/L" --jobs 2 >local.log 2>&1 || fail local.run "$(tail -c 400 local.log)"
echo "# local study run: $((SECONDS - t)) s, $(grep -c 'onset round' local.log) rounds"

# --- dry run: the first round's array and its planning job, nothing submitted ---
"$STUDY" submit s.campaign --slurm --runs "$TMP/S" --dry-run >dry.out 2>dry.err
rc=$?
[ "$rc" -eq 0 ] && grep -q "onset round: 2 runs, 1 of 1 group searching" dry.err &&
	grep -q '^# after the array, its planning job; .*/slurm/plan.sh would hold:' dry.out &&
	grep -Eq "^sbatch --dependency=afterany:JOB --job-name=$NAME.plan .*--time=[0-9]+ .*plan.sh'? JOB$" dry.out &&
	grep -Eq "^exec .*/study submit .*/s.campaign --slurm --runs .* --after \"\\\$1\"$" dry.out && idle &&
	[ ! -e "S/$NAME/slurm/plan.sh" ] && ok search.dry_run || fail search.dry_run "exit $rc: $(cat dry.err; tail -n 6 dry.out)"

# --- the first round, held; its planning job waits for it ---
DB=S/study.db
"$STUDY" submit s.campaign --slurm --runs "$TMP/S" --sbatch-args=--hold >sub1.log 2>&1
rc=$?
J1=$(q $DB "SELECT job_id FROM slurm_job WHERE campaign = '$NAME'")
P1=$(sed -n 's/.*planning job \([0-9]*\) submits the next round when job .* has ended.*/\1/p' sub1.log)
dep=$(scontrol show job "$P1" 2>/dev/null | grep -o 'Dependency=[^ ]*')
[ "$rc" -eq 0 ] && [ -n "$J1" ] && [ -n "$P1" ] && [ "$dep" = "Dependency=afterany:${J1}_*(unfulfilled)" ] &&
	grep -q "submitted 2 runs in 2 tasks as Slurm job $J1" sub1.log && [ -x "S/$NAME/slurm/plan.sh" ] &&
	grep -q -- "--after \"\$1\"" "S/$NAME/slurm/plan.sh" && ok search.first_round_and_planner ||
	fail search.first_round_and_planner "exit $rc, job '$J1', planner '$P1' ($dep): $(cat sub1.log)"
# a second submit while the round is queued submits nothing
"$STUDY" submit s.campaign --slurm --runs "$TMP/S" >sub_busy.log 2>&1
rc=$?
[ "$rc" -eq 0 ] && grep -q "a round is queued or running in Slurm (2 runs)" sub_busy.log &&
	[ "$(q $DB "SELECT COUNT(*) FROM slurm_job")" = 1 ] && ok search.submit_while_queued ||
	fail search.submit_while_queued "exit $rc: $(cat sub_busy.log)"

# --- the round cancelled: its planning job stops the search, and says so ---
scancel "$J1"
scontrol release "$P1"
poll_until 120 idle || fail search.planner_ran "still queued: $(queued)"
PLOG="S/$NAME/slurm/logs/plan_$P1.out"
state=$(scontrol show job "$P1" 2>/dev/null | grep -o 'ExitCode=[0-9:]*' | head -n 1)
grep -q "the round of Slurm job $J1 finished no run" "$PLOG" 2>/dev/null &&
	[ "$(q $DB "SELECT COUNT(*) FROM slurm_job")" = 1 ] && { [ -z "$state" ] || [ "$state" = ExitCode=7:0 ]; } &&
	ok search.cancelled_round_stops || fail search.cancelled_round_stops "$state: $(cat "$PLOG" 2>&1 | tail -n 5)"

# --- submit again: the planning jobs carry the search to its end ---
t=$SECONDS
"$STUDY" submit s.campaign --slurm --runs "$TMP/S" >sub2.log 2>&1
rc=$?
[ "$rc" -eq 0 ] && grep -q "onset round: 2 runs" sub2.log && grep -q "planning job [0-9]* submits the next round" sub2.log &&
	ok search.resubmitted || fail search.resubmitted "exit $rc: $(cat sub2.log)"
# done: the last planning job found no run to submit
done_log() { grep -l "the search has no run to submit" S/$NAME/slurm/logs/plan_*.out 2>/dev/null | head -n 1; }
poll_until 600 eval '[ -n "$(done_log)" ] && idle' || fail search.ends "still queued: $(queued); $(tail -n 3 S/$NAME/slurm/logs/plan_*.out)"
rounds=$(q $DB "SELECT COUNT(*) FROM slurm_job")
echo "# the search on Slurm: $((SECONDS - t)) s, $rounds arrays (the cancelled one too)"
LAST=$(done_log)
[ -n "$LAST" ] && grep -q "$NAME: all: onset .* Hz, 95% interval .*: done" "$LAST" && [ "$rounds" -ge 3 ] &&
	[ "$(q $DB "SELECT COUNT(*) FROM run WHERE state <> 'done'")" = 0 ] && ok search.planners_finish ||
	fail search.planners_finish "$rounds arrays: $(cat "$LAST" 2>&1 | tail -n 4)"

# --- the same search as study run's ---
search_of() { # DB: each replicate's state, bracket and chain, then the group's onset
	q "$1" "SELECT r.replicate, r.state, printf('%g', r.lo), printf('%g', r.hi),
		(SELECT group_concat(f, ' ') FROM (SELECT printf('%g', frequency) AS f FROM onset_run o
		 WHERE o.campaign = r.campaign AND o.replicate = r.replicate ORDER BY step))
		FROM onset_replicate r WHERE r.campaign = '$NAME' ORDER BY r.replicate"
	q "$1" "SELECT grp, state, printf('%.6g %.6g %.6g', estimate, ci_lo, ci_hi), runs FROM onset_group WHERE campaign = '$NAME'"
}
search_of L/study.db >L.search
search_of S/study.db >S.search
[ "$(wc -l <L.search)" = 3 ] && cmp -s L.search S.search && ok search.same_onset_as_study_run ||
	fail search.same_onset_as_study_run "local $(tr '\n' ';' <L.search) slurm $(tr '\n' ';' <S.search)"
"$STUDY" status "$NAME" --runs "$TMP/S" >status.out 2>&1
grep -q "onset search (done; " status.out && ok search.status_done || fail search.status_done "$(head -n 20 status.out)"
# the export without the columns that say when, where and how (tests/strip_how.sh)
. "$REPO/tests/strip_how.sh"
"$STUDY" export "$NAME" --runs "$TMP/L" >L.csv && "$STUDY" export "$NAME" --runs "$TMP/S" >S.csv &&
	strip_how L.csv | sort >L.cmp && strip_how S.csv | sort >S.cmp &&
	[ "$(wc -l <L.cmp)" -ge 5 ] && cmp -s L.cmp S.cmp && ok search.export_same_as_local ||
	fail search.export_same_as_local "$(diff L.cmp S.cmp | head -n 4 | cut -c1-300)"
same=0 n=0
for f in L/$NAME/*.h5; do
	n=$((n + 1))
	same_output "$f" "S/$NAME/$(basename "$f")" && same=$((same + 1))
done
[ "$n" -ge 4 ] && [ "$same" = "$n" ] && ok search.files_bit_identical || fail search.files_bit_identical "$same of $n run files identical"
echo "# study_slurm_search.sh: $((SECONDS - T0)) s"
finish
