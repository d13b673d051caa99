#!/usr/bin/env bash
# study_deleted.sh - a deleted run directory or packing cache never wedges a campaign
# (docs/driver.md, "Deleted files"): the database's rows are not the files, so after
# `rm -rf runs/NAME/cache`, `rm -rf runs/NAME` (the database elsewhere, or beside it)
# or the cache deleted while the campaign runs, `study run` builds the packings again,
# writes the argument files that named them again, runs what is missing and ends with
# every run done and files bit-identical to an undisturbed campaign's. A done run whose
# output was deleted is run again (recorded as a `damaged` attempt); --no-cache makes a
# run whose packing is gone settle itself instead. A job whose campaign directory is gone
# when its worker starts is reported as such (exit 2: not the run's fault, its input
# is prepared again), never as a "bad job" that fails the run.
# tier: slow: campaigns whose outputs and caches are deleted and run again
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1

# the reference: the tiny campaign (lib.sh), built once per build
tiny_campaign d 3 >d.campaign
fixture_runs d.campaign REF || { fail setup.reference "exit $?: $(tail -n 3 REF.log)"; finish; }
ids=($(q REF/study.db "SELECT id FROM run WHERE campaign = 'd' ORDER BY id"))
[ "${#ids[@]}" = 4 ] && [ "$(q REF/study.db "SELECT COUNT(*) FROM run WHERE from_cache = 1")" = 4 ] ||
	{ fail setup.reference "expected 4 runs from the packing cache: $(q REF/study.db "SELECT id, from_cache FROM run")"; finish; }

# all_done ID DB LOG RUNDIR : every run done, and each file equals the reference's
all_done() {
	local id=$1 db=$2 log=$3 dir=$4 bad="" r
	[ "$(q "$db" "SELECT COUNT(*) FROM run WHERE campaign = 'd' AND state = 'done'")" = 4 ] ||
		{ fail "$id.all_done" "$(q "$db" "SELECT id, state FROM run") / $(tail -n 3 "$log")"; return; }
	ok "$id.all_done"
	for r in "${ids[@]}"; do
		same_output "REF/d/$r.h5" "$dir/$r.h5" 2>/dev/null || bad="$bad $r"
	done
	[ -z "$bad" ] && ok "$id.bit_identical" || fail "$id.bit_identical" "runs differ from the reference:$bad"
	[ "$(q "$db" "SELECT COUNT(*) FROM run WHERE campaign = 'd' AND from_cache = 1")" = 4 ] &&
		ok "$id.from_cache" || fail "$id.from_cache" "$(q "$db" "SELECT id, from_cache FROM run")"
}

# --- the packing cache deleted between two `study run`, with a done run's output ---
cp -a REF C
rm -rf C/d/cache
rm -f "C/d/${ids[0]}.h5"
"$STUDY" run d.campaign --runs C --jobs 2 --no-progress >c.log 2>&1
rc=$?
[ "$rc" = 0 ] && grep -q "cache/.*missing: building it again" c.log && ok cache.rebuilt ||
	fail cache.rebuilt "exit $rc: $(tail -n 3 c.log)"
all_done cache C/study.db c.log C/d
grep -q "was done but the output file is missing" c.log &&
	[ "$(q C/study.db "SELECT COUNT(*) FROM attempt WHERE status = 'damaged' AND run = '${ids[0]}'")" = 1 ] &&
	ok cache.deleted_output_recorded || fail cache.deleted_output_recorded "$(q C/study.db "SELECT run, status FROM attempt")"

# --- the whole run directory deleted, the database beside it kept ---
cp -a REF W
rm -rf W/d
"$STUDY" run d.campaign --runs W --jobs 2 --no-progress >w.log 2>&1
rc=$?
[ "$rc" = 0 ] && ok rundir.exit_0 || fail rundir.exit_0 "exit $rc: $(tail -n 3 w.log)"
all_done rundir W/study.db w.log W/d

# --- the runs directory deleted whole, the database elsewhere (--db) ---
"$STUDY" run d.campaign --runs E --db "$TMP/e.db" --jobs 2 --no-progress >e1.log 2>&1 ||
	fail elsewhere.setup "exit $?: $(tail -n 3 e1.log)"
rm -rf E
"$STUDY" run d.campaign --runs E --db "$TMP/e.db" --jobs 2 --no-progress >e.log 2>&1
rc=$?
[ "$rc" = 0 ] && ok elsewhere.exit_0 || fail elsewhere.exit_0 "exit $rc: $(tail -n 3 e.log)"
all_done elsewhere e.db e.log E/d

# --- only a pending run's argument file names the packing: it is built for it alone ---
cp -a REF P
rm -rf P/d/cache "P/d/${ids[1]}.h5"
"$STUDY" run d.campaign --runs P --jobs 2 --no-progress >p.log 2>&1
rc=$?
[ "$rc" = 0 ] && grep -q "settling 1 shared packing" p.log && ok alone.packing_built ||
	fail alone.packing_built "exit $rc: $(tail -n 3 p.log)"
all_done alone P/study.db p.log P/d

# --- --no-cache: a run whose packing is gone settles itself (its argument file rewritten) ---
cp -a REF N
rm -rf N/d/cache "N/d/${ids[2]}.h5"
"$STUDY" run d.campaign --runs N --jobs 2 --no-cache --no-progress >n.log 2>&1
rc=$?
[ "$rc" = 0 ] && [ "$(q N/study.db "SELECT state || from_cache FROM run WHERE id = '${ids[2]}'")" = done0 ] &&
	grep -q "argument file is written again" n.log && ! grep -q '^particles=cache' "N/d/jobs/${ids[2]}.args" &&
	ok nocache.settles_itself || fail nocache.settles_itself "exit $rc: $(tail -n 3 n.log)"
