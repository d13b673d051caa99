#!/usr/bin/env bash
# db_damage.sh - a damaged study database is named, never read as empty (docs/database.md,
# "A damaged database"): a table's root page zeroed makes status, export, run and a tool
# say the database is corrupt with what to do, exit non-zero, and after the database is
# moved aside study run rebuilds it to the same export; a dropped table makes the readers
# name the table, and study run rebuilds it from the campaign and run files to the same
# export; a value no run can have (risen = 2, ramp = 3) is refused by the readers and
# rewritten from the run file by study run; so is a value any run could have that is not
# the one recorded (the row seal), and a byte changed inside a record.
. "$(dirname "$0")/lib.sh"
study_setup
WAITING="$(dirname "$SHAKE")/waiting"
cd "$TMP" || exit 1

# the tiny campaign (lib.sh: 4 runs of 40 grains, 0.2 s), built once per build; every
# case works on a copy
tiny_campaign t >t.campaign
fixture_runs t.campaign R || { fail setup "exit $?: $(tail -n 3 R.log)"; finish; }
# timing columns aside (started is when a driver saw the run start)
strip() { awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i == "started") s = i; if ($i == "file") p = i } } { $s = ""; $p = ""; print }' OFS=, "$1"; }
"$STUDY" export t --runs R >good.csv || fail setup "export of the undamaged database"

fresh() { rm -rf D; cp -r R D; }
# says ID WANT FILE WORDS : the command just run exited WANT ('!0': anything but 0) with
# WORDS (a basic regex) in FILE
says() {
	local rc=$? id=$1 want=$2 f=$3 words=$4
	if { [ "$rc" = "$want" ] || { [ "$want" = '!0' ] && [ "$rc" != 0 ]; }; } && grep -q -- "$words" "$f"; then
		ok "$id"
	else
		fail "$id" "exit $rc (want $want, '$words'): $(tail -c 300 "$f")"
	fi
}
# reads NAME WORDS: status, export, list, run and bin/waiting all exit non-zero naming WORDS
reads() {
	local name=$1 words=$2 bad=""
	"$STUDY" status t --runs D >st.out 2>st.err; local rs=$?
	"$STUDY" export t --runs D >ex.out 2>ex.err; local re=$?
	"$STUDY" list --runs D >li.out 2>li.err; local rl=$?
	"$WAITING" t --runs D --no-plot --no-store >wa.out 2>wa.err; local rw=$?
	[ "$rs" = 2 ] && grep -q "$words" st.err || bad="$bad status exit $rs: $(head -c 300 st.err);"
	[ "$re" = 2 ] && grep -q "$words" ex.err || bad="$bad export exit $re: $(head -c 300 ex.err);"
	[ "$rl" = 2 ] && grep -q "$words" li.err || bad="$bad list exit $rl: $(head -c 300 li.err);"
	# the tools read attempt and result when they are there (a database of an older driver lacks them)
	[ "$rw" = 2 ] && grep -q "$words" wa.err || [ "$name" = dropped_attempt ] || bad="$bad waiting exit $rw: $(head -c 300 wa.err);"
	[ -z "$bad" ] && ok "$name.readers_refuse" || fail "$name.readers_refuse" "$bad"
}
rebuilt() { # NAME: study run restores the undamaged export
	"$STUDY" export t --runs D >after.csv 2>&1
	cmp -s <(strip good.csv) <(strip after.csv) && ok "$1.rebuilt_export_equal" ||
		fail "$1.rebuilt_export_equal" "$(diff <(strip good.csv) <(strip after.csv) | head -n 3 | cut -c1-300)"
}

# --- a table's root page zeroed: corrupt, in every reader and in study run ---
for tb in run campaign param; do
	fresh
	ps=$(sqlite3 D/study.db "PRAGMA page_size")
	rp=$(sqlite3 D/study.db "SELECT rootpage FROM sqlite_schema WHERE type = 'table' AND name = '$tb'")
	dd if=/dev/zero of=D/study.db bs="$ps" seek=$((rp - 1)) count=1 conv=notrunc 2>/dev/null
	reads "zeroed_$tb" "the database is corrupt.*move it aside"
	"$STUDY" run t.campaign --runs D --no-progress >run.log 2>&1
	says "zeroed_$tb.run_refuses" 2 run.log "study.db: the database is corrupt"
	# what the message says to do
	mv D/study.db D/study.db.bad
	rm -f D/study.db-wal D/study.db-shm
	"$STUDY" run t.campaign --runs D --no-progress >run2.log 2>&1 || fail "zeroed_$tb.rebuild" "exit $?: $(tail -n 2 run2.log)"
	rebuilt "zeroed_$tb"
