/* sql.h - the one way SQL reaches SQLite, for the study database's writer (bin/study)
 * and its readers (bin/study's reports, the analysis tools): an open database, prepared
 * statements bound from a format, scripts, and the columns a table has. */
#ifndef LIB_SQL_H
#define LIB_SQL_H

#include <sqlite3.h>
#include <stddef.h>

#include "err.h"

typedef struct sql_db {
	sqlite3 *h;
	char path[1024]; /* named in every message */
} sql_db;

/* Open path with SQLITE_OPEN_* flags; a reader waits up to a minute for a writer's
 * transaction. Refused when something other than a regular file stands at path or at
 * a side file (-journal, -wal, -shm), and, without SQLITE_OPEN_CREATE, when the file
 * is empty. */
int sql_open(sql_db *d, const char *path, int flags, sb_err *e);
void sql_close(sql_db *d);

/* Prepared statement, bound from fmt: 't' text (NULL: null), 'l' long, 'd' double, 'n'
 * null (no argument), 'D' double or null when the paired int is 0 (int ok, double v).
 * Runs it to completion when out is NULL; else returns the statement in *out. */
int sql_exec(sql_db *d, sb_err *e, sqlite3_stmt **out, const char *sql, const char *fmt, ...);
/* Statements separated by semicolons, no parameters (a schema, BEGIN, COMMIT). */
int sql_script(sql_db *d, const char *sql, sb_err *e);
/* Columns of a table, as "a,b,c," ("" when the table does not exist). */
void sql_columns(sql_db *d, const char *table, char *out, size_t len);
/* A column added since the table was first created (older databases lack it): added
 * with its declaration decl unless the table has it. */
int sql_ensure_column(sql_db *d, const char *table, const char *col, const char *decl, sb_err *e);

#endif
