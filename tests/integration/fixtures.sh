#!/usr/bin/env bash
# fixtures.sh - the integration scripts share one fixture layer (lib.sh): one query helper
# q DB SQL, the tiny bed spelt once (TINY_BED, tiny_bed, tiny_scene, tiny_campaign) and
# campaigns built once per build (fixture_runs). Fails when a script defines its own q()
# again or spells the tiny bed's settling by hand; the checker is tried on planted
# scripts first. Then lib.sh's helpers on known answers: the bed with keys changed,
# left out and added, and a fixture run once, copied after, built anew for other bits,
# and never kept when its campaign failed (a stand-in driver counts its runs).
. "$(dirname "$0")/lib.sh"
IT="$REPO/tests/integration"
cd "$TMP" || exit 1

# offenders DIR : "FILE:LINE: WHAT" for every script of DIR but lib.sh that defines a
# function q or spells the tiny bed's settling (settle_min 0.2, in a scene file's or a
# command line's spelling)
offenders() {
	grep -nE '^[[:space:]]*(function[[:space:]]+)?q[[:space:]]*\(\)' "$1"/*.sh | grep -v "^$1/lib.sh:" |
		sed "s|^$1/||; s|\$| (its own q(); lib.sh has q DB SQL)|"
	grep -nE 'settle_min[[:space:]]*=[[:space:]]*0?\.2([^0-9.]|$)' "$1"/*.sh | grep -v "^$1/lib.sh:" |
		sed "s|^$1/||; s|\$| (the tiny bed by hand; lib.sh has tiny_bed, tiny_scene, tiny_campaign)|"
}

# --- the checker, on planted scripts (the words built here, so that this file has none) ---
P=$TMP/planted
mkdir -p "$P"
qdef='q() { sqlite3 -batch "$1" "$2"; }'
sm=settle_min
printf '%s\n' '. lib.sh' "$qdef" 'ok x' >"$P/own_q.sh"
printf '%s\n' '. lib.sh' "	function $qdef" >"$P/own_q_function.sh"
printf '%s\n' 'cat >c.campaign <<EOF' '[scene]' 'n_grains = 40' "$sm = 0.2" 'EOF' >"$P/bed_ini.sh"
printf '%s\n' '"$SHAKE" n_grains=60 width=20 settle_ke=1 '"$sm=0.2"' duration=1' >"$P/bed_cmdline.sh"
printf '%s\n' 'q "$DB" "SELECT 1"' "tiny_scene $sm=0.25" "echo $sm = 0.2.5x" "tiny_bed $sm=1" >"$P/clean.sh"
printf '%s\n' "$qdef" "$sm = 0.2" >"$P/lib.sh"
got=$(offenders "$P" | cut -d: -f1,2 | sort | tr '\n' ' ')
[ "$got" = "bed_cmdline.sh:1 bed_ini.sh:4 own_q.sh:2 own_q_function.sh:2 " ] && ok fixtures.selftest.planted_found ||
	fail fixtures.selftest.planted_found "found '$got', want the four planted ones (not clean.sh, not lib.sh)"

# --- the scripts ---
offenders "$IT" >offenders.txt
bad=$(grep -F '(its own q()' offenders.txt)
[ -z "$bad" ] && ok fixtures.one_q || fail fixtures.one_q "$bad"
bad=$(grep -F '(the tiny bed by hand' offenders.txt)
[ -z "$bad" ] && ok fixtures.tiny_bed_spelt_once || fail fixtures.tiny_bed_spelt_once "$bad"

# --- the bed's helpers, on known answers ---
got=$(tiny_scene n_grains=40 depth=- radius_ratio=0 flux=yes | tr '\n' '|')
[ "$got" = "n_grains = 40|width = 20|radius_ratio = 0|settle_ke = 1|$sm = 0.2|flux = yes|" ] &&
	ok fixtures.tiny_scene.overrides || fail fixtures.tiny_scene.overrides "'$got'"
tiny_bed width=15 x=- y=2
[ "${BEDARGS[*]}" = "n_grains=60 width=15 radius_ratio=2 depth=1 settle_ke=1 $sm=0.2 y=2" ] &&
	[ "${FAST[*]:0:${#TINY_BED[@]}}" = "${TINY_BED[*]}" ] && ok fixtures.tiny_bed.words ||
	fail fixtures.tiny_bed.words "'${BEDARGS[*]}'; FAST '${FAST[*]}'"
got=$(tiny_campaign c 7 'flux = yes' | tr '\n' '|')
[ "$got" = "[campaign]|name = c|seed = 7|replicates = 2|[scene]|n_grains = 40|width = 16|radius_ratio = 2|depth = 1|settle_ke = 1|$sm = 0.2|duration = 0.2|traj_rate = 100|snapshots = no|flux = yes|[grid]|frequency = 4, 5|" ] &&
	ok fixtures.tiny_campaign.text || fail fixtures.tiny_campaign.text "'$got'"
tiny_campaign c >c.campaign
[ "$(sed -n 's/^seed = //p' c.campaign)" = 5 ] && ok fixtures.tiny_campaign.default_seed ||
	fail fixtures.tiny_campaign.default_seed "$(head -n 3 c.campaign | tr '\n' '|')"

# --- fixture_runs, with a stand-in driver that counts its runs and writes a database ---
export FIXTURES=$TMP/fixtures
mkdir -p fake
cat >fake/study <<EOF
#!/usr/bin/env bash
# run CAMPAIGN --runs DIR ...
echo run >>"$TMP/fake/calls"
grep -q '^name = broken' "\$2" && { echo "stand-in: campaign broken" >&2; exit 3; }
mkdir -p "\$4/c" && sqlite3 "\$4/study.db" "CREATE TABLE run(id TEXT); INSERT INTO run VALUES ('r1')" &&
	echo "stand-in: 1 done" && echo "\$PWD" >"\$4/c/where"
EOF
printf '#!/bin/sh\n# the engine beside it\n' >fake/shake
chmod +x fake/study fake/shake
calls() { wc -l <fake/calls 2>/dev/null || echo 0; }
tiny_campaign c >c.campaign
fixture_runs c.campaign A fake/study
rc=$?
[ "$rc" = 0 ] && [ "$(calls)" -eq 1 ] && [ "$(q A/study.db "SELECT id FROM run")" = r1 ] && grep -q '1 done' A.log &&
	ok fixtures.runs.built || fail fixtures.runs.built "exit $rc, $(calls) runs: $(cat A.log 2>&1)"
# built in the cache, not in the caller's directory
case $(cat A/c/where 2>/dev/null) in "$FIXTURES"/*) ok fixtures.runs.built_in_cache ;; *) fail fixtures.runs.built_in_cache "ran in '$(cat A/c/where 2>&1)'" ;; esac
fixture_runs c.campaign B fake/study
rc=$?
[ "$rc" = 0 ] && [ "$(calls)" -eq 1 ] && [ "$(q B/study.db "SELECT id FROM run")" = r1 ] &&
	ok fixtures.runs.copied_once_built || fail fixtures.runs.copied_once_built "exit $rc, $(calls) runs"
# a copy is the caller's own: changing it leaves the cache as it was
q B/study.db "DELETE FROM run"
fixture_runs c.campaign C fake/study
[ "$(q C/study.db "SELECT id FROM run")" = r1 ] && ok fixtures.runs.copy_is_own || fail fixtures.runs.copy_is_own "the cache changed with a copy"
# other bits of the engine beside the driver, or another campaign text: built anew
echo '# another build' >>fake/shake
fixture_runs c.campaign D fake/study
[ "$(calls)" -eq 2 ] && ok fixtures.runs.new_engine_new_build || fail fixtures.runs.new_engine_new_build "$(calls) runs, want 2"
tiny_campaign c 6 >c.campaign
fixture_runs c.campaign E fake/study
[ "$(calls)" -eq 3 ] && ok fixtures.runs.new_text_new_build || fail fixtures.runs.new_text_new_build "$(calls) runs, want 3"
# a campaign that did not end well: its exit code and log, nothing kept
tiny_campaign broken >b.campaign
fixture_runs b.campaign F fake/study
rc=$?
fixture_runs b.campaign G fake/study
rc2=$?
[ "$rc" = 3 ] && [ "$rc2" = 3 ] && [ "$(calls)" -eq 5 ] && grep -q 'campaign broken' F.log && [ ! -e F ] &&
	[ -z "$(ls "$FIXTURES" | grep '^b.campaign')" ] && ok fixtures.runs.failure_not_kept ||
	fail fixtures.runs.failure_not_kept "exit $rc, $rc2, $(calls) runs: $(cat F.log 2>&1); $(ls -a "$FIXTURES")"
finish
