/* collect.c - what the tasks of a campaign's Slurm arrays did, into the
 * database. The nodes never touch the database: a task's run leaves its output file
 * (completion, as everywhere in study) and its worker's START/DONE lines in the
 * task's log, and this reads both on the submitting machine, through the same ingest
 * as study run's (ingest.c: the output decides), so a run done on the cluster is
 * recorded exactly as one done locally. Also `study status`'s lines about the arrays. */
#include "collect.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dirs.h"
#include "fsutil.h"
#include "layout.h"
#include "lock.h"
#include "schema.h"
#include "job/worker.h"
#include "plan.h"
#include "submit.h"

int slurm_tables(st_db *db, sb_err *e)
{
	return schema_slurm(db, e);
}

/* ---- a campaign, as the driver sees it ---- */

int slurm_drv_open(drv *d, const driver_opts *o, const char *path, sb_err *e)
{
	d->o = o;
	if (campaign_load(&d->c, path, e) || grid_expand(&d->g, &d->c, e))
		return e->code;
	const char *rd = o->runs_dir ? o->runs_dir : "runs";
	if (dirs_make(rd, e))
		return e->code;
	if (!realpath(rd, d->root))
		return sb_errf(e, SB_EIO, "%s: %s", rd, strerror(errno));
	if (strlen(d->root) > 3000)
		return sb_errf(e, SB_EUSAGE, "%s: path too long", d->root);
	layout_campaign(d->root, d->c.name, d->dir, sizeof d->dir);
	char dbp[PATHLEN];
	driver_db_path(o->runs_dir, o->db_path, dbp, sizeof dbp);
	if (db_open(&d->db, dbp, 1, e) || slurm_tables(&d->db, e))
		return e->code;
	/* a search's runs are its chains' so far: the grid they make now */
	if (driver_search_open(d, e) || (d->loc && driver_search_derive(d, e)))
		return e->code;
	return drv_runs_alloc(d, e);
}

void slurm_drv_close(drv *d)
{
	driver_search_close(d);
	drv_runs_free(d);
	db_close(&d->db);
	grid_free(&d->g);
	campaign_free(&d->c);
}

/* ---- the tasks' logs ---- */

typedef struct tline {
	int kind;        /* 1 START, 2 DONE */
	char name[40];
	char *text;      /* the whole line */
} tline;

typedef struct tlog {
	tline *l;
	long n;
	int exists;
} tlog;

static void tlog_free(tlog *t)
{
	for (long i = 0; i < t->n; i++)
		free(t->l[i].text);
	free(t->l);
	memset(t, 0, sizeof *t);
}

/* The worker lines of task (job, index)'s log. */
static int tlog_read(drv *d, long job, long index, tlog *t, sb_err *e)
{
	memset(t, 0, sizeof *t);
	char p[PATHX + 64];
	snprintf(p, sizeof p, "%s/" SLURM_SUB "/logs/%ld_%ld.out", d->dir, job, index);
	sb_err fe = {0};
	FILE *f = fs_open_input(p, "Slurm task log", 0, SB_EIO, &fe); /* a regular file only */
	if (!f)
		return 0;
	t->exists = 1;
	char *line = NULL;
	size_t cap = 0;
	long tcap = 0;
	while (getline(&line, &cap, f) >= 0) {
		line[strcspn(line, "\r\n")] = 0;
		tline x = {0};
		long code;
		if (!(x.kind = slurm_plan_parse_worker(line, x.name, sizeof x.name, &code)))
			continue;
		if (t->n == tcap) {
			tcap = tcap * 2 + 8;
			tline *nl = realloc(t->l, (size_t)tcap * sizeof *nl);
			if (!nl)
				break;
			t->l = nl;
		}
		if (!(x.text = strdup(line)))
			break;
		t->l[t->n++] = x;
	}
	free(line);
	int bad = ferror(f);
	fclose(f);
	return bad ? sb_errf(e, SB_EIO, "%s: cannot read", p) : 0;
}

