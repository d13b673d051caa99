/* adb.c - campaign runs, parameter grouping and the analysis results tables. */
#include "adb.h"

#include "layout.h"
#include "num.h"
#include "params.h"
#include "provenance.h"
#include "rowseal.h"
#include "schema.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* the last SQLite failure, named as every reader of the database names it (sql.h) */
static int dberr(adb *d, sb_err *e)
{
	int rc = sqlite3_errcode(d->db.h);
	return sql_failed(&d->db, rc == SQLITE_OK ? SQLITE_ERROR : rc, e);
}

int adb_open(adb *d, const char *path, int writable, sb_err *e)
{
	memset(d, 0, sizeof *d);
	/* the driver may be writing: sql_open waits for its short transactions */
	if (sql_open(&d->db, path, writable ? SQLITE_OPEN_READWRITE : SQLITE_OPEN_READONLY, e))
		return e->code;
	sql_on_wait(&d->db, sql_say_stderr, "analysis");
	/* the tables every tool reads; attempt and result may be an older driver's */
	if (schema_complete(&d->db, 0, e))
		sql_close(&d->db);
	return e->code;
}

void adb_close(adb *d)
{
	if (d->ins)
		sqlite3_finalize(d->ins);
	if (d->rins)
		sqlite3_finalize(d->rins);
	d->ins = d->rins = NULL;
	sql_close(&d->db);
}

static char *dup_text(const unsigned char *s)
{
	const char *t = s ? (const char *)s : "";
	size_t l = strlen(t) + 1;
	char *p = malloc(l);
	if (p)
		memcpy(p, t, l);
	return p;
}

/* 1 when table (or, with col, its column) exists: a database written by an older
 * bin/study lacks some of what a newer one records. */
static int has(adb *d, const char *table, const char *col)
{
	sqlite3_stmt *st;
	const char *sql = col ? "SELECT COUNT(*) FROM pragma_table_info(?1) WHERE name = ?2"
			      : "SELECT COUNT(*) FROM sqlite_master WHERE type = 'table' AND name = ?1";
	if (sqlite3_prepare_v2(d->db.h, sql, -1, &st, NULL) != SQLITE_OK)
		return 0;
	sqlite3_bind_text(st, 1, table, -1, SQLITE_TRANSIENT);
	if (col)
		sqlite3_bind_text(st, 2, col, -1, SQLITE_TRANSIENT);
	int yes = sqlite3_step(st) == SQLITE_ROW && sqlite3_column_int(st, 0) > 0;
	sqlite3_finalize(st);
	return yes;
}

int adb_campaign_exists(adb *d, const char *campaign, int *yes, sb_err *e)
{
	sqlite3_stmt *st;
	*yes = 0;
	if (sqlite3_prepare_v2(d->db.h, "SELECT COUNT(*) FROM campaign WHERE name = ?", -1, &st, NULL) != SQLITE_OK)
		return dberr(d, e);
	sqlite3_bind_text(st, 1, campaign, -1, SQLITE_TRANSIENT);
	*yes = sqlite3_step(st) == SQLITE_ROW && sqlite3_column_int(st, 0) > 0;
	return sql_done(&d->db, st, e);
}

const char *an_str(const an_run *r, const char *key)
{
	for (int i = 0; i < r->nparam; i++)
		if (!strcmp(r->key[i], key))
			return r->val[i];
	return NULL;
}

double an_num(const an_run *r, const char *key, double dflt)
{
	const char *s = an_str(r, key);
	double v;
	if (!s)
		return dflt;
	return num_real(s, &v) ? NAN : v;
}

/* a number key of the engine's table: its value must be a number */
static int numeric_key(const char *key)
{
	const sb_param *p = params_find(key);
	return p && (p->type == PT_INT || p->type == PT_REAL);
}

int an_known(const an_run *r, const char *key, char *why, size_t n)
{
	const char *s = an_str(r, key);
	double v;
	if (!s) {
		snprintf(why, n, "%s: no row in the param table", key);
		return 1;
	}
	if (numeric_key(key) && num_real(s, &v)) {
		snprintf(why, n, "%s = '%.60s' in the param table: not a finite number", key, s);
		return 1;
	}
	return 0;
}

/* The keys every run has recorded since the first bin/study (the campaign keys of the
 * scene contract, docs/scene.md, numbers all): a run without one was not written by it, and
 * a default in its place would put it in another run's group (radius_ratio 0: no
 * intruder). */
