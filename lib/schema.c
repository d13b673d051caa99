/* schema.c - every table and view of the study database (schema.h). The tables are
 * documented in docs/database.md ("Schema", "Derived numbers"). */
#include "schema.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drive.h"
#include "params.h"
#include "ratio.h"
#include "results.h"

/* The runs view's columns of the drive's derived axes (docs/database.md), by axis. */
static const char *const VIEW_AXES[AXIS_N] = {[AXIS_GAMMA] = "gamma", [AXIS_VELOCITY] = "v_box"};

int schema_view_axis(const char *column)
{
	for (int k = 0; k < AXIS_N; k++)
		if (VIEW_AXES[k] && !strcmp(VIEW_AXES[k], column))
			return k;
	return -1;
}

/* The driver's tables and views (bin/study run). */
static const char STUDY[] =
	"CREATE TABLE IF NOT EXISTS campaign(\n"
	"  name TEXT PRIMARY KEY, description TEXT, file TEXT, scene_file TEXT,\n"
	"  seed TEXT, seeds TEXT, axes TEXT, created TEXT, updated TEXT,\n"
	"  version INTEGER NOT NULL DEFAULT 1);\n"
	"CREATE TABLE IF NOT EXISTS run(\n"
	"  campaign TEXT NOT NULL, id TEXT NOT NULL, replicate INTEGER, seed INTEGER,\n"
	"  cache_key TEXT, state TEXT NOT NULL DEFAULT 'pending'\n"
	"    CHECK (state IN ('pending', 'running', 'done', 'failed')),\n"
	"  attempts INTEGER NOT NULL DEFAULT 0, from_cache INTEGER NOT NULL DEFAULT 0,\n"
	"  host TEXT, added TEXT, started TEXT, finished TEXT,\n"
	"  current INTEGER NOT NULL DEFAULT 1,\n"
	"  PRIMARY KEY (campaign, id));\n"
	"CREATE TABLE IF NOT EXISTS param(\n"
	"  campaign TEXT NOT NULL, run TEXT NOT NULL, key TEXT NOT NULL, value,\n"
	"  PRIMARY KEY (campaign, run, key)) WITHOUT ROWID;\n"
	"CREATE TABLE IF NOT EXISTS attempt(\n"
	"  campaign TEXT NOT NULL, run TEXT NOT NULL, n INTEGER NOT NULL, host TEXT,\n"
	"  exit_code INTEGER, status TEXT, message TEXT, finished TEXT, wall_seconds REAL,\n"
	"  PRIMARY KEY (campaign, run, n));\n"
	"CREATE TABLE IF NOT EXISTS cache(\n"
	"  campaign TEXT NOT NULL, key TEXT NOT NULL, state TEXT, settle_time REAL,\n"
	"  settle_steps INTEGER, wall_seconds REAL, host TEXT, message TEXT, built TEXT,\n"
	"  PRIMARY KEY (campaign, key));\n"
	"CREATE INDEX IF NOT EXISTS run_state ON run(campaign, state);\n"
	/* an [onset] campaign's search, as the driver's last pass left it (search.c) */
	"CREATE TABLE IF NOT EXISTS onset_search(\n"
	"  campaign TEXT PRIMARY KEY, observable TEXT, axis TEXT, freq_from REAL, freq_to REAL, tolerance REAL,\n"
	"  threshold REAL, band_lo REAL, band_hi REAL, skip REAL, replicates TEXT, max_replicates INTEGER,\n"
	"  batch INTEGER, target REAL, level REAL, state TEXT, updated TEXT);\n"
	"CREATE TABLE IF NOT EXISTS onset_group(\n"
	"  campaign TEXT NOT NULL, grp TEXT NOT NULL, point INTEGER, replicates INTEGER, searching INTEGER,\n"
	"  found INTEGER, below INTEGER, above INTEGER, blocked INTEGER, nonmonotone INTEGER, runs INTEGER,\n"
	"  estimate REAL, ci_lo REAL, ci_hi REAL, width REAL, state TEXT, reason TEXT, PRIMARY KEY (campaign, grp));\n"
	"CREATE TABLE IF NOT EXISTS onset_replicate(\n"
	"  campaign TEXT NOT NULL, grp TEXT NOT NULL, replicate INTEGER NOT NULL, state TEXT, lo REAL, hi REAL,\n"
	"  lo_run INTEGER, hi_run INTEGER, next REAL, runs INTEGER, nonmonotone INTEGER,\n"
	"  PRIMARY KEY (campaign, grp, replicate));\n"
	"CREATE TABLE IF NOT EXISTS onset_run(\n"
	"  campaign TEXT NOT NULL, run TEXT NOT NULL, grp TEXT, replicate INTEGER, step INTEGER,\n"
	"  axis_value REAL, frequency REAL, value REAL, class TEXT, PRIMARY KEY (campaign, run));\n"
	/* a grid with replicates = auto, per point, as the driver's last pass left it
	 * (sharpen.c) */
	"CREATE TABLE IF NOT EXISTS auto_point(\n"
	"  campaign TEXT NOT NULL, point INTEGER NOT NULL, grp TEXT, result TEXT, replicates INTEGER,\n"
	"  used INTEGER, waiting INTEGER, failed INTEGER, estimate REAL, ci_lo REAL, ci_hi REAL, width REAL,\n"
	"  target REAL, level REAL, batch INTEGER, max_replicates INTEGER, state TEXT, updated TEXT,\n"
	"  PRIMARY KEY (campaign, point));\n"
	"DROP VIEW IF EXISTS progress;\n"
	"CREATE VIEW progress AS SELECT campaign, state, COUNT(*) AS runs FROM run GROUP BY campaign, state;\n"
	"DROP VIEW IF EXISTS failures;\n"
	"CREATE VIEW failures AS SELECT a.campaign, a.run, a.n AS attempt, a.exit_code, a.status,\n"
	"  a.message, a.host, a.finished, r.state FROM attempt a JOIN run r\n"
	"  ON r.campaign = a.campaign AND r.id = a.run WHERE a.status <> 'ok';\n"
	"DROP VIEW IF EXISTS caches;\n"
	"CREATE VIEW caches AS SELECT c.*, (SELECT COUNT(*) FROM run r WHERE r.campaign = c.campaign\n"
	"  AND r.cache_key = c.key AND r.from_cache) AS hits FROM cache c;\n";

