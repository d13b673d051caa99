#!/usr/bin/env bash
# errors_named.sh - errors are named for what they are:
#   * a full disk while the engine writes its HDF5 file is an I/O fault, exit 2 with
#     the system's word for it, never a crash at exit (HDF5 1.10 closes a file whose
#     close failed a second time in its exit handler: core/io/h5md.c, h5w_init), and no
#     temporary file is left;
#   * a full disk found only when HDF5 closes a dataset (its last chunks are written
#     then; staged with the build/faults/iofail.so shim, IOFAIL_CLOSE) is the same I/O
#     fault: exit 2, nothing at the run file's name (never a sealed file holding zeros
#     where the chunks belong), the finished run kept as a checkpoint, and the same
#     command then writes the file;
#   * a read-only runs directory is an I/O fault of `study run` (exit 2, the lock file
#     and why), not "another study driver" (exit 4, which only a held lock is);
#   * an engine that crashes (SIGSEGV, SIGABRT) has failed - recorded with its signal,
#     never run again - where one killed from outside is retried (study_retry.sh).
# The file-system cases need tmpfs mounts (root); without them they are skipped, said so.
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1
MOUNTS=()
# unmounted before lib.sh's trap removes TMP (rm -rf must not meet a mount)
trap 'for m in "${MOUNTS[@]}"; do umount "$m" 2>/dev/null; done; rm -rf "$TMP"' EXIT
# tmpfs DIR OPTIONS : a tmpfs at DIR (made), remembered for the unmount; fails without root
tmpfs() {
	mkdir -p "$1" && mount -t tmpfs -o "$2" tmpfs "$1" 2>/dev/null && MOUNTS+=("$1")
}

