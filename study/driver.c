/* driver.c - `study run`: the only writer of the study database. Completion is
 * decided from each run's own output file (written atomically by the engine), never
 * from GNU parallel's bookkeeping, so any interruption is repaired by running again. */
#include "driver.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "campaign.h"
#include "changes.h"
#include "db.h"
#include "grid.h"
#include "h5sum.h"
#include "layout.h"
#include "safe.h"
#include "search.h"
#include "sharpen.h"
#include "worker.h"

#define PATHLEN 4096
#define PATHX (PATHLEN + 256)

typedef struct drv {
	const driver_opts *o;
	campaign c;
	grid g;
	st_db db;
	char root[PATHLEN];   /* absolute runs root */
	char dir[PATHLEN + 128];    /* root/name */
	char *cache_ok;       /* per grid run: start from the packing cache */
	char *started;        /* per grid run: 1 START seen, 2 DONE seen (this driver) */
	long *logfrom;        /* per grid run: size of its log when START was seen */
	long *pend;           /* per grid run: the indices of the runs to run */
	char **names;         /* their ids, for GNU parallel */
	int adaptive;         /* an [onset] campaign: the grid is its chains' runs, pass by pass */
	search srch;
	int autorep;          /* a grid with replicates = auto: its points' replicates, pass by pass */
	sharpen shp;
	long rounds;
	long n_ingested, n_failed_now;
	int jobs;
	int io_fault;         /* a run failed on I/O: launch nothing more */
	char io_msg[1200];
} drv;

static volatile sig_atomic_t g_stop;
static volatile sig_atomic_t g_parallel;

static void on_signal(int sig)
{
	(void)sig;
	if (!g_stop && g_parallel > 0)
		kill((pid_t)g_parallel, SIGTERM); /* no new jobs; running ones checkpoint */
	g_stop = 1;
}

void driver_db_path(const char *runs_dir, const char *db_path, char *out, size_t len)
{
	layout_db(runs_dir, db_path, out, len);
}

static int mkdir_p(const char *path, sb_err *e)
{
	char tmp[PATHLEN];
	snprintf(tmp, sizeof tmp, "%s", path);
	for (char *p = tmp + 1; *p; p++)
		if (*p == '/') {
			*p = 0;
			mkdir(tmp, 0777);
			*p = '/';
		}
	if (mkdir(tmp, 0777) && errno != EEXIST)
		return sb_errf(e, SB_EIO, "%s: cannot create directory: %s", path, strerror(errno));
	return 0;
}

static int exists(const char *p)
{
	return access(p, F_OK) == 0;
}

/* ---- ingestion ---- */

static void cache_state(drv *d, const char *key, char *st, size_t len);
static int ingest_cache(drv *d, const char *key, sb_err *e);

static int ingest_run(drv *d, const char *id, sb_err *e)
{
	char path[PATHX], now[32];
	layout_file(d->dir, 0, id, LAY_OUTPUT, path, sizeof path);
	db_now(now, sizeof now);
	h5sum s;
	sb_err re = {0};
	if (db_begin(&d->db, e))
		return e->code;
	if (h5sum_read(path, &s, &re)) {
		db_attempt(&d->db, d->c.name, id, SB_EIO, "io", re.msg, "", now, "failed", e);
	} else {
		/* the file says whether the run started from the packing cache: a database
		 * rebuilt from the files gets from_cache and the cache's row back */
		const grid_run *r = grid_find(&d->g, id);
		char want[128];
		layout_cache_particles("", r ? r->cache_key : "", want, sizeof want);
		if (r && !strcmp(s.particles, want)) {
			char st[16];
			cache_state(d, r->cache_key, st, sizeof st);
			char h5[PATHX];
			layout_file(d->dir, 1, r->cache_key, LAY_OUTPUT, h5, sizeof h5);
			if (!st[0] && exists(h5))
				ingest_cache(d, r->cache_key, e);
			if (!e->code)
				db_exec(&d->db, e, NULL, "UPDATE run SET from_cache = 1 WHERE campaign = ? AND id = ?", "tt",
					d->c.name, id);
		}
		if (!e->code)
			db_ingest(&d->db, d->c.name, id, &s, now, e);
	}
	if (e->code) {
		db_rollback(&d->db);
		return e->code;
	}
	d->n_ingested++;
	if (re.code || strcmp(h5sum_text(&s, "status"), "ok"))
		d->n_failed_now++;
	return db_commit(&d->db, e);
}

static int ingest_cache(drv *d, const char *key, sb_err *e)
{
	char path[PATHX], txt[PATHX], now[32];
	layout_file(d->dir, 1, key, LAY_OUTPUT, path, sizeof path);
	layout_cache_particles(d->dir, key, txt, sizeof txt);
	db_now(now, sizeof now);
	h5sum s;
	sb_err re = {0};
	h5sum_read(path, &s, &re);
	int okc = !re.code && !strcmp(h5sum_text(&s, "status"), "ok") && exists(txt);
	const char *end = h5sum_text(&s, "end_time");
	return db_exec(&d->db, e, NULL,
		       "INSERT OR REPLACE INTO cache(campaign, key, state, settle_time, settle_steps, wall_seconds,"
		       " host, message, built) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)",
		       "tttdldttt", d->c.name, key, okc ? "ok" : "failed", h5sum_real(&s, "settle_time"),
		       h5sum_int(&s, "settle_steps"), h5sum_real(&s, "wall_seconds"), h5sum_text(&s, "host"),
		       re.code ? re.msg : h5sum_text(&s, "message"), end[0] ? end : now);
}

