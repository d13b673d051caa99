/* h5md.c - HDF5 writing in the H5MD 1.1 conventions (see h5md.h). */
#include "h5md.h"
#include "h5seal.h"

#include <stdio.h>
#include <string.h>

/* Rows below this many bytes stay contiguous: chunking and compressing a few
 * hundred doubles costs more than it saves. */
#define BIG_BYTES 4096

void h5w_init(void)
{
	/* HDF5 1.10 frees a file's structures when H5Fclose fails (a full disk while it
	 * flushes) but keeps the id, and its exit handler then closes that id a second
	 * time: a segfault in H5F__close_cb at exit, which the study driver would take for
	 * a killed engine (exit 2 is what an I/O fault must give: docs/scene.md, "Exit codes").
	 * Without the handler nothing touches the stale id; every file is closed by its
	 * writer anyway. Only effective before the library's first use, hence called
	 * first (a second call, or one after some other use, fails harmlessly). The flaw
	 * is H5F__dest's, known as CVE-2020-10812 and mended in later HDF5 releases; the
	 * 1.10 of Debian 12 has it. */
	H5dont_atexit();
}

/* What HDF5 said at the innermost failed call, for the message of a failed write: the
 * system's word when it quotes one (a failed write's description holds "error message
 * = 'No space left on device'" among time, file descriptor and buffer), else its
 * first line. */
static herr_t innermost(unsigned n, const H5E_error2_t *err, void *data)
{
	if (n == 0 && err->desc)
		snprintf(data, 1024, "%s", err->desc);
	return 0;
}

void h5w_last_error(char *buf, size_t len)
{
	char d[1024] = "";
	buf[0] = 0;
	if (H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, innermost, d) < 0 || !d[0])
		return;
	static const char key[] = "error message = '";
	const char *m = strstr(d, key), *q = m ? strchr(m + sizeof key - 1, '\'') : NULL;
	if (q)
		snprintf(buf, len, "%.*s", (int)(q - m - (sizeof key - 1)), m + sizeof key - 1);
	else
		snprintf(buf, len, "%.*s", (int)strcspn(d, "\n"), d);
}

void h5w_fail(h5w *h)
{
	if (!h->bad)
		h5w_last_error(h->why, sizeof h->why);
	h->bad = 1;
}

int h5w_create(h5w *h, const char *path, int deflate_level)
{
	memset(h, 0, sizeof *h);
	h->level = deflate_level;
	hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
	H5Pset_obj_track_times(fcpl, 0);
	/* room for the seal h5seal_write writes once the file is closed (core/io/h5seal.h) */
	H5Pset_userblock(fcpl, H5SEAL_BYTES);
	/* the root lists h5md first, as readers that take the first group expect */
	H5Pset_link_creation_order(fcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED);
	h->gcpl = H5Pcreate(H5P_GROUP_CREATE);
	H5Pset_obj_track_times(h->gcpl, 0);
	h->ogcpl = H5Pcreate(H5P_GROUP_CREATE);
	H5Pset_obj_track_times(h->ogcpl, 0);
	H5Pset_link_creation_order(h->ogcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED);
	/* the 1.10 format, which bed_xyz (a virtual dataset) requires of readers anyway:
	 * its object headers carry HDF5's own metadata checksums, and a one-chunk dataset
	 * costs no chunk B-tree (chunking every dataset for Fletcher32 with the 1.8
	 * format's B-trees made a small run's file 14 % larger; with these, 15 % smaller
	 * than before) */
	hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
	H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_V110);
	h->file = H5Fcreate(path, H5F_ACC_TRUNC, fcpl, fapl);
	H5Pclose(fapl);
	H5Pclose(fcpl);
	if (h->file < 0) {
		H5Pclose(h->gcpl);
		H5Pclose(h->ogcpl);
		return -1;
	}
	return 0;
}

int h5w_close(h5w *h)
{
	H5Pclose(h->gcpl);
	H5Pclose(h->ogcpl);
	if (H5Fclose(h->file) < 0)
		h5w_fail(h);
	return h->bad ? -1 : 0;
}

