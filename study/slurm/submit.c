/* submit.c - `study submit CAMPAIGN --slurm`: the runs that are not done, prepared as
 * study run prepares them (driver.c: the campaign recorded, the packing choice, the
 * argument files), handed to Slurm as one job array instead of GNU parallel. Nothing
 * on the nodes writes the database: each task runs `study exec` (worker.c) for its
 * runs, whose outputs and START/DONE lines collect.c reads back here. */
#include "submit.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <math.h>

#include "layout.h"
#include "campaign/safe.h"
#include "report/cost.h"
#include "ledger/changes.h"
#include "sql.h"
#include "local/packing.h"
#include "collect.h"
#include "plan.h"

enum { MAX_SBATCH_ARGS = 64 };

/* The array's script: the same for every submission of the campaign (sbatch keeps a
 * copy of it per job, so rewriting it never changes a queued job). A task runs the
 * words of its line of the task file given as $1. */
static const char SCRIPT[] =
	"#!/bin/bash\n"
	"# array.sh - written by `study submit --slurm` for the shakebox campaign %s.\n"
	"# sbatch gets it with --array=... and a task file (slurm/tasks-N.txt): array task I\n"
	"# runs the words of line I + 1 in order, each with `study exec` (which runs bin/shake\n"
	"# from the run's argument file): c:KEY builds the shared packing KEY unless it is\n"
	"# built (a task that needs it while another builds it waits), r:ID runs the run ID.\n"
	"# Slurm's SIGTERM (scancel, the time limit, --signal=B:TERM@SECONDS) makes the\n"
	"# engine write a checkpoint and stop, and no further word starts; the next\n"
	"# `study submit` resumes the run from its checkpoint. Logs: slurm/logs/JOB_INDEX.out\n"
	"# (this script's) and logs/ID.log (the engine's).\n"
	"set -u\n"
	"study=%s\n"
	"dir=%s\n"
	"if [ $# -ne 1 ] || [ -z \"${SLURM_ARRAY_TASK_ID:-}\" ]; then\n"
	"\techo \"array.sh: for sbatch --array=... array.sh TASKFILE (study submit does it)\" >&2\n"
	"\texit 1\n"
	"fi\n"
	"line=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" \"$1\")\n"
	"[ -n \"$line\" ] || { echo \"array.sh: $1 has no line for task $SLURM_ARRAY_TASK_ID\" >&2; exit 1; }\n"
	"stop=0 child=0 rc=0\n"
	"# scancel signals every process of the job, the engine too; a signal to this shell\n"
	"# alone (scancel --batch, --signal=B:TERM@...) is passed on to the running word\n"
	"trap 'stop=1; [ \"$child\" -gt 0 ] && kill -TERM \"$child\" 2>/dev/null' TERM INT\n"
	"for w in $line; do\n"
	"\t[ \"$stop\" -eq 0 ] || break\n"
	"\tcase $w in\n"
	"\tc:*) kind=cache ;;\n"
	"\tr:*) kind=run ;;\n"
	"\t*) continue ;;\n"
	"\tesac\n"
	"\t\"$study\" exec \"$dir\" \"$kind\" \"${w#*:}\" &\n"
	"\tchild=$!\n"
	"\t# a trapped signal ends `wait` early: wait on until the word has stopped\n"
	"\twhile wait \"$child\"; st=$?; [ \"$st\" -gt 128 ] && kill -0 \"$child\" 2>/dev/null; do :; done\n"
	"\tchild=0\n"
	"\t[ \"$st\" -eq 0 ] || rc=$st\n"
	"done\n"
	"exit \"$rc\"\n";

/* The planning job's script, for a campaign whose runs come round by round (an
 * [onset] search, replicates = auto): Slurm starts it when a round's array has ended
 * (--dependency=afterany), and it does what `study submit` on the login node would. */
