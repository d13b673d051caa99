#!/usr/bin/env bash
# study_run.sh - `study run` end to end on a tiny campaign: every run recorded and
# ingested, the packing cache shared and bit-identical to settling per run, a second
# run does nothing, an extension runs only the new points, a failing run keeps its
# reason and is retried only with --retry-failed; status, list and export.
# tier: slow: campaigns run, extended, interrupted
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1

SCENE="[scene]
$(tiny_scene n_grains=50 depth=-)
amplitude = 1
duration = 0.25
traj_rate = 200"
mk() { # FILE NAME GRID-LINES...
	local f=$1 n=$2
	shift 2
	{ printf '[campaign]\nname = %s\nseed = 11\nreplicates = 2\n%s\n[grid]\n' "$n" "$SCENE"; printf '%s\n' "$@"; } >"$f"
}

mk t.campaign t 'frequency = 3, 4'
t0=$(date +%s%N)
"$STUDY" run t.campaign --runs "$TMP/R" --jobs 2 >run1.log 2>&1
rc=$?
echo "# first run: $((($(date +%s%N) - t0) / 1000000)) ms"
DB=R/study.db
[ "$rc" -eq 0 ] && ok run.exit || fail run.exit "exit $rc: $(tail -c 400 run1.log)"
# GNU parallel ran one job per run and kept its joblog (exit value in column 7)
[ "$(awk -F'\t' '$7 == 0 && $9 ~ / run [0-9a-f]+$/' R/t/joblog.txt 2>/dev/null | wc -l)" = 4 ] &&
	ok run.joblog || fail run.joblog "$(cat R/t/joblog.txt 2>&1 | head -n 8)"
[ "$(ls R/t/*.h5 2>/dev/null | wc -l)" = 4 ] && ok run.outputs || fail run.outputs "$(ls R/t)"
[ "$(q $DB "SELECT COUNT(*) FROM runs WHERE campaign = 't' AND state = 'done' AND status = 'ok' AND attempts = 1
	AND intruder_final_y_box IS NOT NULL AND wall_seconds > 0 AND host <> '' AND steps = 5000")" = 4 ] &&
	ok run.db_rows || fail run.db_rows "$(q $DB "SELECT id, state, status, attempts, steps FROM runs")"
# the ids in the database are the ids `study expand` gives, and the files are named by them
"$STUDY" expand t.campaign | tail -n +2 | cut -f1 | sort >ids.expand
q $DB "SELECT id FROM run WHERE campaign = 't' ORDER BY id" >ids.db
(cd R/t && ls *.h5 | sed 's/\.h5$//' | sort) >ids.files
cmp -s ids.expand ids.db && cmp -s ids.db ids.files && ok run.ids || fail run.ids "expand, database and files disagree"
# parameters recorded per run, typed
[ "$(q $DB "SELECT COUNT(DISTINCT frequency) || ' ' || MIN(frequency) || ' ' || typeof(MIN(frequency)) || ' ' || MIN(n_grains) FROM runs")" = "2 3.0 real 50" ] &&
	ok run.params || fail run.params "$(q $DB "SELECT frequency, n_grains FROM runs")"
# the output's own attributes agree with the recorded parameters
id=$(head -n 1 ids.db)
[ "$(h5param R/t/$id.h5 frequency)" = "$(q $DB "SELECT printf('%.17g', frequency) FROM runs WHERE id = '$id'")" ] &&
	[ "$(h5param R/t/$id.h5 seed)" = "$(q $DB "SELECT seed FROM run WHERE id = '$id'")" ] &&
	ok run.params_match_output || fail run.params_match_output "frequency/seed differ between $id.h5 and the database"

# --- packing cache: one settle per replicate, shared by both frequencies ---
[ "$(q $DB "SELECT COUNT(*) || ' ' || SUM(hits) FROM caches WHERE campaign = 't' AND state = 'ok'")" = "2 4" ] &&
	ok cache.hits || fail cache.hits "$(q $DB "SELECT * FROM caches")"
[ "$(q $DB "SELECT COUNT(*) FROM runs r JOIN cache c ON c.key = r.cache_key WHERE r.from_cache AND r.settle_time = c.settle_time AND c.settle_time > 0")" = 4 ] &&
	ok cache.settle_time_recorded || fail cache.settle_time_recorded "runs from the cache lack the cache's settle_time"