/* The Slurm arrays of `study submit --slurm` (study/slurm/). */
static const char SLURM[] =
	/* one row per submitted array */
	"CREATE TABLE IF NOT EXISTS slurm_job(\n"
	"  campaign TEXT NOT NULL, job_id INTEGER NOT NULL, array TEXT, tasks INTEGER, runs INTEGER,\n"
	"  runs_per_task INTEGER, throttle INTEGER, sbatch_args TEXT, script TEXT, task_file TEXT,\n"
	"  campaign_file TEXT, dir TEXT, submitted TEXT, PRIMARY KEY (campaign, job_id));\n"
	/* one row per run per array it was submitted in; attempt: the attempt (attempt.n)
	 * the task made of the run, once known */
	"CREATE TABLE IF NOT EXISTS slurm_task(\n"
	"  campaign TEXT NOT NULL, run TEXT NOT NULL, job_id INTEGER NOT NULL, array_index INTEGER NOT NULL,\n"
	"  attempt INTEGER, state TEXT NOT NULL DEFAULT 'submitted'\n"
	"    CHECK (state IN ('submitted', 'started', 'ended', 'unstarted')),\n"
	"  host TEXT, submitted TEXT, PRIMARY KEY (campaign, run, job_id));\n"
	"CREATE INDEX IF NOT EXISTS slurm_task_open ON slurm_task(campaign, state);\n";

/* The analysis tools' derived numbers (docs/database.md, "Derived numbers"). A
 * definition is one tool's invocation on a campaign: its options in canonical form, the
 * tool's version and the build; every number it stores points at it, so that a rerun
 * with other options adds rows beside the earlier ones, and one with the same options
 * replaces its own (analysis/common/adb.c). `analysis` shows each tool's latest
 * definition, the one most queries want; each tool adds a column to analysis_all per
 * grouping key it stores. An id is never reused (AUTOINCREMENT): a rerun's definition
 * is the newest even when it replaces the newest. */
