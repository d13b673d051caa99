#!/usr/bin/env bash
# faults.sh - faults of the machine, injected on purpose, never poison a campaign:
#   * an I/O fault (writes fail as on a read-only or full run directory, staged with the
#     build/faults/iofail.so shim since root ignores permissions) stops the launching,
#     leaves every untouched run pending and marks none failed; the run that hit it
#     keeps its end as a checkpoint, so the next `study run` only writes its file; the
#     campaign then ends as an uninterrupted one (export equal, timing aside);
#   * a truncated or deleted output of a done run is found on the next sweep and run
#     again, instead of shrinking its group silently;
#   * what killed engines leave beside finished runs (stale checkpoints, temporary
#     files of dead processes) is removed, a live process's is not;
#   * a deleted packing cache or run directory (the database kept), between two
#     `study run` or at a random moment while one runs, is built and run again: every
#     run ends done, none failed, the export equals an uninterrupted campaign's;
#   * a real full disk (a small tmpfs, root only) under a campaign stops the launching
#     wherever the first write fails, marks no run failed, leaves none 'running' (the
#     runs it stopped are recorded, even when the database is on the full disk), and
#     the same command completes the campaign once there is room;
#   * a second driver on the same campaign is refused with its own exit code (4).
# `make faults` runs it with FAULT_ROUNDS rounds of the I/O fault armed at random
# moments; `make check` runs one round armed from the start.
# tier: slow: a campaign per fault (I/O at random moments, damaged and deleted outputs)
. "$(dirname "$0")/lib.sh"
STUDY="${STUDY:-$(dirname "$SHAKE")/study}"
SHIM="${IOFAIL:-$REPO/build/faults/iofail.so}"
ROUNDS="${FAULT_ROUNDS:-1}"
[ -x "$STUDY" ] || { fail setup "STUDY=$STUDY is not an executable (run make)"; finish; }
[ -f "$SHIM" ] || { fail setup "$SHIM is missing (make tests builds it)"; finish; }
cd "$TMP" || exit 1
# the sanitizer build's runtime must come first; the shim is preloaded before it
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}:verify_asan_link_order=0"

cat >f.campaign <<EOF
[campaign]
name = f
seed = 3
replicates = 3
[scene]
$(tiny_scene n_grains=40 width=16 depth=-)
duration = 0.4
checkpoint_every = 0.1
traj_rate = 100
snapshots = no
[grid]
frequency = 4, 5
EOF
# an uninterrupted campaign to compare with
"$STUDY" run f.campaign --runs "$TMP/REF" --jobs 2 --no-cache >ref.log 2>&1 || fail setup.reference "exit $?: $(tail -n 2 ref.log)"
"$STUDY" export f --runs "$TMP/REF" >ref.csv
# export without the columns that say when, where and how (tests/strip_how.sh)
. "$REPO/tests/strip_how.sh"
strip() { strip_how "$1"; }

# --- an I/O fault: launching stops, nothing is marked failed, resume completes ---
for round in $(seq 1 "$ROUNDS"); do
	R="$TMP/R$round"
	rm -f trig
	if [ "$round" = 1 ]; then
		touch trig # armed from the start: the first run to finish hits it
	else
		# the moment is drawn here, not in the subshell (bash reseeds RANDOM there)
		at=$(awk -v s="$RANDOM" 'BEGIN { srand(s); printf "%.2f", 0.3 + 2 * rand() }')
		echo "# round $round: the fault armed at $at s"
		(sleep "$at" && touch trig) &
	fi
	LD_PRELOAD="$SHIM" IOFAIL_TRIGGER="$TMP/trig" IOFAIL_MATCH=".h5.tmp" \
		"$STUDY" run f.campaign --runs "$R" --jobs 1 --no-cache >io$round.log 2>&1
	rc=$?
	wait
	nfail=$(q "$R/study.db" "SELECT COUNT(*) FROM run WHERE campaign = 'f' AND state = 'failed'")
	ndone=$(q "$R/study.db" "SELECT COUNT(*) FROM run WHERE campaign = 'f' AND state = 'done'")
	if [ "$rc" = 2 ]; then
		[ "$nfail" = 0 ] && [ "$ndone" -lt 6 ] && grep -q 'I/O fault' io$round.log &&
			ok "io.round$round.stops_launching_none_failed" ||
			fail "io.round$round.stops_launching_none_failed" "failed $nfail, done $ndone: $(tail -n 2 io$round.log)"
		# the run that hit the fault kept its end: the next attempt only writes the file
		hit=$(q "$R/study.db" "SELECT run FROM attempt WHERE campaign = 'f' AND status = 'io' LIMIT 1")
		if [ "$round" = 1 ]; then
			[ -n "$hit" ] && [ -f "$R/f/$hit.h5.ckpt" ] && ok io.checkpoint_kept ||
				fail io.checkpoint_kept "run '$hit': no checkpoint of its end ($(ls "$R/f" | head -n 5 | tr '\n' ' '))"
		fi
	elif [ "$rc" = 0 ] && [ "$round" != 1 ]; then
		ok "io.round$round.armed_after_the_end" # the trigger came after the last write
	else
		fail "io.round$round.exit" "exit $rc (expected 2): $(tail -n 3 io$round.log)"
	fi
	rm -f trig
	"$STUDY" run f.campaign --runs "$R" --jobs 2 --no-cache >resume$round.log 2>&1 ||
		fail "io.round$round.resume" "exit $?: $(tail -n 3 resume$round.log)"
	if [ "$round" = 1 ] && [ -n "${hit:-}" ]; then
		grep -q "resuming from .* at t = 0.4000 s" "$R/f/logs/$hit.log" && ok io.resume_only_writes ||
			fail io.resume_only_writes "the faulted run simulated again: $(tail -n 3 "$R/f/logs/$hit.log")"
	fi
	"$STUDY" export f --runs "$R" >io$round.csv
	cmp -s <(strip ref.csv) <(strip io$round.csv) && ok "io.round$round.export_equals_uninterrupted" ||
		fail "io.round$round.export_equals_uninterrupted" "$(diff <(strip ref.csv) <(strip io$round.csv) | head -n 3 | cut -c1-300)"
