#!/usr/bin/env bash
# analysis_defs.sh - stored results keep their definition (docs/database.md, "Derived
# numbers"): on a tiny campaign (no intruder, three frequencies, two seeds), bin/onset
# twice with the same options (given in other forms) leaves one definition and the
# same rows; with another threshold it adds a definition and its rows, both
# retrievable with their options, the view `analysis` showing the newest; the `runs`
# view and `study export` carry each run's Phi and its class (on past the group's
# threshold, off before it), checked against onset_runs.csv and an awk classification
# in both directions; a database of an earlier version (an `analysis` table, no
# definitions) opens in bin/study and in bin/onset, its rows kept.
# tier: slow: a campaign for the definitions
. "$(dirname "$0")/lib.sh"
analysis_tools_setup
cd "$TMP" || exit 1
# same A B : equal numbers to 12 digits, or both absent (nan / NULL)
same() {
	awk -v a="$1" -v b="$2" 'BEGIN { if (a == "nan") a = ""; if (b == "nan") b = ""
		if (a == "" || b == "") exit !(a == b); d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b
		exit !(d <= 1e-12 * (1 + m)) }'
}
# onset OUT ARGS... : bin/onset on campaign t into OUT (stdout, stderr in OUT.out, OUT.err)
onset() {
	local out=$1
	shift
	"$BINDIR/onset" t --runs R --out "$TMP/$out" --no-plot "$@" >"$out.out" 2>"$out.err"
}
# classes OUT [THRESHOLD] : "run phi class" per run of OUT/onset_runs.csv, the class by
# the threshold (default: halfway between the smallest and largest mean Phi per
# frequency), on at or past it in the direction the means rise
classes() {
	awk -F, -v thr="${2:-}" 'NR > 1 { run[NR] = $3; f[NR] = $8; phi[NR] = $9; s[$8] += $9; c[$8]++ }
		END { n = 0; for (x in s) { m[x] = s[x] / c[x]; xs[++n] = x + 0 }
			for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (xs[j] < xs[i]) { t = xs[i]; xs[i] = xs[j]; xs[j] = t }
			lo = hi = m[xs[1]]; for (i = 2; i <= n; i++) { v = m[xs[i]]; if (v < lo) lo = v; if (v > hi) hi = v }
			if (thr == "") thr = (lo + hi) / 2; rise = m[xs[n]] >= m[xs[1]]
			for (k in run) print run[k], phi[k], ((rise ? phi[k] >= thr : phi[k] <= thr) ? "on" : "off") }' "$1/onset_runs.csv" | sort
}