static const char ANALYSIS[] =
	"CREATE TABLE IF NOT EXISTS analysis_def(\n"
	"  id INTEGER PRIMARY KEY AUTOINCREMENT, campaign TEXT NOT NULL, tool TEXT NOT NULL, version TEXT,\n"
	"  options TEXT, build TEXT, created TEXT);\n"
	"CREATE INDEX IF NOT EXISTS analysis_def_tool ON analysis_def(campaign, tool);\n"
	"CREATE TABLE IF NOT EXISTS analysis_all(\n"
	"  campaign TEXT NOT NULL, tool TEXT NOT NULL, version TEXT, grp TEXT NOT NULL,\n"
	"  key TEXT NOT NULL, value REAL, lo REAL, hi REAL, n INTEGER, created TEXT, def INTEGER NOT NULL,\n"
	"  PRIMARY KEY (campaign, tool, def, grp, key));\n"
	/* the observable a tool computed for each run, and the run's class by it */
	"CREATE TABLE IF NOT EXISTS analysis_run(\n"
	"  def INTEGER NOT NULL, campaign TEXT NOT NULL, tool TEXT NOT NULL, run TEXT NOT NULL, key TEXT NOT NULL,\n"
	"  value REAL, class TEXT, PRIMARY KEY (def, run, key));\n"
	"CREATE INDEX IF NOT EXISTS analysis_run_run ON analysis_run(campaign, run)";
static const char ANALYSIS_VIEW[] =
	"CREATE VIEW IF NOT EXISTS analysis AS SELECT a.* FROM analysis_all a WHERE a.def =\n"
	"  (SELECT MAX(d.id) FROM analysis_def d WHERE d.campaign = a.campaign AND d.tool = a.tool)";

/* The fixed columns of analysis_all (ANALYSIS) that an `analysis` table of an earlier
 * version has too; its other columns are grouping keys. */
static const char *const AN_FIXED[] = {"campaign", "tool", "version", "grp", "key", "value", "lo", "hi", "n",
				       "created", NULL};

/* s quoted into buf: as an SQL string literal (quote '), or as an identifier (quote ") */
static void quoted(char *buf, size_t n, const char *s, char q)
{
	size_t l = 0;
	buf[l++] = q;
	for (; s && *s && l + 3 < n; s++) {
		if (*s == q)
			buf[l++] = q;
		buf[l++] = *s;
	}
	buf[l++] = q;
	buf[l] = 0;
}

static void literal(char *buf, size_t n, const char *s)
{
	quoted(buf, n, s, '\'');
}

static void ident(char *buf, size_t n, const char *s)
{
	quoted(buf, n, s, '"');
}

static const char *sql_type(rt_type t)
{
	return t == RT_TEXT ? "TEXT" : t == RT_INT ? "INTEGER" : "REAL";
}

/* The `result` table, one column per stored column of the results table. A database
 * whose result table has other columns (written by another version) gets the table
 * anew: every result is in the run files, and the sweep reads them again. */
int schema_result_current(sql_db *d)
{
	size_t n;
	const rcol *t = results_table(&n);
	char want[4096] = "campaign,run,", have[4096];
	size_t l = strlen(want);
	for (size_t i = 0; i < n; i++)
		if (!(t[i].flags & RF_DERIVED))
			l += (size_t)snprintf(want + l, sizeof want - l, "%s,", t[i].name);
	sql_columns(d, "result", have, sizeof have);
	return !strcmp(have, want);
}

static int result_table(sql_db *d, sb_err *e)
{
	size_t n, l;
	const rcol *t = results_table(&n);
	if (schema_result_current(d))
		return 0;
	char sql[8192] = "DROP TABLE IF EXISTS result; CREATE TABLE result(campaign TEXT NOT NULL, run TEXT NOT NULL";
	l = strlen(sql);
	for (size_t i = 0; i < n; i++)
		if (!(t[i].flags & RF_DERIVED))
			l += (size_t)snprintf(sql + l, sizeof sql - l, ", %s %s", t[i].name, sql_type(t[i].type));
	snprintf(sql + l, sizeof sql - l, ", PRIMARY KEY (campaign, run))");
	return sql_script(d, sql, e);
}

