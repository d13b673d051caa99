#!/usr/bin/env bash
# hostile_paths.sh - the engine's rule for what stands at a path (docs/output.md,
# docs/inputs.md "Files") holds for the analysis tools, the study database and
# bin/dumpflux: a symbolic link, FIFO, character device or directory at a tool's CSV,
# gnuplot script or figure, at the tools' output directory, at the database or a file
# SQLite keeps beside it, at study export's --output, or at a dumpflux input is refused at
# once (exit code and message naming the path and what stands there), left as it was,
# nothing written through a link; an empty database is named empty; a campaign named
# after the runs directory's own files is refused with file, line and key; a done run
# whose file became a dangling link is moved aside into damaged/ and run again, and a
# node planted at its damaged/ name is not renamed over; -j2 is read as -j 2; a full
# disk under a tool's output directory (a small tmpfs, root only) is exit 2 naming the
# table and the system's word, the earlier tables kept whole, no temporary left;
# dumpflux stats power refuses a bed count it cannot compute quickly. The devices are
# made here with /dev/null's numbers (mknod, root only; said with a SKIP line otherwise).
# tier: slow: a campaign, then about 150 invocations of the tools and the driver refused
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
DUMPFLUX=$BINDIR/dumpflux
cd "$TMP" || exit 1
LIMIT=20 # seconds: a refusal is at once; a hang is what this catches

KINDS="symlink fifo chardev dir"
mknod "$TMP/probe" c 1 3 2>/dev/null || { KINDS="symlink fifo dir"; echo "SKIP chardev: mknod is not allowed here (not root)"; }
rm -f "$TMP/probe"
echo "the target" >"$TMP/target"
ln -s "$TMP/target" "$TMP/anchor" # the node a check without one of its own looks at
# plant PATH KIND: a fresh node; same PATH KIND: still that node, a link's target untouched
plant() {
	rm -rf "$1"
	case $2 in
	symlink) ln -s "$TMP/target" "$1" ;; fifo) mkfifo "$1" ;; chardev) mknod "$1" c 1 3 ;; dir) mkdir "$1" ;;
	esac
}
same() {
	local want
	case $2 in
	symlink) want="symbolic link" ;; fifo) want=fifo ;; chardev) want="character special file" ;; dir) want=directory ;;
	esac
	[ "$(stat -c %F "$1")" = "$want" ] && [ "$(cat "$TMP/target")" = "the target" ] || return 1
	[ "$2" != chardev ] || [ "$(stat -c %t:%T "$1")" = 1:3 ] || return 1
	[ "$2" != symlink ] || [ "$(readlink "$1")" = "$TMP/target" ]
}
# what KIND: the words the message uses for it
what() {
	case $1 in
	symlink) echo "a symbolic link" ;; fifo) echo "a FIFO" ;; chardev) echo "a character device" ;; dir) echo "a directory" ;;
	esac
}
# refused ID RC-WANT NEEDLE PATH KIND -- COMMAND...: COMMAND exits RC-WANT within LIMIT with
# NEEDLE on stderr, the node at PATH unchanged
refused() {
	local id=$1 want=$2 needle=$3 p=$4 kind=$5 rc
	shift 6
	timeout -k 5 "$LIMIT" "$@" >"$TMP/$id.out" 2>"$TMP/$id.err"
	rc=$?
	if [ "$rc" = "$want" ] && grep -qF -- "$needle" "$TMP/$id.err" && same "$p" "$kind"; then
		ok "$id"
	else
		fail "$id" "exit $rc (want $want), $(stat -c %F "$p" 2>&1), stderr: $(head -c 300 "$TMP/$id.err")"
	fi
}

# --- a small campaign (tests/fuzz/runs.campaign: 4 runs with every observable) ---
cp "$REPO/tests/fuzz/runs.campaign" fz.campaign
"$STUDY" run fz.campaign --runs R -j2 --no-progress >setup.log 2>&1 &&
	[ "$(sqlite3 R/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'")" = 4 ] && ok setup.campaign_and_j2 ||
	{ fail setup.campaign_and_j2 "$(tail -c 400 setup.log)"; finish; }
