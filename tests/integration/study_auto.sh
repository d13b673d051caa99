#!/usr/bin/env bash
# study_auto.sh - replicates = auto on a fixed grid (docs/driver.md, "Replicates until
# the answer is sharp") with the real engine: a grid of two points whose intruder
# rises within a fraction of a second; a loose target stops every point after its
# first batch, a tight one at max_replicates; the runs are those of a fixed grid with
# as many replicates (same ids); a driver killed mid-campaign and run again ends with
# the same runs; study status shows every point's interval; bad input is refused with
# file, line and key.
# tier: slow: auto replicates until a verdict, one killed
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1

# 60 grains, an intruder of 2 mean radii at A = 1.5 cm, 8 and 9 Hz: every packing's
# intruder rises within 0.8 s; runs end at the rise
campaign() { # NAME [CAMPAIGN-LINES...]
	printf '[campaign]\nname = %s\nseed = 11\n' "$1"
	shift
	[ $# -gt 0 ] && printf '%s\n' "$@"
	cat <<C
[scene]
preset = fast
$(tiny_scene width=16 radius_ratio=${RR:-2} depth=-)
amplitude = 1.5
duration = 4
stop = risen
traj_rate = 0
snapshots = no
[grid]
frequency = 8, 9
C
	[ -n "${GRIDX:-}" ] && printf '%s\n' "$GRIDX"
	return 0
}
# at level 0.75 three runs give an interval of the median: batches of 3 up to 6
AUTO=('replicates = auto' 'result = median_wait' 'batch = 3' 'max_replicates = 6' 'level = 0.75')

# --- bad input: refused before anything runs, with file, line and key ---
bad() { # ID EXPECTED [campaign] lines...
	local id=$1 want=$2
	shift 2
	campaign bad "$@" >bad.campaign
	local out rc
	out=$("$STUDY" run bad.campaign --runs "$TMP/BAD" 2>&1)
	rc=$?
	if [ "$rc" -eq 1 ] && printf '%s' "$out" | grep -qF -- "$want" && [ ! -e BAD/bad ]; then ok "$id"; else
		fail "$id" "exit $rc: $out"; fi
}
bad auto.bad.no_result "bad.campaign:4: replicates: auto needs result = median_wait|rise_fraction|mean_flux" \
	'replicates = auto' 'target = 1'
bad auto.bad.no_target "bad.campaign:4: replicates: auto needs target = W" \
	'replicates = auto' 'result = median_wait'
bad auto.bad.result "bad.campaign:5: result: expected one of median_wait|rise_fraction|mean_flux, got 'mode'" \
	'replicates = auto' 'result = mode' 'target = 1'
bad auto.bad.target "bad.campaign:6: target: expected a number in (0, 1e+09], got '0'" \
	'replicates = auto' 'result = median_wait' 'target = 0'
bad auto.bad.level "bad.campaign:7: level: expected a number in [0.5, 0.999], got '1'" \
	'replicates = auto' 'result = median_wait' 'target = 1' 'level = 1'
bad auto.bad.batch "bad.campaign:7: batch: expected an integer in [1, 1000], got '0'" \
	'replicates = auto' 'result = median_wait' 'target = 1' 'batch = 0'
bad auto.bad.max "bad.campaign:7: max_replicates: at least 6 replicates are needed for an interval of the median wait at level 0.95, got 4" \
	'replicates = auto' 'result = median_wait' 'target = 1' 'max_replicates = 4'
bad auto.bad.without_auto "bad.campaign:5: batch: only with replicates = auto under [campaign]" \
	'replicates = 3' 'batch = 3'
bad auto.bad.replicates "bad.campaign:4: replicates: expected auto or an integer in [1, 100000], got 'many'" \
	'replicates = many'
RR=0 bad auto.bad.no_intruder "bad.campaign:5: result: median_wait needs an intruder, but grid point frequency=8 has radius_ratio = 0" \
	'replicates = auto' 'result = median_wait' 'target = 1'
GRIDX='seed = 1..3' bad auto.bad.seed_axis "bad.campaign:21: seed: replicates = auto (line 4) numbers the replicates 1, 2, ...; remove it" \
	'replicates = auto' 'result = median_wait' 'target = 1'

# --- the first batch, without running anything ---
campaign loose "${AUTO[@]}" 'target = 100' >loose.campaign
"$STUDY" expand loose.campaign >expand.tsv 2>expand.err
[ "$(awk -F'\t' 'NR > 1 { print $3 ":" $5 }' expand.tsv | sort | tr '\n' ' ')" = "1:8 1:9 2:8 2:9 3:8 3:9 " ] &&
	ok auto.expand.first_batch || fail auto.expand.first_batch "$(cat expand.tsv expand.err)"

# runs per point: "frequency:count ..."
per_point() { # DB CAMPAIGN
	sqlite3 "$1" "SELECT printf('%g', frequency) || ':' || COUNT(*) || ':' || MAX(replicate) FROM runs
		WHERE campaign = '$2' AND current GROUP BY frequency ORDER BY frequency" | tr '\n' ' '
}

# --- a loose target: every point stops after its first batch ---
"$STUDY" run loose.campaign --runs "$TMP/L" --jobs 2 >loose.log 2>&1
rc=$?
[ "$rc" -eq 0 ] && [ "$(per_point L/study.db loose)" = "8:3:3 9:3:3 " ] &&
	[ "$(grep -c 'replicates round' loose.log)" = 1 ] &&
	grep -q "loose: frequency=8: median_wait .*, 75% interval \[.*\] (width .*, target 100), 3 replicates (3 used): done" loose.log &&
	ok auto.loose.first_batch || fail auto.loose.first_batch "exit $rc: $(per_point L/study.db loose) $(tail -c 600 loose.log)"

# --- a tight target: every point goes on to max_replicates, a batch at a time ---
campaign tight "${AUTO[@]}" 'target = 1e-9' >tight.campaign
"$STUDY" run tight.campaign --runs "$TMP/T" --jobs 2 >tight.log 2>&1
rc=$?
[ "$rc" -eq 0 ] && [ "$(per_point T/study.db tight)" = "8:6:6 9:6:6 " ] &&
	[ "$(grep -c 'replicates round' tight.log)" = 2 ] &&
	grep -q "tight: frequency=9: .* 6 replicates (6 used): max_replicates" tight.log &&
	ok auto.tight.max_replicates || fail auto.tight.max_replicates "exit $rc: $(per_point T/study.db tight) $(tail -c 600 tight.log)"
# the interval stored is the order-statistic interval of the six waits (level 0.75:
# ranks 2 and 5), every run risen
want=$(sqlite3 T/study.db "SELECT group_concat(w, ' ') FROM (SELECT printf('%g', frequency) || ':' ||
	printf('%g', (SELECT waiting_time FROM runs r2 WHERE r2.campaign = 'tight' AND r2.frequency = r.frequency
	 ORDER BY waiting_time LIMIT 1 OFFSET 1)) || ':' ||
	printf('%g', (SELECT waiting_time FROM runs r2 WHERE r2.campaign = 'tight' AND r2.frequency = r.frequency
	 ORDER BY waiting_time LIMIT 1 OFFSET 4)) AS w FROM runs r WHERE campaign = 'tight' GROUP BY frequency ORDER BY frequency)")
got=$(sqlite3 T/study.db "SELECT group_concat(w, ' ') FROM (SELECT substr(grp, 11) || ':' || printf('%g', ci_lo) || ':' ||
	printf('%g', ci_hi) AS w FROM auto_point WHERE campaign = 'tight' ORDER BY point)")
[ -n "$want" ] && [ "$want" = "$got" ] && [ "$(sqlite3 T/study.db "SELECT MIN(risen) FROM runs WHERE campaign = 'tight'")" = 1 ] &&
	ok auto.tight.interval || fail auto.tight.interval "waits give $want, stored $got"

# --- ordinary runs: the same ids as a fixed grid of 6 replicates ---
campaign fixed 'replicates = 6' >fixed.campaign
"$STUDY" expand fixed.campaign 2>/dev/null | awk -F'\t' 'NR > 1 { print $1 }' | sort >fixed.ids
sqlite3 T/study.db "SELECT id FROM runs WHERE campaign = 'tight' ORDER BY id" >tight.ids
cmp -s fixed.ids tight.ids && [ "$(wc -l <tight.ids)" = 12 ] && ok auto.runs.same_as_fixed_grid ||
	fail auto.runs.same_as_fixed_grid "$(paste fixed.ids tight.ids | head)"
"$STUDY" export tight --runs "$TMP/T" >export.csv 2>/dev/null
[ "$(($(wc -l <export.csv) - 1))" = 12 ] && ok auto.export.every_run || fail auto.export.every_run "$(wc -l <export.csv)"

# --- status: per point the interval reached and the runs so far ---
"$STUDY" status tight --runs "$TMP/T" >status.txt 2>&1
grep -q "replicates auto (last pass .*): median_wait, 3 at a time up to 6, until the 75% interval is at most 1e-09 wide" status.txt &&
	grep -Eq "^ +frequency=8 +6 +6 +0 +0 +[0-9.]+ +\[[0-9.]+, [0-9.]+\] +[0-9.e-]+ +max_replicates" status.txt &&
	ok auto.status.points || fail auto.status.points "$(cat status.txt)"

tight_iv=$(sqlite3 T/study.db "SELECT group_concat(printf('%g:%g', ci_lo, ci_hi), ' ') FROM auto_point ORDER BY point")

# --- run again: nothing new; a looser target keeps every run ---
"$STUDY" run tight.campaign --runs "$TMP/T" --jobs 2 >again.log 2>&1
[ $? -eq 0 ] && ! grep -q 'replicates round' again.log && [ "$(per_point T/study.db tight)" = "8:6:6 9:6:6 " ] &&
	ok auto.rerun.nothing_new || fail auto.rerun.nothing_new "$(tail -c 400 again.log)"
sed -i 's/^target = 1e-9/target = 100/' tight.campaign
"$STUDY" run tight.campaign --runs "$TMP/T" --jobs 2 >looser.log 2>&1
# the sequence is the file's and the results': the looser target stops after the
# first batch again, and the later replicates stay recorded runs of the campaign
[ $? -eq 0 ] && grep -q "tight: frequency=8: .* 3 replicates (3 used): done" looser.log &&
	! grep -q 'replicates round' looser.log && [ "$(per_point T/study.db tight)" = "8:6:6 9:6:6 " ] &&
	ok auto.retarget.keeps_runs ||
	fail auto.retarget.keeps_runs "$(tail -c 400 looser.log)"

# --- SIGKILL of the driver mid-campaign, run again: the same runs as uninterrupted ---
campaign tight "${AUTO[@]}" 'target = 1e-9' >kill.campaign
"$STUDY" run kill.campaign --runs "$TMP/K" --jobs 2 >kill1.log 2>&1 &
pid=$!
for _ in $(seq 1 100); do
	[ "$(sqlite3 K/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'" 2>/dev/null)" -ge 2 ] 2>/dev/null && break
	sleep 0.05
done
# (bash reports the killed job on stderr: not a failure)
exec 3>&2 2>/dev/null
kill -9 "$pid"
wait "$pid"
exec 2>&3 3>&-
sleep 0.5
"$STUDY" run kill.campaign --runs "$TMP/K" --jobs 2 >kill2.log 2>&1
rc=$?
sqlite3 K/study.db "SELECT id FROM runs WHERE campaign = 'tight' ORDER BY id" >kill.ids
[ "$rc" -eq 0 ] && cmp -s kill.ids tight.ids &&
	[ "$(sqlite3 K/study.db "SELECT group_concat(printf('%g:%g', ci_lo, ci_hi), ' ') FROM auto_point ORDER BY point")" = \
	  "$tight_iv" ] &&
	ok auto.resume.same_runs || fail auto.resume.same_runs "exit $rc: $(paste kill.ids tight.ids | head -3) $(tail -c 300 kill2.log)"
finish
