#!/usr/bin/env bash
# run_identity.sh - a run file is the run it claims to be (docs/inputs.md, "Run files"):
# another run's file copied over a run's, another campaign's file linked into its place,
# a bit flipped in a dataset's stored bytes and a root attribute changed after the engine
# wrote it are each found, by the analysis tools (the run is unreadable, with the reason)
# and by bin/study's sweep (the run was done, its file goes to damaged/ and it runs
# again), never read as numbers. The first check is the file's seal against the one
# the database recorded (docs/inputs.md, "Run files"); `recorded` puts the new file's
# seal in the database, so that the checks behind it are tested too.
# The runs are tests/fuzz/runs.campaign's; build/fuzz/h5mut changes them.
# tier: slow: campaigns whose files are swapped, linked and damaged, then swept
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
H5MUT="${H5MUT:-$REPO/build/fuzz/h5mut}"
[ -x "$H5MUT" ] || { fail setup "$H5MUT is not an executable (run make tests)"; finish; }
cd "$TMP" || exit 1
LIMIT=60

cp "$REPO/tests/fuzz/runs.campaign" fz.campaign
# another campaign, one run of another length
sed -e 's/^name = fz/name = other/' -e 's/^duration = 0.6/duration = 0.3/' -e 's/^radius_ratio = 0, 1.5/radius_ratio = 1.5/' \
	-e 's/^ramp = none, updown/ramp = none/' fz.campaign >other.campaign
fixture_runs fz.campaign R
rc=$?
cat R.log >setup.log 2>/dev/null
[ "$rc" = 0 ] && "$STUDY" run other.campaign --runs R --jobs 1 --no-progress >>setup.log 2>&1 &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'")" = 5 ] && ok setup.campaigns ||
	{ fail setup.campaigns "$(tail -c 400 setup.log)"; finish; }
