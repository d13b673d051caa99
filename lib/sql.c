/* sql.c - the one way SQL reaches SQLite (sql.h). */
#include "sql.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "fsutil.h"

/* The database and the files SQLite keeps beside it: each is nothing or a regular file
 * (docs/database.md). SQLite writes its pages into whatever it opens: a
 * device would take them (a block device's first pages), a FIFO would hang every
 * reader and writer, a link would put the campaign's record elsewhere. */
static int sql_paths(const char *path, sb_err *e)
{
	static const char *const side[] = {"", "-journal", "-wal", "-shm"};
	for (size_t i = 0; i < sizeof side / sizeof *side; i++) {
		char p[1100];
		const char *kind;
		snprintf(p, sizeof p, "%s%s", path, side[i]);
		if (!fs_replaceable(p, &kind))
			return sb_errf(e, SB_EIO, "%s: %s stands there, not a regular file: the database %s is not opened "
				       "(remove it)", p, kind, path);
	}
	return 0;
}

/* A reader's database that holds nothing: a file of 0 bytes (and no write-ahead log
 * holding its pages) opens as a database without tables. */
static int sql_empty(const char *path)
{
	char wal[1100];
	struct stat st;
	snprintf(wal, sizeof wal, "%s-wal", path);
	return stat(path, &st) == 0 && st.st_size == 0 && (stat(wal, &st) != 0 || st.st_size == 0);
}

int sql_open(sql_db *d, const char *path, int flags, sb_err *e)
{
	memset(d, 0, sizeof *d);
	snprintf(d->path, sizeof d->path, "%s", path);
	if (sql_paths(path, e))
		return e->code;
	if (!(flags & SQLITE_OPEN_CREATE) && sql_empty(path))
		return sb_errf(e, SB_EUSAGE, "%s: an empty file (0 bytes): no campaigns in it (study run makes the "
			       "database)", path);
	/* NOFOLLOW: a link that comes between the check and the open is refused too */
	if (sqlite3_open_v2(path, &d->h, flags | SQLITE_OPEN_NOFOLLOW, NULL) != SQLITE_OK) {
		sb_errf(e, SB_EIO, "%s: cannot open database: %s", path, d->h ? sqlite3_errmsg(d->h) : "out of memory");
		sqlite3_close(d->h);
		d->h = NULL;
		return e->code;
	}
	/* readers wait for the driver's short write transactions instead of failing */
	sqlite3_busy_timeout(d->h, 60000);
	return 0;
}

void sql_close(sql_db *d)
{
	if (d->h)
		sqlite3_close(d->h);
	d->h = NULL;
}

int sql_exec(sql_db *d, sb_err *e, sqlite3_stmt **out, const char *sql, const char *fmt, ...)
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

int sql_script(sql_db *d, const char *sql, sb_err *e)
{
	char *msg = NULL;
	if (sqlite3_exec(d->h, sql, NULL, NULL, &msg) != SQLITE_OK) {
		sb_errf(e, SB_EIO, "%s: %s", d->path, msg ? msg : sqlite3_errmsg(d->h));
		sqlite3_free(msg);
		return e->code;
	}
	return 0;
}

void sql_columns(sql_db *d, const char *table, char *out, size_t len)
{
	sqlite3_stmt *st;
	sb_err e = {0};
	size_t l = 0;
	out[0] = 0;
	char sql[128];
	snprintf(sql, sizeof sql, "PRAGMA table_info(%s)", table);
	if (sql_exec(d, &e, &st, sql, ""))
		return;
	while (sqlite3_step(st) == SQLITE_ROW && l < len)
		l += (size_t)snprintf(out + l, len - l, "%s,", (const char *)sqlite3_column_text(st, 1));
	sqlite3_finalize(st);
}

int sql_ensure_column(sql_db *d, const char *table, const char *col, const char *decl, sb_err *e)
{
	char cols[4096] = ",", want[128], sql[256];
	sql_columns(d, table, cols + 1, sizeof cols - 1);
	snprintf(want, sizeof want, ",%s,", col);
	if (strstr(cols, want))
		return 0;
	snprintf(sql, sizeof sql, "ALTER TABLE %s ADD COLUMN %s %s", table, col, decl);
	return sql_script(d, sql, e);
}
