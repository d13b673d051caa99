/* fsutil.c - temporary-name-then-rename file writing. */
#define _GNU_SOURCE /* renameat2 and RENAME_NOREPLACE (glibc 2.28) */
#include "fsutil.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void fs_tmp_name(const char *path, char *out, size_t len)
{
	snprintf(out, len, "%s.tmp.%ld", path, (long)getpid());
	fs_clear_litter(path);
}

void fs_clear_litter(const char *path)
{
	char d[4096], b[4096];
	snprintf(d, sizeof d, "%s", path);
	snprintf(b, sizeof b, "%s", path);
	const char *dir = dirname(d), *base = basename(b);
	const size_t lb = strlen(base);
	DIR *dd = opendir(dir);
	if (!dd)
		return;
	for (struct dirent *de; (de = readdir(dd));) {
		if (strncmp(de->d_name, base, lb) || strncmp(de->d_name + lb, ".tmp.", 5))
			continue;
		char *end;
		const long pid = strtol(de->d_name + lb + 5, &end, 10);
		/* a process that is gone: kill(pid, 0) says so with ESRCH (a live one of another
		 * user's says EPERM, and its file stays) */
		if (*end || pid <= 0 || pid == (long)getpid() || kill((pid_t)pid, 0) == 0 || errno != ESRCH)
			continue;
		char p[8192];
		struct stat st;
		snprintf(p, sizeof p, "%s/%s", dir, de->d_name);
		if (lstat(p, &st) == 0 && S_ISREG(st.st_mode))
			unlink(p);
	}
	closedir(dd);
}

const char *fs_kind(unsigned mode)
{
	switch (mode & S_IFMT) {
	case S_IFREG: return "a regular file";
	case S_IFDIR: return "a directory";
	case S_IFLNK: return "a symbolic link";
	case S_IFCHR: return "a character device";
	case S_IFBLK: return "a block device";
	case S_IFIFO: return "a FIFO";
	case S_IFSOCK: return "a socket";
	}
	return "not a regular file";
}

int fs_replaceable(const char *path, const char **kind)
{
	struct stat st;
	*kind = NULL;
	/* lstat: a symbolic link is judged itself, never what it points to */
	if (lstat(path, &st) != 0 || S_ISREG(st.st_mode))
		return 1; /* nothing there (or nothing to see: the write will say why) */
	*kind = fs_kind((unsigned)st.st_mode);
	return 0;
}

/* path with its directory part resolved (realpath), or as given when the directory
 * cannot be resolved (then the write will say why); a trailing "/." or "/" is not a
 * file name a run writes, so the base name is kept as given. */
static void resolved(const char *path, char *out, size_t len)
{
	char d[4096], b[4096], *real;
	snprintf(d, sizeof d, "%s", path);
	snprintf(b, sizeof b, "%s", path);
	real = realpath(dirname(d), NULL);
	if (!real) {
		snprintf(out, len, "%s", path);
		return;
	}
	snprintf(out, len, "%s/%s", strcmp(real, "/") ? real : "", basename(b));
	free(real);
}

