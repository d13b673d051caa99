/* collect.h - private to submit.c and collect.c: the Slurm tables, and what
 * the tasks of a campaign's arrays did, read from their logs and squeue into the
 * database through the driver's own ingest (drv.h). */
#ifndef ST_SLURM_COLLECT_H
#define ST_SLURM_COLLECT_H

#include "local/drv.h"
#include "queue.h"

/* RUNS/NAME/slurm: the array script, the task files, the tasks' logs */
#define SLURM_SUB "slurm"

/* CREATE TABLE IF NOT EXISTS slurm_job, slurm_task (docs/database.md). */
int slurm_tables(st_db *db, sb_err *e);

/* Every task of the campaign's arrays not yet accounted for: its log's START/DONE
 * lines (the output file decides, as in ingest.c; else the exit code), a
 * finished output without a line, a task that ended (q: squeue now; NULL when it
 * could not say) after its run started but before it reported (an attempt
 * "killed"), or before its run started (no attempt). */
int slurm_collect(drv *d, const slurm_queue *q, sb_err *e);

/* Per grid run of d: 1 when a task of an array holds it (queued or running). */
int slurm_busy(drv *d, const slurm_queue *q, char *busy, long *nbusy, sb_err *e);

/* A drv for campaign file `path` under runs root `root` (absolute), the database
 * open, the per-run arrays allocated; driver-like options in *o. */
int slurm_drv_open(drv *d, const driver_opts *o, const char *path, sb_err *e);
void slurm_drv_close(drv *d);

#endif
