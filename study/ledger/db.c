/* db.c - SQLite schema, views and the few writes the driver makes. */
#include "db.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const char SCHEMA[] =
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
	"  campaign TEXT PRIMARY KEY, observable TEXT, freq_from REAL, freq_to REAL, tolerance REAL,\n"
	"  threshold REAL, band_lo REAL, band_hi REAL, skip REAL, replicates TEXT, max_replicates INTEGER,\n"
	"  batch INTEGER, target REAL, level REAL, state TEXT, updated TEXT);\n"
	"CREATE TABLE IF NOT EXISTS onset_group(\n"
	"  campaign TEXT NOT NULL, grp TEXT NOT NULL, point INTEGER, replicates INTEGER, searching INTEGER,\n"
	"  found INTEGER, below INTEGER, above INTEGER, blocked INTEGER, nonmonotone INTEGER, runs INTEGER,\n"
	"  estimate REAL, ci_lo REAL, ci_hi REAL, width REAL, state TEXT, PRIMARY KEY (campaign, grp));\n"
	"CREATE TABLE IF NOT EXISTS onset_replicate(\n"
	"  campaign TEXT NOT NULL, grp TEXT NOT NULL, replicate INTEGER NOT NULL, state TEXT, lo REAL, hi REAL,\n"
	"  lo_run INTEGER, hi_run INTEGER, next REAL, runs INTEGER, nonmonotone INTEGER,\n"
	"  PRIMARY KEY (campaign, grp, replicate));\n"
	"CREATE TABLE IF NOT EXISTS onset_run(\n"
	"  campaign TEXT NOT NULL, run TEXT NOT NULL, grp TEXT, replicate INTEGER, step INTEGER,\n"
	"  frequency REAL, value REAL, class TEXT, PRIMARY KEY (campaign, run));\n"
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

int db_exec(st_db *d, sb_err *e, sqlite3_stmt **out, const char *sql, const char *fmt, ...)
{
	sqlite3_stmt *st = NULL;
	if (sqlite3_prepare_v2(d->h, sql, -1, &st, NULL) != SQLITE_OK)
		return sb_errf(e, SB_EIO, "%s: %s", d->path, sqlite3_errmsg(d->h));
	va_list ap;
	va_start(ap, fmt);
	int k = 1;
	for (const char *f = fmt; *f; f++, k++) {
		switch (*f) {
		case 't': {
			const char *s = va_arg(ap, const char *);
			if (s)
				sqlite3_bind_text(st, k, s, -1, SQLITE_TRANSIENT);
			else
				sqlite3_bind_null(st, k);
			break;
		}
		case 'l': sqlite3_bind_int64(st, k, va_arg(ap, long)); break;
		case 'd': sqlite3_bind_double(st, k, va_arg(ap, double)); break;
		case 'D': {
			int okv = va_arg(ap, int);
			double v = va_arg(ap, double);
			if (okv)
				sqlite3_bind_double(st, k, v);
			else
				sqlite3_bind_null(st, k);
			break;
		}
		default: sqlite3_bind_null(st, k); break;
		}
	}
	va_end(ap);
	if (out) {
		*out = st;
		return 0;
	}
	int rc;
	while ((rc = sqlite3_step(st)) == SQLITE_ROW)
		;
	sqlite3_finalize(st);
	if (rc != SQLITE_DONE)
		return sb_errf(e, SB_EIO, "%s: %s", d->path, sqlite3_errmsg(d->h));
	return 0;
}

static int exec_script(st_db *d, const char *sql, sb_err *e)
{
	char *msg = NULL;
	if (sqlite3_exec(d->h, sql, NULL, NULL, &msg) != SQLITE_OK) {
		sb_errf(e, SB_EIO, "%s: %s", d->path, msg ? msg : sqlite3_errmsg(d->h));
		sqlite3_free(msg);
		return e->code;
	}
	return 0;
}

