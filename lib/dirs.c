/* dirs.c - making directories, refusing planted links (dirs.h). */
#include "dirs.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

int dirs_make(const char *path, sb_err *e)
{
	char tmp[4096];
	if (snprintf(tmp, sizeof tmp, "%s", path) >= (int)sizeof tmp)
		return sb_errf(e, SB_EIO, "%s: cannot create directory: path too long", path);
	/* the parents' own failures show in the last mkdir's */
	for (char *p = tmp + 1; *p; p++)
		if (*p == '/') {
			*p = 0;
			mkdir(tmp, 0777);
			*p = '/';
		}
	if (mkdir(tmp, 0777) && errno != EEXIST)
		return sb_errf(e, SB_EIO, "%s: cannot create directory: %s", path, strerror(errno));
	return 0;
}

int dirs_own(const char *path, sb_err *e)
{
	struct stat st;
	if (mkdir(path, 0777) && errno != EEXIST)
		return sb_errf(e, SB_EIO, "%s: cannot create directory: %s", path, strerror(errno));
	if (lstat(path, &st))
		return sb_errf(e, SB_EIO, "%s: %s", path, strerror(errno));
	if (S_ISLNK(st.st_mode))
		return sb_errf(e, SB_EIO, "%s: is a symbolic link; study writes only into directories it made "
			       "(remove the link)", path);
	if (!S_ISDIR(st.st_mode))
		return sb_errf(e, SB_EIO, "%s: is not a directory", path);
	return 0;
}

int dirs_own_file(const char *path, sb_err *e)
{
	struct stat st;
	if (lstat(path, &st) == 0 && !S_ISREG(st.st_mode))
		return sb_errf(e, SB_EIO, "%s: is %s; study writes only files it made (remove it)", path,
			       S_ISLNK(st.st_mode) ? "a symbolic link" : "not a regular file");
	return 0;
}
