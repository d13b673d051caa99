#!/usr/bin/env bash
# restart.sh - checkpoint/restart identity. A run killed with SIGKILL at some moment
# after its first checkpoint, then started again with the same command, gives the same
# file as an uninterrupted run (apart from /provenance and the output path): for two
# kill moments with gear5 and one with verlet. SIGTERM exits with code 7, leaves a
# checkpoint, and the rerun resumes to the same file. A checkpoint of other physics is
# refused (code 1) unless restart = no; restart = yes without a checkpoint is refused.
# A checkpoint whose journal is missing or shorter than it says (a run directory deleted
# while the run wrote), or a journal without its checkpoint, starts the run over: exit 0
# with a note, the same file as an uninterrupted run; restart = yes refuses the former.
# The shear spring's history (tangential = spring, periodic sides) resumes the same way.
# tier: slow: six runs of 2.5 s, each killed and resumed
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

# 150 grains, 2.5 s of shaking, a checkpoint every 0.125 s (20 in a run)
tiny_bed n_grains=150 width=24
SCENE=("${BEDARGS[@]}" duration=2.5
	"${GENTLE[@]}" traj_rate=200 snapshots=yes progress=no checkpoint_every=0.125)

# reference ID args... : uninterrupted run into ID.h5
reference() {
	local id=$1
	shift
	"$SHAKE" "${SCENE[@]}" "$@" output="$TMP/$id.h5" >"$TMP/$id.log" 2>&1
	local rc=$?
	if [ "$rc" -ne 0 ]; then
		fail "$id.run" "exit $rc: $(head -c 300 "$TMP/$id.log")"
		return 1
	fi
	[ ! -e "$TMP/$id.h5.ckpt" ] && [ ! -e "$TMP/$id.h5.journal" ] && ok "$id.run" ||
		fail "$id.run" "checkpoint or journal left after a finished run"
}

# wait_for FILE PID : until FILE exists (or PID ended); returns 1 when PID ended first
wait_for() {
	local i
	for ((i = 0; i < 3000; i++)); do
		[ -e "$1" ] && return 0
		kill -0 "$2" 2>/dev/null || { [ -e "$1" ]; return; }
		sleep 0.005
	done
	return 1
}

# wait_ckpts FILE PID K : until FILE (a checkpoint, rewritten every checkpoint_every) has
# been written K times; prints the milliseconds between its last two writes (0 for K = 1);
# returns 1 when PID ended first
wait_ckpts() {
	local seen="" now k=0 i t_prev=0 t_last=0
	for ((i = 0; i < 60000 && k < $3; i++)); do
		now=$(stat -c '%i %y' "$1" 2>/dev/null)
		if [ -n "$now" ] && [ "$now" != "$seen" ]; then
			seen=$now k=$((k + 1)) t_prev=$t_last t_last=$(date +%s%N)
			continue
		fi
		kill -0 "$2" 2>/dev/null || return 1
		sleep 0.005
	done
	[ "$k" -ge "$3" ] || return 1
	[ "$k" -gt 1 ] && echo $(((t_last - t_prev) / 1000000)) || echo 0
}

# killed_and_resumed ID REF SIGNAL K args... :
# starts the run, waits for its K-th checkpoint and then a random part of the time
# between its last two (the moment counted in checkpoints, so that a machine whose
# load changed since the reference cannot let the run end first), sends SIGNAL,
# checks the process really was interrupted, reruns the same command and compares with REF
killed_and_resumed() {
	local id=$1 ref=$2 sig=$3 k=$4
	shift 4
	local out="$TMP/$id.h5"
	"$SHAKE" "${SCENE[@]}" "$@" output="$out" >"$TMP/$id.1.log" 2>&1 &
	local pid=$! gap delay
	if ! gap=$(wait_ckpts "$out.ckpt" $pid "$k"); then
		wait $pid
		fail "$id.killed" "checkpoint $k did not appear before the run ended (exit $?)"
		return
	fi
	delay=$((RANDOM % 100 * gap / 100))
	sleep "$(awk -v d="$delay" 'BEGIN { printf "%.3f", d / 1000 }')"
	kill -s "$sig" $pid 2>/dev/null
	{ wait $pid; } 2>/dev/null
	local rc=$?
	if [ -e "$out" ]; then
		fail "$id.killed" "the run finished before $sig arrived (${delay} ms after checkpoint $k); test did not interrupt it"
		return
	fi
	case $sig in
	KILL) [ "$rc" -eq 137 ] && ok "$id.killed" || fail "$id.killed" "exit $rc after SIGKILL" ;;
	TERM)
		[ "$rc" -eq 7 ] && ok "$id.sigterm_code7" || fail "$id.sigterm_code7" "exit $rc after SIGTERM, expected 7"
		contains "$TMP/$id.1.log" "checkpoint" && ok "$id.sigterm_message" ||
			fail "$id.sigterm_message" "no message about the checkpoint: $(head -c 200 "$TMP/$id.1.log")"
		;;
	esac
	[ -s "$out.ckpt" ] && ok "$id.checkpoint_exists" || fail "$id.checkpoint_exists" "no $out.ckpt after the interruption"
	echo "# $id: $sig ${delay} ms after checkpoint $k" >&2
	[ -n "${ON_INTERRUPTED:-}" ] && $ON_INTERRUPTED "$id" "$out"
	"$SHAKE" "${SCENE[@]}" "$@" output="$out" >"$TMP/$id.2.log" 2>&1
	rc=$?
	if [ "$rc" -ne 0 ]; then
		fail "$id.resumed" "rerun exit $rc: $(head -c 300 "$TMP/$id.2.log")"
		return
	fi
	ok "$id.resumed"
	check "$id.same_as_uninterrupted" "resumed run differs from the uninterrupted one" \
		same_output "$TMP/$ref.h5" "$out" output
	[ ! -e "$out.ckpt" ] && [ ! -e "$out.journal" ] && ok "$id.cleanup" ||
		fail "$id.cleanup" "checkpoint or journal left after the resumed run finished"
}