/* Columns of a table, as "a,b,c," ("" when the table does not exist). */
static void table_columns(st_db *d, const char *table, char *out, size_t len)
{
	sqlite3_stmt *st;
	sb_err e = {0};
	size_t l = 0;
	out[0] = 0;
	char sql[128];
	snprintf(sql, sizeof sql, "PRAGMA table_info(%s)", table);
	if (db_exec(d, &e, &st, sql, ""))
		return;
	while (sqlite3_step(st) == SQLITE_ROW && l < len)
		l += (size_t)snprintf(out + l, len - l, "%s,", (const char *)sqlite3_column_text(st, 1));
	sqlite3_finalize(st);
}

/* A column added since the table was first created (older databases lack it). */
static int ensure_column(st_db *d, const char *table, const char *col, const char *decl, sb_err *e)
{
	char cols[4096] = ",", want[128], sql[256];
	table_columns(d, table, cols + 1, sizeof cols - 1);
	snprintf(want, sizeof want, ",%s,", col);
	if (strstr(cols, want))
		return 0;
	snprintf(sql, sizeof sql, "ALTER TABLE %s ADD COLUMN %s %s", table, col, decl);
	return exec_script(d, sql, e);
}

static const char *sql_type(rt_type t)
{
	return t == RT_TEXT ? "TEXT" : t == RT_INT ? "INTEGER" : "REAL";
}

/* The `result` table, one column per stored column of the results table. A database
 * whose result table has other columns (written by another version) gets the table
 * anew: every result is in the run files, and the sweep reads them again. */
static int make_result_table(st_db *d, sb_err *e)
{
	size_t n;
	const rcol *t = results_table(&n);
	char want[4096] = "campaign,run,", have[4096];
	size_t l = strlen(want);
	for (size_t i = 0; i < n; i++)
		if (!(t[i].flags & RF_DERIVED))
			l += (size_t)snprintf(want + l, sizeof want - l, "%s,", t[i].name);
	table_columns(d, "result", have, sizeof have);
	if (!strcmp(have, want))
		return 0;
	char sql[8192] = "DROP TABLE IF EXISTS result; CREATE TABLE result(campaign TEXT NOT NULL, run TEXT NOT NULL";
	l = strlen(sql);
	for (size_t i = 0; i < n; i++)
		if (!(t[i].flags & RF_DERIVED))
			l += (size_t)snprintf(sql + l, sizeof sql - l, ", %s %s", t[i].name, sql_type(t[i].type));
	snprintf(sql + l, sizeof sql - l, ", PRIMARY KEY (campaign, run))");
	return exec_script(d, sql, e);
}

/* The `runs` view: one row per run with every engine parameter as a column (generated
 * from the engine's table, so a new key shows up without a schema change), its state
 * and every result column of the results table (derived ones computed). */
static int make_runs_view(st_db *d, sb_err *e)
{
	size_t n, nr;
	const sb_param *t = params_table(&n);
	const rcol *rc = results_table(&nr);
	size_t cap = 4096 + n * 256 + nr * 128;
	char *sql = malloc(cap);
	if (!sql)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	size_t l = 0;
	l += (size_t)snprintf(sql + l, cap - l,
			      "CREATE VIEW runs AS SELECT b.*,\n"
			      /* the drive's peak acceleration in g and peak velocity: the literature
			       * reports onsets in both (at a ramp's start frequency) */
			      "  b.amplitude * (6.283185307179586 * b.frequency) * (6.283185307179586 * b.frequency)"
			      " / b.gravity AS gamma,\n"
			      "  6.283185307179586 * b.frequency * b.amplitude AS v_box\nFROM (SELECT r.campaign, r.id, r.state,"
			      " r.attempts, r.replicate, r.current");
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
	l += (size_t)snprintf(sql + l, cap - l,
			      ", r.host, r.started, r.finished\n"
			      "FROM run r LEFT JOIN result s ON s.campaign = r.campaign AND s.run = r.id) b");
	sqlite3_stmt *st;
	int same = 0;
	if (!db_exec(d, e, &st, "SELECT sql FROM sqlite_master WHERE type = 'view' AND name = 'runs'", "")) {
		if (sqlite3_step(st) == SQLITE_ROW && sqlite3_column_text(st, 0))
			same = !strcmp((const char *)sqlite3_column_text(st, 0), sql);
		sqlite3_finalize(st);
	}
	int rcode = 0;
	if (!same && !e->code) {
		rcode = exec_script(d, "DROP VIEW IF EXISTS runs", e);
		if (!rcode)
			rcode = exec_script(d, sql, e);
	}
	free(sql);
	return e->code;
}

