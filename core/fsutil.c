/* fsutil.c - temporary-name-then-rename file writing. */
#define _POSIX_C_SOURCE 200809L
#include "fsutil.h"

#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <string.h>
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
