#!/usr/bin/env bash
# study_slurm.sh - `study submit --slurm` against a real Slurm: a one-node cluster
# started here (scripts/slurm_local.sh: munged, slurmctld, slurmd under $TMP, own key,
# socket and ports), a small campaign submitted as a job array (throttle, two runs per
# task, extra sbatch arguments), one task cancelled with scancel while its run shakes
# (the engine must checkpoint), `study submit` again (only the runs not done go, the
# stopped one resumes), and the export equal to an uninterrupted local `study run`
# of the same campaign, the run files bit-identical. Skips only where Slurm cannot
# be installed.
# tier: slow: a one-node Slurm cluster started, a job array run, cancelled and resubmitted
. "$(dirname "$0")/lib.sh"
study_setup
T0=$SECONDS
slurm_cluster_up
cd "$TMP" || exit 1

# the tasks of job $1 still known to the scheduler
tasks_of() { squeue --noheader --array --jobs="$1" --format=%i 2>/dev/null; }
drained() { [ -z "$(tasks_of "$1")" ]; }

# Four runs of a few seconds (two frequencies x two replicates: two shared packings);
# a checkpoint every tenth of the run.
NAME=sl
cat >s.campaign <<C
[campaign]
name = $NAME
seed = 7
replicates = 2
[scene]
$(tiny_scene n_grains=50 depth=-)
amplitude = 1
duration = 6
traj_rate = 20
[grid]
frequency = 3, 4
C

# --- the command line ---
"$STUDY" submit --help >help.out 2>&1 && grep -q -- "--runs-per-task" help.out && grep -q -- "--throttle" help.out &&
	grep -q -- "--sbatch-args" help.out && ok submit.help || fail submit.help "$(head -n 3 help.out)"
"$STUDY" submit s.campaign --runs S >noslurm.out 2>&1
[ $? -eq 1 ] && grep -q -- "--slurm" noslurm.out && ok submit.needs_slurm || fail submit.needs_slurm "$(cat noslurm.out)"
"$STUDY" submit s.campaign --slurm --runs S --sbatch-args="--array=0-1" >bad.out 2>&1
[ $? -eq 1 ] && grep -q "sets --array itself" bad.out && [ -z "$(squeue --noheader)" ] && ok submit.refuses_array ||
	fail submit.refuses_array "$(cat bad.out)"
"$STUDY" submit s.campaign --slurm --runs S --throttle 0 >bad.out 2>&1
[ $? -eq 1 ] && grep -q "throttle" bad.out && ok submit.bad_throttle || fail submit.bad_throttle "$(cat bad.out)"

# --- the reference: the same campaign, uninterrupted, here ---
t=$SECONDS
"$STUDY" run s.campaign --runs "$TMP/L" --jobs 2 >local.log 2>&1 || fail local.run "$(tail -c 400 local.log)"
echo "# local study run: $((SECONDS - t)) s"

# --- submit --dry-run: the script, the task lines and the sbatch command with the time
# limit from the cost model (no --time given); nothing submitted, no task file, no script ---
"$STUDY" submit s.campaign --slurm --runs "$TMP/S" --throttle 2 --runs-per-task 2 --dry-run >dry.out 2>dry.err
rc=$?
mins=$(sed -n 's/^study: .*: --time=\([0-9]*\) min: the longest task.s runs take \([0-9]*\) CPU s at this machine.s measured rate, times 3 .*/\1 \2/p' dry.err)
[ "$rc" -eq 0 ] && grep -q '^# study submit --dry-run: nothing submitted' dry.out && grep -q '^#!/bin/bash' dry.out &&
	[ "$(grep -c '^[cr]:' dry.out)" = 2 ] && [ "$(grep -o ' r:' dry.out | wc -l)" -ge 2 ] &&
	grep -Eq "^sbatch --array=0-1%2 --job-name=$NAME '?--output=.*'? --time=${mins% *} .*/slurm/array.sh'? .*/slurm/tasks-N.txt'?$" dry.out &&
	awk -v m="$mins" 'BEGIN { split(m, v, " "); exit !(v[1] >= 5 && v[1] >= v[2] * 3 / 60) }' &&
	[ -z "$(q S/study.db "SELECT job_id FROM slurm_job")" ] && ! ls S/$NAME/slurm/tasks-*.txt S/$NAME/slurm/array.sh >/dev/null 2>&1 &&
	ok submit.dry_run || fail submit.dry_run "exit $rc, time '$mins': $(cat dry.err; tail -n 4 dry.out)"

