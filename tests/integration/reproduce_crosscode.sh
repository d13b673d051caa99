#!/usr/bin/env bash
# reproduce_crosscode.sh - `REPRODUCE_CROSSCODE=1 make reproduce` (scripts/reproduce.sh):
# only what REPRODUCTION.md takes from the validation fragment is rewritten, by the code
# of a full report. On the committed pair (REPRODUCTION.md and docs/validate_lammps.md)
# nothing but the row saying so changes; a fragment with a known new claim-5 result and
# sentence puts exactly those in; a report without one of the places is refused and left
# as it was. Seconds; no engine run.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1
R=$REPO/scripts/reproduce.sh
export REPRODUCE_QUICK=1 REPRODUCE_WORK=$TMP/w REPRODUCE_CROSSCODE=1
mkdir -p w
cp "$REPO/REPRODUCTION.md" w/REPRODUCTION.md

# 1. the committed pair: the pieces regenerate to what the report holds
bash "$R" >out.txt 2>&1
rc=$?
# (a committed report refreshed before has the row saying so already: the row aside)
diff <(grep -v '^| cross-code lines |' "$REPO/REPRODUCTION.md") <(grep -v '^| cross-code lines |' w/REPRODUCTION.md) >d.txt
[ "$rc" = 0 ] && [ ! -s d.txt ] && grep -q "^| cross-code lines | refreshed on $(date -u +%Y-%m-%d) " w/REPRODUCTION.md &&
	ok crosscode.same_pair_same_report || fail crosscode.same_pair_same_report "exit $rc: $(head -c 600 d.txt) $(tail -n 3 out.txt)"
# a second refresh keeps one such row
bash "$R" >/dev/null 2>&1
[ "$(grep -c '^| cross-code lines |' w/REPRODUCTION.md)" = 1 ] && ok crosscode.one_row || fail crosscode.one_row "$(grep -c '^| cross-code lines |' w/REPRODUCTION.md) rows"

# 2. a fragment whose part C has a known new result and sentence
awk '$0 ~ /^\| C \| / { n = split($0, f, " [|] "); f[4] = "PLANTED RESULT"; s = f[1]; for (i = 2; i <= n; i++) s = s " | " f[i]; print s; next }
	/^## C\./ { c = 1 } /^## D\./ { c = 0 }
	c && /^Across the codes: / { next }
	{ print } c && /^shakebox: .*LAMMPS: / { print "Across the codes: PLANTED SENTENCE" }' \
	"$REPO/docs/validate_lammps.md" >val.md
grep -q 'PLANTED RESULT' val.md && grep -q 'PLANTED SENTENCE' val.md || fail crosscode.planted "the planted fragment lacks its marks"
cp "$REPO/REPRODUCTION.md" w/REPRODUCTION.md
REPRODUCE_VALIDATION=$TMP/val.md bash "$R" >out.txt 2>&1
rc=$?
c5=$(awk '/^## Claim 5/ { on = 1 } /^## Validation/ { on = 0 } on' w/REPRODUCTION.md)
[ "$rc" = 0 ] && [ "$(grep -c '^Across the codes: PLANTED SENTENCE$' <<<"$c5")" = 1 ] &&
	[ "$(grep -c '^Across the codes:' w/REPRODUCTION.md)" = 1 ] &&
	grep -q '^\*Cross-checked in LAMMPS\* (make validate-lammps, part C, .*PLANTED RESULT\.$' <<<"$c5" &&
	ok crosscode.claim5_rewritten || fail crosscode.claim5_rewritten "exit $rc: $(grep -n 'PLANTED\|Across' w/REPRODUCTION.md | head -c 600)"
# the validation section's table has the planted row, the other claims' lines are as they were
[ "$(awk '/^## Validation against LAMMPS/ { on = 1; next } on && /^## / { on = 0 } on' w/REPRODUCTION.md | grep -c '^| C | .*PLANTED RESULT')" = 1 ] &&
	ok crosscode.section_rewritten || fail crosscode.section_rewritten "the validation section lacks the planted row"
diff <(grep -v 'PLANTED\|^| C | \|^| cross-code lines |\|^Across the codes:\|^\*Cross-checked in LAMMPS\* (make validate-lammps, part C' "$REPO/REPRODUCTION.md") \
	<(grep -v 'PLANTED\|^| C | \|^| cross-code lines |\|^Across the codes:\|^\*Cross-checked in LAMMPS\* (make validate-lammps, part C' w/REPRODUCTION.md) >d.txt &&
	ok crosscode.rest_unchanged || fail crosscode.rest_unchanged "$(head -c 600 d.txt)"

# 3. a report without the validation section: refused, the file as it was
awk '/^## Validation against LAMMPS$/ { skip = 1; next } skip && /^## / { skip = 0 } !skip' "$REPO/REPRODUCTION.md" >w/REPRODUCTION.md
cp w/REPRODUCTION.md before.md
bash "$R" >out.txt 2>&1
rc=$?
[ "$rc" != 0 ] && grep -q 'places for the cross-code piece V' out.txt && cmp -s before.md w/REPRODUCTION.md &&
	ok crosscode.refuses_missing_place || fail crosscode.refuses_missing_place "exit $rc: $(tail -n 3 out.txt)"
# no report at all: refused with the reason
rm -f w/REPRODUCTION.md
bash "$R" >out.txt 2>&1
rc=$?
[ "$rc" != 0 ] && grep -q 'needs .*REPRODUCTION.md' out.txt && [ ! -e w/REPRODUCTION.md ] &&
	ok crosscode.refuses_no_report || fail crosscode.refuses_no_report "exit $rc: $(tail -n 3 out.txt)"
finish
