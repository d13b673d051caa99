#!/usr/bin/env bash
# harness.sh - the suite's runner tells the truth about planted scripts: tests/run.sh is
# run on a copy of itself with a folder of scripts whose outcomes are known, and every
# way a script can say nothing is counted as a failure or as a visible SKIP
# (docs/testing.md, "What the runner counts").
. "$(dirname "$0")/lib.sh"

H="$TMP/h"
mkdir -p "$H/tests/integration"
cp "$REPO/tests/run.sh" "$H/tests/"
cp "$REPO/tests/integration/lib.sh" "$H/tests/integration/"
plant() { # name body
	printf '#!/usr/bin/env bash\n. "$(dirname "$0")/lib.sh"\n%s\n' "$2" >"$H/tests/integration/$1.sh"
}
plant good 'ok good.one
finish'
plant nocheck 'echo "a script that checks nothing"
finish'
plant silent 'true'
plant hang 'echo "about to hang"
sleep 600
ok hang.never'
plant lowerskip 'echo "skip lower.case: its reason"
ok lowerskip.other
finish'
plant helperskip 'skip helper.skip "no tmpfs here"
finish'
plant failing 'fail failing.one "it broke"
finish'
plant crash 'ok crash.before
kill -SEGV $$'

out="$TMP/run.out"
t0=$(date +%s)
SHAKE=/bin/true TEST_TIMEOUT=3 TEST_JOBS=2 timeout -k 5 60 bash "$H/tests/run.sh" >"$out" 2>&1
rc=$? t=$(($(date +%s) - t0))

line() { grep -E "^$1 " "$out" | head -n 1; }
[ "$rc" -ne 0 ] && ok harness.exit_nonzero || fail harness.exit_nonzero "run.sh exited 0 on planted failures"
case $(line tests/integration/good.sh) in *" 1 ok   0 failed"*) ok harness.good ;; *) fail harness.good "$(line tests/integration/good.sh)" ;; esac
for s in nocheck silent; do
	if line "tests/integration/$s.sh" | grep -q ' 1 failed' && grep -q "FAIL.*$s.*\(no check\|ran no check\)" "$out"; then
		ok "harness.$s.counted_failed"
	else
		fail "harness.$s.counted_failed" "a script with no check passed: $(line tests/integration/$s.sh)"
	fi
done
if line tests/integration/hang.sh | grep -q ' 1 failed' && grep -q 'FAIL tests/integration/hang.sh: timed out after 3 s' "$out" &&
	grep -q 'about to hang' "$out"; then
	ok harness.hang.timed_out
else
	fail harness.hang.timed_out "a hanging script was not reported as timed out with its last lines"
fi
# the hang is killed at 3 s (+ 10 s grace at most), not after its 600 s sleep
[ "$t" -lt 60 ] && ok harness.hang.killed || fail harness.hang.killed "run.sh took $t s"
grep -q '^  SKIP lower.case: its reason' "$out" && ok harness.lowercase_skip.shown ||
	fail harness.lowercase_skip.shown "a lower-case skip line vanished"
grep -q '^  SKIP helper.skip: no tmpfs here' "$out" && ok harness.skip_helper.shown ||
	fail harness.skip_helper.shown "lib.sh's skip was not shown"
line tests/integration/helperskip.sh | grep -q ' 0 failed 1 skipped' && ok harness.skip_only.passes ||
	fail harness.skip_only.passes "a script that skips its one check with a reason is not a failure: $(line tests/integration/helperskip.sh)"
grep -q '^  FAIL failing.one: it broke' "$out" && ok harness.fail.shown || fail harness.fail.shown "a FAIL line vanished"
line tests/integration/crash.sh | grep -q ' 1 failed' && ok harness.crash.counted ||
	fail harness.crash.counted "a script killed by a signal passed"
last=$(tail -n 1 "$out")
[ "$last" = "3 passed, 5 failed, 2 skipped" ] && ok harness.totals || fail harness.totals "last line: '$last'"
grep -q '^# the slowest tests' "$out" && grep -qE '^#  +[0-9.]+  tests/integration/hang.sh' "$out" &&
	ok harness.slowest || fail harness.slowest "no slowest-tests list naming the hang"
finish
