/* drv.h - private to the campaign driver's modules (driver.c, ingest.c, parallel.c,
 * sweep.c): the state of one `study run` and what the modules ask of each other. */
#ifndef ST_DRV_H
#define ST_DRV_H

#include <unistd.h>

#include "adaptive/search.h"
#include "adaptive/sharpen.h"
#include "campaign/campaign.h"
#include "campaign/grid.h"
#include "ledger/db.h"
#include "driver.h"

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
	long *transient;      /* per grid run: attempts killed, failed on I/O or lost in this
			       * `study run` (retried while at most o->retries) */
	char *outcome;        /* per grid run, its last launch: 0 nothing heard, 'k' killed,
			       * 'i' I/O, 'l' lost, 'h' stopped by the driver, 'r' recorded,
			       * 'm' its input (argument file, packing) deleted under it */
	int reserve;          /* the database's reserve is held (reserve.c) */
	struct owed *owed;    /* attempts the database would not take, to be written again
			       * before the driver ends (ingest.c) */
	struct watch *watch;  /* the progress line's look; NULL: no progress line */
	int progress_tty;     /* the progress line rewrites itself (stderr is a terminal) */
} drv;

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

/* parallel.c: GNU parallel over the jobs, the workers' lines handed to ingest.c (the
 * driver's SIGINT/SIGTERM reach parallel through stop.h) */
int run_parallel(drv *d, const char *kind, char **names, long n, char **basefiles, long nbase, sb_err *e);

/* ingest.c: a run's or a packing's outcome into the database (and into d->outcome,
 * d->transient for the retries) */
int ingest_run(drv *d, const char *id, sb_err *e);
int ingest_cache(drv *d, const char *key, sb_err *e);
void cache_state(drv *d, const char *key, char *st, size_t len);
int on_start(drv *d, char *line, sb_err *e);
int on_done(drv *d, int is_cache, char *line, sb_err *e);
void unreported(drv *d, sb_err *e);
/* The attempts the database would not take when they came (a full disk), written now;
 * each one that still cannot be is said on stderr. Frees them. */
int owed_settle(drv *d, sb_err *e);
/* the runs a killed driver left 'running': each an interrupted attempt, pending */
int orphans(drv *d, sb_err *e);

/* reserve.c: room on the campaign's disk held from the start (reserve_make), given
 * back for the last records after a full disk stopped the launching (reserve_release:
 * 1 when there was some to give) */
void reserve_make(drv *d);
int reserve_release(drv *d);

/* sweep.c: outputs finished while no driver listened, damaged ones, litter, failed
 * runs back in the queue (--retry-failed); the pending runs' indices in *pend */
int sweep(drv *d, long *pend, long *npend, sb_err *e);

#endif
