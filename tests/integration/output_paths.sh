#!/usr/bin/env bash
# output_paths.sh - a run never replaces what stands at an output path unless it is a
# regular file: a device, FIFO, socket, directory or symbolic link at output (or its
# sidecar, journal, checkpoint), checkpoint, write_particles or write_lammps is refused
# before anything runs (exit 1, the key, where it was set, the path and what stands
# there), and is left as it was; one that appears while the run shakes is not renamed
# over at the end (exit 2, said so, no temporary left); one planted at a temporary name
# (OUTPUT.tmp.PID) is neither followed nor written (exit 2). output = none runs without a
# run file. The nodes live in this test's directory: /dev/null and /dev/zero are never
# touched (a device node here has their numbers, so an engine that renamed over it
# would show it without harming the machine).
# tier: slow: every kind of node at every output path, before and during a run
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1
LIMIT=10 # timeout(1): a refused run ends at once, a run that is not refused shakes for ~15 s
PROMPT=5 # seconds: "before anything runs", with room for the sanitizer build

D="$TMP/d"
mkdir "$D"
echo "the target" >"$TMP/target"
# make_node NAME KIND : a fresh node of KIND at $D/NAME (a socket by Debian's python3: the
# first python3 on PATH may be a pyenv shim, most of a second a call, and the standard
# library is all it needs)
make_node() {
	rm -rf "${D:?}/$1"
	case $2 in
	fifo) mkfifo "$D/$1" ;;
	chardev) mknod "$D/$1" c 1 3 ;; # /dev/null's numbers, here
	dir) mkdir "$D/$1" ;;
	symlink) ln -s "$TMP/target" "$D/$1" ;;
	socket) /usr/bin/python3 -c 'import socket, sys; socket.socket(socket.AF_UNIX).bind(sys.argv[1])' "$D/$1" ;;
	esac
}
# same_node NAME KIND : it is still that node (and the link still points at the target,
# which still holds what it held)
same_node() {
	local want
	case $2 in
	fifo) want="fifo" ;; chardev) want="character special file" ;; dir) want="directory" ;;
	symlink) want="symbolic link" ;; socket) want="socket" ;;
	esac
	[ "$(stat -c %F "$D/$1")" = "$want" ] || return 1
	[ "$2" != chardev ] || [ "$(stat -c %t:%T "$D/$1")" = 1:3 ] || return 1
	[ "$2" != symlink ] || { [ "$(readlink "$D/$1")" = "$TMP/target" ] && [ "$(cat "$TMP/target")" = "the target" ]; }
}

KINDS="fifo chardev dir symlink socket"
mknod "$TMP/probe" c 1 3 2>/dev/null || { KINDS="fifo dir symlink socket"; skip output_paths.chardev "mknod is not allowed here"; }
rm -f "$TMP/probe"

# --- refused before anything runs, left as it was, nothing written beside it ---
# key:node-name[:extra args]; the node stands at the path the key makes the run write
CASES=("output:o.h5" "write_lammps:bed.data:output=$D/r.h5" "write_particles:bed.txt:output=$D/r.h5"
	"checkpoint:run.ckpt:output=$D/r.h5 checkpoint_every=1"
	"output:r.h5.journal:output=$D/r.h5" "output:r.xmf:output=$D/r.h5" "output:r.h5.ckpt:output=$D/r.h5")
for kind in $KINDS; do
	for c in "${CASES[@]}"; do
		IFS=: read -r key name extra <<<"$c"
		make_node "$name" "$kind"
		before=$(ls -A "$D" | sort | tr '\n' ' ')
		id="refused.$kind.${name//./_}"
		arg=$key=$D/$name
		[ "$key" = output ] && [ -n "$extra" ] && arg="" # the node is a file the output implies
		t0=$SECONDS
		# shellcheck disable=SC2086 # extra holds key=value words without blanks
		timeout -k 5 "$LIMIT" "$SHAKE" "${FAST[@]}" "${GENTLE[@]}" duration=30 $extra $arg >"$id.log" 2>&1
		rc=$? took=$((SECONDS - t0))
		after=$(ls -A "$D" | sort | tr '\n' ' ')
		if [ "$rc" = 1 ] && [ "$took" -le "$PROMPT" ] && same_node "$name" "$kind" && [ "$before" = "$after" ] &&
			grep -q "^shake: command line: $key: '$D/$name'.* is a.*, not a regular file" "$id.log"; then
			ok "$id"
		else
			fail "$id" "exit $rc in $took s, now $(stat -c %F "$D/$name" 2>&1), files [$before] -> [$after]: $(head -c 300 "$id.log")"
		fi
		rm -rf "${D:?}/$name"
	done
