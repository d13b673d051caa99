/* sweep.c - the driver's look at the campaign directory before and after it runs
 * anything: outputs that finished while no driver listened are ingested; every done
 * run's file is read again (a damaged or missing one goes back in the queue); what
 * killed engines left beside finished runs is removed; with --retry-failed, failed
 * runs go back in the queue; a database rebuilt from the files gets its results back. */
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sys/stat.h>

#include "dirs.h"
#include "fsutil.h"
#include "h5sum.h"
#include "layout.h"
#include "drv.h"
#include "job/worker.h"

/* Whatever stands at path (a link itself, not what it points to) moved to keep, only
 * over nothing or a regular file: a node planted at keep is neither replaced nor
 * written (fs_rename_durable). */
static int move_aside(const char *path, const char *keep, sb_err *e)
{
	sb_err re = {0};
	if (fs_rename_durable(path, keep, &re))
		return sb_errf(e, SB_EIO, "%s: cannot move aside: %s", path, re.msg);
	return 0;
}

/* 1 when something stands at path (lstat: a dangling link too) */
static int present(const char *path)
{
	struct stat st;
	return lstat(path, &st) == 0;
}

/* Why a done run's file cannot be its record, or NULL when it can be read (h5sum_read,
 * error in re): missing, or not a regular file at the name (a link to elsewhere, the
 * engine's rule for its outputs, docs/output.md) - moved aside as a damaged file is. */
static const char *done_unreadable(const char *path, const char *id, const char *seal, sb_err *re, char *buf,
				   size_t n)
{
	struct stat st;
	h5sum s;
	if (lstat(path, &st))
		return "the output file is missing";
	if (!S_ISREG(st.st_mode)) {
		snprintf(buf, n, "%s stands at its output file, not a regular file", fs_kind((unsigned)st.st_mode));
		return buf;
	}
	return h5sum_read_sealed(path, id, seal, &s, re) ? re->msg : NULL;
}

/* A done run whose file is damaged or gone: the file moves to damaged/, the attempt
 * is recorded with the reason, the result row goes, and the run is pending again. */
static int requeue_damaged(drv *d, const char *id, long att, const char *why, sb_err *e)
{
	char path[PATHX], keep[PATHX + 64], now[32];
	layout_file(d->dir, 0, id, LAY_OUTPUT, path, sizeof path);
	if (present(path)) {
		layout_sub(d->dir, "damaged", keep, sizeof keep);
		if (dirs_own(keep, e))
			return e->code;
		layout_aside(d->dir, "damaged", id, att, keep, sizeof keep);
		if (move_aside(path, keep, e))
			return e->code;
	}
	fprintf(stderr, "study: %s: run %s was done but %s: run again\n", d->c.name, id, why);
	db_now(now, sizeof now);
	if (db_begin(&d->db, e))
		return e->code;
	if (db_attempt(&d->db, d->c.name, id, SB_EIO, "damaged", why, "", NULL, now, "pending", e) ||
	    sql_exec(&d->db, e, NULL, "DELETE FROM result WHERE campaign = ? AND run = ?", "tt", d->c.name, id)) {
		db_rollback(&d->db);
		return e->code;
	}
	return db_commit(&d->db, e);
}

/* What an engine killed at the wrong moment leaves beside a finished run: its last
 * checkpoint and journal (a finished run removes them itself), and temporary files
 * of processes that are gone. */
static void remove_litter(drv *d, const char *id)
{
	static const enum lay_kind stale[] = {LAY_CKPT, LAY_JOURNAL};
	char p[PATHX + 256];
	for (size_t k = 0; k < sizeof stale / sizeof *stale; k++) {
		layout_file(d->dir, 0, id, stale[k], p, sizeof p);
		unlink(p);
	}
	DIR *dd = opendir(d->dir);
	if (!dd)
		return;
	char pre[64];
	size_t lp = (size_t)snprintf(pre, sizeof pre, "%s.h5", id);
	for (struct dirent *de; (de = readdir(dd));) {
		const char *t = strstr(de->d_name, ".tmp.");
		if (strncmp(de->d_name, pre, lp) || !t)
			continue;
		char *end;
		long pid = strtol(t + 5, &end, 10);
		if (*end || pid <= 0 || (kill((pid_t)pid, 0) != 0 && errno == ESRCH)) {
			snprintf(p, sizeof p, "%s/%s", d->dir, de->d_name);
			unlink(p);
		}
	}
	closedir(dd);
}