/* The last line of this kind about name, or NULL. */
static const tline *tlog_find(const tlog *t, int kind, const char *name)
{
	for (long i = t->n - 1; i >= 0; i--)
		if (t->l[i].kind == kind && !strcmp(t->l[i].name, name))
			return &t->l[i];
	return NULL;
}

/* The host field of a START line ("STUDY-START\tID\tHOST"). */
static void start_host(const tline *s, char *host, size_t len)
{
	const char *h = s ? strrchr(s->text, '\t') : NULL;
	snprintf(host, len, "%s", h ? h + 1 : "");
}

/* ---- outcomes into the database ---- */

typedef struct trow {
	char run[40];
	long job, index;
	char state[16];
} trow;

static int load_open_tasks(drv *d, trow **rows, long *n, sb_err *e)
{
	sqlite3_stmt *q;
	*rows = NULL;
	*n = 0;
	if (sql_exec(&d->db, e, &q,
		    "SELECT run, job_id, array_index, state FROM slurm_task WHERE campaign = ?"
		    " AND state IN ('submitted', 'started') ORDER BY job_id, array_index, run",
		    "t", d->c.name))
		return e->code;
	long cap = 0;
	while (sqlite3_step(q) == SQLITE_ROW) {
		if (*n == cap) {
			cap = cap * 2 + 16;
			trow *nr = realloc(*rows, (size_t)cap * sizeof *nr);
			if (!nr) {
				sqlite3_finalize(q);
				return sb_errf(e, SB_ENOMEM, "out of memory");
			}
			*rows = nr;
		}
		trow *r = &(*rows)[(*n)++];
		snprintf(r->run, sizeof r->run, "%s", (const char *)sqlite3_column_text(q, 0));
		r->job = (long)sqlite3_column_int64(q, 1);
		r->index = (long)sqlite3_column_int64(q, 2);
		snprintf(r->state, sizeof r->state, "%s", (const char *)sqlite3_column_text(q, 3));
	}
	sqlite3_finalize(q);
	return 0;
}

/* The task's row: its state, and the attempt it made (the run's latest) when `link`. */
static int set_task(drv *d, const trow *r, const char *state, int link, const char *host, sb_err *e)
{
	if (db_begin(&d->db, e))
		return e->code;
	if (sql_exec(&d->db, e, NULL,
		    "UPDATE slurm_task SET state = ?, host = COALESCE(NULLIF(?, ''), host),"
		    " attempt = CASE WHEN ? THEN (SELECT MAX(n) FROM attempt WHERE campaign = ?4 AND run = ?5) END"
		    " WHERE campaign = ?4 AND run = ?5 AND job_id = ?6",
		    "ttlttl", state, host, (long)link, d->c.name, r->run, r->job)) {
		db_rollback(&d->db);
		return e->code;
	}
	return db_commit(&d->db, e);
}

/* A DONE line of a run that left no output, classified as study run's ingest_on_done does
 * (ingest.c): interrupted (7), killed by a signal (128 + n) and I/O faults (2) are
 * resumable and leave the run pending; bad input (1) and a crash (worker_crashed)
 * fail it. */
static int record_done(drv *d, const char *id, const worker_done *w, const db_usage *u, sb_err *e)
{
	const long code = w->code;
	if (code == 0) /* 0 without an output: nothing happened to record */
		return 0;
	const int crashed = worker_crashed(code);
	int resumable = code == SB_EINTR || (code >= 128 && !crashed) || code == SB_EIO;
	const char *status = code == SB_EINTR ? "interrupted"
			     : crashed         ? "crashed"
			     : code >= 128     ? "killed"
					       : sb_code_name((int)code);
	char now[32];
	db_now(now, sizeof now);
	if (!db_begin(&d->db, e)) {
		if (db_attempt(&d->db, d->c.name, id, code, status, w->msg, w->host, u, now, resumable ? "pending" : "failed", e))
			db_rollback(&d->db);
		else
			db_commit(&d->db, e);
	}
	return e->code;
}

