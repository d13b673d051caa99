/* ingest.c - what became of a run or a packing, into the database: from its output
 * file when there is one (the file decides), else from the worker's exit code and the
 * log's last line; an I/O fault stops the launching. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dirent.h>
#include <fcntl.h>
#include <time.h>
#include <unistd.h>
#include <sys/file.h>
#include <sys/stat.h>

#include "fsutil.h"
#include "h5sum.h"
#include "layout.h"
#include "campaign/safe.h"
#include "job/worker.h"
#include "drvlocal.h"
#include "packing.h"
#include "stop.h"

/* A run the database has no attempt of (it was rebuilt from the files) gets back the
 * attempts whose files the sweep kept aside (failed/, damaged/: ID.attemptN.h5), in
 * their order; attempts that left no file (interrupted, lost) cannot come back. */
static int recover_kept(drv *d, const char *id, sb_err *e)
{
	char st[16];
	long att;
	if (db_run_state(&d->db, d->c.name, id, st, sizeof st, &att, e) || att)
		return e->code;
	static const char *const subs[] = {"failed", "damaged"};
	long kept[2][64];
	int nk[2] = {0, 0};
	char pre[96];
	int lp = snprintf(pre, sizeof pre, "%s.attempt", id);
	for (int w = 0; w < 2; w++) {
		char dir[PATHX];
		layout_sub(d->dir, subs[w], dir, sizeof dir);
		DIR *dd = opendir(dir);
		for (struct dirent *de; dd && (de = readdir(dd));) {
			char *end;
			long k = strncmp(de->d_name, pre, (size_t)lp) ? 0 : strtol(de->d_name + lp, &end, 10);
			if (k > 0 && !strcmp(end, ".h5") && nk[w] < 64)
				kept[w][nk[w]++] = k;
		}
		if (dd)
			closedir(dd);
	}
	char now[32];
	db_now(now, sizeof now);
	/* merged by attempt number: the two lists come in directory order */
	for (long last = 0;;) {
		int bw = -1, bi = -1;
		for (int w = 0; w < 2; w++)
			for (int i = 0; i < nk[w]; i++)
				if (kept[w][i] > last && (bw < 0 || kept[w][i] < kept[bw][bi]))
					bw = w, bi = i;
		if (bw < 0)
			return 0;
		last = kept[bw][bi];
		char path[PATHX + 64];
		layout_aside(d->dir, subs[bw], id, last, path, sizeof path);
		h5sum s;
		sb_err re = {0};
		int bad = h5sum_read(path, id, &s, &re) != 0;
		char msg[1200];
		if (bw)
			snprintf(msg, sizeof msg, "damaged (kept as damaged/%s.attempt%ld.h5)%s%s", id, last, bad ? ": " : "",
				 bad ? re.msg : "");
		else
			snprintf(msg, sizeof msg, "%s", bad ? re.msg : h5sum_text(&s, "message"));
		if (db_attempt_kept(&d->db, d->c.name, id, bad ? NULL : &s,
				    bw ? "damaged" : bad ? "io" : h5sum_text(&s, "status"), msg, now, e))
			return e->code;
	}
}

static int ingest_file(drv *d, const char *id, const char *path, const db_usage *u, const char *now, h5sum *sp,
		       sb_err *rep, int *gone, sb_err *e);
static int attempt(drv *d, long ix, long code, const char *status, const char *msg, const char *host,
		   const db_usage *u, const char *end, const char *state, sb_err *e);

int ingest_run(drv *d, const char *id, const db_usage *u, sb_err *e)
{
	char path[PATHX], now[32];
	layout_file(d->dir, 0, id, LAY_OUTPUT, path, sizeof path);
	db_now(now, sizeof now);
	h5sum s;
	sb_err re = {0};
	if (db_begin(&d->db, e))
		return e->code;
	int gone = 0;
	if (ingest_file(d, id, path, u, now, &s, &re, &gone, e)) {
		db_rollback(&d->db); /* a full disk: the final sweep tries again (ingest_owed_settle) */
		return e->code;
	}
	const grid_run *gr = grid_find(&d->g, id);
	if (gone) {
		/* the file was there when the caller looked and gone when it was read (its
		 * directory deleted meanwhile: a killed engine's late rename, a user's rm -rf):
		 * not the run's fault; as for an input that went, it is prepared and run again */
		db_rollback(&d->db);
		if (!gr)
			return 0;
		if (d->runs.outcome)
			d->runs.outcome[gr - d->g.runs] = 'm';
		return attempt(d, gr - d->g.runs, SB_EIO, "missing_input", re.msg, "", u, now, "pending", e);
	}
	d->n_ingested++;
	if (gr && d->runs.outcome)
		d->runs.outcome[gr - d->g.runs] = 'r';
	if (re.code || strcmp(h5sum_text(&s, "status"), "ok"))
		d->n_failed_now++;
	return 0;
}