/* The `runs` view: one row per run with every engine parameter as a column (generated
 * from the engine's table, so a new key shows up without a schema change), its state
 * and every result column of the results table (derived ones computed). */
static int runs_view(sql_db *d, sb_err *e)
{
	size_t n, nr;
	const sb_param *t = params_table(&n);
	const rcol *rc = results_table(&nr);
	/* the per-run observables the analysis tools stored (analysis_run): a column
	 * TOOL_KEY and TOOL_KEY_class each, of the tool's latest definition */
	sqlite3_stmt *ob = NULL;
	int nob = 0;
	if (sql_exec(d, e, &ob, "SELECT COUNT(*) FROM (SELECT DISTINCT tool, key FROM analysis_run)", ""))
		return e->code;
	if (sqlite3_step(ob) == SQLITE_ROW)
		nob = sqlite3_column_int(ob, 0);
	if (sql_done(d, ob, e))
		return e->code;
	size_t cap = 4096 + n * 256 + nr * 128 + (size_t)nob * 1024;
	char *sql = malloc(cap);
	if (!sql)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	size_t l = 0;
	l += (size_t)snprintf(sql + l, cap - l,
			      "CREATE VIEW runs AS SELECT b.*,\n"
			      /* the drive's peak acceleration in g (drive_gamma, core/model/drive.h, factor
			       * for factor, so the same bits) and peak velocity: the literature
			       * reports onsets in both (at a ramp's start frequency) */
			      "  b.amplitude * (6.283185307179586 * b.frequency) * (6.283185307179586 * b.frequency)"
			      " / b.gravity AS %s,\n"
			      "  6.283185307179586 * b.frequency * b.amplitude AS %s",
			      VIEW_AXES[AXIS_GAMMA], VIEW_AXES[AXIS_VELOCITY]);
	/* the campaigns' ratio keys (ratio.h): what each run's parameters make of them */
	size_t nra;
	const sb_ratio *ra = ratio_table(&nra);
	for (size_t i = 0; i < nra; i++) {
		char col[256];
		ratio_view_column(&ra[i], col, sizeof col);
		l += (size_t)snprintf(sql + l, cap - l, ",\n  %s", col);
	}
	l += (size_t)snprintf(sql + l, cap - l, "\nFROM (SELECT r.campaign, r.id, r.state, r.attempts, r.replicate, r.current");
	for (size_t i = 0; i < n; i++) {
		if (t[i].flags & PF_OUT)
			continue; /* paths and recording switches: in the param table */
		l += (size_t)snprintf(sql + l, cap - l,
				      ",\n  (SELECT value FROM param p WHERE p.campaign = r.campaign AND p.run = r.id"
				      " AND p.key = '%s') AS %s", t[i].name, t[i].name);
	}
	l += (size_t)snprintf(sql + l, cap - l, ",\n  r.from_cache, r.cache_key");
	for (size_t i = 0; i < nr; i++) {
		if (rc[i].flags & RF_NOVIEW)
			continue;
		if (rc[i].flags & RF_DERIVED) {
			/* the expression's column names are the result table's */
			char expr[256];
			size_t el = 0;
			for (const char *p = rc[i].where; *p && el < sizeof expr - 4;) {
				if ((*p >= 'a' && *p <= 'z') && (p == rc[i].where || p[-1] == ' ')) {
					expr[el++] = 's';
					expr[el++] = '.';
				}
				expr[el++] = *p++;
			}
			expr[el] = 0;
			l += (size_t)snprintf(sql + l, cap - l, ", %s AS %s", expr, rc[i].name);
		} else {
			l += (size_t)snprintf(sql + l, cap - l, ", s.%s", rc[i].name);
		}
	}
	l += (size_t)snprintf(sql + l, cap - l, ", r.host, r.started, r.finished,\n"
			      /* an [onset] search's observable and class of the run (search.c) */
			      "  (SELECT o.value FROM onset_run o WHERE o.campaign = r.campaign AND o.run = r.id) AS search_value,\n"
			      "  (SELECT o.class FROM onset_run o WHERE o.campaign = r.campaign AND o.run = r.id) AS search_class");
	if (sql_exec(d, e, &ob, "SELECT DISTINCT tool, key FROM analysis_run ORDER BY tool, key", "")) {
		free(sql);
		return e->code;
	}
	for (int i = 0; i < nob && sqlite3_step(ob) == SQLITE_ROW; i++) {
		char tool[160], key[160], name[400];
		literal(tool, sizeof tool, (const char *)sqlite3_column_text(ob, 0));
		literal(key, sizeof key, (const char *)sqlite3_column_text(ob, 1));
		for (int c = 0; c < 2; c++) {
			char col[400];
			snprintf(col, sizeof col, "%s_%s%s", (const char *)sqlite3_column_text(ob, 0),
				 (const char *)sqlite3_column_text(ob, 1), c ? "_class" : "");
			ident(name, sizeof name, col);
			l += (size_t)snprintf(sql + l, cap - l,
					      ",\n  (SELECT x.%s FROM analysis_run x WHERE x.campaign = r.campaign AND x.run = r.id"
					      " AND x.tool = %s AND x.key = %s AND x.def = (SELECT MAX(q.id) FROM analysis_def q"
					      " WHERE q.campaign = r.campaign AND q.tool = %s)) AS %s",
					      c ? "class" : "value", tool, key, tool, name);
		}
	}
	sqlite3_finalize(ob);
	l += (size_t)snprintf(sql + l, cap - l, "\nFROM run r LEFT JOIN result s ON s.campaign = r.campaign AND s.run = r.id) b");
	sqlite3_stmt *st;
	int same = 0;
	if (!sql_exec(d, e, &st, "SELECT sql FROM sqlite_master WHERE type = 'view' AND name = 'runs'", "")) {
		if (sqlite3_step(st) == SQLITE_ROW && sqlite3_column_text(st, 0))
			same = !strcmp((const char *)sqlite3_column_text(st, 0), sql);
		sqlite3_finalize(st);
	}
	int rcode = 0;
	if (!same && !e->code) {
		rcode = sql_script(d, "DROP VIEW IF EXISTS runs", e);
		if (!rcode)
			rcode = sql_script(d, sql, e);
	}
	free(sql);
	return e->code;
}