static const char *const EVERY_RUN[] = {"n_grains", "width", "radius_ratio", "depth", "amplitude", "frequency",
					"duration", NULL};

/* r->bad: the first parameter the tools cannot use (adb.h). */
static void check_params(an_run *r)
{
	r->bad[0] = 0;
	for (int i = 0; EVERY_RUN[i] && !r->bad[0]; i++)
		an_known(r, EVERY_RUN[i], r->bad, sizeof r->bad);
	for (int i = 0; i < r->nparam && !r->bad[0]; i++)
		an_known(r, r->key[i], r->bad, sizeof r->bad);
}

int adb_runs(adb *d, const char *campaign, const char *runs_dir, an_run **out, int *n, sb_err *e)
{
	*out = NULL;
	*n = 0;
	sqlite3_stmt *st = NULL, *ps = NULL;
	/* A failed run has a result row when the engine wrote its file (a physics failure);
	 * without one (bad input, I/O) its last attempt says why. */
	const int res = has(d, "result", NULL), att = has(d, "attempt", NULL);
	/* the row seals, where the result table is this version's (rowseal.h) */
	const int sealed = res && schema_result_current(&d->db);
	const char *cur = has(d, "run", "current") ? "r.current" : "1";
	char last[2][200], sql[2048];
	static const char *const acol[2] = {"status", "message"};
	for (int c = 0; c < 2; c++) {
		if (att)
			snprintf(last[c], sizeof last[c],
				 "(SELECT a.%s FROM attempt a WHERE a.campaign = r.campaign AND a.run = r.id"
				 " ORDER BY a.n DESC LIMIT 1)", acol[c]);
		else
			snprintf(last[c], sizeof last[c], "NULL");
	}
	snprintf(sql, sizeof sql,
		 "SELECT r.id, r.replicate, r.seed, r.state, %s, COALESCE(%s, %s), COALESCE(%s, %s), %s, %s, %s, %s FROM run r %s"
		 " WHERE r.campaign = ? ORDER BY r.id",
		 cur, res ? "s.status" : "NULL", last[0], res && has(d, "result", "message") ? "s.message" : "NULL", last[1],
		 res && has(d, "result", "status_time") ? "s.status_time" : "NULL",
		 res && has(d, "result", "file_seal") ? "s.file_seal" : "NULL",
		 /* the row seal, where the result table has one (rowseal.h) */
		 sealed ? "s.run IS NOT NULL" : "0", sealed ? "s." ROWSEAL_COLUMN : "NULL",
		 res ? "LEFT JOIN result s ON s.campaign = r.campaign AND s.run = r.id" : "");
	if (sqlite3_prepare_v2(d->db.h, sql, -1, &st, NULL) != SQLITE_OK)
		return dberr(d, e);
	if (sqlite3_prepare_v2(d->db.h, "SELECT key, value FROM param WHERE campaign = ? AND run = ? ORDER BY key", -1,
			       &ps, NULL) != SQLITE_OK) {
		sqlite3_finalize(st);
		return dberr(d, e);
	}
	sqlite3_bind_text(st, 1, campaign, -1, SQLITE_TRANSIENT);
	an_run *r = NULL;
	int cap = 0, k = 0, rc;
	while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
		if (k == cap) {
			cap = cap ? 2 * cap : 64;
			an_run *q = realloc(r, sizeof *r * (size_t)cap);
			if (!q) {
				sb_errf(e, SB_ENOMEM, "out of memory");
				break;
			}
			r = q;
		}
		an_run *x = &r[k++];
		memset(x, 0, sizeof *x);
		snprintf(x->id, sizeof x->id, "%s", (const char *)sqlite3_column_text(st, 0));
		x->replicate = (long)sqlite3_column_int64(st, 1);
		x->seed = (long)sqlite3_column_int64(st, 2);
		x->unit = x->replicate;
		snprintf(x->state, sizeof x->state, "%s", sqlite3_column_text(st, 3) ? (const char *)sqlite3_column_text(st, 3) : "");
		x->current = sqlite3_column_int(st, 4) != 0;
		snprintf(x->status, sizeof x->status, "%s", sqlite3_column_text(st, 5) ? (const char *)sqlite3_column_text(st, 5) : "");
		snprintf(x->message, sizeof x->message, "%s",
			 sqlite3_column_text(st, 6) ? (const char *)sqlite3_column_text(st, 6) : "");
		x->status_time = sqlite3_column_type(st, 7) == SQLITE_NULL ? NAN : sqlite3_column_double(st, 7);
		snprintf(x->seal, sizeof x->seal, "%s", sqlite3_column_text(st, 8) ? (const char *)sqlite3_column_text(st, 8) : "");
		x->used_s = x->planned_s = NAN;
		char dir[1200];
		layout_campaign(runs_dir, campaign, dir, sizeof dir);
		layout_file(dir, 0, x->id, LAY_OUTPUT, x->path, sizeof x->path);
		sqlite3_bind_text(ps, 1, campaign, -1, SQLITE_TRANSIENT);
		sqlite3_bind_text(ps, 2, x->id, -1, SQLITE_TRANSIENT);
		int pc = 0;
		while (sqlite3_step(ps) == SQLITE_ROW) {
			if (x->nparam == pc) {
				pc = pc ? 2 * pc : 64;
				char **a = realloc(x->key, sizeof *a * (size_t)pc), **b = a ? realloc(x->val, sizeof *b * (size_t)pc) : NULL;
				if (a)
					x->key = a;
				if (!a || !b) {
					sb_errf(e, SB_ENOMEM, "out of memory");
					break;
				}
				x->val = b;
			}
			x->key[x->nparam] = dup_text(sqlite3_column_text(ps, 0));
			x->val[x->nparam] = dup_text(sqlite3_column_text(ps, 1));
			x->nparam++;
		}
		if (sqlite3_reset(ps) != SQLITE_OK && !e->code)
			dberr(d, e);
		if (e->code)
			break;
		check_params(x);
		if (!e->code && sqlite3_column_int(st, 9)) {
			/* its rows must be those recorded: a value edited or damaged in the
			 * database reads as a value like any other */
			char now[17], was[17];
			snprintf(was, sizeof was, "%s", sqlite3_column_text(st, 10) ? (const char *)sqlite3_column_text(st, 10) : "");
			if (!rowseal_of(&d->db, campaign, x->id, now, e) && strcmp(now, was))
				snprintf(x->rows, sizeof x->rows, "its rows in the database are not those recorded (row seal %s, "
					 "recorded %s): edited or damaged; study run writes them again", now, was[0] ? was : "none");
		}
	}
	if (!e->code && rc != SQLITE_DONE && rc != SQLITE_ROW)
		sql_failed(&d->db, rc, e);
	sqlite3_finalize(st);
	sqlite3_finalize(ps);
	/* a campaign recorded without a single run is a database that lost rows (the
	 * driver records a campaign and its runs together): corrupt, or a table emptied */
	if (!e->code && k == 0)
		schema_runs_lost(&d->db, campaign, e);
	if (!e->code)
		schema_values(&d->db, campaign, 0, e);
	/* rows not as recorded are an edit, or a page damaged where SQLite's reads do not
	 * fail (a cell's bytes changed): a quick check tells which */
	int changed = 0;
	for (int i = 0; i < k && !e->code; i++)
		changed |= r[i].rows[0] != 0;
	char why[512];
	if (changed && !e->code && sql_check(&d->db, why, sizeof why))
		sb_errf(e, SB_EIO, "%s: the database is corrupt (quick_check: %s): %s", d->db.path, why, SQL_REBUILD);
	if (e->code) {
		adb_runs_free(r, k);
		return e->code;
	}
	*out = r;
	*n = k;
	return 0;
}