done
rm -rf "${D:?}"/*

# --- a node that appears while the run shakes is not renamed over at the end ---
# (the run file, and the sidecar, which is renamed into place after it)
for kind in $KINDS; do
	for name in late.h5 late.xmf; do
		id="appeared.$kind.${name//./_}"
		rm -rf "${D:?}"/*
		"$SHAKE" "${FAST[@]}" "${GENTLE[@]}" duration=6 output="$D/late.h5" >"$id.log" 2>&1 &
		pid=$!
		for i in $(seq 500); do [ -e "$D/late.h5.journal" ] && break; sleep 0.02; done # shaking now
		# held while the node is made, so that a slow python or a busy machine cannot let
		# the run end first
		kill -STOP $pid
		make_node "$name" "$kind"
		kill -CONT $pid
		wait $pid
		rc=$?
		left=$(cd "$D" && ls -d ./*.tmp.* 2>/dev/null | tr '\n' ' ')
		[ "$rc" = 2 ] && same_node "$name" "$kind" && [ -z "$left" ] &&
			grep -q "^shake: $D/$name: a.* stands there, not a regular file: not replaced" "$id.log" && ok "$id" ||
			fail "$id" "exit $rc, now $(stat -c %F "$D/$name" 2>&1), left [$left]: $(head -c 300 "$id.log")"
	done
done
rm -rf "${D:?}"/*

# --- a node planted at a temporary name (OUTPUT.tmp.PID, the sidecar's) before the
# engine writes it is neither followed nor written (exit 2, the path named) ---
for kind in symlink fifo chardev; do
	for name in t.h5 t.xmf; do
		id="planted_tmp.$kind.${name//./_}"
		rm -rf "${D:?}"/*
		# the engine's pid is known before it starts: a shell that stops itself, then
		# becomes the engine
		sh -c 'kill -STOP $$; exec "$@"' sh "$SHAKE" "${FAST[@]}" "${GENTLE[@]}" output="$D/t.h5" >"$id.log" 2>&1 &
		pid=$!
		for i in $(seq 250); do case $(ps -o stat= -p $pid) in T*) break ;; esac; sleep 0.02; done
		make_node "$name.tmp.$pid" "$kind"
		(sleep 60 && kill -KILL $pid 2>/dev/null) &
		dog=$!
		kill -CONT $pid
		wait $pid
		rc=$?
		kill $dog 2>/dev/null
		[ "$rc" = 2 ] && same_node "$name.tmp.$pid" "$kind" && [ ! -e "$D/$name" ] &&
			grep -q "$D/$name.tmp.$pid: a.* stands there, not a regular file: not written" "$id.log" && ok "$id" ||
			fail "$id" "exit $rc, now $(stat -c %F "$D/$name.tmp.$pid" 2>&1): $(head -c 300 "$id.log")"
	done
done
rm -rf "${D:?}"/*

# --- two output keys at one file: refused before anything runs (exit 1), naming both
# keys and where each was set; nothing written, what stood there left as it was. Each
# pair the run would otherwise resolve by deleting or overwriting one of them. ---
mkdir "$D/real" && ln -s real "$D/via" # a directory reached through a symbolic link
# id|arguments (the scene is FAST, GENTLE, duration=0.5)|the later key|the earlier key
SAME=("ckpt_is_output|output=$D/r.h5 checkpoint=$D/r.h5 checkpoint_every=0.25|checkpoint|output"
	"particles_is_ckpt|output=$D/r.h5 write_particles=$D/r.h5.ckpt|write_particles|output"
	"particles_is_journal|output=$D/r.h5 write_particles=$D/r.h5.journal|write_particles|output"
	"particles_is_output|output=$D/r.h5 write_particles=$D/r.h5|write_particles|output"
	"particles_is_xmf|output=$D/r.h5 write_particles=$D/r.xmf|write_particles|output"
	"ckpt_is_xmf|output=$D/r.h5 checkpoint=$D/r.xmf checkpoint_every=0.25|checkpoint|output"
	"particles_is_lammps|output=$D/r.h5 write_particles=$D/bed.txt write_lammps=$D/bed.txt|write_lammps|write_particles"
	"lammps_is_output_none|output=none write_particles=$D/bed.txt write_lammps=$D/./bed.txt|write_lammps|write_particles"
	"dot_slash|output=$D/r.h5 checkpoint=$D/./r.h5 checkpoint_every=0.25|checkpoint|output"
	"dir_symlink|output=$D/real/r.h5 write_particles=$D/via/r.xmf|write_particles|output"
	"relative|output=r.h5 write_lammps=$D/r.h5|write_lammps|output")
for c in "${SAME[@]}"; do
	IFS='|' read -r name args later earlier <<<"$c"
	id="same_file.$name"
	rm -rf "${D:?}"/*.* "${D:?}"/real/*
	echo "stood here" >"$D/r.h5"
	before=$(cd "$D" && ls -AR | tr '\n' ' ')
	# shellcheck disable=SC2086 # args holds key=value words without blanks
	(cd "$D" && timeout -k 5 "$LIMIT" "$SHAKE" "${FAST[@]}" "${GENTLE[@]}" duration=0.5 $args >"$TMP/$id.log" 2>&1)
	rc=$?
	after=$(cd "$D" && ls -AR | tr '\n' ' ')
	[ "$rc" = 1 ] && [ "$before" = "$after" ] && [ "$(cat "$D/r.h5")" = "stood here" ] &&
		grep -q "^shake: command line: $later: '[^']*'.* is the same file as $earlier: '[^']*'.* (command line): one would delete or overwrite the other" "$id.log" &&
		ok "$id" || fail "$id" "exit $rc, files [$before] -> [$after]: $(head -c 300 "$id.log")"
done
# where each key was set: a scene file's line and the command line
printf 'output = %s\nwrite_lammps = %s\n' "$D/r.h5" "$D/r.xmf" >"$TMP/same.scene"
"$SHAKE" "$TMP/same.scene" "${FAST[@]}" write_lammps="$D/r.h5.journal" >same_where.log 2>&1
rc=$?
[ "$rc" = 1 ] && grep -q "^shake: command line: write_lammps: '$D/r.h5.journal' is the same file as output: '$D/r.h5.journal' (its journal) ($TMP/same.scene:1)" same_where.log &&
	ok same_file.where_set || fail same_file.where_set "exit $rc: $(head -c 300 same_where.log)"
# paths that differ still run (the check is not a blanket refusal)
"$SHAKE" "${FAST[@]}" duration=0 output="$D/real/r.h5" write_particles="$D/via/r.txt" write_lammps="$D/r.txt" >same_ok.log 2>&1
rc=$?
[ "$rc" = 0 ] && [ -s "$D/real/r.h5" ] && [ -s "$D/real/r.txt" ] && [ -s "$D/r.txt" ] && ok same_file.different_run ||
	fail same_file.different_run "exit $rc: $(head -c 300 same_ok.log)"
rm -rf "${D:?}"/*

# --- a regular file is replaced, as before (a run again over its old file) ---
echo old >"$D/again.h5"
"$SHAKE" "${FAST[@]}" "${GENTLE[@]}" output="$D/again.h5" >again.log 2>&1 && [ "$(h5param "$D/again.h5" output)" = "$D/again.h5" ] &&
	ok regular.replaced || fail regular.replaced "$(tail -n 2 again.log)"

# --- output = none: no run file, nothing beside it; what was asked for is written ---
mkdir none && cd none || exit 1
"$SHAKE" "${FAST[@]}" duration=0 output=none write_lammps=bed.data write_particles=bed.txt >../none.log 2>&1
rc=$?
[ "$rc" = 0 ] && [ "$(ls -A | sort | tr '\n' ' ')" = "bed.data bed.txt " ] && ok none.only_what_was_asked ||
	fail none.only_what_was_asked "exit $rc, files: $(ls -A | tr '\n' ' '): $(tail -n 2 ../none.log)"
"$SHAKE" "${FAST[@]}" "${GENTLE[@]}" output=none >../none2.log 2>&1
rc=$?
[ "$rc" = 0 ] && [ -z "$(ls -A | grep -v '^bed\.')" ] && ok none.shaken_without_files ||
	fail none.shaken_without_files "exit $rc, files: $(ls -A | tr '\n' ' '): $(tail -n 2 ../none2.log)"
# a physics failure is still the exit code, and says it is recorded nowhere
"$SHAKE" "${FAST[@]}" output=none settle_max=0.01 settle_min=0.005 >../none3.log 2>&1
rc=$?
[ "$rc" = 6 ] && grep -q "output = none: not recorded" ../none3.log && [ -z "$(ls -A | grep -v '^bed\.')" ] &&
	ok none.failure_said || fail none.failure_said "exit $rc: $(tail -n 2 ../none3.log)"
# a checkpoint resumes into the run file: none has none to resume into
for a in checkpoint_every=1 checkpoint=c.ckpt restart=yes; do
	"$SHAKE" "${FAST[@]}" output=none "$a" >../none4.log 2>&1
	rc=$?
	[ "$rc" = 1 ] && grep -q "^shake: command line: ${a%%=*}: a checkpoint resumes a run into its run file, and output = none (command line) has none" ../none4.log &&
		ok "none.refuses_${a%%=*}" || fail "none.refuses_${a%%=*}" "exit $rc: $(tail -n 2 ../none4.log)"
done
cd .. || exit 1
# the study driver sets every run's output itself (a campaign cannot), so never none
printf '[campaign]\nname = n\nseed = 1\n[scene]\noutput = none\n' >n.campaign
STUDY="${STUDY:-$(dirname "$SHAKE")/study}"
"$STUDY" run n.campaign --runs "$TMP/N" >n.log 2>&1
rc=$?
[ "$rc" = 1 ] && grep -q "output: set by the study driver" n.log && ok none.not_in_a_campaign ||
	fail none.not_in_a_campaign "exit $rc: $(tail -n 2 n.log)"
finish