static const char PLAN[] =
	"#!/bin/bash\n"
	"# plan.sh - written by `study submit --slurm` for the shakebox campaign %s, whose\n"
	"# runs are chosen round by round from the results (an [onset] search or replicates\n"
	"# = auto). Slurm starts it when a round's array has ended (sbatch\n"
	"# --dependency=afterany:JOB plan.sh JOB): it reads what the round did and submits the\n"
	"# next round's array with the next planning job, as `study submit` on the login node\n"
	"# would. It stops when the search is over, or when the round finished no run (its\n"
	"# array cancelled): `study submit` then goes on. Log: slurm/logs/plan_ID.out\n"
	"# (docs/cluster.md, \"Searches on Slurm\").\n"
	"set -u\n"
	"if [ $# -ne 1 ]; then\n"
	"\techo \"plan.sh: for sbatch --dependency=afterany:JOB plan.sh JOB (study submit does it)\" >&2\n"
	"\texit 1\n"
	"fi\n"
	"# this job's own SLURM_* variables are not the next jobs' (the configuration stays)\n"
	"for v in $(compgen -v SLURM_); do [ \"$v\" = SLURM_CONF ] || unset \"$v\"; done\n"
	"exec %s --after \"$1\"\n";

/* Written to a temporary name and renamed, so that no reader sees half of it. */
static int write_file(const char *path, const char *text, int mode, sb_err *e)
{
	char tmp[PATHX + 32];
	snprintf(tmp, sizeof tmp, "%s.tmp.%ld", path, (long)getpid());
	int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, mode);
	if (fd < 0)
		return sb_errf(e, SB_EIO, "%s: cannot create: %s", tmp, strerror(errno));
	size_t n = strlen(text), off = 0;
	while (off < n) {
		ssize_t w = write(fd, text + off, n - off);
		if (w < 0 && errno == EINTR)
			continue;
		if (w <= 0)
			break;
		off += (size_t)w;
	}
	int bad = off < n || fsync(fd) != 0;
	bad |= close(fd) != 0;
	if (bad || rename(tmp, path)) {
		unlink(tmp);
		return sb_errf(e, SB_EIO, "%s: cannot write: %s", path, strerror(errno));
	}
	return 0;
}

static int write_script(drv *d, const char *self, char *path, size_t len, sb_err *e)
{
	char qs[PATHX], qd[PATHX];
	if (safe_shell_quote(self, qs, sizeof qs) || safe_shell_quote(d->dir, qd, sizeof qd))
		return sb_errf(e, SB_EUSAGE, "path too long");
	size_t n = sizeof SCRIPT + strlen(d->c.name) + strlen(qs) + strlen(qd);
	char *text = malloc(n);
	if (!text)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	snprintf(text, n, SCRIPT, d->c.name, qs, qd);
	snprintf(path, len, "%s/" SLURM_SUB "/array.sh", d->dir);
	write_file(path, text, 0755, e);
	free(text);
	return e->code;
}

/* Which pending runs start from a packing, decided as study run decides it
 * (driver.c, caches()): a packing that is built, or one that two or more of them
 * share; a packing that failed is not used (its runs settle themselves). Unlike
 * study run nothing is built here: a task builds it before its first run that needs
 * it. */
typedef struct {
	const char *key;
	long run; /* grid index */
} keyed;

static int by_key(const void *a, const void *b)
{
	const keyed *x = a, *y = b;
	int c = strcmp(x->key, y->key);
	return c ? c : (x->run > y->run) - (x->run < y->run);
}