static int one_task(drv *d, const trow *r, const tlog *t, const slurm_queue *q, sb_err *e)
{
	char st[16], path[PATHX], host[256];
	long att;
	if (db_run_state(&d->db, d->c.name, r->run, st, sizeof st, &att, e))
		return e->code;
	int open = !strcmp(st, "pending") || !strcmp(st, "running");
	const tline *done = tlog_find(t, 2, r->run), *start = tlog_find(t, 1, r->run);
	start_host(start, host, sizeof host);
	layout_file(d->dir, 0, r->run, LAY_OUTPUT, path, sizeof path);
	const char *qs = q ? slurm_queue_state(q, r->job, r->index) : "?";
	/* a task runs its runs one after the other: a later run's START means this one's
	 * worker is gone without a word, though the task goes on */
	int passed = 0;
	for (const tline *l = start ? start + 1 : NULL; l && l < t->l + t->n; l++)
		passed |= l->kind == 1 && strcmp(l->name, r->run);
	if (done) {
		/* what the worker said; a run recorded meanwhile (a study run swept its
		 * output) keeps its attempts: the task's is that one */
		char *copy = strdup(done->text);
		worker_done w;
		if (!copy)
			return sb_errf(e, SB_ENOMEM, "out of memory");
		const int parsed = worker_done_parse(copy, &w);
		/* what the engine used (worker.h), recorded with the attempt either way */
		const db_usage *u = parsed ? worker_usage(&w) : NULL;
		if (open && (exists(path) ? ingest_run(d, r->run, u, e) : parsed && record_done(d, r->run, &w, u, e))) {
			free(copy);
			return e->code;
		}
		free(copy);
		long att2;
		db_run_state(&d->db, d->c.name, r->run, st, sizeof st, &att2, e);
		return set_task(d, r, "ended", att2 > att || !open, host, e);
	}
	if (open && exists(path)) { /* finished; its line lost */
		if (ingest_run(d, r->run, NULL, e))
			return e->code;
		return set_task(d, r, "ended", 1, host, e);
	}
	if (!open && !strcmp(r->state, "submitted") && !start)
		return qs ? 0 : set_task(d, r, "unstarted", 0, "", e); /* done elsewhere meanwhile */
	if (qs && start && !passed) {
		/* running now: the run shows as running in study status (again after a
		 * submit, which records every run of the campaign as not running) */
		if (!strcmp(st, "pending")) {
			char *copy = strdup(start->text);
			if (!copy)
				return sb_errf(e, SB_ENOMEM, "out of memory");
			ingest_on_start(d, copy, e);
			free(copy);
		}
		return e->code || strcmp(r->state, "submitted") ? e->code : set_task(d, r, "started", 0, host, e);
	}
	if (qs && !passed)
		return 0; /* queued or running: later */
	if (!start)
		return set_task(d, r, "unstarted", 0, "", e); /* cancelled while queued, or an earlier run of its task stopped it */
	if (!open)
		return set_task(d, r, "ended", 1, host, e);
	/* it started and its task is gone without a DONE line: the worker itself was
	 * killed (SIGKILL after the KillWait of a cancel or a time limit, the node lost,
	 * out of memory); the run resumes from its last checkpoint */
	char now[32], msg[1200];
	db_now(now, sizeof now);
	if (passed)
		snprintf(msg, sizeof msg, "study exec ended without a word in Slurm task %ld_%ld, which went on (killed; see "
			 "%s/logs/%ld_%ld.out)", r->job, r->index, SLURM_SUB, r->job, r->index);
	else
		snprintf(msg, sizeof msg,
			 "Slurm task %ld_%ld ended before study exec reported (killed after KillWait, node failure, memory "
			 "or time limit; see %s/logs/%ld_%ld.out)",
			 r->job, r->index, SLURM_SUB, r->job, r->index);
	if (db_begin(&d->db, e))
		return e->code;
	if (db_attempt(&d->db, d->c.name, r->run, -1, "killed", msg, host, NULL, now, "pending", e)) {
		db_rollback(&d->db);
		return e->code;
	}
	if (db_commit(&d->db, e))
		return e->code;
	return set_task(d, r, "ended", 1, host, e);
}

