/* fsutil.h - crash-safe files: write to a temporary name in the same directory,
 * fsync, rename into place, fsync the directory. A reader never sees half a file.
 * And the one way an input is opened for reading: regular files only. */
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
/* fs_commit's first half: flush, fsync and close the temporary (removed when that
 * fails), not yet renamed: a writer of several files puts them in place together
 * (fs_rename_durable), all or none. */
int fs_finish(sb_file *o, sb_err *e);

/* Creates (or truncates) path for writing, read too if rdwr, only where nothing or a
 * regular file stands: a symbolic link, FIFO, device, socket or directory there is
 * refused, never followed or written. A file descriptor, or -1 with the message. */
int fs_create(const char *path, int rdwr, sb_err *e);

/* Temporary name for `path` (same directory), for writers that open files themselves.
 * Clears the litter of earlier writers of path first (fs_clear_litter). */
void fs_tmp_name(const char *path, char *out, size_t len);
/* Removes path.tmp.PID where PID is a process that is gone (a writer killed before its
 * rename: SIGKILL, the OOM killer, a power cut) and a regular file stands: its
 * temporary would otherwise stay beside the output for good. A live writer's, this
 * process's and anything not a regular file are left. On a directory shared between
 * hosts a PID is only this host's: a writer elsewhere must not share the path. */
void fs_clear_litter(const char *path);
int fs_fsync_path(const char *path, sb_err *e);
/* Rename tmp to path, only over nothing or a regular file (fsutil.c), then fsync the
 * directory. */
int fs_rename_durable(const char *tmp, const char *path, sb_err *e);

/* May a run put a file at path: nothing stands there, or a regular file (a symbolic
 * link is not followed)? When not, *kind says what stands there ("a FIFO"). */
int fs_replaceable(const char *path, const char **kind);
/* Do two output paths name the same file: the same path once the directory part is
 * resolved (realpath: "./a.h5" and "a.h5", a path through a directory's symbolic link),
 * or the same existing file (device and inode, lstat). Two outputs of one run at one
 * path would have one delete or overwrite the other (docs/output.md). */
int fs_same_file(const char *a, const char *b);
/* "a directory", "a character device", ... for a st_mode. */
const char *fs_kind(unsigned mode);

/* Opens an input for reading when it is a regular file (docs/inputs.md, "Files"): a
 * FIFO would block the open, and then every read, until a writer comes; a directory
 * opens and reads as an empty file; a device never ends. The open itself does not
 * block. `what` names the input in the message ("scene file"); a file that is not
 * regular, or larger than max_bytes (> 0), is refused with `code`; a file that cannot
 * be opened too (its errno said). NULL on error. */
FILE *fs_open_input(const char *path, const char *what, long long max_bytes, int code, sb_err *e);

/* The same check for a reader that opens the file by name itself (HDF5): 0 when path
 * is a regular file, else `code` with the message. Stat first: an open of a FIFO would
 * wait for a writer. */
int fs_check_input(const char *path, const char *what, int code, sb_err *e);

#endif
