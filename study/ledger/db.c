/* db.c - the study database opened, and the few writes the driver makes (its
 * schema is lib/schema.c). */
#include "db.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "schema.h"
#include "ratio.h"
#include "rowseal.h"

/* A study database that lacks some of the driver's run tables (schema_lost) is
 * repaired, opened to write, as the files allow (docs/database.md, "A damaged database"): a table gone is created anew
 * and refilled from the campaign file (campaign, param: driver_record) or the run files
 * (result: the sweep); without run or attempt the rows of the four tables that hang
 * together by run are cleared and rebuilt from the run files as for a deleted database
 * (the attempts that left no file are lost then, as there). */
static int repair(st_db *d, const char *lost, sb_err *e)
{
	char list[160];
	snprintf(list, sizeof list, ", %s,", lost);
	if (strstr(list, " run,") || strstr(list, " attempt,")) {
		if (sql_script(d, "DELETE FROM attempt; DELETE FROM result; DELETE FROM param; DELETE FROM run", e))
			return e->code;
		snprintf(d->note, sizeof d->note,
			 "%s: lacked table %s: the runs of every campaign in it are recorded again, each by study run "
			 "on its campaign file, from the run files (attempts that left no file are lost)", d->path, lost);
	} else {
		snprintf(d->note, sizeof d->note, "%s: lacked table %s: made again, its rows from the campaign and "
			 "run files as study run on each campaign file reads them", d->path, lost);
	}
	return 0;
}

int db_open(st_db *d, const char *path, int writable, sb_err *e)
{
	int flags = writable ? SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE : SQLITE_OPEN_READONLY;
	if (sql_open(d, path, flags, e))
		return e->code;
	/* a wait for another process's lock is said after SQL_SAY_MS, with its holder */
	sql_on_wait(d, sql_say_stderr, "study");
	if (!writable)
		return 0;
	if (sql_script(d, "PRAGMA journal_mode = WAL; PRAGMA synchronous = NORMAL;", e))
		return e->code;
	if (db_begin(d, e))
		return e->code;
	char lost[128];
	if (schema_lost(d, 1, lost, sizeof lost, e) || schema_study(d, e) || (lost[0] && repair(d, lost, e))) {
		db_rollback(d);
		return e->code;
	}
	return db_commit(d, e);
}

void db_close(st_db *d)
{
	sql_close(d);
}

int db_begin(st_db *d, sb_err *e)
{
	return sql_script(d, "BEGIN IMMEDIATE", e);
}

