/* progress.h - the progress line of `study run` (the reporting part of a drv, d->prog):
 * report/watch.h's look, rewritten in place on a terminal, a line at a time
 * otherwise, on stderr. */
#ifndef ST_PROGRESS_H
#define ST_PROGRESS_H

#include "ledger/db.h"

typedef struct drv_progress drv_progress;

/* For campaign `name` in directory `dir`; tty: stderr is a terminal (the line rewrites
 * itself). NULL when out of memory (then there is no progress line). */
drv_progress *progress_open(const char *name, const char *dir, int tty);
void progress_close(drv_progress *p);
/* One look at the database and the journals, shown; final: the last, ended by a
 * newline. Nothing for p NULL. */
void progress_show(drv_progress *p, st_db *db, int final);
/* The line rewrites itself: a worker's own line must first clear it (0 for p NULL). */
int progress_tty(const drv_progress *p);

#endif