static void cache_state(drv *d, const char *key, char *st, size_t len)
{
	sqlite3_stmt *q;
	sb_err e = {0};
	st[0] = 0;
	if (db_exec(&d->db, &e, &q, "SELECT state FROM cache WHERE campaign = ? AND key = ?", "tt", d->c.name, key))
		return;
	if (sqlite3_step(q) == SQLITE_ROW && sqlite3_column_text(q, 0))
		snprintf(st, len, "%s", (const char *)sqlite3_column_text(q, 0));
	sqlite3_finalize(q);
}

/* A DONE line from a worker: the output file decides; without one, the exit code. */
static int on_done(drv *d, int is_cache, char *line, sb_err *e)
{
	char *f[6] = {0};
	int n = 0;
	for (char *s = line, *t; n < 6 && (t = strsep(&s, "\t"));)
		f[n++] = t;
	if (n < 6 || !safe_name(f[1]))
		return 0;
	const char *name = f[1], *host = f[3], *msg = f[5];
	long code = strtol(f[2], NULL, 10);
	char path[PATHX];
	if (is_cache) {
		layout_file(d->dir, 1, name, LAY_OUTPUT, path, sizeof path);
		if (exists(path) || (code != 0 && code != SB_EINTR && code < 128)) {
			if (db_begin(&d->db, e))
				return e->code;
			if (exists(path))
				ingest_cache(d, name, e);
			else
				db_exec(&d->db, e, NULL,
					"INSERT OR REPLACE INTO cache(campaign, key, state, host, message) VALUES (?, ?, 'failed', ?, ?)",
					"tttt", d->c.name, name, host, msg);
			return e->code ? (db_rollback(&d->db), e->code) : db_commit(&d->db, e);
		}
		return 0;
	}
	const grid_run *r = grid_find(&d->g, name);
	if (!r)
		return 0;
	d->started[r - d->g.runs] = 2;
	layout_file(d->dir, 0, name, LAY_OUTPUT, path, sizeof path);
	if (exists(path))
		return ingest_run(d, name, e);
	if (code == 0)
		return 0; /* output still on its way back from a remote host: the final sweep */
	/* interrupted (7) or killed by a signal: resumable, stays pending. An I/O fault
	 * (2: a full disk, a read-only directory) is the machine's, not the run's: the run
	 * stays pending and no further run starts, since every one would fail the same way
	 * and a queue emptied in seconds would be marked failed. Bad input (1) fails. */
	int io = code == SB_EIO;
	int resumable = code == SB_EINTR || code >= 128 || io;
	const char *status = code == SB_EINTR ? "interrupted" : code >= 128 ? "killed" : sb_code_name((int)code);
	if (io && !d->io_fault) {
		d->io_fault = 1;
		snprintf(d->io_msg, sizeof d->io_msg, "run %s: %s", name, msg);
		if (g_parallel > 0)
			kill((pid_t)g_parallel, SIGTERM); /* no new jobs; running ones checkpoint */
	}
	char now[32];
	db_now(now, sizeof now);
	if (db_begin(&d->db, e))
		return e->code;
	if (db_attempt(&d->db, d->c.name, name, code, status, msg, host, now, resumable ? "pending" : "failed", e)) {
		db_rollback(&d->db);
		return e->code;
	}
	if (!resumable)
		d->n_failed_now++;
	return db_commit(&d->db, e);
}

