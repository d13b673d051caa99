#!/usr/bin/env bash
# regression.sh - a shaken bed with an intruder, run by every integrator, must end exactly
# (%.17g) as the committed reference in tests/reference/ (written by
# `bash tests/reference/regress.sh write`). Every build is compared: the sanitizer build
# (-O1), the release build (-O3, vectorised, the AVX-512 force kernel where the machine
# has it) and the portable build (baseline x86-64, the scalar force kernel), so an
# optimisation that reorders a sum, a SIMD kernel that differs from the scalar one, or a
# compiler flag that contracts a multiply-add is caught. A perturbed run (mu) must
# differ, so the comparison can fail.
. "$(dirname "$0")/lib.sh"
. "$REPO/tests/reference/regress.sh"
REL="$REPO/bin/shake"
PORT="$REPO/build/port/bin/shake"

# compare ID SHAKE CASE : run and compare with the reference
compare() {
	local id=$1 bin=$2 c=$3 out="$TMP/$1.h5"
	if ! regress_run "$bin" "$c" "$out" >"$TMP/$id.log" 2>&1; then
		fail "$id.run" "exit $?: $(head -c 300 "$TMP/$id.log")"
		return
	fi
	regress_reduce "$out" >"$TMP/$id.txt"
	if cmp -s "$TMP/$id.txt" "$REPO/tests/reference/$c.txt"; then
		ok "$id"
	else
		fail "$id" "differs from tests/reference/$c.txt: $(diff "$TMP/$id.txt" "$REPO/tests/reference/$c.txt" | grep -c '^<') of $(wc -l <"$TMP/$id.txt") lines, first: $(diff "$TMP/$id.txt" "$REPO/tests/reference/$c.txt" | sed -n 2p)"
	fi
}

for c in "${REGRESS_CASES[@]}"; do
	[ -s "$REPO/tests/reference/$c.txt" ] || { fail "regression.$c.reference" "tests/reference/$c.txt is missing"; continue; }
	compare "regression.$c.sanitizer_build" "$SHAKE" "$c"
	if [ -x "$REL" ] && [ "$REL" != "$SHAKE" ]; then
		compare "regression.$c.release_build" "$REL" "$c"
	fi
	if [ -x "$PORT" ] && [ "$PORT" != "$SHAKE" ]; then
		compare "regression.$c.portable_build" "$PORT" "$c"
	fi
done

# the comparison can fail: a 2 % change of mu changes the reference scene's end state
if "$SHAKE" "${REGRESS_SCENE[@]}" integrator=gear5 mu=0.49 output="$TMP/mu.h5" >"$TMP/mu.log" 2>&1; then
	regress_reduce "$TMP/mu.h5" >"$TMP/mu.txt"
	if cmp -s "$TMP/mu.txt" "$REPO/tests/reference/gear5.txt"; then
		fail regression.detects_change "mu = 0.49 gave the reference output of mu = 0.5"
	else
		ok regression.detects_change
	fi
else
	fail regression.detects_change.run "exit: $(head -c 300 "$TMP/mu.log")"
fi
finish