# --- submit: 4 runs, 2 per task, at most 2 tasks at once, extra sbatch options (--hold:
# the array waits for scontrol release, so that no run starts before the test watches) ---
t=$SECONDS
"$STUDY" submit s.campaign --slurm --runs "$TMP/S" --throttle 2 --runs-per-task 2 \
	--sbatch-args="--comment=shakebox-test --time=10 --hold" >sub1.log 2>&1
rc=$?
DB=S/study.db
J1=$(q $DB "SELECT job_id FROM slurm_job WHERE campaign = '$NAME'")
[ "$rc" -eq 0 ] && [ -n "$J1" ] && grep -q "submitted 4 runs in 2 tasks as Slurm job $J1 (--array=0-1%2)" sub1.log &&
	ok submit.first || fail submit.first "exit $rc: $(cat sub1.log)"
# the array as Slurm has it: throttle, the extra options, the one script, the task file
info=$(scontrol show job "$J1" 2>&1)
echo "$info" | grep -q "ArrayTaskThrottle=2" && echo "$info" | grep -q "Comment=shakebox-test" &&
	echo "$info" | grep -q "Command=$TMP/S/$NAME/slurm/array.sh $TMP/S/$NAME/slurm/tasks-1.txt" &&
	ok submit.sbatch_options || fail submit.sbatch_options "$(echo "$info" | grep -E 'Throttle|Comment|Command')"
[ "$(wc -l <S/$NAME/slurm/tasks-1.txt)" = 2 ] && [ "$(grep -o 'r:' S/$NAME/slurm/tasks-1.txt | wc -l)" = 4 ] &&
	[ "$(q $DB "SELECT COUNT(*) || ' ' || COUNT(DISTINCT array_index) FROM slurm_task WHERE job_id = $J1")" = "4 2" ] &&
	ok submit.two_per_task || fail submit.two_per_task "$(cat S/$NAME/slurm/tasks-1.txt)"
# every run's argument file written here, before any node runs it
[ "$(ls S/$NAME/jobs/*.args | wc -l)" = 4 ] && ok submit.args_written || fail submit.args_written "$(ls S/$NAME/jobs)"

