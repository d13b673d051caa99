#!/usr/bin/env bash
# fuzz_quick.sh - the short run of `make fuzz` for make check: a fixed seed and a fixed
# number of mutated scene, campaign and particle files (input k is the same bytes in
# every run of the same tree) against the sanitizer builds of shake and `study
# expand`. One FAIL per distinct finding (crash, sanitizer report, hang, undocumented
# exit code, an input the reader must refuse that was accepted), with the command that
# reproduces it; the findings stay in build/fuzz/quick/ (run files: fuzz_runfile_quick.sh).
# tier: slow: 250 mutated inputs, each run by the sanitizer build
. "$(dirname "$0")/lib.sh"
STUDY="${STUDY:-$(dirname "$SHAKE")/study}"
FUZZ="${FUZZ_BIN:-$REPO/build/fuzz/fuzz}"
for b in "$STUDY" "$FUZZ"; do
	[ -x "$b" ] || { fail setup "$b is not an executable (run make tests)"; finish; }
done
N="${FUZZ_QUICK_INPUTS:-250}"
SEED="${FUZZ_QUICK_SEED:-11}"
OUT="$REPO/build/fuzz/quick"
# Findings that others are fixing: "kind<TAB>target<TAB>signature<TAB>why" lines; a
# match is reported as a comment, not a failure, and an entry this run no longer
# finds is named so that it can go
KNOWN="${FUZZ_QUICK_KNOWN:-$REPO/tests/fuzz/known.tsv}"

FUZZ_SHAKE="$SHAKE" FUZZ_STUDY="$STUDY" FUZZ_BIN="$FUZZ" FUZZ_TARGETS=scene,campaign,particles FUZZ_SECONDS=0 \
	FUZZ_INPUTS="$N" FUZZ_SEED="$SEED" \
	FUZZ_OUT="$OUT" FUZZ_WORK="$TMP/work" bash "$REPO/tests/fuzz/fuzz.sh" >"$TMP/fuzz.log" 2>&1
rc=$?
grep -E '^fuzz: [0-9]+ inputs in .* seed|^fuzz: findings|exit codes' "$TMP/fuzz.log" | sed 's/^/# /'
if [ "$rc" -gt 1 ] || [ ! -s "$OUT/summary.tsv" ]; then
	fail fuzz.quick.runs "exit $rc: $(tail -n 5 "$TMP/fuzz.log")"
	finish
fi
read -r tried <<<"$(sed -n 's/^fuzz: \([0-9]*\) inputs in .*, seed .*/\1/p' "$TMP/fuzz.log")"
[ "${tried:-0}" = "$N" ] && ok fuzz.quick.runs || fail fuzz.quick.runs "$tried of $N inputs tried"

declare -A seen=()
slug() { tr 'A-Z' 'a-z' <<<"$1" | tr -c 'a-z0-9\n' '_' | sed 's/__*/_/g; s/^_//; s/_$//' | cut -c1-48; }
while IFS=$'\t' read -r kind target n sig repro; do
	[ "$kind" = kind ] && continue
	key="$kind"$'\t'"$target"$'\t'"$sig"
	if [ -f "$KNOWN" ] && cut -f1-3 "$KNOWN" | grep -qxF -- "$key"; then
		seen[$key]=1
		echo "# known finding (being fixed): $kind $target, $n inputs: $sig; reproduce: $repro"
		continue
	fi
	fail "fuzz.quick.$target.$kind.$(slug "$sig")" "$n inputs: $sig; reproduce: $repro"
done <"$OUT/summary.tsv"
if [ -f "$KNOWN" ]; then
	while IFS=$'\t' read -r kind target sig why; do
		case "$kind" in '' | '#'*) continue ;; esac
		[ -n "${seen[$kind$'\t'$target$'\t'$sig]:-}" ] ||
			echo "# known finding not found any more (remove it from $KNOWN): $kind $target: $sig"
	done <"$KNOWN"
fi
[ "$NFAIL" -eq 0 ] && ok fuzz.quick.no_findings
finish
