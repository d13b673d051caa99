/* drv.h - a campaign's runs as a driver holds them, and what the driver's modules ask
 * of each other: for local/ (`study run`) and slurm/ (`study submit --slurm`, and the
 * collection of the arrays' results), which prepare and ingest runs as `study run`
 * does. What only `study run` keeps is drvlocal.h's (local/ only); the progress line
 * is progress.h's. */
#ifndef ST_DRV_H
#define ST_DRV_H

#include <unistd.h>

#include "campaign/campaign.h"
#include "campaign/grid.h"
#include "ledger/db.h"
#include "driver.h"

#define PATHLEN 4096
#define PATHX (PATHLEN + 256)

/* Per grid run, for the grid as it is now (an [onset] campaign's grid grows pass by
 * pass): allocated together and freed together, by drv_runs_alloc and drv_runs_free
 * only (drv.c). */
typedef struct drv_runs {
	char *cache_ok;       /* start from the packing cache */
	char *started;        /* 1 START seen, 2 DONE seen (this driver) */
	long *logfrom;        /* size of its log when START was seen */
	long *pend;           /* the indices of the runs to run */
	char **names;         /* their ids, for GNU parallel */
	long *transient;      /* attempts killed, failed on I/O or lost in this `study run`
			       * (retried while at most o->retries) */
	char *outcome;        /* its last launch: 0 nothing heard, 'k' killed, 'i' I/O,
			       * 'l' lost, 'h' stopped by the driver, 'r' recorded, 'm' its
			       * input (argument file, packing) deleted under it */
} drv_runs;

struct drv_local;    /* `study run` only (drvlocal.h) */
struct drv_progress; /* the progress line (progress.h) */

typedef struct drv {
	/* the campaign as both drivers hold it: `study run` and the Slurm commands */
	const driver_opts *o;
	campaign c;
	grid g;
	st_db db;
	char root[PATHLEN];   /* absolute runs root */
	char dir[PATHLEN + 128];    /* root/name */
	drv_runs runs;
	/* ingest.c's account of what it recorded */
	long n_ingested, n_failed_now;
	int io_fault;         /* a run failed on I/O: launch nothing more */
	char io_msg[1200];
	struct owed *owed;    /* attempts the database would not take, to be written again
			       * before the driver ends (ingest.c) */
	/* `study run`'s own: the passes, the jobs, the disk reserve (drvlocal.h); under
	 * the Slurm commands only the passes of a campaign with rounds
	 * (driver_search_open), else NULL */
	struct drv_local *loc;
	/* reporting: the progress line of `study run`; NULL: none */
	struct drv_progress *prog;
} drv;

/* drv.c: d->runs for d->g as it is now, zeroed (those of an earlier grid freed);
 * and freed. */
int drv_runs_alloc(drv *d, sb_err *e);
void drv_runs_free(drv *d);

static inline int exists(const char *p)
{
	return access(p, F_OK) == 0;
}

/* driver.c, also for `study submit`: the campaign's lock and the lock of the
 * campaign in its database (lib/lock.h, with this campaign's paths), a descriptor;
 * -1 with e set: DRV_BUSY when another driver holds it, an I/O error when the lock
 * cannot be made or taken (a read-only or full runs directory), naming the file and
 * why. */
int driver_lock(const drv *d, sb_err *e);
int driver_db_lock(const drv *d, sb_err *e);
/* driver.c: the directories the driver writes inside the campaign directory, made if
 * missing, a link planted there refused (lib/dirs.h): d->dir and its subdirectories
 * sub[0..n). */
int driver_dirs(const drv *d, const char *const *sub, size_t n, sb_err *e);
enum { DRIVER_NSUB = 4 };
extern const char *const driver_subdirs[DRIVER_NSUB]; /* jobs, logs, cache, failed */
/* driver.c: a packing's state ("ok", "failed", "" to build) after forgetting a
 * recorded one whose file is gone (and a failed one with --retry-failed) and
 * ingesting one built unheard (the files as packing.h reads them). */
int driver_cache_check(drv *d, const char *key, char *st, size_t len, sb_err *e);

/* driver.c, also for `study submit` (slurm/submit.c), which prepares runs as `study run`
 * does and hands them to Slurm: the campaign and its runs recorded; the argument
 * file of a packing's job (key, settled from grid run `first`); the runs' argument
 * files (from the packing where d->cache_ok says), their ids into names */
int driver_record(drv *d, sb_err *e);
int driver_cache_args(drv *d, const char *key, long first, sb_err *e);
int driver_prepare_jobs(drv *d, const long *pend, long npend, char **names, sb_err *e);

/* driver.c, the rounds of an [onset] search or of replicates = auto, for `study run`
 * and `study submit` alike (docs/driver.md): driver_search_open gives d->loc the
 * search's state when the campaign has rounds (else does nothing: d->loc stays NULL),
 * driver_search_close frees it. driver_search_derive: the grid as the chains stand,
 * walked again from the database and the run files, nothing written. driver_search_pass:
 * that, and (first: a campaign file that changed is refused as by study run) the runs
 * recorded, the search's state stored, d->runs for the new grid.
 * driver_search_open_groups: the groups (points) still searching, *groups of them in
 * all; driver_search_summary: one line per group on stderr. */
int driver_search_open(drv *d, sb_err *e);
void driver_search_close(drv *d);
int driver_search_derive(drv *d, sb_err *e);
int driver_search_pass(drv *d, int first, sb_err *e);
long driver_search_open_groups(const drv *d, long *groups);
void driver_search_summary(drv *d);

/* ingest.c: a run's or a packing's outcome into the database (and into
 * d->runs.outcome, d->runs.transient for the retries); the workers' START and DONE
 * lines; the runs started whose DONE never came (after a pass) */
int ingest_run(drv *d, const char *id, const db_usage *u, sb_err *e); /* u: NULL when no worker said */
int ingest_cache(drv *d, const char *key, sb_err *e);
void ingest_cache_state(drv *d, const char *key, char *st, size_t len);
int ingest_on_start(drv *d, char *line, sb_err *e);
int ingest_on_done(drv *d, int is_cache, char *line, sb_err *e);
void ingest_unreported(drv *d, sb_err *e);
/* The attempts the database would not take when they came (a full disk), written now;
 * each one that still cannot be is said on stderr. Frees them. */
int ingest_owed_settle(drv *d, sb_err *e);
/* the runs a killed driver left 'running': each an interrupted attempt, pending */
int ingest_orphans(drv *d, sb_err *e);

/* sweep.c: outputs finished while no driver listened, damaged ones, litter, failed
 * runs back in the queue (--retry-failed); the pending runs' indices in *pend */
int sweep(drv *d, long *pend, long *npend, sb_err *e);

#endif