ID=$(q R/study.db "SELECT r.id FROM run r JOIN param a ON a.run = r.id AND a.key = 'radius_ratio' AND a.value > 0
	JOIN param b ON b.run = r.id AND b.key = 'ramp' AND b.value = 'none' WHERE r.campaign = 'fz'")
ID0=$(q R/study.db "SELECT r.id FROM run r JOIN param a ON a.run = r.id AND a.key = 'radius_ratio' AND a.value = 0
	JOIN param b ON b.run = r.id AND b.key = 'ramp' AND b.value = 'none' WHERE r.campaign = 'fz'")
IDO=$(q R/study.db "SELECT id FROM run WHERE campaign = 'other'")
h5dump -a /parameters/run_id "R/fz/$ID.h5" | grep -qF "\"$ID\"" && ok identity.written ||
	fail identity.written "$(h5dump -a /parameters/run_id "R/fz/$ID.h5" 2>&1 | head -c 300)"

# unreadable ID TOOL DIR NEEDLE: TOOL exits 0 and counts run $ID unreadable with NEEDLE
unreadable() {
	local id=$1 t=$2 d=$3 needle=$4 rc row
	timeout -k 5 "$LIMIT" "$BINDIR/$t" fz --runs "$d" --no-plot --no-store --out "$d/out" >"$d/$t.out" 2>"$d/$t.err"
	rc=$?
	row=$(grep -F ",$ID," "$d/out/${t}_accounting.csv" 2>/dev/null)
	if [ "$rc" -ne 0 ]; then
		fail "$id" "exit $rc: $(head -c 300 "$d/$t.err")"
	elif grep -qE 'runtime error|AddressSanitizer|LeakSanitizer' "$d/$t.err"; then
		fail "$id" "sanitizer: $(grep -m1 -E 'runtime error|Sanitizer' "$d/$t.err")"
	elif ! grep -qF ",unreadable," <<<"$row" || ! grep -qF -- "$needle" <<<"$row"; then
		fail "$id" "run $ID: '$row' (want unreadable and '$needle')"
	else
		ok "$id"
	fi
}

# swept ID DIR NEEDLE: `study run` finds run $ID's file wrong: NEEDLE in the damaged
# attempt's message and on stderr, the file set aside in damaged/, and the run done
# again with a file that is its own
swept() {
	local id=$1 d=$2 needle=$3 rc msg
	timeout -k 5 "$LIMIT" "$STUDY" run fz.campaign --runs "$d" --jobs 1 --no-progress >"$d.study.log" 2>&1
	rc=$?
	msg=$(q "$d/study.db" "SELECT message FROM attempt WHERE run = '$ID' AND status = 'damaged' ORDER BY n DESC LIMIT 1")
	if [ "$rc" -ne 0 ] || grep -q Sanitizer "$d.study.log"; then
		fail "$id" "exit $rc: $(tail -c 300 "$d.study.log")"
	elif ! grep -qF -- "$needle" <<<"$msg" || ! grep -qF -- "$needle" "$d.study.log"; then
		fail "$id" "message '$msg', want '$needle': $(tail -c 300 "$d.study.log")"
	elif ! ls "$d/fz/damaged/$ID".attempt*.h5 >/dev/null 2>&1; then
		fail "$id" "nothing in $d/fz/damaged/"
	elif [ "$(q "$d/study.db" "SELECT state FROM run WHERE id = '$ID'")" != done ] ||
		! h5dump -a /parameters/run_id "$d/fz/$ID.h5" | grep -qF "\"$ID\""; then
		fail "$id" "run $ID not done again with its own file"
	else
		ok "$id"
	fi
}

fresh() { rm -rf "$1" && cp -a R "$1"; }
# recorded DIR: DIR's database holds the seal of run $ID's file as it now is
recorded() {
	q "$1/study.db" "UPDATE result SET file_seal = '$(head -c 64 "$1/fz/$ID.h5" | sed -n 's/^fnv1a64w //p')' WHERE run = '$ID'" &&
		reseal_rows "$1/study.db"
}
SEALED="but the database recorded"

# (a) run A's file copied over run B's
fresh C && cp "C/fz/$ID0.h5" "C/fz/$ID.h5"
unreadable copied.waiting waiting C "$SEALED"
recorded C
unreadable copied.figures figures C "holds run '$ID0', not run '$ID'"
swept copied.study C "holds run '$ID0', not run '$ID'"

# (b) another campaign's file linked into place
fresh L && rm "L/fz/$ID.h5" && ln -s "../other/$IDO.h5" "L/fz/$ID.h5"
unreadable linked.waiting waiting L "$SEALED"
recorded L
unreadable linked.onset onset L "holds run '$IDO', not run '$ID'"
# (the sweep refuses the link itself: a done run's file must be a regular file)
swept linked.study L "a symbolic link stands at its output file, not a regular file"
[ -f "L/other/$IDO.h5" ] && [ ! -L "L/other/$IDO.h5" ] && ok linked.target_untouched ||
	fail linked.target_untouched "the other campaign's file moved"

# (c) a bit of a dataset's stored data flipped behind HDF5's back: its seal no longer
# matches; sealed again, its chunk's Fletcher32 checksum does not
fresh B1 && "$H5MUT" "B1/fz/$ID.h5" B1/x.h5 --flip /observables/flux/phi/value --stale-seal &&
	mv B1/x.h5 "B1/fz/$ID.h5" || fail setup.flip "h5mut --flip"
unreadable flipped.seal.onset onset B1 "its bytes do not match its seal"
fresh B && "$H5MUT" "B/fz/$ID.h5" B/x.h5 --flip /observables/flux/phi/value && mv B/x.h5 "B/fz/$ID.h5" && recorded B ||
	fail setup.flip "h5mut --flip"
unreadable flipped.onset onset B "checksum error"
unreadable flipped.rolls rolls B "checksum error"
swept flipped.study B "checksum error"

# (d) a root attribute changed after the engine wrote it (steps: what the run did)
fresh A && "$H5MUT" "A/fz/$ID.h5" A/x.h5 --stale-digest --attr / steps 5 && mv A/x.h5 "A/fz/$ID.h5" && recorded A ||
	fail setup.attr "h5mut --attr"
unreadable attribute.waiting waiting A "do not match their digest"
unreadable attribute.figures figures A "do not match their digest"
swept attribute.study A "do not match their digest"

# control: the untouched runs are used
fresh U
timeout -k 5 "$LIMIT" "$BINDIR/waiting" fz --runs U --no-plot --no-store --out U/out >U/w.out 2>U/w.err &&
	grep -F ",$ID," U/out/waiting_accounting.csv | grep -qF ",used," && ok control.waiting ||
	fail control.waiting "$(grep -F ",$ID," U/out/waiting_accounting.csv) $(head -c 300 U/w.err)"
finish