int db_open(st_db *d, const char *path, int writable, sb_err *e)
{
	memset(d, 0, sizeof *d);
	snprintf(d->path, sizeof d->path, "%s", path);
	int flags = writable ? SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE : SQLITE_OPEN_READONLY;
	if (sqlite3_open_v2(path, &d->h, flags, NULL) != SQLITE_OK) {
		sb_errf(e, SB_EIO, "%s: cannot open database: %s", path, d->h ? sqlite3_errmsg(d->h) : "out of memory");
		sqlite3_close(d->h);
		d->h = NULL;
		return e->code;
	}
	/* readers wait for the driver's short write transactions instead of failing */
	sqlite3_busy_timeout(d->h, 60000);
	if (!writable)
		return 0;
	if (exec_script(d, "PRAGMA journal_mode = WAL; PRAGMA synchronous = NORMAL;", e))
		return e->code;
	if (db_begin(d, e))
		return e->code;
	if (exec_script(d, SCHEMA, e) || ensure_column(d, "run", "current", "INTEGER NOT NULL DEFAULT 1", e) ||
	    ensure_column(d, "campaign", "version", "INTEGER NOT NULL DEFAULT 1", e) || make_result_table(d, e) ||
	    make_runs_view(d, e)) {
		db_rollback(d);
		return e->code;
	}
	return db_commit(d, e);
}

void db_close(st_db *d)
{
	if (d->h)
		sqlite3_close(d->h);
	d->h = NULL;
}

int db_begin(st_db *d, sb_err *e)
{
	return exec_script(d, "BEGIN IMMEDIATE", e);
}

int db_commit(st_db *d, sb_err *e)
{
	return exec_script(d, "COMMIT", e);
}

void db_rollback(st_db *d)
{
	sqlite3_exec(d->h, "ROLLBACK", NULL, NULL, NULL);
}

void db_now(char *buf, size_t len)
{
	time_t t = time(NULL);
	struct tm tm;
	gmtime_r(&t, &tm);
	strftime(buf, len, "%Y-%m-%dT%H:%M:%SZ", &tm);
}

int db_campaign_put(st_db *d, const campaign *c, const char *now, sb_err *e)
{
	char axes[2048] = "", seed[32];
	size_t l = 0;
	for (int i = 0; i < c->naxes && l < sizeof axes; i++)
		l += (size_t)snprintf(axes + l, sizeof axes - l, "%s%s", i ? " " : "", c->axes[i].key);
	/* an [onset] search varies both too: the analysis tools group by the swept keys */
	if (c->onset.line && l < sizeof axes)
		snprintf(axes + l, sizeof axes - l, "%sfrequency seed", l ? " " : "");
	/* and replicates = auto the replicate, as replicates = N would */
	if (c->autorep.on && l < sizeof axes)
		snprintf(axes + l, sizeof axes - l, "%sseed", l ? " " : "");
	snprintf(seed, sizeof seed, "%llu", c->seed);
	return db_exec(d, e, NULL,
		       "INSERT INTO campaign(name, description, file, scene_file, seed, seeds, axes, created, updated)"
		       " VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?8) ON CONFLICT(name) DO UPDATE SET"
		       " description = ?2, file = ?3, scene_file = ?4, seed = ?5, seeds = ?6, axes = ?7, updated = ?8",
		       "tttttttt", c->name, c->description, c->path, c->scene_file, seed,
		       c->seeds == CP_SEEDS_LITERAL ? "literal" : "derived", axes, now);
}

