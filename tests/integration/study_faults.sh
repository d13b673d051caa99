#!/usr/bin/env bash
# study_faults.sh - faults around the engine, injected on purpose: an engine that
# prints more after its error message (a diagnostic at exit, a sanitizer report) still
# has its own message recorded, and an argument file with more parameters than the
# worker passes on is refused, never run with some of them dropped.
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1

# `study exec` runs the engine that sits next to it: a copy of bin/study beside a
# wrapper that runs the real engine and then writes one more line to stderr
mkdir bin && cp "$STUDY" bin/study || { fail setup "cannot copy $STUDY"; finish; }
cat >bin/shake <<W
#!/bin/sh
"$SHAKE" "\$@"
rc=\$?
echo "diagnostic printed at exit" >&2
exit \$rc
W
chmod +x bin/shake

scene() { # NAME [SCENE-LINES...]
	printf '[campaign]\nname = %s\nseed = 1\n[scene]\n' "$1"
	tiny_scene n_grains=40 depth=-
	printf 'duration = 0.1\n'
	shift
	printf '%s\n' "$@"
}

# --- the engine's message, not what it printed after it ---
scene nofile 'particles = nofile.txt' >nofile.campaign
bin/study run nofile.campaign --runs "$TMP/R" >nofile.log 2>&1
rc=$?
row=$(sqlite3 R/study.db "SELECT state || '|' || exit_code || '|' || message FROM failures WHERE campaign = 'nofile'")
case "$row" in
"failed|1|shake: nofile.txt: cannot open particle file"*) [ "$rc" -eq 3 ] && ok fault.engine_message_kept ||
	fail fault.engine_message_kept "exit $rc (expected 3)" ;;
*) fail fault.engine_message_kept "exit $rc, recorded '$row'" ;;
esac
# the wrapper did run (its line is in the run's log), so the check above means something
grep -q "diagnostic printed at exit" R/nofile/logs/*.log && ok fault.wrapper_ran || fail fault.wrapper_ran "$(cat R/nofile/logs/*.log)"

# --- an argument file longer than the worker's argv: refused, recorded, not run ---
scene over >over.campaign
id=$(bin/study expand over.campaign | awk 'NR == 2 { print $1 }')
mkdir -p R/over/jobs
{ for i in $(seq 130); do echo "frequency=3"; done; echo "output=$id.h5"; } >"R/over/jobs/$id.args"
bin/study run over.campaign --runs "$TMP/R" >over.log 2>&1
rc=$?
row=$(sqlite3 R/study.db "SELECT state || '|' || exit_code || '|' || message FROM failures WHERE campaign = 'over'")
[ -n "$id" ] && [ "$rc" -eq 3 ] && [ ! -e "R/over/$id.h5" ] &&
	[ "$row" = "failed|1|exec: argument file has more than 126 parameters" ] && ok fault.args_overflow_refused ||
	fail fault.args_overflow_refused "exit $rc, output $(ls R/over/*.h5 2>/dev/null), recorded '$row'"
finish
