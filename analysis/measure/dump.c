/* dump.c - LAMMPS text dumps, frame by frame (dump.h). */
#include "dump.h"

#include <errno.h>
#include "fsutil.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

int dump_open(dump_reader *rd, const char *path, sb_err *e)
{
	memset(rd, 0, sizeof *rd);
	snprintf(rd->path, sizeof rd->path, "%s", path);
	/* a regular file only (docs/inputs.md, "Files"): a FIFO would hang the read, a
	 * device never end */
	rd->f = fs_open_input(path, "position dump", 0, SB_EIO, e);
	return rd->f ? 0 : e->code;
}

void dump_close(dump_reader *rd)
{
	if (rd->f)
		fclose(rd->f);
	free(rd->buf);
	memset(rd, 0, sizeof *rd);
}

void dump_frame_free(dump_frame *fr)
{
	free(fr->id);
	free(fr->type);
	free(fr->x);
	free(fr->y);
	free(fr->r);
	memset(fr, 0, sizeof *fr);
}

/* The next line without its newline: 1, or 0 at the end of the file. */
static int next_line(dump_reader *rd)
{
	ssize_t k = getline(&rd->buf, &rd->cap, rd->f);
	if (k < 0)
		return 0;
	rd->line++;
	while (k > 0 && (rd->buf[k - 1] == '\n' || rd->buf[k - 1] == '\r'))
		rd->buf[--k] = 0;
	return 1;
}

static int need_line(dump_reader *rd, const char *what, sb_err *e)
{
	if (next_line(rd))
		return 0;
	return sb_errf(e, SB_EIO, "%s:%ld: the file ends inside a frame (expected %s)", rd->path, rd->line, what);
}

static int parse_long(dump_reader *rd, const char *s, long *v, sb_err *e)
{
	char *end;
	errno = 0;
	long x = strtol(s, &end, 10);
	while (*end == ' ' || *end == '\t')
		end++;
	if (end == s || *end || errno)
		return sb_errf(e, SB_EIO, "%s:%ld: expected an integer, got '%.60s'", rd->path, rd->line, s);
	*v = x;
	return 0;
}

/* The whitespace-separated fields of s (modified in place), at most max. */
static int split(char *s, char **w, int max)
{
	int n = 0;
	for (char *t = strtok(s, " \t"); t && n < max; t = strtok(NULL, " \t"))
		w[n++] = t;
	return n;
}

typedef struct row {
	long id;
	int type;
	double x, y, r;
} row;

static int cmp_row(const void *a, const void *b)
{
	long x = ((const row *)a)->id, y = ((const row *)b)->id;
	return (x > y) - (x < y);
}

/* Sorts the frame's rows by id (LAMMPS writes them in processor order unless the
 * dump says `dump_modify sort id`). */
static int sort_rows(dump_frame *fr, sb_err *e)
{
	int sorted = 1;
	for (long i = 1; i < fr->n && sorted; i++)
		sorted = fr->id[i - 1] < fr->id[i];
	if (sorted)
		return 0;
	row *t = malloc(sizeof *t * (size_t)fr->n);
	if (!t)
		return sb_errf(e, SB_ENOMEM, "out of memory sorting a dump frame");
	for (long i = 0; i < fr->n; i++)
		t[i] = (row){fr->id[i], fr->type[i], fr->x[i], fr->y[i], fr->r[i]};
	qsort(t, (size_t)fr->n, sizeof *t, cmp_row);
	for (long i = 0; i < fr->n; i++) {
		fr->id[i] = t[i].id;
		fr->type[i] = t[i].type;
		fr->x[i] = t[i].x;
		fr->y[i] = t[i].y;
		fr->r[i] = t[i].r;
	}
	free(t);
	return 0;
}

static int grow(dump_frame *fr, long n, sb_err *e)
{
	if (n <= fr->cap)
		return 0;
	long *id = realloc(fr->id, sizeof *id * (size_t)n);
	if (id)
		fr->id = id;
	int *ty = realloc(fr->type, sizeof *ty * (size_t)n);
	if (ty)
		fr->type = ty;
	double *x = realloc(fr->x, sizeof *x * (size_t)n);
	if (x)
		fr->x = x;
	double *y = realloc(fr->y, sizeof *y * (size_t)n);
	if (y)
		fr->y = y;
	double *r = realloc(fr->r, sizeof *r * (size_t)n);
	if (r)
		fr->r = r;
	if (!id || !ty || !x || !y || !r)
		return sb_errf(e, SB_ENOMEM, "out of memory for a dump frame of %ld atoms", n);
	fr->cap = n;
	return 0;
}