printf '[campaign]\nname = t\nseed = 3\nreplicates = 2\n[scene]\n'"$(tiny_scene radius_ratio=-)"'\namplitude = 1\nflux = yes\nduration = 1\n[grid]\nradius_ratio = 0\nfrequency = 3, 5, 7\n' >t.campaign
# made by the release engine (lib.sh's data_driver_setup): the definitions the tools
# store are under test, not the engine; the driver under test opens the databases below
data_driver_setup
t0=$SECONDS
"$DATA_STUDY" run t.campaign --runs "$TMP/R" --jobs 2 --no-progress >study.log 2>&1
[ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'")" = 6 ] && ok defs.setup.campaign ||
	{ fail defs.setup.campaign "$(tail -c 300 study.log)"; finish; }
echo "# campaign: $((SECONDS - t0)) s"
# an earlier version's database: the campaign before any definition was recorded (the
# tables the tools and the driver add now dropped, an `analysis` table of that version
# with a row of another campaign, the runs view as it was without the observables)
cp R/study.db old.db
q old.db "DROP VIEW analysis; DROP TABLE analysis_all; DROP TABLE analysis_def; DROP TABLE analysis_run;
	DROP VIEW runs; CREATE VIEW runs AS SELECT r.campaign, r.id, r.state FROM run r;
	CREATE TABLE analysis(campaign TEXT NOT NULL, tool TEXT NOT NULL, version TEXT, grp TEXT NOT NULL,
	key TEXT NOT NULL, value REAL, lo REAL, hi REAL, n INTEGER, created TEXT, radius_ratio, PRIMARY KEY (campaign, tool, grp, key));
	INSERT INTO analysis VALUES ('old', 'onset', '1', 'radius_ratio=4', 'threshold_f', 3.1, 3, 3.2, 9, '2024-01-01T00:00:00Z', 4)"

# ---- (a) the same options twice: one definition, the same rows ----
onset a1 --boot 30 --seed 5 || fail defs.same.exit "$(cat a1.err)"
snap() { q R/study.db "SELECT (SELECT COUNT(*) FROM analysis_def) || ' ' || (SELECT COUNT(*) FROM analysis_all) || ' ' ||
	(SELECT COUNT(*) FROM analysis_run) || ' ' || (SELECT group_concat(options, ';') FROM analysis_def)"; }
s1=$(snap)
rows1=$(q R/study.db "SELECT grp, key, value, lo, hi, n FROM analysis_all ORDER BY grp, key")
# the same definition in other forms: --opt=value, another order, a default given
onset a2 --seed=5 --band 0.4:0.6 --boot=30 --skip 0.20 || fail defs.same.exit "$(cat a2.err)"
s2=$(snap)
rows2=$(q R/study.db "SELECT grp, key, value, lo, hi, n FROM analysis_all ORDER BY grp, key")
[ "${s1%% *}" = 1 ] && [ "$s1" = "$s2" ] && [ "$rows1" = "$rows2" ] && [ "$(echo "$s1" | cut -d' ' -f3)" = 6 ] &&
	ok defs.same_options.replaced || fail defs.same_options.replaced "before: $s1; after: $s2"
case "$s2" in *'band=0.4:0.6 skip=0.2 threshold=halfway boot=30 seed=5 level=0.95'*) ok defs.options.canonical ;;
*) fail defs.options.canonical "$s2" ;; esac
# the tool's version as its rows carry it, the build as the engine's run files name it
[ "$(q R/study.db "SELECT COUNT(*) FROM analysis_def d WHERE d.version = (SELECT DISTINCT version FROM analysis_all)
	AND d.build = (SELECT DISTINCT 'shakebox ' || git_hash FROM runs)")" = 1 ] &&
	ok defs.versions_recorded || fail defs.versions_recorded "$(q R/study.db "SELECT version, build FROM analysis_def")"

# ---- (b) other options: rows added, each set with its options ----
onset b --seed=5 --boot 30 --threshold 0.3 || fail defs.other.exit "$(cat b.err)"
nd=$(q R/study.db "SELECT COUNT(*) FROM analysis_def WHERE campaign = 't' AND tool = 'onset'")
na=$(q R/study.db "SELECT COUNT(*) FROM analysis_all")
n1=$(echo "$s1" | cut -d' ' -f2)
[ "$nd" = 2 ] && [ "$na" = $((2 * n1)) ] && [ "$(q R/study.db "SELECT COUNT(*) FROM analysis")" = "$n1" ] &&
	ok defs.other_options.added || fail defs.other_options.added "$nd definitions, $na rows (one set: $n1)"
# each definition's threshold_f is its own run's summary; the view shows the newest
thr_of() { q R/study.db "SELECT a.value FROM analysis_all a JOIN analysis_def d ON d.id = a.def
	WHERE a.key = 'threshold_f' AND d.options LIKE '%threshold=$1 %'"; }
csv_thr() { awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "threshold_f") c = i; next } { print $c; exit }' "$1/onset_summary.csv"; }
same "$(thr_of halfway)" "$(csv_thr a2)" && same "$(thr_of 0.3)" "$(csv_thr b)" &&
	same "$(q R/study.db "SELECT value FROM analysis WHERE key = 'threshold_f'")" "$(csv_thr b)" &&
	! same "$(csv_thr a2)" "$(csv_thr b)" && ok defs.other_options.both_retrievable ||
	fail defs.other_options.both_retrievable "halfway: $(thr_of halfway) vs $(csv_thr a2); 0.3: $(thr_of 0.3) vs $(csv_thr b)"

# docs/database.md's example: every definition's onset with its options, newest first
sqlq=$(awk -v t="-- onset by every definition stored" '/^  ```sql/ { on = 1; next } /^  ```/ { on = 0 } !on { next }
	index($0, t) == 3 { take = 1 } take && /^ *$/ { exit } take { print } take && /;$/ { exit }' "$REPO/docs/database.md")
got=$(q R/study.db "$sqlq" | awk -F'|' '{ print $2 "|" $4 }')
[ -n "$sqlq" ] && [ "$(echo "$got" | wc -l)" = 2 ] && case "$(echo "$got" | head -n 1)" in *threshold=0.3*) true ;; *) false ;; esac &&
	same "$(echo "$got" | head -n 1 | cut -d'|' -f2)" "$(csv_thr b)" && same "$(echo "$got" | tail -n 1 | cut -d'|' -f2)" "$(csv_thr a2)" &&
	ok defs.example.every_definition || fail defs.example.every_definition "query '$sqlq': '$got'"