static void attr_write(h5w *h, hid_t obj, const char *name, hid_t ftype, hid_t mtype, hid_t sp, const void *v)
{
	hid_t a = H5Acreate2(obj, name, ftype, sp, H5P_DEFAULT, H5P_DEFAULT);
	if (a < 0 || H5Awrite(a, mtype, v) < 0)
		h5w_fail(h);
	if (a >= 0 && H5Aclose(a) < 0)
		h5w_fail(h);
	H5Sclose(sp);
}

void h5w_attr_double(h5w *h, hid_t obj, const char *name, double v)
{
	attr_write(h, obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, H5Screate(H5S_SCALAR), &v);
}

void h5w_attr_long(h5w *h, hid_t obj, const char *name, long v)
{
	long long x = v;
	attr_write(h, obj, name, H5T_STD_I64LE, H5T_NATIVE_LLONG, H5Screate(H5S_SCALAR), &x);
}

void h5w_attr_ints(h5w *h, hid_t obj, const char *name, const int *v, int n)
{
	hsize_t d = (hsize_t)n;
	attr_write(h, obj, name, H5T_STD_I32LE, H5T_NATIVE_INT, H5Screate_simple(1, &d, NULL), v);
}

void h5w_attr_str(h5w *h, hid_t obj, const char *name, const char *v)
{
	hid_t t = H5Tcopy(H5T_C_S1);
	H5Tset_size(t, strlen(v) + 1);
	H5Tset_strpad(t, H5T_STR_NULLTERM);
	attr_write(h, obj, name, t, t, H5Screate(H5S_SCALAR), v);
	H5Tclose(t);
}

void h5w_attr_strs(h5w *h, hid_t obj, const char *name, const char *const *v, int n)
{
	size_t w = 1;
	for (int i = 0; i < n; i++)
		w = strlen(v[i]) + 1 > w ? strlen(v[i]) + 1 : w;
	char buf[8][32];
	if (n > 8 || w > sizeof buf[0]) {
		h5w_fail(h);
		return;
	}
	memset(buf, 0, sizeof buf);
	for (int i = 0; i < n; i++)
		memcpy(buf[i], v[i], strlen(v[i]));
	char packed[8 * 32];
	for (int i = 0; i < n; i++)
		memcpy(packed + (size_t)i * w, buf[i], w);
	hid_t t = H5Tcopy(H5T_C_S1);
	H5Tset_size(t, w);
	H5Tset_strpad(t, H5T_STR_NULLTERM);
	hsize_t d = (hsize_t)n;
	attr_write(h, obj, name, t, t, H5Screate_simple(1, &d, NULL), packed);
	H5Tclose(t);
}

hid_t h5w_group(h5w *h, hid_t loc, const char *name, int ordered)
{
	hid_t g = H5Gcreate2(loc, name, H5P_DEFAULT, ordered ? h->ogcpl : h->gcpl, H5P_DEFAULT);
	if (g < 0)
		h5w_fail(h);
	return g;
}

hid_t h5w_group_get(h5w *h, hid_t loc, const char *name)
{
	if (H5Lexists(loc, name, H5P_DEFAULT) > 0)
		return H5Gopen2(loc, name, H5P_DEFAULT);
	return h5w_group(h, loc, name, 0);
}

/* The creation properties of a dataset of this shape: every one that holds data is
 * chunked, for the Fletcher32 checksum HDF5 keeps per chunk and verifies on every
 * read (a flipped bit in a finished file is an error, not a changed statistic;
 * docs/inputs.md, "Run files"). Large ones are chunked by rows (one first-dimension
 * index at a time, the unit readers slice by) and, when a level is set, shuffled and
 * deflated; small ones are one chunk. */
