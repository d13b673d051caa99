/* driver.c - `study run`: the only writer of the study database. Completion is
 * decided from each run's own output file (written atomically by the engine), never
 * from GNU parallel's bookkeeping, so any interruption is repaired by running again. */
#include "driver.h"

#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "dirs.h"
#include "h5sum.h"
#include "layout.h"
#include "lock.h"
#include "pfile.h"
#include "rowseal.h"
#include "schema.h"
#include "validate.h"
#include "adaptive/search.h"
#include "adaptive/sharpen.h"
#include "campaign/axes.h"
#include "campaign/campaign.h"
#include "campaign/grid.h"
#include "campaign/safe.h"
#include "job/worker.h"
#include "rule/adapt.h"
#include "ledger/changes.h"
#include "ledger/db.h"
#include "drvlocal.h"
#include "progress.h"
#include "packing.h"
#include "stop.h"

void driver_db_path(const char *runs_dir, const char *db_path, char *out, size_t len)
{
	layout_db(runs_dir, db_path, out, len);
}

const char *const driver_subdirs[DRIVER_NSUB] = {"jobs", "logs", "cache", "failed"};

int driver_dirs(const drv *d, const char *const *sub, size_t n, sb_err *e)
{
	if (dirs_own(d->dir, e))
		return e->code;
	for (size_t i = 0; i < n && !e->code; i++) {
		char p[PATHX];
		snprintf(p, sizeof p, "%s/%s", d->dir, sub[i]);
		dirs_own(p, e);
	}
	return e->code;
}

/* The protocol is lib/lock.c's; these give it the campaign's paths. */
int driver_db_lock(const drv *d, sb_err *e)
{
	char dbp[PATHLEN];
	driver_db_path(d->o->runs_dir, d->o->db_path, dbp, sizeof dbp);
	return lock_database(dbp, d->c.name, e);
}

int driver_lock(const drv *d, sb_err *e)
{
	return lock_campaign(d->dir, d->c.name, e);
}

_Static_assert(DRV_BUSY == LOCK_BUSY, "a busy lock is the driver's exit code 4");

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
	int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0666);
	FILE *f = fd < 0 ? NULL : fdopen(fd, "w");
	if (!f) {
		if (fd >= 0)
			close(fd);
		return sb_errf(e, SB_EIO, "%s: cannot create: %s", tmp, strerror(errno));
	}
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

/* ---- a particle file's radius_ratio and n_intruders ---- */

/* The file a run's particles names, read once while the runs in a row share it and
 * what its reading depends on (a campaign of 10^4 runs over one file reads it once):
 * the ratio is over the scene's mean grain radius, and the reading's checks take
 * max_overlap and sides. */
typedef struct pratio {
	char path[PATHX + SB_STR_MAX];
	double mean, max_overlap;
	int sides;
	int known;   /* 1: read; -1: could not be read (the engine says why, per run) */
	sb_pintr in; /* what its intruders make of radius_ratio and n_intruders */
} pratio;

/* A run's scene as the driver records it (param rows) and hands it to the engine (its
 * argument file): the grid's, with a particle file's radius_ratio (docs/model.md,
 * "Units and the paper's values"), which the engine would set from the file itself,
 * and which its argument file then gives explicitly. A file the driver cannot read
 * leaves the campaign's value: the engine fails the run with the file's error, as it
 * fails every run of a bad input. A radius_ratio the campaign sets that disagrees with
 * the file, and a file without intruder where the campaign needs one, refuse the
 * campaign before anything runs. A relative path is the run directory's, where the
 * engine runs (worker.c). */
