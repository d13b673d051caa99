/* sql.c - the one way SQL reaches SQLite (sql.h). */
#include "sql.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "fsutil.h"

static int sql_fail(sql_db *d, int rc, sb_err *e);

int sql_check(sql_db *d, char *why, size_t len)
{
	sqlite3_stmt *st;
	why[0] = 0;
	/* quick_check: every page's structure and every row's format, not the indexes'
	 * contents (those integrity_check adds); half a second on an 80 MB database */
	int rc = sqlite3_prepare_v2(d->h, "PRAGMA quick_check(3)", -1, &st, NULL);
	if (rc != SQLITE_OK) {
		snprintf(why, len, "%s", sqlite3_errmsg(d->h));
		return (rc & 0xff) == SQLITE_CORRUPT || (rc & 0xff) == SQLITE_NOTADB;
	}
	size_t l = 0;
	int bad = 0;
	while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
		const char *t = (const char *)sqlite3_column_text(st, 0);
		/* findings, not the heading of each attached database before them */
		if (t && !strncmp(t, "*** in database ", 16))
			t = strchr(t, '\n') ? strchr(t, '\n') + 1 : "";
		if (t && *t && strcmp(t, "ok") && l < len) {
			l += (size_t)snprintf(why + l, len - l, "%s%s", bad ? "; " : "", t);
			bad = 1;
		}
		/* one line: a message that names the fault in a sentence */
		for (char *c = why; *c; c++)
			if (*c == '\n')
				*c = ' ';
	}
	if (rc != SQLITE_DONE && !bad) {
		snprintf(why, len, "%s", sqlite3_errmsg(d->h));
		bad = (rc & 0xff) == SQLITE_CORRUPT || (rc & 0xff) == SQLITE_NOTADB;
	}
	sqlite3_finalize(st);
	return bad;
}

/* The one place an SQLite failure becomes an error: a corrupt database, or one that
 * lacks a table, is named so with what to do, not in SQLite's words alone
 * (docs/database.md, "A damaged database"). */
static int sql_fail(sql_db *d, int rc, sb_err *e)
{
	char msg[512], why[512];
	snprintf(msg, sizeof msg, "%s", sqlite3_errmsg(d->h));
	int code = rc & 0xff;
	if (code == SQLITE_CORRUPT || code == SQLITE_NOTADB) {
		sql_check(d, why, sizeof why);
		int more = why[0] && strcmp(why, msg);
		return sb_errf(e, SB_EIO, "%s: the database is corrupt (%s%s%s): %s", d->path, msg,
			       more ? "; quick_check: " : "", more ? why : "", SQL_REBUILD);
	}
	if (code == SQLITE_BUSY) {
		char who[400];
		sql_lock_holder(d, who, sizeof who);
		return sb_errf(e, SB_EIO, "%s: %s: waited %d s for %s, which holds the database's lock; try again when it "
			       "has ended", d->path, msg, SQL_WAIT_MS / 1000, who[0] ? who : "another process");
	}
	if (!strncmp(msg, "no such table: ", 15))
		return sb_errf(e, SB_EIO, "%s: %s: the database lacks a table it should have (dropped, or not a study "
			       "database): study run on the campaign file rebuilds it from the run files (docs/database.md, "
			       "\"A damaged database\")", d->path, msg);
	return sb_errf(e, SB_EIO, "%s: %s", d->path, msg);
}

static long long now_ms(void)
{
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return (long long)t.tv_sec * 1000 + t.tv_nsec / 1000000;
}

