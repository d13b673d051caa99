/* h5read.h - reading run outputs: numeric and string attributes, whole datasets as
 * doubles (HDF5 converts integer types). HDF5's own error printing is switched off;
 * failures come back as sb_err. */
#ifndef AN_H5READ_H
#define AN_H5READ_H

#include <hdf5.h>

#include "err.h"

int h5r_open(const char *path, hid_t *f, sb_err *e);
void h5r_close(hid_t f);
int h5r_exists(hid_t f, const char *path);
/* Attribute name of object obj ("/", "/observables/flux", ...): 0 found, 1 missing (v untouched). */
int h5r_attr_num(hid_t f, const char *obj, const char *name, double *v);
int h5r_attr_str(hid_t f, const char *obj, const char *name, char *buf, size_t len);
/* The whole dataset as doubles (malloc'd, free by the caller), rank <= 3, dims[]. */
int h5r_read(hid_t f, const char *path, double **data, int *rank, size_t dims[3], sb_err *e);

#endif