# a random-ish moment: one of the first 12 of the run's 20 checkpoints
# (drawn in this shell: a $(...) subshell would reseed RANDOM, and TEST_SEED would not
# reproduce it)
moment() { MOMENT=$((RANDOM % 12 + 1)); }

# --- gear5 ---
reference gear5_ref || finish
killed_and_resumed gear5_kill_early gear5_ref KILL 1
moment
killed_and_resumed gear5_kill_late gear5_ref KILL "$MOMENT"

# --- SIGTERM, and what a checkpoint of other physics does ---
physics_checks() { # ID OUT : called while the interrupted run's checkpoint exists
	local out=$2
	cp "$out.ckpt" "$TMP/saved.ckpt"
	"$SHAKE" "${SCENE[@]}" frequency=4.1 output="$out" >"$TMP/chg.log" 2>&1
	local rc=$?
	[ "$rc" -eq 1 ] && ok changed_physics.refused || fail changed_physics.refused "exit $rc with frequency changed, expected 1"
	contains "$TMP/chg.log" "$out.ckpt" && contains "$TMP/chg.log" "restart" && ok changed_physics.message ||
		fail changed_physics.message "message does not name the checkpoint and the restart key: $(head -c 300 "$TMP/chg.log")"
	[ ! -e "$out" ] && cmp -s "$out.ckpt" "$TMP/saved.ckpt" && ok changed_physics.untouched ||
		fail changed_physics.untouched "the refused run wrote output or changed the checkpoint"
	# the same with other physics in a dynamics-only key and a preparation key
	"$SHAKE" "${SCENE[@]}" n_grains=151 output="$out" >"$TMP/chg2.log" 2>&1
	rc=$?
	[ "$rc" -eq 1 ] && ok changed_prep.refused || fail changed_prep.refused "exit $rc with n_grains changed, expected 1"
	# restart = no ignores the checkpoint: a fresh run with the new frequency
	"$SHAKE" "${SCENE[@]}" frequency=4.1 restart=no duration=0.5 output="$TMP/fresh.h5" \
		checkpoint="$out.ckpt" >"$TMP/fresh.log" 2>&1
	rc=$?
	[ "$rc" -eq 0 ] && [ "$(attr "$TMP/fresh.h5" /status)" = ok ] && [ "$(h5param "$TMP/fresh.h5" frequency)" = 4.0999999999999996 ] &&
		[ "$(attr "$TMP/fresh.h5" /steps)" = 10000 ] && ok restart_no.ignores_checkpoint ||
		fail restart_no.ignores_checkpoint "exit $rc, status $(attr "$TMP/fresh.h5" /status), steps $(attr "$TMP/fresh.h5" /steps): $(head -c 300 "$TMP/fresh.log")"
	# (that run removes the checkpoint it was pointed at when it ends: put it back)
	cp "$TMP/saved.ckpt" "$out.ckpt"
}
moment
ON_INTERRUPTED=physics_checks killed_and_resumed gear5_term gear5_ref TERM "$MOMENT"

# restart = yes needs a checkpoint
"$SHAKE" "${SCENE[@]}" restart=yes output="$TMP/none.h5" >"$TMP/yes.log" 2>&1
rc=$?
[ "$rc" -eq 1 ] && contains "$TMP/yes.log" "none.h5.ckpt" && ok restart_yes.needs_checkpoint ||
	fail restart_yes.needs_checkpoint "exit $rc: $(head -c 200 "$TMP/yes.log")"

# SIGTERM without checkpoints: code 7 and a file that says so
"$SHAKE" "${SCENE[@]}" checkpoint_every=0 output="$TMP/nock.h5" >"$TMP/nock.log" 2>&1 &
pid=$!
# once shaking has begun (the journal exists), plus a little
wait_for "$TMP/nock.h5.journal" $pid && sleep 0.1
kill -TERM $pid 2>/dev/null
wait $pid
rc=$?
if [ "$rc" -eq 7 ]; then
	ok sigterm_nockpt.code7
	s=$(attr "$TMP/nock.h5" /status)
	[ -n "$s" ] && [ "$s" != ok ] && [ "$(attr "$TMP/nock.h5" /exit_code)" = 7 ] && ok sigterm_nockpt.recorded ||
		fail sigterm_nockpt.recorded "status '$s', exit_code '$(attr "$TMP/nock.h5" /exit_code)' in the output"