done

# --- a damaged or deleted output of a done run is run again ---
R="$TMP/R1"
ids=($(q "$R/study.db" "SELECT id FROM run WHERE campaign = 'f' ORDER BY id"))
sz=$(stat -c %s "$R/f/${ids[0]}.h5")
truncate -s $((sz / 2)) "$R/f/${ids[0]}.h5"
rm -f "$R/f/${ids[1]}.h5"
"$STUDY" run f.campaign --runs "$R" --jobs 2 --no-cache >dmg.log 2>&1
rc=$?
[ "$rc" = 0 ] && [ "$(q "$R/study.db" "SELECT COUNT(*) FROM run WHERE campaign = 'f' AND state = 'done'")" = 6 ] &&
	[ -n "$(ls "$R/f/damaged/${ids[0]}".attempt*.h5 2>/dev/null)" ] && # numbered by its attempts (retries add some)
	grep -q "was done but" dmg.log && ok damaged.rerun || fail damaged.rerun "exit $rc: $(tail -n 3 dmg.log)"
"$STUDY" export f --runs "$R" >dmg.csv
cmp -s <(strip ref.csv) <(strip dmg.csv) && ok damaged.export_equals_uninterrupted ||
	fail damaged.export_equals_uninterrupted "$(diff <(strip ref.csv) <(strip dmg.csv) | head -n 3 | cut -c1-300)"
[ "$(q "$R/study.db" "SELECT COUNT(*) FROM attempt WHERE campaign = 'f' AND status = 'damaged'")" = 2 ] &&
	ok damaged.recorded || fail damaged.recorded "$(q "$R/study.db" "SELECT run, status, message FROM attempt WHERE status <> 'ok'")"

# --- litter of killed engines beside finished runs ---
sleep 300 &
live=$!
touch "$R/f/${ids[2]}.h5.ckpt" "$R/f/${ids[2]}.h5.journal" "$R/f/${ids[2]}.h5.ckpt.tmp.999999999" \
	"$R/f/${ids[2]}.h5.tmp.999999998" "$R/f/${ids[3]}.h5.ckpt.tmp.$live"
"$STUDY" run f.campaign --runs "$R" --jobs 2 --no-cache >litter.log 2>&1
left=$(cd "$R/f" && ls "${ids[2]}".h5.* 2>/dev/null | tr '\n' ' ')
[ -z "$left" ] && [ -f "$R/f/${ids[3]}.h5.ckpt.tmp.$live" ] && ok litter.removed_but_live_kept ||
	fail litter.removed_but_live_kept "left: '$left'"
kill "$live" 2>/dev/null
rm -f "$R/f/${ids[3]}.h5.ckpt.tmp.$live"