/* Columns added to the driver's tables since they were first created: an older
 * database gets them by ALTER TABLE, and so does a new one where STUDY does not name
 * them (the attempt's: declared here only). */
static const struct {
	const char *table, *column, *decl;
} ADDED[] = {
	{"run", "current", "INTEGER NOT NULL DEFAULT 1"},
	{"campaign", "version", "INTEGER NOT NULL DEFAULT 1"},
	/* a search's axis (Gamma, v) and why a group is blocked */
	{"onset_search", "axis", "TEXT"},
	{"onset_group", "reason", "TEXT"},
	{"onset_run", "axis_value", "REAL"},
	/* an attempt's start (db.c's attempt_row) */
	{"attempt", "started", "TEXT"},
	/* what its engine used, as its worker measured it (wait4; NULL: no worker said):
	 * the cost model's rate from finished runs (study/report/calib.h) */
	{"attempt", "cpu_seconds", "REAL"},
	{"attempt", "max_rss_kb", "INTEGER"},
};

int schema_study(sql_db *d, sb_err *e)
{
	if (sql_script(d, STUDY, e))
		return e->code;
	for (size_t i = 0; i < sizeof ADDED / sizeof ADDED[0]; i++)
		if (sql_ensure_column(d, ADDED[i].table, ADDED[i].column, ADDED[i].decl, e))
			return e->code;
	if (result_table(d, e) ||
	    /* the runs view shows the tools' per-run observables */
	    schema_analysis(d, e))
		return e->code;
	return runs_view(d, e);
}

