#!/usr/bin/env bash
# mutations_apply.sh - every planted bug of `make mutate` (tests/mutate/mutations.tsv)
# still plants: its file exists, its sed script changes it, and the tests it names are
# tests the suite has. `make mutate` builds and runs each one (minutes a bug), so it is
# not part of make check; a line whose code moved on would otherwise be found only
# there, as BROKEN, long after the change that moved it. Known answers: a line whose
# script matches nothing, and one naming a test that does not exist, are found (in a
# copy of the list). Seconds.
. "$(dirname "$0")/lib.sh"
cd "$REPO" || exit 1
LIST=tests/mutate/mutations.tsv
TESTS=$(ls tests/unit/*.c tests/physics/*.c tests/analysis/*.c tests/integration/*.sh 2>/dev/null |
	sed 's/\.c$//')

# check_list FILE : "id: why" for each line of FILE that does not plant its bug
check_list() {
	local id file script tests what out
	while IFS=$'\t' read -r id file script tests what; do
		case $id in '' | '#'*) continue ;; esac
		if [ ! -f "$file" ]; then
			echo "$id: no file $file"
			continue
		fi
		out=$(sed -e "$script" "$file" 2>&1) || { echo "$id: sed failed: $out"; continue; }
		[ "$out" = "$(cat "$file")" ] && echo "$id: the script changes nothing in $file (update $LIST)"
		grep -qE "$tests" <<<"$TESTS" || echo "$id: no test of the suite matches '$tests'"
	done <"$1"
}

n=$(grep -cvE '^(#|$)' "$LIST")
bad=$(check_list "$LIST")
[ -z "$bad" ] && ok "mutations.all_$n.plant" || fail mutations.plant "$(head -n 5 <<<"$bad")"

# the checker finds what it must (in copies of the list)
first=$(grep -m1 -vE '^(#|$)' "$LIST")
printf '%s\n' "$first" | awk -F'\t' -v OFS='\t' '{ $3 = "s/no such text anywhere 12345/x/"; print }' >"$TMP/nomatch.tsv"
[ -n "$(check_list "$TMP/nomatch.tsv")" ] && ok mutations.selftest.script_changes_nothing ||
	fail mutations.selftest.script_changes_nothing "a script that matches nothing passed"
printf '%s\n' "$first" | awk -F'\t' -v OFS='\t' '{ $4 = "tests/unit/no_such_test"; print }' >"$TMP/notest.tsv"
[ -n "$(check_list "$TMP/notest.tsv")" ] && ok mutations.selftest.unknown_test ||
	fail mutations.selftest.unknown_test "a line naming a test that does not exist passed"
[ -z "$(check_list <(printf '%s\n' "$first"))" ] && ok mutations.selftest.good_line ||
	fail mutations.selftest.good_line "the list's first line was refused: $(check_list <(printf '%s\n' "$first"))"
finish
