/* driver.h - `study run`: expand a campaign, record it, build the packing caches,
 * run what is not complete with GNU parallel and ingest each run as it finishes. */
#ifndef ST_DRIVER_H
#define ST_DRIVER_H

#include "err.h"

typedef struct driver_opts {
	const char *campaign_file;
	const char *runs_dir;      /* root of every campaign's outputs (default "runs") */
	const char *db_path;       /* default RUNS/study.db */
	const char *sshloginfile;  /* NULL: local */
	const char *self;          /* absolute path of the study binary */
	int jobs;                  /* 0: number of cores */
	int retry_failed;
	int keep_old;              /* runs no longer in the file: keep as an earlier version */
	int forget_old;            /* ... or delete their rows, move their files aside */
	int use_cache;             /* packing cache on (default) */
	int progress;              /* -1 auto (terminal), 0 no, 1 yes */
	int retries;               /* a run killed, failed on I/O or lost with its host runs
				    * again up to this many times in one `study run` */
} driver_opts;

#define DRIVER_RETRIES 2

/* Driver exit codes (documented in docs/campaigns.md). */
enum { DRV_OK = 0, DRV_USAGE = 1, DRV_IO = 2, DRV_FAILED = 3, DRV_BUSY = 4, DRV_INTERRUPTED = 7 };

int driver_run(const driver_opts *o, sb_err *e);

/* Paths shared with the reporting commands. */
void driver_db_path(const char *runs_dir, const char *db_path, char *out, size_t len);

#endif
