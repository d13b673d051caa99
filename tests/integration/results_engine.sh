#!/usr/bin/env bash
# results_engine.sh - the engine's results that the database copies: the largest overlap
# of a run (recorded exactly, the stop a safety net whose threshold changes no force),
# the CPU time of a resumed run (the sum of its attempts), and degenerate scenes (no
# grains, one grain, only walls, only an intruder) with every observable on: a complete
# file or a clear refusal, never a crash.
# tier: slow: runs interrupted and resumed, and degenerate scenes
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

# --- the largest overlap ---
shake_run a.log "${FAST[@]}" "${GENTLE[@]}" duration=0.5 output=a.h5 || fail overlap.run "exit $?: $(tail -n 2 a.log)"
M=$(attr a.h5 /overlap_max) T=$(attr a.h5 /overlap_max_time)
awk -v m="$M" 'BEGIN { exit !(m > 0.05 && m < 1) }' && ok overlap.recorded || fail overlap.recorded "overlap_max '$M'"
[ -n "$(attr a.h5 /overlap_max_disk_a)" ] && [ -n "$(attr a.h5 /overlap_max_y_box)" ] && ok overlap.where_and_which ||
	fail overlap.where_and_which "disks or place of the largest overlap missing"
# a stop just below the record stops the same run at or before the record's time ...
lo=$(awk -v m="$M" 'BEGIN { printf "%.17g", 0.9 * m }')
shake_run b.log "${FAST[@]}" "${GENTLE[@]}" duration=0.5 max_overlap="$lo" output=b.h5
rc=$?
st=$(attr b.h5 /status_time)
[ "$rc" = 4 ] && [ "$(attr b.h5 /status)" = overlap ] && awk -v s="$st" -v t="$T" 'BEGIN { exit !(s <= t + 1e-12) }' &&
	ok overlap.stop_below_record_stops || fail overlap.stop_below_record_stops "exit $rc, stopped at '$st', record at $T"
# ... and one above it (the record is within 1 % of the largest overlap) lets the run end
# exactly as without it (the threshold arms a flag; it changes no force)
hi=$(awk -v m="$M" 'BEGIN { printf "%.17g", 1.0101 * m }')
shake_run c.log "${FAST[@]}" "${GENTLE[@]}" duration=0.5 max_overlap="$hi" output=c.h5
rc=$?
[ "$rc" = 0 ] && same_output a.h5 c.h5 output max_overlap && ok overlap.stop_above_record_changes_nothing ||
	fail overlap.stop_above_record_changes_nothing "exit $rc or the outputs differ"

# --- a resumed run's CPU time is the sum of its attempts ---
long=("${FAST[@]}" "${GENTLE[@]}" duration=40 snapshots=no checkpoint_every=1)
# interrupted OUT LOG : the long run into OUT, SIGTERM once it has written its fourth
# checkpoint (4 of its 40 s shaken): conditions, not times, so that a loaded machine
# (slow to prepare the bed, or to start the second attempt) changes nothing
interrupted() {
	"$SHAKE" "${long[@]}" output="$1" >"$2" 2>&1 &
	local pid=$! i seen="" now k=0
	for ((i = 0; i < 30000 && k < 4; i++)); do
		kill -0 $pid 2>/dev/null || break
		now=$(stat -c '%i %y' "$1.ckpt" 2>/dev/null)
		[ -n "$now" ] && [ "$now" != "$seen" ] && seen=$now k=$((k + 1))
		sleep 0.01
	done
	kill -TERM $pid 2>/dev/null
	wait $pid
}
interrupted r.h5 r1.log
if [ -f r.h5.ckpt ] && [ ! -f r.h5 ]; then
	t0=$(date +%s%N)
	"$SHAKE" "${long[@]}" output=r.h5 restart=yes >r2.log 2>&1 || fail resume.run "exit $?: $(tail -n 2 r2.log)"
	w2=$(( ($(date +%s%N) - t0) / 1000000 ))
	L=$(attr r.h5 /provenance/loop_seconds)
	# the second attempt ran at most w2 ms; the first one's loop time (4 s of 40 shaken)
	# must be in the total too
	awk -v l="$L" -v w="$w2" 'BEGIN { exit !(l * 1000 > w + 300) }' && ok resume.loop_seconds_summed ||
		fail resume.loop_seconds_summed "loop_seconds $L s after a resume whose second attempt took $w2 ms"