# --- scancel a task whose run is shaking: the engine must write a checkpoint ---
# is_shaking ID: the run has written a checkpoint but no output yet
is_shaking() { [ -e "S/$NAME/$1.h5.ckpt" ] && [ ! -e "S/$NAME/$1.h5" ]; }
# interrupted JOB: the runs the job's tasks left interrupted
interrupted() {
	q $DB "SELECT s.run FROM slurm_task s JOIN attempt a ON a.campaign = s.campaign AND a.run = s.run
		AND a.n = s.attempt WHERE s.job_id = $1 AND a.status = 'interrupted' AND a.exit_code = 7"
}
# The moment is a state, not a time: the engine of a task's first run, found shaking, is
# stopped (SIGSTOP) before the scancel, so that it cannot end (and its task start its
# second run) while the signal is on its way; it goes on once the SIGTERM is pending.
# The runs last a few seconds: the poll starts no process until it has found one
# (is_shaking and engine_of are builtins), so that a loaded machine cannot step over it.
# The first run of each task, from the task file (r:ID words in order)
FIRST=()
while read -r line; do
	id=""
	for w in $line; do case $w in r:*) id=${w#r:}; break ;; esac; done
	FIRST+=("$id")
done <"S/$NAME/slurm/tasks-1.txt"
# hold_shaking: IDX, busy (the run) and held (its engine's pid) of a task whose first
# run is shaking, its engine stopped
hold_shaking() {
	local i
	for i in "${!FIRST[@]}"; do
		is_shaking "${FIRST[i]}" && engine_of "${FIRST[i]}" || continue
		kill -STOP "$REPLY" 2>/dev/null || continue
		# stopped after it wrote its output (on its way out): let it go, look again
		if ! is_shaking "${FIRST[i]}"; then
			kill -CONT "$REPLY"
			continue
		fi
		IDX=$i busy=${FIRST[i]} held=$REPLY
		return 0
	done
	return 1
}
held=""
scontrol release "$J1" || fail scancel.setup "scontrol release $J1: exit $?"
poll_until 300 eval 'hold_shaking || drained "$J1"'
if [ -z "$held" ]; then
	fail scancel.setup "no task's first run was seen shaking before the array ended: $(squeue --array 2>&1 | tail -n 3)"
	finish
fi
echo "# run $busy of task ${J1}_$IDX shaking after $((SECONDS - t)) s, its engine $held stopped: scancel ${J1}_$IDX"
# while a task runs, study run refuses: it would run its runs a second time (the held
# engine keeps the array running)
"$STUDY" run s.campaign --runs "$TMP/S" >busy.log 2>&1
rc=$?
[ "$rc" -eq 4 ] && grep -q "queued or running in Slurm" busy.log && ok run.refuses_while_queued ||
	fail run.refuses_while_queued "exit $rc: $(tail -n 3 busy.log)"
# as a user cancels: SIGTERM to every process of the task, SIGKILL after KillWait (30 s)
scancel "${J1}_$IDX"
# (Slurm sends SIGCONT before SIGTERM; should it not, the held engine goes on once the
# SIGTERM waits for it)
poll_until 30 eval 'term_pending $held || ! kill -0 $held 2>/dev/null' ||
	fail scancel.signal_sent "no SIGTERM reached engine $held within 30 s"
kill -CONT "$held" 2>/dev/null
poll_until 300 drained "$J1" || fail slurm.array_end "job $J1 still has tasks: $(tasks_of "$J1")"

# --- study status reads what the tasks did ---
"$STUDY" status "$NAME" --runs "$TMP/S" >status1.out 2>&1 || fail status.exit "$(cat status1.out)"
RID=$(interrupted "$J1")
[ -n "$RID" ] && [ "$(echo "$RID" | wc -l)" = 1 ] &&
	[ "$(q $DB "SELECT array_index || ' ' || attempt FROM slurm_task WHERE job_id = $J1 AND run = '$RID'")" = "$IDX 1" ] &&
	q $DB "SELECT message FROM attempt WHERE run = '$RID' AND n = 1" | grep -q "checkpoint" &&
	[ "$(q $DB "SELECT state FROM run WHERE id = '$RID'")" = pending ] &&
	ok scancel.engine_checkpointed || fail scancel.engine_checkpointed "interrupted: '$RID'; $(q $DB "SELECT * FROM attempt")"
grep -q "interrupted at t = .*checkpoint .* written" "S/$NAME/logs/$RID.log" && [ -e "S/$NAME/$RID.h5.ckpt" ] &&
	ok scancel.checkpoint_file || fail scancel.checkpoint_file "$(tail -n 3 "S/$NAME/logs/$RID.log")"
# the uncancelled task's runs are done, recorded from the nodes' files
[ "$(q $DB "SELECT COUNT(*) FROM slurm_task s JOIN attempt a ON a.campaign = s.campaign AND a.run = s.run
	AND a.n = s.attempt WHERE s.job_id = $J1 AND s.array_index <> $IDX AND s.state = 'ended' AND a.status = 'ok'")" = 2 ] &&
	[ "$(q $DB "SELECT COUNT(*) FROM run WHERE state = 'done'")" -ge 2 ] && ok status.ingested ||
	fail status.ingested "$(q $DB "SELECT * FROM slurm_task")"
grep -q "slurm job $J1 (.*array 0-1%2, 4 runs in 2 tasks): tasks 0 queued, 0 running, 2 ended; runs [23] done, 0 failed, 1 stopped" status1.out &&
	ok status.slurm_line || fail status.slurm_line "$(grep -A1 slurm status1.out)"
# the cancelled task started no run after the stopped one (runs of a task go in order)
other=$(q $DB "SELECT run FROM slurm_task WHERE job_id = $J1 AND array_index = $IDX AND run <> '$RID'")
ost=$(q $DB "SELECT state FROM slurm_task WHERE job_id = $J1 AND run = '$other'")
if [ "$ost" = unstarted ] || { [ "$ost" = ended ] && [ -e "S/$NAME/$other.h5" ] &&
	[ "$(q $DB "SELECT MIN(n) FROM attempt WHERE run = '$other' AND status = 'ok'")" = 1 ]; }; then
	ok scancel.rest_of_task_not_started
else
	fail scancel.rest_of_task_not_started "$(q $DB "SELECT * FROM slurm_task WHERE job_id = $J1")"
fi

# --- submit again: only what is not done, in a new array (one run per task this
# time, held until the test watches); the stopped run resumes ---
t=$SECONDS
"$STUDY" submit s.campaign --slurm --runs "$TMP/S" --sbatch-args=--hold >sub2.log 2>&1
rc=$?
J2=$(q $DB "SELECT MAX(job_id) FROM slurm_job")
left=$(q $DB "SELECT COUNT(*) FROM run WHERE state <> 'done'")
[ "$rc" -eq 0 ] && [ "$J2" != "$J1" ] && grep -q "4 runs, $((4 - left)) done, 0 failed, 0 queued or running in Slurm, $left to submit" sub2.log &&
	[ "$(q $DB "SELECT COUNT(*) FROM slurm_task WHERE job_id = $J2")" = "$left" ] &&
	[ "$(q $DB "SELECT COUNT(*) FROM slurm_task WHERE job_id = $J2 AND run = '$RID'")" = 1 ] &&
	[ "$(wc -l <S/$NAME/slurm/tasks-2.txt)" = "$left" ] && ok resubmit.only_not_done || fail resubmit.only_not_done "exit $rc: $(cat sub2.log)"
# live progress of the array: no driver runs this campaign, its Slurm tasks do; the watch
# shows their runs in flight (swept values, t/T from the journals on the shared file
# system) and ends by itself when the tasks have ended
"$STUDY" status "$NAME" --runs "$TMP/S" --watch --interval 0.5 >watch.out 2>watch.err &
WPID=$!
# a signal to the task's shell alone (scancel --batch; what sbatch --signal=B:TERM@T
# sends before a time limit) reaches the engine through the script's trap and the
# worker: the run that never started in the first array, stopped once it shakes
# (the cancelled task's second run is unstarted: its first was held until the signal came)
# shaking_held ID: the run is shaking and its engine (held, its pid) stopped; whenever it
# starts (the array's tasks may run one after the other), not within a time
shaking_held() { is_shaking "$1" && engine_of "$1" && held=$REPLY && kill -STOP "$held" 2>/dev/null; }
RID2="" held=""
scontrol release "$J2" || fail scancel.batch_setup "scontrol release $J2: exit $?"
if [ "$ost" != unstarted ]; then
	fail scancel.batch_setup "the cancelled task's other run $other is '$ost', not unstarted: no run to stop"
elif ! poll_until 600 eval 'shaking_held "$other" || { drained "$J2" && held=""; }' || [ -z "$held" ]; then
	fail scancel.batch_setup "run $other was not seen shaking before its array ended (or its engine not held): $(ls "S/$NAME" | grep -F "$other" | tr '\n' ' '); engines: $(pgrep -a -x shake | cut -c1-300)"
elif ! is_shaking "$other"; then
	kill -CONT "$held"
	fail scancel.batch_setup "run $other ended as its engine was stopped"
else
	# its engine held (as above) until the signal, passed on by the script and the
	# worker, is pending
	RID2=$other
	scancel --batch --signal=TERM "${J2}_$(q $DB "SELECT array_index FROM slurm_task WHERE job_id = $J2 AND run = '$other'")"
	poll_until 30 term_pending "$held" || fail scancel.batch_passed_on "engine $held of run $other got no SIGTERM within 30 s"
	kill -CONT "$held"
fi
poll_until 300 drained "$J2" || fail slurm.array2_end "job $J2 still has tasks: $(tasks_of "$J2")"
poll_until 20 eval '! kill -0 $WPID 2>/dev/null' || { kill $WPID 2>/dev/null; echo "# the watch did not end"; }
wait $WPID
wrc=$?
grep -Eq "^  frequency=[34] seed=[12] +t [0-9.e+-]+/6 s" watch.out && grep -q "Slurm tasks queued or running hold" watch.out &&
	[ "$wrc" -eq 0 ] && tail -n 4 watch.out | grep -q '(final)' &&
	ok watch.slurm_runs_in_flight_and_end ||
	fail watch.slurm_runs_in_flight_and_end "exit $wrc: $(grep -c '^[0-9][0-9]:' watch.out) looks; $(tail -n 4 watch.out | tr '\n' '|') $(head -c 200 watch.err)"
"$STUDY" status "$NAME" --runs "$TMP/S" >status2.out 2>&1 || fail status2.exit "$(cat status2.out)"
[ -n "$RID2" ] && [ "$(interrupted "$J2")" = "$RID2" ] && grep -q "interrupted at t = .*checkpoint .* written" "S/$NAME/logs/$RID2.log" &&
	ok scancel.batch_signal_reaches_engine ||
	fail scancel.batch_signal_reaches_engine "run '$RID2': $(q $DB "SELECT * FROM attempt WHERE run = '$RID2'"; tail -n 2 "S/$NAME/logs/$RID2.log" 2>&1)"
if [ -n "$RID2" ]; then
	"$STUDY" submit s.campaign --slurm --runs "$TMP/S" >sub3.log 2>&1 && grep -q "1 to submit" sub3.log ||
		fail resubmit.third "$(cat sub3.log)"
	J3=$(q $DB "SELECT MAX(job_id) FROM slurm_job")
	poll_until 300 drained "$J3" || fail slurm.array3_end "job $J3 still has tasks: $(tasks_of "$J3")"
	"$STUDY" status "$NAME" --runs "$TMP/S" >status3.out 2>&1 || fail status3.exit "$(cat status3.out)"
fi
echo "# resubmitted arrays: $((SECONDS - t)) s"
[ "$(q $DB "SELECT COUNT(*) FROM run WHERE state = 'done'")" = 4 ] && ok resubmit.all_done ||
	fail resubmit.all_done "$(q $DB "SELECT id, state, attempts FROM run"; cat status2.out)"
grep -q "resuming from .*$RID.h5.ckpt" "S/$NAME/logs/$RID.log" && ok resubmit.resumed_from_checkpoint ||
	fail resubmit.resumed_from_checkpoint "$(tail -n 4 "S/$NAME/logs/$RID.log")"
# per run and attempt: the job and the array index that made it
[ "$(q $DB "SELECT group_concat(s.job_id || ':' || s.attempt || ':' || a.status, ' ') FROM (SELECT * FROM slurm_task
	WHERE run = '$RID' ORDER BY job_id) s JOIN attempt a ON a.campaign = s.campaign AND a.run = s.run AND a.n = s.attempt")" = \
	"$J1:1:interrupted $J2:2:ok" ] && ok db.job_and_index_per_attempt ||
	fail db.job_and_index_per_attempt "$(q $DB "SELECT * FROM slurm_task WHERE run = '$RID'")"
# nothing left: one more submit submits nothing, and study run finds every run done
njobs=$(q $DB "SELECT COUNT(*) FROM slurm_job")
"$STUDY" submit s.campaign --slurm --runs "$TMP/S" >sub4.log 2>&1 && grep -q "0 to submit" sub4.log &&
	[ "$(q $DB "SELECT COUNT(*) FROM slurm_job")" = "$njobs" ] && ok resubmit.nothing_left || fail resubmit.nothing_left "$(cat sub4.log)"
"$STUDY" run s.campaign --runs "$TMP/S" >run_after.log 2>&1 && grep -q "4 runs, 0 to run" run_after.log &&
	ok run.after_slurm || fail run.after_slurm "$(cat run_after.log)"

# --- the same results as the uninterrupted local run ---
# columns that say when, where and how often, not what: attempts (the stopped run has
# two), host, started, finished, wall_seconds, file (the runs directory's path)
# (Debian's python3: the first on PATH may be a pyenv shim, most of a second a call)
strip() {
	/usr/bin/python3 -c '
import csv, sys
drop = {"attempts", "host", "started", "finished", "wall_seconds", "file"}
r = csv.reader(open(sys.argv[1], newline=""))
head = next(r)
keep = [i for i, h in enumerate(head) if h not in drop]
w = csv.writer(sys.stdout, lineterminator="\n")
w.writerow([head[i] for i in keep])
for row in sorted(r):
    w.writerow([row[i] for i in keep])' "$1"
}
"$STUDY" export "$NAME" --runs "$TMP/L" >L.csv && "$STUDY" export "$NAME" --runs "$TMP/S" >S.csv &&
	strip L.csv >L.cmp && strip S.csv >S.cmp && [ "$(wc -l <L.cmp)" = 5 ] && cmp -s L.cmp S.cmp &&
	ok export.same_as_local || fail export.same_as_local "$(diff L.cmp S.cmp | head -n 4 | cut -c1-300)"
same=0
for f in L/$NAME/*.h5; do same_output "$f" "S/$NAME/$(basename "$f")" && same=$((same + 1)); done
[ "$same" = 4 ] && ok files.bit_identical || fail files.bit_identical "$same of 4 run files identical to the local run's"
echo "# study_slurm.sh: $((SECONDS - T0)) s"
finish
