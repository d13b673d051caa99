#!/usr/bin/env bash
# run.sh - the suite: the sanitizer build of every unit and physics test binary, then
# every integration script against the sanitizer build of bin/shake, TEST_JOBS (default:
# the CPUs) at a time. Each test prints "ok ID" or "FAIL ID: why"; a program that dies
# without saying FAIL counts as one failure, and so does a program that reports no check
# at all (neither ok, FAIL nor SKIP) or runs past its time limit (below). A check that
# cannot run says "SKIP ID: why" and is shown and counted, never silently dropped. One line
# per test in a fixed order whatever finishes first; then the ten slowest tests; ends with
# "N passed, N failed, N skipped" and exits non-zero on any failure.
#
# Time limits (TEST_TIMEOUT overrides both, in seconds): a test program or a script of the
# quick tier gets 600 s, a script marked slow 1200 s: about six times the slowest such
# test's wall time in a quiet clean-clone CI on 2 cores, twice what a CI run on a machine
# loaded four times over took (docs/testing.md, "What the runner counts"), so a hang ends
# the test, not the suite: it is killed with its process group and reported as FAIL with
# the last lines it printed.
#
#   bash tests/run.sh [--quick] [PATTERN]   # PATTERN: an extended regex on the test names
#   bash tests/run.sh --tiers               # the marked scripts as a Markdown table
#
# An integration script says in its header how it must be run, one line each, with why:
#   # tier: slow: WHY    left out of --quick (make quick)
#   # tier: alone: WHY   never beside another test (it runs after the others)
# docs/testing.md, "Tiers", lists them (generated from these lines by --tiers).
set -u
cd "$(dirname "$0")/.."
quick=0 pattern=${T:-}
while [ $# -gt 0 ]; do
	case $1 in
	--quick) quick=1 ;;
	--tiers) tiers=1 ;;
	-h | --help)
		sed -n '2,/^set -u/p' "$0" | sed '$d; s/^# \{0,1\}//'
		exit 0
		;;
	-*) echo "run.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
	*) pattern=$1 ;;
	esac
	shift
done

# every script's tier lines, read once: TIER[SCRIPT:WORD]=WHY
declare -A TIER=()
while IFS= read -r line; do
	f=${line%%:# tier: *} rest=${line#*:# tier: }
	TIER[$f:${rest%%: *}]=${rest#*: }
done < <(grep -H '^# tier: [a-z]*: ' tests/integration/*.sh)

if [ -n "${tiers:-}" ]; then
	printf '| script | tier | why |\n|---|---|---|\n'
	for t in tests/integration/*.sh; do
		for w in slow alone; do
			why=${TIER[$t:$w]:-}
			[ -n "$why" ] && printf '| `%s` | %s | %s |\n' "${t##*/}" "$w" "$why"
		done
	done
	exit 0
fi

# Integration scripts drive the sanitizer build of bin/shake too, so that every path
# they reach is checked by ASan/UBSan.
export SHAKE="${SHAKE:-$PWD/build/san/bin/shake}"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"
jobs=${TEST_JOBS:-$(nproc 2>/dev/null || echo 1)}
case $jobs in '' | *[!0-9]* | 0) echo "run.sh: TEST_JOBS must be a whole number >= 1, got '$jobs'" >&2; exit 2 ;; esac

# --- the tests: names, commands, how they run ---
LIMIT_QUICK=600 LIMIT_SLOW=1200
if [ -n "${TEST_TIMEOUT:-}" ]; then
	case $TEST_TIMEOUT in *[!0-9]* | 0) echo "run.sh: TEST_TIMEOUT must be a whole number of seconds >= 1, got '$TEST_TIMEOUT'" >&2; exit 2 ;; esac
	LIMIT_QUICK=$TEST_TIMEOUT LIMIT_SLOW=$TEST_TIMEOUT
fi
names=() cmds=() alone=() first=() limit=()
add() { # name alone(0/1) slow-first(0/1) command
	local n=$1 a=$2 s=$3
	shift 3
	if [ -n "$pattern" ]; then
		[[ $n =~ $pattern ]] || return 0
	fi
	names+=("$n") alone+=("$a") first+=("$s") cmds+=("$*")
	if [ "$s" = 1 ]; then limit+=("$LIMIT_SLOW"); else limit+=("$LIMIT_QUICK"); fi
}
for t in build/san/tests/*/*; do
	[ -x "$t" ] && [ -f "$t" ] || continue
	case "$t" in *.d | */bench/*) continue ;; esac # bench: programs the scripts drive
	add "${t#build/san/}" 0 0 "$t"
done
for t in tests/integration/*.sh; do
	[ -f "$t" ] || continue
	case "$t" in */lib.sh) continue ;; esac
	slow=0 a=0
	[ -n "${TIER[$t:slow]:-}" ] && slow=1
	[ -n "${TIER[$t:alone]:-}" ] && a=1
	[ "$quick" = 1 ] && [ "$slow" = 1 ] && continue
	add "$t" "$a" "$slow" bash "$t"
