/* submit.h - a campaign on a Slurm cluster: `study submit CAMPAIGN --slurm` prepares
 * the runs exactly as `study run` does (argument files, packing choice) and submits
 * one job array whose tasks run `study exec` on the nodes; what the tasks did is read
 * back from their files by `study status`, `study run` and the next `study submit`.
 * The database never leaves the machine study runs on (the login node); the campaign
 * directory must be on a file system the nodes see at the same path. */
#ifndef ST_SLURM_H
#define ST_SLURM_H

#include <stdio.h>

#include "err.h"
#include "local/driver.h"

typedef struct slurm_opts {
	long throttle;            /* at most this many tasks at once (--array=...%K); 0: no limit */
	long runs_per_task;       /* runs one after the other in a task (>= 1) */
	const char *sbatch_args;  /* more sbatch options, split at whitespace; NULL: none */
	int dry_run;              /* print the script, the task lines and the sbatch command;
				   * submit nothing (the runs are recorded and their argument
				   * files written, as a submit would) */
	long after;               /* the planning job of a search: the array of the round it
				   * follows (0: a submit of the user's) */
} slurm_opts;

/* The array's time limit: the longest task's runs at this machine's measured CPU rate
 * (report/cost.h) times this margin, rounded up to whole minutes, at least SLURM_TIME_MIN
 * minutes; a user's --sbatch-args --time=... wins (docs/cluster.md). */
#define SLURM_TIME_MARGIN 3.0
#define SLURM_TIME_MIN 5
/* The planning job of a search's round (docs/cluster.md, "Searches on Slurm"): its time
 * limit in minutes; it reads the round's results and submits the next round. */
#define SLURM_PLAN_MINUTES 10

/* Submits the runs of the campaign that are neither done (nor failed, unless
 * o->retry_failed) nor queued or running in an earlier array: writes their argument
 * files, a task file and RUNS/NAME/slurm/array.sh, runs sbatch, records the job in
 * the tables slurm_job and slurm_task. Exit codes as study run's (driver.h). */
int slurm_submit(const driver_opts *o, const slurm_opts *so, sb_err *e);

/* What the tasks of the recorded arrays of campaign `name` (NULL: every campaign
 * with arrays) did, into the database: finished runs ingested, interrupted and killed
 * attempts recorded with their job and index. *active gets the runs whose tasks are
 * still queued or running (-1 when squeue cannot say). Does nothing without arrays;
 * a campaign that a driver holds is left to it. Messages go to msg. */
int slurm_refresh(const char *runs_dir, const char *db_path, const char *name, long *active, FILE *msg,
		  sb_err *e);

/* For study status: one line per array of the campaign (NULL: all): its tasks
 * queued, running and ended, what became of its runs, where its logs are. */
int slurm_report(const char *db_path, const char *name, FILE *out, sb_err *e);

#endif