void adb_runs_free(an_run *r, int n)
{
	for (int i = 0; r && i < n; i++) {
		for (int j = 0; j < r[i].nparam; j++) {
			free(r[i].key[j]);
			free(r[i].val[j]);
		}
		free(r[i].key);
		free(r[i].val);
	}
	free(r);
}

int adb_axes(adb *d, const char *campaign, char axes[][48], int max, int *n, sb_err *e)
{
	*n = 0;
	sqlite3_stmt *st;
	if (sqlite3_prepare_v2(d->db.h, "SELECT axes FROM campaign WHERE name = ?", -1, &st, NULL) != SQLITE_OK)
		return dberr(d, e);
	sqlite3_bind_text(st, 1, campaign, -1, SQLITE_TRANSIENT);
	int rc = sqlite3_step(st);
	if (rc == SQLITE_ROW && sqlite3_column_text(st, 0)) {
		char buf[2048];
		snprintf(buf, sizeof buf, "%s", (const char *)sqlite3_column_text(st, 0));
		for (char *sv, *tok = strtok_r(buf, " ,", &sv); tok && *n < max; tok = strtok_r(NULL, " ,", &sv))
			snprintf(axes[(*n)++], 48, "%s", tok);
	}
	return sql_done(&d->db, st, e);
}