else
	fail sigterm_nockpt.code7 "exit $rc after SIGTERM 0.1 s into the shaking of a ~1 s run"
fi

# --- a checkpoint without its journal, or with a short one, and a journal without its
# checkpoint: the run starts over (a note, not a fault), and ends as an uninterrupted
# one; restart = yes, which asks to continue, is refused (exit 1) and touches nothing ---
SMALL=("${FAST[@]}" "${GENTLE[@]}" duration=1 checkpoint_every=0.25)
"$SHAKE" "${SMALL[@]}" output="$TMP/small_ref.h5" >"$TMP/small_ref.log" 2>&1 || fail orphan.reference "exit $?: $(head -c 300 "$TMP/small_ref.log")"
# orphan ID MODE : a run stopped by SIGTERM (its checkpoint written at the stop), then
# MODE done to its files, then the same command again
orphan() {
	local id=$1 mode=$2 out="$TMP/$1.h5" rc note
	"$SHAKE" "${SMALL[@]}" output="$out" >"$TMP/$id.1.log" 2>&1 &
	local pid=$!
	wait_ckpts "$out.ckpt" $pid 1 >/dev/null && kill -TERM $pid 2>/dev/null
	wait $pid
	rc=$?
	[ "$rc" = 7 ] && [ -s "$out.ckpt" ] && [ -s "$out.journal" ] || { fail "orphan.$id" "setup: exit $rc: $(head -c 300 "$TMP/$id.1.log")"; return; }
	case $mode in
	nojournal) note="is missing" && rm "$out.journal" ;;
	short) note="is shorter than the checkpoint says" && truncate -s 12 "$out.journal" ;;
	nockpt) rm "$out.ckpt" ;;
	esac
	if [ "$mode" != nockpt ]; then
		cp "$out.ckpt" "$TMP/$id.saved"
		"$SHAKE" "${SMALL[@]}" restart=yes output="$out" >"$TMP/$id.yes.log" 2>&1
		rc=$?
		[ "$rc" = 1 ] && [ ! -e "$out" ] && cmp -s "$out.ckpt" "$TMP/$id.saved" &&
			grep -q "^shake: $out.ckpt: restart = yes, but its journal $out.journal $note; remove the checkpoint or set restart = auto" "$TMP/$id.yes.log" &&
			ok "orphan.$id.restart_yes_refused" || fail "orphan.$id.restart_yes_refused" "exit $rc: $(head -c 300 "$TMP/$id.yes.log")"
	fi
	"$SHAKE" "${SMALL[@]}" output="$out" >"$TMP/$id.2.log" 2>&1
	rc=$?
	if [ "$mode" = nockpt ]; then
		! grep -q "resuming" "$TMP/$id.2.log"
	else
		grep -q "^shake: warning: $out.ckpt: its journal $out.journal $note: starting the run over" "$TMP/$id.2.log"
	fi
	local said=$?
	[ "$rc" = 0 ] && [ "$said" = 0 ] && [ ! -e "$out.ckpt" ] && [ ! -e "$out.journal" ] &&
		same_output "$TMP/small_ref.h5" "$out" output && ok "orphan.$id.started_over" ||
		fail "orphan.$id.started_over" "exit $rc, files $(ls "$TMP/$id"* | tr '\n' ' '): $(head -c 300 "$TMP/$id.2.log")"
}
orphan ckpt_without_journal nojournal
orphan ckpt_with_short_journal short
orphan journal_without_ckpt nockpt

# --- the shear spring (tangential = spring): its per-contact history lives in the
#     checkpoint; periodic sides put seam pairs in it too, the energy series its energy ---
SPRING=(tangential=spring sides=periodic energy_rate=200)
if reference spring_ref "${SPRING[@]}"; then
	moment
	killed_and_resumed spring_kill spring_ref KILL "$MOMENT" "${SPRING[@]}"
fi

# --- verlet ---
SCENE+=(integrator=verlet)
reference verlet_ref || finish
moment
killed_and_resumed verlet_kill verlet_ref KILL "$MOMENT"
# gear5 and verlet differ (the comparison can fail)
if same_output "$TMP/gear5_ref.h5" "$TMP/verlet_ref.h5" output integrator 2>/dev/null; then
	fail integrators_differ "verlet gave the same file as gear5"
else
	ok integrators_differ
fi
# --- observables and a frequency ramp survive a kill: their accumulators live in
#     the checkpoint and their records in the journal ---
OBS=(flux=yes field=yes field_periods=3 ring=yes ring_every=7 ramp=updown ramp_from=3.5 ramp_to=4.5)
if reference obs_ref "${OBS[@]}"; then
	moment
	killed_and_resumed obs_kill obs_ref KILL "$MOMENT" "${OBS[@]}"
fi
finish