/* A packing's DONE line (a name that is not a run): recorded once, as study run does. */
static int caches_of(drv *d, const tlog *t, sb_err *e)
{
	for (long i = 0; i < t->n && !e->code; i++) {
		if (t->l[i].kind != 2 || grid_find(&d->g, t->l[i].name))
			continue;
		char st[16];
		ingest_cache_state(d, t->l[i].name, st, sizeof st);
		if (st[0])
			continue;
		char *copy = strdup(t->l[i].text);
		if (!copy)
			return sb_errf(e, SB_ENOMEM, "out of memory");
		ingest_on_done(d, 1, copy, e);
		free(copy);
	}
	return e->code;
}

int slurm_collect(drv *d, const slurm_queue *q, sb_err *e)
{
	trow *rows;
	long n;
	if (load_open_tasks(d, &rows, &n, e))
		return e->code;
	tlog t = {0};
	long tj = -1, ti = -1;
	for (long i = 0; i < n && !e->code; i++) {
		if (rows[i].job != tj || rows[i].index != ti) {
			tlog_free(&t);
			tj = rows[i].job;
			ti = rows[i].index;
			if (tlog_read(d, tj, ti, &t, e) || caches_of(d, &t, e))
				break;
		}
		one_task(d, &rows[i], &t, q, e);
	}
	tlog_free(&t);
	free(rows);
	return e->code;
}

int slurm_busy(drv *d, const slurm_queue *q, char *busy, long *nbusy, sb_err *e)
{
	sqlite3_stmt *s;
	*nbusy = 0;
	if (sql_exec(&d->db, e, &s,
		    "SELECT run, job_id, array_index FROM slurm_task WHERE campaign = ? AND state IN ('submitted', 'started')",
		    "t", d->c.name))
		return e->code;
	while (sqlite3_step(s) == SQLITE_ROW) {
		const grid_run *r = grid_find(&d->g, (const char *)sqlite3_column_text(s, 0));
		if (!r || busy[r - d->g.runs])
			continue;
		if (!q || slurm_queue_state(q, (long)sqlite3_column_int64(s, 1), (long)sqlite3_column_int64(s, 2))) {
			busy[r - d->g.runs] = 1;
			(*nbusy)++;
		}
	}
	sqlite3_finalize(s);
	return 0;
}

/* ---- study status and study run ---- */

/* The campaigns with arrays (name, or all), with the campaign file each was submitted
 * from. */
typedef struct camp_ref {
	char name[80];
	char file[PATHLEN];
	char root[PATHLEN];
} camp_ref;

static int array_campaigns(st_db *db, const char *name, camp_ref **out, long *n, sb_err *e)
{
	sqlite3_stmt *q;
	*out = NULL;
	*n = 0;
	/* the latest submission's file and directory */
	if (sql_exec(db, e, &q,
		    "SELECT campaign, campaign_file, dir FROM slurm_job j WHERE (?1 IS NULL OR campaign = ?1)"
		    " AND job_id = (SELECT MAX(job_id) FROM slurm_job k WHERE k.campaign = j.campaign) ORDER BY campaign",
		    "t", name))
		return e->code;
	long cap = 0;
	while (sqlite3_step(q) == SQLITE_ROW) {
		if (*n == cap) {
			cap = cap * 2 + 4;
			camp_ref *nr = realloc(*out, (size_t)cap * sizeof *nr);
			if (!nr) {
				sqlite3_finalize(q);
				return sb_errf(e, SB_ENOMEM, "out of memory");
			}
			*out = nr;
		}
		camp_ref *c = &(*out)[(*n)++];
		snprintf(c->name, sizeof c->name, "%s", (const char *)sqlite3_column_text(q, 0));
		snprintf(c->file, sizeof c->file, "%s", (const char *)sqlite3_column_text(q, 1));
		const char *dir = (const char *)sqlite3_column_text(q, 2);
		snprintf(c->root, sizeof c->root, "%s", dir ? dir : "");
		char *sl = strrchr(c->root, '/'); /* RUNS/NAME -> RUNS */
		if (sl)
			*sl = 0;
	}
	sqlite3_finalize(q);
	return 0;
}

