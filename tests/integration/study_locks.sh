#!/usr/bin/env bash
# study_locks.sh - one driver per campaign and database, and no writing through links
# (docs/driver.md, "What `study run` does", step 2, and "Safety"): a second driver
# on the same --db with another --runs is refused with exit 4 while the first runs; a
# symbolic link planted in the campaign directory (logs/, jobs/, cache/, the directory
# itself, the joblog) is refused naming the path, and nothing is written where it
# points.
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1

# the tiny campaign (lib.sh), one replicate
tiny_campaign l 3 | sed '/^replicates = /d' >l.campaign

# --- two drivers, one database, two runs directories ---
"$STUDY" run l.campaign --runs A --db "$TMP/shared.db" --jobs 1 --no-progress >a.log 2>&1 &
first=$!
for _ in $(seq 1 400); do
	[ -f "$TMP/shared.db.l.lock" ] && break
	sleep 0.05
done
"$STUDY" run l.campaign --runs B --db "$TMP/shared.db" --jobs 1 --no-progress >b.log 2>&1
rc=$?
wait "$first"
rc1=$?
[ "$rc" = 4 ] && grep -q "another study driver" b.log && grep -qF "shared.db" b.log && ok db_lock.second_driver_refused ||
	fail db_lock.second_driver_refused "exit $rc: $(cat b.log)"
[ "$rc1" = 0 ] && [ -z "$(ls B/l/*.h5 2>/dev/null)" ] && ok db_lock.first_completes_alone ||
	fail db_lock.first_completes_alone "exit $rc1: $(tail -n 2 a.log); B has $(ls B/l 2>/dev/null | tr '\n' ' ')"
# another campaign on the same database is not held back
sed -e 's/^name = l/name = l2/' l.campaign >l2.campaign
# campaign l's lock held from the moment it is taken (a state) until the test lets it go,
# however long the l2 campaign takes (a lock held 30 s from a start 0.2 s before was a
# race a loaded machine lost: the lock gone before its check, exit 0)
(exec 9>>"$TMP/shared.db.l.lock" && flock 9 && : >lock.held && while [ ! -e lock.release ]; do sleep 0.05; done) &
holder=$!
while [ ! -e lock.held ] && kill -0 "$holder" 2>/dev/null; do sleep 0.05; done
[ -e lock.held ] || fail db_lock.setup "flock on $TMP/shared.db.l.lock did not take the lock"
"$STUDY" run l2.campaign --runs B --db "$TMP/shared.db" --jobs 1 --no-progress >l2.log 2>&1 &&
	ok db_lock.other_campaign_runs || fail db_lock.other_campaign_runs "exit $?: $(tail -n 2 l2.log)"
"$STUDY" run l.campaign --runs C --db "$TMP/shared.db" --no-progress >c.log 2>&1
rc=$?
: >lock.release
wait "$holder" 2>/dev/null
[ "$rc" = 4 ] && ok db_lock.held_lock_exit_4 || fail db_lock.held_lock_exit_4 "exit $rc: $(cat c.log)"

# --- symbolic links planted in the campaign directory ---
# plant NAME PATH : a fresh runs directory S_NAME whose PATH (relative to the campaign
# directory; "." for the directory itself) is a link to OUT_NAME, then study run
plant() {
	local name=$1 path=$2
	local R="S_$name" out="$TMP/OUT_$name"
	mkdir -p "$R/l" "$out"
	if [ "$path" = . ]; then
		rmdir "$R/l"
		ln -s "$out" "$R/l"
	else
		mkdir -p "$(dirname "$R/l/$path")"
		ln -s "$out" "$R/l/$path"
	fi
	"$STUDY" run l.campaign --runs "$R" --jobs 1 --no-progress >"$name.log" 2>&1
	rc=$?
	local left
	left=$(ls -A "$out")
	[ "$rc" = 2 ] && grep -q "symbolic link" "$name.log" && grep -qF "$R/l" "$name.log" &&
		[ -z "$left" ] && ok "symlink.$name.refused" ||
		fail "symlink.$name.refused" "exit $rc, written outside: '$left': $(tail -n 2 "$name.log")"
}
plant logs logs
plant jobs jobs
plant cache cache
plant failed failed
plant dir .
# a link at a file the driver writes (GNU parallel's joblog)
mkdir -p S_joblog/l OUT_joblog
ln -s "$TMP/OUT_joblog/joblog" S_joblog/l/joblog.txt
"$STUDY" run l.campaign --runs S_joblog --jobs 1 --no-progress >joblog.log 2>&1
rc=$?
[ "$rc" = 2 ] && grep -q "joblog.txt: is a symbolic link" joblog.log && [ -z "$(ls -A OUT_joblog)" ] &&
	ok symlink.joblog.refused || fail symlink.joblog.refused "exit $rc: $(tail -n 2 joblog.log)"
finish