/* ---- grouping ---- */

/* the grouping keys; each element sorted carries them, so that qsort's comparator
 * needs no state of its own */
typedef struct {
	char (*keys)[48];
	int nk;
} group_keys;

typedef struct {
	an_run *r;
	const group_keys *g;
} keyed_run;

static int cmp_runs(const group_keys *g, const an_run *a, const an_run *b)
{
	for (int k = 0; k < g->nk; k++) {
		const char *sa = an_str(a, g->keys[k]), *sb = an_str(b, g->keys[k]);
		double va = an_num(a, g->keys[k], NAN), vb = an_num(b, g->keys[k], NAN);
		if (!isnan(va) && !isnan(vb)) {
			if (va != vb)
				return va < vb ? -1 : 1;
			continue;
		}
		int c = strcmp(sa ? sa : "", sb ? sb : "");
		if (c)
			return c;
	}
	return 0;
}

static int cmp_keyed(const void *a, const void *b)
{
	const keyed_run *x = a, *y = b;
	int c = cmp_runs(x->g, x->r, y->r);
	return c ? c : strcmp(x->r->id, y->r->id);
}

int an_group_runs(an_run *r, int n, char keys[][48], int nk, char ***labels)
{
	*labels = NULL;
	if (n <= 0)
		return 0;
	const group_keys g = {keys, nk};
	keyed_run *p = malloc(sizeof *p * (size_t)n);
	char **lab = malloc(sizeof *lab * (size_t)n);
	if (!p || !lab) {
		free(p);
		free(lab);
		return -1;
	}
	for (int i = 0; i < n; i++)
		p[i] = (keyed_run){&r[i], &g};
	qsort(p, (size_t)n, sizeof *p, cmp_keyed);
	int ng = 0;
	for (int i = 0; i < n; i++) {
		if (i == 0 || cmp_runs(&g, p[i - 1].r, p[i].r)) {
			char buf[1024] = "";
			size_t l = 0;
			for (int k = 0; k < nk && l < sizeof buf; k++) {
				const char *v = an_str(p[i].r, keys[k]);
				double x = an_num(p[i].r, keys[k], NAN);
				if (!isnan(x))
					l += (size_t)snprintf(buf + l, sizeof buf - l, "%s%s=%g", k ? " " : "", keys[k], x);
				else
					l += (size_t)snprintf(buf + l, sizeof buf - l, "%s%s=%s", k ? " " : "", keys[k], v ? v : "");
			}
			if (!nk)
				snprintf(buf, sizeof buf, "all");
			lab[ng] = malloc(strlen(buf) + 1);
			if (lab[ng])
				strcpy(lab[ng], buf);
			ng++;
		}
		p[i].r->group = ng - 1;
	}
	free(p);
	*labels = lab;
	return ng;
}

void an_labels_free(char **labels, int ng)
{
	for (int i = 0; labels && i < ng; i++)
		free(labels[i]);
	free(labels);
}

/* ---- results ---- */

/* The columns analysis_all has besides the grouping keys' (adb.h). */
static const char *const FIXED[] = {"campaign", "tool", "version", "grp", "key", "value", "lo", "hi", "n", "created",
				    "def", NULL};
/* The keys campaigns sweep most: their columns exist whichever tool ran first, so a
 * query that names them never fails on a table without them. */
static const char *const COMMON_KEYS[] = {"radius_ratio", "depth", "width", "frequency", "amplitude", "n_grains",
					  NULL};

int adb_key_column(const char *key)
{
	for (int i = 0; FIXED[i]; i++)
		if (!strcmp(FIXED[i], key))
			return 0;
	return *key != 0;
}

/* "name" quoted as an SQL identifier into buf */
static void ident(char *buf, size_t n, const char *name)
{
	size_t l = 0;
	if (n < 3)
		return;
	buf[l++] = '"';
	for (; *name && l + 3 < n; name++) {
		if (*name == '"')
			buf[l++] = '"';
		buf[l++] = *name;
	}
	buf[l++] = '"';
	buf[l] = 0;
}

