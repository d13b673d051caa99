#!/usr/bin/env bash
# study_retry.sh - what is transient is run again, what is physics is not: an engine
# killed by a signal, or failing on I/O (a fault that passes), is run again within the
# same `study run` (every attempt recorded) and the campaign ends as an uninterrupted
# one; --retries bounds it (exhausted: pending, exit 7, said so); a run that blows up
# (overlap) fails once, is not run again, and is listed with its reason by status and
# list.
# tier: slow: campaigns with engines killed and I/O faults, each run again
. "$(dirname "$0")/lib.sh"
STUDY="${STUDY:-$(dirname "$SHAKE")/study}"
SHIM="${IOFAIL:-$REPO/build/faults/iofail.so}"
[ -x "$STUDY" ] || { fail setup "STUDY=$STUDY is not an executable (run make)"; finish; }
[ -f "$SHIM" ] || { fail setup "$SHIM is missing (make tests builds it)"; finish; }
cd "$TMP" || exit 1
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}:verify_asan_link_order=0"
campaign() { # NAME FREQUENCIES [SCENE-LINES...]
	printf '[campaign]\nname = %s\nseed = 4\n[scene]\n' "$1"
	tiny_scene n_grains=40 width=16 depth=-
	printf 'amplitude = 1\nduration = 3\ncheckpoint_every = 0.2\ntraj_rate = 100\n'
	printf '%s\n' "${@:3}"
	printf '[grid]\nfrequency = %s\n' "$2"
}
strip() { # export without when, where (the file's path too) and how often
	awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i ~ /^(attempts|started|finished|wall_seconds|host|git_hash|git_dirty|file)$/) drop[i] = 1 }
		{ s = ""; for (i = 1; i <= NF; i++) if (!drop[i]) s = s $i ","; print s }' "$1"
}
# kill_engine DIR [NOT-PID]: SIGKILL to a running engine of the campaign in DIR that has
# written a checkpoint (and is not NOT-PID); prints its pid
kill_engine() {
	local w e id i
	for i in $(seq 500); do
		for w in $(pgrep -f "exec $1 run" 2>/dev/null); do
			id=$({ tr '\0' '\n' <"/proc/$w/cmdline"; } 2>/dev/null | tail -n 1)
			e=$(pgrep -x -P "$w" shake 2>/dev/null | head -n 1) # the engine, never a helper the worker started
			if [ -n "$e" ] && [ "$e" != "${2:-}" ] && [ -e "$1/$id.h5.ckpt" ]; then kill -KILL "$e" && echo "$e" && return 0; fi
		done
		sleep 0.02
	done
	return 1
}

campaign r "3, 4" >r.campaign
"$STUDY" run r.campaign --runs "$TMP/REF" --jobs 2 >ref.log 2>&1 || fail setup.reference "exit $?: $(tail -n 2 ref.log)"
"$STUDY" export r --runs "$TMP/REF" >ref.csv

# --- killed: run again at once, both attempts recorded, the same results ---
t0=$(date +%s%N)
"$STUDY" run r.campaign --runs "$TMP/K" --jobs 2 >k.log 2>&1 &
pid=$!
kill_engine "$TMP/K/r" >/dev/null || fail killed.setup "no engine with a checkpoint to kill"
wait $pid
rc=$?
echo "# killed once, retried: $((($(date +%s%N) - t0) / 1000000)) ms"
rows=$(q K/study.db "SELECT group_concat(status || ':' || exit_code, ' ') FROM (SELECT status, exit_code FROM attempt
	WHERE campaign = 'r' AND run IN (SELECT run FROM attempt WHERE status = 'killed') ORDER BY n)")
[ "$rc" -eq 0 ] && [ "$rows" = "killed:137 ok:0" ] && grep -q "running again 1 run" k.log && ok killed.retried ||
	fail killed.retried "exit $rc, attempts '$rows': $(tail -n 3 k.log)"
# the killed engine's CPU and peak memory are its attempt's (its worker's wait4), as the rerun's
use=$(q K/study.db "SELECT group_concat(status || ':' || (cpu_seconds > 0) || (max_rss_kb > 0), ' ') FROM (SELECT * FROM attempt
	WHERE campaign = 'r' AND run IN (SELECT run FROM attempt WHERE status = 'killed') ORDER BY n)")
[ "$use" = "killed:11 ok:11" ] && ok killed.usage_recorded || fail killed.usage_recorded "'$use'"
"$STUDY" export r --runs "$TMP/K" >k.csv
cmp -s <(strip ref.csv) <(strip k.csv) && ok killed.export_equals_uninterrupted ||
	fail killed.export_equals_uninterrupted "$(diff <(strip ref.csv) <(strip k.csv) | head -n 3 | cut -c1-300)"