int schema_runs(sql_db *d, sb_err *e)
{
	/* a database an earlier driver wrote has that version's result columns: a view of
	 * this version's would name columns it lacks and fail on every query; it keeps its
	 * view until the driver (result_table) brings the table up to date */
	if (!schema_result_current(d))
		return 0;
	return runs_view(d, e);
}

static const char *const RUN_TABLES[] = {"campaign", "run", "param", "attempt", "result", "cache", NULL};

int schema_lost(sql_db *d, int all, char *lost, size_t len, sb_err *e)
{
	sqlite3_stmt *st;
	lost[0] = 0;
	int have = 0;
	size_t l = 0;
	for (int i = 0; RUN_TABLES[i] && (all || i < 3); i++) {
		if (sql_exec(d, e, &st, "SELECT 1 FROM sqlite_schema WHERE type = 'table' AND name = ?", "t", RUN_TABLES[i]))
			return e->code;
		int yes = sqlite3_step(st) == SQLITE_ROW;
		if (sql_done(d, st, e))
			return e->code;
		have += yes;
		if (!yes && l < len)
			l += (size_t)snprintf(lost + l, len - l, "%s%s", l ? ", " : "", RUN_TABLES[i]);
	}
	if (!have) /* a new database */
		lost[0] = 0;
	return 0;
}

static int indexes_agree(sql_db *d, sb_err *e);

int schema_complete(sql_db *d, int all, sb_err *e)
{
	char lost[128];
	if (schema_lost(d, all, lost, sizeof lost, e))
		return e->code;
	if (!lost[0])
		return indexes_agree(d, e);
	return sb_errf(e, SB_EIO, "%s: lacks table %s (dropped, or not a study database): study run on the campaign "
		       "file rebuilds it from the campaign and run files (docs/database.md, \"A damaged database\")",
		       d->path, lost);
}

/* The indexes the readers find runs and campaigns by, against their tables: every
 * entry must be a row's (the same rowid, the same key values) and every row must have
 * one. PRAGMA quick_check does not compare an index with its table, and a damaged
 * index page made study export write a run under campaign 'f' with no parameters, exit
 * 0 (found by make fuzz's database family). A rowid lookup per entry: milliseconds for
 * 20 000 runs. */
static int indexes_agree(sql_db *d, sb_err *e)
{
	static const struct {
		const char *table, *index, *c1, *c2;
	} IX[] = {
		{"run", "sqlite_autoindex_run_1", "campaign", "id"},
		{"run", "run_state", "campaign", "state"},
		{"campaign", "sqlite_autoindex_campaign_1", "name", "name"},
	};
	for (size_t k = 0; k < sizeof IX / sizeof IX[0]; k++) {
		char sql[1024];
		const char *t = IX[k].table, *i = IX[k].index, *a = IX[k].c1, *b = IX[k].c2;
		/* the range on the first column makes SQLite read the index, not the table */
		snprintf(sql, sizeof sql,
			 "SELECT (SELECT count(*) FROM %s NOT INDEXED) - (SELECT count(*) FROM %s INDEXED BY %s WHERE %s > '' "
			 "OR %s <= ''), (SELECT count(*) FROM (SELECT rowid AS r, %s AS a, %s AS b FROM %s INDEXED BY %s WHERE "
			 "%s > '' OR %s <= '') x WHERE NOT EXISTS (SELECT 1 FROM %s AS y NOT INDEXED WHERE y.rowid = x.r AND "
			 "y.%s IS x.a AND y.%s IS x.b))",
			 t, t, i, a, a, a, b, t, i, a, a, t, a, b);
		sqlite3_stmt *st;
		if (sqlite3_prepare_v2(d->h, sql, -1, &st, NULL) != SQLITE_OK)
			continue; /* an index an older database lacks: nothing to compare */
		int rc = sqlite3_step(st);
		long long missing = rc == SQLITE_ROW ? sqlite3_column_int64(st, 0) : 0,
			  wrong = rc == SQLITE_ROW ? sqlite3_column_int64(st, 1) : 0;
		if (rc != SQLITE_ROW) {
			sql_failed(d, rc, e);
			sqlite3_finalize(st);
			return e->code;
		}
		sqlite3_finalize(st);
		if (missing || wrong)
			return sb_errf(e, SB_EIO, "%s: the database is corrupt (index %s disagrees with table %s: %lld rows "
				       "without an entry, %lld entries without their row): %s", d->path, i, t, missing, wrong,
				       SQL_REBUILD);
	}
	return 0;
}

