/* h5read.c - attributes and datasets of run outputs as doubles and strings. */
#include "h5read.h"

#include <stdlib.h>
#include <string.h>

int h5r_open(const char *path, hid_t *f, sb_err *e)
{
	H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
	*f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
	if (*f < 0)
		return sb_errf(e, SB_EIO, "%s: cannot open HDF5 file", path);
	return 0;
}

void h5r_close(hid_t f)
{
	if (f >= 0)
		H5Fclose(f);
}

int h5r_exists(hid_t f, const char *path)
{
	/* every prefix must exist for H5Lexists to answer without an error */
	char buf[512];
	snprintf(buf, sizeof buf, "%s", path);
	for (char *p = buf + 1; *p; p++) {
		if (*p != '/')
			continue;
		*p = 0;
		if (H5Lexists(f, buf, H5P_DEFAULT) <= 0)
			return 0;
		*p = '/';
	}
	return H5Lexists(f, buf, H5P_DEFAULT) > 0;
}

int h5r_attr_num(hid_t f, const char *obj, const char *name, double *v)
{
	if (H5Aexists_by_name(f, obj, name, H5P_DEFAULT) <= 0)
		return 1;
	hid_t a = H5Aopen_by_name(f, obj, name, H5P_DEFAULT, H5P_DEFAULT);
	if (a < 0)
		return 1;
	hid_t t = H5Aget_type(a);
	int bad = H5Tget_class(t) != H5T_INTEGER && H5Tget_class(t) != H5T_FLOAT;
	double x;
	if (!bad)
		bad = H5Aread(a, H5T_NATIVE_DOUBLE, &x) < 0;
	H5Tclose(t);
	H5Aclose(a);
	if (bad)
		return 1;
	*v = x;
	return 0;
}

int h5r_attr_str(hid_t f, const char *obj, const char *name, char *buf, size_t len)
{
	buf[0] = 0;
	if (H5Aexists_by_name(f, obj, name, H5P_DEFAULT) <= 0)
		return 1;
	hid_t a = H5Aopen_by_name(f, obj, name, H5P_DEFAULT, H5P_DEFAULT);
	if (a < 0)
		return 1;
	hid_t t = H5Aget_type(a);
	int rc = 1;
	if (H5Tget_class(t) == H5T_STRING && !H5Tis_variable_str(t)) {
		size_t n = H5Tget_size(t);
		char *tmp = calloc(n + 1, 1);
		if (tmp && H5Aread(a, t, tmp) >= 0) {
			snprintf(buf, len, "%s", tmp);
			rc = 0;
		}
		free(tmp);
	}
	H5Tclose(t);
	H5Aclose(a);
	return rc;
}

int h5r_read(hid_t f, const char *path, double **data, int *rank, size_t dims[3], sb_err *e)
{
	*data = NULL;
	*rank = 0;
	dims[0] = dims[1] = dims[2] = 1;
	if (!h5r_exists(f, path))
		return sb_errf(e, SB_EIO, "%s: no such dataset", path);
	hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
	if (d < 0)
		return sb_errf(e, SB_EIO, "%s: cannot open dataset", path);
	hid_t sp = H5Dget_space(d);
	int r = H5Sget_simple_extent_ndims(sp);
	hsize_t hd[3] = {1, 1, 1};
	if (r < 0 || r > 3) {
		H5Sclose(sp);
		H5Dclose(d);
		return sb_errf(e, SB_EIO, "%s: rank %d not supported", path, r);
	}
	H5Sget_simple_extent_dims(sp, hd, NULL);
	size_t n = 1;
	for (int k = 0; k < r; k++) {
		dims[k] = (size_t)hd[k];
		n *= dims[k];
	}
	double *p = malloc(sizeof *p * (n ? n : 1));
	int bad = !p || (n && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, p) < 0);
	H5Sclose(sp);
	H5Dclose(d);
	if (bad) {
		free(p);
		return sb_errf(e, SB_EIO, "%s: cannot read dataset", path);
	}
	*data = p;
	*rank = r;
	return 0;
}
