/* plan.h - the pure part of `study submit --slurm`: which runs go into which
 * array task, the --array value, the user's sbatch arguments, and reading what sbatch,
 * squeue and the tasks' logs say. No I/O here, so all of it is unit-tested
 * (tests/unit/study_slurm.c). */
#ifndef ST_SLURM_PLAN_H
#define ST_SLURM_PLAN_H

#include <stddef.h>

/* One run to submit: its id and, when it starts from a packing nobody has built yet,
 * that packing's key ("" otherwise). */
typedef struct slurm_plan_run {
	const char *id;
	const char *build_key;
} slurm_plan_run;

/* The line of every array task: "c:KEY r:ID r:ID ...", `per_task` runs a line, each
 * packing to build named (c:) before the first run of the line that needs it (so
 * whichever task gets there first builds it; the others find it built, or wait for
 * its lock). With per_task > 1 the runs are ordered by packing first, so that the
 * runs of one packing share tasks. lines[i] is malloc'd; returns the number of lines,
 * -1 when out of memory. */
long slurm_plan_task_lines(const slurm_plan_run *runs, long n, long per_task, char ***lines);
void slurm_plan_free_lines(char **lines, long n);

/* "0-9%2", "0-9" (throttle 0: none) for ntasks tasks. */
void slurm_plan_array_spec(long ntasks, long throttle, char *out, size_t len);

/* The user's --sbatch-args split at whitespace (no quoting: no shell sees them).
 * Refuses the options study submit sets itself (--array, --output, --parsable,
 * --wrap), naming the word. argv gets at most max words (malloc'd); returns the count
 * or -1 with the reason in why. */
int slurm_plan_split_args(const char *s, char **argv, int max, char *why, size_t whylen);

/* The job id from `sbatch --parsable` ("123" or "123;cluster"), -1 when there is none. */
long slurm_plan_parse_jobid(const char *out);

/* One line of `squeue --noheader --array --format=%i|%T`: "123_4|RUNNING" gives job
 * 123, index 4 and the state; a job that is not an array task, or a range the
 * scheduler has not split yet ("123_[4-9%2]"), gives index -1. 0 when the line is not
 * of that form. */
int slurm_plan_parse_squeue(const char *line, long *job, long *index, char *state, size_t slen);

/* A worker's line in a task's log (worker.h): WORKER_START or WORKER_DONE, its name,
 * and for DONE the exit code. 1 START, 2 DONE, 0 any other line. */
int slurm_plan_parse_worker(const char *line, char *name, size_t nlen, long *code);

#endif