int schema_runs_lost(sql_db *d, const char *campaign, sb_err *e)
{
	sqlite3_stmt *st;
	if (sql_exec(d, e, &st,
		     "SELECT EXISTS (SELECT 1 FROM campaign WHERE name = ?1), EXISTS (SELECT 1 FROM run WHERE campaign = ?1)",
		     "t", campaign))
		return e->code;
	const int lost = sqlite3_step(st) == SQLITE_ROW && sqlite3_column_int(st, 0) && !sqlite3_column_int(st, 1);
	if (sql_done(d, st, e) || !lost)
		return e->code;
	char why[512];
	if (sql_check(d, why, sizeof why))
		return sb_errf(e, SB_EIO, "%s: the database is corrupt (quick_check: %s): %s", d->path, why, SQL_REBUILD);
	return sb_errf(e, SB_EIO, "%s: campaign '%s' is recorded without any run (the rows of table run were lost): "
		       "study run on its campaign file records them again from the run files (docs/database.md, "
		       "\"A damaged database\")", d->path, campaign);
}

int schema_bad_value(sql_db *d, const char *campaign, int numbers, char *run, size_t rlen, char *why, size_t wlen,
		     sb_err *e)
{
	sqlite3_stmt *st;
	int bad = 0;
	if (run)
		run[0] = 0;
	why[0] = 0;
	/* each distinct value once: a campaign of 20 000 runs has few besides the seeds */
	if (sql_exec(d, e, &st,
		     "SELECT key, value, typeof(value), MIN(run) FROM param WHERE campaign = ? GROUP BY key, value", "t",
		     campaign))
		return e->code;
	sb_scene *sc = malloc(sizeof *sc);
	if (!sc) {
		sqlite3_finalize(st);
		return sb_errf(e, SB_ENOMEM, "out of memory");
	}
	params_defaults(sc);
	while (!bad && sqlite3_step(st) == SQLITE_ROW) {
		const char *key = (const char *)sqlite3_column_text(st, 0);
		const sb_param *p = key ? params_find(key) : NULL;
		if (!p) /* a key of another engine version: not this parser's to judge */
			continue;
		if (!numbers && (p->type == PT_INT || p->type == PT_REAL))
			continue;
		char txt[SB_STR_MAX + 8];
		if (sqlite3_column_type(st, 1) == SQLITE_FLOAT) /* all 17 digits */
			snprintf(txt, sizeof txt, "%.17g", sqlite3_column_double(st, 1));
		else
			snprintf(txt, sizeof txt, "%s", sqlite3_column_text(st, 1) ? (const char *)sqlite3_column_text(st, 1) : "");
		sb_err pe = {0};
		if (sqlite3_column_type(st, 1) == SQLITE_NULL)
			sb_errf(&pe, SB_EUSAGE, "NULL");
		else
			params_set(sc, key, txt, "", &pe);
		if (pe.code) {
			bad = 1;
			if (run)
				snprintf(run, rlen, "%s", (const char *)sqlite3_column_text(st, 3));
			snprintf(why, wlen, "run %s: %s = '%s' in table param: %s", (const char *)sqlite3_column_text(st, 3), key,
				 txt, pe.msg[0] == ':' ? pe.msg + 2 : pe.msg);
		}
	}
	free(sc);
	if (sql_done(d, st, e) || bad)
		return e->code ? e->code : bad;
	size_t n;
	const rcol *t = results_table(&n);
	for (size_t i = 0; i < n && !bad && !e->code; i++) {
		if (!(t[i].flags & RF_FLAG))
			continue;
		char sql[256];
		snprintf(sql, sizeof sql, "SELECT run, quote(%s) FROM result WHERE campaign = ? AND %s NOT IN (0, 1) LIMIT 1",
			 t[i].name, t[i].name);
		if (sql_exec(d, e, &st, sql, "t", campaign))
			return e->code;
		if (sqlite3_step(st) == SQLITE_ROW) {
			bad = 1;
			if (run)
				snprintf(run, rlen, "%s", (const char *)sqlite3_column_text(st, 0));
			snprintf(why, wlen, "run %s: %s = %s in table result: expected 0 or 1 (NULL: none)",
				 (const char *)sqlite3_column_text(st, 0), t[i].name, (const char *)sqlite3_column_text(st, 1));
		}
		sql_done(d, st, e);
	}
	return e->code ? e->code : bad;
}