done

# --- an index entry that no longer matches its row: PRAGMA quick_check does not compare
# them, and study export wrote the run under the entry's campaign, exit 0 ---
fresh
sqlite3 D/study.db "PRAGMA wal_checkpoint(TRUNCATE)" >/dev/null
ps=$(sqlite3 D/study.db "PRAGMA page_size")
rp=$(sqlite3 D/study.db "SELECT rootpage FROM sqlite_schema WHERE name = 'sqlite_autoindex_run_1'")
rid=$(sqlite3 D/study.db "SELECT id FROM run ORDER BY id LIMIT 1")
# the entry's campaign 't' (just before its run id) becomes 'u', in the index page only
/usr/bin/python3 -c 'import sys
path, off, size, key = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4].encode()
with open(path, "r+b") as f:
    f.seek(off); page = f.read(size); k = page.find(b"t" + key)
    assert k >= 0, "entry not found"
    f.seek(off + k); f.write(b"u")' D/study.db $(((rp - 1) * ps)) "$ps" "$rid" || fail index_entry.setup "no entry to change"
reads index_entry "the database is corrupt (index sqlite_autoindex_run_1 disagrees with table run: 0 rows without an entry, 1 entries without their row)"

# --- a table dropped: named by the readers, rebuilt by study run ---
for tb in run param campaign attempt; do
	fresh
	sqlite3 D/study.db "DROP TABLE $tb"
	reads "dropped_$tb" "table $tb"
	"$STUDY" run t.campaign --runs D --no-progress >run.log 2>&1
	rc=$?
	[ "$rc" = 0 ] && grep -q "lacked table $tb" run.log && grep -q "4 done, 0 failed" run.log && ok "dropped_$tb.run_repairs" ||
		fail "dropped_$tb.run_repairs" "exit $rc: $(tail -n 3 run.log)"
	rebuilt "dropped_$tb"
	"$STUDY" run t.campaign --runs D --no-progress >run3.log 2>&1 && "$WAITING" t --runs D --no-plot --no-store >wa.out 2>&1 &&
		ok "dropped_$tb.tool_after" || fail "dropped_$tb.tool_after" "$(tail -n 2 run3.log wa.out)"
done

# --- a value no run can have: refused by the readers, rewritten by study run ---
fresh
sqlite3 D/study.db "UPDATE result SET risen = 2 WHERE run = (SELECT MIN(run) FROM result)"
"$STUDY" export t --runs D >ex.out 2>ex.err
says values.risen_export_refused 2 ex.err "risen = 2.*expected"
"$STUDY" run t.campaign --runs D --no-progress >run.log 2>&1
says values.risen_rewritten 0 run.log "risen = 2 in table result: expected 0 or 1.*written again from the run file"
rebuilt values_risen
fresh
sqlite3 D/study.db "UPDATE param SET value = '3' WHERE key = 'ramp' AND run = (SELECT MIN(run) FROM param)"
"$WAITING" t --runs D --no-plot --no-store >wa.out 2>wa.err
says values.ramp_tool_refused '!0' wa.err "ramp = '3'"
"$STUDY" export t --runs D >ex.out 2>ex.err
says values.ramp_export_refused 2 ex.err "ramp = '3'"
"$STUDY" run t.campaign --runs D --no-progress >run.log 2>&1
rc=$?
[ "$rc" = 0 ] && rebuilt values_ramp || fail values.ramp_rewritten "exit $rc: $(tail -n 2 run.log)"

# --- a value any run could have, not the one recorded: the row seal (lib/rowseal.h) ---
# its definition written a second time (rowseal.py) gives the seals the driver wrote,
# and another after a value changed
/usr/bin/python3 "$REPO/tests/integration/rowseal.py" check R/study.db >seals.txt
n=$(awk '$2 == $3' seals.txt | wc -l)
[ "$n" = 4 ] && [ "$(wc -l <seals.txt)" = 4 ] && ok rowseal.second_definition_agrees ||
	fail rowseal.second_definition_agrees "$n of 4 seals agree: $(head -n 4 seals.txt | tr '\n' ' ')"
fresh
sqlite3 D/study.db "UPDATE result SET steps = steps + 1 WHERE run = (SELECT MIN(run) FROM result)"
/usr/bin/python3 "$REPO/tests/integration/rowseal.py" check D/study.db >seals2.txt
[ "$(awk '$2 != $3' seals2.txt | wc -l)" = 1 ] && ok rowseal.second_definition_sees_edit ||
	fail rowseal.second_definition_sees_edit "$(cat seals2.txt | tr '\n' ' ')"