int db_run_add(st_db *d, const campaign *c, const grid_run *r, const sb_scene *s, const char *now, sb_err *e)
{
	if (db_exec(d, e, NULL,
		    "INSERT OR IGNORE INTO run(campaign, id, replicate, seed, cache_key, added)"
		    " VALUES (?, ?, ?, ?, ?, ?)",
		    "ttllt" "t", c->name, r->id, r->replicate, r->seed, r->cache_key, now))
		return e->code;
	if (sqlite3_changes(d->h) == 0) /* known run: its parameters are already recorded */
		return db_exec(d, e, NULL, "UPDATE run SET current = 1 WHERE campaign = ? AND id = ? AND current = 0",
			       "tt", c->name, r->id);
	size_t n;
	const sb_param *t = params_table(&n);
	sqlite3_stmt *st;
	if (db_exec(d, e, &st, "INSERT OR REPLACE INTO param(campaign, run, key, value) VALUES (?, ?, ?, ?)", "tt",
		    c->name, r->id))
		return e->code;
	for (size_t i = 0; i < n; i++) {
		if (t[i].flags & PF_DRIVER) /* the same for every run: the driver's */
			continue;
		const char *base = (const char *)s + t[i].offset;
		char v[SB_STR_MAX + 8];
		params_format(s, &t[i], v, sizeof v);
		sqlite3_bind_text(st, 3, t[i].name, -1, SQLITE_STATIC);
		/* typed, so that WHERE frequency = 2.8 and ORDER BY work without casts */
		if (t[i].type == PT_INT)
			sqlite3_bind_int64(st, 4, *(const long *)base);
		else if (t[i].type == PT_REAL)
			sqlite3_bind_double(st, 4, *(const double *)base);
		else
			sqlite3_bind_text(st, 4, v, -1, SQLITE_TRANSIENT);
		if (sqlite3_step(st) != SQLITE_DONE) {
			sb_errf(e, SB_EIO, "%s: %s", d->path, sqlite3_errmsg(d->h));
			break;
		}
		sqlite3_reset(st);
	}
	sqlite3_finalize(st);
	return e->code;
}

int db_run_state(st_db *d, const char *camp, const char *id, char *state, size_t len, long *attempts,
		 sb_err *e)
{
	sqlite3_stmt *st;
	state[0] = 0;
	*attempts = 0;
	if (db_exec(d, e, &st, "SELECT state, attempts FROM run WHERE campaign = ? AND id = ?", "tt", camp, id))
		return e->code;
	if (sqlite3_step(st) == SQLITE_ROW) {
		snprintf(state, len, "%s", (const char *)sqlite3_column_text(st, 0));
		*attempts = (long)sqlite3_column_int64(st, 1);
	}
	sqlite3_finalize(st);
	return 0;
}

static int attempt_row(st_db *d, const char *camp, const char *id, long exit_code, const char *status,
		       const char *message, const char *host, const char *now, int has_wall, double wall,
		       const char *state, sb_err *e)
{
	if (db_exec(d, e, NULL,
		    "INSERT INTO attempt(campaign, run, n, host, exit_code, status, message, finished, wall_seconds)"
		    " VALUES (?1, ?2, (SELECT attempts + 1 FROM run WHERE campaign = ?1 AND id = ?2), ?3, ?4, ?5, ?6, ?7, ?8)",
		    "tttlttt" "D", camp, id, host, exit_code, status, message, now, has_wall, wall))
		return e->code;
	return db_exec(d, e, NULL,
		       "UPDATE run SET attempts = attempts + 1, state = ?3, host = ?4, finished = ?5"
		       " WHERE campaign = ?1 AND id = ?2",
		       "ttttt", camp, id, state, host, now);
}

int db_attempt(st_db *d, const char *camp, const char *id, long exit_code, const char *status,
	       const char *message, const char *host, const char *now, const char *state, sb_err *e)
{
	return attempt_row(d, camp, id, exit_code, status, message, host, now, 0, 0, state, e);
}