done
n=${#names[@]}
if [ "$n" -eq 0 ]; then
	echo "run.sh: no test matches '${pattern}' (names like tests/unit/params, tests/integration/study_run.sh)" >&2
	exit 2
fi

# The order lines are printed in: every test that may run beside others, in the order
# above, then the ones that run alone. The order they are started in: the slow ones
# first, so that the last minutes are not one long script on one CPU.
order=() start=() late=()
for ((i = 0; i < n; i++)); do [ "${alone[i]}" = 0 ] && order+=("$i"); done
for ((i = 0; i < n; i++)); do [ "${alone[i]}" = 1 ] && order+=("$i") && late+=("$i"); done
for ((i = 0; i < n; i++)); do [ "${alone[i]}" = 0 ] && [ "${first[i]}" = 1 ] && start+=("$i"); done
for ((i = 0; i < n; i++)); do [ "${alone[i]}" = 0 ] && [ "${first[i]}" = 0 ] && start+=("$i"); done

D=$(mktemp -d "${TMPDIR:-/tmp}/shake-run.XXXXXX")
trap 'rm -rf "$D"' EXIT
launch() { # index: runs the test in the background; DIR/i.rc gets "status seconds"
	local i=$1
	(
		t0=$(date +%s%N)
		# timeout makes itself a process group and signals all of it: the engines and
		# helpers a hung script started end with it
		timeout -k 10 "${limit[i]}" bash -c "${cmds[i]}" >"$D/$i.log" 2>&1 </dev/null
		rc=$?
		echo "$rc $((($(date +%s%N) - t0) / 1000000))" >"$D/$i.tmp" && mv "$D/$i.tmp" "$D/$i.rc"
	) &
}

pass=0 fail=0 skipped=0 sum_ms=0 times=()
report() { # index: the test's lines, from its log
	local i=$1 name=${names[$1]} log="$D/$1.log" rc ms p f k
	read -r rc ms <"$D/$i.rc"
	p=$(grep -c '^ok ' "$log")
	f=$(grep -c '^FAIL ' "$log")
	# a skip in any spelling is shown and counted: a check that cannot run is news
	k=$(grep -ciE '^(# )?skip[ :]' "$log")
	grep -iE '^(FAIL|ok |(# )?skip[ :])' "$log" | sed -E 's/^(# )?[sS][kK][iI][pP][ :]/SKIP /; s/^/  /' | grep -v '^  ok ' || true
	if [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then
		echo "  FAIL $name: timed out after ${limit[i]} s (run.sh's limit for its tier); its output ends:"
		tail -n 15 "$log" | sed 's/^/    /'
		f=$((f + 1))
	elif [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
		echo "  FAIL $name: exited with status $rc without reporting a failure; its output ends:"
		tail -n 15 "$log" | sed 's/^/    /'
		f=1
	elif [ "$p" -eq 0 ] && [ "$f" -eq 0 ] && [ "$k" -eq 0 ]; then
		echo "  FAIL $name: reported no check (no ok, FAIL or SKIP line); its output ends:"
		tail -n 15 "$log" | sed 's/^/    /'
		f=1
	fi
	pass=$((pass + p)) fail=$((fail + f)) skipped=$((skipped + k)) sum_ms=$((sum_ms + ms))
	times+=("$ms $name")
	printf '%-48s %3d ok %3d failed%s  (%ds)\n' "$name" "$p" "$f" "$([ "$k" -gt 0 ] && echo " $k skipped")" $(((ms + 500) / 1000))
}

t_start=$(date +%s%N)
next=0 shown=0 running=0
flush() { # prints, in order, every test that has ended
	while [ "$shown" -lt "$n" ] && [ -e "$D/${order[shown]}.rc" ]; do
		report "${order[shown]}"
		shown=$((shown + 1))
	done
}
while [ "$next" -lt "${#start[@]}" ] || [ "$running" -gt 0 ]; do
	while [ "$running" -lt "$jobs" ] && [ "$next" -lt "${#start[@]}" ]; do
		launch "${start[next]}"
		next=$((next + 1)) running=$((running + 1))
	done
	wait -n
	running=0
	for i in "${start[@]:0:next}"; do [ -e "$D/$i.rc" ] || running=$((running + 1)); done
	flush
done
wait
for i in "${late[@]}"; do
	launch "$i"
	wait
	flush
done
flush
echo "# the slowest tests (s of wall time):"
printf '%s\n' "${times[@]}" | sort -rn | head -n 10 | awk '{ printf "#   %6.1f  %s\n", $1 / 1000, $2 }'
echo "# $n tests, $jobs at a time: $((($(date +%s%N) - t_start) / 1000000000)) s of wall time, $((sum_ms / 1000)) s summed over the tests"
echo "$pass passed, $fail failed, $skipped skipped"
[ "$fail" -eq 0 ]