A=R/fz/analysis

# --- the tools' outputs: a CSV, a gnuplot script, a figure, and the directory ---
# tool:file (the tool writes file into its output directory)
OUTS=("waiting:waiting_km.csv" "onset:onset_runs.csv" "rolls:rolls.gp" "onset:onset.png" "figures:fig1.pdf")
for kind in $KINDS; do
	for c in "${OUTS[@]}"; do
		t=${c%%:*} f=${c#*:}
		mkdir -p "$A"
		plant "$A/$f" "$kind"
		refused "out.$kind.${f//./_}" 2 "$A/$f: $(what "$kind") stands there, not a regular file: not written" \
			"$A/$f" "$kind" -- "$BINDIR/$t" fz --runs R --no-store
		rm -rf "${A:?}/$f"
	done
	[ "$kind" = dir ] && continue # a directory is what belongs there
	rm -rf "$A"
	plant "$A" "$kind"
	refused "outdir.$kind" 2 "$A: $(what "$kind") stands there, not a directory: nothing written" "$A" "$kind" -- \
		"$BINDIR/ring" fz --runs R --no-store
	rm -rf "$A"
done
# and with nothing planted, no temporary is left and the figures are there
"$BINDIR/onset" fz --runs R --no-store >onset.log 2>&1 && [ -s $A/onset.png ] && [ -s $A/onset.pdf ] &&
	[ -z "$(ls $A | grep '\.tmp\.')" ] && ok out.figures_renamed_into_place ||
	fail out.figures_renamed_into_place "$(ls $A | tr '\n' ' '): $(tail -c 300 onset.log)"

# --- a full disk under the tools' output (a small tmpfs, root only): the write that
# fails is an I/O error naming the file and the system's word; the tables written
# before stay as they were, whole; no temporary is left; in a fresh directory nothing
# is put at a table's name ---
FULL=$TMP/full
mkdir -p "$FULL"
if mount -t tmpfs -o size=256k tmpfs "$FULL" 2>/dev/null; then
	trap 'umount "$FULL" 2>/dev/null; rm -rf "$TMP"' EXIT # before lib.sh's rm -rf meets the mount
	W=$FULL/w
	# the earlier tables with one histogram bin; the rewrite with 1000 would need more
	# room than the old histogram frees (a table truncated in place runs out of disk)
	"$BINDIR/waiting" fz --runs R --no-store --no-plot --bins 1 --out "$W" >full0.log 2>&1 && [ -s "$W/waiting_km.csv" ] &&
		cp -r "$W" keep && ok full.first_written || fail full.first_written "$(tail -c 300 full0.log)"
	dd if=/dev/zero of="$FULL/fill" bs=4k >/dev/null 2>&1 # until the disk is full
	"$BINDIR/waiting" fz --runs R --no-store --no-plot --bins 1000 --out "$W" >full1.log 2>full1.err
	rc=$?
	[ "$rc" = 2 ] && grep -qE "^waiting: $W/waiting_[a-z_]+\.csv: write failed: No space left on device$" full1.err &&
		ok full.write_failed_named || fail full.write_failed_named "exit $rc, stderr: $(head -c 300 full1.err)"
	diff -r keep "$W" >full.diff 2>&1 && ok full.old_tables_kept || fail full.old_tables_kept "$(head -c 300 full.diff)"
	"$BINDIR/onset" fz --runs R --no-store --no-plot --out "$FULL/new" >full2.log 2>full2.err
	rc=$?
	[ "$rc" = 2 ] && grep -qF "$FULL/new/onset_" full2.err && grep -qF ": write failed: No space left on device" full2.err &&
		[ -z "$(ls -A "$FULL/new")" ] && ok full.nothing_at_the_name ||
		fail full.nothing_at_the_name "exit $rc, $(ls -A "$FULL/new" | tr '\n' ' '), stderr: $(head -c 300 full2.err)"
	umount "$FULL"
else
	skip full.tool_outputs "cannot mount a tmpfs here (not root?)"
fi

# --- a killed tool's temporaries: the next writer of the same table clears them ---
# (SIGKILL comes before the rename; fs_clear_litter) a dead process's NAME.tmp.PID goes,
# a live one's and a node planted at such a name stay
L=$TMP/litter
mkdir -p "$L"
dead=$(sh -c 'echo $$') # a process that has ended
echo half >"$L/waiting_km.csv.tmp.$dead"
echo half >"$L/waiting_km.gp.tmp.$dead"
echo live >"$L/waiting_km.csv.tmp.$$"
mkfifo "$L/waiting_runs.csv.tmp.$dead"
"$BINDIR/waiting" fz --runs R --no-store --out "$L" >litter.log 2>&1
rc=$?
[ "$rc" = 0 ] && [ ! -e "$L/waiting_km.csv.tmp.$dead" ] && [ ! -e "$L/waiting_km.gp.tmp.$dead" ] &&
	ok litter.dead_writer_cleared || fail litter.dead_writer_cleared "exit $rc: $(ls "$L" | grep tmp | tr '\n' ' ')"
[ "$(cat "$L/waiting_km.csv.tmp.$$" 2>/dev/null)" = live ] && [ -p "$L/waiting_runs.csv.tmp.$dead" ] &&
	[ -z "$(ls "$L" | grep '\.tmp\.' | grep -v -e "\.tmp\.$$\$" -e "^waiting_runs.csv.tmp.$dead\$")" ] &&
	ok litter.live_and_nodes_kept || fail litter.live_and_nodes_kept "$(ls "$L" | grep tmp | tr '\n' ' ')"

# --- a tool replaces all of its tables or none ---
# waiting writes its histogram before its summary: with a node planted at the summary
# the run is refused, and the histogram written before it is not put in place either
A=$TMP/allornone
"$BINDIR/waiting" fz --runs R --no-store --no-plot --bins 1 --out "$A" >aon0.log 2>&1 && cp -r "$A" aon.keep ||
	fail all_or_none.setup "$(tail -c 300 aon0.log)"
rm -f "$A/waiting_summary.csv" && mkdir "$A/waiting_summary.csv" && rm -rf aon.keep/waiting_summary.csv &&
	mkdir aon.keep/waiting_summary.csv
"$BINDIR/waiting" fz --runs R --no-store --no-plot --bins 1000 --out "$A" >aon1.log 2>aon1.err
rc=$?
[ "$rc" = 2 ] && grep -qF "waiting_summary.csv: a directory stands there" aon1.err && diff -r aon.keep "$A" >aon.diff 2>&1 &&
	[ -z "$(ls "$A" | grep '\.tmp\.')" ] && ok all_or_none.earlier_tables_kept ||
	fail all_or_none.earlier_tables_kept "exit $rc: $(head -c 200 aon1.err) $(head -c 300 aon.diff)"

# --- the database and its side files, for the writer and the readers ---
cp -r R D
for kind in $KINDS; do
	for side in "" -journal -wal -shm; do
		p=D/study.db$side
		[ -z "$side" ] && mv D/study.db D/keep.db
		plant "$p" "$kind"
		need="$p: $(what "$kind") stands there, not a regular file: the database D/study.db is not opened"
		# the writer and a reader at every path; export and a tool at the database's
		refused "db.run.$kind$side" 2 "$need" "$p" "$kind" -- "$STUDY" run fz.campaign --runs D --no-progress
		refused "db.status.$kind$side" 2 "$need" "$p" "$kind" -- "$STUDY" status fz --runs D
		[ -z "$side" ] || { rm -rf "$p"; continue; }
		refused "db.export.$kind$side" 2 "$need" "$p" "$kind" -- "$STUDY" export fz --runs D
		refused "db.tool.$kind$side" 2 "$need" "$p" "$kind" -- "$BINDIR/waiting" fz --runs D --no-plot
		rm -rf "$p"
		[ -z "$side" ] && mv D/keep.db D/study.db
	done
done
# --db NODE given on the command line
plant "$TMP/dev.db" fifo
refused db.given_fifo 2 "$TMP/dev.db: a FIFO stands there" "$TMP/dev.db" fifo -- \
	"$STUDY" run fz.campaign --runs D --db "$TMP/dev.db" --no-progress
# an empty database is said to be one, by a reader
mkdir E && : >E/study.db
timeout "$LIMIT" "$STUDY" status fz --runs E >empty.out 2>empty.err
rc=$?
[ "$rc" = 1 ] && grep -qF "E/study.db: an empty file (0 bytes): no campaigns in it" empty.err && ok db.empty_said ||
	fail db.empty_said "exit $rc: $(head -c 300 empty.err)"
# study export --output NODE
for kind in $KINDS; do
	plant "$TMP/x.csv" "$kind"
	refused "export_out.$kind" 2 "$TMP/x.csv: $(what "$kind") stands there, not a regular file: not written" \
		"$TMP/x.csv" "$kind" -- "$STUDY" export fz --runs R --output "$TMP/x.csv"
done

# --- a campaign named after the runs directory's files ---
for n in study.db-journal study.db-wal study.db-shm study.db; do
	sed "s/^name = fz/name = $n/" fz.campaign >n.campaign
	line=$(grep -n "^name = " n.campaign | cut -d: -f1)
	refused "name.$n" 1 "n.campaign:$line: name: '$n' is a name of the runs directory's own files" \
		"$TMP/anchor" symlink -- "$STUDY" run n.campaign --runs N --no-progress
	[ ! -e N ] && ok "name.$n.nothing_made" || fail "name.$n.nothing_made" "$(ls N)"
done

# --- dumpflux inputs ---
H5=$(ls R/fz/*.h5 | head -1)
for kind in $KINDS; do
	p=$TMP/in.$kind
	plant "$p" "$kind"
	[ "$kind" = symlink ] && continue # a link to a regular file is read as that file, as every input is
	w=$(what "$kind")
	refused "dumpflux.run.$kind" 2 "$p: is $w, not a regular file: a run file" "$p" "$kind" -- "$DUMPFLUX" run "$p"
	refused "dumpflux.dump.$kind" 2 "$p: is $w, not a regular file: a position dump" "$p" "$kind" -- \
		"$DUMPFLUX" dump "$p" --like "$H5" --amplitude 0.05 --frequency 20 --dt 1e-4
	refused "dumpflux.compare.$kind" 2 "$p: is $w, not a regular file: a profile" "$p" "$kind" -- \
		"$DUMPFLUX" compare "$p" "$p" -- "$p" "$p"
	refused "dumpflux.paired.$kind" 2 "$p: is $w, not a regular file: a paired file" "$p" "$kind" -- \
		"$DUMPFLUX" stats paired "$p"
done
refused dumpflux.power_bounded 1 "stats power: N (beds, 1 to 1000)" "$TMP/anchor" symlink -- \
	"$DUMPFLUX" stats power 10000 0.5

# --- a done run whose file became a dangling link: moved aside, run again ---
cp -r R L
ID=$(sqlite3 L/study.db "SELECT id FROM run ORDER BY id LIMIT 1")
rm "L/fz/$ID.h5" && ln -s "$TMP/nowhere" "L/fz/$ID.h5"
timeout 120 "$STUDY" run fz.campaign --runs L --no-progress >dangling.log 2>&1
rc=$?
[ "$rc" = 0 ] && [ -L "L/fz/damaged/$ID.attempt1.h5" ] && [ -f "L/fz/$ID.h5" ] && [ ! -L "L/fz/$ID.h5" ] &&
	grep -qF "run $ID was done but a symbolic link stands at its output file" dangling.log &&
	[ "$(sqlite3 L/study.db "SELECT state FROM run WHERE id = '$ID'")" = done ] && ok damaged.dangling_link ||
	fail damaged.dangling_link "exit $rc: $(tail -c 300 dangling.log)"
# a node planted at the damaged/ name is not renamed over
cp -r R P
: >"P/fz/$ID.h5"
mkdir -p P/fz/damaged
plant "P/fz/damaged/$ID.attempt1.h5" fifo
refused damaged.planted_fifo 2 "P/fz/damaged/$ID.attempt1.h5: a FIFO stands there, not a regular file: not replaced" \
	"P/fz/damaged/$ID.attempt1.h5" fifo -- "$STUDY" run fz.campaign --runs P --no-progress
finish