# the same campaign without the cache: every dataset identical, only the attributes
# that say how the packing was obtained differ
"$STUDY" run t.campaign --runs "$TMP/N" --no-cache --jobs 2 >nocache.log 2>&1 || fail cache.nocache_run "$(tail -c 300 nocache.log)"
[ "$(q N/study.db "SELECT COUNT(*) FROM run WHERE from_cache")" = 0 ] && ok cache.off || fail cache.off "from_cache set with --no-cache"
same=0
for f in R/t/*.h5; do
	b=$(basename "$f")
	same_output "$f" "N/t/$b" particles settle settle_steps settle_time && same=$((same + 1))
done
[ "$same" = 4 ] && ok cache.bit_identical || fail cache.bit_identical "only $same of 4 runs identical with and without the cache"
[ "$(q N/study.db "SELECT group_concat(printf('%.17g', intruder_final_y_box)) FROM (SELECT intruder_final_y_box FROM result ORDER BY run)")" = \
	"$(q $DB "SELECT group_concat(printf('%.17g', intruder_final_y_box)) FROM (SELECT intruder_final_y_box FROM result ORDER BY run)")" ] &&
	ok cache.same_results || fail cache.same_results "results differ with and without the cache"

# --- a second run does nothing ---
stamp=$(stat -c %Y.%s R/t/*.h5 | md5sum)
"$STUDY" run t.campaign --runs "$TMP/R" >run2.log 2>&1
rc=$?
[ "$rc" -eq 0 ] && grep -q "4 runs, 0 to run" run2.log && [ "$stamp" = "$(stat -c %Y.%s R/t/*.h5 | md5sum)" ] &&
	[ "$(q $DB "SELECT SUM(attempts) FROM run")" = 4 ] && ok rerun.nothing_to_do || fail rerun.nothing_to_do "exit $rc: $(cat run2.log)"
n=$(getconf _NPROCESSORS_ONLN)
grep -Eq "0 to run, $n jobs?\$" run2.log && ok run.jobs_default_cores || fail run.jobs_default_cores "expected $n jobs: $(cat run2.log)"

# --- extend: a new frequency and a third replicate: only the 4 new points run ---
sed 's/frequency = 3, 4/frequency = 3, 4, 5/; s/replicates = 2/replicates = 3/' t.campaign >t3.campaign
"$STUDY" run t3.campaign --runs "$TMP/R" >ext.log 2>&1
rc=$?
[ "$rc" -eq 0 ] && grep -q "9 runs, 5 to run" ext.log && ok extend.only_new || fail extend.only_new "exit $rc: $(cat ext.log)"
[ "$(q $DB "SELECT COUNT(*) || ' ' || SUM(attempts) || ' ' || SUM(state = 'done') FROM run")" = "9 9 9" ] &&
	[ "$stamp" = "$(stat -c %Y.%s $(sed 's|^|R/t/|; s|$|.h5|' ids.db) | md5sum)" ] &&
	ok extend.old_untouched || fail extend.old_untouched "$(q $DB "SELECT id, attempts, state FROM run")"
# the new replicate's packing is settled once for its 3 frequencies; replicates 1, 2
# reuse theirs for the new frequency
[ "$(q $DB "SELECT COUNT(*) || ' ' || SUM(hits) FROM caches")" = "3 9" ] && ok extend.cache_reused ||
	fail extend.cache_reused "$(q $DB "SELECT key, hits FROM caches")"

# --- every column of the run tables is in its row of docs/database.md's table (lib/schema.c
# declares them; a column added without its documentation fails here) ---
undoc=
for t in campaign run param attempt cache; do
	row=$(grep "^| \`$t\` |" "$REPO/docs/database.md")
	for c in $(q $DB "SELECT name FROM pragma_table_info('$t')"); do
		case $row in *"\`$c\`"*) ;; *) undoc+=" $t.$c" ;; esac
	done
done
[ -z "$undoc" ] && [ -n "$(q $DB "SELECT name FROM pragma_table_info('attempt') WHERE name = 'cpu_seconds'")" ] &&
	ok db.columns_documented || fail db.columns_documented "not in docs/database.md's table:$undoc"

# --- the example queries of docs/database.md and docs/driver.md, pasted as a user
# would (on campaign t) ---
cat "$REPO/docs/database.md" "$REPO/docs/driver.md" | sed -n '/^```sql$/,/^```$/p' | grep -v '^```' |
	sed "s/'demo'/'t'/g; s/'claim4_waiting_time'/'t'/g" >examples.sql
nq=0 nbad=0
while IFS= read -r -d ';' stmt; do
	[ -n "$(printf '%s' "$stmt" | grep -v '^ *--' | tr -d ' \n')" ] || continue
	nq=$((nq + 1))
	out=$(printf '%s;\n' "$stmt" | sqlite3 -batch -bail "$DB" 2>&1) && case "$out" in *rror*) false ;; esac ||
		{ nbad=$((nbad + 1)); echo "# query failed: $stmt -> $out"; }
done <examples.sql
[ "$nq" -ge 7 ] && [ "$nbad" = 0 ] && ok readme.example_queries || fail readme.example_queries "$nbad of $nq queries failed"
[ "$(q $DB "$(awk '/mean rise of the intruder per frequency/ { on = 1; next } on && /;/ { print; exit } on' examples.sql)" | wc -l)" = 3 ] &&
	ok readme.rise_per_frequency || fail readme.rise_per_frequency "expected one row per frequency (3)"

# --- a failing run: its reason recorded, retried only on request ---
{ printf '[campaign]\nname = f\nseed = 1\n%s\ndt_guard = off\n[grid]\ndt = 5e-5, 0.002\n' "$SCENE"; } >f.campaign
"$STUDY" run f.campaign --runs "$TMP/R" >fail1.log 2>&1
rc=$?
[ "$rc" -eq 3 ] && ok fail.exit_code || fail fail.exit_code "exit $rc, expected 3: $(tail -c 300 fail1.log)"
row=$(q $DB "SELECT state || '|' || status || '|' || exit_code || '|' || attempts FROM runs WHERE campaign = 'f' AND dt = 0.002")
[ "$row" = "failed|overlap|4|1" ] && ok fail.recorded || fail fail.recorded "got '$row'"
q $DB "SELECT message FROM failures WHERE campaign = 'f'" | grep -q "overlap of disks" && ok fail.reason ||
	fail fail.reason "$(q $DB "SELECT * FROM failures")"
[ "$(q $DB "SELECT state FROM runs WHERE campaign = 'f' AND dt = 5e-5")" = done ] && ok fail.others_done || fail fail.others_done "the good run did not finish"
"$STUDY" status f --runs "$TMP/R" >status.out 2>&1
grep -q "failed 1" status.out && grep -q "overlap of disks" status.out && ok status.failures ||
	fail status.failures "$(cat status.out)"
"$STUDY" run f.campaign --runs "$TMP/R" >fail2.log 2>&1
rc=$?
[ "$rc" -eq 3 ] && grep -q "0 to run" fail2.log && [ "$(q $DB "SELECT attempts FROM run WHERE campaign = 'f' AND state = 'failed'")" = 1 ] &&
	ok fail.not_retried || fail fail.not_retried "exit $rc: $(cat fail2.log)"
"$STUDY" run f.campaign --runs "$TMP/R" --retry-failed >fail3.log 2>&1
fid=$(q $DB "SELECT id FROM run WHERE campaign = 'f' AND state = 'failed'")
[ "$(q $DB "SELECT COUNT(*) || ' ' || COUNT(DISTINCT message) FROM attempt WHERE campaign = 'f' AND run = '$fid'")" = "2 1" ] &&
	[ -e "R/f/failed/$fid.attempt1.h5" ] && [ -e "R/f/$fid.h5" ] && ok fail.retry_keeps_attempts ||
	fail fail.retry_keeps_attempts "$(q $DB "SELECT * FROM attempt WHERE campaign = 'f'")"
# a database rebuilt from the files gets the history back: the kept attempt, the last
# one, and when each run started
hist() { q "$1" "SELECT n || ':' || status || ':' || exit_code || ':' || message FROM attempt WHERE campaign = 'f' AND run = '$fid' ORDER BY n"; }
before=$(hist $DB)
cp $DB rebuilt.orig.db
rm -f $DB $DB-wal $DB-shm
"$STUDY" run f.campaign --runs "$TMP/R" >rebuild.log 2>&1
after=$(hist $DB)
[ -n "$before" ] && [ "$before" = "$after" ] && ok rebuild.attempt_history ||
	fail rebuild.attempt_history "before: $before; after: $after"
[ "$(q $DB "SELECT COUNT(*) FROM run WHERE campaign = 'f' AND started IS NULL")" = 0 ] &&
	[ "$(q $DB "SELECT attempts FROM run WHERE campaign = 'f' AND id = '$fid'")" = 2 ] && ok rebuild.started ||
	fail rebuild.started "$(q $DB "SELECT id, attempts, started FROM run WHERE campaign = 'f'")"
cp rebuilt.orig.db $DB && rm -f $DB-wal $DB-shm

# --- list and export ---
"$STUDY" list --runs "$TMP/R" >list.out 2>&1
grep -Eq '^t +9 +9 +0 +0 ' list.out && grep -Eq '^f +2 +1 +1 +0 ' list.out && ok list || fail list "$(cat list.out)"
"$STUDY" export t --runs "$TMP/R" -o t.csv 2>export.err
head -n 1 t.csv | grep -q '^campaign,id,state,attempts,replicate,.*frequency.*,intruder_final_y_box' &&
	[ "$(wc -l <t.csv)" = 10 ] && ok export.csv || fail export.csv "$(head -c 300 t.csv) $(cat export.err)"
"$STUDY" export nosuch --runs "$TMP/R" >/dev/null 2>exp.err
rc=$?
[ $rc = 1 ] && grep -q "nosuch" exp.err && ok export.unknown || fail export.unknown "exit $rc: $(head -n 1 exp.err)"
# the database answers while a driver holds it (WAL): a reader during a run
"$STUDY" run t3.campaign --runs "$TMP/R" --retry-failed >/dev/null 2>&1 &
pid=$!
q $DB "SELECT COUNT(*) FROM runs" >/dev/null 2>reader.err && ok db.concurrent_reader || fail db.concurrent_reader "$(cat reader.err)"
wait $pid
# a second driver on the same campaign is refused while the first holds it
mk slow.campaign slow 'frequency = 3, 4, 5, 6'
sed -i 's/duration = 0.25/duration = 3/' slow.campaign
"$STUDY" run slow.campaign --runs "$TMP/R" --jobs 1 >slow1.log 2>&1 &
pid=$!
for i in $(seq 100); do [ -e R/slow/jobs ] && break; sleep 0.05; done
sleep 0.3
"$STUDY" run slow.campaign --runs "$TMP/R" >slow2.log 2>&1
rc=$?
[ "$rc" -eq 4 ] && grep -q "another study driver" slow2.log && ok driver.exclusive || fail driver.exclusive "exit $rc: $(cat slow2.log)"
# each run is in the database as soon as it has finished, and sqlite3 reads it while
# the driver is still running the others (8 runs, one job at a time)
live=
for i in $(seq 400); do
	kill -0 $pid 2>/dev/null || break
	n=$(q $DB "SELECT COUNT(*) FROM runs WHERE campaign = 'slow' AND state = 'done' AND status = 'ok'" 2>/dev/null)
	if [ "${n:-0}" -ge 1 ] && kill -0 $pid 2>/dev/null; then live=$n; break; fi
	sleep 0.05
done
[ -n "$live" ] && [ "$live" -lt 8 ] && ok db.ingested_while_running ||
	fail db.ingested_while_running "no finished run in the database while the driver ran: $(tail -c 300 slow1.log)"
# the TERM meets a run in flight (not the moment between two): one that has written a
# checkpoint (it shakes) and no output yet, whatever the machine's load
shaking_run() {
	local id
	id=$(q $DB "SELECT id FROM run WHERE campaign = 'slow' AND state = 'running'" 2>/dev/null)
	[ -n "$id" ] && [ -e "R/slow/$id.h5.ckpt" ] && [ ! -e "R/slow/$id.h5" ]
}
for i in $(seq 600); do
	shaking_run && break
	kill -0 $pid 2>/dev/null || break
	sleep 0.02
done
kill -TERM $pid 2>/dev/null
wait $pid
# every attempt records what its engine used (wait4), the one the TERM interrupted too
# (its DONE line dropped by GNU parallel: from the worker's line in its log)
use=$(q $DB "SELECT SUM(status = 'interrupted'), SUM(status = 'interrupted' AND cpu_seconds > 0 AND max_rss_kb > 0),
	SUM(status = 'ok'), SUM(status = 'ok' AND cpu_seconds > 0 AND max_rss_kb > 0) FROM attempt WHERE campaign = 'slow'")
IFS='|' read -r ni niu nk nku <<<"$use"
[ "${ni:-0}" -ge 1 ] && [ "$ni" = "$niu" ] && [ "${nk:-0}" -ge 1 ] && [ "$nk" = "$nku" ] && ok attempt.usage_recorded ||
	fail attempt.usage_recorded "interrupted, with usage, ok, with usage: $use: $(q $DB "SELECT status, cpu_seconds, max_rss_kb FROM attempt WHERE campaign = 'slow'")"
# status of a half-done campaign: counts and an ETA from the finished runs
"$STUDY" status slow --runs "$TMP/R" >slow_status.out 2>&1
grep -Eq "runs 8: done [1-7], failed 0, pending [1-7]" slow_status.out && grep -q "ETA: about" slow_status.out &&
	ok status.eta || fail status.eta "$(cat slow_status.out)"
# --progress shows GNU parallel's bar (on stderr); without a terminal there is none by default
# (the bar needs runs, not long ones: two of a twentieth of a second)
mk bar.campaign bar 'frequency = 3'
sed -i 's/duration = 0.25/duration = 0.05/' bar.campaign
"$STUDY" run bar.campaign --runs "$TMP/P" --jobs 2 --progress >bar.log 2>&1
grep -q "100%" bar.log && ! grep -q "100%" run1.log && ok run.progress_bar || fail run.progress_bar "$(tail -c 300 bar.log)"
finish