static int choose_packings(drv *d, const long *pend, long npend, sb_err *e)
{
	if (!d->o->use_cache)
		return 0;
	keyed *k = calloc((size_t)npend + 1, sizeof *k);
	long nk = 0;
	if (!k)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	for (long i = 0; i < npend; i++) {
		sb_scene s;
		grid_scene(&d->g, &d->g.runs[pend[i]], &s);
		if (!s.particles[0] && s.settle != TRI_NO) /* else nothing to settle, or a user file */
			k[nk++] = (keyed){d->g.runs[pend[i]].cache_key, pend[i]};
	}
	qsort(k, (size_t)nk, sizeof *k, by_key);
	for (long a = 0, b; a < nk && !e->code; a = b) {
		for (b = a; b < nk && !strcmp(k[b].key, k[a].key); b++)
			;
		char st[16];
		if (driver_cache_check(d, k[a].key, st, sizeof st, e))
			break;
		/* a run whose argument file starts it from the packing needs it, alone or not */
		int named = 0;
		for (long i = a; i < b && !named; i++) {
			char ak[64];
			packing_of_args(d->dir, d->g.runs[k[i].run].id, ak, sizeof ak);
			named = !strcmp(ak, k[a].key);
		}
		/* a search's replicate runs its frequencies one round at a time: its packing
		 * is worth building from its first run on, as study run does */
		int use = !strcmp(st, "ok") || (!st[0] && (b - a >= (d->loc ? 1 : 2) || named));
		for (long i = a; i < b; i++)
			d->runs.cache_ok[k[i].run] = (char)use;
	}
	free(k);
	return e->code;
}

/* The task file: tasks-N.txt with the first N not taken (a queued task reads its own
 * file, so none is ever rewritten). */
static int write_tasks(drv *d, char **lines, long ntasks, char *path, size_t len, sb_err *e)
{
	for (long k = 1;; k++) {
		snprintf(path, len, "%s/" SLURM_SUB "/tasks-%ld.txt", d->dir, k);
		if (!exists(path))
			break;
	}
	size_t n = 1;
	for (long t = 0; t < ntasks; t++)
		n += strlen(lines[t]) + 1;
	char *text = malloc(n), *p = text;
	if (!text)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	for (long t = 0; t < ntasks; t++)
		p += sprintf(p, "%s\n", lines[t]);
	*p = 0;
	write_file(path, text, 0644, e);
	free(text);
	return e->code;
}

static int member(void *ctx, const char *id, long replicate, double frequency)
{
	(void)replicate, (void)frequency;
	return grid_find(&((drv *)ctx)->g, id) != NULL;
}

/* The job and, per run, its task, in one transaction. */
static int record_job(drv *d, const slurm_opts *so, long job, const char *spec, long ntasks, long npend,
		      char **lines, const char *script, const char *tasks, sb_err *e)
{
	char now[32], cfile[PATHLEN];
	db_now(now, sizeof now);
	if (!realpath(d->o->campaign_file, cfile))
		snprintf(cfile, sizeof cfile, "%s", d->o->campaign_file);
	if (db_begin(&d->db, e))
		return e->code;
	sql_exec(&d->db, e, NULL,
		"INSERT OR REPLACE INTO slurm_job(campaign, job_id, array, tasks, runs, runs_per_task, throttle,"
		" sbatch_args, script, task_file, campaign_file, dir, submitted) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
		"tltllllttttt" "t", d->c.name, job, spec, ntasks, npend, so->runs_per_task, so->throttle,
		so->sbatch_args ? so->sbatch_args : "", script, tasks, cfile, d->dir, now);
	for (long t = 0; t < ntasks && !e->code; t++) {
		char *copy = strdup(lines[t]);
		if (!copy) {
			sb_errf(e, SB_ENOMEM, "out of memory");
			break;
		}
		for (char *s = copy, *w; (w = strsep(&s, " ")) && !e->code;)
			if (!strncmp(w, "r:", 2))
				sql_exec(&d->db, e, NULL,
					"INSERT OR REPLACE INTO slurm_task(campaign, run, job_id, array_index, state, submitted)"
					" VALUES (?, ?, ?, ?, 'submitted', ?)",
					"ttllt", d->c.name, w + 2, job, t, now);
		free(copy);
	}
	if (e->code) {
		db_rollback(&d->db);
		return e->code;
	}
	return db_commit(&d->db, e);
}

/* The CPU seconds of grid run i alone at rates (its settling counted when it settles
 * its own bed or builds its packing: the task that does it pays for it). */
static double run_cpu(const drv *d, long i, const calib *rates)
{
	grid one = d->g;
	one.runs = &d->g.runs[i];
	one.n = 1;
	cost_sum t;
	cost_count(&d->c, &one, 0, NULL, &t);
	return cost_cpu(&t, rates);
}

