/* flux.c - the flux-plane summary on a synthetic run file written here: the band
 * picks the right lines, the transient is dropped (of a failed run: the transient of
 * the run as planned), the profile is the time mean per line; a file without /flux
 * is an error. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "flux.h"
#include "h5read.h"
#include "testlib.h"

enum { P = 10, L = 20 };

static void dset(hid_t g, const char *name, int rank, hsize_t d0, hsize_t d1, const double *v)
{
	hsize_t dims[2] = {d0, d1};
	hid_t sp = H5Screate_simple(rank, dims, NULL);
	hid_t d = H5Dcreate2(g, name, H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
	H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
	H5Dclose(d);
	H5Sclose(sp);
}

int main(void)
{
	char path[] = "/tmp/an_flux_XXXXXX";
	int fd = mkstemp(path);
	close(fd);
	/* surface 40 cm, 20 lines at (l + 0.5) * 2 cm; phi = l + 1 after 2 transient
	 * periods of 1000 */
	double t[P], f[P], phi[P * L], h[L];
	for (int p = 0; p < P; p++) {
		t[p] = 0.25 * (p + 1);
		f[p] = 4;
		for (int l = 0; l < L; l++)
			phi[p * L + l] = p < 2 ? 1000 : l + 1 + (p % 2 ? 0.5 : -0.5);
	}
	for (int l = 0; l < L; l++)
		h[l] = 40.0 * (l + 0.5) / L;
	hid_t file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
	/* the engine's layout: H5MD elements under /observables/flux */
	hid_t go = H5Gcreate2(file, "/observables", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
	hid_t g = H5Gcreate2(go, "flux", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
	hid_t gp = H5Gcreate2(g, "phi", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
	hid_t gf = H5Gcreate2(g, "frequency", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
	dset(gp, "time", 1, P, 0, t);
	dset(gp, "value", 2, P, L, phi);
	dset(gf, "time", 1, P, 0, t);
	dset(gf, "value", 1, P, 0, f);
	dset(g, "heights", 1, L, 0, h);
	H5Gclose(gp);
	H5Gclose(gf);
	H5Gclose(go);
	double s = 40;
	hid_t sp = H5Screate(H5S_SCALAR);
	hid_t a = H5Acreate2(g, "surface_height", H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
	H5Awrite(a, H5T_NATIVE_DOUBLE, &s);
	H5Aclose(a);
	H5Sclose(sp);
	H5Gclose(g);
	H5Fclose(file);

	flux_data d;
	sb_err e = {0};
	CHECK("flux.read.ok", flux_read(path, &d, &e) == 0, "%s", e.msg);
	CHECK("flux.read.sizes", d.P == P && d.L == L && d.surface == 40, "P %zu L %zu surface %g", d.P, d.L, d.surface);
	flux_opts o = FLUX_OPTS_DEFAULT;
	o.skip = 0.2; /* floor(0.2 * 10) = 2 periods dropped */
	size_t l0, l1;
	flux_band(&d, &o, &l0, &l1);
	/* band 16..24 cm: lines at 17, 19, 21, 23 cm = l 8..11 */
	CHECK("flux.band.lines", l0 == 8 && l1 == 12, "lines [%zu, %zu), want [8, 12)", l0, l1);
	CHECK("flux.first_period", flux_first(&d, &o) == 2, "first %zu", flux_first(&d, &o));
	/* mean of l + 1 over l = 8..11 = 10.5; the +-0.5 alternation cancels over 8 periods */
	CHECK_REL("flux.summary.middle_band", flux_summary(&d, &o), 10.5, 1e-12);
	CHECK_REL("flux.plane.one_period", flux_plane(&d, 3, l0, l1), 11.0, 1e-12);
	o.skip = 0;
	CHECK("flux.summary.transient_counts_when_not_skipped", flux_summary(&d, &o) > 100, "summary %g",
	      flux_summary(&d, &o));
	o.skip = 0.2;
	o.band_lo = o.band_hi = 0.51; /* thinner than the spacing: the nearest line (21 cm, l = 10) */
	flux_band(&d, &o, &l0, &l1);
	CHECK("flux.band.nearest_line", l0 == 10 && l1 == 11, "lines [%zu, %zu)", l0, l1);
	CHECK_REL("flux.summary.single_line", flux_summary(&d, &o), 11.0, 1e-12);
	double prof[L];
	flux_profile(&d, &o, prof);
	CHECK("flux.profile", fabs(prof[0] - 1) < 1e-12 && fabs(prof[19] - 20) < 1e-12, "profile %g .. %g", prof[0],
	      prof[19]);
	/* a run stopped by a failure after its 10 periods of 40 planned: its transient is
	 * floor(0.2 * 40) = 8 periods, so periods 8 and 9 are used; one planned for 60
	 * stopped within its transient (12 periods) and has nothing to use */
	o.band_lo = 0.4;
	o.band_hi = 0.6;
	d.planned = 40;
	CHECK("flux.failed.first_of_planned", flux_first(&d, &o) == 8, "first %zu", flux_first(&d, &o));
	CHECK_REL("flux.failed.summary_after_planned_transient", flux_summary(&d, &o), 10.5, 1e-12);
	d.planned = 60;
	flux_profile(&d, &o, prof);
	CHECK("flux.failed.within_transient", isnan(flux_summary(&d, &o)) && isnan(prof[0]), "summary %g",
	      flux_summary(&d, &o));
	d.planned = 0;
	flux_free(&d);

	/* a run without flux = yes */
	file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
	H5Fclose(file);
	sb_err e2 = {0};
	CHECK("flux.read.missing_group", flux_read(path, &d, &e2) == SB_EIO && strstr(e2.msg, "no /observables/flux"), "rc %d: %s",
	      e2.code, e2.msg);
	sb_err e3 = {0};
	CHECK("flux.read.missing_file", flux_read("/nonexistent/x.h5", &d, &e3) == SB_EIO, "rc %d", e3.code);
	unlink(path);
	return tl_done();
}
