#!/usr/bin/env bash
# analysis_sql.sh - the `analysis` table answers plain SQL: the example queries of
# docs/database.md (read from that file: onset per radius ratio and depth, median
# wait per radius ratio, failed runs per group and status, failed runs and why) on a
# small campaign over two depths in which some runs fail on physics (a small
# max_overlap), checked against the tools' CSV files; the grouping keys' columns typed
# as the param table has them and NULL for keys that are not grouping keys; an
# `analysis` table of an earlier version (without those columns) given them, its rows
# kept.
# The campaigns are run by the release engine (lib.sh's data_driver_setup: the tools are
# what is tested).
# tier: slow: a campaign for the SQL examples
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
data_driver_setup
README="$REPO/docs/database.md"
cd "$TMP" || exit 1
# example TITLE: the query of docs/database.md's sql block that starts with "-- TITLE"
example() {
	awk -v t="-- $1" '/^  ```sql/ { on = 1; next } /^  ```/ { on = 0 } !on { next }
		index($0, t) == 3 { take = 1 } take && /^ *$/ { exit } take { print } take && /;$/ { exit }' "$README"
}
# col FILE GROUP NAME : the value of column NAME in the row of GROUP of a summary CSV
col() {
	awk -F, -v g="\"$2\"" -v n="$3" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == n) c = i; next }
		$1 == g && c { v = $c; gsub(/"/, "", v); print v; exit }' "$1"
}
# same A B : equal numbers (to the 15 digits sqlite3 prints), or both absent (nan / NULL)
same() {
	awk -v a="$1" -v b="$2" 'BEGIN { if (a == "nan") a = ""; if (b == "nan") b = ""
		if (a == "" || b == "") exit !(a == b); d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b
		exit !(d <= 1e-12 * (1 + m)) }'
}

# a table of an earlier version: the ten columns only, with another campaign's row
mkdir -p R
sqlite3 R/study.db "CREATE TABLE analysis(campaign TEXT NOT NULL, tool TEXT NOT NULL, version TEXT, grp TEXT NOT NULL,
	key TEXT NOT NULL, value REAL, lo REAL, hi REAL, n INTEGER, created TEXT, PRIMARY KEY (campaign, tool, grp, key));
	INSERT INTO analysis VALUES ('old', 'onset', '1', 'radius_ratio=4', 'threshold_f', 3.1, 3, 3.2, 9, '2024-01-01T00:00:00Z');"
# at 8 Hz the largest overlaps of this bed pass 0.26 of the smaller radius: those runs
# stop with status overlap (analysis_accounting.sh)
printf '[campaign]\nname = sweep\nseed = 2\nreplicates = 2\n[scene]\n'"$(tiny_scene radius_ratio=- depth=-)"'\namplitude = 1\nflux = yes\nmax_overlap = 0.26\ntraj_rate = 100\nduration = 1.5\n[grid]\nradius_ratio = 0, 2\ndepth = 1, 2\nfrequency = 4, 6, 8\n' >sweep.campaign
t0=$SECONDS
"$DATA_STUDY" run sweep.campaign --runs "$TMP/R" --jobs 2 --no-progress >study.log 2>&1
nf=$(q R/study.db "SELECT COUNT(*) FROM run WHERE campaign = 'sweep' AND state = 'failed'")
[ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE campaign = 'sweep' AND state IN ('done', 'failed')")" = 24 ] && [ "$nf" -ge 1 ] &&
	ok sql.setup.campaign || { fail sql.setup.campaign "$nf failed: $(tail -c 300 study.log)"; finish; }
echo "# campaign: $((SECONDS - t0)) s, $nf runs failed"
"$BINDIR/onset" sweep --runs R --boot 30 --no-plot >onset.out 2>onset.err &&
	"$BINDIR/waiting" sweep --runs R --no-plot >waiting.out 2>waiting.err ||
	{ fail sql.setup.tools "$(cat onset.err waiting.err)"; finish; }
A=R/sweep/analysis

# ---- the grouping keys' columns ----
cols=$(q R/study.db "SELECT name FROM pragma_table_info('analysis')" | tr '\n' ' ')
for c in radius_ratio depth width frequency amplitude n_grains; do
	case " $cols " in *" $c "*) ;; *) bad="$bad $c" ;; esac
done
[ -z "${bad:-}" ] && [ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 'old' AND value = 3.1 AND radius_ratio IS NULL")" = 1 ] &&
	ok sql.columns.migrated_old_table || fail sql.columns.migrated_old_table "columns: $cols; missing:${bad:-}"
