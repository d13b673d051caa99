/* traj.c - the second waiting-time definition on synthetic trajectories with a known
 * answer: the crossing time interpolated between samples, a start above the level, no
 * crossing (censored at the last sample); and a synthetic run file whose lab-frame
 * trajectory carries the box motion A sin(2 pi f t), which traj_read takes off. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "testlib.h"
#include "measure/traj.h"

#include "h5synth.h"

enum { T = 101 };

int main(void)
{
	const double t[6] = {0, 1, 2, 3, 4, 5}, y[6] = {0, 1, 2, 3, 4, 5};
	CHECK_REL("traj.crossing.interpolated", traj_crossing(t, y, 6, 2.5), 2.5, 1e-12);
	CHECK("traj.crossing.on_a_sample", traj_crossing(t, y, 6, 3) == 3, "got %g", traj_crossing(t, y, 6, 3));
	CHECK("traj.crossing.start_above", traj_crossing(t, y, 6, -1) == 0, "got %g", traj_crossing(t, y, 6, -1));
	CHECK("traj.crossing.never", isnan(traj_crossing(t, y, 6, 6)), "got %g", traj_crossing(t, y, 6, 6));

	/* settled at 5 cm, surface 25 cm: half the way is 15 cm; y = 5 + t^2 / 2 passes it
	 * between t = 4 (13) and 5 (17.5): at 4 + 2 / 4.5 */
	double tt[11], yb[11];
	for (int i = 0; i < 11; i++) {
		tt[i] = i;
		yb[i] = 5 + 0.5 * i * i;
	}
	traj tr = {.n = 11, .t = tt, .ybox = yb, .y0 = 5, .surface = 25};
	double w;
	CHECK("traj.fraction.event", traj_fraction(&tr, 0.5, &w) == 1 && fabs(w - (4 + 2 / 4.5)) < 1e-12, "time %g", w);
	CHECK("traj.fraction.censored_at_last_sample", traj_fraction(&tr, 3, &w) == 0 && w == 10, "time %g", w);
	tr.y0 = NAN;
	CHECK("traj.fraction.no_settled_height", traj_fraction(&tr, 0.5, &w) == -1, "accepted");

	/* a run file: f = 2 Hz, A = 1.5 cm, the centre rising 1 cm/s in the box from 4 cm,
	 * recorded in the lab frame at 100 Hz */
	char path[] = "/tmp/an_traj_XXXXXX";
	int fd = mkstemp(path);
	close(fd);
	double tm[T], pos[2 * T];
	for (int i = 0; i < T; i++) {
		tm[i] = 0.01 * i;
		pos[2 * i] = 10;
		pos[2 * i + 1] = 4 + tm[i] + 1.5 * sin(2 * M_PI * 2 * tm[i]);
	}
	hid_t f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
	hid_t par = H5Gcreate2(f, "/parameters", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
	attr_d(par, "amplitude", 1.5);
	attr_d(par, "frequency", 2);
	attr_d(par, "duration", 1);
	attr_s(par, "ramp", "none");
	H5Gclose(par);
	hid_t root = H5Gopen2(f, "/", H5P_DEFAULT);
	attr_d(root, "intruder_settled_y", 4);
	attr_d(root, "surface_height", 5);
	attr_s(root, "stopped_by", "none");
	H5Gclose(root);
	hid_t lc = H5Pcreate(H5P_LINK_CREATE); /* with /particles and /particles/intruder */
	H5Pset_create_intermediate_group(lc, 1);
	hid_t g = H5Gcreate2(f, "/particles/intruder/position", lc, H5P_DEFAULT, H5P_DEFAULT);
	H5Pclose(lc);
	const hsize_t d1[1] = {T}, d3[3] = {T, 1, 2};
	dset(g, "time", 1, d1, tm);
	dset(g, "value", 3, d3, pos);
	H5Gclose(g);
	H5Fclose(f);
	traj r;
	sb_err e = {0};
	CHECK("traj.read.ok", traj_read(path, &r, &e) == 0 && r.n == T, "%s (n %zu)", e.msg, r.n);
	double worst = 0;
	for (size_t i = 0; i < r.n; i++)
		worst = fmax(worst, fabs(r.ybox[i] - (4 + r.t[i])));
	CHECK("traj.read.box_frame", worst < 1e-12, "largest error %g cm", worst);
	CHECK("traj.read.attributes", r.y0 == 4 && r.surface == 5 && !strcmp(r.stopped_by, "none"), "y0 %g surface %g",
	      r.y0, r.surface);
	/* half the way from 4 to 5 cm: 4.5 cm at t = 0.5 s (the lab frame would say earlier) */
	CHECK("traj.read.fraction_in_box_frame", traj_fraction(&r, 0.5, &w) == 1 && fabs(w - 0.5) < 1e-9, "time %g", w);
	traj_free(&r);
	/* a file without a trajectory (traj_rate = 0) */
	f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
	H5Fclose(f);
	CHECK("traj.read.none", traj_read(path, &r, &e) == 1 && r.n == 0, "n %zu", r.n);
	traj_free(&r);
	unlink(path);
	return tl_done();
}
