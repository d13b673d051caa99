/* whale.c - the whale oscillation's observables on synthetic heights with a known
 * answer (analysis/measure/whale.h, whalespec.h, whalestat.h, whalerun.h): dives of a known
 * shape at known, uneven times under the bed's flight at the drive frequency and
 * noise; a sine; no dive; one dive; noise at the threshold (hysteresis); a dive under
 * way when the window opens; the spectrum's period; Spearman's rho against hand
 * values and its permutation p; and a synthetic run file read end to end. */
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "testlib.h"
#include "measure/whale.h"
#include "measure/whalerun.h"
#include "measure/whalespec.h"
#include "measure/whalestat.h"

enum { RATE = 100 };          /* samples per second, the engine's traj_rate default */
#define DUR 600.0             /* s: the long runs whale is for */
#define FDRIVE 3.2            /* Hz */
#define TOP 20.0              /* cm */
#define DEPTH 6.0             /* cm: how deep each synthetic dive goes */
#define DLEN 10.0             /* s: how long each dive lasts */

/* The dives' start times: intervals alternating 30 s and 44 s (mean 37 s), so that
 * the period is the mean interval, not one of them; *n of them fit in [5, DUR - DLEN). */
static size_t dive_starts(double *s, size_t cap)
{
	size_t n = 0;
	for (double t = 5; t < DUR - DLEN && n < cap; t += n % 2 ? 44 : 30)
		s[n++] = t;
	return n;
}

/* y(t): the top, a half-sine dip of DEPTH over DLEN at each start, the bed's flight
 * (1.5 cm at the drive frequency, which the running mean over one period removes) and
 * white noise of sd sigma */
static void synth(double *t, double *y, size_t n, const double *s, size_t ns, double sigma, gsl_rng *r)
{
	for (size_t i = 0; i < n; i++) {
		t[i] = (double)i / RATE;
		double v = TOP + 1.5 * sin(2 * M_PI * FDRIVE * t[i]);
		for (size_t k = 0; k < ns; k++)
			if (t[i] >= s[k] && t[i] < s[k] + DLEN)
				v -= DEPTH * sin(M_PI * (t[i] - s[k]) / DLEN);
		y[i] = v + (sigma > 0 ? gsl_ran_gaussian(r, sigma) : 0);
	}
}

#include "h5synth.h"

/* A run file like the engine's: /parameters (amplitude, frequency, duration, ramp),
 * the root attributes of the rise and the intruder, and the lab-frame trajectory
 * (box-frame y plus the box motion A sin(2 pi f t), which traj_read takes off). */
