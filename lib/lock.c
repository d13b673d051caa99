/* lock.c - the runs directory's lock protocol (lock.h). */
#include "lock.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#define LOCK_PATH 4400

int lock_campaign_path(const char *dir, char *out, size_t len)
{
	return snprintf(out, len, "%s/.driver.lock", dir);
}

/* beside the database, as SQLite keeps DB-journal there: two drivers given the same
 * database but different runs directories would each hold their own directory's lock
 * and run every run twice */
int lock_database_path(const char *db, const char *name, char *out, size_t len)
{
	return snprintf(out, len, "%s.%s.lock", db, name);
}

/* what: "campaign's" or "database's"; busy: the message when another holds it */
static int take(const char *lp, const char *what, const char *busy, sb_err *e)
{
	int fd = open(lp, O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0666);
	if (fd < 0) {
		sb_errf(e, SB_EIO, "%s: cannot open the %s driver lock: %s", lp, what, strerror(errno));
		return -1;
	}
	if (flock(fd, LOCK_EX | LOCK_NB)) {
		/* only a lock held elsewhere is another driver; any other failure is the file
		 * system's (flock(2): EWOULDBLOCK is the one "held by another") */
		const int err = errno;
		close(fd);
		if (err == EWOULDBLOCK)
			sb_errf(e, LOCK_BUSY, "%s (%s)", busy, lp);
		else
			sb_errf(e, SB_EIO, "%s: cannot lock the %s driver lock: %s", lp, what, strerror(err));
		return -1;
	}
	return fd;
}

int lock_campaign(const char *dir, const char *name, sb_err *e)
{
	char lp[LOCK_PATH], busy[LOCK_PATH];
	lock_campaign_path(dir, lp, sizeof lp);
	snprintf(busy, sizeof busy, "campaign %s is being run by another study driver", name);
	return take(lp, "campaign's", busy, e);
}

int lock_database(const char *db, const char *name, sb_err *e)
{
	char lp[LOCK_PATH], busy[2 * LOCK_PATH];
	lock_database_path(db, name, lp, sizeof lp);
	snprintf(busy, sizeof busy, "campaign %s of database %s is being run by another study driver", name, db);
	return take(lp, "database's", busy, e);
}

int lock_campaign_try(const char *dir)
{
	char lp[LOCK_PATH];
	lock_campaign_path(dir, lp, sizeof lp);
	int fd = open(lp, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
	if (fd >= 0 && flock(fd, LOCK_EX | LOCK_NB)) {
		close(fd);
		fd = -1;
	}
	return fd;
}

int lock_campaign_held(const char *dir)
{
	char lp[LOCK_PATH];
	struct stat sb;
	lock_campaign_path(dir, lp, sizeof lp);
	if (stat(lp, &sb))
		return 0;
	FILE *f = fopen("/proc/locks", "r");
	if (!f)
		return -1;
	char line[256];
	int found = 0;
	while (!found && fgets(line, sizeof line, f)) {
		char kind[16];
		unsigned maj, min;
		unsigned long ino;
		/* "1: FLOCK  ADVISORY  WRITE 1234 fd:01:5678 0 EOF" (waiters have "->" first) */
		const char *p = strstr(line, ": ");
		if (p && sscanf(p + 2, "%15s %*s %*s %*d %x:%x:%lu", kind, &maj, &min, &ino) == 4 && !strcmp(kind, "FLOCK") &&
		    ino == (unsigned long)sb.st_ino && maj == major(sb.st_dev) && min == minor(sb.st_dev) && !strstr(line, "->"))
			found = 1;
	}
	fclose(f);
	return found;
}