static int run_scene(drv *d, const grid_run *r, sb_scene *s, pratio *m, sb_err *e)
{
	grid_scene(&d->g, r, s);
	if (!s->particles[0])
		return 0;
	char path[PATHX + SB_STR_MAX];
	if (s->particles[0] == '/')
		snprintf(path, sizeof path, "%s", s->particles);
	else
		snprintf(path, sizeof path, "%s/%s", d->dir, s->particles);
	double lo, hi, mean;
	params_grain_radii(s, &lo, &hi, &mean);
	if (!m->known || strcmp(m->path, path) || m->mean != mean || m->max_overlap != s->max_overlap ||
	    m->sides != s->sides) {
		sb_err pe = {0};
		snprintf(m->path, sizeof m->path, "%s", path);
		m->mean = mean;
		m->max_overlap = s->max_overlap;
		m->sides = s->sides;
		m->known = pfile_intruders(s, path, &m->in, &pe) ? -1 : 1;
	}
	if (m->known < 0)
		return 0;
	sb_err ae = {0};
	if (pfile_intruders_apply(s, s->particles, &m->in, &ae))
		return sb_errf(e, ae.code, "%s: run %s: %s", d->c.path, r->id, ae.msg);
	const campaign *c = &d->c;
	const char *need = c->onset.line && c->onset.observable == CP_OBS_RISE ? "the search's observable rise"
			   : c->autorep.on && c->autorep.result != CP_RES_MEAN_FLUX ? "replicates = auto's result"
										  : NULL;
	if (need && !(s->radius_ratio > 0))
		return sb_errf(e, SB_EUSAGE, "%s: run %s: %s needs an intruder, but particles = %s holds none", c->path,
			       r->id, need, s->particles);
	sb_err ve = {0};
	if (params_validate(s, &ve))
		return sb_errf(e, SB_EUSAGE, "%s: run %s (particles = %s): %s", c->path, r->id, s->particles, ve.msg);
	return 0;
}

/* ---- the campaign ---- */

int driver_record(drv *d, sb_err *e)
{
	char now[32];
	db_now(now, sizeof now);
	if (db_begin(&d->db, e))
		return e->code;
	/* a value no run can have (edited, damaged) is dropped and written again: a
	 * parameter from the campaign file (db_run_add, below), a result from the run file
	 * (the sweep reads a done run's file again when its row is gone) */
	for (int k = 0; k < 10000 && !e->code; k++) {
		char run[128], why[1200];
		if (schema_bad_value(&d->db, d->c.name, 1, run, sizeof run, why, sizeof why, e) != 1)
			break;
		fprintf(stderr, "study: %s: %s: a value no run can have: written again from the %s file\n", d->c.name, why,
			strstr(why, "in table result") ? "run" : "campaign");
		sql_exec(&d->db, e, NULL,
			 strstr(why, "in table result") ? "DELETE FROM result WHERE campaign = ? AND run = ?"
							 : "DELETE FROM param WHERE campaign = ? AND run = ?",
			 "tt", d->c.name, run);
	}
	/* rows not as recorded (rowseal.h: edited with sqlite3, a byte changed in a page)
	 * of a run of the campaign file are dropped and written again the same way, the
	 * parameters and the result both; those of a run of an earlier version (no longer
	 * in the file) cannot be, and are left as they are, said */
	char after[128] = "";
	for (int k = 0; k < 10000 && !e->code; k++) {
		char run[128], why[600];
		if (rowseal_bad(&d->db, d->c.name, k ? after : NULL, 0, run, sizeof run, why, sizeof why, e) != 1)
			break;
		/* an edit, or a page damaged where SQLite's reads do not fail: a quick check
		 * tells, and a corrupt database is not written into */
		char bad[512];
		if (!k && sql_check(&d->db, bad, sizeof bad)) {
			sb_errf(e, SB_EIO, "%s: the database is corrupt (quick_check: %s): %s", d->db.path, bad, SQL_REBUILD);
			break;
		}
		snprintf(after, sizeof after, "%s", run);
		if (!grid_find(&d->g, run)) {
			fprintf(stderr, "study: %s: %s: a run of an earlier version of the campaign, whose rows cannot be "
				"written again: left as they are (the analysis tools refuse the campaign until its rows are "
				"repaired or it is forgotten)\n", d->c.name, why);
			continue;
		}
		fprintf(stderr, "study: %s: %s: written again from the campaign and run files\n", d->c.name, why);
		if (!sql_exec(&d->db, e, NULL, "DELETE FROM result WHERE campaign = ? AND run = ?", "tt", d->c.name, run))
			sql_exec(&d->db, e, NULL, "DELETE FROM param WHERE campaign = ? AND run = ?", "tt", d->c.name, run);
	}
	if (!e->code)
		db_campaign_put(&d->db, &d->c, now, e);
	pratio pr = {.known = 0};
	for (long i = 0; i < d->g.n && !e->code; i++) {
		sb_scene s;
		if (!run_scene(d, &d->g.runs[i], &s, &pr, e))
			db_run_add(&d->db, &d->c, &d->g.runs[i], &s, now, e);
	}
	/* nothing runs while this driver holds the campaign lock: a 'running' row is
	 * left from a driver that was killed */
	if (!e->code)
		sql_exec(&d->db, e, NULL, "UPDATE run SET state = 'pending' WHERE campaign = ? AND state = 'running'",
			"t", d->c.name);
	if (e->code) {
		db_rollback(&d->db);
		return e->code;
	}
	return db_commit(&d->db, e);
}

