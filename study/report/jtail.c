/* jtail.c - the last record's time of a journal being written (see jtail.h). Only
 * record headers and each record's first double are read (pread, no stdio buffer to
 * go stale), so a long journal of snapshots costs a few bytes per record. */
#include "jtail.h"

#include <fcntl.h>
#include <stdint.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* the journal's header: magic + int32 nm (core/io/journal.c) */
enum { JT_HEAD = 12, JT_MAXTAG = 64 };
static const char MAGIC[8] = {'S', 'B', 'J', 'R', 'N', 'L', '0', '1'};

void jtail_init(jtail *j)
{
	j->offset = 0;
	j->ino = 0;
	j->t = -1;
}

int jtail_poll(jtail *j, const char *path)
{
	int fd = open(path, O_RDONLY | O_CLOEXEC);
	if (fd < 0) {
		jtail_init(j);
		return 0;
	}
	struct stat sb;
	if (fstat(fd, &sb) || sb.st_size < JT_HEAD) {
		close(fd);
		jtail_init(j);
		return 0;
	}
	long size = (long)sb.st_size;
	if (j->offset > size || j->ino != (unsigned long)sb.st_ino) /* truncated to a checkpoint, or a new attempt's journal */
		jtail_init(j);
	j->ino = (unsigned long)sb.st_ino;
	if (j->offset == 0) {
		char m[8];
		if (pread(fd, m, 8, 0) != 8 || memcmp(m, MAGIC, 8)) {
			close(fd);
			return 0;
		}
		j->offset = JT_HEAD;
	}
	for (;;) {
		int32_t h[2];
		double t;
		if (j->offset + 16 > size || pread(fd, h, 8, j->offset) != 8)
			break;
		if (h[0] < 1 || h[0] > JT_MAXTAG || h[1] < 1) {
			/* not a record header: the file was replaced under us; read it anew
			 * next time */
			jtail_init(j);
			break;
		}
		long end = j->offset + 8 + 8 * (long)h[1];
		if (end > size) /* being written */
			break;
		if (pread(fd, &t, 8, j->offset + 8) != 8)
			break;
		j->t = t;
		j->offset = end;
	}
	close(fd);
	return j->t >= 0;
}