int schema_values(sql_db *d, const char *campaign, int numbers, sb_err *e)
{
	char why[1200];
	int r = schema_bad_value(d, campaign, numbers, NULL, 0, why, sizeof why, e);
	if (r <= 0 || e->code)
		return e->code;
	return sb_errf(e, SB_EIO, "%s: campaign '%s': %s: a value no run can have (edited or damaged): study run on its "
		       "campaign file writes it again from the campaign and run files (docs/database.md, \"A damaged "
		       "database\")", d->path, campaign, why);
}

int schema_slurm(sql_db *d, sb_err *e)
{
	return sql_script(d, SLURM, e);
}

/* An `analysis` table of an earlier version (one set of rows per campaign and tool,
 * with the grouping keys' columns it was given) becomes analysis_all: its rows kept,
 * under one definition per campaign and tool whose options are NULL (not recorded
 * then). */
static int analysis_migrate(sql_db *d, sb_err *e)
{
	sqlite3_stmt *st;
	if (sql_exec(d, e, &st, "SELECT COUNT(*) FROM sqlite_master WHERE type = 'table' AND name = 'analysis'", ""))
		return e->code;
	const int old = sqlite3_step(st) == SQLITE_ROW && sqlite3_column_int(st, 0) > 0;
	sqlite3_finalize(st);
	if (!old)
		return 0;
	char cols[8192];
	sql_columns(d, "analysis", cols, sizeof cols);
	const size_t cap = 3 * sizeof cols + 1024;
	char *list = malloc(cap), *sql = malloc(2 * cap);
	if (!list || !sql) {
		free(list);
		free(sql);
		return sb_errf(e, SB_ENOMEM, "out of memory");
	}
	size_t l = 0;
	list[0] = 0;
	for (char *sv, *c = strtok_r(cols, ",", &sv); c && !e->code; c = strtok_r(NULL, ",", &sv)) {
		int fixed = !strcmp(c, "def");
		for (int i = 0; AN_FIXED[i]; i++)
			fixed |= !strcmp(c, AN_FIXED[i]);
		char q[300];
		ident(q, sizeof q, c);
		if (!fixed) { /* a grouping key's column, untyped as adb.c adds them */
			snprintf(sql, 2 * cap, "ALTER TABLE analysis_all ADD COLUMN %s", q);
			sql_script(d, sql, e);
		}
		if (strcmp(c, "def"))
			l += (size_t)snprintf(list + l, cap - l, "%s%s", l ? ", " : "", q);
	}
	if (!e->code) {
		snprintf(sql, 2 * cap,
			 "INSERT INTO analysis_def(campaign, tool, version, options, build, created)\n"
			 "  SELECT campaign, tool, MAX(version), NULL, NULL, MAX(created) FROM analysis\n"
			 "  GROUP BY campaign, tool ORDER BY MIN(rowid);\n"
			 "INSERT INTO analysis_all(%s, def) SELECT %s, (SELECT MAX(d.id) FROM analysis_def d\n"
			 "  WHERE d.campaign = a.campaign AND d.tool = a.tool) FROM analysis a;\n"
			 "DROP TABLE analysis", list, list);
		sql_script(d, sql, e);
	}
	free(list);
	free(sql);
	return e->code;
}

int schema_analysis(sql_db *d, sb_err *e)
{
	if (sql_script(d, ANALYSIS, e) || analysis_migrate(d, e))
		return e->code;
	return sql_script(d, ANALYSIS_VIEW, e);
}
