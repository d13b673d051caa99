/* fsutil.h - crash-safe files: write to a temporary name in the same directory,
 * fsync, rename into place, fsync the directory. A reader never sees half a file. */
#ifndef SB_FSUTIL_H
#define SB_FSUTIL_H

#include <stdio.h>

#include "err.h"

typedef struct sb_file {
	FILE *f;
	char path[4096];
	char tmp[4096 + 32];
} sb_file;

int fs_open_tmp(sb_file *o, const char *path, sb_err *e);
int fs_commit(sb_file *o, sb_err *e);   /* flush, fsync, close, rename, fsync dir; the
					* temporary is removed when that fails */
void fs_abort(sb_file *o);              /* close and remove the temporary */

/* Temporary name for `path` (same directory), for writers that open files themselves. */
void fs_tmp_name(const char *path, char *out, size_t len);
int fs_fsync_path(const char *path, sb_err *e);
/* Rename tmp to path, only over nothing or a regular file (fsutil.c), then fsync the
 * directory. */
int fs_rename_durable(const char *tmp, const char *path, sb_err *e);

/* May a run put a file at path: nothing stands there, or a regular file (a symbolic
 * link is not followed)? When not, *kind says what stands there ("a FIFO"). */
int fs_replaceable(const char *path, const char **kind);
/* "a directory", "a character device", ... for a st_mode. */
const char *fs_kind(unsigned mode);

#endif
