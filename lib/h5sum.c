/* h5sum.c - a run's results from its HDF5 file, column by column as results.c says
 * where each lives. */
#include "h5sum.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "h5id.h"
#include "h5read.h"
#include "runfile.h"
#include "runvals.h"

/* One column: an attribute (OBJ@NAME) or a dataset's rows (PATH#rows). An attribute
 * or dataset that is there but not what the column needs (an array where one value
 * belongs, a string where a number does, a shape the file cannot hold) makes the file
 * unreadable, through the same checked reads as the analysis tools' (core/io/h5read.h). */
static void read_column(hid_t f, const rcol *c, h5val *v, int *bad, sb_err *e)
{
	char obj[256];
	const char *at = strchr(c->where, '@'), *rows = strstr(c->where, "#rows");
	if (rows) {
		snprintf(obj, sizeof obj, "%.*s", (int)(rows - c->where), c->where);
		if (!h5r_exists(f, obj))
			return;
		int rank;
		size_t dims[8], n;
		sb_err se = {0};
		if (h5r_shape(f, obj, &rank, dims, &n, &se) || rank < 1 || dims[0] > LLONG_MAX) {
			if (!*bad)
				sb_errf(e, SB_EIO, "%s", se.code ? se.msg : "a dataset of rank 0 where rows belong");
			*bad = 1;
			return;
		}
		v->i = (long long)dims[0];
		v->has = 1;
		return;
	}
	if (!at)
		return;
	snprintf(obj, sizeof obj, "%.*s", (int)(at - c->where), c->where);
	if (!obj[0])
		snprintf(obj, sizeof obj, "/");
	else if (!h5r_exists(f, obj))
		return;
	const char *name = at + 1;
	int rc;
	if (c->type == RT_TEXT)
		rc = h5r_attr_str(f, obj, name, v->s, sizeof v->s);
	else if (c->type == RT_INT)
		rc = h5r_attr_int(f, obj, name, &v->i);
	else
		rc = h5r_attr_num(f, obj, name, &v->d);
	v->has = rc == 0;
	if (rc < 0) {
		if (!*bad)
			sb_errf(e, SB_EIO, "%s@%s: not one %s", obj, name,
				c->type == RT_TEXT ? "string" : c->type == RT_INT ? "integer" : "number");
		*bad = 1;
	} else if (!rc && c->type == RT_REAL && !isfinite(v->d)) {
		/* the engine writes no NaN or Inf (docs/scene.md, "Exit codes"): a waiting time of
		 * Inf would enter a median as a time (docs/inputs.md, "Run files") */
		if (!*bad)
			sb_errf(e, SB_EIO, "%s@%s = %g: not a finite number", obj, name, v->d);
		*bad = 1;
	}
}

int h5sum_read(const char *path, const char *want_id, h5sum *s, sb_err *e)
{
	return h5sum_read_sealed(path, want_id, NULL, s, e);
}

int h5sum_read_sealed(const char *path, const char *want_id, const char *want_seal, h5sum *s, sb_err *e)
{
	memset(s, 0, sizeof *s);
	size_t n;
	const rcol *t = results_table(&n);
	if (n > H5SUM_MAX)
		return sb_errf(e, SB_ENOMEM, "results table larger than H5SUM_MAX");
	hid_t f;
	sb_err oe = {0};
	char seal[17];
	/* a FIFO is refused before the open could wait for a writer, changed bytes before
	 * HDF5 parses them */
	if (h5r_open_sealed(path, want_seal, &f, seal, &oe))
		return sb_errf(e, oe.code, "%s", oe.msg);
	/* nothing of a file is believed before it is known to be the run it claims to be */
	if (h5id_check(f, path, want_id, &s->unsealed, &oe)) {
		h5r_close(f);
		return sb_errf(e, oe.code, "%s", oe.msg);
	}
	int bad = 0;
	sb_err why = {0};
	for (size_t i = 0; i < n; i++)
		if (!strcmp(t[i].where, RESULTS_SEAL)) {
			snprintf(s->v[i].s, sizeof s->v[i].s, "%s", seal);
			s->v[i].has = seal[0] != 0;
		} else if (!strcmp(t[i].where, RESULTS_ROWSEAL)) {
			s->v[i].has = 0; /* the database's, written after the row (rowseal.h) */
		} else if (!(t[i].flags & RF_DERIVED)) {
			read_column(f, &t[i], &s->v[i], &bad, &why);
		}
	/* values the engine cannot have written: a waiting time beyond the run's end */
	sb_err ve = {0};
	if (!bad && runvals_check(f, path, &ve)) {
		h5r_close(f);
		return sb_errf(e, ve.code, "%s", ve.msg);
	}
	/* the scene's parameters are attributes of /parameters (H5MD) */
	if (h5r_exists(f, RUNFILE_PARAMS) && h5r_attr_str(f, RUNFILE_PARAMS, "particles", s->particles,
							   sizeof s->particles) < 0) {
		if (!bad)
			sb_errf(&why, SB_EIO, "/parameters@particles: not one string");
		bad = 1;
	}
	/* and every byte of its data is what was written (Fletcher32) */
	if (!bad && h5r_verify(f, &why))
		bad = 1;
	h5r_close(f);
	if (bad)
		return sb_errf(e, SB_EIO, "%s: not a complete shakebox run file (%s)", path, why.msg);
	if (!h5sum_text(s, "status")[0])
		return sb_errf(e, SB_EIO, "%s: not a complete shakebox run file (missing or unreadable status)", path);
	return 0;
}

const char *h5sum_text(const h5sum *s, const char *name)
{
	int k = results_find(name);
	return k >= 0 && s->v[k].has ? s->v[k].s : "";
}

double h5sum_real(const h5sum *s, const char *name)
{
	int k = results_find(name);
	return k >= 0 && s->v[k].has ? s->v[k].d : 0;
}

long h5sum_int(const h5sum *s, const char *name)
{
	int k = results_find(name);
	return k >= 0 && s->v[k].has ? (long)s->v[k].i : 0;
}