int db_commit(st_db *d, sb_err *e)
{
	return sql_script(d, "COMMIT", e);
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

/* is w one of the blank-separated words of list? */
static int has_word(const char *list, const char *w)
{
	const size_t n = strlen(w);
	for (const char *p = list; (p = strstr(p, w)); p += n)
		if ((p == list || p[-1] == ' ') && (p[n] == ' ' || !p[n]))
			return 1;
	return 0;
}

int db_campaign_put(st_db *d, const campaign *c, const char *now, sb_err *e)
{
	char axes[2048] = "", seed[32];
	size_t l = 0;
	/* the scene keys the axes set: a derived axis (gamma, velocity, a ratio) by the keys
	 * it sets, which the runs record in the param table and the tools group by */
	for (int i = 0; i < c->naxes && l < sizeof axes; i++) {
		const char *k = c->axes[i].key, *k2 = NULL;
		const sb_ratio *ra = ratio_find(k);
		if (ra)
			k = ra->sets;
		else if (campaign_key_derived(k)) {
			k = c->derive == CP_DERIVE_AMPLITUDE ? "amplitude" : "frequency";
			k2 = c->derive == CP_DERIVE_BOTH ? "amplitude" : NULL;
		}
		/* once: gamma and velocity both set frequency and amplitude */
		for (const char *w = k; w && l < sizeof axes; w = w == k ? k2 : NULL)
			if (!has_word(axes, w))
				l += (size_t)snprintf(axes + l, sizeof axes - l, "%s%s", l ? " " : "", w);
	}
	/* an [onset] search varies both too: the analysis tools group by the swept keys */
	if (c->onset.line && l < sizeof axes)
		snprintf(axes + l, sizeof axes - l, "%sfrequency seed", l ? " " : "");
	/* and replicates = auto the replicate, as replicates = N would */
	if (c->autorep.on && l < sizeof axes)
		snprintf(axes + l, sizeof axes - l, "%sseed", l ? " " : "");
	snprintf(seed, sizeof seed, "%llu", c->seed);
	return sql_exec(d, e, NULL,
		       "INSERT INTO campaign(name, description, file, scene_file, seed, seeds, axes, created, updated)"
		       " VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?8) ON CONFLICT(name) DO UPDATE SET"
		       " description = ?2, file = ?3, scene_file = ?4, seed = ?5, seeds = ?6, axes = ?7, updated = ?8",
		       "tttttttt", c->name, c->description, c->path, c->scene_file, seed,
		       c->seeds == CP_SEEDS_LITERAL ? "literal" : "derived", axes, now);
}

int db_run_add(st_db *d, const campaign *c, const grid_run *r, const sb_scene *s, const char *now, sb_err *e)
{
	if (sql_exec(d, e, NULL,
		    "INSERT OR IGNORE INTO run(campaign, id, replicate, seed, cache_key, added)"
		    " VALUES (?, ?, ?, ?, ?, ?)",
		    "ttllt" "t", c->name, r->id, r->replicate, r->seed, r->cache_key, now))
		return e->code;
	if (sqlite3_changes(d->h) == 0) { /* known run: its parameters are recorded, unless lost */
		sqlite3_stmt *q;
		if (sql_exec(d, e, NULL, "UPDATE run SET current = 1 WHERE campaign = ? AND id = ? AND current = 0", "tt",
			     c->name, r->id) ||
		    sql_exec(d, e, &q, "SELECT EXISTS (SELECT 1 FROM param WHERE campaign = ? AND run = ?)", "tt", c->name,
			     r->id))
			return e->code;
		const int has = sqlite3_step(q) == SQLITE_ROW && sqlite3_column_int(q, 0);
		if (sql_done(d, q, e) || has)
			return e->code;
	}
	size_t n;
	const sb_param *t = params_table(&n);
	sqlite3_stmt *st;
	if (sql_exec(d, e, &st, "INSERT OR REPLACE INTO param(campaign, run, key, value) VALUES (?, ?, ?, ?)", "tt",
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
		int rc = sqlite3_step(st);
		if (rc != SQLITE_DONE) {
			sql_failed(d, rc, e);
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
	if (sql_exec(d, e, &st, "SELECT state, attempts FROM run WHERE campaign = ? AND id = ?", "tt", camp, id))
		return e->code;
	if (sqlite3_step(st) == SQLITE_ROW) {
		snprintf(state, len, "%s", (const char *)sqlite3_column_text(st, 0));
		*attempts = (long)sqlite3_column_int64(st, 1);
	}
	return sql_done(d, st, e);
}

/* An attempt's row and its run's new state. Its start is the run's start when the
 * driver saw the attempt begin (the run is 'running'), else `started` (the engine's
 * own start from the run file, or NULL: not known). `now` may be NULL: the end is not
 * known. */
static int attempt_row(st_db *d, const char *camp, const char *id, long exit_code, const char *status,
		       const char *message, const char *host, const char *started, const char *now, int has_wall,
		       double wall, const db_usage *u, const char *state, sb_err *e)
{
	if (sql_exec(d, e, NULL,
		    "INSERT INTO attempt(campaign, run, n, host, exit_code, status, message, started, finished, wall_seconds,"
		    " cpu_seconds, max_rss_kb)"
		    " VALUES (?1, ?2, (SELECT attempts + 1 FROM run WHERE campaign = ?1 AND id = ?2), ?3, ?4, ?5, ?6,"
		    " COALESCE((SELECT started FROM run WHERE campaign = ?1 AND id = ?2 AND state = 'running'), ?7),"
		    " ?8, ?9, ?10, ?11)",
		    "tttlttttDDL", camp, id, host, exit_code, status, message, started, now, has_wall, wall, u != NULL,
		    u ? u->cpu_seconds : 0, u != NULL, u ? u->max_rss_kb : 0))
		return e->code;
	return sql_exec(d, e, NULL,
		       "UPDATE run SET attempts = attempts + 1, state = ?3, host = ?4, finished = ?5"
		       " WHERE campaign = ?1 AND id = ?2",
		       "ttttt", camp, id, state, host, now);
}

int db_attempt(st_db *d, const char *camp, const char *id, long exit_code, const char *status,
	       const char *message, const char *host, const db_usage *u, const char *now, const char *state, sb_err *e)
{
	return attempt_row(d, camp, id, exit_code, status, message, host, NULL, now, 0, 0, u, state, e);
}

int db_attempt_kept(st_db *d, const char *camp, const char *id, const h5sum *s, const char *status,
		    const char *message, const char *now, sb_err *e)
{
	const char *end = s ? h5sum_text(s, "end_time") : "";
	const char *start = s ? h5sum_text(s, "start_time") : "";
	return attempt_row(d, camp, id, s ? h5sum_int(s, "exit_code") : SB_EIO, status, message,
			   s ? h5sum_text(s, "host") : "", start[0] ? start : NULL, end[0] ? end : now, s != NULL,
			   s ? h5sum_real(s, "wall_seconds") : 0, NULL, "pending", e);
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
	if (sql_exec(d, e, &st, sql, "tt", camp, id))
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
	if (rc != SQLITE_DONE)
		sql_failed(d, rc, e);
	sqlite3_finalize(st);
	/* and the seal of the rows as they now are, which every reader checks (rowseal.h) */
	return e->code ? e->code : rowseal_put(d, camp, id, e);
}

int db_ingest(st_db *d, const char *camp, const char *id, const h5sum *s, const db_usage *u, const char *now,
	      sb_err *e)
{
	const char *status = h5sum_text(s, "status");
	/* the run finished when the engine wrote its file, not when the driver read it */
	const char *end = h5sum_text(s, "end_time");
	/* a run no driver saw start (a database rebuilt from the files): it started when
	 * its file says the engine did */
	const char *start = h5sum_text(s, "start_time");
	/* a worker launched again for a run whose file an earlier one had finished (the
	 * driver killed before it read it) marked the run started after the file's end:
	 * the file's start is the truth then, for the run and so for this attempt */
	if (start[0] && end[0] &&
	    sql_exec(d, e, NULL, "UPDATE run SET started = ?3 WHERE campaign = ?1 AND id = ?2 AND started > ?4",
		     "tttt", camp, id, start, end))
		return e->code;
	if (attempt_row(d, camp, id, h5sum_int(s, "exit_code"), status, h5sum_text(s, "message"),
			h5sum_text(s, "host"), start[0] ? start : NULL, end[0] ? end : now, 1,
			h5sum_real(s, "wall_seconds"), u, strcmp(status, "ok") ? "failed" : "done", e))
		return e->code;
	if (start[0] && sql_exec(d, e, NULL, "UPDATE run SET started = ?3 WHERE campaign = ?1 AND id = ?2 AND started IS NULL",
				"ttt", camp, id, start))
		return e->code;
	return db_result_put(d, camp, id, s, e);
}
