/* slurm_queue.h - asking Slurm: sbatch and squeue run as child processes from an argv
 * (never through a shell), their output captured, their errors returned with what
 * they printed. SLURM_CONF and the rest of the environment pass through. */
#ifndef ST_SLURM_QUEUE_H
#define ST_SLURM_QUEUE_H

#include "err.h"

typedef struct sq_task {
	long job, index;    /* index -1: tasks of the job still in one pending range */
	char state[24];     /* PENDING, RUNNING, COMPLETING, ... */
} sq_task;

typedef struct sq_queue {
	sq_task *t;
	long n;
} sq_queue;

/* Runs argv (argv[0] looked up in PATH); stdout into *out (malloc'd, NUL-ended),
 * stderr's last line into err. Returns the exit status, 128 + signal, or 127 when it
 * could not be started. */
int sq_run(char *const argv[], char **out, char *err, size_t errlen);

/* sbatch --parsable ARGS...: the job id in *jobid. */
int sq_submit(char *const args[], int nargs, long *jobid, sb_err *e);

/* This user's array tasks still known to the scheduler (squeue --array). */
int sq_list(sq_queue *q, sb_err *e);
/* The task's state, or NULL when it is no longer queued, running or completing (it
 * ended, or was never this user's). */
const char *sq_state(const sq_queue *q, long job, long index);
void sq_free(sq_queue *q);

#endif
