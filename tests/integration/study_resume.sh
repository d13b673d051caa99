#!/usr/bin/env bash
# study_resume.sh - a campaign killed with SIGKILL at random moments (the driver
# alone, or the driver with all its workers as in a crash) and run again ends with
# the same database rows and bit-identical HDF5 outputs as an uninterrupted campaign;
# SIGTERM stops it cleanly with exit code 7 and the runs resume from checkpoints.
. "$(dirname "$0")/lib.sh"
STUDY="${STUDY:-$(dirname "$SHAKE")/study}"
[ -x "$STUDY" ] || { fail setup "STUDY=$STUDY is not an executable (run make)"; finish; }
cd "$TMP" || exit 1

cat >k.campaign <<'C'
[campaign]
name = k
seed = 5
replicates = 2
[scene]
n_grains = 60
width = 20
radius_ratio = 2
settle_ke = 1
settle_min = 0.2
amplitude = 1
duration = 3
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

# kill at random moments within the reference duration; odd kills hit the driver only
# (its workers finish or stop on their own), even kills the whole process group
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
rows() {
	sqlite3 -batch "$1" "SELECT id, state, status, exit_code, steps, replicate, printf('%.17g|%.17g|%.17g|%.17g', frequency,
		intruder_final_y, intruder_max_y, settle_time), from_cache, seed FROM runs ORDER BY id"
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
"$STUDY" run k.campaign --runs "$TMP/T" --jobs 2 --no-cache >term2.log 2>&1
rc=$?
same=0
for f in REF/k/*.h5; do same_output "$f" "T/k/$(basename "$f")" particles settle settle_steps settle_time && same=$((same + 1)); done
[ "$rc" -eq 0 ] && [ "$same" = 6 ] && ok term.resumed_identical || fail term.resumed_identical "exit $rc, $same of 6 identical"
finish
