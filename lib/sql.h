/* sql.h - the one way SQL reaches SQLite, for the study database's writer (bin/study)
 * and its readers (bin/study's reports, the analysis tools): an open database, prepared
 * statements bound from a format, scripts, and the columns a table has. */
#ifndef LIB_SQL_H
#define LIB_SQL_H

#include <sqlite3.h>
#include <stddef.h>

#include "err.h"

/* What to do with a corrupt database (every message that names one ends with it). */
#define SQL_REBUILD                                                                                          \
	"move it aside with its -wal and -shm files and run study run on each campaign file: it is rebuilt "   \
	"from the run files (docs/database.md, \"A damaged database\")"

/* How long a statement waits for another process's transaction before it fails, and
 * after how long the wait is said (sql_on_wait). */
enum { SQL_WAIT_MS = 60000, SQL_SAY_MS = 2000 };

typedef struct sql_db {
	sqlite3 *h;
	char path[1024]; /* named in every message */
	char note[1400]; /* what opening it repaired (study/ledger/db.c), for the caller to say */
	/* the wait for a lock held elsewhere (sql.c), allocated: SQLite's busy handler
	 * keeps its address, which a copy of this struct must not change */
	struct sql_wait *wait;
} sql_db;

/* Open path with SQLITE_OPEN_* flags; a statement waits up to SQL_WAIT_MS for another
 * process's transaction, then fails naming the process that holds the lock. Refused
 * when something other than a regular file stands at path or at a side file
 * (-journal, -wal, -shm), and, without SQLITE_OPEN_CREATE, when the file is empty. */
int sql_open(sql_db *d, const char *path, int flags, sb_err *e);
/* Tell f(ctx, message) once per wait when a statement has waited SQL_SAY_MS for a lock
 * (the message names the holder where the system says it); sql_say_stderr prints it as
 * "CTX: message" on stderr, for a program's main to choose. */
void sql_on_wait(sql_db *d, void (*f)(void *ctx, const char *msg), void *ctx);
void sql_say_stderr(void *ctx, const char *msg);
/* Who holds a lock on the database or its -shm/-journal file: "process PID (COMMAND)",
 * or "" when the system does not say (/proc/locks). */
void sql_lock_holder(const sql_db *d, char *out, size_t len);
void sql_close(sql_db *d);

/* Prepared statement, bound from fmt: 't' text (NULL: null), 'l' long, 'd' double, 'n'
 * null (no argument), 'D' double or null when the paired int is 0 (int ok, double v), 'L'
 * the same for a long (int ok, long v).
 * Runs it to completion when out is NULL; else returns the statement in *out. */
int sql_exec(sql_db *d, sb_err *e, sqlite3_stmt **out, const char *sql, const char *fmt, ...);
/* Statements separated by semicolons, no parameters (a schema, BEGIN, COMMIT). */
int sql_script(sql_db *d, const char *sql, sb_err *e);
/* Finalize a statement the caller stepped: an error of its last step (a corrupt page
 * read half-way through the rows) into e, as sql_exec's own. Returns e->code. */
int sql_done(sql_db *d, sqlite3_stmt *st, sb_err *e);
/* rc of a call the caller made (sqlite3_step, sqlite3_prepare_v2) into e, as sql_exec's
 * errors: nothing for OK, ROW and DONE. Returns e->code. */
int sql_failed(sql_db *d, int rc, sb_err *e);
/* The root page of every table read (sql_open does): a corrupt one named so in e. */
int sql_probe(sql_db *d, sb_err *e);
/* PRAGMA quick_check: 1 when the database is corrupt (why: the first findings), 0 when
 * it is sound. Costs a read of the whole file: for a failure, never on every open. */
int sql_check(sql_db *d, char *why, size_t len);
/* Columns of a table, as "a,b,c," ("" when the table does not exist). */
void sql_columns(sql_db *d, const char *table, char *out, size_t len);
/* A column added since the table was first created (older databases lack it): added
 * with its declaration decl unless the table has it. */
int sql_ensure_column(sql_db *d, const char *table, const char *col, const char *decl, sb_err *e);

#endif