/* A run's file into the database, within the caller's transaction (committed here). */
static int ingest_file(drv *d, const char *id, const char *path, const db_usage *u, const char *now, h5sum *sp,
		       sb_err *rep, int *gone, sb_err *e)
{
	h5sum s;
	sb_err re = {0};
	if (recover_kept(d, id, e))
		return e->code;
	if (h5sum_read(path, id, &s, &re) && !exists(path)) {
		/* (ingest_run: gone between the look and the read) */
		*sp = s;
		*rep = (sb_err){SB_EIO, ""};
		snprintf(rep->msg, sizeof rep->msg, "its output file was gone when it was to be read (%.900s): its "
			 "directory deleted meanwhile?", re.msg);
		*gone = 1;
		return 0;
	} else if (re.code) {
		db_attempt(&d->db, d->c.name, id, SB_EIO, "io", re.msg, "", u, now, "failed", e);
	} else {
		/* the file says whether the run started from the packing cache: a database
		 * rebuilt from the files gets from_cache and the cache's row back */
		const grid_run *r = grid_find(&d->g, id);
		char want[128];
		layout_cache_particles("", r ? r->cache_key : "", want, sizeof want);
		if (r && !strcmp(s.particles, want)) {
			char st[16];
			ingest_cache_state(d, r->cache_key, st, sizeof st);
			char h5[PATHX];
			layout_file(d->dir, 1, r->cache_key, LAY_OUTPUT, h5, sizeof h5);
			if (!st[0] && exists(h5))
				ingest_cache(d, r->cache_key, e);
			if (!e->code)
				sql_exec(&d->db, e, NULL, "UPDATE run SET from_cache = 1 WHERE campaign = ? AND id = ?", "tt",
					d->c.name, id);
		}
		if (!e->code)
			db_ingest(&d->db, d->c.name, id, &s, u, now, e);
	}
	*sp = s;
	*rep = re;
	return e->code ? e->code : db_commit(&d->db, e);
}

int ingest_cache(drv *d, const char *key, sb_err *e)
{
	char path[PATHX], txt[PATHX], now[32];
	layout_file(d->dir, 1, key, LAY_OUTPUT, path, sizeof path);
	layout_cache_particles(d->dir, key, txt, sizeof txt);
	db_now(now, sizeof now);
	h5sum s;
	sb_err re = {0};
	h5sum_read(path, key, &s, &re);
	int okc = !re.code && !strcmp(h5sum_text(&s, "status"), "ok") && exists(txt);
	const char *end = h5sum_text(&s, "end_time");
	return sql_exec(&d->db, e, NULL,
		       "INSERT OR REPLACE INTO cache(campaign, key, state, settle_time, settle_steps, wall_seconds,"
		       " host, message, built) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)",
		       "tttdldttt", d->c.name, key, okc ? "ok" : "failed", h5sum_real(&s, "settle_time"),
		       h5sum_int(&s, "settle_steps"), h5sum_real(&s, "wall_seconds"), h5sum_text(&s, "host"),
		       re.code ? re.msg : h5sum_text(&s, "message"), end[0] ? end : now);
}

void ingest_cache_state(drv *d, const char *key, char *st, size_t len)
{
	sqlite3_stmt *q;
	sb_err e = {0};
	st[0] = 0;
	if (sql_exec(&d->db, &e, &q, "SELECT state FROM cache WHERE campaign = ? AND key = ?", "tt", d->c.name, key))
		return;
	if (sqlite3_step(q) == SQLITE_ROW && sqlite3_column_text(q, 0))
		snprintf(st, len, "%s", (const char *)sqlite3_column_text(q, 0));
	sqlite3_finalize(q);
}

