#!/usr/bin/env bash
# mutate.sh - does the suite catch planted bugs? (`make mutate`; not in make check)
#
#   bash tests/mutate/mutate.sh [ID-REGEX]
#
# Each line of tests/mutate/mutations.tsv plants one bug (a sed script on one file) in a
# scratch copy of this tree (the committed HEAD plus the work tree's changes), builds the
# sanitizer build there, runs the tests named for that bug with tests/run.sh, and puts
# the file back. A bug is caught when one of its tests fails; it survived when they all
# pass. A script that does not change its file (the code moved on) or a file that no
# longer compiles is an error of the list, said so. Prints one line per bug and
# "N caught, N survived, N broken"; exits non-zero unless every bug was caught.
# docs/testing.md, "Planted bugs".
set -u
cd "$(dirname "$0")/../.."
REPO=$PWD
LIST=tests/mutate/mutations.tsv
only=${1:-}
case $only in -h | --help) sed -n '2,/^set -u/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac

W=$(mktemp -d "${TMPDIR:-/tmp}/shake-mutate.XXXXXX")
trap 'rm -rf "$W"' EXIT
# the scratch copy: every tracked file as the work tree has it (no build, no runs)
git ls-files -z | tar --null -T - -cf - | tar -xf - -C "$W"
cd "$W" || exit 2
jobs=${NPROC:-$(nproc 2>/dev/null || echo 1)}
echo "# building the sanitizer build in $W ($jobs jobs)"
if ! make -j"$jobs" SAN=1 tests >build.log 2>&1; then
	echo "mutate: the unmutated tree does not build: $(tail -n 3 build.log)" >&2
	exit 2
fi
caught=0 survived=0 broken=0
while IFS=$'\t' read -r id file script tests what; do
	case $id in '' | '#'*) continue ;; esac
	[ -n "$only" ] && ! [[ $id =~ $only ]] && continue
	cp "$file" "$file.orig"
	t0=$(date +%s)
	sed -i -e "$script" "$file"
	if cmp -s "$file" "$file.orig"; then
		printf '%-34s BROKEN    the script changes nothing in %s (the code moved on: update %s)\n' "$id" "$file" "$LIST"
		broken=$((broken + 1))
		mv "$file.orig" "$file"
		continue
	fi
	if ! make -j"$jobs" SAN=1 tests >"$id.build.log" 2>&1; then
		printf '%-34s BROKEN    does not compile: %s\n' "$id" "$(grep -m1 'error' "$id.build.log")"
		broken=$((broken + 1))
	else
		bash tests/run.sh "$tests" >"$id.log" 2>&1
		rc=$?
		failed=$(grep -E '^ +FAIL ' "$id.log" | head -n 1 | sed 's/^ *//' | cut -c1-110)
		if [ -z "$failed" ] && grep -q 'no test matches' "$id.log"; then
			# a test the scratch copy lacks (not yet added to git?) catches nothing
			printf '%-34s BROKEN    %s\n' "$id" "$(grep -m1 'no test matches' "$id.log")"
			broken=$((broken + 1))
		elif [ "$rc" -ne 0 ]; then
			printf '%-34s caught    in %ss by %s\n' "$id" "$(($(date +%s) - t0))" "$failed"
			caught=$((caught + 1))
		else
			printf '%-34s SURVIVED  %s; its tests (%s) all pass\n' "$id" "$what" "$tests"
			survived=$((survived + 1))
		fi
	fi
	mv "$file.orig" "$file"
	touch "$file" # older than its object now: make rebuilds it for the next bug
done <"$REPO/$LIST"
echo "$caught caught, $survived survived, $broken broken"
[ "$survived" -eq 0 ] && [ "$broken" -eq 0 ] && [ "$caught" -gt 0 ]
