#!/usr/bin/env bash
# docs_lists.sh - the docs and the code list the same things (docs/testing.md, "The docs
# agree with the code"): scripts/docs_lists.sh check passes on the docs as they are,
# and each list, broken on purpose in a copy of its doc (an entry dropped or one added
# that the code does not have), makes exactly that list's check fail. Seconds.
. "$(dirname "$0")/lib.sh"
study_setup
export SHAKE STUDY

# what the code says is the same for every call below: computed by the first, kept
export DOCS_LISTS_CACHE="$TMP/cache"
mkdir -p "$DOCS_LISTS_CACHE"

# --- the docs as they are ---
SHAKE="$SHAKE" STUDY="$STUDY" bash "$REPO/scripts/docs_lists.sh" check >"$TMP/check.out" 2>&1
rc=$?
cat "$TMP/check.out"
NOK=$((NOK + $(grep -c '^ok ' "$TMP/check.out")))
NFAIL=$((NFAIL + $(grep -c '^FAIL ' "$TMP/check.out")))
[ "$rc" -eq 0 ] || grep -q '^FAIL ' "$TMP/check.out" || fail docs_lists.exit "check exited $rc without a FAIL line"
# every list the code gives was kept for the calls below (else each would compute it again)
missing=
for f in scene-keys.new result-columns.new test-tiers.new study-options.new tools.code campaign-tools.code groups.code names.code; do
	[ -s "$DOCS_LISTS_CACHE/$f" ] || missing="$missing $f"
done
[ -z "$missing" ] && ok cache.kept || fail cache.kept "scripts/docs_lists.sh did not keep$missing in DOCS_LISTS_CACHE"

# --- broken on purpose: ID DOC SED-SCRIPT [FAILS] -> the checks FAILS (default: ID), and
# no other, must fail ---
broken() {
	local id=$1 path=$2 script=$3 want="${4:-$1} " o="$TMP/override.$1"
	mkdir -p "$o/$(dirname "$path")"
	sed "$script" "$REPO/$path" >"$o/$path"
	if cmp -s "$REPO/$path" "$o/$path"; then
		fail "broken.$id" "the sed script '$script' changed nothing in $path"
		return
	fi
	DOCS_OVERRIDE="$o" bash "$REPO/scripts/docs_lists.sh" check >"$TMP/broken.$id" 2>&1
	local rc=$? failed
	failed=$(sed -n 's/^FAIL docs_lists\.\([^:]*\):.*/\1/p' "$TMP/broken.$id" | tr '\n' ' ')
	[ "$rc" -ne 0 ] && [ "$failed" = "$want" ] && ok "broken.$id" ||
		fail "broken.$id" "after breaking $path (exit $rc) the failed checks are '$failed', expected '$want'"
}
broken scene-keys.current docs/scene.md '/^| `seed` |/d'
broken result-columns.current docs/database.md 's/^| `risen` | INTEGER |/| `risen` | REAL |/'
broken study-options.current docs/campaigns.md '/^| `--throttle K` |/d'
broken tools.docs_analysis docs/analysis.md '/^| `bin\/dumpflux` |/d'
broken tools.analysis_readme analysis/README.md 's/`bin\/convect`,/`bin\/convect`, `bin\/sweep`,/'
broken tools.fuzz_c tests/fuzz/fuzz.c 's/"convect", //'
# a second list of the tools, by hand, in a doc that had none
broken tools.no_copy docs/campaigns.md "1a The tools: $(make -s --no-print-directory -C "$REPO" print-campaign-tools)."
broken lib-files lib/README.md '/^| `km\.\[ch\]` |/d'
broken python-files python/README.md '/^| `shakebox\/mda\.py` |/d'
broken core-files core/README.md 's/^| `io\/h5id\.\[ch\]` |/| `io\/h5ident.[ch]` |/'
broken campaigns campaigns/README.md '/^| `reproduce\/q4_large\.campaign` |/d'
# a group's row dropped: its members are named nowhere either
broken run-file.groups docs/output.md '/^| `\/observables\/energy`/d' 'run-file.groups run-file.members'
broken run-file.members docs/output.md 's/`neighbour_builds`; //'
broken docs-map README.md 's#docs/cluster\.md#docs/slurm.md#g'
broken test-tiers.current docs/testing.md '/^| `study_ssh\.sh` | slow |/d'
broken fuzz-inputs docs/testing.md 's/fuzz_quick\.sh` runs \([0-9]*\) inputs/fuzz_quick.sh` runs 1\1 inputs/'
finish