/* An attempt the database would not take when it came. */
struct owed {
	struct owed *next;
	long ix, code;
	char status[24], msg[1024], host[256], end[32], state[16];
	int has_usage;
	db_usage u;
};

/* Records an attempt of grid run ix (its run's state becomes `state`). One the database
 * would not take (a full disk: "database or disk is full") is kept and written again
 * before the driver ends (ingest_owed_settle, with the room reserve.c held), so that no run it started is left 'running' to
 * be taken for one whose driver was killed; and it stops the launching as an I/O fault
 * would, since every later run would end the same way. */
static int attempt(drv *d, long ix, long code, const char *status, const char *msg, const char *host,
		   const db_usage *u, const char *end, const char *state, sb_err *e)
{
	const char *id = d->g.runs[ix].id;
	if (!db_begin(&d->db, e)) {
		if (!db_attempt(&d->db, d->c.name, id, code, status, msg, host, u, end, state, e) && !db_commit(&d->db, e))
			return 0;
		db_rollback(&d->db);
	}
	struct owed *o = calloc(1, sizeof *o);
	if (o) {
		*o = (struct owed){d->owed, ix, code, "", "", "", "", "", u != NULL, u ? *u : (db_usage){0, 0}};
		snprintf(o->status, sizeof o->status, "%s", status);
		snprintf(o->msg, sizeof o->msg, "%s", msg);
		snprintf(o->host, sizeof o->host, "%s", host);
		snprintf(o->end, sizeof o->end, "%s", end);
		snprintf(o->state, sizeof o->state, "%s", state);
		d->owed = o;
	}
	if (!d->io_fault) {
		d->io_fault = 1;
		snprintf(d->io_msg, sizeof d->io_msg, "the database would not record run %s: %s", id, e->msg);
		stop_halt(); /* no new jobs; running ones checkpoint */
	}
	return e->code;
}

int ingest_owed_settle(drv *d, sb_err *e)
{
	/* every engine has stopped: the room held since the start is for these writes
	 * and the final sweep's (space freed while engines ran went to them) */
	if (d->owed || d->io_fault)
		reserve_release(d);
	/* oldest first: the list is newest first, and a run's later attempt decides its state */
	struct owed *rev = NULL;
	while (d->owed) {
		struct owed *o = d->owed;
		d->owed = o->next;
		o->next = rev;
		rev = o;
	}
	while (rev) {
		struct owed *o = rev;
		rev = o->next;
		const char *id = d->g.runs[o->ix].id;
		sb_err le = {0};
		int bad = db_begin(&d->db, &le) ||
			  db_attempt(&d->db, d->c.name, id, o->code, o->status, o->msg, o->host, o->has_usage ? &o->u : NULL,
				     o->end, o->state, &le) ||
			  db_commit(&d->db, &le);
		if (bad) {
			db_rollback(&d->db);
			fprintf(stderr, "study: %s: run %s ended (%s%s%s) but the database would not record it: %s; the next "
				"study run records it as interrupted\n", d->c.name, id, o->status, o->msg[0] ? ": " : "", o->msg,
				le.msg);
			if (!e->code)
				sb_errf(e, le.code, "%s", le.msg);
		}
		free(o);
	}
	return e->code;
}

/* Is a run's input gone: its argument file, or the packing that file starts it from? */
static int input_gone(drv *d, const char *id, char *why, size_t n)
{
	char args[PATHX], key[64];
	layout_file(d->dir, 0, id, LAY_ARGS, args, sizeof args);
	if (!exists(args)) {
		snprintf(why, n, "its argument file %s was deleted while the campaign ran", args);
		return 1;
	}
	packing_of_args(d->dir, id, key, sizeof key);
	if (key[0] && !packing_present(d->dir, key)) {
		snprintf(why, n, "its packing %s was deleted from the cache while the campaign ran", key);
		return 1;
	}
	return 0;
}