static void write_run(const char *path, const double *t, const double *ybox, size_t n, int risen, double wait,
		      double radius, int with_traj)
{
	const double A = 2;
	hid_t f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
	hid_t par = H5Gcreate2(f, "/parameters", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
	attr_d(par, "amplitude", A);
	attr_d(par, "frequency", FDRIVE);
	attr_d(par, "duration", DUR);
	attr_s(par, "ramp", "none");
	H5Gclose(par);
	hid_t root = H5Gopen2(f, "/", H5P_DEFAULT);
	attr_d(root, "risen", risen);
	attr_d(root, "waiting_time", wait);
	attr_d(root, "intruder_radius", radius);
	attr_d(root, "intruder_settled_y", 5);
	attr_d(root, "surface_height", 25);
	attr_s(root, "stopped_by", "none");
	H5Gclose(root);
	if (with_traj) {
		double *pos = malloc(sizeof *pos * 2 * n);
		for (size_t i = 0; i < n; i++) {
			pos[2 * i] = 15;
			pos[2 * i + 1] = ybox[i] + A * sin(2 * M_PI * FDRIVE * t[i]);
		}
		hid_t lc = H5Pcreate(H5P_LINK_CREATE);
		H5Pset_create_intermediate_group(lc, 1);
		hid_t g = H5Gcreate2(f, "/particles/intruder/position", lc, H5P_DEFAULT, H5P_DEFAULT);
		H5Pclose(lc);
		const hsize_t d1[1] = {n}, d3[3] = {n, 1, 2};
		dset(g, "time", 1, d1, t);
		dset(g, "value", 3, d3, pos);
		H5Gclose(g);
		free(pos);
	}
	H5Fclose(f);
}

int main(void)
{
	const size_t n = (size_t)(DUR * RATE) + 1;
	double *t = malloc(sizeof *t * n), *y = malloc(sizeof *y * n), s[64];
	gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(r, 7);
	const size_t ns = dive_starts(s, 64);
	const whale_opts o = {2.0, 0.9, FDRIVE}; /* D = 2 cm, one radius of a 2 cm intruder */
	whale_run w;
	double *st = NULL;

	/* ---- dives of a known shape and times, flight and noise (sd 0.3 cm) ----
	 * Each dive crosses top - D at the same time after its start (same shape), so the
	 * period is (s[last] - s[0]) / (n - 1) exactly but for the noise: after the running
	 * mean over one period (31 samples) its sd is 0.3 / sqrt(31) = 0.054 cm, and the dip
	 * crosses the threshold at 6 pi / 10 cos(asin(1/3)) = 1.78 cm/s: 0.03 s of jitter per
	 * start, 0.003 s on the mean of 15 intervals. 0.05 s is over 10 sd of that, and 25
	 * times smaller than the 1.2 s a lost or doubled dive would shift the mean by. */
	synth(t, y, n, s, ns, 0.3, r);
	CHECK("whale.dives.ok", whale_dives(t, y, n, 0, &o, &w, &st) == 0, "samples %zu", w.samples);
	const double want_p = (s[ns - 1] - s[0]) / (double)(ns - 1);
	CHECK("whale.dives.count", w.dives == (long)ns && w.done == (long)ns, "%ld dives (%ld ended), want %zu", w.dives,
	      w.done, ns);
	CHECK("whale.dives.period", fabs(w.period - want_p) < 0.05, "period %.4f s, want %.4f s", w.period, want_p);
	/* each start is found 1.08 s + the running mean's lead after the true start */
	double worst = 0;
	for (long k = 0; k < w.dives && k < (long)ns; k++)
		worst = fmax(worst, fabs(st[k] - (s[k] + 10 / M_PI * asin(1.0 / 3))));
	CHECK("whale.dives.start_times", worst < 0.25, "largest error %.3f s", worst);
	free(st);
	/* the top level is the 90th percentile: at the top (dives take 10 of 37 s) and
	 * above the mean top by about 1.3 sd of the averaged noise; the depth is the dip's
	 * 6 cm plus that: within 0.15 cm (2.5 %) */
	CHECK("whale.top.level", fabs(w.top - TOP) < 0.15, "top %.4f cm, want %.1f", w.top, TOP);
	CHECK("whale.depth.mean", fabs(w.depth - DEPTH) < 0.15, "depth %.4f cm, want %.1f", w.depth, DEPTH);
	CHECK("whale.depth.max", w.depth_max >= w.depth && w.depth_max < DEPTH + 0.3, "max %.4f", w.depth_max);
	CHECK_REL("whale.rate.per_minute", w.rate, 60.0 * (double)ns / DUR, 1e-9);
	/* the flight at the drive frequency is averaged out: without the running mean it
	 * swings 3 cm peak to peak, more than D, and every period would be a dive */
	whale_opts raw = o;
	raw.drive_f = 0;
	whale_run wr;
	whale_dives(t, y, n, 0, &raw, &wr, NULL);
	CHECK("whale.smoothing.needed", wr.dives > 10 * (long)ns, "without the running mean %ld dives", wr.dives);
	/* the spectrum's period: the dives are not periodic (30 and 44 s alternate), its
	 * strongest line is the 74 s cycle's or its harmonic at 37 s; here just that it is
	 * in the band and not at its edge */
	whale_spec sp;
	double *ys = malloc(sizeof *ys * n);
	whale_smooth(t, y, n, 1 / FDRIVE, ys);
	CHECK("whale.spec.runs", whale_spectrum(t, ys, n, FDRIVE, &sp) == 0 && isfinite(sp.period), "period %g",
	      sp.period);
	CHECK("whale.spec.harmonic_of_74s", fabs(sp.period - 37) < 1.5 || fabs(sp.period - 74) < 3, "period %.3f s",
	      sp.period);

	/* ---- a sine of period 45 s and amplitude 3 cm (noise sd 0.2) ----
	 * The top level is the 90th percentile of 17 + 3 cos: 17 + 3 cos(pi / 10) = 19.853;
	 * the depth top - 14 = 5.853 cm. The spectrum's bins are 1/600 Hz apart (7.5 % of
	 * the line at 1/45 Hz); the parabola through the three highest bins of a Hann
	 * window's main lobe is good to a fraction of a bin: within 3 %. */
	for (size_t i = 0; i < n; i++)
		y[i] = 17 + 3 * cos(2 * M_PI * t[i] / 45) + 1.5 * sin(2 * M_PI * FDRIVE * t[i]) + gsl_ran_gaussian(r, 0.2);
	whale_dives(t, y, n, 0, &o, &w, NULL);
	CHECK("whale.sine.period", fabs(w.period - 45) < 0.05, "period %.4f s, %ld dives", w.period, w.dives);
	CHECK("whale.sine.top", fabs(w.top - (17 + 3 * cos(M_PI / 10))) < 0.05, "top %.4f", w.top);
	CHECK("whale.sine.depth", fabs(w.depth - 3 * (1 + cos(M_PI / 10))) < 0.1, "depth %.4f", w.depth);
	CHECK("whale.sine.rms", fabs(w.rms - 3 / sqrt(2)) < 0.05, "rms %.4f, want %.4f", w.rms, 3 / sqrt(2));
	whale_smooth(t, y, n, 1 / FDRIVE, ys);
	whale_spectrum(t, ys, n, FDRIVE, &sp);
	CHECK("whale.spec.sine_period", fabs(sp.period - 45) < 0.03 * 45 && !sp.edge && sp.share > 0.5,
	      "period %.3f s, edge %d, share %.3f", sp.period, sp.edge, sp.share);
	/* the window from t0 on: 300 s of the same sine */
	whale_dives(t, y, n, 300, &o, &w, NULL);
	CHECK("whale.window.from_t0", w.t0 >= 300 && w.t0 < 300.011 && fabs(w.period - 45) < 0.1 && w.dives >= 6,
	      "t0 %g, period %g, dives %ld", w.t0, w.period, w.dives);

	/* ---- at the top only: no dive, no period, rate 0 ---- */
	synth(t, y, n, s, 0, 0.3, r);
	whale_dives(t, y, n, 0, &o, &w, NULL);
	CHECK("whale.none.no_dive", w.dives == 0 && isnan(w.period) && isnan(w.depth) && w.rate == 0,
	      "%ld dives, period %g, depth %g, rate %g", w.dives, w.period, w.depth, w.rate);
	whale_spectrum(t, y, n, FDRIVE, &sp);
	CHECK("whale.none.spectrum_has_no_line", sp.share < 0.2, "share %.3f at %.3f s", sp.share, sp.period);

	/* ---- one dive: counted, its depth, but no period ---- */
	synth(t, y, n, s + 3, 1, 0.3, r);
	whale_dives(t, y, n, 0, &o, &w, NULL);
	CHECK("whale.one.no_period", w.dives == 1 && w.done == 1 && isnan(w.period) && fabs(w.depth - DEPTH) < 0.15,
	      "%ld dives, period %g, depth %g", w.dives, w.period, w.depth);

	/* ---- hysteresis: after one descent, y hovers around top - D (+-0.2 cm every
	 * 0.5 s, below top - D/2 all along): one dive, not one per crossing ---- */
	for (size_t i = 0; i < n; i++)
		y[i] = t[i] < 100 ? TOP : TOP - 2 + ((long)(t[i] / 0.5) % 2 ? 0.2 : -0.2);
	whale_dives(t, y, n, 0, &raw, &w, NULL);
	CHECK("whale.hysteresis.one_dive", w.dives == 1 && w.done == 0 && isnan(w.depth), "%ld dives, %ld ended",
	      w.dives, w.done);
	/* the same with a hysteresis band of zero would count each crossing: the levels */
	CHECK("whale.hysteresis.levels", w.lo == w.top - 2 && w.hi == w.top - 1, "lo %g hi %g top %g", w.lo, w.hi, w.top);

	/* ---- a dive under way when the window opens is not counted (start unknown) ---- */
	for (size_t i = 0; i < n; i++)
		y[i] = t[i] < 50 ? TOP - 5 : TOP;
	whale_dives(t, y, n, 0, &raw, &w, NULL);
	CHECK("whale.window.dive_under_way", w.dives == 0 && w.done == 0, "%ld dives", w.dives);
	CHECK("whale.window.too_short", whale_dives(t, y, n, DUR - 0.015, &raw, &w, NULL) == 1 && w.samples == 2,
	      "samples %zu", w.samples);

	/* ---- running mean, quantile, FFT size ---- */
	double tt[5] = {0, 1, 2, 3, 4}, yy[5] = {1, 2, 3, 4, 5}, sm[5];
	whale_smooth(tt, yy, 5, 2, sm);
	CHECK("whale.smooth.linear", sm[0] == 1.5 && sm[1] == 2 && sm[2] == 3 && sm[3] == 4 && sm[4] == 4.5,
	      "%g %g %g %g %g", sm[0], sm[1], sm[2], sm[3], sm[4]);
	CHECK("whale.quantile", whale_quantile(yy, 5, 0.9) == 4.6 && whale_quantile(yy, 5, 0.5) == 3, "q90 %g",
	      whale_quantile(yy, 5, 0.9));
	CHECK("whale.fft_size", whale_fft_size(7) == 8 && whale_fft_size(11) == 12 && whale_fft_size(60001) == 60750 &&
				       whale_fft_size(60000) == 60000, "%zu %zu %zu", whale_fft_size(7),
	      whale_fft_size(11), whale_fft_size(60001));

	/* ---- statistics over runs ---- */
	double x5[5] = {1, 2, 3, 4, 5}, y5[5] = {2, 1, 4, 3, 5}, rk[5];
	whale_trend tr;
	/* 1 - 6 sum d^2 / (n (n^2 - 1)) = 1 - 6 * 4 / 120 */
	CHECK("whale.spearman.untied", whale_spearman(x5, y5, 5, 0, 1, &tr) == 0 && fabs(tr.rho - 0.8) < 1e-12,
	      "rho %g", tr.rho);
	double tie[4] = {3, 1, 3, 7};
	whale_ranks(tie, 4, rk);
	CHECK("whale.ranks.mid", rk[0] == 2.5 && rk[1] == 1 && rk[2] == 2.5 && rk[3] == 4, "%g %g %g %g", rk[0], rk[1],
	      rk[2], rk[3]);
	/* ties in x as bin/whale has them (many runs per R): x = 2 2 2 3 3 3 4 4 4, y rising
	 * with noise; Pearson's correlation of the mid-ranks, computed apart (a few lines of
	 * Python with its own ranking), is 0.8959787 */
	double xr[9] = {2, 2, 2, 3, 3, 3, 4, 4, 4}, yr[9] = {10, 12, 15, 13, 17, 16, 18, 21, 19};
	whale_spearman(xr, yr, 9, 4000, 3, &tr);
	CHECK("whale.spearman.tied", fabs(tr.rho - 0.8959787) < 1e-6, "rho %.7f", tr.rho);
	CHECK("whale.spearman.p_small", tr.p < 0.02 && tr.p > 0 && tr.n == 9, "p %g", tr.p);
	double yflat[9] = {5, 1, 9, 4, 8, 2, 6, 3, 7};
	whale_spearman(xr, yflat, 9, 4000, 3, &tr);
	CHECK("whale.spearman.no_trend", fabs(tr.rho) < 0.3 && tr.p > 0.4, "rho %g p %g", tr.rho, tr.p);
	double same[9] = {4, 4, 4, 4, 4, 4, 4, 4, 4};
	whale_spearman(xr, same, 9, 100, 3, &tr);
	CHECK("whale.spearman.constant", isnan(tr.rho) && isnan(tr.p), "rho %g", tr.rho);
	whale_spearman(xr, yr, 2, 100, 3, &tr);
	CHECK("whale.spearman.too_few", isnan(tr.rho), "rho %g", tr.rho);
	whale_ci ci;
	whale_mean_ci(same, 9, 500, 1, 0.95, &ci);
	CHECK("whale.ci.constant", ci.mean == 4 && ci.lo == 4 && ci.hi == 4 && ci.n == 9, "%g [%g, %g]", ci.mean, ci.lo,
	      ci.hi);
	whale_mean_ci(yr, 9, 2000, 1, 0.95, &ci);
	CHECK("whale.ci.covers_mean", ci.lo < ci.mean && ci.mean < ci.hi && ci.hi - ci.lo < 6, "%g [%g, %g]", ci.mean,
	      ci.lo, ci.hi);
	whale_mean_ci(yr, 1, 500, 1, 0.95, &ci);
	CHECK("whale.ci.one_run", ci.mean == 10 && isnan(ci.lo) && isnan(ci.hi), "%g [%g, %g]", ci.mean, ci.lo, ci.hi);

	/* ---- a run file end to end: risen at 40 s, skip 20 s: the window from 60 s ---- */
	char path[] = "/tmp/an_whale_XXXXXX";
	int fd = mkstemp(path);
	close(fd);
	synth(t, y, n, s, ns, 0.3, r);
	write_run(path, t, y, n, 1, 40, 2, 1);
	whale_obs ob;
	sb_err e = {0};
	const whale_cfg cfg = {20, NAN, 1, 0.9};
	size_t in_window = 0;
	for (size_t k = 0; k < ns; k++)
		in_window += s[k] + 10 / M_PI * asin(1.0 / 3) >= 60 + 2; /* + the running mean's lead, and not in a dive at 60 s */
	CHECK("whale.read.ok", whale_read(path, &cfg, &ob, &e) == 0 && ob.status == WHALE_OK, "%s status %s", e.msg,
	      whale_status_name(ob.status));
	CHECK("whale.read.window", fabs(ob.run.t0 - 60) < 0.011 && fabs(ob.run.t1 - DUR) < 1e-9 && ob.dive == 2 &&
					   fabs(ob.drive_f - FDRIVE) < 1e-12,
	      "window %g .. %g, D %g, f %g", ob.run.t0, ob.run.t1, ob.dive, ob.drive_f);
	CHECK("whale.read.box_frame_dives", ob.run.dives == (long)in_window && fabs(ob.run.depth - DEPTH) < 0.15,
	      "%ld dives (want %zu), depth %g", ob.run.dives, in_window, ob.run.depth);
	CHECK("whale.read.spectrum", isfinite(ob.spec.period), "spectral period %g", ob.spec.period);
	double *tr_t, *tr_y;
	size_t tn;
	CHECK("whale.trace.one_per_period", whale_trace(path, 60, 1 / FDRIVE, &tr_t, &tr_y, &tn, &e) == 0 &&
						   labs((long)tn - (long)((DUR - 60) * FDRIVE)) <= 2,
	      "%zu points", tn);
	free(tr_t);
	free(tr_y);
	/* the dive threshold in cm instead of radii */
	const whale_cfg cm = {20, 3, 1, 0.9};
	whale_read(path, &cm, &ob, &e);
	CHECK("whale.read.dive_in_cm", ob.dive == 3, "D %g", ob.dive);
	/* never rose: listed as such, not analysed */
	write_run(path, t, y, n, 0, DUR, 2, 1);
	CHECK("whale.read.not_risen", whale_read(path, &cfg, &ob, &e) == 0 && ob.status == WHALE_NOT_RISEN && !ob.risen,
	      "status %s", whale_status_name(ob.status));
	/* rose, no trajectory (traj_rate = 0) */
	write_run(path, t, y, n, 1, 40, 2, 0);
	CHECK("whale.read.no_trajectory", whale_read(path, &cfg, &ob, &e) == 0 && ob.status == WHALE_NO_TRAJ,
	      "status %s", whale_status_name(ob.status));
	/* rose 3 s before the end: the window after the skip is empty */
	write_run(path, t, y, n, 1, DUR - 3, 2, 1);
	CHECK("whale.read.too_short", whale_read(path, &cfg, &ob, &e) == 0 && ob.status == WHALE_SHORT, "status %s",
	      whale_status_name(ob.status));
	/* a file without the rise's attributes is an error, not a run that did not rise */
	hid_t f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
	H5Fclose(f);
	sb_err e2 = {0};
	CHECK("whale.read.no_attributes", whale_read(path, &cfg, &ob, &e2) != 0 && strstr(e2.msg, "risen"), "%s",
	      e2.msg);
	unlink(path);
	sb_err e3 = {0};
	CHECK("whale.read.missing_file", whale_read(path, &cfg, &ob, &e3) == SB_EIO, "%s", e3.msg);

	free(ys);
	free(t);
	free(y);
	gsl_rng_free(r);
	return tl_done();
}
