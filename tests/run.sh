#!/usr/bin/env bash
# run.sh - the whole suite: the sanitizer build of every unit and physics test
# binary, then every integration script against bin/shake. Each test prints
# "ok ID" or "FAIL ID: why"; a program that dies without saying FAIL counts as one
# failure. Ends with "N passed, N failed" and exits non-zero on any failure.
set -u
cd "$(dirname "$0")/.."
pass=0 fail=0
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# Integration scripts drive the sanitizer build of bin/shake too, so that every path
# they reach is checked by ASan/UBSan.
export SHAKE="${SHAKE:-$PWD/build/san/bin/shake}"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"

run_one() { # name, command...
	local name=$1; shift
	local t0=$SECONDS
	"$@" >"$log" 2>&1
	local rc=$?
	local p f
	p=$(grep -c '^ok ' "$log")
	f=$(grep -c '^FAIL ' "$log")
	grep -E '^(FAIL|ok |SKIP )' "$log" | sed 's/^/  /' | grep -v '^  ok ' || true
	if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
		echo "  FAIL $name: exited with status $rc without reporting a failure; its output ends:"
		tail -n 15 "$log" | sed 's/^/    /'
		f=1
	fi
	pass=$((pass + p)); fail=$((fail + f))
	printf '%-48s %3d ok %3d failed  (%ds)\n' "$name" "$p" "$f" $((SECONDS - t0))
}

for t in build/san/tests/*/*; do
	[ -x "$t" ] && [ -f "$t" ] || continue
	case "$t" in *.d) continue ;; esac
	run_one "${t#build/san/}" "$t"
done
for t in tests/integration/*.sh; do
	[ -f "$t" ] || continue
	case "$t" in */lib.sh) continue ;; esac
	run_one "$t" bash "$t"
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
