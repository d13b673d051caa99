/* h5mut.c - a run file (HDF5) changed on purpose, for `make fuzz` and the tests of the
 * readers of run files: a copy of IN written to OUT with the operations applied in
 * order. A tool, not what is tested: it trusts its input.
 *
 *   h5mut IN OUT [OP ...]
 *     --shape PATH D0,D1,...    PATH becomes a double dataset of that shape with nothing
 *                               written (contiguous storage, allocated late: the file
 *                               holds no byte of it)
 *     --set PATH INDEX VALUE    element INDEX (flat) of dataset PATH := VALUE (a number,
 *                               nan, inf or -inf)
 *     --attr OBJ NAME VALUE     attribute NAME of OBJ := the scalar double VALUE
 *     --attr-array OBJ NAME N   attribute NAME of OBJ := N doubles
 *     --attr-str OBJ NAME TEXT  attribute NAME of OBJ := the string TEXT
 *     --delete PATH             unlink PATH
 *     --flip PATH               one bit of the stored bytes of dataset PATH's data
 *                               flipped behind HDF5's back (in its first chunk), as a
 *                               failing disk would
 *     --elink PATH FILE         PATH becomes an external link to FILE:PATH
 *     --extern PATH FILE        PATH becomes a dataset of its shape (doubles) whose data
 *                               is kept in FILE (HDF5's external storage)
 *     --vds PATH FILE           PATH becomes a virtual dataset of FILE:PATH, its shape
 *     --flip-vds-name           the NUL after a virtual dataset's source file name "."
 *                               (in the global heap, which no checksum covers) changed
 *                               to 'x', behind HDF5's back
 *     --stale-digest            (anywhere) the attribute digest is left as it was;
 *                               without it every change through HDF5 is sealed again
 *                               (core/io/h5id.h), so that the readers' checks behind the
 *                               digest are what is tested
 *     --stale-seal              (anywhere) the file's seal (its user block) is left as
 *                               it was; without it the file is sealed again after the
 *                               last operation, bytes included (h5seal_write), as a
 *                               hostile hand would, so the checks behind it are tested
 *     --random SEED             one random change: a dataset's shape, type or values, an
 *                               attribute's type, shape or value, an object deleted or
 *                               turned into the other kind, a link to another dataset,
 *                               a dataset pointing out of the file (external link or
 *                               storage, virtual dataset: /dev/zero, nothing, itself),
 *                               or bytes (truncation, bit flips, a block overwritten);
 *                               what it did goes to stderr; the seal is renewed for
 *                               half of the seeds
 *     --random-structure SEED   one random change of the structure or the values made
 *                               through HDF5 (as --random, without changes of the bytes
 *                               or links out of the file), always sealed again: the
 *                               `resealed` family of `make fuzz` (tests/fuzz/families.sh)
 *     --random-link SEED FIFO OTHER
 *                               a dataset (mostly one a tool reads) made an external
 *                               link, a soft link (dangling, to a group, to another
 *                               dataset, to itself), external storage or a virtual
 *                               dataset, pointing at the FIFO, at the file OTHER, at
 *                               the file itself or at nothing; always sealed again: the
 *                               `links` family
 * Exit 0, or 2 when an operation could not be applied (the message on stderr). */
#define _GNU_SOURCE
#include <hdf5.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "h5id.h"
#include "h5seal.h"

static void die(const char *fmt, const char *a)
{
	fprintf(stderr, "h5mut: ");
	fprintf(stderr, fmt, a);
	fputc('\n', stderr);
	exit(2);
}

static int copy_file(const char *from, const char *to)
{
	FILE *in = fopen(from, "rb"), *out = in ? fopen(to, "wb") : NULL;
	char buf[65536];
	size_t n;
	int bad = !in || !out;
	while (!bad && (n = fread(buf, 1, sizeof buf, in)) > 0)
		bad = fwrite(buf, 1, n, out) != n;
	if (in)
		fclose(in);
	if (out && fclose(out))
		bad = 1;
	return bad ? -1 : 0;
}

static double value_of(const char *s)
{
	if (!strcmp(s, "nan"))
		return NAN;
	if (!strcmp(s, "inf"))
		return INFINITY;
	if (!strcmp(s, "-inf"))
		return -INFINITY;
	return strtod(s, NULL);
}

/* ---- randomness: SplitMix64 ---- */

static unsigned long long rs;
static unsigned long long rnd(void)
{
	unsigned long long z = (rs += 0x9e3779b97f4a7c15ULL);
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
	return z ^ (z >> 31);
}
static size_t below(size_t n)
{
	return n ? (size_t)(rnd() % n) : 0;
}

/* ---- the file's objects ---- */

#define MAXOBJ 4096
static char *dsets[MAXOBJ], *groups[MAXOBJ];
static int ndsets, ngroups;