/* A DONE line from a worker: the output file decides; without one, the exit code. */
int ingest_on_done(drv *d, int is_cache, char *line, sb_err *e)
{
	worker_done w;
	if (!worker_done_parse(line, &w) || !safe_name(w.name))
		return 0;
	const char *name = w.name, *host = w.host, *msg = w.msg;
	const long code = w.code;
	/* what the engine used (worker.h), recorded with the attempt whatever its outcome */
	const db_usage *u = worker_usage(&w);
	char path[PATHX];
	if (is_cache) {
		layout_file(d->dir, 1, name, LAY_OUTPUT, path, sizeof path);
		char args[PATHX];
		layout_file(d->dir, 1, name, LAY_ARGS, args, sizeof args);
		if (!exists(path) && !exists(args))
			return 0; /* its directory was deleted under it: not the packing's failure */
		if (exists(path) || (code != 0 && code != SB_EINTR && code < 128) || worker_crashed(code)) {
			if (db_begin(&d->db, e))
				return e->code;
			if (exists(path))
				ingest_cache(d, name, e);
			else
				sql_exec(&d->db, e, NULL,
					"INSERT OR REPLACE INTO cache(campaign, key, state, host, message) VALUES (?, ?, 'failed', ?, ?)",
					"tttt", d->c.name, name, host, msg);
			return e->code ? (db_rollback(&d->db), e->code) : db_commit(&d->db, e);
		}
		return 0;
	}
	const grid_run *r = grid_find(&d->g, name);
	if (!r)
		return 0;
	d->runs.started[r - d->g.runs] = 2;
	layout_file(d->dir, 0, name, LAY_OUTPUT, path, sizeof path);
	if (exists(path))
		return ingest_run(d, name, u, e);
	if (code == 0)
		return 0; /* output still on its way back from a remote host: the final sweep */
	long ix = r - d->g.runs;
	char now[32];
	/* a checkpoint of other arguments beside a run whose argument file was written
	 * again (its directory deleted while an engine still ran there, which then wrote
	 * it): the driver's own stale file, not the run's fault; it goes, and the run is
	 * prepared and run again */
	if (code == SB_EUSAGE && strstr(msg, ".h5.ckpt: written by a run with other parameters")) {
		char p[PATHX + 16];
		const char *kind;
		layout_file(d->dir, 0, name, LAY_CKPT, p, sizeof p);
		if (fs_replaceable(p, &kind))
			unlink(p);
		layout_file(d->dir, 0, name, LAY_JOURNAL, p, sizeof p);
		if (fs_replaceable(p, &kind))
			unlink(p);
		d->runs.outcome[ix] = 'm';
		db_now(now, sizeof now);
		return attempt(d, ix, code, "missing_input", msg, host, u, now, "pending", e);
	}
	char gone[PATHX + 96];
	if (code != SB_EINTR && code < 128 && input_gone(d, name, gone, sizeof gone)) {
		/* its argument file or its packing was deleted while the campaign ran (the
		 * engine cannot open them, or the worker found no argument file): no fault
		 * of the run's nor of the machine's; launch() prepares it again. The worker
		 * may have said nothing (it found no file to run): the attempt says what went */
		d->runs.outcome[ix] = 'm';
		db_now(now, sizeof now);
		return attempt(d, ix, code, "missing_input", msg[0] ? msg : gone, host, u, now, "pending", e);
	}
	/* interrupted (7) or killed by a signal: resumable, stays pending. An I/O fault
	 * (2: a full disk, a read-only directory) is the machine's, not the run's: the run
	 * stays pending and no further run starts, since every one would fail the same way
	 * and a queue emptied in seconds would be marked failed. Bad input (1) fails.
	 * Killed and I/O-failed runs are transient: the driver runs them again (up to
	 * --retries); an interruption the driver asked for (its signal, its halt after an
	 * I/O fault) is not. */
	/* on another host, a job the worker could not start there (its argument file
	 * never arrived: a host going away) is that host's fault, not this machine's */
	int lost = d->o->sshloginfile && code == SB_EIO && !strncmp(msg, "exec: ", 6);
	int io = code == SB_EIO && !lost;
	/* a crash (SIGSEGV, SIGABRT, ...) is the engine's own and would repeat: failed */
	const int crashed = worker_crashed(code);
	int resumable = code == SB_EINTR || (code >= 128 && !crashed) || io || lost;
	int ours = code == SB_EINTR && (stop_requested() || d->io_fault);
	d->runs.outcome[ix] = !resumable ? 'r' : ours ? 'h' : io ? 'i' : lost ? 'l' : 'k';
	if (resumable && !ours)
		d->runs.transient[ix]++;
	const char *status = code == SB_EINTR ? "interrupted"
			     : crashed         ? "crashed"
			     : code >= 128     ? "killed"
			     : lost            ? "lost"
					       : sb_code_name((int)code);
	/* an engine on a full disk may not get its last words into its log either */
	if (!msg[0] && io)
		msg = "exit 2 (I/O) and no word in its log (a full disk takes no log line either)";
	if (io && !d->io_fault) {
		d->io_fault = 1;
		snprintf(d->io_msg, sizeof d->io_msg, "run %s: %s", name, msg);
		stop_halt(); /* no new jobs; running ones checkpoint */
	}
	db_now(now, sizeof now);
	if (!resumable)
		d->n_failed_now++;
	return attempt(d, ix, code, status, msg, host, u, now, resumable ? "pending" : "failed", e);
}

