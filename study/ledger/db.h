/* db.h - the study database (SQLite): campaigns, runs, their parameters, every
 * attempt, results and packing caches. Only the driver writes it; WAL lets sqlite3
 * read while a campaign runs. The schema (lib/schema.c) is documented in
 * docs/database.md. */
#ifndef ST_DB_H
#define ST_DB_H

#include <sqlite3.h>

#include "err.h"
#include "h5sum.h"
#include "sql.h"
#include "campaign/grid.h"

/* The study database as lib/sql.h opens it; statements go through sql_exec. */
typedef sql_db st_db;

/* Open (creating the schema and views when writable). */
int db_open(st_db *d, const char *path, int writable, sb_err *e);
void db_close(st_db *d);

/* BEGIN IMMEDIATE / COMMIT / ROLLBACK: writers take the lock up front, so a reader
 * never makes a write transaction fail half-way. */
int db_begin(st_db *d, sb_err *e);
int db_commit(st_db *d, sb_err *e);
void db_rollback(st_db *d);

int db_campaign_put(st_db *d, const campaign *c, const char *now, sb_err *e);
/* Insert a run and its parameters unless it is already known (extension keeps rows). */
int db_run_add(st_db *d, const campaign *c, const grid_run *r, const sb_scene *s, const char *now, sb_err *e);
/* State of a run ("pending", "running", "done", "failed"), attempts; state "" if unknown. */
int db_run_state(st_db *d, const char *camp, const char *id, char *state, size_t len, long *attempts,
		 sb_err *e);

/* What an attempt's engine used, as its worker measured it (wait4): CPU seconds (user
 * + system) and peak resident memory in KiB. A NULL db_usage: not known (no worker
 * reported it: an attempt recorded from the files alone, or whose worker died). */
typedef struct db_usage {
	double cpu_seconds;
	long max_rss_kb;
} db_usage;

/* Record a finished attempt from its output file (state done/failed by its status). */
int db_ingest(st_db *d, const char *camp, const char *id, const h5sum *s, const db_usage *u, const char *now,
	      sb_err *e);
/* Write (or rewrite) only the result row of a run from its file: a database rebuilt
 * or written by another version gets its results back from the files. */
int db_result_put(st_db *d, const char *camp, const char *id, const h5sum *s, sb_err *e);
/* Record an attempt that left no output file; state is the run's new state. */
/* An earlier attempt of a run, recovered from the file it left in failed/ or damaged/
 * (s NULL: the file is unreadable); the run stays pending for the attempts after it. */
int db_attempt_kept(st_db *d, const char *camp, const char *id, const h5sum *s, const char *status,
		    const char *message, const char *now, sb_err *e);
int db_attempt(st_db *d, const char *camp, const char *id, long exit_code, const char *status,
	       const char *message, const char *host, const db_usage *u, const char *now, const char *state, sb_err *e);

void db_now(char *buf, size_t len);

#endif