# ---- (c) the runs view and the export: Phi and class per run ----
check_runs() { # ID OUT [THRESHOLD]: the latest definition's per-run rows against OUT's CSV
	local want got
	want=$(classes "$2" "${3:-}")
	got=$(q R/study.db "SELECT id, onset_phi, onset_phi_class FROM runs WHERE campaign = 't'" | tr '|' ' ' | sort)
	local bad
	bad=$(paste -d' ' <(echo "$want") <(echo "$got") | awk '$1 != $4 || $3 != $6 { print; next }
		{ d = $2 - $5; if (d < 0) d = -d; if (d > 1e-12 * (1 + ($2 < 0 ? -$2 : $2))) print }')
	[ -n "$want" ] && [ "$(echo "$want" | wc -l)" = 6 ] && [ -z "$bad" ] && echo "$want" | grep -q ' on$' &&
		echo "$want" | grep -q ' off$' && ok "$1" || fail "$1" "want '$want', got '$got'"
}
check_runs defs.runs_view.threshold_given b 0.3
"$STUDY" export t --runs "$TMP/R" >export.csv 2>export.err
hdr=$(head -n 1 export.csv)
ci=$(echo "$hdr" | tr ',' '\n' | grep -nx 'id' | cut -d: -f1)
pi=$(echo "$hdr" | tr ',' '\n' | grep -nx 'onset_phi' | cut -d: -f1)
ki=$(echo "$hdr" | tr ',' '\n' | grep -nx 'onset_phi_class' | cut -d: -f1)
got=$(awk -F, -v c="${ci:-0}" -v p="${pi:-0}" -v k="${ki:-0}" 'NR > 1 && p && k { print $c, $p, $k }' export.csv | sort)
bad=$(paste -d' ' <(classes b 0.3) <(echo "$got") | awk '$1 != $4 || $3 != $6 { print; next }
	{ d = $2 - $5; if (d < 0) d = -d; if (d > 1e-12 * (1 + ($2 < 0 ? -$2 : $2))) print }')
[ -n "$pi" ] && [ -n "$ki" ] && [ "$(echo "$got" | wc -l)" = 6 ] && [ -z "$bad" ] && ok defs.export.phi_and_class ||
	fail defs.export.phi_and_class "header '$hdr'; rows '$got'; differ: $bad"
# the first definition again: it becomes the newest, its classes by the halfway level
onset a3 --seed=5 --boot 30 || fail defs.rerun.exit "$(cat a3.err)"
newest=$(q R/study.db "SELECT options FROM analysis_def ORDER BY id DESC LIMIT 1")
[ "$(q R/study.db "SELECT COUNT(*) FROM analysis_def")" = 2 ] && case "$newest" in *threshold=halfway*) true ;; *) false ;; esac &&
	ok defs.rerun.newest || fail defs.rerun.newest "$(q R/study.db "SELECT * FROM analysis_def")"
check_runs defs.runs_view.threshold_halfway a3
# --no-store writes nothing
before=$(q R/study.db "SELECT group_concat(id) FROM analysis_def")
onset n --seed=5 --boot 30 --threshold 0.1 --no-store
[ "$(q R/study.db "SELECT group_concat(id) FROM analysis_def")" = "$before" ] && ok defs.no_store || fail defs.no_store "$(q R/study.db "SELECT * FROM analysis_def")"

# ---- (d) a database of an earlier version ----
# read-only first (nothing migrated), then bin/study (migrates when it opens it to write)
"$BINDIR/onset" t --db old.db --runs R --out "$TMP/od" --no-plot --no-store --boot 30 >od.out 2>od.err &&
	[ "$(q old.db "SELECT type FROM sqlite_master WHERE name = 'analysis'")" = table ] && ok defs.old.read_only ||
	fail defs.old.read_only "$(cat od.err)"