# sealed ID SQL: SQL makes export refuse naming the rows, study run write them again to
# the undamaged export (make fuzz, family database: a frequency of 25 Hz, a waiting
# time of 'abc' were exported, exit 0)
sealed() {
	fresh
	sqlite3 D/study.db "$2"
	"$STUDY" export t --runs D >ex.out 2>ex.err
	says "rows.$1.export_refused" 2 ex.err "are not those recorded (row seal [0-9a-f]*, recorded [0-9a-f]*): edited or damaged.*study run"
	[ -s ex.out ] && fail "rows.$1.export_nothing_printed" "$(head -c 200 ex.out)" || ok "rows.$1.export_nothing_printed"
	"$STUDY" run t.campaign --runs D --no-progress >run.log 2>&1
	says "rows.$1.run_writes_again" 0 run.log "not those recorded.*written again from the campaign and run files"
	rebuilt "rows_$1"
}
sealed param "UPDATE param SET value = 25 WHERE key = 'frequency' AND run = (SELECT MIN(run) FROM param)"
sealed result "UPDATE result SET waiting_time = 'abc' WHERE run = (SELECT MIN(run) FROM result)"
sealed seed "UPDATE run SET seed = seed + 1 WHERE id = (SELECT MIN(id) FROM run)"
# a run's id changed: its rows no longer meet; done without a result is named
fresh
sqlite3 D/study.db "UPDATE run SET id = 'x' || id WHERE id = (SELECT MIN(id) FROM run)"
"$STUDY" export t --runs D >ex.out 2>ex.err
says rows.id_edited.export_refused 2 ex.err "recorded done without its row in table result"
# a byte changed inside a record of table result (SQLite keeps no checksum of a page's
# content): one digit of a run's end_time, in the table's page (dbstat) of the file itself
fresh
sqlite3 D/study.db "PRAGMA wal_checkpoint(TRUNCATE)" >/dev/null
end=$(sqlite3 D/study.db "SELECT end_time FROM result ORDER BY run LIMIT 1")
pg=$(sqlite3 D/study.db "SELECT pageno FROM dbstat WHERE name = 'result' AND pagetype = 'leaf' ORDER BY pageno LIMIT 1")
ps=$(sqlite3 D/study.db "PRAGMA page_size")
/usr/bin/python3 -c 'import sys
path, s, off, size = sys.argv[1], sys.argv[2].encode(), int(sys.argv[3]), int(sys.argv[4])
b = bytearray(open(path, "rb").read()); k = b.find(s, off, off + size)
assert k >= 0, "not in the page"
i = k + len(s) - 2; b[i] = ord("0") + (b[i] - ord("0") + 1) % 10
open(path, "r+b").write(b)' D/study.db "$end" $(((pg - 1) * ps)) "$ps" || fail rows.byte_changed.setup "end_time $end not in page $pg"
[ "$(sqlite3 D/study.db "PRAGMA quick_check")" = ok ] && ok rows.byte_changed.quick_check_sees_nothing ||
	fail rows.byte_changed.quick_check_sees_nothing "$(sqlite3 D/study.db "PRAGMA quick_check" | head -n 2)"
"$STUDY" export t --runs D >ex.out 2>ex.err
says rows.byte_changed.export_refused 2 ex.err "are not those recorded"

# --- a lock held elsewhere: the wait is said, with its holder, and ends with the lock ---
fresh
# an exclusive transaction held for 4 s by another process (python3's sqlite3: its
# pid is the holder the message must name)
/usr/bin/python3 -c 'import sqlite3, time, sys
c = sqlite3.connect(sys.argv[1], isolation_level=None); c.execute("BEGIN EXCLUSIVE")
c.execute("UPDATE campaign SET name = name"); print("held", flush=True); time.sleep(4); c.execute("COMMIT")' \
	D/study.db >holder.out 2>&1 &
holder=$!
for _ in $(seq 100); do grep -q held holder.out && break; sleep 0.05; done
# (a writer: in WAL mode readers do not wait for one)
t0=$(date +%s%N)
"$STUDY" run t.campaign --runs D --no-progress >lk.out 2>lk.err
rc=$? ms=$((($(date +%s%N) - t0) / 1000000))
wait $holder
[ "$rc" = 0 ] && grep -q "D/study.db: waiting for process $holder (/usr/bin/python3 -c import sqlite3.*which holds the database's lock (up to 60 s)" lk.err &&
	[ "$ms" -ge 2000 ] && [ "$(grep -c waiting lk.err)" = 1 ] && ok lock.wait_said_with_holder ||
	fail lock.wait_said_with_holder "exit $rc after $ms ms: $(head -c 300 lk.err)"
finish
