/* journal.c - binary record stream: header "SBJRNL01" + int32 nm, then records of
 * int32 tag, int32 count, count doubles. Native byte order: the journal never leaves
 * the machine that writes it (the HDF5 output does). */
#include "journal.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <string.h>
#include <unistd.h>
#include <sys/stat.h>

#include "fsutil.h"

static const char MAGIC[8] = {'S', 'B', 'J', 'R', 'N', 'L', '0', '1'};

int journal_open(sb_journal *j, const char *path, int nm, long offset, sb_err *e)
{
	memset(j, 0, sizeof *j);
	snprintf(j->path, sizeof j->path, "%s", path);
	j->nm = nm;
	j->discard = !path[0];
	if (j->discard)
		return 0;
	if (offset < 0) {
		int fd = fs_create(path, 1, e);
		if (fd < 0)
			return e->code;
		j->f = fdopen(fd, "w+b");
		if (!j->f) {
			close(fd);
			return sb_errf(e, SB_EIO, "%s: cannot create journal: %s", path, strerror(errno));
		}
		int32_t n32 = nm;
		if (fwrite(MAGIC, 1, 8, j->f) != 8 || fwrite(&n32, 4, 1, j->f) != 1)
			return sb_errf(e, SB_EIO, "%s: write failed", path);
		return 0;
	}
	/* a journal is only ever the engine's own regular file: no link is followed */
	int fd = open(path, O_RDWR | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
	struct stat st;
	if (fd >= 0 && (fstat(fd, &st) || !S_ISREG(st.st_mode))) {
		close(fd);
		return sb_errf(e, SB_EIO, "%s: not a regular file: not reopened for restart", path);
	}
	j->f = fd < 0 ? NULL : fdopen(fd, "r+b");
	if (!j->f) {
		if (fd >= 0)
			close(fd);
		return sb_errf(e, SB_EIO, "%s: cannot reopen journal for restart: %s", path, strerror(errno));
	}
	if (ftruncate(fileno(j->f), offset) || fseek(j->f, offset, SEEK_SET))
		return sb_errf(e, SB_EIO, "%s: cannot truncate to the checkpoint: %s", path, strerror(errno));
	return 0;
}

static int put(sb_journal *j, int32_t tag, int32_t count, sb_err *e)
{
	int32_t h[2] = {tag, count};
	if (j->discard)
		return 0;
	if (fwrite(h, 4, 2, j->f) != 2)
		return sb_errf(e, SB_EIO, "%s: write failed: %s", j->path, strerror(errno));
	return 0;
}

int journal_record(sb_journal *j, int tag, const double *data, int count, sb_err *e)
{
	if (put(j, tag, count, e))
		return e->code;
	if (j->discard)
		return 0;
	if (fwrite(data, sizeof(double), (size_t)count, j->f) != (size_t)count)
		return sb_errf(e, SB_EIO, "%s: write failed: %s", j->path, strerror(errno));
	return 0;
}

int journal_snap(sb_journal *j, int tag, double t, const double *x, const double *y, const double *th,
		 const double *vx, const double *vy, sb_err *e)
{
	size_t n = (size_t)j->nm;
	if (put(j, tag, (int32_t)(1 + 5 * n), e))
		return e->code;
	if (j->discard)
		return 0;
	if (fwrite(&t, sizeof t, 1, j->f) != 1 || fwrite(x, sizeof(double), n, j->f) != n ||
	    fwrite(y, sizeof(double), n, j->f) != n || fwrite(th, sizeof(double), n, j->f) != n ||
	    fwrite(vx, sizeof(double), n, j->f) != n || fwrite(vy, sizeof(double), n, j->f) != n)
		return sb_errf(e, SB_EIO, "%s: write failed: %s", j->path, strerror(errno));
	return 0;
}

int journal_sync(sb_journal *j, long *offset, sb_err *e)
{
	*offset = 0;
	if (j->discard)
		return 0;
	if (fflush(j->f) || fsync(fileno(j->f)))
		return sb_errf(e, SB_EIO, "%s: sync failed: %s", j->path, strerror(errno));
	*offset = ftell(j->f);
	return 0;
}

void journal_close(sb_journal *j)
{
	if (j->f)
		fclose(j->f);
	j->f = NULL;
}

int journal_reader_open(sb_jreader *r, const char *path, sb_err *e)
{
	char m[8];
	int32_t n32;
	r->f = fopen(path, "rb");
	if (!r->f)
		return sb_errf(e, SB_EIO, "%s: cannot open journal: %s", path, strerror(errno));
	if (fread(m, 1, 8, r->f) != 8 || memcmp(m, MAGIC, 8) || fread(&n32, 4, 1, r->f) != 1)
		return sb_errf(e, SB_EIO, "%s: not a shakebox journal", path);
	r->nm = n32;
	return 0;
}

int journal_next(sb_jreader *r, double *buf, long cap, int *count, sb_err *e)
{
	int32_t h[2];
	size_t got = fread(h, 4, 2, r->f);
	if (got == 0 && feof(r->f))
		return 0;
	if (got != 2)
		return -sb_errf(e, SB_EIO, "journal: truncated record header");
	if (h[0] < 1 || h[1] < 0 || h[1] > cap)
		return -sb_errf(e, SB_EIO, "journal: corrupt record (tag %d, count %d)", h[0], h[1]);
	if (fread(buf, sizeof(double), (size_t)h[1], r->f) != (size_t)h[1])
		return -sb_errf(e, SB_EIO, "journal: truncated record");
	*count = h[1];
	return h[0];
}

void journal_reader_close(sb_jreader *r)
{
	if (r->f)
		fclose(r->f);
	r->f = NULL;
}
