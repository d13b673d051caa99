/* reserve.c - room kept on the campaign's disk for the database's last records. A full
 * disk stops the launching (ingest.c), but the runs it stopped must still be recorded
 * as interrupted, with the reason, or the next `study run` finds them 'running' and
 * takes them for the runs of a killed driver (docs/driver.md, "What `study run`
 * does"). SQLite needs room for that (its write-ahead log grows), and on a full disk
 * there is none: the driver holds a little from its start (a file of allocated blocks
 * in the campaign's directory) and gives it back once its engines have stopped, for
 * the records it owes (ingest.c, ingest_owed_settle): given back earlier, the running engines
 * would take it. */
#define _GNU_SOURCE /* posix_fallocate's prototype is POSIX; O_NOFOLLOW, O_CLOEXEC */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include "drvlocal.h"

/* a stopped run's attempt is a few pages of the log (4 KiB each) */
#define RESERVE_PER_JOB (32L << 10)
#define RESERVE_MAX (4L << 20)
#define RESERVE_MIN (8L << 10)

static void reserve_path(const drv *d, char *out, size_t len)
{
	snprintf(out, len, "%s/.db_reserve", d->dir);
}

void reserve_make(drv *d)
{
	char p[PATHX];
	reserve_path(d, p, sizeof p);
	long n = RESERVE_PER_JOB * (d->loc->jobs + 1L);
	n = n < RESERVE_MAX ? n : RESERVE_MAX;
	/* O_NOFOLLOW: never blocks allocated through a link planted there */
	int fd = open(p, O_WRONLY | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0666);
	if (fd < 0)
		return; /* no reserve: a full disk then leaves runs 'running' at worst */
	/* less when that much is not free: a small disk needs it most */
	int bad = 1;
	for (; bad && n >= RESERVE_MIN; n /= 2)
		bad = posix_fallocate(fd, 0, n) != 0;
	close(fd);
	if (bad)
		unlink(p); /* too little room already: the launching will stop soon anyway */
	d->loc->reserve = !bad;
}

int reserve_release(drv *d)
{
	if (!d->loc || !d->loc->reserve)
		return 0;
	char p[PATHX];
	reserve_path(d, p, sizeof p);
	d->loc->reserve = 0;
	struct stat sb;
	/* only a regular file: what else stands there is not the driver's */
	return lstat(p, &sb) == 0 && S_ISREG(sb.st_mode) && unlink(p) == 0;
}