# --- a deleted packing cache or run directory: built and run again, none failed ---
# (with the packing cache, unlike the rounds above; `make faults` deletes at random
# moments while the driver runs, alternately the cache and the whole directory)
"$STUDY" run f.campaign --runs "$TMP/CREF" --jobs 2 >cref.log 2>&1 || fail deleted.setup "exit $?: $(tail -n 2 cref.log)"
"$STUDY" export f --runs "$TMP/CREF" >cref.csv
for round in $(seq 1 "$ROUNDS"); do
	D="$TMP/D$round"
	what=$([ $((round % 2)) = 1 ] && echo cache || echo dir)
	if [ "$round" = 1 ]; then
		# between two `study run`: one run's output and the cache, then everything
		cp -a "$TMP/CREF" "$D"
		rm -rf "$D/f/cache" "$D/f/${ids[0]}.h5"
		"$STUDY" run f.campaign --runs "$D" --jobs 2 >del$round.a.log 2>&1 ||
			fail deleted.between.cache "exit $?: $(tail -n 2 del$round.a.log)"
		rm -rf "$D/f"
	else
		"$STUDY" run f.campaign --runs "$D" --jobs 1 >del$round.a.log 2>&1 &
		drv=$!
		sleep "$(awk -v s="$RANDOM" 'BEGIN { srand(s); printf "%.2f", 0.3 + 3 * rand() }')"
		if [ "$what" = cache ]; then rm -rf "$D/f/cache"; else find "$D/f" -mindepth 1 -delete 2>/dev/null; fi
		wait "$drv"
	fi
	"$STUDY" run f.campaign --runs "$D" --jobs 2 >del$round.log 2>&1
	rc=$?
	nf=$(q "$D/study.db" "SELECT COUNT(*) FROM run WHERE campaign = 'f' AND state = 'failed'")
	nd=$(q "$D/study.db" "SELECT COUNT(*) FROM run WHERE campaign = 'f' AND state = 'done'")
	[ "$rc" = 0 ] && [ "$nf" = 0 ] && [ "$nd" = 6 ] && ok "deleted.round$round.$what.all_done" ||
		fail "deleted.round$round.$what.all_done" "exit $rc, done $nd, failed $nf: $(tail -n 3 del$round.log)"
	"$STUDY" export f --runs "$D" >del$round.csv
	cmp -s <(strip cref.csv) <(strip del$round.csv) && ok "deleted.round$round.$what.export_equals_uninterrupted" ||
		fail "deleted.round$round.$what.export_equals_uninterrupted" "$(diff <(strip cref.csv) <(strip del$round.csv) | head -n 3 | cut -c1-300)"
done

# --- a full disk under a campaign (a small tmpfs): the launching stops at the first
# write that fails, wherever it is (an argument file, the HDF5 file, the database as
# SQLite says it: "database or disk is full", after a run is done), no run is marked failed; with room again the same command completes it ---
FULL="$TMP/full"
mkdir -p "$FULL"
if mount -t tmpfs -o size=200k tmpfs "$FULL" 2>/dev/null; then
	umount "$FULL"
	for size in 200k 280k 360k; do
		mount -t tmpfs -o "size=$size" tmpfs "$FULL" || { fail "full_disk.$size.mount" "cannot mount"; continue; }
		# HDF5 leaks what it allocated for a file whose creation failed (its failure
		# path): the leak check is off for these runs
		ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" "$STUDY" run f.campaign --runs "$FULL" --jobs 1 --no-cache >full.$size.log 2>&1
		rc=$?
		nf=$(q "$FULL/study.db" "SELECT COUNT(*) FROM run WHERE campaign = 'f' AND state = 'failed'")
		[ "$rc" = 2 ] && [ "$nf" = 0 ] && grep -Eq 'No space left on device|I/O fault|study.db: database or disk is full' full.$size.log &&
			ok "full_disk.$size.stops_none_failed" ||
			fail "full_disk.$size.stops_none_failed" "exit $rc, failed $nf: $(tail -n 2 full.$size.log | cut -c1-300)"
		# the runs it stopped are recorded, with the reason, before it exits: none is left
		# 'running' (the next driver would record it as one whose driver was killed), and
		# a fault without the engine's word (its log is on the full disk too) says so
		nr=0
		[ ! -f "$FULL/study.db" ] || nr=$(q "$FULL/study.db" "SELECT COUNT(*) FROM run WHERE campaign = 'f' AND state = 'running'" 2>&1)
		[ "${nr:-0}" = 0 ] && ! grep -Eq 'I/O fault \(run [0-9a-f]+: \)' full.$size.log && ok "full_disk.$size.none_left_running" ||
			fail "full_disk.$size.none_left_running" "running $nr: $(tail -n 2 full.$size.log | cut -c1-300)"
		mount -o remount,size=64m "$FULL"
		ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" "$STUDY" run f.campaign --runs "$FULL" --jobs 2 --no-cache >full.$size.resume.log 2>&1
		rc=$?
		"$STUDY" export f --runs "$FULL" >full.$size.csv
		[ "$rc" = 0 ] && cmp -s <(strip ref.csv) <(strip full.$size.csv) && ok "full_disk.$size.resumed_equal" ||
			fail "full_disk.$size.resumed_equal" "exit $rc: $(tail -n 2 full.$size.resume.log | cut -c1-200) $(diff <(strip ref.csv) <(strip full.$size.csv) | head -n 2 | cut -c1-200)"
		umount "$FULL"
	done
else
	skip faults.full_disk "cannot mount a tmpfs here (not root?)"
fi

# --- a second driver on the same campaign: refused with its own exit code ---
flock "$R/f/.driver.lock" sleep 5 &
holder=$!
sleep 0.3
"$STUDY" run f.campaign --runs "$R" >busy.log 2>&1
rc=$?
kill "$holder" 2>/dev/null
wait 2>/dev/null
[ "$rc" = 4 ] && grep -q 'another study driver' busy.log && ok busy.exit_code_4 || fail busy.exit_code_4 "exit $rc: $(cat busy.log)"
finish