"$STUDY" run t.campaign --db "$TMP/old.db" --runs "$TMP/R" --no-progress >old_study.log 2>&1
rc=$?
[ "$rc" = 0 ] && [ "$(q old.db "SELECT type FROM sqlite_master WHERE name = 'analysis'")" = view ] &&
	[ "$(q old.db "SELECT value || ' ' || radius_ratio || ' ' || typeof(d.options) FROM analysis a JOIN analysis_def d ON d.id = a.def
		WHERE a.campaign = 'old'")" = '3.1 4 null' ] && [ "$(q old.db "SELECT COUNT(*) FROM runs WHERE frequency = 5")" = 2 ] &&
	ok defs.old.study_migrates || fail defs.old.study_migrates "exit $rc: $(tail -c 300 old_study.log)"
"$BINDIR/onset" t --db old.db --runs R --out "$TMP/od2" --no-plot --boot 30 >od2.out 2>od2.err &&
	[ "$(q old.db "SELECT COUNT(*) FROM analysis WHERE campaign = 'old'")" = 1 ] &&
	[ "$(q old.db "SELECT COUNT(*) FROM analysis WHERE campaign = 't' AND key = 'threshold_f'")" = 1 ] &&
	[ "$(q old.db "SELECT COUNT(onset_phi_class) FROM runs WHERE campaign = 't'")" = 6 ] &&
	ok defs.old.tool_stores || fail defs.old.tool_stores "$(cat od2.err)"
# a result table of an earlier driver (a result column fewer): after a tool stores, the
# runs view still answers (it is rebuilt when the driver brings the table up to date)
cp R/study.db oldres.db
col=steps
q oldres.db "DROP VIEW runs; ALTER TABLE result DROP COLUMN $col;
	CREATE VIEW runs AS SELECT r.campaign, r.id, r.state, s.risen FROM run r LEFT JOIN result s ON s.run = r.id"
"$BINDIR/onset" t --db oldres.db --runs R --out "$TMP/or" --no-plot --boot 30 >or.out 2>or.err &&
	[ "$(q oldres.db "SELECT COUNT(*) FROM runs WHERE campaign = 't'" 2>&1)" = 6 ] &&
	[ "$(q oldres.db "SELECT COUNT(*) FROM analysis WHERE campaign = 't' AND key = 'threshold_f'")" = 1 ] &&
	ok defs.old_result.view_answers || fail defs.old_result.view_answers "$col: $(cat or.err; q oldres.db "SELECT COUNT(*) FROM runs" 2>&1)"
"$STUDY" run t.campaign --db "$TMP/oldres.db" --runs "$TMP/R" --no-progress >oldres_study.log 2>&1
[ "$(q oldres.db "SELECT COUNT($col) FROM runs WHERE campaign = 't'" 2>&1)" = 6 ] &&
	ok defs.old_result.driver_updates || fail defs.old_result.driver_updates "$(tail -c 300 oldres_study.log)"
# an old table that no driver opened: the tool migrates it itself
cp R/study.db raw.db
q raw.db "DROP VIEW analysis; DROP TABLE analysis_all; DROP TABLE analysis_def; DROP TABLE analysis_run;
	CREATE TABLE analysis(campaign TEXT NOT NULL, tool TEXT NOT NULL, version TEXT, grp TEXT NOT NULL,
	key TEXT NOT NULL, value REAL, lo REAL, hi REAL, n INTEGER, created TEXT, PRIMARY KEY (campaign, tool, grp, key));
	INSERT INTO analysis VALUES ('t', 'onset', '1', 'all', 'threshold_f', 9, NULL, NULL, 1, '2024-01-01T00:00:00Z')"
"$BINDIR/onset" t --db raw.db --runs R --out "$TMP/rd" --no-plot --boot 30 >rd.out 2>rd.err &&
	[ "$(q raw.db "SELECT COUNT(*) || ' ' || COUNT(options) FROM analysis_def")" = '2 1' ] &&
	[ "$(q raw.db "SELECT COUNT(*) FROM analysis_all WHERE value = 9")" = 1 ] &&
	[ "$(q raw.db "SELECT COUNT(*) FROM analysis WHERE value = 9")" = 0 ] &&
	ok defs.old.tool_migrates || fail defs.old.tool_migrates "$(cat rd.err; q raw.db "SELECT * FROM analysis_def")"
echo "# total: $((SECONDS - t0)) s"
finish
