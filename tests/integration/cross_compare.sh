#!/usr/bin/env bash
# cross_compare.sh - `make cross-aarch64` compares each test's output under qemu with
# this machine's (tests/cross/same_output.sh, docs/cross.md "What it checks"): the
# kernel test's output of this host, planted as an aarch64 host's (neon instead of the
# x86-64 paths) and as an x86-64 host's without AVX-512 ("SKIP kernel.avx512"), must
# compare the same both ways; a difference of arithmetic must not: a w8 number
# changed, a w8 check on one side alone, a SKIP of a path the other side runs, another
# test's check on one side alone. Seconds, no qemu.
# tier: quick
. "$(dirname "$0")/lib.sh"
KT=$(dirname "$SHAKE")/../tests/unit/kernel
[ -x "$KT" ] || { fail setup "$KT is not built (make tests)"; finish; }
SAME="$REPO/tests/cross/same_output.sh"
"$KT" >"$TMP/host" 2>/dev/null
grep -q '^ok kernel\.w8\.' "$TMP/host" && grep -q '^ok kernel\.sse2\.' "$TMP/host" ||
	{ fail setup "the kernel test printed no w8 and sse2 checks: $(head -c 300 "$TMP/host")"; finish; }
# an x86-64 host without AVX-512: its avx512 checks one SKIP line (as kernel.c prints it)
{ grep -v '^ok kernel\.avx512\.' "$TMP/host"
  echo "SKIP kernel.avx512: this CPU cannot run it (it needs AVX-512F, AVX-512DQ)"; } >"$TMP/x86_avx2"
# an x86-64 host with AVX-512: this host's output, with its avx512 checks whether this
# CPU has them or not
{ grep -v '^SKIP kernel\.avx512' "$TMP/host"
  sed -n 's/^ok kernel\.w8\./ok kernel.avx512./p' "$TMP/host"; } | awk '!seen[$0]++' >"$TMP/x86_avx512"
# aarch64: neon and w8, no x86-64 path
{ grep -Ev '^(ok|SKIP) kernel\.(sse2|avx2|avx512)[.:]' "$TMP/host"
  sed -n 's/^ok kernel\.w8\./ok kernel.neon./p' "$TMP/host"; } >"$TMP/arm"

# same ID A B: no difference; differs ID A B: a difference, and the line shown
same() {
	local out rc
	out=$(bash "$SAME" "$2" "$3" 2>"$TMP/own")
	rc=$?
	check "cross_compare.same.$1" "same_output.sh exited $rc and showed: $(echo "$out" | head -n 3)" test -z "$out" -a "$rc" -eq 0
}
differs() {
	local out rc
	out=$(bash "$SAME" "$2" "$3" 2>/dev/null)
	rc=$?
	check "cross_compare.differs.$1" "exit $rc and '$out', wanted exit 1 and the line '$4'" \
		test "$rc" -eq 1 -a "$(printf '%s\n' "$out" | grep -cxF -- "$4")" -eq 1
}
same arm_vs_avx2 "$TMP/arm" "$TMP/x86_avx2"
n=$(grep -c '^ok kernel\.neon\.' "$TMP/arm") m=$(grep -Ec '^ok kernel\.(sse2|avx2)\.' "$TMP/x86_avx2")
check cross_compare.same.own_counted "the stderr line '$(cat "$TMP/own")' does not count $n neon checks as aarch64's own, $m sse2 and avx2 ones as x86-64's" \
	grep -qx "mine $n; theirs $m" "$TMP/own"
same arm_vs_avx512 "$TMP/arm" "$TMP/x86_avx512"

# a w8 check's line, changed on the aarch64 side
w8=$(grep -m1 '^ok kernel\.w8\.' "$TMP/host")
sed "s/^$w8\$/FAIL ${w8#ok }: planted/" "$TMP/arm" >"$TMP/arm_fail"
differs w8_failed "$TMP/arm_fail" "$TMP/x86_avx2" "< FAIL ${w8#ok }: planted"
grep -vxF "$w8" "$TMP/arm" >"$TMP/arm_less"
differs w8_one_side "$TMP/arm_less" "$TMP/x86_avx2" "> $w8"
{ cat "$TMP/arm"; echo "SKIP kernel.w8: this CPU cannot run it (it needs nothing)"; } >"$TMP/arm_skip"
differs skip_of_a_shared_path "$TMP/arm_skip" "$TMP/x86_avx2" "< SKIP kernel.w8: this CPU cannot run it (it needs nothing)"
{ cat "$TMP/arm"; echo "ok boot.quantile.gsl_bits"; } >"$TMP/arm_more"
differs other_check_one_side "$TMP/arm_more" "$TMP/x86_avx2" "< ok boot.quantile.gsl_bits"
{ cat "$TMP/arm"; echo "SKIP boot.quantile.gsl_bits: planted"; } >"$TMP/arm_oskip"
differs other_skip_one_side "$TMP/arm_oskip" "$TMP/x86_avx2" "< SKIP boot.quantile.gsl_bits: planted"
{ cat "$TMP/arm"; echo "# error 1.5e-09"; } >"$TMP/arm_n1"
{ cat "$TMP/x86_avx2"; echo "# error 1.6e-09"; } >"$TMP/x86_n1"
differs numbers "$TMP/arm_n1" "$TMP/x86_n1" "< # error 1.5e-09"
finish
