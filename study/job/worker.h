/* worker.h - `study exec`: one job on whichever host GNU parallel chose. Runs
 * bin/shake with the argument file the driver wrote (no shell involved) and reports
 * one START and one DONE line on stdout for the driver to ingest. */
#ifndef ST_WORKER_H
#define ST_WORKER_H

#include <stddef.h>

#include "ledger/db.h"

/* kind "run": args jobs/NAME.args, log logs/NAME.log, output NAME.h5;
 * kind "cache": args cache/NAME.args, log cache/NAME.log, output cache/NAME.h5.
 * Paths are relative to dir. The outcome (the engine's exit code, 128 + signal if
 * killed) is in the DONE line; the return value is 0 whenever the engine ran, so that
 * GNU parallel tries a job again on another host (--retries) only when this host could
 * not run it (its argument file did not arrive, the run could not be locked: 2) or the
 * worker never got to report (its host died, it was killed) - never for a run's own
 * failure, which the driver records and retries itself when it is transient. */
int worker_exec(const char *dir, const char *kind, const char *name, const char *self);

/* The engine's message in its log from byte `from` on: the last "shake: " line,
 * else the last non-empty line; "" when there is none. */
void worker_last_message(const char *log, long from, char *out, size_t len);

/* An engine's end by a signal (exit code 128 + n in the DONE line) that is a crash of
 * its own (SIGSEGV, SIGBUS, SIGILL, SIGABRT, SIGFPE): a bug or a broken binary, which a
 * second attempt repeats, so the run is failed, never retried; any other signal
 * (SIGKILL of the OOM killer, SIGTERM of an admin or a scheduler) is a transient kill
 * (docs/driver.md, "Retry what is transient"). The one classification of
 * `study run` and of the Slurm tasks' results. */
int worker_crashed(long code);

#define WORKER_START "STUDY-START"
#define WORKER_DONE "STUDY-DONE"

/* A DONE line's fields, in this order after WORKER_DONE, tab-separated (the one place
 * that reads them; docs/driver.md): the job's name, the engine's exit code (128 + n
 * for signal n), the host, the wall seconds, the engine's CPU seconds (user + system)
 * and its peak resident memory in KiB (wait4: also when a signal ended it; "-" when no
 * engine ran), and the engine's last word (never a tab). */
typedef struct worker_done {
	const char *name, *host, *msg; /* into the line */
	long code;
	double wall;
	int ran;      /* an engine ran: its usage is known */
	db_usage u;
} worker_done;

/* Splits a DONE line in place into w; 0 when line is not one (or lacks a field). A
 * line of the earlier form without the two usage fields is read, its usage unknown. */
int worker_done_parse(char *line, worker_done *w);

/* The line the worker appends to the run's log when its engine has ended:
 * WORKER_USAGE "1.234 s of CPU, peak memory 16556 KiB (exit 7)". worker_last_message
 * skips it; worker_log_usage reads the last one from byte `from` on (1, into *u; 0:
 * none: the worker died with its engine). */
#define WORKER_USAGE "study exec: the engine used "
int worker_log_usage(const char *log, long from, db_usage *u);

/* The engine's usage for the attempt's row (db_attempt, db_ingest): NULL when none ran. */
static inline const db_usage *worker_usage(const worker_done *w)
{
	return w && w->ran ? &w->u : NULL;
}

#endif
