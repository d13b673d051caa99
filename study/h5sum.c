/* h5sum.c - a run's results from its HDF5 file, column by column as results.c says
 * where each lives. */
#include "h5sum.h"

#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int attr_exists(hid_t obj, const char *name)
{
	return H5Aexists(obj, name) > 0;
}

static double get_double(hid_t obj, const char *name, int *bad)
{
	double v = 0;
	if (!attr_exists(obj, name))
		return 0;
	hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
	if (a < 0 || H5Aread(a, H5T_NATIVE_DOUBLE, &v) < 0)
		*bad = 1;
	if (a >= 0)
		H5Aclose(a);
	return v;
}

static long get_long(hid_t obj, const char *name, int *bad)
{
	long long v = 0;
	if (!attr_exists(obj, name))
		return 0;
	hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
	if (a < 0 || H5Aread(a, H5T_NATIVE_LLONG, &v) < 0)
		*bad = 1;
	if (a >= 0)
		H5Aclose(a);
	return (long)v;
}

/* Fixed-length strings as the engine writes them; variable-length ones too, for
 * files written by other tools. */
static void get_str(hid_t obj, const char *name, char *out, size_t len, int *bad)
{
	out[0] = 0;
	if (!attr_exists(obj, name))
		return;
	hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
	hid_t ft = a >= 0 ? H5Aget_type(a) : -1;
	if (ft < 0 || H5Tget_class(ft) != H5T_STRING) {
		*bad = 1;
	} else if (H5Tis_variable_str(ft) > 0) {
		hid_t mt = H5Tcopy(H5T_C_S1);
		H5Tset_size(mt, H5T_VARIABLE);
		char *p = NULL;
		if (H5Aread(a, mt, &p) >= 0 && p) {
			snprintf(out, len, "%s", p);
			H5free_memory(p);
		} else {
			*bad = 1;
		}
		H5Tclose(mt);
	} else {
		size_t sz = H5Tget_size(ft);
		char *buf = calloc(sz + 1, 1);
		hid_t mt = H5Tcopy(H5T_C_S1);
		H5Tset_size(mt, sz);
		if (buf && H5Aread(a, mt, buf) >= 0)
			snprintf(out, len, "%s", buf);
		else
			*bad = 1;
		H5Tclose(mt);
		free(buf);
	}
	if (ft >= 0)
		H5Tclose(ft);
	if (a >= 0)
		H5Aclose(a);
}

/* Rows of a dataset (its first dimension). */
static long long dataset_rows(hid_t f, const char *path, int *has, int *bad)
{
	if (H5Lexists(f, path, H5P_DEFAULT) <= 0) /* parents are checked by the caller */
		return 0;
	hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
	hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
	hsize_t dims[8] = {0};
	int nd = sp >= 0 ? H5Sget_simple_extent_ndims(sp) : -1;
	if (nd < 1 || nd > 8 || H5Sget_simple_extent_dims(sp, dims, NULL) < 0)
		*bad = 1;
	else
		*has = 1;
	if (sp >= 0)
		H5Sclose(sp);
	if (d >= 0)
		H5Dclose(d);
	return (long long)dims[0];
}

/* Does every group along path exist? (H5Lexists fails on a missing parent.) */
static int path_exists(hid_t f, const char *path)
{
	char buf[256];
	snprintf(buf, sizeof buf, "%s", path);
	for (char *p = buf + 1;; p++) {
		char c = *p;
		if (c == '/' || c == 0) {
			*p = 0;
			if (H5Lexists(f, buf, H5P_DEFAULT) <= 0)
				return 0;
			*p = c;
		}
		if (!c)
			return 1;
	}
}

static void read_column(hid_t f, const rcol *c, h5val *v, int *bad)
{
	char obj[256];
	const char *at = strchr(c->where, '@'), *rows = strstr(c->where, "#rows");
	if (rows) {
		snprintf(obj, sizeof obj, "%.*s", (int)(rows - c->where), c->where);
		if (path_exists(f, obj))
			v->i = dataset_rows(f, obj, &v->has, bad);
		return;
	}
	if (!at)
		return;
	snprintf(obj, sizeof obj, "%.*s", (int)(at - c->where), c->where);
	hid_t o = f;
	if (obj[0]) {
		if (!path_exists(f, obj))
			return;
		o = H5Oopen(f, obj, H5P_DEFAULT);
		if (o < 0) {
			*bad = 1;
			return;
		}
	}
	const char *name = at + 1;
	if (attr_exists(o, name)) {
		v->has = 1;
		if (c->type == RT_TEXT)
			get_str(o, name, v->s, sizeof v->s, bad);
		else if (c->type == RT_INT)
			v->i = get_long(o, name, bad);
		else
			v->d = get_double(o, name, bad);
	}
	if (o != f)
		H5Oclose(o);
}

int h5sum_read(const char *path, h5sum *s, sb_err *e)
{
	memset(s, 0, sizeof *s);
	size_t n;
	const rcol *t = results_table(&n);
	if (n > H5SUM_MAX)
		return sb_errf(e, SB_ENOMEM, "results table larger than H5SUM_MAX");
	H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* errors are returned, not printed */
	hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
	if (f < 0)
		return sb_errf(e, SB_EIO, "%s: cannot open HDF5 file", path);
	int bad = 0;
	for (size_t i = 0; i < n; i++)
		if (!(t[i].flags & RF_DERIVED))
			read_column(f, &t[i], &s->v[i], &bad);
	/* the scene's parameters are attributes of /parameters (H5MD) */
	if (H5Lexists(f, "parameters", H5P_DEFAULT) > 0) {
		hid_t g = H5Gopen2(f, "parameters", H5P_DEFAULT);
		get_str(g, "particles", s->particles, sizeof s->particles, &bad);
		H5Gclose(g);
	}
	H5Fclose(f);
	if (bad || !h5sum_text(s, "status")[0])
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