else
	fail resume.setup "the interrupted run left no checkpoint: $(tail -n 2 r1.log)"
fi

# --- a checkpoint of another engine version: restart = auto starts over, yes refuses ---
if [ -f r.h5.ckpt ] || { interrupted v.h5 v0.log; [ -f v.h5.ckpt ]; }; then
	ck=$( [ -f r.h5.ckpt ] && echo r || echo v )
	printf 'SBCKPT01' | dd of=$ck.h5.ckpt conv=notrunc 2>/dev/null
	cp $ck.h5.ckpt old.ckpt
	shake_run v1.log "${FAST[@]}" "${GENTLE[@]}" duration=0.2 checkpoint=old.ckpt restart=yes output=v1.h5
	rc=$?
	[ "$rc" = 1 ] && grep -q 'format 01' v1.log && ok checkpoint.other_version_refused_with_restart_yes ||
		fail checkpoint.other_version_refused_with_restart_yes "exit $rc: $(tail -n 1 v1.log)"
	shake_run v2.log "${FAST[@]}" "${GENTLE[@]}" duration=0.2 checkpoint=old.ckpt restart=auto output=v2.h5
	rc=$?
	[ "$rc" = 0 ] && grep -q 'starting over' v2.log && ok checkpoint.other_version_starts_over_with_auto ||
		fail checkpoint.other_version_starts_over_with_auto "exit $rc: $(tail -n 1 v2.log)"
else
	fail checkpoint.setup "no checkpoint to alter"
fi

# --- degenerate scenes, every observable on ---
ALL=(flux=yes field=yes ring=yes snapshots=yes traj_rate=100 duration=0.3 "${GENTLE[@]}" progress=no)
shake_run d0.log n_grains=0 width=12 radius_ratio=2 "${ALL[@]}" output=d0.h5
rc=$?
[ "$rc" = 0 ] && [ "$(attr d0.h5 /status)" = ok ] && [ "$(dims d0.h5 /particles/intruder/position/value | cut -d' ' -f1)" -gt 10 ] &&
	ok degenerate.no_grains || fail degenerate.no_grains "exit $rc: $(tail -n 2 d0.log)"
shake_run d1.log n_grains=1 width=12 radius_ratio=2 "${ALL[@]}" output=d1.h5
rc=$?
[ "$rc" = 0 ] && [ "$(attr d1.h5 /n_mobile)" = 2 ] && ok degenerate.one_grain || fail degenerate.one_grain "exit $rc: $(tail -n 2 d1.log)"
shake_run d2.log n_grains=1 width=12 radius_ratio=0 ring_y=3 "${ALL[@]}" output=d2.h5
rc=$?
[ "$rc" = 0 ] && [ "$(attr d2.h5 /n_mobile)" = 1 ] && ok degenerate.one_grain_no_intruder ||
	fail degenerate.one_grain_no_intruder "exit $rc: $(tail -n 2 d2.log)"
shake_run p.log n_grains=3 width=12 radius_ratio=2 duration=0 write_particles=p.txt output=p.h5 progress=no
awk '$4 != "grain" && $4 != "intruder"' p.txt >walls.txt
awk '$4 != "grain"' p.txt >intruder.txt
shake_run d3.log particles=walls.txt width=12 "${ALL[@]}" output=d3.h5
rc=$?
[ "$rc" = 1 ] && [ ! -f d3.h5 ] && grep -q 'walls.txt.*no mobile disks' d3.log && ok degenerate.only_walls_refused ||
	fail degenerate.only_walls_refused "exit $rc: $(tail -n 2 d3.log)"
shake_run d4.log particles=intruder.txt width=12 "${ALL[@]}" output=d4.h5
rc=$?
[ "$rc" = 0 ] && [ "$(attr d4.h5 /n_mobile)" = 1 ] && [ -n "$(attr d4.h5 /risen)" ] && ok degenerate.only_an_intruder ||
	fail degenerate.only_an_intruder "exit $rc: $(tail -n 2 d4.log)"
finish
