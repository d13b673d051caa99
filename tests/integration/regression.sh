#!/usr/bin/env bash
# regression.sh - a shaken bed with an intruder, run by every integrator, must end exactly
# (%.17g) as the committed reference in tests/reference/ (written by
# `bash tests/reference/regress.sh write`). Every build and path is compared: the
# sanitizer build (-O1) on the path it picks, and the release build on every path of
# the force kernel this CPU can run (`shake --kernel-paths`; the others are named on
# SKIP lines), so an optimisation that reorders a sum, a vector path that differs from
# another, or a compiler flag that contracts a multiply-add is caught. A perturbed run
# (mu) must differ, so the comparison can fail.
. "$(dirname "$0")/lib.sh"
. "$REPO/tests/reference/regress.sh"
REL="$REPO/bin/shake"

# compare ID SHAKE CASE [PATH] : run (on the kernel path PATH, else the one the CPU
# picks) and compare with the reference
compare() {
	local id=$1 bin=$2 c=$3 path=${4:-auto} out="$TMP/$1.h5"
	local rc
	SHAKEBOX_KERNEL=$path regress_run "$bin" "$c" "$out" >"$TMP/$id.log" 2>&1
	rc=$?
	if [ $rc != 0 ]; then
		fail "$id.run" "exit $rc: $(head -c 300 "$TMP/$id.log")"
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
		while read -r path runs _ needs; do
			if [ "$runs" = yes ]; then
				compare "regression.$c.release_build.$path" "$REL" "$c" "$path"
			else
				echo "SKIP regression.$c.release_build.$path: this CPU cannot run it (it needs $needs)"
			fi
		done < <("$REL" --kernel-paths)
	fi
done
# every path of the release build was run (none lost to a failing --kernel-paths)
n=$("$REL" --kernel-paths 2>/dev/null | wc -l)
[ "$n" -ge 2 ] && ok regression.paths_listed || fail regression.paths_listed "shake --kernel-paths listed $n paths"

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
