#!/usr/bin/env bash
# run.sh TEST... - run cross-built test programs under $QEMU (`make cross-aarch64`,
# docs/cross.md). Each test prints "ok ID" or "FAIL ID: why", as natively; a program
# that dies without saying FAIL counts as one failure. With NATIVE (a build directory
# of this machine, e.g. build/rel), the same test built natively runs too, and its
# output must be the same line for line, the numbers the tests print included
# ("# ..." lines): a check "cross.same_output.TEST". Only the passed and skipped checks
# of a kernel path the other side does not run may be on one side alone
# (tests/cross/same_output.sh: kernel.avx512.* passes on an AVX-512 host and says SKIP
# on one without it, kernel.neon.* passes on aarch64 only).
# One line per program, then "N passed, N failed"; exits non-zero on any failure.
set -u
cd "$(dirname "$0")/../.." || exit 1
QEMU=${QEMU:-qemu-aarch64 -L /usr/aarch64-linux-gnu}
# a program still running after this many seconds under qemu is a failure (the slowest,
# the Gear convergence test, takes about a minute)
LIMIT=${CROSS_TIMEOUT:-600}
pass=0 fail=0
log=$(mktemp)
nlog=$(mktemp)
olog=$(mktemp)
trap 'rm -f "$log" "$nlog" "$olog"' EXIT
NATIVE=${NATIVE:-}
CROSS_BUILD=${CROSS_BUILD:-build/aarch64}
[ $# -gt 0 ] || { echo "run.sh: no test programs given" >&2; exit 2; }
# Can qemu run a dynamically linked program that forks? qemu-user 7.2 (Debian 12) on a
# Linux 6.18 host cannot: the child spins forever (a static one forks fine). Every
# program whose code forks (a run file no recorded seal vouches for is walked in a
# child, core/io/h5read.c; csv's check through Python) then ends at the time limit.
probe=$(mktemp)
if printf '#include <unistd.h>\n#include <sys/wait.h>\nint main(void){pid_t p=fork();if(!p)_exit(7);int s=0;waitpid(p,&s,0);return WEXITSTATUS(s)==7?0:1;}\n' |
	"${CROSS_CC:-aarch64-linux-gnu-gcc}" -x c - -o "$probe" 2>/dev/null; then
	# shellcheck disable=SC2086
	timeout -k 2 20 $QEMU "$probe" >/dev/null 2>&1
	prc=$?
	[ "$prc" = 0 ] || echo "# cross: $QEMU cannot fork here (a program that forks and waits: exit $prc$([ "$prc" = 124 ] && echo ', still running after 20 s')): the programs that fork will fail at the time limit ($LIMIT s; docs/cross.md)"
fi
rm -f "$probe"
for t in "$@"; do
	t0=$SECONDS
	# shellcheck disable=SC2086 # QEMU is a command and its options
	timeout -k 10 "$LIMIT" $QEMU "$t" >"$log" 2>&1
	rc=$?
	[ "$rc" = 124 ] && echo "FAIL $t: still running after $LIMIT s under qemu (CROSS_TIMEOUT; a fork hangs qemu-user 7.2 on some hosts: docs/cross.md)" >>"$log"
	p=$(grep -c '^ok ' "$log")
	f=$(grep -c '^FAIL ' "$log")
	grep '^FAIL ' "$log" | sed 's/^/  /'
	if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
		echo "  FAIL $t: exited with status $rc without reporting a failure; its output ends:"
		tail -n 15 "$log" | sed 's/^/    /'
		f=1
	elif [ "$p" -eq 0 ] && [ "$f" -eq 0 ]; then
		echo "  FAIL $t: reported no check; its output ends:"
		tail -n 15 "$log" | sed 's/^/    /'
		f=1
	fi
	same=""
	if [ -n "$NATIVE" ]; then
		n=$NATIVE/${t#"$CROSS_BUILD"/}
		"$n" >"$nlog" 2>&1
		# what differs, but the summary lines and the checks of a kernel path the other
		# side does not run (same_output.sh)
		d=$(bash tests/cross/same_output.sh "$log" "$nlog" 2>"$olog")
		if [ $? -eq 0 ]; then
			p=$((p + 1))
			same=", output as on x86-64"
			mine=$(sed -n 's/^mine \([0-9]*\);.*/\1/p' "$olog")
			theirs=$(sed -n 's/.*; theirs \([0-9]*\)$/\1/p' "$olog")
			[ "${mine:-0}" -eq 0 ] || same+="; $mine checks aarch64's own"
			[ "${theirs:-0}" -eq 0 ] || same+="; $theirs x86-64's own"
		else
			echo "  FAIL cross.same_output.${t#"$CROSS_BUILD"/}: the output differs from $n's (< aarch64, > x86-64):"
			printf '%s\n' "$d" | head -n 10 | sed 's/^/    /'
			f=$((f + 1))
		fi
	fi
	pass=$((pass + p)); fail=$((fail + f))
	printf '%-44s %3d passed %3d failed  (%ds%s)\n' "$t" "$p" "$f" $((SECONDS - t0)) "$same"
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
