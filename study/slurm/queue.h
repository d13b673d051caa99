/* queue.h - asking Slurm: sbatch and squeue run as child processes from an argv
 * (never through a shell), their output captured, their errors returned with what
 * they printed. SLURM_CONF and the rest of the environment pass through. */
#ifndef ST_SLURM_QUEUE_H
#define ST_SLURM_QUEUE_H

#include "err.h"

typedef struct slurm_queue_task {
	long job, index;    /* index -1: tasks of the job still in one pending range */
	char state[24];     /* PENDING, RUNNING, COMPLETING, ... */
} slurm_queue_task;

typedef struct slurm_queue {
	slurm_queue_task *t;
	long n;
} slurm_queue;

/* Runs argv (argv[0] looked up in PATH); stdout into *out (malloc'd, NUL-ended),
 * stderr's last line into err. Returns the exit status, 128 + signal, or 127 when it
 * could not be started. */
int slurm_queue_run(char *const argv[], char **out, char *err, size_t errlen);

/* sbatch --parsable ARGS...: the job id in *jobid. */
int slurm_queue_submit(char *const args[], int nargs, long *jobid, sb_err *e);

/* This user's array tasks still known to the scheduler (squeue --array). */
int slurm_queue_list(slurm_queue *q, sb_err *e);
/* The task's state, or NULL when it is no longer queued, running or completing (it
 * ended, or was never this user's). */
const char *slurm_queue_state(const slurm_queue *q, long job, long index);
void slurm_queue_free(slurm_queue *q);

#endif