int ingest_on_start(drv *d, char *line, sb_err *e)
{
	char *f[3] = {0};
	int n = 0;
	for (char *s = line, *t; n < 3 && (t = strsep(&s, "\t"));)
		f[n++] = t;
	const grid_run *r = n < 3 ? NULL : grid_find(&d->g, f[1]);
	if (!r)
		return 0;
	d->runs.started[r - d->g.runs] = 1;
	/* where this attempt's lines begin in the run's log (earlier attempts precede) */
	char lp[PATHX];
	struct stat sb;
	layout_file(d->dir, 0, r->id, LAY_LOG, lp, sizeof lp);
	d->runs.logfrom[r - d->g.runs] = stat(lp, &sb) == 0 ? (long)sb.st_size : 0;
	char now[32];
	db_now(now, sizeof now);
	if (db_begin(&d->db, e))
		return e->code;
	if (sql_exec(&d->db, e, NULL,
		    "UPDATE run SET state = 'running', started = ?, host = ? WHERE campaign = ? AND id = ?"
		    " AND state = 'pending'",
		    "tttt", now, f[2], d->c.name, f[1])) {
		db_rollback(&d->db);
		return e->code;
	}
	return db_commit(&d->db, e);
}

/* Jobs that started but whose DONE line never came: GNU parallel stopped them (a
 * signal to the driver, or the driver's death) and dropped their output. Each is
 * recorded as an interrupted attempt with the engine's last words; it stays pending. */
void ingest_unreported(drv *d, sb_err *e)
{
	/* every one, also after one the database would not take (it is owed) */
	for (long i = 0; i < d->g.n; i++) {
		if (d->runs.started[i] != 1)
			continue;
		d->runs.started[i] = 2;
		const char *id = d->g.runs[i].id;
		char path[PATHX], msg[1024] = "", now[32];
		layout_file(d->dir, 0, id, LAY_OUTPUT, path, sizeof path);
		if (exists(path))
			continue; /* finished after all: the sweep ingests it */
		layout_file(d->dir, 0, id, LAY_LOG, path, sizeof path);
		worker_last_message(path, d->runs.logfrom[i], msg, sizeof msg);
		/* the engine's words when SIGTERM/SIGINT stopped it (while settling there is
		 * no checkpoint yet, and it says so) */
		int intr = !strncmp(msg, "shake: interrupted", 18) || strstr(msg, "checkpoint") != NULL;
		/* not stopped by the driver: its worker died without a word (killed, or
		 * its host lost): run again */
		int lost = !stop_requested() && !d->io_fault;
		d->runs.outcome[i] = lost ? 'l' : 'h';
		if (lost) {
			d->runs.transient[i]++;
			intr = 0;
		}
		db_now(now, sizeof now);
		/* what its engine used, from the line its worker left in the log (worker.h) */
		db_usage lu;
		const db_usage *u = worker_log_usage(path, d->runs.logfrom[i], &lu) ? &lu : NULL;
		sb_err le = {0};
		attempt(d, i, intr ? SB_EINTR : -1, lost ? "lost" : "interrupted",
			msg[0] && !lost ? msg
			: lost          ? "the job ended without its outcome (worker killed or host lost)"
			: d->io_fault   ? "stopped by the driver after an I/O fault"
					: "stopped with the driver",
			"", u, now, "pending", &le);
		if (le.code && !e->code)
			*e = le;
	}
}


/* The ISO time (db_now's form) a file was last written, "" if it is not there. */
static void mtime_iso(const char *path, char *out, size_t len)
{
	struct stat sb;
	struct tm tm;
	out[0] = 0;
	if (stat(path, &sb) == 0 && gmtime_r(&sb.st_mtime, &tm))
		strftime(out, len, "%Y-%m-%dT%H:%M:%SZ", &tm);
}