"$STUDY" status r --runs "$TMP/K" >k.status
grep -q "killed by signal 9  \[run again: done\]" k.status && grep -q "transient attempts.*killed 1 (1 of their runs now done)" k.status &&
	ok killed.status || fail killed.status "$(cat k.status)"

# --- --retries 1, killed twice: exhausted, pending, exit 7, said so ---
campaign x 3 >x.campaign
"$STUDY" run x.campaign --runs "$TMP/X" --retries 1 >x.log 2>&1 &
pid=$!
first=$(kill_engine "$TMP/X/x")
second=$(kill_engine "$TMP/X/x" "$first")
wait $pid
rc=$?
rows=$(q X/study.db "SELECT state || ' ' || attempts || ' ' || (SELECT group_concat(status, ',') FROM attempt WHERE campaign = 'x') FROM run WHERE campaign = 'x'")
[ -n "$second" ] && [ "$rc" -eq 7 ] && [ "$rows" = "pending 2 killed,killed" ] && grep -q "killed or lost 2 times in this run (--retries 1" x.log &&
	ok retries.exhausted || fail retries.exhausted "exit $rc, '$rows': $(tail -n 2 x.log)"
"$STUDY" run x.campaign --runs "$TMP/X" >x2.log 2>&1 && [ "$(q X/study.db "SELECT state FROM run")" = done ] &&
	ok retries.resumed_later || fail retries.resumed_later "$(tail -n 2 x2.log)"

# --- an I/O fault that passes: the run that hit it is run again, then the rest ---
LD_PRELOAD="$SHIM" IOFAIL_TRIGGER="$TMP/trig" IOFAIL_MATCH=".h5.tmp" "$STUDY" run r.campaign --runs "$TMP/I" --jobs 1 >io.log 2>&1 &
pid=$!
# armed once the shared packing is built (a packing that fails is not a run's fault:
# its runs settle themselves), so that the first run to finish hits it
for i in $(seq 600); do
	[ "$(q I/study.db "SELECT COUNT(*) FROM cache WHERE state = 'ok'" 2>/dev/null)" -gt 0 ] 2>/dev/null && break
	sleep 0.01
done
touch trig
for i in $(seq 600); do
	[ "$(q I/study.db "SELECT COUNT(*) FROM attempt WHERE status = 'io'" 2>/dev/null)" -gt 0 ] 2>/dev/null && break
	sleep 0.02
done
rm -f trig # the disk has room again
wait $pid
rc=$?
io=$(q I/study.db "SELECT COUNT(*) FROM attempt WHERE status = 'io'")
[ "$rc" -eq 0 ] && [ "$io" -ge 1 ] && [ "$(q I/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'")" = 2 ] &&
	grep -q "that hit an I/O fault" io.log && ok io.transient_retried || fail io.transient_retried "exit $rc, $io io attempts: $(tail -n 3 io.log)"
"$STUDY" export r --runs "$TMP/I" >io.csv
cmp -s <(strip ref.csv) <(strip io.csv) && ok io.export_equals_uninterrupted ||
	fail io.export_equals_uninterrupted "$(diff <(strip ref.csv) <(strip io.csv) | head -n 3 | cut -c1-300)"

# --- physics: an overlap fails once and is not run again; status and list say why ---
campaign p "4" dt_guard=off >p.campaign
printf 'dt = 5e-5, 0.002\n' >>p.campaign
"$STUDY" run p.campaign --runs "$TMP/P" >p.log 2>&1
rc=$?
row=$(q P/study.db "SELECT state || ' ' || attempts || ' ' || status FROM runs WHERE dt = 0.002")
[ "$rc" -eq 3 ] && [ "$row" = "failed 1 overlap" ] && ! grep -q "running again" p.log && ok physics.not_retried ||
	fail physics.not_retried "exit $rc, '$row': $(tail -n 3 p.log)"
"$STUDY" status p --runs "$TMP/P" >p.status
"$STUDY" list --runs "$TMP/P" >p.list
grep -q "failed runs by reason (not run again; --retry-failed does): overlap 1" p.status && grep -q "overlap of disks" p.status &&
	grep -Eq '^p +2 +1 +1 +0 .*\[failed: overlap:1\]' p.list && ok physics.listed_with_reason ||
	fail physics.listed_with_reason "$(cat p.status p.list)"
finish
