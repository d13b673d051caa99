/* dirs.h - directories the tools make: with their parents (mkdir -p), and the ones a
 * driver writes into, where a planted link is refused rather than followed. */
#ifndef LIB_DIRS_H
#define LIB_DIRS_H

#include "err.h"

/* path and every missing parent (an existing directory is fine); SB_EIO naming the
 * path when it cannot be made. */
int dirs_make(const char *path, sb_err *e);
/* A directory a driver writes into, made if missing (not its parents): a symbolic
 * link (or anything else) planted where it belongs is refused, never followed, so
 * nothing is written outside the runs directory through a link the driver did not
 * make. */
int dirs_own(const char *path, sb_err *e);
/* A file a driver writes: a symbolic link or anything but a regular file where it
 * belongs is refused (lstat: the link itself is judged); nothing there is fine. */
int dirs_own_file(const char *path, sb_err *e);

#endif