/* The column of a grouping key, added to a table that has none yet (a table written
 * before the tools stored their keys, or by a tool grouping by other keys). */
static int add_column(adb *d, const char *key, sb_err *e)
{
	if (!adb_key_column(key) || has(d, "analysis_all", key))
		return 0;
	char q[200], sql[300];
	ident(q, sizeof q, key);
	snprintf(sql, sizeof sql, "ALTER TABLE analysis_all ADD COLUMN %s", q);
	return sql_script(&d->db, sql, e);
}

static void now_utc(char now[32])
{
	time_t t = time(NULL);
	struct tm tm;
	gmtime_r(&t, &tm);
	strftime(now, 32, "%Y-%m-%dT%H:%M:%SZ", &tm);
}

/* The definition being stored into d->def: an earlier one of the same campaign, tool,
 * version and options deleted with its rows (a rerun replaces its own), a new one
 * recorded (its id the largest yet: the newest). */
static int define(adb *d, const char *campaign, const char *tool, const char *version, const char *options,
		  sb_err *e)
{
	static const char *const del[] = {
		"DELETE FROM analysis_all WHERE def IN (SELECT id FROM analysis_def WHERE campaign = ? AND tool = ?"
		" AND version IS ? AND options IS ?)",
		"DELETE FROM analysis_run WHERE def IN (SELECT id FROM analysis_def WHERE campaign = ? AND tool = ?"
		" AND version IS ? AND options IS ?)",
		"DELETE FROM analysis_def WHERE campaign = ? AND tool = ? AND version IS ? AND options IS ?"};
	for (size_t i = 0; i < sizeof del / sizeof *del; i++)
		if (sql_exec(&d->db, e, NULL, del[i], "tttt", campaign, tool, version, options))
			return e->code;
	char now[32];
	now_utc(now);
	if (sql_exec(&d->db, e, NULL,
		     "INSERT INTO analysis_def(campaign, tool, version, options, build, created) VALUES (?, ?, ?, ?, ?, ?)",
		     "tttttt", campaign, tool, version, options, prov_version(), now))
		return e->code;
	d->def = (long long)sqlite3_last_insert_rowid(d->db.h);
	return 0;
}

int adb_store_begin(adb *d, const char *campaign, const char *tool, const char *version, const char *options,
		    char keys[][48], int nk, sb_err *e)
{
	if (sql_script(&d->db, "BEGIN IMMEDIATE", e))
		return e->code;
	sqlite3_stmt *st = NULL;
	if (schema_analysis(&d->db, e))
		goto fail;
	for (int i = 0; COMMON_KEYS[i]; i++)
		if (add_column(d, COMMON_KEYS[i], e))
			goto fail;
	for (int k = 0; k < nk; k++)
		if (add_column(d, keys[k], e))
			goto fail;
	if (define(d, campaign, tool, version, options, e))
		goto fail;
	if (sqlite3_prepare_v2(d->db.h,
			       "INSERT OR REPLACE INTO analysis_run(def, campaign, tool, run, key, value, class)"
			       " VALUES (?, ?, ?, ?, ?, ?, ?)", -1, &d->rins, NULL) != SQLITE_OK) {
		dberr(d, e);
		goto fail;
	}
	/* the grouping keys' columns follow the fixed ten; a key without a column (one
	 * named like a fixed column) is bound nowhere */
	char sql[4096] = "INSERT OR REPLACE INTO analysis_all(campaign, tool, version, grp, key, value, lo, hi, n, created, def";
	size_t l = strlen(sql);
	d->nk = 0;
	for (int k = 0; k < nk && k < AN_ADB_MAXKEYS; k++) {
		d->col[k] = 0;
		if (!adb_key_column(keys[k]))
			continue;
		char q[200];
		ident(q, sizeof q, keys[k]);
		l += (size_t)snprintf(sql + l, sizeof sql - l, ", %s", q);
		d->col[k] = 1;
	}
	d->nk = nk < AN_ADB_MAXKEYS ? nk : AN_ADB_MAXKEYS;
	l += (size_t)snprintf(sql + l, sizeof sql - l, ") VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?");
	for (int k = 0; k < d->nk; k++)
		if (d->col[k])
			l += (size_t)snprintf(sql + l, sizeof sql - l, ", ?");
	snprintf(sql + l, sizeof sql - l, ")");
	if (l >= sizeof sql - 2 || sqlite3_prepare_v2(d->db.h, sql, -1, &d->ins, NULL) != SQLITE_OK) {
		dberr(d, e);
		goto fail;
	}
	return 0;
fail:
	sqlite3_finalize(st);
	sqlite3_finalize(d->rins);
	d->rins = NULL;
	sqlite3_exec(d->db.h, "ROLLBACK", NULL, NULL, NULL);
	return e->code;
}

