#!/usr/bin/env bash
# study_resume.sh - a campaign killed with SIGKILL at random moments (the driver
# alone, or the driver with all its workers as in a crash) and run again ends with
# the same database rows and bit-identical HDF5 outputs as an uninterrupted campaign;
# SIGTERM stops it cleanly with exit code 7 and the runs resume from checkpoints; the
# attempts a killed driver could not record are recorded by the next run.
# tier: slow: campaigns killed at several moments and resumed
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1

cat >k.campaign <<C
[campaign]
name = k
seed = 5
replicates = 2
[scene]
$(tiny_scene depth=-)
amplitude = 1
duration = 1.5
traj_rate = 200
checkpoint_every = 0.1
[grid]
frequency = 3, 4, 5
C
t0=$(date +%s%N)
"$STUDY" run k.campaign --runs "$TMP/REF" --jobs 2 >ref.log 2>&1
rc=$?
ref_ms=$((($(date +%s%N) - t0) / 1000000))
echo "# uninterrupted campaign (6 runs, 2 jobs): $ref_ms ms"
[ "$rc" -eq 0 ] && ok reference || { fail reference "exit $rc: $(tail -c 300 ref.log)"; finish; }

# kill at random moments within the reference duration; odd kills hit the driver only,
# even kills its process group (the driver and GNU parallel; parallel starts each job in
# a process group of its own, so in both cases the workers and engines finish or stop
# on their own)
ckpts=0
for k in 1 2 3 4; do
	setsid "$STUDY" run k.campaign --runs "$TMP/K" --jobs 2 >"kill$k.log" 2>&1 &
	pid=$!
	ms=$((100 + RANDOM % (ref_ms > 600 ? ref_ms / 3 : 100)))
	sleep "$(awk -v m=$ms 'BEGIN { printf "%.3f", m / 1000 }')"
	if [ $((k % 2)) -eq 1 ]; then kill -KILL $pid 2>/dev/null; else kill -KILL -- -$pid 2>/dev/null; fi
	wait $pid 2>/dev/null
	n=$(ls K/k/*.ckpt 2>/dev/null | wc -l)
	ckpts=$((ckpts + n))
	echo "# kill $k after $ms ms ($([ $((k % 2)) -eq 1 ] && echo driver || echo group)): $(ls K/k/*.h5 2>/dev/null | wc -l) outputs, $n checkpoints"
done
echo "# checkpoints seen between kills: $ckpts"
"$STUDY" run k.campaign --runs "$TMP/K" --jobs 2 >final.log 2>&1
rc=$?
[ "$rc" -eq 0 ] && ok resume.completes || fail resume.completes "exit $rc: $(tail -c 400 final.log)"
# a run (and an attempt) never ends before it starts, even when a worker launched again
# finds the file an earlier one finished (the file's start is the truth then)
bad=$(sqlite3 K/study.db "SELECT (SELECT COUNT(*) FROM run WHERE started > finished) +
	(SELECT COUNT(*) FROM attempt WHERE started > finished)")
[ "$bad" = 0 ] && ok resume.times_ordered ||
	fail resume.times_ordered "$bad rows end before they start: $(sqlite3 K/study.db "SELECT id, started, finished FROM run WHERE started > finished")"
rows() {
	sqlite3 -batch "$1" "SELECT id, state, status, exit_code, steps, replicate, printf('%.17g|%.17g|%.17g|%.17g', frequency,
		intruder_final_y_box, intruder_max_y_box, settle_time), from_cache, seed FROM runs ORDER BY id"
}
rows REF/study.db >ref.rows
rows K/study.db >k.rows
[ -s ref.rows ] && cmp -s ref.rows k.rows && ok resume.same_rows || fail resume.same_rows "$(diff ref.rows k.rows | head -n 4)"
[ "$(sqlite3 K/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'")" = 6 ] && ok resume.all_done || fail resume.all_done "not all done"
# completed runs are never recomputed: one successful attempt each
[ "$(sqlite3 K/study.db "SELECT COUNT(*) FROM attempt WHERE status = 'ok'")" = 6 ] && ok resume.one_ok_attempt_each ||
	fail resume.one_ok_attempt_each "$(sqlite3 K/study.db "SELECT run, n, status FROM attempt")"
same=0
for f in REF/k/*.h5; do same_output "$f" "K/k/$(basename "$f")" && same=$((same + 1)); done
[ "$same" = 6 ] && ok resume.bit_identical || fail resume.bit_identical "only $same of 6 outputs identical"
[ -z "$(ls K/k/*.ckpt K/k/*.journal 2>/dev/null)" ] && ok resume.no_leftovers || fail resume.no_leftovers "$(ls K/k)"
[ -z "$(pgrep -f "$TMP/K" 2>/dev/null)" ] && ok resume.no_orphans || fail resume.no_orphans "processes still running"

# SIGTERM (and Ctrl-C, which reaches the whole group): exit 7, runs stopped with a
# checkpoint, recorded as interrupted (resumable), then resumed to identical files
"$STUDY" run k.campaign --runs "$TMP/T" --jobs 2 --no-cache >term1.log 2>&1 &
pid=$!
for i in $(seq 200); do [ -n "$(ls T/k/*.ckpt 2>/dev/null)" ] && break; sleep 0.02; done
kill -TERM $pid
wait $pid
rc=$?
[ "$rc" -eq 7 ] && ok term.exit_7 || fail term.exit_7 "exit $rc: $(tail -c 300 term1.log)"
pend=$(sqlite3 T/study.db "SELECT COUNT(*) FROM run WHERE state = 'pending'")
intr=$(sqlite3 T/study.db "SELECT COUNT(*) FROM attempt WHERE status = 'interrupted'")
[ "$pend" -gt 0 ] && [ "$intr" -gt 0 ] && ok term.recorded_interrupted || fail term.recorded_interrupted "pending $pend, interrupted attempts $intr"
# with the engine's own words and exit code ("interrupted at t = ...; checkpoint ...
# written" or "interrupted while settling"), not a line printed after them
[ "$(sqlite3 T/study.db "SELECT COUNT(*) FROM attempt WHERE status = 'interrupted' AND exit_code = 7
	AND message LIKE 'shake: interrupted %'")" = "$intr" ] && ok term.interrupted_message ||
	fail term.interrupted_message "$(sqlite3 T/study.db "SELECT exit_code, message FROM attempt WHERE status = 'interrupted'")"
"$STUDY" run k.campaign --runs "$TMP/T" --jobs 2 --no-cache >term2.log 2>&1
rc=$?
same=0
for f in REF/k/*.h5; do same_output "$f" "T/k/$(basename "$f")" particles settle settle_steps settle_time && same=$((same + 1)); done
[ "$rc" -eq 0 ] && [ "$same" = 6 ] && ok term.resumed_identical || fail term.resumed_identical "exit $rc, $same of 6 identical"

# Ctrl-C reaches the driver's process group, and the driver passes it on to its jobs: exit 7,
# every stopped run recorded as interrupted with its engine's message, then resumed
setsid "$STUDY" run k.campaign --runs "$TMP/C" --jobs 2 >int1.log 2>&1 &
pid=$!
for i in $(seq 200); do [ -n "$(ls C/k/*.ckpt 2>/dev/null)" ] && break; sleep 0.02; done
kill -INT -- -$pid
wait $pid
rc=$?
intr=$(sqlite3 C/study.db "SELECT COUNT(*) FROM attempt WHERE status = 'interrupted' AND exit_code = 7 AND message LIKE 'shake: interrupted%'")
[ "$rc" -eq 7 ] && [ "$intr" -gt 0 ] && ok ctrl_c.recorded_interrupted ||
	fail ctrl_c.recorded_interrupted "exit $rc: $(sqlite3 C/study.db "SELECT run, exit_code, status, message FROM attempt")"
"$STUDY" run k.campaign --runs "$TMP/C" --jobs 2 >int2.log 2>&1
rc=$?
same=0
for f in REF/k/*.h5; do same_output "$f" "C/k/$(basename "$f")" && same=$((same + 1)); done
[ "$rc" -eq 0 ] && [ "$same" = 6 ] && ok ctrl_c.resumed_identical || fail ctrl_c.resumed_identical "exit $rc, $same of 6 identical"

# the driver alone killed outright (SIGKILL): it records nothing, GNU parallel's
# SIGTERM stops its engines with a checkpoint; the next study run records each run it
# finds left running as an interrupted attempt (start, end, why), then resumes it
"$STUDY" run k.campaign --runs "$TMP/D" --jobs 2 >d1.log 2>&1 &
pid=$!
for i in $(seq 200); do [ -n "$(ls D/k/*.ckpt 2>/dev/null)" ] && break; sleep 0.02; done
kill -KILL $pid
wait $pid 2>/dev/null
left=$(sqlite3 D/study.db "SELECT COUNT(*) FROM run WHERE state = 'running'")
[ "$left" -gt 0 ] && [ "$(sqlite3 D/study.db "SELECT COUNT(*) FROM attempt")" = 0 ] && ok killed_driver.left_running ||
	fail killed_driver.left_running "$left runs left running, attempts: $(sqlite3 D/study.db "SELECT run, status FROM attempt")"
"$STUDY" run k.campaign --runs "$TMP/D" --jobs 2 >d2.log 2>&1
rc=$?
# each with its start and an end not before it (the last write of its log or
# checkpoint), and why; a run that finished after all has its one ok attempt instead
intr=$(sqlite3 D/study.db "SELECT COUNT(*) FROM attempt WHERE status = 'interrupted'")
good=$(sqlite3 D/study.db "SELECT COUNT(*) FROM attempt WHERE status = 'interrupted' AND n = 1 AND started IS NOT NULL
	AND (finished IS NULL OR finished >= started) AND message LIKE '%its driver was killed%'")
[ "$rc" -eq 0 ] && [ "$intr" -ge 1 ] && [ "$intr" -le "$left" ] && [ "$good" = "$intr" ] && ok killed_driver.recorded_interrupted ||
	fail killed_driver.recorded_interrupted "exit $rc, $left left running: $(sqlite3 D/study.db "SELECT run, n, exit_code, status, started, finished, message FROM attempt WHERE status <> 'ok'")"
# never twice: one ok attempt per run, the interrupted one before it
[ "$(sqlite3 D/study.db "SELECT COUNT(*) FROM attempt WHERE status = 'ok'")" = 6 ] &&
	[ "$(sqlite3 D/study.db "SELECT COUNT(*) FROM attempt a WHERE status = 'ok' AND n <> 1 + (SELECT COUNT(*) FROM attempt b
		WHERE b.run = a.run AND b.status = 'interrupted')")" = 0 ] && ok killed_driver.one_record_each ||
	fail killed_driver.one_record_each "$(sqlite3 D/study.db "SELECT run, n, status FROM attempt")"
n=$("$STUDY" status k --runs "$TMP/D" 2>&1 | grep -c ' interrupted: .*its driver was killed')
[ "$n" = "$intr" ] && ok killed_driver.status_shows || fail killed_driver.status_shows "$n of $intr in: $("$STUDY" status k --runs "$TMP/D" 2>&1)"
same=0
for f in REF/k/*.h5; do same_output "$f" "D/k/$(basename "$f")" && same=$((same + 1)); done
[ "$same" = 6 ] && ok killed_driver.resumed_identical || fail killed_driver.resumed_identical "$same of 6 identical"

# a signal while the driver writes the runs' argument files, after the packings and
# before GNU parallel starts, starts nothing: no run begins after the driver was told
# to stop (three tries, each signalled when the first argument file appears)
# (runs of 60 s: a run GNU parallel started just before it heeded the signal cannot end
# on its own before it is stopped, even on a loaded machine; at 1.5 s one did)
sed -e 's/^replicates = 2$/replicates = 8/' -e 's/^duration = 1.5$/duration = 60/' k.campaign >g.campaign
late=""
for t in 1 2 3; do
	"$STUDY" run g.campaign --runs "$TMP/G$t" --jobs 2 >g$t.log 2>&1 &
	pid=$!
	for i in $(seq 1000); do ls G$t/k/jobs/*.args >/dev/null 2>&1 && break; sleep 0.005; done
	kill -INT $pid
	for i in $(seq 100); do kill -0 $pid 2>/dev/null || break; sleep 0.1; done
	if kill -0 $pid 2>/dev/null; then
		late="$late try $t: still running 10 s after SIGINT ($(sqlite3 G$t/study.db "SELECT state, COUNT(*) FROM run GROUP BY 1" | tr '\n' ' '))"
		kill -TERM $pid
	fi
	wait $pid
	rc=$?
	# GNU parallel may have started its first jobs before it heeds SIGTERM: those stop
	# with a checkpoint (interrupted); none runs to its end
	n=$(sqlite3 G$t/study.db "SELECT COUNT(*) FROM attempt WHERE status <> 'interrupted'")
	nd=$(sqlite3 G$t/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'")
	[ "$rc" = 7 ] && [ "$n" = 0 ] && [ "$nd" = 0 ] || late="$late try $t: exit $rc, $n attempts not interrupted, $nd done"
done
[ -z "$late" ] && [ -z "$(pgrep -f "$TMP/G" 2>/dev/null)" ] && ok signal.before_parallel_starts_nothing ||
	fail signal.before_parallel_starts_nothing "${late:-engines left running}"

# a worker's engine killed (OOM killer, a node's admin) while the driver runs on, with
# --retries 0 (study_retry.sh tests the retries): the attempt is recorded as killed, the
# run stays pending (exit 7), and the next `study run` continues it from its checkpoint
# to the same file
"$STUDY" run k.campaign --runs "$TMP/W" --jobs 2 --retries 0 >w1.log 2>&1 &
pid=$!
victim=
for i in $(seq 300); do
	for w in $(pgrep -f "exec $TMP/W/k run" 2>/dev/null); do
		id=$({ tr '\0' '\n' <"/proc/$w/cmdline"; } 2>/dev/null | tail -n 1)
		e=$(pgrep -x -P "$w" shake 2>/dev/null | head -n 1) # the engine, never a helper the worker started
		if [ -n "$e" ] && [ -e "W/k/$id.h5.ckpt" ]; then victim=$id; kill -KILL "$e"; break 2; fi
	done
	sleep 0.02
done
wait $pid
rc=$?
row=$(sqlite3 W/study.db "SELECT state || '|' || a.exit_code || '|' || a.status || '|' || a.message FROM attempt a JOIN run r
	ON r.campaign = a.campaign AND r.id = a.run WHERE a.run = '$victim'")
[ -n "$victim" ] && [ "$rc" -eq 7 ] && [ "$row" = "pending|137|killed|killed by signal 9" ] && ok worker_killed.recorded ||
	fail worker_killed.recorded "victim '$victim', exit $rc, attempt '$row'"
# its checkpoint is still there, and its argument file (reused as it is) lets the
# engine resume from it (restart = auto; the engine's restart.sh checks the resume)
[ -s "W/k/$victim.h5.ckpt" ] && grep -qx "restart=auto" "W/k/jobs/$victim.args" && ok worker_killed.checkpoint_kept ||
	fail worker_killed.checkpoint_kept "$(ls W/k) $(grep restart "W/k/jobs/$victim.args" 2>&1)"
"$STUDY" run k.campaign --runs "$TMP/W" --jobs 2 >w2.log 2>&1
rc=$?
[ "$rc" -eq 0 ] && grep -q "6 runs, 1 to run" w2.log && ok worker_killed.only_it_reruns ||
	fail worker_killed.only_it_reruns "exit $rc: $(cat w2.log)"
same=0
for f in REF/k/*.h5; do same_output "$f" "W/k/$(basename "$f")" && same=$((same + 1)); done
[ "$same" = 6 ] && [ "$(sqlite3 W/study.db "SELECT COUNT(*) FROM run WHERE state = 'done' AND attempts = 1 + (id = '$victim')")" = 6 ] &&
	ok worker_killed.identical || fail worker_killed.identical "$same of 6 identical: $(sqlite3 W/study.db "SELECT id, state, attempts FROM run")"
finish