int dump_next(dump_reader *rd, dump_frame *fr, sb_err *e)
{
	/* ITEM: TIMESTEP, after any other ITEM sections (TIME, UNITS) and blank lines */
	for (;;) {
		if (!next_line(rd))
			return 0;
		if (!strcmp(rd->buf, "ITEM: TIMESTEP"))
			break;
		if (!strncmp(rd->buf, "ITEM: TIME", 10) || !strncmp(rd->buf, "ITEM: UNITS", 11)) {
			if (need_line(rd, "the value of an ITEM", e))
				return -1;
			continue;
		}
		if (rd->buf[strspn(rd->buf, " \t")])
			return sb_errf(e, SB_EIO, "%s:%ld: expected 'ITEM: TIMESTEP', got '%.60s'", rd->path, rd->line,
				       rd->buf),
			       -1;
	}
	if (need_line(rd, "the timestep", e) || parse_long(rd, rd->buf, &fr->step, e))
		return -1;
	if (need_line(rd, "ITEM: NUMBER OF ATOMS", e))
		return -1;
	if (strcmp(rd->buf, "ITEM: NUMBER OF ATOMS"))
		return sb_errf(e, SB_EIO, "%s:%ld: expected 'ITEM: NUMBER OF ATOMS', got '%.60s'", rd->path, rd->line,
			       rd->buf),
		       -1;
	long n = 0;
	if (need_line(rd, "the number of atoms", e) || parse_long(rd, rd->buf, &n, e))
		return -1;
	if (n < 0 || n > 100000000)
		return sb_errf(e, SB_EIO, "%s:%ld: %ld atoms", rd->path, rd->line, n), -1;
	if (need_line(rd, "ITEM: BOX BOUNDS", e))
		return -1;
	if (strncmp(rd->buf, "ITEM: BOX BOUNDS", 16))
		return sb_errf(e, SB_EIO, "%s:%ld: expected 'ITEM: BOX BOUNDS', got '%.60s'", rd->path, rd->line, rd->buf),
		       -1;
	for (int k = 0; k < 3; k++) /* xlo xhi, ylo yhi, zlo zhi (always three lines, also in 2D) */
		if (need_line(rd, "a box bounds line", e))
			return -1;
	if (need_line(rd, "ITEM: ATOMS", e))
		return -1;
	if (strncmp(rd->buf, "ITEM: ATOMS", 11))
		return sb_errf(e, SB_EIO, "%s:%ld: expected 'ITEM: ATOMS', got '%.60s'", rd->path, rd->line, rd->buf), -1;
	enum { MAXC = 64 };
	char *w[MAXC];
	int nc = split(rd->buf + 11, w, MAXC);
	int cid = -1, cty = -1, cx = -1, cy = -1, cr = -1;
	for (int c = 0; c < nc; c++) {
		if (!strcmp(w[c], "id"))
			cid = c;
		else if (!strcmp(w[c], "type"))
			cty = c;
		else if (!strcmp(w[c], "x"))
			cx = c;
		else if (!strcmp(w[c], "y"))
			cy = c;
		else if (!strcmp(w[c], "radius"))
			cr = c;
	}
	if (cid < 0 || cty < 0 || cx < 0 || cy < 0)
		return sb_errf(e, SB_EIO, "%s:%ld: the ATOMS columns need id, type, x and y (unwrapped or scaled "
				  "coordinates are not read)",
			       rd->path, rd->line),
		       -1;
	if (grow(fr, n, e))
		return -1;
	fr->n = n;
	fr->has_r = cr >= 0;
	for (long i = 0; i < n; i++) {
		if (need_line(rd, "an atom line", e))
			return -1;
		char *v[MAXC];
		int k = split(rd->buf, v, MAXC);
		if (k != nc)
			return sb_errf(e, SB_EIO, "%s:%ld: %d values for %d columns", rd->path, rd->line, k, nc), -1;
		long id = 0, ty = 0;
		if (parse_long(rd, v[cid], &id, e) || parse_long(rd, v[cty], &ty, e))
			return -1;
		if (ty < 0 || ty > 1000000)
			return sb_errf(e, SB_EIO, "%s:%ld: atom type %ld", rd->path, rd->line, ty), -1;
		double num[3] = {0, 0, NAN};
		const int col[3] = {cx, cy, cr};
		for (int q = 0; q < 3; q++) {
			if (col[q] < 0)
				continue;
			char *end;
			num[q] = strtod(v[col[q]], &end);
			if (end == v[col[q]] || *end || !isfinite(num[q]))
				return sb_errf(e, SB_EIO, "%s:%ld: expected a finite number, got '%.60s'", rd->path, rd->line,
					       v[col[q]]),
				       -1;
		}
		fr->id[i] = id;
		fr->type[i] = (int)ty;
		fr->x[i] = num[0];
		fr->y[i] = num[1];
		fr->r[i] = num[2];
	}
	if (sort_rows(fr, e))
		return -1;
	for (long i = 1; i < n; i++)
		if (fr->id[i] == fr->id[i - 1])
			return sb_errf(e, SB_EIO, "%s: the frame of step %ld has atom id %ld twice", rd->path, fr->step,
				       fr->id[i]),
			       -1;
	return 1;
}