# the same physics: every dataset of the run equals the reference's but the settling's
h5diff --exclude-path /provenance --exclude-path /h5md --exclude-attribute /parameters \
	--exclude-attribute / "REF/d/${ids[2]}.h5" "N/d/${ids[2]}.h5" >/dev/null 2>&1 &&
	ok nocache.same_datasets || fail nocache.same_datasets "$(h5diff -q REF/d/${ids[2]}.h5 N/d/${ids[2]}.h5 2>&1 | head -n 3)"

# --- the packing cache deleted while the campaign runs: nothing fails ---
# The moment is a state, not a time: the driver runs a copy of itself beside an engine
# that holds the first run starting from a packing (its argument particles=cache/...)
# before it reads it, until the cache is gone (or this script is gone: nothing hangs).
# That run and the others of the round lose their input, and are prepared and run again.
mkdir -p mbin && cp "$STUDY" mbin/study || { fail midrun.setup "cannot copy $STUDY to $TMP/mbin"; finish; }
cat >mbin/shake <<EOF
#!/usr/bin/env bash
case " \$* " in
*" particles=cache/"*)
	if mkdir "$TMP/held" 2>/dev/null; then
		: >"$TMP/held/waiting"
		while [ ! -e "$TMP/held/go" ] && kill -0 $$ 2>/dev/null; do sleep 0.05; done
	fi ;;
esac
exec "$SHAKE" "\$@"
EOF
chmod +x mbin/shake
sed -e 's/^duration = 0.2/duration = 1/' d.campaign >m.campaign
sed -i -e 's/^name = d/name = m/' m.campaign
mbin/study run m.campaign --runs M --jobs 1 --no-progress >m.log 2>&1 &
drv=$!
deleted=0
# (until the driver ends: one that ends without a held run fails the checks below)
while kill -0 "$drv" 2>/dev/null; do
	if [ -e held/waiting ]; then
		rm -rf M/m/cache
		deleted=1
		break
	fi
	sleep 0.05
done
mkdir -p held && : >held/go
wait "$drv"
rc=$?
nd=$(q M/study.db "SELECT COUNT(*) FROM run WHERE campaign = 'm' AND state = 'done'")
nf=$(q M/study.db "SELECT COUNT(*) FROM run WHERE campaign = 'm' AND state = 'failed'")
[ "$deleted" = 1 ] && [ "$rc" = 0 ] && [ "$nd" = 4 ] && [ "$nf" = 0 ] && ok midrun.none_failed ||
	fail midrun.none_failed "deleted $deleted, exit $rc, done $nd, failed $nf: $(tail -n 3 m.log)"
grep -q "lost .* input or output while the campaign ran" m.log &&
	[ "$(q M/study.db "SELECT COUNT(*) FROM attempt WHERE status = 'missing_input'")" -ge 1 ] &&
	ok midrun.recorded_missing_input ||
	fail midrun.recorded_missing_input "$(grep -c 'lost .* input' m.log) 'lost input' lines; attempts: $(q M/study.db "SELECT run, status FROM attempt" | tr '\n' ' ')"
# ... each saying what went (the worker may have said nothing: no file to run)
[ "$(q M/study.db "SELECT COUNT(*) FROM attempt WHERE status = 'missing_input' AND COALESCE(message, '') = ''")" = 0 ] &&
	ok midrun.missing_input_says_what ||
	fail midrun.missing_input_says_what "$(q M/study.db "SELECT run, n, message FROM attempt WHERE status = 'missing_input'" | tr '\n' ' ')"

# --- an output file seen and gone before the driver reads it (its directory deleted
# meanwhile): the run is prepared and run again, not failed. The fault shim unlinks the
# file at the driver's first read of it (IOFAIL_VANISH), the race made certain ---
SHIM="${IOFAIL:-$REPO/build/faults/iofail.so}"
tiny_campaign v 3 >v.campaign
vid=$("$STUDY" expand v.campaign | awk -F'\t' 'NR == 2 { print $1 }')
LD_PRELOAD="$SHIM" IOFAIL_VANISH="$vid.h5" ASAN_OPTIONS="${ASAN_OPTIONS:-}:verify_asan_link_order=0" \
	bash -c 'export IOFAIL_VANISH_PID=$$; exec "$0" run v.campaign --runs V --jobs 2 --no-progress' "$STUDY" >v.log 2>&1
rc=$?
[ "$rc" = 0 ] && [ "$(q V/study.db "SELECT COUNT(*) FROM run WHERE campaign = 'v' AND state = 'done'")" = 4 ] &&
	[ "$(q V/study.db "SELECT status FROM attempt WHERE run = '$vid' ORDER BY n LIMIT 1")" = missing_input ] &&
	q V/study.db "SELECT message FROM attempt WHERE run = '$vid' AND n = 1" | grep -q "its output file was gone when it was to be read" &&
	ok vanished.output_run_again ||
	fail vanished.output_run_again "exit $rc: $(q V/study.db "SELECT run, n, status, message FROM attempt" | tr '\n' ' ') $(tail -n 2 v.log)"
# a job whose campaign directory was deleted before its worker started: said so, exit 2
# (the driver finds its input gone and prepares it again), never "bad job" (exit 1, the
# run failed)
"$STUDY" exec "$TMP/gone" run 0123456789abcdef >gone.out 2>&1
rc=$?
[ "$rc" = 0 ] && grep -q "^STUDY-DONE	0123456789abcdef	2	[^	]*	0.000	-	-	exec: cannot enter the campaign's directory $TMP/gone: No such file or directory$" gone.out &&
	ok deleted_dir.worker_says_so || fail deleted_dir.worker_says_so "exit $rc: $(head -c 300 gone.out)"
finish