static int has_result(drv *d, const char *id)
{
	sqlite3_stmt *q;
	sb_err e = {0};
	if (sql_exec(&d->db, &e, &q, "SELECT 1 FROM result WHERE campaign = ? AND run = ?", "tt", d->c.name, id))
		return 1;
	int found = sqlite3_step(q) == SQLITE_ROW;
	sqlite3_finalize(q);
	return found;
}

/* The seal of the run's file as recorded when it was done ("" when none: a database or
 * a file of an earlier version). */
static void recorded_seal(drv *d, const char *id, char seal[17])
{
	sqlite3_stmt *q;
	sb_err e = {0};
	seal[0] = 0;
	if (sql_exec(&d->db, &e, &q, "SELECT file_seal FROM result WHERE campaign = ? AND run = ?", "tt", d->c.name, id))
		return;
	if (sqlite3_step(q) == SQLITE_ROW && sqlite3_column_text(q, 0))
		snprintf(seal, 17, "%s", (const char *)sqlite3_column_text(q, 0));
	sqlite3_finalize(q);
}

/* Ingest every output that exists but is not recorded (finished while no driver was
 * listening), and with --retry-failed put failed runs back in the queue. Returns the
 * pending runs' indices in *pend. */
int sweep(drv *d, long *pend, long *npend, sb_err *e)
{
	*npend = 0;
	for (long i = 0; i < d->g.n; i++) {
		const grid_run *r = &d->g.runs[i];
		char st[16];
		long att;
		if (db_run_state(&d->db, d->c.name, r->id, st, sizeof st, &att, e))
			return e->code;
		char path[PATHX];
		layout_file(d->dir, 0, r->id, LAY_OUTPUT, path, sizeof path);
		int queued = !strcmp(st, "pending") || !strcmp(st, "running");
		if (queued && exists(path)) {
			/* finished while no driver listened, or its DONE line was dropped (GNU
			 * parallel stopped): what its engine used, from its worker's last line in
			 * the log when this driver saw the attempt start (else an earlier
			 * attempt's line could be taken for it) */
			db_usage lu;
			const db_usage *u = NULL;
			if (d->runs.started && d->runs.started[i]) {
				char lp[PATHX];
				layout_file(d->dir, 0, r->id, LAY_LOG, lp, sizeof lp);
				u = worker_log_usage(lp, d->runs.logfrom[i], &lu) ? &lu : NULL;
			}
			if (ingest_run(d, r->id, u, e))
				return e->code;
			continue;
		}
		if (!strcmp(st, "done") && pend) {
			/* a finished run's file is read again on every sweep: a truncated or
			 * deleted one puts the run back in the queue instead of shrinking its
			 * group silently */
			sb_err re = {0};
			char buf[128], seal[17];
			recorded_seal(d, r->id, seal);
			const char *why = done_unreadable(path, r->id, seal, &re, buf, sizeof buf);
			if (why) {
				if (requeue_damaged(d, r->id, att, why, e))
					return e->code;
				queued = 1;
			}
			remove_litter(d, r->id);
		}
		if (!queued && exists(path) && !has_result(d, r->id)) {
			/* a database rebuilt, or written by another version: the result row
			 * comes back from the file (the attempts are as recorded) */
			h5sum s;
			sb_err re = {0};
			if (!h5sum_read(path, r->id, &s, &re)) {
				if (db_begin(&d->db, e) || db_result_put(&d->db, d->c.name, r->id, &s, e)) {
					db_rollback(&d->db);
					return e->code;
				}
				if (db_commit(&d->db, e))
					return e->code;
			}
		}
		if (!strcmp(st, "failed") && pend && d->o->retry_failed) {
			/* keep the failed output beside the attempt that produced it */
			if (exists(path)) {
				char keep[PATHX];
				layout_aside(d->dir, "failed", r->id, att, keep, sizeof keep);
				if (move_aside(path, keep, e))
					return e->code;
			}
			if (db_begin(&d->db, e))
				return e->code;
			if (sql_exec(&d->db, e, NULL, "UPDATE run SET state = 'pending' WHERE campaign = ? AND id = ?", "tt",
				    d->c.name, r->id)) {
				db_rollback(&d->db);
				return e->code;
			}
			if (db_commit(&d->db, e))
				return e->code;
			queued = 1;
		}
		if (queued && pend)
			pend[(*npend)++] = i;
	}
	return 0;
}