/* Is a run's lock free (its engine gone), waiting until `deadline` for an engine of
 * the killed driver to stop: it had SIGTERM from GNU parallel and checkpoints. */
static int lock_free(const char *path, time_t deadline)
{
	int fd = open(path, O_RDWR | O_NOFOLLOW);
	if (fd < 0)
		return 1; /* no lock file: no worker ever held it */
	int got;
	while (!(got = flock(fd, LOCK_EX | LOCK_NB) == 0) && time(NULL) < deadline)
		nanosleep(&(struct timespec){0, 50000000}, NULL);
	close(fd); /* releases it: the workers of this driver take it */
	return got;
}

/* A driver killed outright (SIGKILL, its machine) leaves the runs it had started
 * 'running' with no attempt recorded. The next `study run` records each as an
 * interrupted attempt: its start as that driver saw it, its end the last write of its
 * log or checkpoint (NULL when neither was written after the start), and why, with
 * the engine's last word when its log has one from this attempt. A run that finished
 * after all (its output is there) is left to the sweep, which ingests it; one whose
 * engine still holds it past the wait is left to its next worker, which waits for it. */
int ingest_orphans(drv *d, sb_err *e)
{
	sqlite3_stmt *q;
	if (sql_exec(&d->db, e, &q,
		    "SELECT id, COALESCE(started, '') FROM run WHERE campaign = ? AND state = 'running' ORDER BY id", "t",
		    d->c.name))
		return e->code;
	/* read first: the writes below are transactions of their own */
	struct orphan {
		char id[128], started[32];
	} *o = NULL;
	size_t n = 0, cap = 0;
	while (sqlite3_step(q) == SQLITE_ROW) {
		if (n == cap) {
			struct orphan *m = realloc(o, (cap = cap ? 2 * cap : 16) * sizeof *o);
			if (!m) {
				sb_errf(e, SB_ENOMEM, "out of memory");
				break;
			}
			o = m;
		}
		snprintf(o[n].id, sizeof o[n].id, "%s", (const char *)sqlite3_column_text(q, 0));
		snprintf(o[n].started, sizeof o[n].started, "%s", (const char *)sqlite3_column_text(q, 1));
		n++;
	}
	sql_done(&d->db, q, e);
	const time_t deadline = time(NULL) + 10;
	for (size_t i = 0; i < n && !e->code; i++) {
		const char *id = o[i].id, *started = o[i].started;
		char path[PATHX + 16], logt[32], ckt[32], msg[1024], why[1400];
		layout_file(d->dir, 0, id, LAY_LOCK, path, sizeof path);
		if (!safe_name(id) || !lock_free(path, deadline))
			continue;
		layout_file(d->dir, 0, id, LAY_OUTPUT, path, sizeof path);
		if (exists(path))
			continue;
		layout_file(d->dir, 0, id, LAY_CKPT, path, sizeof path);
		mtime_iso(path, ckt, sizeof ckt);
		layout_file(d->dir, 0, id, LAY_LOG, path, sizeof path);
		mtime_iso(path, logt, sizeof logt);
		/* ISO times compare as strings; a file last written before the start is an
		 * earlier attempt's */
		const char *end = strcmp(logt, ckt) >= 0 ? logt : ckt;
		if (!end[0] || strcmp(end, started) < 0)
			end = NULL;
		msg[0] = 0;
		if (logt[0] && strcmp(logt, started) >= 0)
			worker_last_message(path, 0, msg, sizeof msg);
		/* (strstr: gcc sees the empty message of the path that read none) */
		int intr = strstr(msg, "shake: interrupted") == msg;
		if (intr)
			snprintf(why, sizeof why, "%s (recorded by the next study run: its driver was killed)", msg);
		else
			snprintf(why, sizeof why, "its driver was killed while it ran (recorded by the next study run); %s%s",
				 msg[0] ? "the engine's last word: " : "the engine left no word", msg);
		if (db_begin(&d->db, e))
			break;
		if (db_attempt(&d->db, d->c.name, id, intr ? SB_EINTR : -1, "interrupted", why, "", NULL, end, "pending", e))
			db_rollback(&d->db);
		else
			db_commit(&d->db, e);
	}
	free(o);
	return e->code;
}