static herr_t visit(hid_t g, const char *name, const H5L_info_t *info, void *data)
{
	(void)info;
	(void)data;
	hid_t o = H5Oopen(g, name, H5P_DEFAULT);
	if (o < 0)
		return 0;
	const H5I_type_t t = H5Iget_type(o);
	char path[1100];
	snprintf(path, sizeof path, "/%s", name);
	if (t == H5I_DATASET && ndsets < MAXOBJ)
		dsets[ndsets++] = strdup(path);
	else if (t == H5I_GROUP && ngroups < MAXOBJ)
		groups[ngroups++] = strdup(path);
	H5Oclose(o);
	return 0;
}

static void list_objects(hid_t f)
{
	groups[ngroups++] = strdup("/");
	H5Lvisit(f, H5_INDEX_NAME, H5_ITER_NATIVE, visit, NULL);
}

/* ---- operations ---- */

/* a dataset's values as doubles (NULL when they cannot be read), its element count */
static double *read_all(hid_t f, const char *path, hsize_t *n)
{
	hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
	if (d < 0)
		return NULL;
	hid_t sp = H5Dget_space(d);
	hssize_t np = H5Sget_simple_extent_npoints(sp);
	H5Sclose(sp);
	double *v = np >= 0 && np < 50000000 ? malloc(sizeof *v * (size_t)(np ? np : 1)) : NULL;
	if (v && np && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0) {
		free(v);
		v = NULL;
	}
	H5Dclose(d);
	*n = (hsize_t)(np > 0 ? np : 0);
	return v;
}

static int set_value(hid_t f, const char *path, hsize_t at, double x)
{
	hsize_t n;
	double *v = read_all(f, path, &n);
	if (!v || !n) {
		free(v);
		return -1;
	}
	v[at % n] = x;
	hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
	const int bad = d < 0 || H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0;
	if (d >= 0)
		H5Dclose(d);
	free(v);
	return bad ? -1 : 0;
}

/* PATH replaced by a dataset of type ty and shape dims (rank r; r < 0: a null
 * dataspace), chunked when chunk, written from vals (n doubles, converted) when given */
static int new_dataset(hid_t f, const char *path, hid_t ty, int r, const hsize_t *dims, int chunk, const double *vals,
		       hsize_t n)
{
	H5Ldelete(f, path, H5P_DEFAULT);
	hid_t sp = r < 0 ? H5Screate(H5S_NULL) : r == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(r, dims, NULL);
	if (sp < 0)
		return -1;
	hid_t pl = H5Pcreate(H5P_DATASET_CREATE), lc = H5Pcreate(H5P_LINK_CREATE);
	H5Pset_create_intermediate_group(lc, 1);
	if (chunk && r > 0) {
		hsize_t c[8];
		for (int k = 0; k < r; k++)
			c[k] = dims[k] ? (dims[k] < 16 ? dims[k] : 16) : 1;
		H5Pset_chunk(pl, r, c);
		if (chunk > 1)
			H5Pset_deflate(pl, 4);
	}
	hid_t d = H5Dcreate2(f, path, ty, sp, lc, pl, H5P_DEFAULT);
	int bad = d < 0;
	hssize_t np = H5Sget_simple_extent_npoints(sp);
	if (!bad && vals && np > 0 && (hsize_t)np <= n && H5Tget_class(ty) != H5T_STRING)
		H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, vals);
	if (d >= 0)
		H5Dclose(d);
	H5Pclose(pl);
	H5Pclose(lc);
	H5Sclose(sp);
	return bad ? -1 : 0;
}

static int parse_dims(const char *s, hsize_t *dims)
{
	int r = 0;
	for (const char *p = s; *p && r < 8;) {
		dims[r++] = strtoull(p, (char **)&p, 10);
		if (*p == ',')
			p++;
	}
	return r;
}

/* the attribute replaced by a scalar double, an array of n doubles (n < 0: a null
 * dataspace), an int64, or a string */
static int new_attr(hid_t f, const char *obj, const char *name, int kind, double x, long n, const char *str)
{
	hid_t o = H5Oopen(f, obj, H5P_DEFAULT);
	if (o < 0)
		return -1;
	if (H5Aexists(o, name) > 0)
		H5Adelete(o, name);
	hid_t sp, ty = H5Tcopy(kind == 2 ? H5T_NATIVE_LLONG : H5T_NATIVE_DOUBLE);
	if (kind == 1) {
		hsize_t d = (hsize_t)(n > 0 ? n : 1);
		sp = n < 0 ? H5Screate(H5S_NULL) : H5Screate_simple(1, &d, NULL);
	} else {
		sp = H5Screate(H5S_SCALAR);
	}
	if (kind == 3) {
		H5Tclose(ty);
		ty = H5Tcopy(H5T_C_S1);
		if (str)
			H5Tset_size(ty, strlen(str) + 1);
		else
			H5Tset_size(ty, H5T_VARIABLE);
	}
	hid_t a = H5Acreate2(o, name, ty, sp, H5P_DEFAULT, H5P_DEFAULT);
	int bad = a < 0;
	if (!bad) {
		if (kind == 1 && n > 0) {
			double *v = malloc(sizeof *v * (size_t)n);
			for (long i = 0; v && i < n; i++)
				v[i] = x;
			if (v)
				H5Awrite(a, H5T_NATIVE_DOUBLE, v);
			free(v);
		} else if (kind == 2) {
			long long i = (long long)n;
			H5Awrite(a, H5T_NATIVE_LLONG, &i);
		} else if (kind == 3) {
			const char *vs = str ? str : "variable";
			H5Awrite(a, ty, str ? (const void *)str : (const void *)&vs);
		} else if (kind == 0) {
			H5Awrite(a, H5T_NATIVE_DOUBLE, &x);
		}
		H5Aclose(a);
	}
	H5Tclose(ty);
	H5Sclose(sp);
	H5Oclose(o);
	return bad ? -1 : 0;
}