void sql_lock_holder(const sql_db *d, char *out, size_t len)
{
	out[0] = 0;
	/* SQLite's locks are POSIX record locks on the database file (rollback journal)
	 * or on its -shm file (WAL): /proc/locks lists each with its pid and the file's
	 * device and inode */
	unsigned long long ino[3];
	int ni = 0;
	const char *suffix[3] = {"", "-shm", "-journal"};
	for (int k = 0; k < 3; k++) {
		char p[1100];
		struct stat st;
		snprintf(p, sizeof p, "%s%s", d->path, suffix[k]);
		if (stat(p, &st) == 0)
			ino[ni++] = (unsigned long long)st.st_ino;
	}
	FILE *f = fopen("/proc/locks", "r");
	if (!f)
		return;
	char line[256];
	long me = (long)getpid(), pid = 0;
	while (!pid && fgets(line, sizeof line, f)) {
		long p;
		unsigned long long i;
		char type[16];
		/* "1: POSIX  ADVISORY  WRITE 1234 08:01:5678 0 EOF" (a "->" marks a waiter) */
		if (strstr(line, "->") || sscanf(line, "%*d: %15s %*s %*s %ld %*x:%*x:%llu", type, &p, &i) != 3)
			continue;
		for (int k = 0; k < ni; k++)
			if (i == ino[k] && p != me)
				pid = p;
	}
	fclose(f);
	if (!pid)
		return;
	char cp[64], cmd[256] = "";
	snprintf(cp, sizeof cp, "/proc/%ld/cmdline", pid);
	FILE *c = fopen(cp, "r");
	if (c) {
		size_t n = fread(cmd, 1, sizeof cmd - 1, c);
		fclose(c);
		/* one line: the arguments' NULs and any control character become spaces, and a
		 * long command line is cut */
		for (size_t k = 0; k < n; k++)
			if ((unsigned char)cmd[k] < 0x20)
				cmd[k] = ' ';
		while (n > 0 && cmd[n - 1] == ' ')
			n--;
		cmd[n] = 0;
		if (n > 80)
			snprintf(cmd + 77, sizeof cmd - 77, "...");
	}
	snprintf(out, len, "process %ld%s%s%s", pid, cmd[0] ? " (" : "", cmd, cmd[0] ? ")" : "");
}

struct sql_wait {
	char path[1024];        /* the sql_db's, for the message */
	long long t0;           /* the wait's start (ms, monotonic) */
	int said;               /* told once */
	void (*on_wait)(void *ctx, const char *msg);
	void *ctx;
};

/* SQLite's busy handler: wait with growing naps up to SQL_WAIT_MS, telling on_wait once
 * after SQL_SAY_MS (a reader silent for a minute looks hung). 0 ends the wait: the
 * statement fails with SQLITE_BUSY, and sql_fail names the holder. */
static int sql_busy(void *p, int n)
{
	struct sql_wait *w = p;
	if (n == 0) {
		w->t0 = now_ms();
		w->said = 0;
	}
	long long waited = now_ms() - w->t0;
	if (waited >= SQL_WAIT_MS)
		return 0;
	if (waited >= SQL_SAY_MS && !w->said && w->on_wait) {
		char who[400], msg[1600];
		sql_db d = {.wait = NULL};
		snprintf(d.path, sizeof d.path, "%s", w->path);
		sql_lock_holder(&d, who, sizeof who);
		snprintf(msg, sizeof msg, "%s: waiting for %s, which holds the database's lock (up to %d s)", w->path,
			 who[0] ? who : "another process", SQL_WAIT_MS / 1000);
		w->on_wait(w->ctx, msg);
		w->said = 1;
	}
	sqlite3_sleep(n < 5 ? 1 << n : 50);
	return 1;
}

void sql_on_wait(sql_db *d, void (*f)(void *ctx, const char *msg), void *ctx)
{
	if (d->wait) {
		d->wait->on_wait = f;
		d->wait->ctx = ctx;
	}
}

void sql_say_stderr(void *ctx, const char *msg)
{
	fprintf(stderr, "%s: %s\n", ctx ? (const char *)ctx : "sqlite", msg);
}

int sql_done(sql_db *d, sqlite3_stmt *st, sb_err *e)
{
	int rc = sqlite3_finalize(st);
	if (rc != SQLITE_OK && !e->code)
		return sql_fail(d, rc, e);
	return e->code;
}

