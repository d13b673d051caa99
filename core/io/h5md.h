/* h5md.h - writing HDF5 in the H5MD 1.1 conventions (layout: docs/output.md):
 * attributes, groups, fixed datasets and time-dependent elements (a group holding
 * step, time and value, the three sharing their first dimension). Every dataset with
 * data is chunked and checksummed (Fletcher32), large ones compressed (shuffle +
 * deflate). Errors set a sticky flag instead of
 * returning, so a writer can go on and report once at the end. */
#ifndef SB_H5MD_H
#define SB_H5MD_H

#include <hdf5.h>

typedef struct h5w {
	hid_t file;
	hid_t gcpl;  /* groups: no time stamps, so equal runs give equal files */
	hid_t ogcpl; /* the same, iterated in creation order */
	int bad;     /* sticky: some call failed */
	char why[256]; /* HDF5's word on the first failure ("No space left on device") */
	int level;   /* deflate level of the large datasets (0: none) */
} h5w;

/* Call before any other HDF5 call of the process: no library exit handler, which
 * would close a file whose H5Fclose failed a second time (h5md.c). */
void h5w_init(void);
/* The innermost message on HDF5's error stack ("" when there is none). */
void h5w_last_error(char *buf, size_t len);

/* Mark the writer failed (bad), keeping HDF5's innermost message of the first failure:
 * later calls clear its error stack, and the first fault is the cause. */
void h5w_fail(h5w *h);

/* Open a new file (truncating) with the property lists above; < 0 on failure. */
int h5w_create(h5w *h, const char *path, int deflate_level);
/* Close everything; returns -1 when any call failed on the way. */
int h5w_close(h5w *h);

void h5w_attr_double(h5w *h, hid_t obj, const char *name, double v);
void h5w_attr_long(h5w *h, hid_t obj, const char *name, long v);
void h5w_attr_str(h5w *h, hid_t obj, const char *name, const char *v);
/* ... as a variable-length ASCII string (what H5MD's units module asks of its strings) */
void h5w_attr_vstr(h5w *h, hid_t obj, const char *name, const char *v);
/* The H5MD unit attribute of a dataset (e.g. "cm s-1"). */
void h5w_attr_unit(h5w *h, hid_t obj, const char *unit);
/* An attribute holding n strings (fixed length), e.g. H5MD's box boundary. */
void h5w_attr_strs(h5w *h, hid_t obj, const char *name, const char *const *v, int n);
/* An attribute holding n integers, e.g. H5MD's version. */
void h5w_attr_ints(h5w *h, hid_t obj, const char *name, const int *v, int n);

/* A group at loc/name (ordered: its members are listed in creation order). */
hid_t h5w_group(h5w *h, hid_t loc, const char *name, int ordered);
/* Open loc/name when it exists, else create it. */
hid_t h5w_group_get(h5w *h, hid_t loc, const char *name);

/* A whole dataset of doubles (or ints when ints != NULL) of the given rank and
 * shape, written at once, with a unit attribute (NULL: none). */
void h5w_dset(h5w *h, hid_t loc, const char *name, int rank, const hsize_t *dims, const double *data,
	      const char *unit);
void h5w_dset_int(h5w *h, hid_t loc, const char *name, hsize_t n, const int *data, const char *unit);

/* A time-dependent element: loc/name/{step, time, value[T][tail...]}. Either it gets
 * its own step and time datasets (filled by h5w_elem_row or h5w_elem_all), or it
 * shares those of `clock` (hard links, as H5MD recommends for data sampled
 * together). value is chunked one row at a time and compressed when large. */
typedef struct h5elem {
	hid_t g, step, time, value;
	int rank;        /* of value */
	hsize_t dims[4]; /* of value; dims[0] = T */
	int own_clock;
} h5elem;

int h5w_elem_create(h5w *h, h5elem *el, hid_t loc, const char *name, hsize_t T, int tail_rank,
		    const hsize_t *tail, const char *unit, const h5elem *clock);
/* The same with values stored as ftype (e.g. H5T_IEEE_F32LE; rows are still given as
 * doubles, HDF5 converts). */
int h5w_elem_create_as(h5w *h, h5elem *el, hid_t loc, const char *name, hsize_t T, int tail_rank,
		       const hsize_t *tail, const char *unit, const h5elem *clock, hid_t ftype);
/* Row k: its step and time (ignored when the clock is shared) and its values. */
void h5w_elem_row(h5w *h, h5elem *el, hsize_t k, long step, double t, const double *row);
/* All rows at once: steps and times (NULL when shared), values [T][tail...]. */
void h5w_elem_all(h5w *h, h5elem *el, const long *steps, const double *times, const double *values);
void h5w_elem_close(h5w *h, h5elem *el);

/* Close a group or a dataset (id < 0: nothing). Checked: a dataset's chunks are written
 * when it closes, and a full disk then fails the close, not any earlier write; a file
 * sealed after an unchecked close would hold zeros where they belong (docs/output.md). */
void h5w_close_obj(h5w *h, hid_t id);

#endif