static hid_t dcpl_for(const h5w *h, int rank, const hsize_t *dims, size_t elem)
{
	hid_t p = H5Pcreate(H5P_DATASET_CREATE);
	H5Pset_obj_track_times(p, 0);
	hsize_t row = elem, total = dims[0];
	for (int r = 1; r < rank; r++) {
		row *= dims[r];
		total *= dims[r];
	}
	if (dims[0] > 0 && total * elem >= BIG_BYTES) {
		hsize_t chunk[4];
		chunk[0] = 1;
		for (int r = 1; r < rank; r++)
			chunk[r] = dims[r] ? dims[r] : 1;
		/* short rows: gather several into one chunk of ~16 KiB */
		if (row < 16384) {
			hsize_t k = 16384 / (row ? row : 1);
			chunk[0] = k < dims[0] ? k : dims[0];
		}
		H5Pset_chunk(p, rank, chunk);
		if (h->level > 0) {
			H5Pset_shuffle(p);
			H5Pset_deflate(p, (unsigned)h->level);
		}
	} else if (total > 0) {
		hsize_t chunk[4];
		for (int r = 0; r < rank; r++)
			chunk[r] = dims[r];
		H5Pset_chunk(p, rank, chunk);
	}
	/* last in the pipeline: the checksum is of the bytes stored */
	if (total > 0)
		H5Pset_fletcher32(p);
	return p;
}

void h5w_attr_vstr(h5w *h, hid_t obj, const char *name, const char *v)
{
	hid_t t = H5Tcopy(H5T_C_S1);
	H5Tset_size(t, H5T_VARIABLE);
	H5Tset_cset(t, H5T_CSET_ASCII);
	attr_write(h, obj, name, t, t, H5Screate(H5S_SCALAR), &v);
	H5Tclose(t);
}

/* Units are variable-length ASCII strings, as H5MD's units module has them (h5py reads
 * them as str, as readers in Python - MDAnalysis - compare them). */
void h5w_attr_unit(h5w *h, hid_t obj, const char *unit)
{
	if (!unit || obj < 0)
		return;
	h5w_attr_vstr(h, obj, "unit", unit);
}

static void unit_attr(h5w *h, hid_t d, const char *unit) { h5w_attr_unit(h, d, unit); }

void h5w_dset(h5w *h, hid_t loc, const char *name, int rank, const hsize_t *dims, const double *data,
	      const char *unit)
{
	hid_t sp = H5Screate_simple(rank, dims, NULL);
	hid_t p = dcpl_for(h, rank, dims, sizeof(double));
	hid_t d = H5Dcreate2(loc, name, H5T_IEEE_F64LE, sp, H5P_DEFAULT, p, H5P_DEFAULT);
	hsize_t total = 1;
	for (int r = 0; r < rank; r++)
		total *= dims[r];
	if (d < 0 || (total > 0 && H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0))
		h5w_fail(h);
	unit_attr(h, d, unit);
	h5w_close_obj(h, d);
	H5Pclose(p);
	H5Sclose(sp);
}