int sql_failed(sql_db *d, int rc, sb_err *e)
{
	if (rc == SQLITE_OK || rc == SQLITE_ROW || rc == SQLITE_DONE)
		return e->code;
	return sql_fail(d, rc, e);
}

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
	if (!(d->wait = calloc(1, sizeof *d->wait))) {
		sql_close(d);
		return sb_errf(e, SB_ENOMEM, "%s: out of memory", path);
	}
	snprintf(d->wait->path, sizeof d->wait->path, "%s", d->path);
	sqlite3_busy_handler(d->h, sql_busy, d->wait);
	if (sql_probe(d, e))
		sql_close(d);
	return e->code;
}

int sql_probe(sql_db *d, sb_err *e)
{
	/* the first row of every table, read from its own b-tree (NOT INDEXED: a lookup
	 * by key would read an index and miss the table's pages): a root page zeroed or
	 * overwritten is found on open, for well under a millisecond, where a query of
	 * that table would fail later or, worse, a report of it come out empty */
	sqlite3_stmt *st;
	int rc = sqlite3_prepare_v2(d->h, "SELECT name FROM sqlite_schema WHERE type = 'table' AND name NOT LIKE 'sqlite_%'"
				    " ORDER BY name", -1, &st, NULL);
	if (rc != SQLITE_OK)
		return sql_fail(d, rc, e);
	char names[64][128];
	int n = 0;
	while ((rc = sqlite3_step(st)) == SQLITE_ROW && n < 64)
		snprintf(names[n++], sizeof names[0], "%s", (const char *)sqlite3_column_text(st, 0));
	if (rc != SQLITE_DONE && rc != SQLITE_ROW) {
		sql_fail(d, rc, e);
		sqlite3_finalize(st);
		return e->code;
	}
	sqlite3_finalize(st);
	for (int i = 0; i < n && !e->code; i++) {
		char sql[400], q[300];
		size_t l = 0;
		q[l++] = '"';
		for (const char *c = names[i]; *c && l < sizeof q - 3; c++) {
			if (*c == '"')
				q[l++] = '"';
			q[l++] = *c;
		}
		q[l++] = '"';
		q[l] = 0;
		snprintf(sql, sizeof sql, "SELECT 1 FROM %s NOT INDEXED LIMIT 1", q);
		rc = sqlite3_prepare_v2(d->h, sql, -1, &st, NULL);
		if (rc != SQLITE_OK)
			return sql_fail(d, rc, e);
		rc = sqlite3_step(st);
		sqlite3_finalize(st); /* done reading, before the quick check sql_fail makes */
		if (rc != SQLITE_ROW && rc != SQLITE_DONE)
			sql_fail(d, rc, e);
	}
	return e->code;
}

void sql_close(sql_db *d)
{
	if (d->h)
		sqlite3_close(d->h);
	d->h = NULL;
	free(d->wait);
	d->wait = NULL;
}

int sql_exec(sql_db *d, sb_err *e, sqlite3_stmt **out, const char *sql, const char *fmt, ...)
{
	sqlite3_stmt *st = NULL;
	int prc = sqlite3_prepare_v2(d->h, sql, -1, &st, NULL);
	if (prc != SQLITE_OK)
		return sql_fail(d, prc, e);
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
		case 'L': {
			int okv = va_arg(ap, int);
			long v = va_arg(ap, long);
			if (okv)
				sqlite3_bind_int64(st, k, v);
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
	if (rc != SQLITE_DONE) {
		sql_fail(d, rc, e);
		sqlite3_finalize(st);
		return e->code;
	}
	sqlite3_finalize(st);
	return 0;
}

int sql_script(sql_db *d, const char *sql, sb_err *e)
{
	int rc = sqlite3_exec(d->h, sql, NULL, NULL, NULL);
	if (rc != SQLITE_OK)
		return sql_fail(d, rc, e);
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