# --- a full disk while the HDF5 file is written: exit 2, said so, nothing left ---
# The run's journal (~40 KB) fits every size; its HDF5 file (~115 KB uncompressed) fits
# none, so the write fails at different places: creating the file, writing datasets,
# flushing at H5Fclose (the place of the crash at exit).
if tmpfs full size=48k; then
	umount full && MOUNTS=()
	bad=""
	for size in 48k 64k 80k 96k 112k; do
		tmpfs full "size=$size" || { bad="$bad $size:mount"; continue; }
		# the sanitizer build: HDF5 leaks what it allocated for a file whose close failed
		# (its failure path, not ours), so the leak check is off for these runs
		ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0" "$SHAKE" "${FAST[@]}" "${GENTLE[@]}" duration=2 compression=0 \
			snapshot_precision=double output="$TMP/full/r.h5" >"full.$size.log" 2>&1
		rc=$?
		left=$(cd full && ls -d ./*.tmp.* 2>/dev/null | tr '\n' ' ')
		if [ "$rc" != 2 ] || ! grep -Eq '^shake: .*(No space left on device|cannot create HDF5 file)' "full.$size.log" ||
			[ -n "$left" ]; then
			bad="$bad $size:exit=$rc,left=[$left],$(grep -m1 -E 'shake: |SEGV|Sanitizer' "full.$size.log" | cut -c1-160)"
		fi
		umount full
		MOUNTS=()
	done
	[ -z "$bad" ] && ok full_disk.exit_2_said_so || fail full_disk.exit_2_said_so "$bad"
	# a smaller run (a campaign's), whose journal fits and whose checkpoint or HDF5 file
	# does not (at its first closes, before the journal is copied): said as the write
	# that failed, never a crash on the records not copied, no file at the name
	bad=""
	tiny_bed n_grains=40 width=16 depth=-
	for size in 28k 32k 36k 44k; do
		tmpfs full "size=$size" || { bad="$bad $size:mount"; continue; }
		ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0" "$SHAKE" "${BEDARGS[@]}" duration=0.4 checkpoint_every=0.1 traj_rate=100 snapshots=no frequency=4 progress=no \
			output="$TMP/full/r.h5" >"small.$size.log" 2>&1
		rc=$?
		if [ "$rc" != 2 ] || [ -e full/r.h5 ] || ! grep -Eq '^shake: .*(No space left on device|cannot create HDF5 file)' "small.$size.log"; then
			bad="$bad $size:exit=$rc,$(ls full | tr '\n' ' '),$(grep -m1 -E 'shake: |SEGV|Sanitizer|runtime error' "small.$size.log" | cut -c1-160)"
		fi
		umount full
		MOUNTS=()
	done
	[ -z "$bad" ] && ok full_disk.small_run_exit_2 || fail full_disk.small_run_exit_2 "$bad"
else
	skip errors.full_disk "cannot mount a tmpfs here (not root?)"
fi

# --- a full disk at a dataset's close (its chunk flush): exit 2, no file at the final
# name; run again, the finished run is written from its checkpoint ---
SHIM="${IOFAIL:-$REPO/build/faults/iofail.so}"
if [ -f "$SHIM" ]; then
	mkdir closing
	h5shared_setup shake
	LD_PRELOAD="$SHIM" IOFAIL_CLOSE=.h5.tmp. ASAN_OPTIONS="${ASAN_OPTIONS:-}:verify_asan_link_order=0" \
		"$H5SHARED/shake" "${FAST[@]}" "${GENTLE[@]}" duration=0.5 checkpoint_every=0.25 output="$TMP/closing/r.h5" >closing.log 2>&1
	rc=$?
	left=$(cd closing && ls -A | tr '\n' ' ')
	[ "$rc" = 2 ] && [ "$left" = "r.h5.ckpt r.h5.journal " ] &&
		grep -q "^shake: $TMP/closing/r.h5.tmp.[0-9]*: writing the HDF5 output failed: No space left on device" closing.log &&
		grep -q "^shake: checkpoint $TMP/closing/r.h5.ckpt holds the finished run" closing.log &&
		ok full_disk.at_dataset_close || fail full_disk.at_dataset_close "exit $rc, files [$left]: $(head -c 300 closing.log)"
	"$SHAKE" "${FAST[@]}" "${GENTLE[@]}" duration=0.5 checkpoint_every=0.25 output="$TMP/closing/r.h5" >closing2.log 2>&1
	rc=$?
	left=$(cd closing && ls -A | tr '\n' ' ')
	[ "$rc" = 0 ] && [ "$left" = "r.h5 r.xmf " ] && grep -q "^shake: resuming from" closing2.log &&
		[ "$(attr "$TMP/closing/r.h5" /status)" = ok ] && ok full_disk.at_dataset_close.then_written ||
		fail full_disk.at_dataset_close.then_written "exit $rc, files [$left]: $(head -c 300 closing2.log)"
	# a checkpoint that cannot be written while the run shakes: exit 2, no run file (a
	# driver would ingest it as the run's end, failed), the same command then completes
	touch ckpt.trig
	LD_PRELOAD="$SHIM" IOFAIL_TRIGGER="$TMP/ckpt.trig" IOFAIL_MATCH=.ckpt.tmp IOFAIL_ERRNO=28 \
		ASAN_OPTIONS="${ASAN_OPTIONS:-}:verify_asan_link_order=0" \
		"$SHAKE" "${FAST[@]}" "${GENTLE[@]}" duration=0.5 checkpoint_every=0.25 output="$TMP/closing/c.h5" >ckptfail.log 2>&1
	rc=$?
	[ "$rc" = 2 ] && [ ! -e closing/c.h5 ] && grep -q "^shake: .*c.h5.ckpt.*No space left on device; no run file written" ckptfail.log &&
		ok full_disk.checkpoint_no_run_file || fail full_disk.checkpoint_no_run_file "exit $rc, $(ls closing | tr '\n' ' '): $(head -c 300 ckptfail.log)"
	"$SHAKE" "${FAST[@]}" "${GENTLE[@]}" duration=0.5 checkpoint_every=0.25 output="$TMP/closing/c.h5" >ckptfail2.log 2>&1
	rc=$?
	[ "$rc" = 0 ] && [ "$(attr "$TMP/closing/c.h5" /status)" = ok ] && ok full_disk.checkpoint_then_complete ||
		fail full_disk.checkpoint_then_complete "exit $rc: $(head -c 300 ckptfail2.log)"
else
	fail full_disk.at_dataset_close "$SHIM is missing (make tests builds it)"
fi

# --- a read-only runs directory: exit 2 naming the lock file and why, not exit 4 ---
cat >c.campaign <<EOF
[campaign]
name = c
seed = 1
[scene]
$(tiny_scene n_grains=40 depth=-)
duration = 0.1
[grid]
frequency = 4
EOF
if tmpfs ro size=1m; then
	mkdir -p ro/c/jobs ro/c/logs ro/c/cache ro/c/failed
	if mount -o remount,ro ro 2>/dev/null; then
		"$STUDY" run c.campaign --runs "$TMP/ro" --db "$TMP/ro.db" --jobs 1 >ro.log 2>&1
		rc=$?
		[ "$rc" = 2 ] && grep -q "ro/c/.driver.lock: cannot open the campaign's driver lock: Read-only file system" ro.log &&
			! grep -q "another study driver" ro.log && ok read_only.io_not_busy ||
			fail read_only.io_not_busy "exit $rc: $(tail -n 2 ro.log)"
	else
		skip errors.read_only "cannot remount a tmpfs read-only here"
	fi
else
	skip errors.read_only "cannot mount a tmpfs here (not root?)"
fi

# --- a crashing engine: failed with its signal, not run again ---
# `study exec` runs the engine that sits next to it: a copy of bin/study beside an
# engine that kills itself with the signal its campaign names in its seed's place
mkdir bin && cp "$STUDY" bin/study || { fail setup "cannot copy $STUDY"; finish; }
cat >bin/shake <<'W'
#!/bin/sh
ulimit -c 0
echo "shake: about to crash" >&2
kill -"$CRASH_SIGNAL" $$
W
chmod +x bin/shake
for sig in SEGV BUS ILL ABRT FPE; do
	sed "s/^name = c/name = k$sig/" c.campaign >k$sig.campaign
	CRASH_SIGNAL=$sig bin/study run k$sig.campaign --runs "$TMP/K" --no-cache --jobs 1 --retries 2 >k$sig.log 2>&1
	rc=$?
	num=$(kill -l $sig)
	rows=$(q K/study.db "SELECT r.state || ' ' || r.attempts || ' ' || (SELECT group_concat(a.status || ':' || a.exit_code
		|| ':' || a.message, ',') FROM attempt a WHERE a.campaign = r.campaign AND a.run = r.id) FROM run r
		WHERE r.campaign = 'k$sig'")
	[ "$rc" = 3 ] && [[ "$rows" == "failed 1 crashed:$((128 + num)):crashed by signal $num ("* ]] && ! grep -q "running again" k$sig.log &&
		ok "crash.$sig.failed_not_retried" || fail "crash.$sig.failed_not_retried" "exit $rc, '$rows': $(tail -n 2 k$sig.log)"
done
"$STUDY" status kSEGV --runs "$TMP/K" >k.status 2>&1
grep -q "crashed by signal 11" k.status && ok crash.status_says_so || fail crash.status_says_so "$(cat k.status)"
finish
