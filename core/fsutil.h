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
int fs_commit(sb_file *o, sb_err *e);   /* flush, fsync, close, rename, fsync dir */
void fs_abort(sb_file *o);              /* close and remove the temporary */

/* Temporary name for `path` (same directory), for writers that open files themselves. */
void fs_tmp_name(const char *path, char *out, size_t len);
int fs_fsync_path(const char *path, sb_err *e);
int fs_rename_durable(const char *tmp, const char *path, sb_err *e);

#endif