static int by_id(const void *key, const void *run) { return strcmp(key, ((const grid_run *)run)->id); }

/* The array's --time (minutes) from the cost model: each task's runs summed at this
 * machine's measured rates, the longest task times SLURM_TIME_MARGIN. 0 (and the
 * reason in why) when a rate cannot be had. */
static long task_minutes(drv *d, char **lines, long ntasks, double *worst, char *why, size_t len)
{
	char shake[PATHX + 8];
	snprintf(shake, sizeof shake, "%s", d->o->self);
	char *sl = strrchr(shake, '/');
	snprintf(sl ? sl + 1 : shake, sizeof shake - (size_t)(sl ? sl + 1 - shake : 0), "shake");
	calib rates[COST_NINTEG] = {0};
	cost_sum all;
	cost_count(&d->c, &d->g, 0, NULL, &all);
	for (int i = 0; i < COST_NINTEG; i++) {
		sb_err ce = {0};
		/* the campaign's finished runs say better than the calibration (calib.h) */
		if ((all.grain_steps[i] > 0 || all.settle_grains[i] > 0) &&
		    (calib_get(d->o->runs_dir, shake, i, &rates[i], &ce) || calib_learn(&d->db, d->c.name, i, &rates[i], &ce))) {
			snprintf(why, len, "%s", ce.msg);
			return 0;
		}
	}
	*worst = 0;
	for (long t = 0; t < ntasks; t++) {
		double cpu = 0;
		char *copy = strdup(lines[t]);
		for (char *s = copy, *w; copy && (w = strsep(&s, " "));) {
			/* the grid's runs are sorted by id (grid.h) */
			const grid_run *r = strncmp(w, "r:", 2) ? NULL
							       : bsearch(w + 2, d->g.runs, (size_t)d->g.n, sizeof *d->g.runs, by_id);
			if (r)
				cpu += run_cpu(d, r - d->g.runs, rates);
		}
		free(copy);
		*worst = fmax(*worst, cpu);
	}
	const long m = (long)ceil(*worst * SLURM_TIME_MARGIN / 60.0);
	return m > SLURM_TIME_MIN ? m : SLURM_TIME_MIN;
}

