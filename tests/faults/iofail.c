/* iofail.c - an LD_PRELOAD shim that makes file writes fail on demand, for the fault
 * tests (root ignores a read-only directory, so chmod cannot stage one). While the file
 * named by IOFAIL_TRIGGER exists, opening for writing or renaming a path that contains
 * one of the ':'-separated strings of IOFAIL_MATCH fails with errno IOFAIL_ERRNO
 * (default EROFS). Reads are never touched.
 * A full disk found only when HDF5 closes a dataset: while IOFAIL_CLOSE names a string,
 * every write (pwrite, write) made inside H5Dclose or H5Oclose to a file whose path
 * contains it fails with ENOSPC, the other writes go through. A dataset's last chunks
 * are written when it closes, and the file's metadata after them, so a writer that
 * ignores the close's failure goes on to seal and rename a file that holds zeros in
 * place of those chunks (docs/testing.md, "Hostile input and faults"). The hooks of
 * HDF5's own functions (here and H5Lvisit below) reach only a program linked with the
 * shared HDF5: the tests preload the shim into those links, $(BIN)/h5shared/ (Makefile). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int armed(const char *path)
{
	const char *trig = getenv("IOFAIL_TRIGGER"), *match = getenv("IOFAIL_MATCH");
	if (!trig || !match || !path || access(trig, F_OK) != 0)
		return 0;
	char buf[1024];
	snprintf(buf, sizeof buf, "%s", match);
	for (char *sv, *tok = strtok_r(buf, ":", &sv); tok; tok = strtok_r(NULL, ":", &sv))
		if (*tok && strstr(path, tok)) {
			const char *en = getenv("IOFAIL_ERRNO");
			errno = en ? atoi(en) : EROFS;
			return 1;
		}
	return 0;
}

static int writes(int flags)
{
	return (flags & (O_WRONLY | O_RDWR | O_CREAT | O_TRUNC)) != 0;
}

typedef int (*open_fn)(const char *, int, ...);
typedef int (*openat_fn)(int, const char *, int, ...);
typedef FILE *(*fopen_fn)(const char *, const char *);
typedef int (*rename_fn)(const char *, const char *);
typedef int (*renameat2_fn)(int, const char *, int, const char *, unsigned);
/* the next definition of name (libc's), looked up once */
#define REAL(name, type) \
	static type real_##name; \
	if (!real_##name) \
	*(void **)&real_##name = dlsym(RTLD_NEXT, #name)

/* A file that goes between a look and a read (IOFAIL_VANISH): while IOFAIL_VANISH names
 * a string, the first open for reading of a path that ends with it unlinks the path first,
 * as a deletion racing the reader would (a run directory removed while the driver
 * ingested a file it had just seen). Only in the process IOFAIL_VANISH_PID names (the
 * driver, not its workers), when set. */
static void vanish(const char *path, int flags)
{
	static int done;
	const char *match = getenv("IOFAIL_VANISH");
	const size_t lp = path ? strlen(path) : 0, lm = match ? strlen(match) : 0;
	const char *pid = getenv("IOFAIL_VANISH_PID");
	if (done || writes(flags) || !lm || lp < lm || strcmp(path + lp - lm, match) ||
	    (pid && *pid && atol(pid) != (long)getpid()))
		return;
	done = 1;
	unlink(path);
}

int open(const char *path, int flags, ...)
{
	REAL(open, open_fn);
	mode_t mode = 0;
	if (flags & O_CREAT) {
		va_list ap;
		va_start(ap, flags);
		mode = (mode_t)va_arg(ap, int);
		va_end(ap);
	}
	if (writes(flags) && armed(path))
		return -1;
	vanish(path, flags);
	return real_open(path, flags, mode);
}

int open64(const char *path, int flags, ...)
{
	REAL(open64, open_fn);
	mode_t mode = 0;
	if (flags & O_CREAT) {
		va_list ap;
		va_start(ap, flags);
		mode = (mode_t)va_arg(ap, int);
		va_end(ap);
	}
	if (writes(flags) && armed(path))
		return -1;
	vanish(path, flags);
	return real_open64(path, flags, mode);
}

int openat(int dir, const char *path, int flags, ...)
{
	REAL(openat, openat_fn);
	mode_t mode = 0;
	if (flags & O_CREAT) {
		va_list ap;
		va_start(ap, flags);
		mode = (mode_t)va_arg(ap, int);
		va_end(ap);
	}
	if (writes(flags) && armed(path))
		return -1;
	return real_openat(dir, path, flags, mode);
}

FILE *fopen(const char *path, const char *m)
{
	REAL(fopen, fopen_fn);
	if (m && (strchr(m, 'w') || strchr(m, 'a') || strchr(m, '+')) && armed(path))
		return NULL;
	return real_fopen(path, m);
}

FILE *fopen64(const char *path, const char *m)
{
	REAL(fopen64, fopen_fn);
	if (m && (strchr(m, 'w') || strchr(m, 'a') || strchr(m, '+')) && armed(path))
		return NULL;
	return real_fopen64(path, m);
}

int rename(const char *from, const char *to)
{
	REAL(rename, rename_fn);
	if (armed(from) || armed(to))
		return -1;
	return real_rename(from, to);
}

/* the engine's rename into a free name (core/base/fsutil.c) */
int renameat2(int fd1, const char *from, int fd2, const char *to, unsigned flags)
{
	REAL(renameat2, renameat2_fn);
	if (armed(from) || armed(to))
		return -1;
	return real_renameat2(fd1, from, fd2, to, flags);
}

/* --- failures inside HDF5's dataset close (IOFAIL_CLOSE) --- */
static int in_close; /* the process is inside H5Dclose or H5Oclose */

static int close_armed(int fd)
{
	const char *match = getenv("IOFAIL_CLOSE");
	if (!in_close || !match || !*match)
		return 0;
	char link[64], path[4096];
	snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
	ssize_t n = readlink(link, path, sizeof path - 1);
	if (n <= 0)
		return 0;
	path[n] = 0;
	if (!strstr(path, match))
		return 0;
	errno = ENOSPC;
	return 1;
}

typedef ssize_t (*pwrite_fn)(int, const void *, size_t, off_t);
typedef ssize_t (*write_fn)(int, const void *, size_t);
typedef int64_t shim_hid; /* HDF5 1.10's hid_t and herr_t, without its headers */
typedef int (*close_fn)(shim_hid);

ssize_t pwrite(int fd, const void *buf, size_t n, off_t off)
{
	REAL(pwrite, pwrite_fn);
	if (close_armed(fd))
		return -1;
	return real_pwrite(fd, buf, n, off);
}

ssize_t pwrite64(int fd, const void *buf, size_t n, off_t off)
{
	REAL(pwrite64, pwrite_fn);
	if (close_armed(fd))
		return -1;
	return real_pwrite64(fd, buf, n, off);
}

ssize_t write(int fd, const void *buf, size_t n)
{
	REAL(write, write_fn);
	if (close_armed(fd))
		return -1;
	return real_write(fd, buf, n);
}

int H5Dclose(shim_hid id)
{
	REAL(H5Dclose, close_fn);
	in_close++;
	int rc = real_H5Dclose(id);
	in_close--;
	return rc;
}

int H5Oclose(shim_hid id)
{
	REAL(H5Oclose, close_fn);
	in_close++;
	int rc = real_H5Oclose(id);
	in_close--;
	return rc;
}

/* --- HDF5 crashing on a damaged link table (IOFAIL_H5WALK) ---
 * HDF5 1.10.8 frees a wild pointer in H5Lvisit on some dense link tables that a
 * hostile hand sealed again (docs/inputs.md, "Run files"); the readers walk a file
 * first in a child process so that such a crash refuses the file. While IOFAIL_H5WALK
 * names a string, H5Lvisit crashes as HDF5 did there on every file whose name holds it,
 * without needing such a file; while IOFAIL_H5WALK_HANG does, it loops forever, as
 * HDF5 did on another damaged file (make fuzz, run-file input 1047 of seed 31). */
int H5Lvisit(shim_hid g, int idx, int order, void *op, void *data)
{
	typedef int (*visit_fn)(shim_hid, int, int, void *, void *);
	typedef ssize_t (*name_fn)(shim_hid, char *, size_t);
	REAL(H5Lvisit, visit_fn);
	REAL(H5Fget_name, name_fn);
	const char *match = getenv("IOFAIL_H5WALK");
	char name[4096];
	if (match && *match && real_H5Fget_name && real_H5Fget_name(g, name, sizeof name) > 0 && strstr(name, match))
		raise(SIGSEGV);
	const char *hang = getenv("IOFAIL_H5WALK_HANG");
	if (hang && *hang && real_H5Fget_name && real_H5Fget_name(g, name, sizeof name) > 0 && strstr(name, hang))
		for (;;)
			pause();
	return real_H5Lvisit(g, idx, order, op, data);
}
