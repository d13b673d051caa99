/* lock.h - the runs directory's lock protocol: one driver per campaign and database.
 * A driver (`study run`, `study submit`) holds an exclusive flock on
 * RUNS/NAME/.driver.lock and on DB.NAME.lock beside the database while it works; a
 * reader never waits for either (docs/driver.md, "What `study run` does", step 2). */
#ifndef LIB_LOCK_H
#define LIB_LOCK_H

#include <stddef.h>

#include "err.h"

/* The error code of a lock another process holds (the driver's exit code 4). */
#define LOCK_BUSY 4

/* DIR/.driver.lock and DB.NAME.lock; the length needed (snprintf's). */
int lock_campaign_path(const char *dir, char *out, size_t len);
int lock_database_path(const char *db, const char *name, char *out, size_t len);

/* Take the campaign's lock (dir: RUNS/NAME, name: the campaign's) without waiting:
 * its descriptor, or -1 with e set: LOCK_BUSY when another process holds it, SB_EIO
 * when it cannot be made or taken (a read-only or full runs directory), naming the
 * file and why. A symbolic link planted there is refused, never followed. */
int lock_campaign(const char *dir, const char *name, sb_err *e);
/* The same for the lock of the campaign in the database db: a second driver on the
 * same database with another runs directory is refused with LOCK_BUSY. */
int lock_database(const char *db, const char *name, sb_err *e);
/* The campaign's lock if it is free, else -1 (whatever the reason): for a reader that
 * writes only while no driver works (the Slurm collection of `study status`). */
int lock_campaign_try(const char *dir);
/* Does a process hold the campaign's lock? Read from /proc/locks, never by taking
 * it: a watcher holding it even for a moment would turn a starting driver away.
 * 0 when the lock file does not exist, -1 when it cannot be known. */
int lock_campaign_held(const char *dir);

#endif