int db_attempt_kept(st_db *d, const char *camp, const char *id, const h5sum *s, const char *status,
		    const char *message, const char *now, sb_err *e)
{
	const char *end = s ? h5sum_text(s, "end_time") : "";
	return attempt_row(d, camp, id, s ? h5sum_int(s, "exit_code") : SB_EIO, status, message,
			   s ? h5sum_text(s, "host") : "", end[0] ? end : now, s != NULL,
			   s ? h5sum_real(s, "wall_seconds") : 0, "pending", e);
}

/* The result row of a run from its file's summary: generated from the results table;
 * a run from the packing cache did not settle itself, its settling is the cache's. */
int db_result_put(st_db *d, const char *camp, const char *id, const h5sum *s, sb_err *e)
{
	size_t n;
	const rcol *t = results_table(&n);
	char cols[4096] = "campaign, run", vals[8192] = "?1, ?2";
	size_t lc = strlen(cols), lv = strlen(vals);
	int k = 3;
	for (size_t i = 0; i < n; i++) {
		if (t[i].flags & RF_DERIVED)
			continue;
		lc += (size_t)snprintf(cols + lc, sizeof cols - lc, ", %s", t[i].name);
		if (t[i].flags & RF_CACHE)
			lv += (size_t)snprintf(vals + lv, sizeof vals - lv,
					       ", CASE WHEN (SELECT from_cache FROM run WHERE campaign = ?1 AND id = ?2) THEN"
					       " (SELECT c.%s FROM cache c JOIN run r ON c.campaign = r.campaign"
					       " AND c.key = r.cache_key WHERE r.campaign = ?1 AND r.id = ?2) ELSE ?%d END",
					       t[i].name, k++);
		else
			lv += (size_t)snprintf(vals + lv, sizeof vals - lv, ", ?%d", k++);
	}
	char sql[16384];
	snprintf(sql, sizeof sql, "INSERT OR REPLACE INTO result(%s) VALUES (%s)", cols, vals);
	sqlite3_stmt *st;
	if (db_exec(d, e, &st, sql, "tt", camp, id))
		return e->code;
	k = 3;
	for (size_t i = 0; i < n; i++) {
		if (t[i].flags & RF_DERIVED)
			continue;
		const h5val *v = &s->v[i];
		if (!v->has)
			sqlite3_bind_null(st, k);
		else if (t[i].type == RT_TEXT)
			sqlite3_bind_text(st, k, v->s, -1, SQLITE_TRANSIENT);
		else if (t[i].type == RT_INT)
			sqlite3_bind_int64(st, k, v->i);
		else
			sqlite3_bind_double(st, k, v->d);
		k++;
	}
	int rc = sqlite3_step(st);
	sqlite3_finalize(st);
	if (rc != SQLITE_DONE)
		return sb_errf(e, SB_EIO, "%s: %s", d->path, sqlite3_errmsg(d->h));
	return 0;
}

int db_ingest(st_db *d, const char *camp, const char *id, const h5sum *s, const char *now, sb_err *e)
{
	const char *status = h5sum_text(s, "status");
	/* the run finished when the engine wrote its file, not when the driver read it */
	const char *end = h5sum_text(s, "end_time");
	if (attempt_row(d, camp, id, h5sum_int(s, "exit_code"), status, h5sum_text(s, "message"),
			h5sum_text(s, "host"), end[0] ? end : now, 1, h5sum_real(s, "wall_seconds"),
			strcmp(status, "ok") ? "failed" : "done", e))
		return e->code;
	/* a run no driver saw start (a database rebuilt from the files): it started when
	 * its file says the engine did */
	const char *start = h5sum_text(s, "start_time");
	if (start[0] && db_exec(d, e, NULL, "UPDATE run SET started = ?3 WHERE campaign = ?1 AND id = ?2 AND started IS NULL",
				"ttt", camp, id, start))
		return e->code;
	return db_result_put(d, camp, id, s, e);
}
