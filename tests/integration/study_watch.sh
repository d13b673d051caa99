#!/usr/bin/env bash
# study_watch.sh - live progress: `study status --watch` on a campaign that is running
# shows its runs in flight with their swept values (not ids) and the simulated time t/T
# each reached (from its journal), counts and an ETA from the simulated seconds per
# second measured over the runs in flight; it ends by itself when the campaign does,
# and at once on Ctrl-C. `study run --progress` prints the same look as one line.
# tier: slow: campaigns watched while they run, at the pace of their runs
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1
campaign() { # NAME DURATION
	cat <<C
[campaign]
name = $1
seed = 2
replicates = 2
[scene]
$(tiny_scene depth=-)
amplitude = 1
duration = $2
traj_rate = 100
[grid]
frequency = 3, 4
C
}
# runs of about 2.5 s whatever the build (the sanitizer build is several times slower):
# long enough that the watch looks at each several times, measured on one short run
t0=$(date +%s%N)
tiny_bed depth=-
"$SHAKE" "${BEDARGS[@]}" amplitude=1 frequency=3 duration=2 \
	traj_rate=100 output="$TMP/cal.h5" progress=no >cal.log 2>&1
T=$(awk -v ms=$((($(date +%s%N) - t0) / 1000000)) 'BEGIN { d = 2 * 2500 / (ms > 1 ? ms : 1); d = d < 3 ? 3 : d > 40 ? 40 : d; printf "%d", d }')
campaign w "$T" >w.campaign
t0=$(date +%s%N)
"$STUDY" run w.campaign --runs "$TMP/R" --jobs 2 --progress >run.log 2>&1 &
pid=$!
for i in $(seq 400); do
	[ "$(sqlite3 R/study.db "SELECT COUNT(*) FROM run WHERE state = 'running'" 2>/dev/null)" -gt 0 ] 2>/dev/null && break
	sleep 0.05
done
"$STUDY" status w --runs "$TMP/R" --watch --interval 0.5 >watch.out 2>&1
wrc=$?
t_watch=$(date +%s%N)
wait $pid
rc=$?
t_run=$(date +%s%N)
echo "# campaign (4 runs, 2 jobs): $(((t_run - t0) / 1000000)) ms; $(grep -c '^[0-9][0-9]:' watch.out) looks"
[ "$rc" -eq 0 ] && ok watch.campaign_ran || fail watch.campaign_ran "exit $rc: $(tail -c 300 run.log)"
# in flight: "frequency=3 seed=1   t 2.34/$T s ..." with t > 0
grep -Eq "^  frequency=[34] seed=[12] +t [0-9.e+-]+/$T s" watch.out &&
	awk '/^  frequency=/ && $3 == "t" { split($4, a, "/"); if (a[1] + 0 > 0) found = 1 } END { exit !found }' watch.out &&
	ok watch.in_flight_values_and_t || fail watch.in_flight_values_and_t "$(head -n 12 watch.out)"
# the ETA from what runs: simulated seconds per second measured over the runs in flight
grep -q 'ETA [0-9.]* \(s\|min\) at [0-9.e+-]* simulated s per s from the runs in flight' watch.out &&
	ok watch.eta_measured || fail watch.eta_measured "$(grep ETA watch.out | head -n 3)"
# it ended by itself when the campaign did (the driver's last words come after it)
[ "$wrc" -eq 0 ] && tail -n 3 watch.out | grep -q '(final)' && tail -n 3 watch.out | grep -q 'w: 4/4 finished (100%)' &&
	[ $(((t_watch - t_run) / 1000000)) -lt 1000 ] && ok watch.ends_with_campaign ||
	fail watch.ends_with_campaign "exit $wrc, $(((t_watch - t_run) / 1000000)) ms from the campaign's end: $(tail -n 3 watch.out)"
# study run --progress: the same look as lines (no terminal here), ending at 100%
grep -q "frequency=[34] seed=[12] t [0-9.e+-]*/$T s" run.log && grep -q 'w: 4/4 finished (100%)' run.log &&
	ok watch.run_progress_line || fail watch.run_progress_line "$(cat run.log)"

# Ctrl-C: the watch stops at once, exit 0; the campaign is not disturbed
campaign c "$T" >c.campaign
"$STUDY" run c.campaign --runs "$TMP/C" --jobs 2 >c.log 2>&1 &
pid=$!
for i in $(seq 400); do
	[ "$(sqlite3 C/study.db "SELECT COUNT(*) FROM run WHERE state = 'running'" 2>/dev/null)" -gt 0 ] 2>/dev/null && break
	sleep 0.05
done
"$STUDY" status c --runs "$TMP/C" --watch --interval 0.5 >cw.out 2>&1 &
wpid=$!
sleep 1.2
t0=$(date +%s%N)
kill -INT $wpid
wait $wpid
wrc=$?
ms=$((($(date +%s%N) - t0) / 1000000))
[ "$wrc" -eq 0 ] && [ "$ms" -lt 700 ] && grep -q 'frequency=' cw.out && ok watch.ctrl_c || fail watch.ctrl_c "exit $wrc after $ms ms: $(tail -n 3 cw.out)"
kill -0 $pid 2>/dev/null && ok watch.campaign_undisturbed || fail watch.campaign_undisturbed "the campaign ended with the watch"
kill -TERM $pid
wait $pid
# a campaign nobody runs: one look, and it says so
"$STUDY" status c --runs "$TMP/C" --watch --interval 0.5 >idle.out 2>&1
[ $? -eq 0 ] && grep -q "no driver is running c" idle.out && ok watch.no_driver || fail watch.no_driver "$(cat idle.out)"
finish