static int by_str(const void *a, const void *b)
{
	return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The argument file of a packing's job: run `first`'s preparation, settled and written
 * out (duration 0), never resumed. */
int driver_cache_args(drv *d, const char *key, long first, sb_err *e)
{
	sb_scene s;
	grid_scene(&d->g, &d->g.runs[first], &s);
	char args[PATHX], out[64];
	layout_file(d->dir, 1, key, LAY_ARGS, args, sizeof args);
	layout_file("", 1, key, LAY_OUTPUT, out, sizeof out);
	driver_owned(&s, out);
	s.duration = 0;
	s.checkpoint_every = 0;
	s.restart = TRI_NO;
	layout_cache_particles("", key, s.write_particles, sizeof s.write_particles);
	return write_args(args, &s, e);
}

/* A packing's state ("ok", "failed", "" not built) as the files say: the database's
 * row is not the file. A packing recorded as built whose particle file is gone (its
 * directory deleted) is forgotten, so that it is built again; a failed one is
 * forgotten with --retry-failed; one built while no driver listened is ingested. */
int driver_cache_check(drv *d, const char *key, char *st, size_t len, sb_err *e)
{
	char h5[PATHX];
	ingest_cache_state(d, key, st, len);
	layout_file(d->dir, 1, key, LAY_OUTPUT, h5, sizeof h5);
	int gone = !strcmp(st, "ok") && !packing_present(d->dir, key);
	if (gone || (!strcmp(st, "failed") && d->o->retry_failed)) {
		if (gone)
			fprintf(stderr, "study: %s: packing %s is recorded as built but cache/%s.txt is missing: "
				"building it again\n", d->c.name, key, key);
		unlink(h5); /* without its particle file it is no packing */
		if (db_begin(&d->db, e))
			return e->code;
		if (sql_exec(&d->db, e, NULL, "DELETE FROM cache WHERE campaign = ? AND key = ?", "tt", d->c.name, key)) {
			db_rollback(&d->db);
			return e->code;
		}
		if (db_commit(&d->db, e))
			return e->code;
		st[0] = 0;
	}
	if (!st[0] && exists(h5)) {
		if (!db_begin(&d->db, e) && !ingest_cache(d, key, e))
			db_commit(&d->db, e);
		else
			db_rollback(&d->db);
		ingest_cache_state(d, key, st, len);
	}
	return e->code;
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
	char *named = calloc((size_t)npend, 1);
	if (!count || !named) {
		free(keys), free(first), free(build), free(count), free(named);
		return sb_errf(e, SB_ENOMEM, "out of memory");
	}
	for (long i = 0; i < npend; i++) {
		const grid_run *r = &d->g.runs[pend[i]];
		d->runs.cache_ok[pend[i]] = 0; /* decided again: a packing may have gone since */
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
		/* a run whose argument file already starts it from the packing needs it
		 * (built again if it was deleted), alone or not */
		char ak[64];
		packing_of_args(d->dir, r->id, ak, sizeof ak);
		named[k] |= !strcmp(ak, r->cache_key);
	}
	for (long k = 0; k < nk && !e->code; k++) {
		char st[16];
		if (driver_cache_check(d, keys[k], st, sizeof st, e))
			break;
		/* a replicate of an [onset] search runs several frequencies, one at a time:
		 * its packing is worth settling once from its first run on */
		if (st[0] || (count[k] < (d->loc->adaptive ? 1 : 2) && !named[k]))
			continue;
		if (!driver_cache_args(d, keys[k], first[k], e))
			build[nb++] = keys[k];
	}
	if (nb && !e->code) {
		fprintf(stderr, "study: %s: settling %ld shared packing%s\n", d->c.name, nb, nb > 1 ? "s" : "");
		run_parallel(d, "cache", build, nb, NULL, 0, e);
	}
	for (long k = 0; k < nk && !e->code; k++) {
		char st[16];
		ingest_cache_state(d, keys[k], st, sizeof st);
		if (strcmp(st, "ok"))
			continue;
		(*basefiles)[(*nbase)++] = strdup(keys[k]);
		for (long i = 0; i < npend; i++)
			if (!strcmp(d->g.runs[pend[i]].cache_key, keys[k]))
				d->runs.cache_ok[pend[i]] = 1;
	}
	free(keys);
	free(first);
	free(build);
	free(count);
	free(named);
	return e->code;
}

int driver_prepare_jobs(drv *d, const long *pend, long npend, char **names, sb_err *e)
{
	pratio pr = {.known = 0};
	for (long i = 0; i < npend && !e->code; i++) {
		const grid_run *r = &d->g.runs[pend[i]];
		char args[PATHX], out[64];
		layout_file(d->dir, 0, r->id, LAY_ARGS, args, sizeof args);
		layout_file("", 0, r->id, LAY_OUTPUT, out, sizeof out);
		names[i] = (char *)r->id;
		if (exists(args)) {
			/* a resumed run keeps its arguments (and its cache choice), unless the
			 * packing they start it from is gone and not built again (--no-cache, or
			 * its build failed): then it settles itself, and a checkpoint of the old
			 * arguments could not be resumed (restart = auto checks them) */
			char ak[64];
			packing_of_args(d->dir, r->id, ak, sizeof ak);
			if (!ak[0] || packing_present(d->dir, ak) ||
			    (d->runs.cache_ok[pend[i]] && !strcmp(ak, r->cache_key)))
				continue; /* (study submit: a task builds it before the run) */
			fprintf(stderr, "study: %s: run %s starts from packing cache/%s.txt, which is missing: its "
				"argument file is written again\n", d->c.name, r->id, ak);
			char p[PATHX + 16];
			layout_file(d->dir, 0, r->id, LAY_CKPT, p, sizeof p);
			unlink(p);
			layout_file(d->dir, 0, r->id, LAY_JOURNAL, p, sizeof p);
			unlink(p);
			if (unlink(args)) {
				sb_errf(e, SB_EIO, "%s: cannot remove: %s", args, strerror(errno));
				break;
			}
		}
		sb_scene s;
		if (run_scene(d, r, &s, &pr, e))
			break;
		driver_owned(&s, out);
		int fc = d->runs.cache_ok[pend[i]];
		if (fc) {
			/* bit-identical to settling here (engine contract); only the particles,
			 * settle and settle_* attributes of the output differ */
			layout_cache_particles("", r->cache_key, s.particles, sizeof s.particles);
			s.settle = TRI_NO;
		}
		if (db_begin(&d->db, e))
			break;
		if (sql_exec(&d->db, e, NULL, "UPDATE run SET from_cache = ? WHERE campaign = ? AND id = ?", "ltt",
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

/* The failed runs of an [onset] search whose outcome the search used (adapt_failure_class:
 * grains thrown over the walls while shaking count as "on", by design): a campaign whose
 * groups all reached their onset ends well with them. *what: "3 left_box" and so on. */
static long search_used_failures(drv *d, char *what, size_t len)
{
	long used = 0;
	size_t o = 0;
	what[0] = 0;
	sqlite3_stmt *q;
	sb_err e = {0};
	if (sql_exec(&d->db, &e, &q,
		     "SELECT a.status, COUNT(*) FROM run r"
		     " LEFT JOIN result s ON s.campaign = r.campaign AND s.run = r.id"
		     " LEFT JOIN attempt a ON a.campaign = r.campaign AND a.run = r.id"
		     "  AND a.n = (SELECT MAX(n) FROM attempt b WHERE b.campaign = r.campaign AND b.run = r.id)"
		     " WHERE r.campaign = ? AND r.current AND r.state = 'failed' AND s.steps > 0 GROUP BY a.status",
		     "t", d->c.name))
		return 0;
	while (sqlite3_step(q) == SQLITE_ROW) {
		const char *st = (const char *)sqlite3_column_text(q, 0);
		const long n = (long)sqlite3_column_int64(q, 1);
		if (!st || adapt_failure_class(st) == AD_FAILED)
			continue;
		used += n;
		if (o < len)
			o += (size_t)snprintf(what + o, len - o, "%s%ld %s", o ? ", " : "", n, st);
	}
	sql_done(&d->db, q, &e);
	return used;
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

/* After a pass over names[0..n): the runs to run again. A run left pending by a pass
 * that ran to its end without its outcome (no DONE line: parallel gave up on its
 * hosts, or its output never came back) is recorded as lost. A run is run again while
 * its killed, I/O-failed and lost attempts in this `study run` are at most --retries;
 * after an I/O fault only the runs that hit it, as a probe: when they succeed the
 * fault was transient and the launching goes on. Returns their number, ids in again;
 * *io_probe says whether they are a probe. */
static long retries_due(drv *d, char **names, long n, char **last, long nlast, int halted, char **again, int *io_probe,
			sb_err *e)
{
	long m = 0;
	*io_probe = d->io_fault;
	/* the last pass's runs: heard of, or lost */
	for (long k = 0; k < nlast && !halted; k++) {
		const grid_run *r = grid_find(&d->g, last[k]);
		if (r && !d->runs.outcome[r - d->g.runs])
			d->runs.outcome[r - d->g.runs] = '?';
	}
	for (long k = 0; k < n && !e->code; k++) {
		const grid_run *r = grid_find(&d->g, names[k]);
		if (!r)
			continue;
		long i = r - d->g.runs, att;
		char st[16];
		if (db_run_state(&d->db, d->c.name, r->id, st, sizeof st, &att, e))
			break;
		if (strcmp(st, "pending") && strcmp(st, "running"))
			continue;
		char path[PATHX];
		layout_file(d->dir, 0, r->id, LAY_OUTPUT, path, sizeof path);
		if (exists(path))
			continue; /* came back after its DONE line: the sweep ingests it */
		if (d->runs.outcome[i] == '?') {
			char now[32];
			db_now(now, sizeof now);
			d->runs.outcome[i] = 'l';
			d->runs.transient[i]++;
			if (db_begin(&d->db, e))
				break;
			if (db_attempt(&d->db, d->c.name, r->id, -1, "lost", "no outcome came back (host lost, output not returned)",
				       "", NULL, now, "pending", e)) {
				db_rollback(&d->db);
				break;
			}
			db_commit(&d->db, e);
		}
		if (d->runs.transient[i] > d->o->retries || d->runs.outcome[i] == 'm')
			continue; /* exhausted: stays pending for the next `study run`; or its input
				   * went: launch() prepares it again */
		if (*io_probe && d->runs.outcome[i] != 'i')
			continue;
		again[m++] = (char *)r->id;
	}
	return e->code ? 0 : m;
}

/* Runs the given runs: their packings, their argument files, GNU parallel. */
static int launch_once(drv *d, long *pend, long npend, sb_err *e)
{
	char **basefiles = NULL;
	long nbase = 0;
	if (!caches(d, pend, npend, &basefiles, &nbase, e) && !stop_requested() &&
	    !driver_prepare_jobs(d, pend, npend, d->runs.names, e)) {
		if (nbase)
			qsort(basefiles, (size_t)nbase, sizeof *basefiles, by_str);
		char **again = calloc((size_t)npend + 1, sizeof *again);
		char **list = d->runs.names;
		long n = npend;
		while (again && !e->code) {
			for (long k = 0; k < n; k++) {
				const grid_run *r = grid_find(&d->g, list[k]);
				if (r)
					d->runs.outcome[r - d->g.runs] = 0;
			}
			run_parallel(d, "run", list, n, basefiles, nbase, e);
			int halted = d->io_fault || stop_requested(), probe;
			if (e->code || stop_requested())
				break;
			/* every run of this launch, not only the last pass's: a probe's success
			 * puts the runs its fault halted back in the queue */
			n = retries_due(d, d->runs.names, npend, list, n, halted, again, &probe, e);
			if (n == 0 || e->code)
				break;
			fprintf(stderr, "study: %s: running again %ld run%s %s (--retries %d)\n", d->c.name, n, n > 1 ? "s" : "",
				probe ? "that hit an I/O fault, to see whether it passed"
				      : "killed, failed on I/O, lost, or held back by an I/O fault",
				d->o->retries);
			if (probe) {
				/* a moment for a transient fault to pass */
				struct timespec ts = {1, 0};
				while (nanosleep(&ts, &ts) && !stop_requested())
					;
				d->io_fault = 0;
			}
			list = again;
		}
		free(again);
	}
	for (long i = 0; i < nbase; i++)
		free(basefiles[i]);
	free(basefiles);
	return e->code;
}

/* Runs the pending runs. A run whose input went while the campaign ran (its argument
 * file or its packing deleted: ingest.c, outcome 'm') is prepared again and run again,
 * a few times at most (someone still deleting gets the runs left pending, exit 7). */
static int launch(drv *d, long npend, sb_err *e)
{
	long *again = malloc(((size_t)npend + 1) * sizeof *again);
	if (!again)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	long *list = d->runs.pend, n = npend;
	for (int round = 0; round < 3; round++) {
		if (launch_once(d, list, n, e) || stop_requested() || d->io_fault)
			break;
		long m = 0;
		for (long k = 0; k < n; k++)
			if (d->runs.outcome[list[k]] == 'm')
				again[m++] = list[k];
		if (m == 0 || round == 2)
			break;
		fprintf(stderr, "study: %s: %ld run%s lost %s input or output while the campaign ran (argument file, "
			"packing or output file deleted): prepared and run again\n", d->c.name, m, m > 1 ? "s" : "",
			m > 1 ? "their" : "its");
		if (driver_dirs(d, driver_subdirs, DRIVER_NSUB, e))
			break;
		memcpy(list, again, (size_t)m * sizeof *again); /* list is d->runs.pend: free to reuse */
		n = m;
	}
	free(again);
	return e->code;
}

/* Does the campaign file still ask for a recorded run? An [onset] campaign's runs are
 * its chains' so far, and more may come: a run belongs to it when some chain can ask
 * for it; with replicates = auto, when it is a replicate of a grid point. */
static int asks_for(void *ctx, const char *id, long replicate, double frequency)
{
	drv *d = ctx;
	if (d->loc->autorep)
		return sharpen_member(&d->loc->shp, d->g.points, replicate, id);
	return d->loc->adaptive ? search_member(&d->c, d->g.points, replicate, frequency, id) : grid_find(&d->g, id) != NULL;
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
	if (driver_search_derive(d, e))
		return e->code;
	if (first && check_changes(d, e))
		return e->code;
	if (driver_record(d, e) || (d->loc->autorep ? sharpen_store(&d->loc->shp, &d->db, e) : search_store(&d->loc->srch, &d->db, e)))
		return e->code;
	return drv_runs_alloc(d, e);
}

/* ---- the rounds of a search, for study submit too (drv.h) ---- */

int driver_search_open(drv *d, sb_err *e)
{
	if (!d->c.onset.line && !d->c.autorep.on)
		return 0;
	if (!(d->loc = calloc(1, sizeof *d->loc)))
		return sb_errf(e, SB_ENOMEM, "out of memory");
	d->loc->adaptive = d->c.onset.line != 0;
	d->loc->autorep = d->c.autorep.on;
	d->loc->jobs = 1;
	if (d->loc->adaptive)
		search_init(&d->loc->srch, &d->c, d->dir);
	if (d->loc->autorep)
		sharpen_init(&d->loc->shp, &d->c, d->dir);
	return 0;
}

void driver_search_close(drv *d)
{
	if (!d->loc)
		return;
	search_free(&d->loc->srch);
	sharpen_free(&d->loc->shp);
	free(d->loc);
	d->loc = NULL;
}

int driver_search_derive(drv *d, sb_err *e)
{
	grid_free(&d->g);
	if (grid_expand(&d->g, &d->c, e))
		return e->code;
	return d->loc->autorep ? sharpen_derive(&d->loc->shp, &d->g, &d->db, e) : search_derive(&d->loc->srch, &d->g, &d->db, e);
}

int driver_search_pass(drv *d, int first, sb_err *e)
{
	return onset_pass(d, first, e);
}

long driver_search_open_groups(const drv *d, long *groups)
{
	long searching = 0;
	*groups = d->loc->autorep ? d->loc->shp.npoints : d->loc->srch.ngroups;
	for (long i = 0; i < *groups; i++)
		searching += d->loc->autorep ? d->loc->shp.pts[i].state == SH_RUNNING
					     : d->loc->srch.groups[i].state == AD_G_SEARCHING;
	return searching;
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
		if (sweep(d, d->runs.pend, &npend, e))
			return e->code;
		if (d->n_ingested > got)
			continue;
		if (!npend || stop_requested() || d->io_fault)
			return 0;
		long groups, searching = driver_search_open_groups(d, &groups);
		d->loc->rounds++;
		fprintf(stderr, "study: %s: %s round %ld: %ld run%s, %ld of %ld %s%s %s, %d job%s%s%s\n", d->c.name,
			d->loc->autorep ? "replicates" : "onset", d->loc->rounds, npend, npend > 1 ? "s" : "", searching, groups,
			d->loc->autorep ? "point" : "group", groups > 1 ? "s" : "", d->loc->autorep ? "running" : "searching",
			d->loc->jobs, d->loc->jobs > 1 ? "s" : "", d->o->sshloginfile ? " per host of " : "",
			d->o->sshloginfile ? d->o->sshloginfile : "");
		if (launch(d, npend, e) || stop_requested() || d->io_fault)
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
	for (long i = 0; i < d->loc->srch.ngroups; i++) {
		const srch_group *gr = &d->loc->srch.groups[i];
		char est[32], lo[32], hi[32];
		onset_number(gr->iv.est, est, sizeof est);
		onset_number(gr->iv.lo, lo, sizeof lo);
		onset_number(gr->iv.hi, hi, sizeof hi);
		long found = 0;
		for (long k = 0; k < gr->nrep; k++)
			found += gr->reps[k].state == AD_FOUND;
		char onset[64];
		if (isnan(gr->iv.est))
			snprintf(onset, sizeof onset, "%s (no replicate answered)", est);
		else
			drive_axis_text(o->axis, est, onset, sizeof onset);
		fprintf(stderr, "study: %s: %s: onset %s, %g%% interval [%s, %s], %ld replicate%s (%ld found), %ld "
			"runs: %s%s%s%s\n", d->c.name, gr->label, onset,
			100 * o->level, lo, hi, gr->nrep, gr->nrep > 1 ? "s" : "", found, gr->runs,
			adapt_gstate_name(gr->state), gr->state == AD_G_BLOCKED ? " (" : "",
			gr->state == AD_G_BLOCKED ? gr->reason : "", gr->state == AD_G_BLOCKED ? ")" : "");
	}
}

/* One line per point of a grid with replicates = auto: the interval it reached. */
static void autorep_summary(drv *d)
{
	const cp_auto *a = &d->c.autorep;
	for (long i = 0; i < d->loc->shp.npoints; i++) {
		const shp_point *pt = &d->loc->shp.pts[i];
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

void driver_search_summary(drv *d)
{
	if (d->loc->autorep)
		autorep_summary(d);
	else
		onset_summary(d);
}

/* A database given with --db in the runs directory: the campaign's directory must not
 * take its name or that of a file beside it (layout_reserved; campaign_load has refused
 * those of study.db). */
static int name_free(const drv *d, sb_err *e)
{
	char db[PATHLEN], dir[PATHLEN], real[PATH_MAX];
	if (!d->o->db_path)
		return 0;
	snprintf(db, sizeof db, "%s", d->o->db_path);
	snprintf(dir, sizeof dir, "%s", d->o->db_path);
	const char *file = basename(db);
	if (!realpath(dirname(dir), real) || strcmp(real, d->root) || !layout_reserved(d->c.name, file))
		return 0;
	return sb_errf(e, SB_EUSAGE, "%s:%d: name: '%s' is a name of the runs directory's own files (the database %s "
		       "and the files beside it: -journal, -wal, -shm, .NAME.lock); choose a name that does not begin "
		       "with '%s'", d->c.path, d->c.name_line, d->c.name, d->o->db_path, file);
}

int driver_run(const driver_opts *o, sb_err *e)
{
	drv *d = calloc(1, sizeof *d);
	struct drv_local *loc = calloc(1, sizeof *loc);
	if (!d || !loc) {
		free(d);
		free(loc);
		return sb_errf(e, SB_ENOMEM, "out of memory");
	}
	d->o = o;
	d->loc = loc;
	int lock = -1, dblock = -1;
	if (campaign_load(&d->c, o->campaign_file, e) || grid_expand(&d->g, &d->c, e))
		goto out;
	d->loc->adaptive = d->c.onset.line != 0;
	d->loc->autorep = d->c.autorep.on;
	d->loc->jobs = o->jobs > 0 ? o->jobs : (int)sysconf(_SC_NPROCESSORS_ONLN);
	if (d->loc->jobs < 1)
		d->loc->jobs = 1;
	const char *rd = o->runs_dir ? o->runs_dir : "runs";
	if (dirs_make(rd, e))
		goto out;
	if (!realpath(rd, d->root)) {
		sb_errf(e, SB_EIO, "%s: %s", rd, strerror(errno));
		goto out;
	}
	if (strlen(d->root) > 3000) {
		sb_errf(e, SB_EUSAGE, "%s: path too long", d->root);
		goto out;
	}
	if (name_free(d, e))
		goto out;
	/* the campaign name is checked ([A-Za-z0-9_.-], no leading dot): this stays inside root */
	layout_campaign(d->root, d->c.name, d->dir, sizeof d->dir);
	if (driver_dirs(d, driver_subdirs, DRIVER_NSUB, e))
		goto out;
	if ((lock = driver_lock(d, e)) < 0 || (dblock = driver_db_lock(d, e)) < 0)
		goto out;
	if (d->loc->adaptive)
		search_init(&d->loc->srch, &d->c, d->dir);
	if (d->loc->autorep)
		sharpen_init(&d->loc->shp, &d->c, d->dir);
	char dbp[PATHLEN];
	driver_db_path(o->runs_dir, o->db_path, dbp, sizeof dbp);
	int rounds = d->loc->adaptive || d->loc->autorep; /* the grid grows pass by pass */
	if (db_open(&d->db, dbp, 1, e))
		goto out;
	if (d->db.note[0])
		fprintf(stderr, "study: %s\n", d->db.note);
	if (ingest_orphans(d, e) ||
	    (!rounds && (check_changes(d, e) || driver_record(d, e))))
		goto out;

	reserve_make(d); /* room for the last records on a full disk (reserve.c) */
	stop_signals();
	if (o->progress < 0 ? isatty(2) : o->progress) {
		d->prog = progress_open(d->c.name, d->dir, isatty(2));
	}

	if (d->loc->adaptive) /* what the first points are, and where the model fails there */
		for (long i = 0; i < d->g.points; i++) {
			char pv[2048];
			search_preview(&d->c, i, pv, sizeof pv);
			for (char *sv, *ln = strtok_r(pv, "\n", &sv); ln; ln = strtok_r(NULL, "\n", &sv))
				fprintf(stderr, "study: %s: %s\n", d->c.name, ln);
		}
	long npend;
	if (rounds) {
		if (run_onset(d, e) && e->code == SB_EUSAGE)
			goto out; /* a changed campaign: nothing ran */
	} else {
		if (drv_runs_alloc(d, e) || sweep(d, d->runs.pend, &npend, e))
			goto out;
		fprintf(stderr, "study: %s: %ld runs, %ld to run, %d job%s%s%s\n", d->c.name, d->g.n, npend, d->loc->jobs,
			d->loc->jobs > 1 ? "s" : "", o->sshloginfile ? " per host of " : "",
			o->sshloginfile ? o->sshloginfile : "");
		if (npend && !stop_requested() && !d->io_fault)
			launch(d, npend, e);
	}
	sb_err se = {0};
	ingest_owed_settle(d, &se); /* before the counts: no run this driver started is left 'running' */
	sweep(d, NULL, &npend, &se); /* outputs that came back after their DONE line */
	if (rounds && !e->code && !se.code) {
		/* the state after the last round, for study status */
		onset_pass(d, 0, &se);
		driver_search_summary(d);
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
	long exhausted = 0;
	for (long i = 0; d->runs.transient && i < d->g.n; i++)
		exhausted += d->runs.transient[i] > o->retries;
	if (!e->code && !d->io_fault && !stop_requested() && exhausted)
		sb_errf(e, DRV_INTERRUPTED,
			"%s: %ld runs not complete, %ld of them killed or lost %d times in this run (--retries %d; study "
			"status %s lists the attempts); run the same command again to resume",
			d->c.name, pending, exhausted, o->retries + 1, o->retries, d->c.name);
	else if (!e->code && (stop_requested() || pending))
		sb_errf(e, DRV_INTERRUPTED, "%s: %ld runs not complete; run the same command again to resume",
			d->c.name, pending);
	long blocked = 0;
	for (long i = 0; d->loc->adaptive && i < d->loc->srch.ngroups; i++)
		blocked += d->loc->srch.groups[i].state == AD_G_BLOCKED;
	/* a search's runs whose failure it used as an outcome are what they were, not
	 * failures of the campaign: said, and the exit status 0 when nothing else failed */
	char used_what[256];
	const long used = d->loc->adaptive ? search_used_failures(d, used_what, sizeof used_what) : 0;
	if (used)
		fprintf(stderr, "study: %s: %ld runs ended early, their outcome used by the search as designed (%s: grains "
				"thrown over the walls count as convecting; docs/campaigns.md, \"Adaptive onset search\")\n",
			d->c.name, used, used_what);
	if (!e->code && !stop_requested() && !pending && blocked)
		sb_errf(e, DRV_FAILED, "%s: %ld of %ld search groups blocked, %ld runs failed (study status %s lists the "
			"reasons)", d->c.name, blocked, d->loc->srch.ngroups, failed - used, d->c.name);
	else if (!e->code && failed > used)
		sb_errf(e, DRV_FAILED, "%s: %ld runs failed (study status %s lists the reasons)", d->c.name, failed - used,
			d->c.name);
out:
	reserve_release(d);
	drv_runs_free(d);
	progress_close(d->prog);
	search_free(&loc->srch);
	sharpen_free(&loc->shp);
	db_close(&d->db);
	grid_free(&d->g);
	campaign_free(&d->c);
	if (lock >= 0)
		close(lock);
	if (dblock >= 0)
		close(dblock);
	free(loc);
	free(d);
	return e->code;
}