/* ---- random changes ---- */

static const double VALUES[] = {NAN, INFINITY, -INFINITY, -1, 0, 1, 2, 0.5, 1e308, -1e308, 9007199254740993.0,
				4294967296.0, 1e-310, 3};
#define NVALUES (sizeof VALUES / sizeof *VALUES)
static const hsize_t DIMS[] = {0, 1, 2, 3, 7, 1000, 2147483648ULL, 4294967296ULL, 4294967297ULL,
			       9223372036854775807ULL};
#define NDIMS (sizeof DIMS / sizeof *DIMS)
/* names the readers look for, whichever object the change lands on */
static const char *const ATTRS[] = {"risen", "waiting_time", "status", "status_time", "surface_height",
				    "intruder_settled_y", "intruder_radius", "cell", "x0", "periods_per_block",
				    "samples_before", "before_from", "before_to", "mean_force_before", "centre_y",
				    "frequency", "radius_ratio", "ramp", "duration", "exit_code", "steps", "particles",
				    "format", "stopped_by"};
#define NATTRS (sizeof ATTRS / sizeof *ATTRS)
/* ... and where they look for them (the tools, core/io/h5read.c's callers; lib/h5sum.c) */
static const struct {
	const char *obj, *name;
} READ_ATTRS[] = {
	{"/", "risen"}, {"/", "waiting_time"}, {"/", "status"}, {"/", "status_time"}, {"/", "surface_height"},
	{"/", "intruder_settled_y"}, {"/", "intruder_radius"}, {"/", "stopped_by"}, {"/", "exit_code"},
	{"/", "steps"}, {"/", "format"}, {"/ring", "samples_before"}, {"/ring", "before_from"},
	{"/ring", "before_to"}, {"/ring", "mean_force_before"}, {"/ring", "centre_y"},
	{"/observables/field", "cell"}, {"/observables/field", "x0"}, {"/observables/field", "periods_per_block"},
	{"/observables/flux", "surface_height"}, {"/parameters", "frequency"}, {"/parameters", "radius_ratio"},
	{"/parameters", "ramp"}, {"/parameters", "amplitude"}, {"/parameters", "duration"},
	{"/parameters", "ramp_hold"}, {"/parameters", "r_min"}, {"/parameters", "particles"},
};
#define NREAD_ATTRS (sizeof READ_ATTRS / sizeof *READ_ATTRS)

struct attr_pick {
	long k, want;
	char name[256];
};
static herr_t pick_attr(hid_t loc, const char *name, const H5A_info_t *ai, void *data)
{
	(void)loc;
	(void)ai;
	struct attr_pick *p = data;
	if (p->k++ == p->want)
		snprintf(p->name, sizeof p->name, "%s", name);
	return 0;
}

/* a dataset, three times in four one that a tool reads (the observables' values and
 * times, the intruder's trajectory): most of a run file is snapshots, walls and step
 * counts, read by none */
static const char *pick_dataset(void)
{
	int read[MAXOBJ], n = 0;
	for (int i = 0; i < ndsets; i++)
		if ((strstr(dsets[i], "/observables/") || strstr(dsets[i], "/particles/intruder/")) &&
		    !strstr(dsets[i], "/step"))
			read[n++] = i;
	if (n && below(4))
		return dsets[read[below((size_t)n)]];
	return ndsets ? dsets[below((size_t)ndsets)] : NULL;
}

/* an object whose attributes a tool reads, mostly: the root (the run's outcome), /ring,
 * the flux and field groups, /parameters; else any group or dataset */
static const char *pick_object(hid_t f, const char *ds)
{
	static const char *const READ[] = {"/", "/", "/", "/ring", "/observables/flux", "/observables/field",
					   "/parameters"};
	if (below(4)) {
		const char *o = READ[below(sizeof READ / sizeof *READ)];
		if (!strcmp(o, "/") || H5Lexists(f, o + 1, H5P_DEFAULT) > 0)
			return o;
	}
	return below(3) && ngroups ? groups[below((size_t)ngroups)] : ds ? ds : "/";
}

static int elsewhere(hid_t f, const char *path, const char *file, int kind);

