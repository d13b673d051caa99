#!/usr/bin/env bash
# fuzz_runfile_quick.sh - the short run of `make fuzz`'s run-file target for make check:
# a fixed seed and a fixed number of run files of tests/fuzz/runs.campaign changed by
# h5mut (shapes, types, attributes, values, truncation, bit flips; input k is the same
# in every run of the same tree), each read by one of the analysis tools or `study run`
# (the sanitizer builds). One FAIL per distinct finding (crash, sanitizer report, hang,
# undocumented exit code), with the command that reproduces it; the findings stay in
# build/fuzz/quick-runfile/. Then a few inputs of each family of tests/fuzz/families.sh
# (run files edited and sealed again, links and virtual datasets, database corruptions,
# planted nodes), from the same seed campaign: one FAIL per crash, hang or silent result
# (what each means: families.sh). About a minute and a half: the seed campaign, then
# ~1 s an input.
# tier: slow: a seed campaign, then every mutated run file read by a tool
. "$(dirname "$0")/lib.sh"
STUDY="${STUDY:-$(dirname "$SHAKE")/study}"
FUZZ="${FUZZ_BIN:-$REPO/build/fuzz/fuzz}"
H5MUT="${FUZZ_H5MUT:-$REPO/build/fuzz/h5mut}"
for b in "$STUDY" "$FUZZ" "$H5MUT"; do
	[ -x "$b" ] || { fail setup "$b is not an executable (run make tests)"; finish; }
done
N="${FUZZ_RUNFILE_QUICK_INPUTS:-32}"
NF="${FUZZ_FAMILIES_QUICK_INPUTS:-3}" # per family
SEED="${FUZZ_RUNFILE_QUICK_SEED:-7}"
OUT="$REPO/build/fuzz/quick-runfile"

FUZZ_SHAKE="$SHAKE" FUZZ_STUDY="$STUDY" FUZZ_BIN="$FUZZ" FUZZ_H5MUT="$H5MUT" FUZZ_TARGETS=runfile,resealed,links,database,paths FUZZ_SECONDS=0 \
	FUZZ_INPUTS="$N" FUZZ_FAMILY_INPUTS="$NF" FUZZ_SEED="$SEED" FUZZ_TIMEOUT="${FUZZ_TIMEOUT:-20}" FUZZ_OUT="$OUT" FUZZ_WORK="$TMP/work" \
	bash "$REPO/tests/fuzz/fuzz.sh" >"$TMP/fuzz.log" 2>&1
rc=$?
{
	grep -E '^fuzz: [0-9]+ inputs in .* seed|^fuzz: findings|runfile exit codes' "$TMP/fuzz.log"
	# the table at the end: inputs, crashes, hangs, silent per family
	awk '/^fuzz: family / { t = "" } /^fuzz: (family|runfile|resealed|links|database|paths|total) / { t = t $0 "\n" } END { printf "%s", t }' "$TMP/fuzz.log"
} | sed 's/^/# /'
if [ "$rc" -gt 1 ] || [ ! -s "$OUT/summary.tsv" ]; then
	fail fuzz.runfile_quick.runs "exit $rc: $(tail -n 5 "$TMP/fuzz.log")"
	finish
fi
read -r tried <<<"$(sed -n 's/^fuzz: \([0-9]*\) inputs in .*, seed .*/\1/p' "$TMP/fuzz.log")"
[ "${tried:-0}" = "$N" ] && ok fuzz.runfile_quick.runs || fail fuzz.runfile_quick.runs "$tried of $N inputs tried"

slug() { tr 'A-Z' 'a-z' <<<"$1" | tr -c 'a-z0-9\n' '_' | sed 's/__*/_/g; s/^_//; s/_$//' | cut -c1-48; }
while IFS=$'\t' read -r kind target n sig repro; do
	[ "$kind" = kind ] && continue
	fail "fuzz.runfile_quick.$kind.$(slug "$sig")" "$n inputs: $sig; reproduce: $repro"
done <"$OUT/summary.tsv"
# every family tried its inputs, and each finding is a FAIL with its reproduction
for fam in resealed links database paths; do
	read -r tried <<<"$(sed -n "s/^fuzz: $fam  *\([0-9]*\) .*/\1/p" "$TMP/fuzz.log" | head -n 1)"
	[ "${tried:-0}" = "$NF" ] && ok "fuzz.families_quick.$fam.runs" ||
		fail "fuzz.families_quick.$fam.runs" "${tried:-no} of $NF inputs tried: $(grep -m3 "families:" "$TMP/fuzz.log")"
done
if [ -f "$OUT/families.tsv" ]; then
	while IFS=$'\t' read -r fam k class cmd what repro; do
		[ "$fam" = family ] && continue
		fail "fuzz.families_quick.$fam.$class.$k" "$cmd: $what; reproduce: $repro"
	done <"$OUT/families.tsv"
else
	fail fuzz.families_quick.summary "no $OUT/families.tsv"
fi
[ "$NFAIL" -eq 0 ] && ok fuzz.runfile_quick.no_findings
finish