static int on_start(drv *d, char *line, sb_err *e)
{
	char *f[3] = {0};
	int n = 0;
	for (char *s = line, *t; n < 3 && (t = strsep(&s, "\t"));)
		f[n++] = t;
	const grid_run *r = n < 3 ? NULL : grid_find(&d->g, f[1]);
	if (!r)
		return 0;
	d->started[r - d->g.runs] = 1;
	/* where this attempt's lines begin in the run's log (earlier attempts precede) */
	char lp[PATHX];
	struct stat sb;
	layout_file(d->dir, 0, r->id, LAY_LOG, lp, sizeof lp);
	d->logfrom[r - d->g.runs] = stat(lp, &sb) == 0 ? (long)sb.st_size : 0;
	char now[32];
	db_now(now, sizeof now);
	if (db_begin(&d->db, e))
		return e->code;
	if (db_exec(&d->db, e, NULL,
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
static void unreported(drv *d, sb_err *e)
{
	for (long i = 0; i < d->g.n && !e->code; i++) {
		if (d->started[i] != 1)
			continue;
		d->started[i] = 2;
		const char *id = d->g.runs[i].id;
		char path[PATHX], msg[1024] = "", now[32];
		layout_file(d->dir, 0, id, LAY_OUTPUT, path, sizeof path);
		if (exists(path))
			continue; /* finished after all: the sweep ingests it */
		layout_file(d->dir, 0, id, LAY_LOG, path, sizeof path);
		worker_last_message(path, d->logfrom[i], msg, sizeof msg);
		/* the engine's words when SIGTERM/SIGINT stopped it (while settling there is
		 * no checkpoint yet, and it says so) */
		int intr = !strncmp(msg, "shake: interrupted", 18) || strstr(msg, "checkpoint") != NULL;
		db_now(now, sizeof now);
		if (db_begin(&d->db, e))
			return;
		if (db_attempt(&d->db, d->c.name, id, intr ? SB_EINTR : -1, "interrupted",
			       msg[0] ? msg : "stopped with the driver", "", now, "pending", e))
			db_rollback(&d->db);
		else
			db_commit(&d->db, e);
	}
}

/* ---- job files ---- */

/* Every parameter as key=value, one per line: the worker passes the lines to
 * bin/shake as argv, so no value ever passes through a shell. Written once
 * (temporary name, rename): a resumed run gets exactly the arguments it started with,
 * which restart = auto requires. */
static int write_args(const char *path, const sb_scene *s, sb_err *e)
{
	if (exists(path))
		return 0;
	char tmp[PATHX];
	snprintf(tmp, sizeof tmp, "%s.tmp.%ld", path, (long)getpid());
	FILE *f = fopen(tmp, "w");
	if (!f)
		return sb_errf(e, SB_EIO, "%s: cannot create: %s", tmp, strerror(errno));
	size_t n;
	const sb_param *t = params_table(&n);
	for (size_t i = 0; i < n; i++) {
		char v[SB_STR_MAX + 8];
		params_format(s, &t[i], v, sizeof v);
		fprintf(f, "%s=%s\n", t[i].name, v);
	}
	int bad = ferror(f) | (fflush(f) != 0) | (fsync(fileno(f)) != 0);
	bad |= fclose(f) != 0;
	if (bad || rename(tmp, path)) {
		unlink(tmp);
		return sb_errf(e, SB_EIO, "%s: cannot write: %s", path, strerror(errno));
	}
	return 0;
}

static void driver_owned(sb_scene *s, const char *output)
{
	snprintf(s->output, sizeof s->output, "%s", output);
	s->checkpoint[0] = 0;
	s->write_particles[0] = 0;
	s->write_lammps[0] = 0;
	s->progress = TRI_NO;
	s->restart = TRI_AUTO;
	/* checkpoints make a killed run resume instead of starting over; a tenth of the
	 * run (at most 30 simulated s) bounds the lost work, unless [scene] says */
	if (s->checkpoint_every <= 0) {
		double c = s->duration / 10;
		s->checkpoint_every = c > 30 ? 30 : c;
	}
}

/* ---- GNU parallel ---- */

static int add_arg(char **argv, int *argc, int max, const char *fmt, const char *a, const char *b)
{
	if (*argc >= max - 1)
		return -1;
	char buf[3 * PATHX];
	snprintf(buf, sizeof buf, fmt, a, b);
	argv[(*argc)++] = strdup(buf);
	argv[*argc] = NULL;
	return 0;
}

/* Runs `study exec` for every name in names through GNU parallel and handles the
 * workers' lines as they arrive. */
static int run_parallel(drv *d, const char *kind, char **names, long n, char **basefiles, long nbase,
			sb_err *e)
{
	int is_cache = !strcmp(kind, "cache");
	char jobfile[PATHX], joblog[PATHX];
	snprintf(jobfile, sizeof jobfile, "%s/%s.jobs", d->dir, kind);
	snprintf(joblog, sizeof joblog, "+%s/joblog.txt", d->dir);
	FILE *jf = fopen(jobfile, "w");
	if (!jf)
		return sb_errf(e, SB_EIO, "%s: cannot create: %s", jobfile, strerror(errno));
	for (long i = 0; i < n; i++)
		fprintf(jf, "%s\n", names[i]);
	if (fclose(jf))
		return sb_errf(e, SB_EIO, "%s: cannot write", jobfile);

	enum { MAXA = 4096 };
	char **argv = calloc(MAXA, sizeof *argv);
	int argc = 0;
	char njobs[32];
	snprintf(njobs, sizeof njobs, "%d", d->jobs);
	const char *fixed[] = {"parallel", "--will-cite", "--jobs", njobs, "--joblog", joblog, "--arg-file", jobfile};
	for (size_t i = 0; i < sizeof fixed / sizeof *fixed; i++)
		add_arg(argv, &argc, MAXA, "%s%s", fixed[i], "");
	int tty = d->o->progress < 0 ? isatty(2) : d->o->progress;
	if (tty)
		add_arg(argv, &argc, MAXA, "%s%s", "--bar", "");
	char q1[PATHX], q2[PATHX];
	if (d->o->sshloginfile) {
		/* Remote: the binaries go once per host (--basefile), each job's argument file
		 * goes out and its output and log come back (--transferfile, --return). The
		 * "/./" marks where the path relative to the remote work dir starts. Output is
		 * grouped per job, so a DONE line arrives after its files are back. */
		char bindir[PATHX];
		snprintf(bindir, sizeof bindir, "%s", d->o->self);
		*strrchr(bindir, '/') = 0;
		char wd[PATHLEN];
		snprintf(wd, sizeof wd, ".shakebox/%s", d->c.name);
		add_arg(argv, &argc, MAXA, "--sshloginfile%s%s", "", "");
		add_arg(argv, &argc, MAXA, "%s%s", d->o->sshloginfile, "");
		add_arg(argv, &argc, MAXA, "--workdir%s%s", "", "");
		add_arg(argv, &argc, MAXA, "%s%s", wd, "");
		add_arg(argv, &argc, MAXA, "--basefile%s%s", "", "");
		add_arg(argv, &argc, MAXA, "%s/./%s", bindir, "study");
		add_arg(argv, &argc, MAXA, "--basefile%s%s", "", "");
		add_arg(argv, &argc, MAXA, "%s/./%s", bindir, "shake");
		for (long i = 0; i < nbase; i++) {
			add_arg(argv, &argc, MAXA, "--basefile%s%s", "", "");
			add_arg(argv, &argc, MAXA, "%s/./cache/%s.txt", d->dir, basefiles[i]);
		}
		const char *xfer = is_cache ? "%s/./cache/{}.args%s" : "%s/./jobs/{}.args%s";
		add_arg(argv, &argc, MAXA, "--transferfile%s%s", "", "");
		add_arg(argv, &argc, MAXA, xfer, d->dir, "");
		const char *ret_run[] = {"%s/./{}.h5%s", "%s/./logs/{}.log%s", NULL};
		const char *ret_cache[] = {"%s/./cache/{}.h5%s", "%s/./cache/{}.txt%s", "%s/./cache/{}.log%s", NULL};
		for (const char **r = is_cache ? ret_cache : ret_run; *r; r++) {
			add_arg(argv, &argc, MAXA, "--return%s%s", "", "");
			add_arg(argv, &argc, MAXA, *r, d->dir, "");
		}
		add_arg(argv, &argc, MAXA, "%s%s", "./study exec . ", kind);
		add_arg(argv, &argc, MAXA, "%s%s", "{}", "");
	} else {
		/* Local: parallel joins the command words into a shell command line, so the
		 * two paths are single-quoted; the job name is a hex id (and parallel quotes {}). */
		if (safe_shell_quote(d->o->self, q1, sizeof q1) || safe_shell_quote(d->dir, q2, sizeof q2)) {
			free(argv);
			return sb_errf(e, SB_EUSAGE, "path too long");
		}
		add_arg(argv, &argc, MAXA, "--line-buffer%s%s", "", "");
		add_arg(argv, &argc, MAXA, "%s exec %s", q1, q2);
		add_arg(argv, &argc, MAXA, "%s%s", kind, "");
		add_arg(argv, &argc, MAXA, "%s%s", "{}", "");
	}

	int pfd[2];
	if (pipe(pfd)) {
		sb_errf(e, SB_EIO, "pipe: %s", strerror(errno));
		goto out;
	}
	pid_t pid = fork();
	if (pid < 0) {
		sb_errf(e, SB_EIO, "fork: %s", strerror(errno));
		goto out;
	}
	if (pid == 0) {
		/* a driver killed outright takes parallel with it: no new jobs start, and
		 * running ones are stopped with a checkpoint */
		prctl(PR_SET_PDEATHSIG, SIGTERM);
		close(pfd[0]);
		dup2(pfd[1], 1);
		close(pfd[1]);
		int dn = open("/dev/null", O_RDONLY);
		if (dn >= 0)
			dup2(dn, 0);
		execvp(argv[0], argv);
		fprintf(stderr, "study: cannot run GNU parallel: %s\n", strerror(errno));
		_exit(127);
	}
	g_parallel = pid;
	close(pfd[1]);
	FILE *in = fdopen(pfd[0], "r");
	char *line = NULL;
	size_t cap = 0;
	ssize_t got;
	while (in && ((got = getline(&line, &cap, in)) >= 0 || errno == EINTR)) {
		if (got < 0) {
			clearerr(in);
			errno = 0;
			continue;
		}
		line[strcspn(line, "\n")] = 0;
		sb_err le = {0};
		if (!strncmp(line, WORKER_START "\t", sizeof WORKER_START))
			on_start(d, line, &le);
		else if (!strncmp(line, WORKER_DONE "\t", sizeof WORKER_DONE))
			on_done(d, is_cache, line, &le);
		else if (line[0])
			fprintf(stderr, "%s\n", line);
		if (le.code)
			fprintf(stderr, "study: %s\n", le.msg); /* the final sweep repairs it */
	}
	free(line);
	if (in)
		fclose(in);
	int st = 0;
	while (waitpid(pid, &st, 0) < 0 && errno == EINTR)
		;
	g_parallel = 0;
	if (!is_cache)
		unreported(d, e);
	if (WIFEXITED(st) && WEXITSTATUS(st) == 127 && !g_stop)
		sb_errf(e, SB_EIO, "GNU parallel did not start (is it installed? make deps)");
	else if (WIFEXITED(st) && WEXITSTATUS(st) == 255 && !g_stop && !d->io_fault)
		sb_errf(e, SB_EIO, "GNU parallel failed (see the messages above)");
out:
	for (int i = 0; i < argc; i++)
		free(argv[i]);
	free(argv);
	return e->code;
}

/* ---- the campaign ---- */

static int record(drv *d, sb_err *e)
{
	char now[32];
	db_now(now, sizeof now);
	if (db_begin(&d->db, e))
		return e->code;
	db_campaign_put(&d->db, &d->c, now, e);
	for (long i = 0; i < d->g.n && !e->code; i++) {
		sb_scene s;
		grid_scene(&d->g, &d->g.runs[i], &s);
		db_run_add(&d->db, &d->c, &d->g.runs[i], &s, now, e);
	}
	/* nothing runs while this driver holds the campaign lock: a 'running' row is
	 * left from a driver that was killed */
	if (!e->code)
		db_exec(&d->db, e, NULL, "UPDATE run SET state = 'pending' WHERE campaign = ? AND state = 'running'",
			"t", d->c.name);
	if (e->code) {
		db_rollback(&d->db);
		return e->code;
	}
	return db_commit(&d->db, e);
}

/* A done run whose file is damaged or gone: the file moves to damaged/, the attempt
 * is recorded with the reason, the result row goes, and the run is pending again. */
static int requeue_damaged(drv *d, const char *id, long att, const char *why, sb_err *e)
{
	char path[PATHX], keep[PATHX + 64], now[32];
	layout_file(d->dir, 0, id, LAY_OUTPUT, path, sizeof path);
	if (exists(path)) {
		layout_sub(d->dir, "damaged", keep, sizeof keep);
		if (mkdir_p(keep, e))
			return e->code;
		layout_aside(d->dir, "damaged", id, att, keep, sizeof keep);
		if (rename(path, keep))
			return sb_errf(e, SB_EIO, "%s: cannot move aside: %s", path, strerror(errno));
	}
	fprintf(stderr, "study: %s: run %s was done but %s: run again\n", d->c.name, id, why);
	db_now(now, sizeof now);
	if (db_begin(&d->db, e))
		return e->code;
	if (db_attempt(&d->db, d->c.name, id, SB_EIO, "damaged", why, "", now, "pending", e) ||
	    db_exec(&d->db, e, NULL, "DELETE FROM result WHERE campaign = ? AND run = ?", "tt", d->c.name, id)) {
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
	static const char *const stale[] = {".ckpt", ".journal"}; /* the engine's, beside its output */
	char p[PATHX + 256];
	for (size_t k = 0; k < sizeof stale / sizeof *stale; k++) {
		int l = layout_file(d->dir, 0, id, LAY_OUTPUT, p, sizeof p - 16);
		snprintf(p + l, sizeof p - (size_t)l, "%s", stale[k]);
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
	if (db_exec(&d->db, &e, &q, "SELECT 1 FROM result WHERE campaign = ? AND run = ?", "tt", d->c.name, id))
		return 1;
	int found = sqlite3_step(q) == SQLITE_ROW;
	sqlite3_finalize(q);
	return found;
}

/* Ingest every output that exists but is not recorded (finished while no driver was
 * listening), and with --retry-failed put failed runs back in the queue. Returns the
 * pending runs' indices in *pend. */
static int sweep(drv *d, long *pend, long *npend, sb_err *e)
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
			if (ingest_run(d, r->id, e))
				return e->code;
			continue;
		}
		if (!strcmp(st, "done") && pend) {
			/* a finished run's file is read again on every sweep: a truncated or
			 * deleted one puts the run back in the queue instead of shrinking its
			 * group silently */
			h5sum s;
			sb_err re = {0};
			if (!exists(path) || h5sum_read(path, &s, &re)) {
				if (requeue_damaged(d, r->id, att, exists(path) ? re.msg : "the output file is missing", e))
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
			if (!h5sum_read(path, &s, &re)) {
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
				if (rename(path, keep))
					return sb_errf(e, SB_EIO, "%s: cannot move aside: %s", path, strerror(errno));
			}
			if (db_begin(&d->db, e))
				return e->code;
			if (db_exec(&d->db, e, NULL, "UPDATE run SET state = 'pending' WHERE campaign = ? AND id = ?", "tt",
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

static int by_str(const void *a, const void *b)
{
	return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The packing cache: preparation keys shared by two or more pending runs (or already
 * built) settle once, in a job of their own; every run then starts from the file. */
static int caches(drv *d, const long *pend, long npend, char ***basefiles, long *nbase, sb_err *e)
{
	*nbase = 0;
	*basefiles = NULL;
	if (!d->o->use_cache || npend == 0)
		return 0;
	char **keys = calloc((size_t)npend, sizeof *keys);
	long *first = calloc((size_t)npend, sizeof *first);
	long nk = 0;
	char **build = calloc((size_t)npend, sizeof *build);
	long nb = 0;
	*basefiles = calloc((size_t)npend, sizeof **basefiles);
	if (!keys || !first || !build || !*basefiles) {
		free(keys), free(first), free(build);
		return sb_errf(e, SB_ENOMEM, "out of memory");
	}
	/* count the runs per key (quadratic only in the number of distinct keys' lookups) */
	long *count = calloc((size_t)npend, sizeof *count);
	for (long i = 0; i < npend; i++) {
		const grid_run *r = &d->g.runs[pend[i]];
		sb_scene s;
		grid_scene(&d->g, r, &s);
		if (s.particles[0] || s.settle == TRI_NO)
			continue; /* nothing to settle, or a user file: no cache */
		long k;
		for (k = 0; k < nk; k++)
			if (!strcmp(keys[k], r->cache_key))
				break;
		if (k == nk) {
			keys[nk] = (char *)r->cache_key;
			first[nk++] = pend[i];
		}
		count[k]++;
	}
	for (long k = 0; k < nk && !e->code; k++) {
		char st[16], h5[PATHX];
		cache_state(d, keys[k], st, sizeof st);
		layout_file(d->dir, 1, keys[k], LAY_OUTPUT, h5, sizeof h5);
		if (!strcmp(st, "failed") && d->o->retry_failed) {
			unlink(h5);
			st[0] = 0;
		}
		if (!st[0] && exists(h5)) {
			if (!db_begin(&d->db, e) && !ingest_cache(d, keys[k], e))
				db_commit(&d->db, e);
			else
				db_rollback(&d->db);
			cache_state(d, keys[k], st, sizeof st);
		}
		/* a replicate of an [onset] search runs several frequencies, one at a time:
		 * its packing is worth settling once from its first run on */
		if (st[0] || count[k] < (d->adaptive ? 1 : 2))
			continue;
		sb_scene s;
		grid_scene(&d->g, &d->g.runs[first[k]], &s);
		char args[PATHX], out[64];
		layout_file(d->dir, 1, keys[k], LAY_ARGS, args, sizeof args);
		layout_file("", 1, keys[k], LAY_OUTPUT, out, sizeof out);
		driver_owned(&s, out);
		s.duration = 0;
		s.checkpoint_every = 0;
		s.restart = TRI_NO;
		layout_cache_particles("", keys[k], s.write_particles, sizeof s.write_particles);
		if (!write_args(args, &s, e))
			build[nb++] = keys[k];
	}
	if (nb && !e->code) {
		fprintf(stderr, "study: %s: settling %ld shared packing%s\n", d->c.name, nb, nb > 1 ? "s" : "");
		run_parallel(d, "cache", build, nb, NULL, 0, e);
	}
	for (long k = 0; k < nk && !e->code; k++) {
		char st[16];
		cache_state(d, keys[k], st, sizeof st);
		if (strcmp(st, "ok"))
			continue;
		(*basefiles)[(*nbase)++] = strdup(keys[k]);
		for (long i = 0; i < npend; i++)
			if (!strcmp(d->g.runs[pend[i]].cache_key, keys[k]))
				d->cache_ok[pend[i]] = 1;
	}
	free(keys);
	free(first);
	free(build);
	free(count);
	return e->code;
}

static int prepare_jobs(drv *d, const long *pend, long npend, char **names, sb_err *e)
{
	for (long i = 0; i < npend && !e->code; i++) {
		const grid_run *r = &d->g.runs[pend[i]];
		char args[PATHX], out[64];
		layout_file(d->dir, 0, r->id, LAY_ARGS, args, sizeof args);
		layout_file("", 0, r->id, LAY_OUTPUT, out, sizeof out);
		names[i] = (char *)r->id;
		if (exists(args))
			continue; /* a resumed run keeps its arguments (and its cache choice) */
		sb_scene s;
		grid_scene(&d->g, r, &s);
		driver_owned(&s, out);
		int fc = d->cache_ok[pend[i]];
		if (fc) {
			/* bit-identical to settling here (engine contract); only the particles,
			 * settle and settle_* attributes of the output differ */
			layout_cache_particles("", r->cache_key, s.particles, sizeof s.particles);
			s.settle = TRI_NO;
		}
		if (db_begin(&d->db, e))
			break;
		if (db_exec(&d->db, e, NULL, "UPDATE run SET from_cache = ? WHERE campaign = ? AND id = ?", "ltt",
			    (long)fc, d->c.name, r->id)) {
			db_rollback(&d->db);
			break;
		}
		if (db_commit(&d->db, e))
			break;
		write_args(args, &s, e);
	}
	return e->code;
}

static void counts(drv *d, long *done, long *failed, long *pending)
{
	*done = *failed = *pending = 0;
	for (long i = 0; i < d->g.n; i++) {
		char st[16];
		long att;
		sb_err e = {0};
		db_run_state(&d->db, d->c.name, d->g.runs[i].id, st, sizeof st, &att, &e);
		if (!strcmp(st, "done"))
			(*done)++;
		else if (!strcmp(st, "failed"))
			(*failed)++;
		else
			(*pending)++;
	}
}

/* The per-run arrays for the grid as it is now (an [onset] campaign's grid grows
 * pass by pass). */
static int alloc_runs(drv *d, sb_err *e)
{
	free(d->pend);
	free(d->names);
	free(d->cache_ok);
	free(d->started);
	free(d->logfrom);
	d->pend = calloc((size_t)d->g.n + 1, sizeof *d->pend);
	d->names = calloc((size_t)d->g.n + 1, sizeof *d->names);
	d->cache_ok = calloc((size_t)d->g.n + 1, 1);
	d->started = calloc((size_t)d->g.n + 1, 1);
	d->logfrom = calloc((size_t)d->g.n + 1, sizeof *d->logfrom);
	if (!d->pend || !d->names || !d->cache_ok || !d->started || !d->logfrom)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	return 0;
}

/* Runs the pending runs: their packings, their argument files, GNU parallel. */
static int launch(drv *d, long npend, sb_err *e)
{
	char **basefiles = NULL;
	long nbase = 0;
	if (!caches(d, d->pend, npend, &basefiles, &nbase, e) && !g_stop &&
	    !prepare_jobs(d, d->pend, npend, d->names, e)) {
		if (nbase)
			qsort(basefiles, (size_t)nbase, sizeof *basefiles, by_str);
		run_parallel(d, "run", d->names, npend, basefiles, nbase, e);
	}
	for (long i = 0; i < nbase; i++)
		free(basefiles[i]);
	free(basefiles);
	return e->code;
}

/* Does the campaign file still ask for a recorded run? An [onset] campaign's runs are
 * its chains' so far, and more may come: a run belongs to it when some chain can ask
 * for it; with replicates = auto, when it is a replicate of a grid point. */
static int asks_for(void *ctx, const char *id, long replicate, double frequency)
{
	drv *d = ctx;
	if (d->autorep)
		return sharpen_member(&d->shp, d->g.points, replicate, id);
	return d->adaptive ? search_member(&d->c, d->g.points, replicate, frequency, id) : grid_find(&d->g, id) != NULL;
}

static int check_changes(drv *d, sb_err *e)
{
	changes_ctx x = {&d->db, &d->c, &d->g, d->dir, d->o->keep_old, d->o->forget_old, asks_for, d};
	return changes_check(&x, e);
}

/* A pass of an [onset] campaign: its chains walked again from the database and the
 * files (search.c), their runs as the grid, recorded, the search's state stored; of a
 * grid with replicates = auto likewise its points' replicates (sharpen.c). On the
 * first pass, recorded runs that it cannot ask for are a changed campaign. */
static int onset_pass(drv *d, int first, sb_err *e)
{
	grid_free(&d->g);
	if (grid_expand(&d->g, &d->c, e) ||
	    (d->autorep ? sharpen_derive(&d->shp, &d->g, &d->db, e) : search_derive(&d->srch, &d->g, &d->db, e)))
		return e->code;
	if (first && check_changes(d, e))
		return e->code;
	if (record(d, e) || (d->autorep ? sharpen_store(&d->shp, &d->db, e) : search_store(&d->srch, &d->db, e)))
		return e->code;
	return alloc_runs(d, e);
}

/* An [onset] campaign, round by round: each round runs what the chains wait for (one
 * run per unanswered replicate), and the next pass chooses from its results. A pass
 * that finds results nobody had recorded (a driver killed mid-round) walks again
 * before anything runs, so a resumed search asks for the points it would have. A grid
 * with replicates = auto goes the same way, a batch of replicates per round. */
static int run_onset(drv *d, sb_err *e)
{
	for (int first = 1;; first = 0) {
		if (onset_pass(d, first, e))
			return e->code;
		long got = d->n_ingested, failed = d->n_failed_now, npend;
		if (sweep(d, d->pend, &npend, e))
			return e->code;
		if (d->n_ingested > got)
			continue;
		if (!npend || g_stop || d->io_fault)
			return 0;
		long searching = 0, groups = d->autorep ? d->shp.npoints : d->srch.ngroups;
		for (long i = 0; i < groups; i++)
			searching += d->autorep ? d->shp.pts[i].state == SH_RUNNING : d->srch.groups[i].state == AD_G_SEARCHING;
		d->rounds++;
		fprintf(stderr, "study: %s: %s round %ld: %ld run%s, %ld of %ld %s%s %s, %d job%s%s%s\n", d->c.name,
			d->autorep ? "replicates" : "onset", d->rounds, npend, npend > 1 ? "s" : "", searching, groups,
			d->autorep ? "point" : "group", groups > 1 ? "s" : "", d->autorep ? "running" : "searching",
			d->jobs, d->jobs > 1 ? "s" : "", d->o->sshloginfile ? " per host of " : "",
			d->o->sshloginfile ? d->o->sshloginfile : "");
		if (launch(d, npend, e) || g_stop || d->io_fault)
			return e->code;
		if (d->n_ingested == got && d->n_failed_now == failed)
			return 0; /* nothing finished (every run stopped): the next `study run` goes on */
	}
}

/* "2.68", "< 2.5", "> 3.2": an end of an interval or an estimate */
static void onset_number(double v, char *buf, size_t len)
{
	if (isnan(v))
		snprintf(buf, len, "none");
	else if (isinf(v))
		snprintf(buf, len, "%s", v < 0 ? "-inf" : "+inf");
	else
		snprintf(buf, len, "%.6g", v);
}

/* One line per group of an [onset] campaign: where its search stands. */
static void onset_summary(drv *d)
{
	const cp_onset *o = &d->c.onset;
	for (long i = 0; i < d->srch.ngroups; i++) {
		const srch_group *gr = &d->srch.groups[i];
		char est[32], lo[32], hi[32];
		onset_number(gr->iv.est, est, sizeof est);
		onset_number(gr->iv.lo, lo, sizeof lo);
		onset_number(gr->iv.hi, hi, sizeof hi);
		long found = 0;
		for (long k = 0; k < gr->nrep; k++)
			found += gr->reps[k].state == AD_FOUND;
		fprintf(stderr, "study: %s: %s: onset %s%s, %g%% interval [%s, %s], %ld replicate%s (%ld found), %ld runs: %s\n",
			d->c.name, gr->label, est, isnan(gr->iv.est) ? " (no replicate answered)" : " Hz", 100 * o->level,
			lo, hi, gr->nrep, gr->nrep > 1 ? "s" : "", found, gr->runs, adapt_gstate_name(gr->state));
	}
}

/* One line per point of a grid with replicates = auto: the interval it reached. */
static void autorep_summary(drv *d)
{
	const cp_auto *a = &d->c.autorep;
	for (long i = 0; i < d->shp.npoints; i++) {
		const shp_point *pt = &d->shp.pts[i];
		char est[32], lo[32], hi[32], w[32];
		onset_number(pt->ev.est, est, sizeof est);
		onset_number(pt->ev.lo, lo, sizeof lo);
		onset_number(pt->ev.hi, hi, sizeof hi);
		onset_number(pt->ev.width, w, sizeof w);
		fprintf(stderr, "study: %s: %s: %s %s, %g%% interval [%s, %s] (width %s, target %g), %ld replicate%s "
			"(%ld used): %s\n", d->c.name, pt->label, sharp_result_name(a->result), est, 100 * a->level, lo, hi,
			w, a->target, pt->nrep, pt->nrep > 1 ? "s" : "", pt->ev.used, sharp_state_name(pt->state));
	}
}

int driver_run(const driver_opts *o, sb_err *e)
{
	drv *d = calloc(1, sizeof *d);
	if (!d)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	d->o = o;
	int lock = -1;
	if (campaign_load(&d->c, o->campaign_file, e) || grid_expand(&d->g, &d->c, e))
		goto out;
	d->adaptive = d->c.onset.line != 0;
	d->autorep = d->c.autorep.on;
	d->jobs = o->jobs > 0 ? o->jobs : (int)sysconf(_SC_NPROCESSORS_ONLN);
	if (d->jobs < 1)
		d->jobs = 1;
	const char *rd = o->runs_dir ? o->runs_dir : "runs";
	if (mkdir_p(rd, e))
		goto out;
	if (!realpath(rd, d->root)) {
		sb_errf(e, SB_EIO, "%s: %s", rd, strerror(errno));
		goto out;
	}
	if (strlen(d->root) > 3000) {
		sb_errf(e, SB_EUSAGE, "%s: path too long", d->root);
		goto out;
	}
	/* the campaign name is checked ([A-Za-z0-9_.-], no leading dot): this stays inside root */
	layout_campaign(d->root, d->c.name, d->dir, sizeof d->dir);
	const char *sub[] = {"", "/jobs", "/logs", "/cache", "/failed"};
	for (size_t i = 0; i < sizeof sub / sizeof *sub; i++) {
		char p[PATHX];
		snprintf(p, sizeof p, "%s%s", d->dir, sub[i]);
		if (mkdir_p(p, e))
			goto out;
	}
	char lp[PATHX];
	snprintf(lp, sizeof lp, "%s/.driver.lock", d->dir);
	lock = open(lp, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
	if (lock < 0 || flock(lock, LOCK_EX | LOCK_NB)) {
		sb_errf(e, DRV_BUSY, "campaign %s is being run by another study driver (%s)", d->c.name, lp);
		goto out;
	}
	if (d->adaptive)
		search_init(&d->srch, &d->c, d->dir);
	if (d->autorep)
		sharpen_init(&d->shp, &d->c, d->dir);
	char dbp[PATHLEN];
	driver_db_path(o->runs_dir, o->db_path, dbp, sizeof dbp);
	int rounds = d->adaptive || d->autorep; /* the grid grows pass by pass */
	if (db_open(&d->db, dbp, 1, e) || (!rounds && (check_changes(d, e) || record(d, e))))
		goto out;

	struct sigaction sa;
	memset(&sa, 0, sizeof sa);
	sa.sa_handler = on_signal;
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);

	long npend;
	if (rounds) {
		if (run_onset(d, e) && e->code == SB_EUSAGE)
			goto out; /* a changed campaign: nothing ran */
	} else {
		if (alloc_runs(d, e) || sweep(d, d->pend, &npend, e))
			goto out;
		fprintf(stderr, "study: %s: %ld runs, %ld to run, %d job%s%s%s\n", d->c.name, d->g.n, npend, d->jobs,
			d->jobs > 1 ? "s" : "", o->sshloginfile ? " per host of " : "",
			o->sshloginfile ? o->sshloginfile : "");
		if (npend && !g_stop && !d->io_fault)
			launch(d, npend, e);
	}
	sb_err se = {0};
	sweep(d, NULL, &npend, &se); /* outputs that came back after their DONE line */
	if (rounds && !e->code && !se.code) {
		/* the state after the last round, for study status */
		onset_pass(d, 0, &se);
		if (d->autorep)
			autorep_summary(d);
		else
			onset_summary(d);
	}
	long done, failed, pending;
	counts(d, &done, &failed, &pending);
	fprintf(stderr, "study: %s: %ld done, %ld failed, %ld pending (ingested %ld now)\n", d->c.name, done, failed,
		pending, d->n_ingested);
	if (!e->code && se.code)
		sb_errf(e, se.code, "%s", se.msg);
	if (!e->code && d->io_fault)
		sb_errf(e, SB_EIO,
			"%s: I/O fault (%s): no further run was started; %ld runs are pending. Fix the cause (disk space, "
			"permissions) and run the same command again",
			d->c.name, d->io_msg, pending);
	else if (!e->code && (g_stop || pending))
		sb_errf(e, DRV_INTERRUPTED, "%s: %ld runs not complete; run the same command again to resume",
			d->c.name, pending);
	else if (!e->code && failed)
		sb_errf(e, DRV_FAILED, "%s: %ld runs failed (study status %s lists the reasons)", d->c.name, failed,
			d->c.name);
out:
	free(d->pend);
	free(d->names);
	free(d->cache_ok);
	free(d->started);
	free(d->logfrom);
	search_free(&d->srch);
	sharpen_free(&d->shp);
	db_close(&d->db);
	grid_free(&d->g);
	campaign_free(&d->c);
	if (lock >= 0)
		close(lock);
	free(d);
	return e->code;
}
