#!/usr/bin/env bash
# same_output.sh A B - the lines in which two outputs of one test program differ that
# are no difference of arithmetic (`make cross-aarch64`, docs/cross.md, "What it
# checks"): A from the aarch64 build under qemu, B from this machine's build. Prints
# them as diff does ("< " A's, "> " B's); exits 1 when there are any, 0 when none.
#
# The one thing two hosts may differ in is the set of kernel paths they run
# (docs/kernel.md): x86-64 has sse2, avx2 and avx512 (this last one only on a CPU with
# AVX-512), aarch64 has neon; both have w8. A path one host does not run is checked
# there not at all (neon on x86-64) or named on a SKIP line (avx512 on a CPU without
# it). So a line "ok kernel.P..." or "SKIP kernel.P: ..." on one side alone is no
# difference exactly when the other side runs no check of path P (no "ok" or "FAIL"
# line of kernel.P.*): a path both run (w8) must give the same lines on both, and
# every other line (other checks, other SKIPs, the numbers on "# ..." lines) must be
# the same. The summary lines "# N passed, N failed" are left out (their counts differ
# with the paths). Also the summary of the other side's own lines on stderr:
# "mine N; theirs N" (one-side ok lines of A, of B).
set -u
[ $# -eq 2 ] && [ -r "$1" ] && [ -r "$2" ] || { echo "usage: same_output.sh A B (two readable files)" >&2; exit 2; }
# the kernel paths a side runs: those of its ok and FAIL lines
run_paths() { sed -n 's/^\(ok\|FAIL\) kernel\.\([a-z0-9]*\)\..*/\2/p' "$1" | sort -u | tr '\n' ' '; }
pa=" $(run_paths "$1")" pb=" $(run_paths "$2")"
diff <(grep -v '^# [0-9]* passed, [0-9]* failed$' "$1") <(grep -v '^# [0-9]* passed, [0-9]* failed$' "$2") |
	grep '^[<>]' | awk -v pa="$pa" -v pb="$pb" '
		{
			side = substr($0, 1, 1); line = substr($0, 3); other = side == "<" ? pb : pa
			if (match(line, /^(ok|SKIP) kernel\.[a-z0-9]+[.:]/)) {
				p = line; sub(/^(ok|SKIP) kernel\./, "", p); sub(/[.:].*/, "", p)
				if (index(other, " " p " ") == 0) { if (line ~ /^ok /) own[side]++; next }
			}
			print; n++
		}
		END {
			printf "mine %d; theirs %d\n", own["<"], own[">"] > "/dev/stderr"
			exit (n > 0)
		}'
