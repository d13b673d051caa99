/* h5sum.c - reading a run's status and cheap results with the HDF5 C API. */
#include "h5sum.h"

#include <hdf5.h>
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

static void trajectory(hid_t f, h5sum *s, int *bad)
{
	if (H5Lexists(f, "/intruder", H5P_DEFAULT) <= 0 || H5Lexists(f, "/intruder/trajectory", H5P_DEFAULT) <= 0)
		return;
	hid_t d = H5Dopen2(f, "/intruder/trajectory", H5P_DEFAULT);
	hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
	hsize_t dims[2] = {0, 0};
	if (sp < 0 || H5Sget_simple_extent_ndims(sp) != 2 || H5Sget_simple_extent_dims(sp, dims, NULL) < 0 ||
	    dims[1] != 6) {
		*bad = 1;
		goto out;
	}
	s->traj_rows = (long)dims[0];
	if (dims[0] > 0) {
		double *t = malloc(sizeof *t * dims[0] * 6);
		if (!t || H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, t) < 0) {
			*bad = 1;
			free(t);
			goto out;
		}
		s->has_traj = 1;
		s->final_y = t[(dims[0] - 1) * 6 + 2];
		s->max_y = s->min_y = t[2];
		double sum = 0;
		s->rise_time = -1;
		for (hsize_t i = 0; i < dims[0]; i++) {
			double y = t[i * 6 + 2];
			sum += y;
			if (y > s->max_y)
				s->max_y = y;
			if (y < s->min_y)
				s->min_y = y;
			if (s->rise_time < 0 && s->intruder_radius > 0 &&
			    y - s->intruder_settled_y > 2 * s->intruder_radius)
				s->rise_time = t[i * 6];
		}
		s->mean_y = sum / (double)dims[0];
		free(t);
	}
out:
	if (sp >= 0)
		H5Sclose(sp);
	if (d >= 0)
		H5Dclose(d);
}

/* The intruder's radius from /particles (its index is an attribute of /intruder). */
static double intruder_radius(hid_t f, int *bad)
{
	if (H5Lexists(f, "/intruder", H5P_DEFAULT) <= 0 || H5Lexists(f, "/particles", H5P_DEFAULT) <= 0 ||
	    H5Lexists(f, "/particles/radius", H5P_DEFAULT) <= 0)
		return 0;
	hid_t g = H5Gopen2(f, "/intruder", H5P_DEFAULT);
	long idx = g >= 0 && attr_exists(g, "index") ? get_long(g, "index", bad) : -1;
	if (g >= 0)
		H5Gclose(g);
	if (idx < 0)
		return 0;
	double r = 0;
	hid_t d = H5Dopen2(f, "/particles/radius", H5P_DEFAULT);
	hid_t fs = d >= 0 ? H5Dget_space(d) : -1;
	hsize_t n = 0;
	if (fs >= 0)
		H5Sget_simple_extent_dims(fs, &n, NULL);
	if (fs >= 0 && (hsize_t)idx < n) {
		hsize_t start = (hsize_t)idx, one = 1;
		hid_t ms = H5Screate_simple(1, &one, NULL);
		H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, NULL, &one, NULL);
		if (H5Dread(d, H5T_NATIVE_DOUBLE, ms, fs, H5P_DEFAULT, &r) < 0)
			*bad = 1;
		H5Sclose(ms);
	}
	if (fs >= 0)
		H5Sclose(fs);
	if (d >= 0)
		H5Dclose(d);
	return r;
}

int h5sum_read(const char *path, h5sum *s, sb_err *e)
{
	memset(s, 0, sizeof *s);
	s->rise_time = -1;
	H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* errors are returned, not printed */
	hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
	if (f < 0)
		return sb_errf(e, SB_EIO, "%s: cannot open HDF5 file", path);
	int bad = 0;
	get_str(f, "status", s->status, sizeof s->status, &bad);
	s->exit_code = get_long(f, "exit_code", &bad);
	get_str(f, "status_message", s->message, sizeof s->message, &bad);
	s->status_time = get_double(f, "status_time", &bad);
	s->steps = get_long(f, "steps", &bad);
	s->settle_time = get_double(f, "settle_time", &bad);
	s->settle_steps = get_long(f, "settle_steps", &bad);
	s->surface_height = get_double(f, "surface_height", &bad);
	s->intruder_settled_y = get_double(f, "intruder_settled_y", &bad);
	s->intruder_settled_depth = get_double(f, "intruder_settled_depth", &bad);
	s->n_mobile = get_long(f, "n_mobile", &bad);
	s->neighbour_builds = get_long(f, "neighbour_builds", &bad);
	if (H5Lexists(f, "/provenance", H5P_DEFAULT) > 0) {
		hid_t g = H5Gopen2(f, "/provenance", H5P_DEFAULT);
		if (g >= 0) {
			s->loop_seconds = get_double(g, "loop_seconds", &bad);
			get_str(g, "host", s->host, sizeof s->host, &bad);
			get_str(g, "git_hash", s->git_hash, sizeof s->git_hash, &bad);
			s->git_dirty = get_long(g, "git_dirty", &bad);
			get_str(g, "start_time", s->start_time, sizeof s->start_time, &bad);
			get_str(g, "end_time", s->end_time, sizeof s->end_time, &bad);
			H5Gclose(g);
		}
	}
	s->intruder_radius = intruder_radius(f, &bad);
	trajectory(f, s, &bad);
	H5Fclose(f);
	if (bad || !s->status[0])
		return sb_errf(e, SB_EIO, "%s: not a complete shakebox run file (missing or unreadable status)", path);
	return 0;
}
