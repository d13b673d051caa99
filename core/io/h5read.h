/* h5read.h - reading run files (HDF5): numeric and string attributes, whole datasets
 * as doubles (HDF5 converts integer types). Nothing is taken on trust: a file must be
 * a regular one, an attribute one value of the kind asked for, and a dataset's shape
 * must fit in memory and in what the file holds for it before anything is allocated
 * (docs/inputs.md, "Run files"). HDF5's own error printing is switched off; failures
 * come back as sb_err. Shared by the analysis tools and the study driver. */
#ifndef SB_H5READ_H
#define SB_H5READ_H

#include <hdf5.h>
#include <stddef.h>

#include "err.h"

/* Opens a run file read-only: SB_EIO when it is no regular file (a FIFO would block
 * the open), its seal does not match its bytes (h5seal_check, before HDF5 reads
 * any of them), it is no HDF5 file, or it reaches outside itself (h5r_contained). */
int h5r_open(const char *path, hid_t *f, sb_err *e);
/* SB_EUSAGE, naming it and its range, when SHAKEBOX_H5_WALK_SECONDS (the time limit of
 * the walk of a file no recorded seal vouches for, docs/inputs.md) is set to anything but
 * a number of seconds in [0.1, 3600]: a program that reads run files checks it at its
 * start, since such a value refuses every such file. */
int h5r_walk_env(sb_err *e);
/* ... and seal gets the file's seal ("" for an older, unsealed file), which must be
 * want_seal when that is neither NULL nor "" (the seal the study driver recorded when
 * the run was done: a file copied, replaced or edited and sealed again differs), checked
 * before HDF5 opens the file. */
int h5r_open_sealed(const char *path, const char *want_seal, hid_t *f, char seal[17], sb_err *e);

/* The file holds only itself: every link is a hard link (no external link, whose
 * target another file is, nor a soft or user-defined one; the engine writes none), no
 * dataset keeps its data in external files, and a virtual dataset's every source is a
 * dataset of this file ("."). Checked from the links and the datasets' creation
 * properties, before any data is read: a FIFO or another campaign's file named there
 * is never opened. An error names the object and what it points at. */
int h5r_contained(hid_t f, const char *path, sb_err *e);
void h5r_close(hid_t f);
int h5r_exists(hid_t f, const char *path);

/* Attribute name of object obj ("/", "/observables/flux", ...): 0 found (*v set), 1
 * missing, -1 there but not one value of the kind asked for (v untouched either way). */
int h5r_attr_num(hid_t f, const char *obj, const char *name, double *v);
/* ... an integer, exact (not through a double): an integer type, or a float that holds
 * an integer */
int h5r_attr_int(hid_t f, const char *obj, const char *name, long long *v);
/* ... a string (fixed or variable length), cut to len - 1 bytes; buf is "" unless 0. */
int h5r_attr_str(hid_t f, const char *obj, const char *name, char *buf, size_t len);

/* The shape of a dataset of rank <= 8 and its number of elements, checked: the count
 * does not overflow, and the file holds the bytes it claims (h5read.c); an error
 * names the dataset and why. dims[k] for k >= rank are 1. */
int h5r_shape(hid_t f, const char *path, int *rank, size_t dims[8], size_t *count, sb_err *e);

/* The whole dataset as doubles (malloc'd, free by the caller), rank <= 3, dims[];
 * its shape checked as h5r_shape does. */
int h5r_read(hid_t f, const char *path, double **data, int *rank, size_t dims[3], sb_err *e);

/* Every dataset's data read once, so that HDF5 verifies the Fletcher32 checksum of
 * each chunk (core/io/h5md.c writes one on every dataset with data): an error names the
 * dataset ("checksum error" when the bytes changed after they were written). Datasets
 * without the filter (older files) are only checked as h5r_shape does. */
int h5r_verify(hid_t f, sb_err *e);

#endif