/* s as one shell word: as it is where a shell reads it so, else quoted */
static const char *shell_word(const char *s, char *q, size_t len)
{
	const int plain = s[0] && s[strspn(s, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_=%/.,:+@-")] == 0;
	return plain || safe_shell_quote(s, q, len) ? s : q;
}

/* The planning job's command line: this submit's, every path absolute, so that it
 * means the same on a node in any directory. */
static int plan_command(drv *d, const slurm_opts *so, char *out, size_t len, sb_err *e)
{
	char cfile[PATHX], db[PATHX], q[PATHX + 64];
	if (!realpath(d->o->campaign_file, cfile) || !realpath(d->db.path, db))
		return sb_errf(e, SB_EIO, "%s: %s", d->o->campaign_file, strerror(errno));
	const char *word[16];
	char thr[32], per[32], sargs[PATHX];
	int n = 0;
	word[n++] = d->o->self;
	word[n++] = "submit";
	word[n++] = cfile;
	word[n++] = "--slurm";
	word[n++] = "--runs";
	word[n++] = d->root;
	word[n++] = "--db";
	word[n++] = db;
	snprintf(per, sizeof per, "--runs-per-task=%ld", so->runs_per_task);
	word[n++] = per;
	if (so->throttle > 0) {
		snprintf(thr, sizeof thr, "--throttle=%ld", so->throttle);
		word[n++] = thr;
	}
	if (!d->o->use_cache)
		word[n++] = "--no-cache";
	if (so->sbatch_args && so->sbatch_args[0]) {
		snprintf(sargs, sizeof sargs, "--sbatch-args=%s", so->sbatch_args);
		word[n++] = sargs;
	}
	size_t o = 0;
	out[0] = 0;
	for (int i = 0; i < n; i++) {
		const char *w = shell_word(word[i], q, sizeof q);
		if (o + strlen(w) + 2 > len)
			return sb_errf(e, SB_EUSAGE, "the planning job's command line is too long");
		o += (size_t)snprintf(out + o, len - o, "%s%s", i ? " " : "", w);
	}
	return 0;
}

/* The planning job of the round just submitted as array `job`: plan.sh written, sbatch
 * run with the dependency (the user's options, then a short time limit of its own);
 * dry: printed, nothing written or submitted. */
static int submit_planner(drv *d, const slurm_opts *so, char **uargs, int nuargs, long job, int dry, sb_err *e)
{
	char cmd[4 * PATHX], path[PATHX], *text = NULL;
	if (plan_command(d, so, cmd, sizeof cmd, e))
		return e->code;
	const size_t tl = sizeof PLAN + strlen(d->c.name) + strlen(cmd);
	snprintf(path, sizeof path, "%s/" SLURM_SUB "/plan.sh", d->dir);
	if (!(text = malloc(tl)))
		return sb_errf(e, SB_ENOMEM, "out of memory");
	snprintf(text, tl, PLAN, d->c.name, cmd);
	char a_dep[64], a_name[128], a_out[PATHX + 64], a_time[32], a_job[32], *args[MAX_SBATCH_ARGS + 8];
	if (job > 0)
		snprintf(a_dep, sizeof a_dep, "--dependency=afterany:%ld", job);
	else /* a dry run: the array has no id yet */
		snprintf(a_dep, sizeof a_dep, "--dependency=afterany:JOB");
	snprintf(a_name, sizeof a_name, "--job-name=%s.plan", d->c.name);
	snprintf(a_out, sizeof a_out, "--output=%s/" SLURM_SUB "/logs/plan_%%j.out", d->dir);
	snprintf(a_time, sizeof a_time, "--time=%d", SLURM_PLAN_MINUTES);
	snprintf(a_job, sizeof a_job, "%ld", job);
	int na = 0;
	args[na++] = a_dep;
	args[na++] = a_name;
	args[na++] = a_out;
	for (int i = 0; i < nuargs; i++) /* partition, account, ...: as the user's arrays */
		args[na++] = uargs[i];
	args[na++] = a_time; /* after the user's: a --time meant for the runs is not the planner's */
	args[na++] = path;
	args[na++] = job > 0 ? a_job : "JOB";
	if (dry) {
		printf("# after the array, its planning job; %s would hold:\n%s# the command:\nsbatch", path, text);
		for (int i = 0; i < na; i++) {
			char q[PATHX + 64];
			printf(" %s", shell_word(args[i], q, sizeof q));
		}
		printf("\n");
		free(text);
		return 0;
	}
	long pj = -1;
	if (!write_file(path, text, 0755, e) && !slurm_queue_submit(args, na, &pj, e))
		fprintf(stderr, "study: %s: planning job %ld submits the next round when job %ld has ended (log: %s/" SLURM_SUB
			"/logs/plan_%ld.out; scancel %ld %ld stops the search, study submit resumes it)\n",
			d->c.name, pj, job, d->dir, pj, job, pj);
	free(text);
	return e->code;
}

/* The planning job's check: did the round of array `job` finish any run? Cancelled
 * before or while its runs ran, it did not, and the search stops there. */
static long round_finished(drv *d, long job, sb_err *e)
{
	sqlite3_stmt *q;
	long n = 0;
	if (sql_exec(&d->db, e, &q,
		     "SELECT COUNT(*) FROM slurm_task s JOIN run r ON r.campaign = s.campaign AND r.id = s.run"
		     " WHERE s.campaign = ? AND s.job_id = ? AND r.state IN ('done', 'failed')",
		     "tl", d->c.name, job))
		return 0;
	if (sqlite3_step(q) == SQLITE_ROW)
		n = (long)sqlite3_column_int64(q, 0);
	sql_done(&d->db, q, e);
	return n;
}

/* Everything after the campaign is open and locked. */
static int submit(drv *d, const slurm_opts *so, char **uargs, int nuargs, sb_err *e)
{
	changes_ctx x = {&d->db, &d->c, &d->g, d->dir, d->o->keep_old, d->o->forget_old, member, d};
	/* a search (d->loc): its grid is its chains' runs so far (driver_search_pass) */
	if (d->loc ? driver_search_pass(d, 1, e) : (changes_check(&x, e) || driver_record(d, e)))
		return e->code;
	/* what the earlier arrays did, and which of their tasks still hold runs; a search
	 * whose last round brought results walks its chains again: its next round */
	char *busy = NULL;
	long nbusy = 0, npend = 0;
	for (;;) {
		slurm_queue q = {0};
		const long got = d->n_ingested;
		free(busy);
		if (!(busy = calloc((size_t)d->g.n + 1, 1)))
			return sb_errf(e, SB_ENOMEM, "out of memory");
		if (slurm_queue_list(&q, e) || slurm_collect(d, &q, e) || slurm_busy(d, &q, busy, &nbusy, e) ||
		    sweep(d, d->runs.pend, &npend, e)) {
			slurm_queue_free(&q);
			free(busy);
			return e->code;
		}
		slurm_queue_free(&q);
		if (!d->loc || d->n_ingested == got)
			break;
		if (driver_search_pass(d, 0, e)) {
			free(busy);
			return e->code;
		}
	}
	if (d->loc && so->after > 0 && !round_finished(d, so->after, e) && !e->code) {
		free(busy);
		return sb_errf(e, DRV_INTERRUPTED, "%s: the round of Slurm job %ld finished no run (cancelled, or out of "
			       "time before a run ended): the search stops here; study submit %s goes on with it",
			       d->c.name, so->after, d->o->campaign_file);
	}
	long n = 0, failed = 0;
	for (long i = 0; i < npend; i++)
		if (!busy[d->runs.pend[i]])
			d->runs.pend[n++] = d->runs.pend[i];
	for (long i = 0; i < d->g.n; i++) {
		char st[16];
		long att;
		db_run_state(&d->db, d->c.name, d->g.runs[i].id, st, sizeof st, &att, e);
		failed += !strcmp(st, "failed");
	}
	free(busy);
	fprintf(stderr, "study: %s: %ld runs, %ld done, %ld failed%s, %ld queued or running in Slurm, %ld to submit\n",
		d->c.name, d->g.n, d->g.n - npend - failed, failed, failed && !d->o->retry_failed ? " (--retry-failed submits them)" : "",
		nbusy, n);
	if (d->loc && nbusy && !e->code) {
		/* the round in flight: its planning job (or the next submit) goes on */
		fprintf(stderr, "study: %s: a round is queued or running in Slurm (%ld run%s): the next round is chosen "
			"from its results when it has ended\n", d->c.name, nbusy, nbusy > 1 ? "s" : "");
		return 0;
	}
	if (d->loc && n == 0 && !e->code) {
		long groups, open = driver_search_open_groups(d, &groups);
		driver_search_summary(d);
		fprintf(stderr, "study: %s: the search has no run to submit: %ld of %ld %s still searching%s\n",
			d->c.name, open, groups, d->c.autorep.on ? "points" : "groups",
			open ? " (their runs failed: study status lists them; --retry-failed submits them again)" : "");
		return 0;
	}
	if (n == 0 || e->code)
		return e->code;
	if (d->loc) {
		long groups, open = driver_search_open_groups(d, &groups);
		fprintf(stderr, "study: %s: %s round: %ld run%s, %ld of %ld %s%s %s\n", d->c.name,
			d->c.autorep.on ? "replicates" : "onset", n, n > 1 ? "s" : "", open, groups,
			d->c.autorep.on ? "point" : "group", groups > 1 ? "s" : "", d->c.autorep.on ? "running" : "searching");
	}

	if (choose_packings(d, d->runs.pend, n, e) || driver_prepare_jobs(d, d->runs.pend, n, d->runs.names, e))
		return e->code;
	slurm_plan_run *runs = calloc((size_t)n, sizeof *runs);
	char(*keys)[40] = calloc((size_t)n, sizeof *keys);
	char **lines = NULL;
	long ntasks = -1;
	if (!runs || !keys) {
		free(runs), free(keys);
		return sb_errf(e, SB_ENOMEM, "out of memory");
	}
	for (long i = 0; i < n && !e->code; i++) {
		const grid_run *r = &d->g.runs[d->runs.pend[i]];
		char h5[PATHX], cargs[PATHX];
		runs[i].id = r->id;
		packing_of_args(d->dir, r->id, keys[i], sizeof keys[i]);
		layout_file(d->dir, 1, keys[i], LAY_OUTPUT, h5, sizeof h5);
		layout_file(d->dir, 1, keys[i], LAY_ARGS, cargs, sizeof cargs);
		/* built: its particle file is there (a packing's output without it was
		 * forgotten by driver_cache_check, and is built again) */
		if (!keys[i][0] || (exists(h5) && packing_present(d->dir, keys[i]))) {
			keys[i][0] = 0; /* settles itself, or its packing is built */
		} else if (!exists(cargs)) {
			/* a run of this packing gives the packing's preparation (the key is its hash) */
			if (strcmp(r->cache_key, keys[i]))
				sb_errf(e, SB_EIO, "run %s: its argument file names packing %s, its key is %s", r->id, keys[i],
					r->cache_key);
			else
				driver_cache_args(d, keys[i], d->runs.pend[i], e);
		}
		runs[i].build_key = keys[i];
	}
	char spec[64], script[PATHX], tasks[PATHX];
	if (!e->code && (ntasks = slurm_plan_task_lines(runs, n, so->runs_per_task, &lines)) < 0)
		sb_errf(e, SB_ENOMEM, "out of memory");
	if (!e->code && so->dry_run) { /* what would be written, and the command: nothing submitted */
		snprintf(tasks, sizeof tasks, "%s/" SLURM_SUB "/tasks-N.txt", d->dir);
		snprintf(script, sizeof script, "%s/" SLURM_SUB "/array.sh", d->dir);
	}
	if (!e->code && (so->dry_run || (!write_tasks(d, lines, ntasks, tasks, sizeof tasks, e) &&
					 !write_script(d, d->o->self, script, sizeof script, e)))) {
		slurm_plan_array_spec(ntasks, so->throttle, spec, sizeof spec);
		char *args[MAX_SBATCH_ARGS + 8];
		char a_array[96], a_name[128], a_out[PATHX + 64], a_time[64], why[1100] = "";
		snprintf(a_array, sizeof a_array, "--array=%s", spec);
		snprintf(a_name, sizeof a_name, "--job-name=%s", d->c.name);
		snprintf(a_out, sizeof a_out, "--output=%s/" SLURM_SUB "/logs/%%A_%%a.out", d->dir);
		int na = 0;
		args[na++] = a_array;
		args[na++] = a_name;
		args[na++] = a_out;
		/* the time limit from the cost model, unless the user gives one */
		int user_time = 0;
		for (int i = 0; i < nuargs; i++)
			user_time |= !strncmp(uargs[i], "--time", 6) || !strncmp(uargs[i], "-t", 2);
		double worst = 0;
		const long minutes = user_time ? 0 : task_minutes(d, lines, ntasks, &worst, why, sizeof why);
		if (minutes > 0) {
			snprintf(a_time, sizeof a_time, "--time=%ld", minutes);
			args[na++] = a_time;
			fprintf(stderr, "study: %s: --time=%ld min: the longest task's runs take %.0f CPU s at this machine's "
					"measured rate, times %g (at least %d min; a node slower than this machine needs "
					"more: --sbatch-args '--time=...' sets it)\n",
				d->c.name, minutes, worst, SLURM_TIME_MARGIN, SLURM_TIME_MIN);
		} else if (!user_time) {
			fprintf(stderr, "study: %s: no --time from the cost model (%s): the cluster's default limit applies\n",
				d->c.name, why);
		}
		/* the user's after study submit's own: later options win, so a user's
		 * --job-name stands, and --array/--output were refused */
		for (int i = 0; i < nuargs; i++)
			args[na++] = uargs[i];
		args[na++] = script;
		args[na++] = tasks;
		long job = -1;
		if (so->dry_run) {
			char qs[PATHX], qd[PATHX];
			if (safe_shell_quote(d->o->self, qs, sizeof qs) || safe_shell_quote(d->dir, qd, sizeof qd))
				sb_errf(e, SB_EUSAGE, "path too long");
			else {
				printf("# study submit --dry-run: nothing submitted; %s would hold:\n", script);
				printf(SCRIPT, d->c.name, qs, qd);
				printf("# %s (N: the first number not taken) would hold %ld line%s, one per array task:\n", tasks,
				       ntasks, ntasks > 1 ? "s" : "");
				for (long t = 0; t < ntasks; t++)
					printf("%s\n", lines[t]);
				printf("# the command:\nsbatch");
				for (int i = 0; i < na; i++) {
					char q[PATHX + 64];
					printf(" %s", shell_word(args[i], q, sizeof q));
				}
				printf("\n");
				if (d->loc)
					submit_planner(d, so, uargs, nuargs, -1, 1, e);
			}
		} else if (slurm_queue_submit(args, na, &job, e)) {
			if (ntasks > 1000)
				fprintf(stderr, "study: %s: %ld array tasks; a cluster's MaxArraySize (often 1001) may "
					"refuse them: --runs-per-task N puts N runs in a task\n", d->c.name, ntasks);
		} else if (!record_job(d, so, job, spec, ntasks, n, lines, script, tasks, e)) {
			fprintf(stderr, "study: %s: submitted %ld run%s in %ld task%s as Slurm job %ld (--array=%s)\n",
				d->c.name, n, n > 1 ? "s" : "", ntasks, ntasks > 1 ? "s" : "", job, spec);
			fprintf(stderr, "study: %s: logs in %s/" SLURM_SUB "/logs/%ld_INDEX.out and %s/logs/RUN.log; "
				"study status %s shows what finished\n", d->c.name, d->dir, job, d->dir, d->c.name);
			if (d->loc)
				submit_planner(d, so, uargs, nuargs, job, 0, e);
		} else {
			fprintf(stderr, "study: %s: Slurm job %ld was submitted but could not be recorded; its runs "
				"are ingested from their files all the same (scancel %ld to stop it)\n",
				d->c.name, job, job);
		}
	}
	if (lines)
		slurm_plan_free_lines(lines, ntasks);
	free(runs);
	free(keys);
	return e->code;
}

int slurm_submit(const driver_opts *o, const slurm_opts *so, sb_err *e)
{
	char *uargs[MAX_SBATCH_ARGS], why[256];
	int nu = slurm_plan_split_args(so->sbatch_args, uargs, MAX_SBATCH_ARGS, why, sizeof why);
	if (nu < 0)
		return sb_errf(e, SB_EUSAGE, "--sbatch-args: %s", why);
	drv *d = calloc(1, sizeof *d);
	int lock = -1, dblock = -1;
	if (!d) {
		sb_errf(e, SB_ENOMEM, "out of memory");
		goto out;
	}
	if (slurm_drv_open(d, o, o->campaign_file, e))
		goto out;
	const char *sub[] = {"jobs", "logs", "cache", "failed", SLURM_SUB, SLURM_SUB "/logs"};
	if (driver_dirs(d, sub, sizeof sub / sizeof *sub, e))
		goto out;
	if ((lock = driver_lock(d, e)) < 0 || (dblock = driver_db_lock(d, e)) < 0)
		goto out;
	submit(d, so, uargs, nu, e);
out:
	if (lock >= 0)
		close(lock);
	if (dblock >= 0)
		close(dblock);
	if (d) {
		slurm_drv_close(d);
		free(d);
	}
	while (nu > 0)
		free(uargs[--nu]);
	return e->code;
}