[ "$(q R/study.db "SELECT DISTINCT typeof(radius_ratio) || ' ' || typeof(depth) || ' ' || typeof(frequency) FROM analysis
	WHERE campaign = 'sweep' AND tool = 'onset'")" = 'real integer null' ] &&
	[ "$(q R/study.db "SELECT DISTINCT typeof(radius_ratio) || ' ' || typeof(depth) || ' ' || typeof(frequency) FROM analysis
	WHERE campaign = 'sweep' AND tool = 'waiting' AND grp <> 'all groups'")" = 'real integer real' ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM analysis WHERE campaign = 'sweep' AND tool = 'onset' AND key = 'runs'
	AND grp = printf('radius_ratio=%g depth=%d', radius_ratio, depth)")" = 4 ] &&
	ok sql.columns.typed_and_null || fail sql.columns.typed_and_null "$(q R/study.db "SELECT tool, grp, typeof(radius_ratio), typeof(depth),
	typeof(frequency) FROM analysis WHERE campaign = 'sweep' AND key = 'runs'")"

# ---- onset per 𝓡 and depth ----
sqlq=$(example 'onset per 𝓡 and depth')
rows=$(q R/study.db "$sqlq")
n=0 bad=
while IFS='|' read -r ra de f lo hi nn; do
	g=$(awk -v r="$ra" -v d="$de" 'BEGIN { printf "radius_ratio=%g depth=%d", r, d }')
	same "$f" "$(col $A/onset_summary.csv "$g" threshold_f)" && same "$lo" "$(col $A/onset_summary.csv "$g" threshold_f_lo)" &&
		same "$hi" "$(col $A/onset_summary.csv "$g" threshold_f_hi)" && [ "$nn" = "$(col $A/onset_summary.csv "$g" runs)" ] ||
		bad="$bad [$g: $f $lo $hi $nn]"
	n=$((n + 1))
done <<<"$rows"
[ -n "$sqlq" ] && [ "$n" = 4 ] && [ -z "$bad" ] && ok sql.example.onset_per_ratio_and_depth ||
	fail sql.example.onset_per_ratio_and_depth "query '$sqlq': $n rows, differ:$bad"

# ---- median wait per 𝓡 ----
sqlq=$(example 'median wait per 𝓡')
rows=$(q R/study.db "$sqlq")
n=0 bad=
while IFS='|' read -r ra de fr med lo hi nn; do
	g=$(awk -v r="$ra" -v d="$de" -v f="$fr" 'BEGIN { printf "radius_ratio=%g depth=%d frequency=%g", r, d, f }')
	same "$med" "$(col $A/waiting_summary.csv "$g" median)" && same "$lo" "$(col $A/waiting_summary.csv "$g" median_lo)" &&
		same "$hi" "$(col $A/waiting_summary.csv "$g" median_hi)" && [ "$nn" = "$(col $A/waiting_summary.csv "$g" runs)" ] ||
		bad="$bad [$g: $med $lo $hi $nn]"
	n=$((n + 1))
done <<<"$rows"
[ -n "$sqlq" ] && [ "$n" = 6 ] && [ -z "$bad" ] && ok sql.example.median_wait_per_ratio ||
	fail sql.example.median_wait_per_ratio "query '$sqlq': $n rows, differ:$bad"

# ---- failed runs per group and status ----
sqlq=$(example 'failed runs per group and status')
# from the summary: runs_failed and failed_by_status ("overlap=3;usage=1") per group
want=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i == "runs_failed") c = i; if ($i == "failed_by_status") s = i }; next }
	{ g = $1; gsub(/"/, "", g); split(g, kv, /[= ]/); if ($c > 0) printf "%g|%d|runs_failed|%d\n", kv[2], kv[4], $c
	  v = $s; gsub(/"/, "", v); n = split(v, p, ";"); for (i = 1; i <= n; i++) if (p[i] != "-") { split(p[i], q, "=")
	  printf "%g|%d|failed_%s|%d\n", kv[2], kv[4], q[1], q[2] } }' $A/onset_summary.csv | sort)
got=$(q R/study.db "$sqlq" | awk -F'|' '{ printf "%g|%d|%s|%d\n", $1, $2, $3, $4 }' | sort)
[ -n "$sqlq" ] && [ -n "$want" ] && [ "$got" = "$want" ] && ok sql.example.failed_per_group ||
	fail sql.example.failed_per_group "query '$sqlq': got '$got', summary '$want'"

# ---- failed runs and why ----
sqlq=$(example 'failed runs and why')
got=$(q R/study.db "$sqlq" | awk -F'|' '{ print $1, $3 }' | sort)
want=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i == "run") r = i; if ($i == "state") s = i; if ($i == "status") t = i }; next }
	{ x = $s; gsub(/"/, "", x); if (x == "failed") { id = $r; st = $t; gsub(/"/, "", id); gsub(/"/, "", st); print id, st } }' \
	$A/onset_accounting.csv | sort)
whyok=$(q R/study.db "$sqlq" | awk -F'|' '$5 == "" { bad = 1 } END { print bad ? 0 : 1 }')
[ -n "$sqlq" ] && [ "$(echo "$got" | wc -l)" = "$nf" ] && [ "$got" = "$want" ] && [ "$whyok" = 1 ] &&
	ok sql.example.failed_runs_and_why || fail sql.example.failed_runs_and_why "query '$sqlq': got '$got', accounting '$want'"
echo "# total: $((SECONDS - t0)) s"
finish
