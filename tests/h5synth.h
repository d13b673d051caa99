/* h5synth.h - writing small synthetic HDF5 run files in analysis tests: a scalar double
 * or string attribute, a double dataset. Included by one test file each (static inline
 * helpers, so that a test using two of the three compiles warning-free);
 * the caller includes hdf5.h and string.h. */
#ifndef SB_TESTS_H5SYNTH_H
#define SB_TESTS_H5SYNTH_H

#include <hdf5.h>
#include <string.h>

static inline void attr_d(hid_t o, const char *name, double v)
{
	hid_t sp = H5Screate(H5S_SCALAR);
	hid_t a = H5Acreate2(o, name, H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
	H5Awrite(a, H5T_NATIVE_DOUBLE, &v);
	H5Aclose(a);
	H5Sclose(sp);
}

static inline void attr_s(hid_t o, const char *name, const char *v)
{
	hid_t sp = H5Screate(H5S_SCALAR), ty = H5Tcopy(H5T_C_S1);
	H5Tset_size(ty, strlen(v) + 1);
	hid_t a = H5Acreate2(o, name, ty, sp, H5P_DEFAULT, H5P_DEFAULT);
	H5Awrite(a, ty, v);
	H5Aclose(a);
	H5Tclose(ty);
	H5Sclose(sp);
}

/* a path's missing groups are made on the way ("observables/field/uy/value") */
static inline void dset(hid_t g, const char *name, int rank, const hsize_t *dims, const double *v)
{
	hid_t lc = H5Pcreate(H5P_LINK_CREATE);
	H5Pset_create_intermediate_group(lc, 1);
	hid_t sp = H5Screate_simple(rank, dims, NULL);
	hid_t d = H5Dcreate2(g, name, H5T_IEEE_F64LE, sp, lc, H5P_DEFAULT, H5P_DEFAULT);
	H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
	H5Dclose(d);
	H5Sclose(sp);
	H5Pclose(lc);
}

#endif