static int random_structured(hid_t f, int inside)
{
	/* the changes that readers trusted most (values, attributes, shapes) more often;
	 * inside: none that points out of the file (op 9) */
	static const int OPS[] = {0, 0, 1, 2, 2, 3, 3, 3, 3, 4, 5, 6, 7, 7, 8, 8, 8, 9, 9};
	const char *ds = pick_dataset();
	const int op = OPS[below(sizeof OPS / sizeof *OPS - (inside ? 2 : 0))];
	if ((op <= 2 || op == 6 || op == 7 || op == 9) && !ds)
		return -1;
	switch (op) {
	case 0: { /* a dataset's shape */
		hsize_t n;
		double *v = read_all(f, ds, &n);
		hsize_t dims[4];
		const int r = (int)below(5) - (below(8) == 0);
		for (int k = 0; k < r; k++)
			dims[k] = below(3) ? DIMS[below(NDIMS)] : (n ? 1 + below((size_t)n) : 1);
		const int chunk = (int)below(3);
		fprintf(stderr, "shape %s rank %d (%llu, %llu, %llu, %llu) %s\n", ds, r, r > 0 ? (unsigned long long)dims[0] : 0ULL,
		       r > 1 ? (unsigned long long)dims[1] : 0ULL, r > 2 ? (unsigned long long)dims[2] : 0ULL,
		       r > 3 ? (unsigned long long)dims[3] : 0ULL, chunk == 2 ? "deflate" : chunk ? "chunked" : "contiguous");
		const int rc = new_dataset(f, ds, H5T_IEEE_F64LE, r, dims, chunk, below(2) ? v : NULL, n);
		free(v);
		return rc;
	}
	case 1: { /* a dataset's type */
		hsize_t n;
		double *v = read_all(f, ds, &n);
		hid_t d = H5Dopen2(f, ds, H5P_DEFAULT);
		hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
		hsize_t dims[8] = {0};
		const int r = sp >= 0 ? H5Sget_simple_extent_dims(sp, dims, NULL) : -1;
		if (sp >= 0)
			H5Sclose(sp);
		if (d >= 0)
			H5Dclose(d);
		if (r < 0) {
			free(v);
			return -1;
		}
		const int k = (int)below(7);
		hid_t ty = H5Tcopy(k == 0   ? H5T_NATIVE_SCHAR
				   : k == 1 ? H5T_NATIVE_UCHAR
				   : k == 2 ? H5T_NATIVE_INT
				   : k == 3 ? H5T_NATIVE_ULLONG
				   : k == 4 ? H5T_NATIVE_FLOAT
				   : k == 5 ? H5T_NATIVE_LLONG
					    : H5T_C_S1);
		if (k == 6)
			H5Tset_size(ty, 8);
		fprintf(stderr, "type %s -> %s\n", ds, (const char *[]){"int8", "uint8", "int32", "uint64", "float32", "int64",
							      "string"}[k]);
		const int rc = new_dataset(f, ds, ty, r, dims, (int)below(2), v, n);
		H5Tclose(ty);
		free(v);
		return rc;
	}
	case 2: { /* a value: NaN, Inf, huge */
		const double x = VALUES[below(NVALUES)];
		const hsize_t at = (hsize_t)rnd();
		fprintf(stderr, "set %s[%llu %% n] = %g\n", ds, (unsigned long long)at, x);
		return set_value(f, ds, at, x);
	}
	case 3: { /* an attribute: half of the time one that a reader reads, where it reads it */
		const char *obj = pick_object(f, ds);
		const int known = (int)below(2 * NREAD_ATTRS);
		if ((size_t)known < NREAD_ATTRS)
			obj = READ_ATTRS[known].obj;
		hid_t o = H5Oopen(f, obj, H5P_DEFAULT);
		struct attr_pick p = {0, 0, ""};
		if (o >= 0) {
			H5Aiterate2(o, H5_INDEX_NAME, H5_ITER_NATIVE, NULL, pick_attr, &p);
			p.want = p.k ? (long)below((size_t)p.k) : -1;
			p.k = 0;
			if (p.want >= 0)
				H5Aiterate2(o, H5_INDEX_NAME, H5_ITER_NATIVE, NULL, pick_attr, &p);
			H5Oclose(o);
		}
		const char *name = (size_t)known < NREAD_ATTRS ? READ_ATTRS[known].name
				   : p.name[0] && below(2) ? p.name : ATTRS[below(NATTRS)];
		const int kind = below(3) ? (int)below(5) : 1; /* an array, often */
		const double x = VALUES[below(NVALUES)];
		/* an array of a few values or of thousands (an attribute lives in its object's
		 * header: at most 64 KiB), or a null dataspace */
		const long n = below(4) == 0 ? -1 : (long)(below(2) ? 2 + below(4) : 1 + below(4000));
		static const char *const S[] = {"nan", "ok", "", "1e999", "0x10", "overlap", "none"};
		const char *str = S[below(sizeof S / sizeof *S)];
		if (kind == 4) {
			fprintf(stderr, "delete attribute %s@%s\n", obj, name);
			hid_t oo = H5Oopen(f, obj, H5P_DEFAULT);
			if (oo >= 0) {
				H5Adelete(oo, name);
				H5Oclose(oo);
			}
			return 0;
		}
		fprintf(stderr, "attribute %s@%s := %s (%g, n %ld, '%s')\n", obj, name,
		       (const char *[]){"double", "array", "int64", "string"}[kind], x, n, str);
		return new_attr(f, obj, name, kind, x, kind == 2 ? (long)(rnd() >> 1) : n,
				kind == 3 && below(3) ? str : kind == 3 ? NULL : str);
	}
	case 4: { /* an object deleted */
		const char *p = below(2) && ds ? ds : ngroups > 1 ? groups[1 + below((size_t)ngroups - 1)] : ds;
		if (!p)
			return -1;
		fprintf(stderr, "delete %s\n", p);
		return H5Ldelete(f, p, H5P_DEFAULT) < 0 ? -1 : 0;
	}
	case 5: { /* a group where a dataset was, or a dataset where a group was */
		if (ds && below(2)) {
			fprintf(stderr, "group in place of dataset %s\n", ds);
			H5Ldelete(f, ds, H5P_DEFAULT);
			hid_t g = H5Gcreate2(f, ds, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
			if (g < 0)
				return -1;
			H5Gclose(g);
			return 0;
		}
		if (ngroups < 2)
			return -1;
		const char *g = groups[1 + below((size_t)ngroups - 1)];
		fprintf(stderr, "dataset in place of group %s\n", g);
		const double one = 1;
		const hsize_t d1 = 1;
		return new_dataset(f, g, H5T_IEEE_F64LE, 1, &d1, 0, &one, 1);
	}
	case 8: { /* the series of one H5MD group alike (field ux, uy, count; flux phi, j_top,
		   * j_bot): their rows kept, each row 2^32 x ... values, so that the shapes
		   * agree with each other and with the time series and only the count wraps */
		hsize_t orig[8] = {0};
		const char *v = strstr(ds, "/value");
		hid_t d = v && !v[6] ? H5Dopen2(f, ds, H5P_DEFAULT) : -1;
		hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
		const int r = sp >= 0 ? H5Sget_simple_extent_dims(sp, orig, NULL) : -1;
		if (sp >= 0)
			H5Sclose(sp);
		if (d >= 0)
			H5Dclose(d);
		if (r < 2)
			return -1;
		char box[1100];
		snprintf(box, sizeof box, "%.*s", (int)(v - ds), ds); /* /observables/field/ux */
		char *slash = strrchr(box, '/');
		if (!slash || slash == box)
			return -1;
		*slash = 0; /* /observables/field */
		hsize_t dims[8];
		dims[0] = orig[0];
		for (int k = 1; k < r; k++)
			dims[k] = 4294967296ULL;
		if (r == 2 && orig[0] > 1) /* rows x ceil(2^64 / rows): wraps to fewer than rows */
			dims[1] = UINT64_MAX / orig[0] + 1;
		int n = 0;
		for (int i = 0; i < ndsets; i++) {
			const char *w = strstr(dsets[i], "/value");
			hsize_t o2[8] = {0};
			if (strncmp(dsets[i], box, strlen(box)) || dsets[i][strlen(box)] != '/' || !w || w[6])
				continue;
			hid_t d2 = H5Dopen2(f, dsets[i], H5P_DEFAULT);
			hid_t s2 = d2 >= 0 ? H5Dget_space(d2) : -1;
			const int r2 = s2 >= 0 ? H5Sget_simple_extent_dims(s2, o2, NULL) : -1;
			if (s2 >= 0)
				H5Sclose(s2);
			if (d2 >= 0)
				H5Dclose(d2);
			if (r2 == r && !memcmp(o2, orig, sizeof o2) && !new_dataset(f, dsets[i], H5T_IEEE_F64LE, r, dims,
											(int)below(2), NULL, 0))
				n++;
		}
		fprintf(stderr, "huge series of %s: %d of them (%llu rows of %llu ...)\n", box, n,
			(unsigned long long)orig[0], (unsigned long long)dims[1]);
		return n ? 0 : -1;
	}
	case 9: { /* a dataset pointing out of the file: an external link, external storage
		   * or a virtual dataset, at a device that never ends, at nothing, or at the
		   * file itself */
		static const char *const TO[] = {"/dev/zero", "/nonexistent/other.h5", "."};
		static const char *const HOW[] = {"external link", "external storage", "virtual dataset"};
		const int how = (int)below(3);
		const char *to = TO[below(3)];
		fprintf(stderr, "%s %s -> %s\n", HOW[how], ds, to);
		return elsewhere(f, ds, to, how);
	}
	case 6: { /* a hard link to another dataset (another shape) */
		const char *other = dsets[below((size_t)ndsets)];
		fprintf(stderr, "link %s -> %s\n", ds, other);
		H5Ldelete(f, ds, H5P_DEFAULT);
		return H5Lcreate_hard(f, other, f, ds, H5P_DEFAULT, H5P_DEFAULT) < 0 ? -1 : 0;
	}
	default: { /* an unwritten dataset of a huge shape, as a crafted file has: half of
		    * the time its rank and first dimension kept (the rows its time series
		    * says it has) and the others 2^32, whose product wraps to 0 in 64 bits */
		hsize_t dims[8] = {1, 4294967296ULL, 4294967296ULL}, orig[8] = {0};
		hid_t d = H5Dopen2(f, ds, H5P_DEFAULT);
		hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
		const int r0 = sp >= 0 ? H5Sget_simple_extent_dims(sp, orig, NULL) : -1;
		if (sp >= 0)
			H5Sclose(sp);
		if (d >= 0)
			H5Dclose(d);
		int r = 1 + (int)below(3);
		if (r0 >= 2 && below(2)) {
			r = r0;
			dims[0] = orig[0];
			for (int k = 1; k < r; k++)
				dims[k] = 4294967296ULL;
		} else if (r < 3) {
			dims[0] = DIMS[6 + below(4)];
		}
		fprintf(stderr, "huge %s rank %d (%llu, %llu, ...)\n", ds, r, (unsigned long long)dims[0],
			(unsigned long long)dims[1]);
		return new_dataset(f, ds, H5T_IEEE_F64LE, r, dims, (int)below(2), NULL, 0);
	}
	}
}

/* truncation, bit flips, a block overwritten: on the bytes, after HDF5 closed them */
static int random_bytes(const char *path)
{
	struct stat sb;
	if (stat(path, &sb) || sb.st_size < 16)
		return -1;
	const long size = (long)sb.st_size;
	const int op = (int)below(3);
	if (op == 0) {
		const long at = (long)below((size_t)size);
		fprintf(stderr, "truncate at %ld of %ld\n", at, size);
		return truncate(path, at);
	}
	FILE *fp = fopen(path, "r+b");
	if (!fp)
		return -1;
	const int n = op == 1 ? 1 + (int)below(16) : 1;
	for (int i = 0; i < n; i++) {
		const long at = (long)below((size_t)size);
		if (op == 1) {
			fseek(fp, at, SEEK_SET);
			int c = fgetc(fp);
			fseek(fp, at, SEEK_SET);
			fputc(c ^ (1 << below(8)), fp);
			fprintf(stderr, "flip a bit at %ld\n", at);
		} else {
			const int len = 8 + (int)below(57), c = below(2) ? 0xff : 0;
			fseek(fp, at, SEEK_SET);
			for (int k = 0; k < len && at + k < size; k++)
				fputc(c, fp);
			fprintf(stderr, "overwrite %d bytes at %ld with 0x%02x\n", len, at, c);
		}
	}
	return fclose(fp) ? -1 : 0;
}

/* The shape of dataset path (rank into *r), or -1. */
static int shape_of(hid_t f, const char *path, int *r, hsize_t *dims)
{
	hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
	hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
	*r = sp >= 0 ? H5Sget_simple_extent_dims(sp, dims, NULL) : -1;
	if (sp >= 0)
		H5Sclose(sp);
	if (d >= 0)
		H5Dclose(d);
	return *r < 1 ? -1 : 0;
}

/* PATH pointing into another file: an external link, external storage or a virtual
 * dataset (kind 0, 1, 2) of FILE */
static int elsewhere(hid_t f, const char *path, const char *file, int kind)
{
	hsize_t dims[8];
	int r;
	if (kind && shape_of(f, path, &r, dims))
		return -1;
	if (H5Ldelete(f, path, H5P_DEFAULT) < 0)
		return -1;
	if (kind == 0)
		return H5Lcreate_external(file, path, f, path, H5P_DEFAULT, H5P_DEFAULT) < 0 ? -1 : 0;
	hid_t sp = H5Screate_simple(r, dims, NULL), pl = H5Pcreate(H5P_DATASET_CREATE);
	int bad = 0;
	if (kind == 1) {
		bad = H5Pset_external(pl, file, 0, H5F_UNLIMITED) < 0;
	} else {
		hid_t src = H5Screate_simple(r, dims, NULL);
		bad = H5Pset_virtual(pl, sp, file, path, src) < 0;
		H5Sclose(src);
	}
	hid_t d = bad ? -1 : H5Dcreate2(f, path, H5T_IEEE_F64LE, sp, H5P_DEFAULT, pl, H5P_DEFAULT);
	bad = d < 0;
	if (d >= 0)
		H5Dclose(d);
	H5Pclose(pl);
	H5Sclose(sp);
	return bad ? -1 : 0;
}

/* One dataset pointing elsewhere (the links family): how and where drawn from the seed;
 * fifo and other are paths the driver made (a FIFO, another run file), file the file
 * itself. What it did goes to stderr. */
static int random_link(hid_t f, const char *file, const char *fifo, const char *other)
{
	const char *ds = pick_dataset();
	if (!ds)
		return -1;
	static const char *const HOW[] = {"external link", "soft link", "external storage", "virtual dataset"};
	const int how = (int)below(4);
	if (how == 1) {
		/* dangling, a group, another dataset, itself (a loop HDF5 stops) */
		const int k = (int)below(4);
		const char *to = k == 0 ? "/nonexistent/value" : k == 1 ? "/observables" : k == 2 ? dsets[below((size_t)ndsets)] : ds;
		fprintf(stderr, "soft link %s -> %s\n", ds, to);
		H5Ldelete(f, ds, H5P_DEFAULT);
		return H5Lcreate_soft(to, f, ds, H5P_DEFAULT, H5P_DEFAULT) < 0 ? -1 : 0;
	}
	const int w = (int)below(4);
	/* a virtual dataset names its own file "." */
	const char *to = w == 0 ? fifo : w == 1 ? other : w == 2 ? (how == 3 && below(2) ? "." : file) : "/nonexistent/other.h5";
	fprintf(stderr, "%s %s -> %s\n", HOW[how], ds, to);
	return elsewhere(f, ds, to, how == 0 ? 0 : how == 2 ? 1 : 2);
}

/* The first ".\0/" in the file's bytes (a virtual dataset's source file "." and the
 * start of its source dataset's path, in the global heap): its NUL becomes 'x'. */
static int flip_vds_name(const char *file)
{
	FILE *fp = fopen(file, "r+b");
	if (!fp)
		return -1;
	int a = 0, b = 0, c, found = 0;
	long at = 0;
	while (!found && (c = fgetc(fp)) != EOF) {
		found = a == '.' && b == 0 && c == '/';
		a = b;
		b = c;
		at++;
	}
	int bad = !found || fseek(fp, at - 2, SEEK_SET) || fputc('x', fp) == EOF;
	return fclose(fp) || bad ? -1 : 0;
}

/* A new digest over the attributes as they now are, unless asked not to. */
static int stale;
static void reseal(hid_t f)
{
	sb_err e = {0};
	if (!stale && H5Aexists(f, H5ID_DIGEST_ATTR) > 0 && h5id_seal(f, &e))
		die("%s", e.msg);
}

/* One bit of dataset path's first stored chunk (or its contiguous data), in the
 * middle of it, flipped in the file's bytes. */
static int flip(const char *file, const char *path)
{
	hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
	hid_t d = f >= 0 ? H5Dopen2(f, path, H5P_DEFAULT) : -1;
	haddr_t at = HADDR_UNDEF;
	hsize_t size = 0, base = 0;
	/* HDF5's addresses count from its superblock, after the user block (the seal) */
	hid_t cp = f >= 0 ? H5Fget_create_plist(f) : -1;
	if (cp < 0 || H5Pget_userblock(cp, &base) < 0)
		base = 0;
	if (cp >= 0)
		H5Pclose(cp);
	if (d >= 0) {
		hid_t pl = H5Dget_create_plist(d);
		if (H5Pget_layout(pl) == H5D_CHUNKED) {
			hsize_t off[8];
			unsigned mask;
			hid_t sp = H5Dget_space(d);
			if (H5Dget_chunk_info(d, sp, 0, off, &mask, &at, &size) < 0)
				at = HADDR_UNDEF;
			H5Sclose(sp);
		} else {
			at = H5Dget_offset(d);
			size = H5Dget_storage_size(d);
		}
		H5Pclose(pl);
		H5Dclose(d);
	}
	if (f >= 0)
		H5Fclose(f);
	if (at == HADDR_UNDEF || size == 0)
		return -1;
	FILE *fp = fopen(file, "r+b");
	if (!fp)
		return -1;
	const long pos = (long)(base + at + size / 2);
	int c = fseek(fp, pos, SEEK_SET) ? EOF : fgetc(fp);
	int bad = c == EOF || fseek(fp, pos, SEEK_SET) || fputc(c ^ 0x10, fp) == EOF;
	return fclose(fp) || bad ? -1 : 0;
}

int main(int argc, char **argv)
{
	if (argc < 3)
		die("%s", "usage: h5mut IN OUT [--shape PATH DIMS | --set PATH INDEX VALUE | --attr OBJ NAME VALUE | "
			  "--attr-array OBJ NAME N | --attr-str OBJ NAME TEXT | --delete PATH | --flip PATH | --elink PATH FILE | --extern PATH FILE | "
			  "--vds PATH FILE | --flip-vds-name | --stale-digest | --stale-seal | --random SEED | --random-structure SEED | --random-link SEED FIFO OTHER] ...");
	H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
	if (copy_file(argv[1], argv[2]))
		die("cannot copy to %s", argv[2]);
	int bytes = 0, stale_seal = 0;
	for (int i = 3; i < argc; i++) {
		if (!strcmp(argv[i], "--stale-digest"))
			stale = 1;
		if (!strcmp(argv[i], "--stale-seal"))
			stale_seal = 1;
	}
	for (int i = 3; i < argc; i++) {
		const char *op = argv[i];
		if (!strcmp(op, "--stale-digest") || !strcmp(op, "--stale-seal"))
			continue;
		if (!strcmp(op, "--flip-vds-name")) {
			if (flip_vds_name(argv[2]))
				die("%s: no virtual dataset's source name found", argv[2]);
			continue;
		}
		if (!strcmp(op, "--flip")) {
			if (i + 1 > argc - 1 || flip(argv[2], argv[i + 1]))
				die("cannot flip a bit of %s", i + 1 < argc ? argv[i + 1] : "?");
			i++;
			continue;
		}
		const int need = !strcmp(op, "--set") || !strcmp(op, "--attr") || !strcmp(op, "--attr-array") ||
						 !strcmp(op, "--attr-str")
					 ? 3
				 : !strcmp(op, "--shape") || !strcmp(op, "--elink") || !strcmp(op, "--extern") ||
						 !strcmp(op, "--vds")
					 ? 2
				 : !strcmp(op, "--delete") || !strcmp(op, "--random") ||
						 !strcmp(op, "--random-structure")
					 ? 1
				 : !strcmp(op, "--random-link") ? 3
								: -1;
		if (need < 0 || i + need > argc - 1)
			die("bad operation '%s'", op);
		if (!strcmp(op, "--random-structure") || !strcmp(op, "--random-link")) {
			rs = strtoull(argv[i + 1], NULL, 10);
			rnd();
			hid_t f = H5Fopen(argv[2], H5F_ACC_RDWR, H5P_DEFAULT);
			if (f < 0)
				die("cannot open %s", argv[2]);
			list_objects(f);
			int rc = -1;
			for (int tries = 0; tries < 8 && rc; tries++)
				rc = !strcmp(op, "--random-link") ? random_link(f, argv[2], argv[i + 2], argv[i + 3])
								  : random_structured(f, 1);
			reseal(f);
			H5Fclose(f);
			if (rc)
				die("%s: no change could be made", op);
			i += need;
			continue;
		}
		if (!strcmp(op, "--random")) {
			rs = strtoull(argv[i + 1], NULL, 10);
			rnd();
			if (below(2))
				stale_seal = 1;
			/* a third of the inputs change bytes, the rest the structure */
			if (below(3) == 0) {
				bytes = 1;
			} else {
				hid_t f = H5Fopen(argv[2], H5F_ACC_RDWR, H5P_DEFAULT);
				if (f < 0)
					die("cannot open %s", argv[2]);
				list_objects(f);
				int rc = -1;
				for (int tries = 0; tries < 8 && rc; tries++)
					rc = random_structured(f, 0);
				reseal(f);
				H5Fclose(f);
				if (below(4) == 0)
					bytes = 1; /* and bytes too */
			}
			if (bytes && random_bytes(argv[2]))
				die("cannot change the bytes of %s", argv[2]);
			i += need;
			continue;
		}
		hid_t f = H5Fopen(argv[2], H5F_ACC_RDWR, H5P_DEFAULT);
		if (f < 0)
			die("cannot open %s", argv[2]);
		int rc = 0;
		if (!strcmp(op, "--shape")) {
			hsize_t dims[8];
			const int r = parse_dims(argv[i + 2], dims);
			rc = new_dataset(f, argv[i + 1], H5T_IEEE_F64LE, r, dims, 0, NULL, 0);
		} else if (!strcmp(op, "--set")) {
			rc = set_value(f, argv[i + 1], strtoull(argv[i + 2], NULL, 10), value_of(argv[i + 3]));
		} else if (!strcmp(op, "--attr")) {
			rc = new_attr(f, argv[i + 1], argv[i + 2], 0, value_of(argv[i + 3]), 0, NULL);
		} else if (!strcmp(op, "--attr-str")) {
			rc = new_attr(f, argv[i + 1], argv[i + 2], 3, 0, 0, argv[i + 3]);
		} else if (!strcmp(op, "--attr-array")) {
			rc = new_attr(f, argv[i + 1], argv[i + 2], 1, 1.0, strtol(argv[i + 3], NULL, 10), NULL);
		} else if (!strcmp(op, "--delete")) {
			rc = H5Ldelete(f, argv[i + 1], H5P_DEFAULT) < 0 ? -1 : 0;
		} else if (!strcmp(op, "--elink") || !strcmp(op, "--extern") || !strcmp(op, "--vds")) {
			rc = elsewhere(f, argv[i + 1], argv[i + 2], !strcmp(op, "--elink") ? 0 : !strcmp(op, "--extern") ? 1 : 2);
		}
		if (!rc)
			reseal(f);
		H5Fclose(f);
		if (rc)
			die("%s failed", op);
		i += need;
	}
	/* a file of a user block (the engine's) is sealed anew; an older one has none */
	sb_err e = {0};
	char seal[17];
	if (!stale_seal && h5seal_check(argv[2], seal, &e)) {
		sb_err se = {0};
		h5seal_write(argv[2], &se); /* a file cut short of its superblock stays as it is */
	}
	return 0;
}