/* Does the database have arrays at all? Read-only, so that a status of a database
 * without any never writes. */
static int has_arrays(const char *db_path, const char *name)
{
	st_db db;
	sb_err e = {0};
	if (access(db_path, R_OK) || db_open(&db, db_path, 0, &e))
		return 0;
	sqlite3_stmt *q;
	int found = 0;
	if (!sql_exec(&db, &e, &q, "SELECT 1 FROM slurm_job WHERE ?1 IS NULL OR campaign = ?1 LIMIT 1", "t", name)) {
		found = sqlite3_step(q) == SQLITE_ROW;
		sqlite3_finalize(q);
	}
	db_close(&db);
	return found;
}

int slurm_refresh(const char *runs_dir, const char *db_path, const char *name, long *active, FILE *msg, sb_err *e)
{
	*active = 0;
	if (!has_arrays(db_path, name))
		return 0;
	st_db db;
	camp_ref *cs = NULL;
	long nc = 0;
	if (db_open(&db, db_path, 0, e))
		return e->code;
	array_campaigns(&db, name, &cs, &nc, e);
	db_close(&db);
	if (e->code)
		return e->code;
	slurm_queue q = {0};
	sb_err qe = {0};
	int have_q = !slurm_queue_list(&q, &qe);
	if (!have_q) {
		fprintf(msg, "study: cannot ask Slurm which tasks are queued (%s); only their logs are read\n", qe.msg);
		*active = -1;
	}
	for (long i = 0; i < nc && !e->code; i++) {
		drv *d = calloc(1, sizeof *d);
		if (!d) {
			sb_errf(e, SB_ENOMEM, "out of memory");
			break;
		}
		/* the runs directory the arrays write to (the campaign's own, whatever
		 * --runs this command was given), and the database this command opened */
		driver_opts o = {.runs_dir = cs[i].root[0] ? cs[i].root : runs_dir, .db_path = db_path, .use_cache = 1};
		sb_err ce = {0};
		int lock = -1;
		const char *rd = o.runs_dir ? o.runs_dir : "runs";
		if (access(rd, F_OK)) /* never made again by a status */
			sb_errf(&ce, SB_EIO, "%s: %s", rd, strerror(errno));
		else if (!slurm_drv_open(d, &o, cs[i].file, &ce)) {
			/* a driver or a submit holds the campaign: it reads the tasks itself */
			if ((lock = lock_campaign_try(d->dir)) >= 0) {
				slurm_collect(d, have_q ? &q : NULL, &ce);
				char *busy = calloc((size_t)d->g.n + 1, 1);
				long nb = 0;
				if (busy && have_q && !ce.code && !slurm_busy(d, &q, busy, &nb, &ce) && *active >= 0)
					*active += nb;
				free(busy);
			}
		}
		if (ce.code)
			fprintf(msg, "study: %s: the Slurm tasks' results were not read: %s\n", cs[i].name, ce.msg);
		if (lock >= 0)
			close(lock);
		slurm_drv_close(d);
		free(d);
	}
	slurm_queue_free(&q);
	free(cs);
	return e->code;
}

