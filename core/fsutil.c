/* fsutil.c - temporary-name-then-rename file writing. */
#define _POSIX_C_SOURCE 200809L
#include "fsutil.h"

#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void fs_tmp_name(const char *path, char *out, size_t len)
{
	snprintf(out, len, "%s.tmp.%ld", path, (long)getpid());
}

int fs_open_tmp(sb_file *o, const char *path, sb_err *e)
{
	snprintf(o->path, sizeof o->path, "%s", path);
	fs_tmp_name(path, o->tmp, sizeof o->tmp);
	o->f = fopen(o->tmp, "w");
	if (!o->f)
		return sb_errf(e, SB_EIO, "%s: cannot create: %s", o->tmp, strerror(errno));
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

int fs_rename_durable(const char *tmp, const char *path, sb_err *e)
{
	if (rename(tmp, path))
		return sb_errf(e, SB_EIO, "%s: cannot rename into place: %s", path, strerror(errno));
	char dir[4096];
	snprintf(dir, sizeof dir, "%s", path);
	return fs_fsync_path(dirname(dir), e);
}

int fs_commit(sb_file *o, sb_err *e)
{
	int bad = fflush(o->f) != 0 || ferror(o->f) || fsync(fileno(o->f)) != 0;
	int saved = errno;
	bad |= fclose(o->f) != 0;
	o->f = NULL;
	if (bad) {
		unlink(o->tmp);
		return sb_errf(e, SB_EIO, "%s: write failed: %s", o->path, strerror(saved ? saved : errno));
	}
	return fs_rename_durable(o->tmp, o->path, e);
}

void fs_abort(sb_file *o)
{
	if (o->f)
		fclose(o->f);
	o->f = NULL;
	unlink(o->tmp);
}

/* why a file of this mode is no input */
static const char *not_regular(mode_t m)
{
	return S_ISDIR(m) ? "is a directory" : S_ISFIFO(m) ? "is not a regular file (a FIFO)" : "is not a regular file";
}

static int refuse(const char *path, const char *what, mode_t m, int code, sb_err *e)
{
	return sb_errf(e, code, "%s: %s: a %s must be a regular file (a FIFO or a device would be read without end)",
		       path, not_regular(m), what);
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