int fs_same_file(const char *a, const char *b)
{
	char ra[8192], rb[8192];
	resolved(a, ra, sizeof ra);
	resolved(b, rb, sizeof rb);
	if (!strcmp(ra, rb))
		return 1;
	struct stat sa, sb;
	return lstat(a, &sa) == 0 && lstat(b, &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

int fs_create(const char *path, int rdwr, sb_err *e)
{
	/* the temporary names carry this process's id: a regular file there is a dead
	 * process's litter, to be overwritten; anything else was put there, and neither
	 * it nor what a link points to is written */
	struct stat st;
	if (lstat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
		sb_errf(e, SB_EIO, "%s: %s stands there, not a regular file: not written", path,
			fs_kind((unsigned)st.st_mode));
		return -1;
	}
	int fd = open(path, (rdwr ? O_RDWR : O_WRONLY) | O_CREAT | O_TRUNC | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0666);
	if (fd < 0) {
		sb_errf(e, SB_EIO, "%s: cannot create: %s", path,
			errno == ELOOP ? "a symbolic link stands there (not followed)" : strerror(errno));
		return -1;
	}
	if (fstat(fd, &st) || !S_ISREG(st.st_mode)) { /* one that came between lstat and open */
		sb_errf(e, SB_EIO, "%s: not a regular file: not written", path);
		close(fd);
		return -1;
	}
	return fd;
}

int fs_open_tmp(sb_file *o, const char *path, sb_err *e)
{
	snprintf(o->path, sizeof o->path, "%s", path);
	fs_tmp_name(path, o->tmp, sizeof o->tmp);
	int fd = fs_create(o->tmp, 0, e);
	if (fd < 0)
		return e->code;
	o->f = fdopen(fd, "w");
	if (!o->f) {
		close(fd);
		return sb_errf(e, SB_EIO, "%s: cannot create: %s", o->tmp, strerror(errno));
	}
	return 0;
}

int fs_fsync_path(const char *path, sb_err *e)
{
	int fd = open(path, O_RDONLY);
	if (fd < 0)
		return sb_errf(e, SB_EIO, "%s: cannot open for fsync: %s", path, strerror(errno));
	int rc = fsync(fd);
	close(fd);
	if (rc && errno != EINVAL) /* some file systems cannot fsync directories */
		return sb_errf(e, SB_EIO, "%s: fsync failed: %s", path, strerror(errno));
	return 0;
}

/* The rename into place replaces only a regular file: a device, FIFO, socket,
 * directory or link that stands at the path (docs/output.md; bin/shake refuses those
 * before it runs, this is for one that appeared meanwhile) is left alone and the write
 * fails. Where nothing stands, RENAME_NOREPLACE takes the name only if it is still
 * free. Where a regular file stands, a window of microseconds remains between lstat
 * and rename in which someone could put a device there; doing that takes write access
 * to the directory (and root, for a device) at that instant, and this guard is against
 * mistakes - a path typed wrong, a fuzzed scene - not against someone who can already
 * replace the directory's files. */
static int rename_regular(const char *tmp, const char *path, sb_err *e)
{
	for (int tries = 0; tries < 3; tries++) {
		struct stat st;
		if (lstat(path, &st) == 0) {
			if (!S_ISREG(st.st_mode))
				return sb_errf(e, SB_EIO, "%s: %s stands there, not a regular file: not replaced", path,
					       fs_kind((unsigned)st.st_mode));
			break; /* a regular file: replaced by rename below */
		}
		if (errno != ENOENT)
			break; /* nothing to see: rename says why */
		if (!renameat2(AT_FDCWD, tmp, AT_FDCWD, path, RENAME_NOREPLACE))
			return 0;
		if (errno == EEXIST)
			continue; /* something took the name meanwhile: look at it */
		if (errno != EINVAL && errno != ENOSYS)
			return sb_errf(e, SB_EIO, "%s: cannot rename into place: %s", path, strerror(errno));
		break; /* a file system without RENAME_NOREPLACE */
	}
	if (rename(tmp, path))
		return sb_errf(e, SB_EIO, "%s: cannot rename into place: %s", path, strerror(errno));
	return 0;
}

int fs_rename_durable(const char *tmp, const char *path, sb_err *e)
{
	if (rename_regular(tmp, path, e))
		return e->code;
	char dir[4096];
	snprintf(dir, sizeof dir, "%s", path);
	return fs_fsync_path(dirname(dir), e);
}

int fs_finish(sb_file *o, sb_err *e)
{
	int bad = fflush(o->f) != 0 || ferror(o->f) || fsync(fileno(o->f)) != 0;
	int saved = bad ? errno : 0; /* a write's failure (a full disk) is the one to say */
	if (fclose(o->f) != 0 && !bad) { /* NFS, for one, reports a failed write only here */
		bad = 1;
		saved = errno;
	}
	o->f = NULL;
	if (bad) {
		unlink(o->tmp);
		return sb_errf(e, SB_EIO, "%s: write failed: %s", o->path, strerror(saved ? saved : EIO));
	}
	return 0;
}

int fs_commit(sb_file *o, sb_err *e)
{
	if (fs_finish(o, e))
		return e->code;
	int rc = fs_rename_durable(o->tmp, o->path, e);
	if (rc)
		unlink(o->tmp); /* still there when the rename failed; gone when it did not */
	return rc;
}

void fs_abort(sb_file *o)
{
	if (o->f)
		fclose(o->f);
	o->f = NULL;
	unlink(o->tmp);
}

static int refuse(const char *path, const char *what, mode_t m, int code, sb_err *e)
{
	return sb_errf(e, code, "%s: is %s, not a regular file: a %s must be a regular file (a FIFO or a device "
		       "would be read without end)", path, fs_kind((unsigned)m), what);
}

int fs_check_input(const char *path, const char *what, int code, sb_err *e)
{
	struct stat sb;
	if (stat(path, &sb))
		return sb_errf(e, code, "%s: cannot open %s: %s", path, what, strerror(errno));
	if (!S_ISREG(sb.st_mode))
		return refuse(path, what, sb.st_mode, code, e);
	return 0;
}

FILE *fs_open_input(const char *path, const char *what, long long max_bytes, int code, sb_err *e)
{
	/* O_NONBLOCK: the open of a FIFO returns at once, to be refused; it changes
	 * nothing for a regular file */
	int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
	if (fd < 0) {
		sb_errf(e, code, "%s: cannot open %s: %s", path, what, strerror(errno));
		return NULL;
	}
	struct stat sb;
	if (fstat(fd, &sb)) {
		sb_errf(e, SB_EIO, "%s: cannot open %s: %s", path, what, strerror(errno));
		close(fd);
		return NULL;
	}
	if (!S_ISREG(sb.st_mode)) {
		refuse(path, what, sb.st_mode, code, e);
		close(fd);
		return NULL;
	}
	if (max_bytes > 0 && sb.st_size > max_bytes) {
		sb_errf(e, code, "%s: %lld bytes, more than the %lld a %s may have", path, (long long)sb.st_size,
			max_bytes, what);
		close(fd);
		return NULL;
	}
	FILE *f = fdopen(fd, "r");
	if (!f) {
		sb_errf(e, SB_ENOMEM, "%s: cannot open %s: %s", path, what, strerror(errno));
		close(fd);
	}
	return f;
}