void h5w_dset_int(h5w *h, hid_t loc, const char *name, hsize_t n, const int *data, const char *unit)
{
	hid_t sp = H5Screate_simple(1, &n, NULL);
	hid_t p = dcpl_for(h, 1, &n, sizeof(int));
	hid_t d = H5Dcreate2(loc, name, H5T_STD_I32LE, sp, H5P_DEFAULT, p, H5P_DEFAULT);
	if (d < 0 || (n > 0 && H5Dwrite(d, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0))
		h5w_fail(h);
	unit_attr(h, d, unit);
	h5w_close_obj(h, d);
	H5Pclose(p);
	H5Sclose(sp);
}

static hid_t clock_dset(h5w *h, hid_t g, const char *name, hid_t type, hsize_t T)
{
	hid_t sp = H5Screate_simple(1, &T, NULL);
	hid_t p = dcpl_for(h, 1, &T, 8);
	hid_t d = H5Dcreate2(g, name, type, sp, H5P_DEFAULT, p, H5P_DEFAULT);
	if (d < 0)
		h5w_fail(h);
	H5Pclose(p);
	H5Sclose(sp);
	return d;
}

int h5w_elem_create(h5w *h, h5elem *el, hid_t loc, const char *name, hsize_t T, int tail_rank,
		    const hsize_t *tail, const char *unit, const h5elem *clock)
{
	return h5w_elem_create_as(h, el, loc, name, T, tail_rank, tail, unit, clock, H5T_IEEE_F64LE);
}

int h5w_elem_create_as(h5w *h, h5elem *el, hid_t loc, const char *name, hsize_t T, int tail_rank,
		       const hsize_t *tail, const char *unit, const h5elem *clock, hid_t ftype)
{
	memset(el, 0, sizeof *el);
	el->step = el->time = el->value = -1;
	el->rank = 1 + tail_rank;
	el->dims[0] = T;
	for (int r = 0; r < tail_rank; r++)
		el->dims[1 + r] = tail[r];
	el->g = h5w_group(h, loc, name, 0);
	if (el->g < 0)
		return -1;
	if (clock) {
		if (H5Lcreate_hard(clock->g, "step", el->g, "step", H5P_DEFAULT, H5P_DEFAULT) < 0 ||
		    H5Lcreate_hard(clock->g, "time", el->g, "time", H5P_DEFAULT, H5P_DEFAULT) < 0)
			h5w_fail(h);
	} else {
		el->own_clock = 1;
		el->step = clock_dset(h, el->g, "step", H5T_STD_I64LE, T);
		el->time = clock_dset(h, el->g, "time", H5T_IEEE_F64LE, T);
		unit_attr(h, el->time, "s");
	}
	hid_t sp = H5Screate_simple(el->rank, el->dims, NULL);
	hid_t p = dcpl_for(h, el->rank, el->dims, H5Tget_size(ftype));
	el->value = H5Dcreate2(el->g, "value", ftype, sp, H5P_DEFAULT, p, H5P_DEFAULT);
	H5Pclose(p);
	H5Sclose(sp);
	if (el->value < 0)
		h5w_fail(h);
	unit_attr(h, el->value, unit);
	return h->bad ? -1 : 0;
}

/* Write count rows starting at k of one dataset from memory. */
static void rows_write(h5w *h, hid_t d, hid_t mtype, int rank, const hsize_t *dims, hsize_t k, hsize_t count,
		       const void *data)
{
	if (d < 0 || count == 0)
		return;
	hsize_t start[4] = {k, 0, 0, 0}, cnt[4];
	cnt[0] = count;
	for (int r = 1; r < rank; r++)
		cnt[r] = dims[r];
	hid_t fsp = H5Dget_space(d);
	hid_t msp = H5Screate_simple(rank, cnt, NULL);
	if (H5Sselect_hyperslab(fsp, H5S_SELECT_SET, start, NULL, cnt, NULL) < 0 ||
	    H5Dwrite(d, mtype, msp, fsp, H5P_DEFAULT, data) < 0)
		h5w_fail(h);
	H5Sclose(msp);
	H5Sclose(fsp);
}

void h5w_elem_row(h5w *h, h5elem *el, hsize_t k, long step, double t, const double *row)
{
	if (el->own_clock) {
		long long s = step;
		rows_write(h, el->step, H5T_NATIVE_LLONG, 1, el->dims, k, 1, &s);
		rows_write(h, el->time, H5T_NATIVE_DOUBLE, 1, el->dims, k, 1, &t);
	}
	rows_write(h, el->value, H5T_NATIVE_DOUBLE, el->rank, el->dims, k, 1, row);
}

void h5w_elem_all(h5w *h, h5elem *el, const long *steps, const double *times, const double *values)
{
	const hsize_t T = el->dims[0];
	if (el->own_clock && T > 0) {
		long long *s = H5allocate_memory(sizeof(long long) * T, 0);
		if (!s) {
			h5w_fail(h);
			return;
		}
		for (hsize_t k = 0; k < T; k++)
			s[k] = steps[k];
		rows_write(h, el->step, H5T_NATIVE_LLONG, 1, el->dims, 0, T, s);
		rows_write(h, el->time, H5T_NATIVE_DOUBLE, 1, el->dims, 0, T, times);
		H5free_memory(s);
	}
	rows_write(h, el->value, H5T_NATIVE_DOUBLE, el->rank, el->dims, 0, T, values);
}

void h5w_close_obj(h5w *h, hid_t id)
{
	if (id >= 0 && H5Oclose(id) < 0)
		h5w_fail(h);
}

void h5w_elem_close(h5w *h, h5elem *el)
{
	if (el->own_clock) {
		h5w_close_obj(h, el->step);
		h5w_close_obj(h, el->time);
	}
	h5w_close_obj(h, el->value);
	h5w_close_obj(h, el->g);
	el->g = el->value = el->step = el->time = -1;
}