int slurm_report(const char *db_path, const char *name, FILE *out, sb_err *e)
{
	if (!has_arrays(db_path, name))
		return 0;
	st_db db;
	if (db_open(&db, db_path, 0, e))
		return e->code;
	slurm_queue q = {0};
	sb_err qe = {0};
	int have_q = !slurm_queue_list(&q, &qe);
	sqlite3_stmt *j;
	if (sql_exec(&db, e, &j,
		    "SELECT campaign, job_id, array, tasks, runs, runs_per_task, submitted, dir, campaign_file FROM slurm_job"
		    " WHERE ?1 IS NULL OR campaign = ?1 ORDER BY campaign, job_id",
		    "t", name)) {
		db_close(&db);
		slurm_queue_free(&q);
		return e->code;
	}
	while (sqlite3_step(j) == SQLITE_ROW) {
		const char *camp = (const char *)sqlite3_column_text(j, 0);
		long job = (long)sqlite3_column_int64(j, 1);
		long queued = 0, running = 0, ended = 0;
		/* the tasks, as squeue sees them now */
		sqlite3_stmt *t;
		if (sql_exec(&db, e, &t, "SELECT DISTINCT array_index FROM slurm_task WHERE campaign = ? AND job_id = ?", "tl",
			    camp, job))
			break;
		while (sqlite3_step(t) == SQLITE_ROW) {
			const char *s = have_q ? slurm_queue_state(&q, job, (long)sqlite3_column_int64(t, 0)) : NULL;
			if (!s)
				ended++;
			else if (!strcmp(s, "PENDING") || !strcmp(s, "REQUEUED"))
				queued++;
			else
				running++;
		}
		sqlite3_finalize(t);
		/* its runs: the attempt each made, or why none */
		long done = 0, failed = 0, stopped = 0, unstarted = 0, open = 0;
		if (sql_exec(&db, e, &t,
			    "SELECT s.state, a.status FROM slurm_task s LEFT JOIN attempt a ON a.campaign = s.campaign"
			    " AND a.run = s.run AND a.n = s.attempt WHERE s.campaign = ? AND s.job_id = ?",
			    "tl", camp, job))
			break;
		while (sqlite3_step(t) == SQLITE_ROW) {
			const char *st = (const char *)sqlite3_column_text(t, 0);
			const char *as = (const char *)sqlite3_column_text(t, 1);
			if (!strcmp(st, "unstarted"))
				unstarted++;
			else if (strcmp(st, "ended"))
				open++;
			else if (as && !strcmp(as, "ok"))
				done++;
			else if (as && (!strcmp(as, "interrupted") || !strcmp(as, "killed") || !strcmp(as, "io")))
				stopped++;
			else
				failed++;
		}
		sqlite3_finalize(t);
		fprintf(out, "slurm job %ld (%s, array %s, %ld run%s in %ld task%s): ", job,
			(const char *)sqlite3_column_text(j, 6), (const char *)sqlite3_column_text(j, 2),
			(long)sqlite3_column_int64(j, 4), sqlite3_column_int64(j, 4) == 1 ? "" : "s",
			(long)sqlite3_column_int64(j, 3), sqlite3_column_int64(j, 3) == 1 ? "" : "s");
		if (have_q)
			fprintf(out, "tasks %ld queued, %ld running, %ld ended; ", queued, running, ended);
		else
			fprintf(out, "tasks: squeue cannot say (%s); ", qe.msg);
		fprintf(out, "runs %ld done, %ld failed, %ld stopped, %ld not started, %ld not ended\n", done, failed,
			stopped, unstarted, open);
		if (stopped + unstarted + failed)
			fprintf(out, "  logs: %s/" SLURM_SUB "/logs/%ld_INDEX.out; runs not done go again with: study submit "
				"%s --slurm%s\n",
				(const char *)sqlite3_column_text(j, 7), job, (const char *)sqlite3_column_text(j, 8),
				failed ? " [--retry-failed]" : "");
	}
	sqlite3_finalize(j);
	db_close(&db);
	slurm_queue_free(&q);
	return e->code;
}
