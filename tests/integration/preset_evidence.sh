#!/usr/bin/env bash
# preset_evidence.sh - the rule that ties a campaign's preset to measured evidence
# (scripts/preset_evidence.sh): every campaign of make reproduce passes it on the table
# the benchmarks wrote (docs/preset_evidence.tsv), and on tables whose answer is known it
# refuses what it must (fast resting on a comparison that differs, on none, on a key that
# is not there; a malformed table or row) and lets the rest through. Seconds; no engine run.
. "$(dirname "$0")/lib.sh"
PE=$REPO/scripts/preset_evidence.sh
cd "$TMP" || exit 1

# the real campaigns against the real table
out=$(bash "$PE" check 2>&1)
rc=$?
[ "$rc" = 0 ] && ! grep -q '^FAIL' <<<"$out" && [ "$(grep -c '^ok evidence\.' <<<"$out")" = "$(ls "$REPO"/campaigns/reproduce/*.campaign | wc -l)" ] &&
	ok reproduce.campaigns || fail reproduce.campaigns "exit $rc: $(grep -v '^ok' <<<"$out" | head -n 5)"
# every key a campaign names is a row (the check above), and every row is named by some
# campaign of make reproduce: no evidence measured for nothing
unused=$(cut -f1 "$REPO/docs/preset_evidence.tsv" | while read -r k; do
	grep -qE "^# preset evidence:.*(^| )$k( |$)" "$REPO"/campaigns/reproduce/*.campaign || echo "$k"; done)
[ -z "$unused" ] && ok table.all_used || fail table.all_used "rows no campaign names: $unused"

# a known table: one comparison indistinguishable, one that differs, one whose answer differs
export EVIDENCE=$TMP/ev.tsv
: >"$EVIDENCE"
bash "$PE" set same indistinguishable "bench X, 2026-01-01, abc" "the same within 0.1" &&
	bash "$PE" set apart differ "bench Y, 2026-01-02, abd" "apart, p = 0.001" &&
	bash "$PE" set answer answer_differs "bench Z, 2026-01-03, abe" "effect with one only" &&
	ok set.rows || fail set.rows "set failed"
# set replaces a row of the same key: still three rows, the new sentence
bash "$PE" set same indistinguishable "bench X, 2026-01-04, abf" "the same within 0.05"
[ "$(wc -l <"$EVIDENCE")" = 3 ] && grep -q $'^same\tindistinguishable\tbench X, 2026-01-04, abf\tthe same within 0.05$' "$EVIDENCE" &&
	ok set.replaces || fail set.replaces "$(cat "$EVIDENCE")"
# bad rows are refused and leave the table as it was
cp "$EVIDENCE" before.tsv
refuse() { # ID KEY VERDICT SOURCE SENTENCE
	local id=$1
	shift
	if bash "$PE" set "$@" 2>err.txt; then fail "set.refuses.$id" "accepted: $*"
	elif ! grep -q 'preset_evidence: ' err.txt; then fail "set.refuses.$id" "no message: $(cat err.txt)"
	else ok "set.refuses.$id"; fi
}
refuse verdict k maybe src s
refuse key bad/key differ src s
refuse tab k differ "src"$'\t'"x" s
refuse newline k differ src "two"$'\n'"lines"
cmp -s before.tsv "$EVIDENCE" && ok set.untouched || fail set.untouched "the table changed"

camp() { # NAME PRESET KEYS...
	local n=$1 p=$2
	shift 2
	{
		echo "# a test campaign"
		echo "# preset: $p, for the test."
		[ $# -gt 0 ] && echo "# preset evidence: $*"
		printf '[campaign]\nname = %s\nseed = 1\n[scene]\npreset = %s   # the preset\nduration = 1\n' "$n" "$p"
	} >"$n.campaign"
}
camp fast_same fast same
camp fast_apart fast same apart
camp fast_answer fast answer
camp fast_none fast
camp fast_missing fast nosuchkey
camp paper_apart paper apart
camp paper_none paper
# expect NAME ok|FAIL [WHAT-IN-MESSAGE]
expect() {
	local o
	o=$(bash "$PE" check "$1.campaign" 2>&1)
	case $2 in
	ok) [ "$o" = "ok evidence.$1.campaign" ] && ok "check.$1" || fail "check.$1" "want ok, got: $o" ;;
	FAIL) grep -q "^FAIL evidence.$1.campaign: .*$3" <<<"$o" && ! bash "$PE" check "$1.campaign" >/dev/null 2>&1 &&
		ok "check.$1" || fail "check.$1" "want FAIL ($3), got: $o" ;;
	esac
}
expect fast_same ok
expect fast_apart FAIL "apart is differ"
expect fast_answer FAIL "answer is answer_differs"
expect fast_none FAIL "without a '# preset evidence:' line"
expect fast_missing FAIL "nosuchkey: no such row"
expect paper_apart ok
expect paper_none ok

# the paragraph REPRODUCTION.md prints: each key with its verdict, sentence and source
l=$(bash "$PE" line fast_apart.campaign)
[ "$l" = "same: indistinguishable (the same within 0.05, bench X, 2026-01-04, abf); apart: differ (apart, p = 0.001, bench Y, 2026-01-02, abd)" ] &&
	ok line.text || fail line.text "$l"
[ "$(bash "$PE" line paper_none.campaign)" = "none measured" ] && ok line.none || fail line.none "$(bash "$PE" line paper_none.campaign)"

# a malformed table fails every check
printf 'k\tmaybe\tsrc\ts\n' >>"$EVIDENCE"
o=$(bash "$PE" check fast_same.campaign 2>&1)
grep -q '^FAIL evidence.table: .*ev.tsv:4' <<<"$o" && ok table.malformed || fail table.malformed "$o"
finish