/* A parameter's text as the value the param table holds: an integer, a real or text
 * (so radius_ratio = 2 matches 2.0 and depth = 1 is 1); NULL when missing. */
static void bind_typed(sqlite3_stmt *st, int k, const char *v)
{
	char *end;
	if (!v || !*v) {
		sqlite3_bind_null(st, k);
		return;
	}
	errno = 0;
	const long long i = strtoll(v, &end, 10);
	if (!*end && !errno) {
		sqlite3_bind_int64(st, k, i);
		return;
	}
	const double x = strtod(v, &end);
	if (!*end && isfinite(x))
		sqlite3_bind_double(st, k, x);
	else
		sqlite3_bind_text(st, k, v, -1, SQLITE_TRANSIENT);
}

static void bind_real(sqlite3_stmt *st, int k, double v)
{
	if (isfinite(v))
		sqlite3_bind_double(st, k, v);
	else
		sqlite3_bind_null(st, k);
}

int adb_store(adb *d, const char *campaign, const char *tool, const char *version, const char *grp,
	      const char *const *vals, const char *key, double value, double lo, double hi, long n, sb_err *e)
{
	char now[32];
	now_utc(now);
	sqlite3_stmt *st = d->ins;
	sqlite3_reset(st);
	sqlite3_bind_text(st, 1, campaign, -1, SQLITE_TRANSIENT);
	sqlite3_bind_text(st, 2, tool, -1, SQLITE_TRANSIENT);
	sqlite3_bind_text(st, 3, version, -1, SQLITE_TRANSIENT);
	sqlite3_bind_text(st, 4, grp, -1, SQLITE_TRANSIENT);
	sqlite3_bind_text(st, 5, key, -1, SQLITE_TRANSIENT);
	bind_real(st, 6, value);
	bind_real(st, 7, lo);
	bind_real(st, 8, hi);
	sqlite3_bind_int64(st, 9, n);
	sqlite3_bind_text(st, 10, now, -1, SQLITE_TRANSIENT);
	sqlite3_bind_int64(st, 11, d->def);
	for (int k = 0, c = 12; k < d->nk; k++)
		if (d->col[k])
			bind_typed(st, c++, vals ? vals[k] : NULL);
	if (sqlite3_step(st) != SQLITE_DONE)
		return dberr(d, e);
	return 0;
}

int adb_store_run(adb *d, const char *campaign, const char *tool, const char *run, const char *key, double value,
		  const char *cls, sb_err *e)
{
	sqlite3_stmt *st = d->rins;
	sqlite3_reset(st);
	sqlite3_bind_int64(st, 1, d->def);
	sqlite3_bind_text(st, 2, campaign, -1, SQLITE_TRANSIENT);
	sqlite3_bind_text(st, 3, tool, -1, SQLITE_TRANSIENT);
	sqlite3_bind_text(st, 4, run, -1, SQLITE_TRANSIENT);
	sqlite3_bind_text(st, 5, key, -1, SQLITE_TRANSIENT);
	bind_real(st, 6, value);
	if (cls)
		sqlite3_bind_text(st, 7, cls, -1, SQLITE_TRANSIENT);
	else
		sqlite3_bind_null(st, 7);
	if (sqlite3_step(st) != SQLITE_DONE)
		return dberr(d, e);
	return 0;
}

int adb_store_end(adb *d, int ok, sb_err *e)
{
	if (d->ins)
		sqlite3_finalize(d->ins);
	if (d->rins)
		sqlite3_finalize(d->rins);
	d->ins = d->rins = NULL;
	/* a database the driver wrote shows the per-run observables in its runs view */
	if (ok && has(d, "run", NULL) && schema_runs(&d->db, e))
		ok = 0;
	if (!ok) {
		sqlite3_exec(d->db.h, "ROLLBACK", NULL, NULL, NULL);
		return e->code;
	}
	return sql_script(&d->db, "COMMIT", e);
}
