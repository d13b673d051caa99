/* onset.c - onset detection on synthetic sigmoid data with a known midpoint and
 * Gaussian noise: the fit recovers the midpoint, the threshold crossing is close,
 * the bootstrap interval over seeds covers the true midpoint in most trials and
 * excludes a wrong one; degenerate input fails cleanly. */
#include <gsl/gsl_randist.h>
#include <math.h>

#include "boot.h"
#include "measure/onsetfit.h"
#include "testlib.h"

enum { NF = 13, NS = 6 };

/* seeds x frequencies 2.5 .. 3.1 of  phi = 10 / (1 + exp(-(f - 2.8) / 0.03)) + noise */
static void synth(gsl_rng *r, double sigma, double x0, double *x, double *y, long *u)
{
	for (int s = 0; s < NS; s++)
		for (int i = 0; i < NF; i++) {
			int k = s * NF + i;
			x[k] = 2.5 + 0.05 * i;
			y[k] = 10 / (1 + exp(-(x[k] - x0) / 0.03)) + gsl_ran_gaussian(r, sigma);
			u[k] = 100 + s;
		}
}

int main(void)
{
	double x[NS * NF], y[NS * NF];
	long u[NS * NF];
	gsl_rng *r = boot_rng(2024);

	/* noiseless: the fit is exact */
	synth(r, 0, 2.8, x, y, u);
	sig_fit f;
	CHECK("onset.fit.noiseless.ok", sig_fit_data(x, y, NS * NF, &f), "fit failed");
	CHECK("onset.fit.noiseless.x0", fabs(f.x0 - 2.8) < 1e-6 && fabs(f.a - 10) < 1e-5 && fabs(f.w - 0.03) < 1e-6,
	      "x0 %.9g a %.9g w %.9g", f.x0, f.a, f.w);
	/* decreasing step: the same midpoint, negative step */
	for (int k = 0; k < NS * NF; k++)
		y[k] = -y[k];
	CHECK("onset.fit.falling", sig_fit_data(x, y, NS * NF, &f) && fabs(f.x0 - 2.8) < 1e-6 && f.a < 0,
	      "x0 %g a %g", f.x0, f.a);
	CHECK("onset.threshold.falling", fabs(sig_threshold(x, y, NS * NF, NAN) - 2.8) < 0.01, "threshold %g",
	      sig_threshold(x, y, NS * NF, NAN));

	/* noisy trials: sigma = 1.5 (15 % of the step) */
	int trials = 12, cover = 0, excl = 0, fitok = 0, throk = 0;
	double worst = 0;
	for (int t = 0; t < trials; t++) {
		synth(r, 1.5, 2.8, x, y, u);
		onset_res o;
		if (onset_estimate(x, y, u, NS * NF, NAN, 200, 1000 + (unsigned long)t, 0.95, &o))
			break;
		fitok += o.fit.ok && fabs(o.fit.x0 - 2.8) < 0.03;
		worst = fmax(worst, fabs(o.fit.x0 - 2.8));
		throk += fabs(o.thr - 2.8) < 0.05;
		cover += o.fit_lo <= 2.8 && 2.8 <= o.fit_hi;
		excl += !(o.fit_lo <= 2.9 && 2.9 <= o.fit_hi);
		if (t == 0) {
			CHECK("onset.units_are_seeds", o.units == NS && o.boot_ok > 150, "units %zu boot ok %zu", o.units, o.boot_ok);
			onset_res o2;
			onset_estimate(x, y, u, NS * NF, NAN, 200, 1000, 0.95, &o2);
			CHECK("onset.bootstrap.reproducible", o2.fit_lo == o.fit_lo && o2.fit_hi == o.fit_hi &&
				  o2.thr_lo == o.thr_lo, "[%.17g, %.17g] vs [%.17g, %.17g]", o.fit_lo, o.fit_hi, o2.fit_lo, o2.fit_hi);
			CHECK("onset.seed_sd", isfinite(o.seed_sd) && o.seed_sd < 0.1, "sd of per-seed thresholds %g", o.seed_sd);
			onset_res_free(&o2);
		}
		onset_res_free(&o);
	}
	CHECK("onset.fit.noisy.accurate", fitok == trials, "%d of %d fits within 0.03 Hz (worst %.3g)", fitok, trials, worst);
	CHECK("onset.threshold.noisy.accurate", throk >= trials - 1, "%d of %d threshold estimates within 0.05 Hz", throk,
	      trials);
	/* a 95 % interval: allow 2 misses in 12 (P(>2 misses) ~ 2 % at nominal coverage) */
	CHECK("onset.ci.covers_truth", cover >= trials - 2, "true midpoint inside the interval in %d of %d trials", cover,
	      trials);
	CHECK("onset.ci.excludes_wrong", excl == trials, "2.9 Hz excluded in only %d of %d trials", excl, trials);

	/* too few points, flat data: no fit, no crash */
	CHECK("onset.fit.too_few", !sig_fit_data(x, y, 4, &f), "fitted 4 points");
	double fx[6] = {1, 2, 3, 4, 5, 6}, fy[6] = {1, 1, 1, 1, 1, 1};
	CHECK("onset.threshold.flat", isnan(sig_threshold(fx, fy, 6, NAN)), "a flat curve crossed its threshold");

	/* Search data: three replicates, each its own bisection between 2.5 and 2.8 Hz with
	 * the threshold 2 (off below it, on above). Replicate A visited 2.6375 once and was
	 * on there (Phi 2.08); B and C cross near 2.67 and 2.69. The pooled means' first
	 * crossing lands on A's lone run; the median of the replicates' own crossings
	 * does not. Known answer: each replicate's crossing by linear interpolation
	 * between its last off and first on run, the median the middle one's. */
	{
		const double sx[] = {2.5, 2.8, 2.65, 2.575, 2.6125, 2.6375, /* A */
				     2.5, 2.8, 2.65, 2.725, 2.6875, 2.66875, /* B */
				     2.5, 2.8, 2.65, 2.725, 2.6875, 2.70625}; /* C */
		const double sy[] = {0.1, 9, 3, 0.2, 0.4, 2.08, /* A: on at 2.6375 */
				     0.1, 9, 1.0, 7, 2.5, 1.9,    /* B: off 2.66875, on 2.6875 */
				     0.1, 9, 0.5, 6, 1.5, 2.2};   /* C: off 2.6875, on 2.70625 */
		const long su[] = {1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 2, 2, 3, 3, 3, 3, 3, 3};
		onset_res o;
		CHECK("onset.search.estimated", !onset_estimate(sx, sy, su, 18, 2.0, 400, 7, 0.95, &o), "failed");
		/* B: off 1.9 at 2.66875, on 2.5 at 2.6875: 2.66875 + 0.01875 * 0.1 / 0.6 */
		const double b = 2.66875 + 0.01875 * (2.0 - 1.9) / (2.5 - 1.9);
		CHECK("onset.search.per_unit", o.per_unit == 1, "per_unit %d", o.per_unit);
		CHECK_REL("onset.search.median_of_replicates", o.thr, b, 1e-12);
		/* the pooled means' first crossing: at or below A's lone run, the old answer */
		const double pooled = sig_threshold(sx, sy, 18, 2.0);
		CHECK("onset.search.pooled_would_land_low", pooled <= 2.6375 + 1e-9 && o.thr > pooled + 0.02,
		      "pooled %g, per replicate %g", pooled, o.thr);
		CHECK("onset.search.interval_holds_it", o.thr_lo <= o.thr && o.thr <= o.thr_hi && o.thr_lo >= 2.6 &&
							       o.thr_hi <= 2.71,
		      "[%g, %g]", o.thr_lo, o.thr_hi);
		onset_res_free(&o);
		/* the same data on a common grid (every replicate at every frequency): the
		 * pooled crossing, as before */
		double gx[18], gy[18];
		long gu[18];
		for (int k = 0; k < 18; k++)
			gx[k] = 2.5 + 0.05 * (k % 6), gy[k] = gx[k] < 2.66 ? 0.5 : 5, gu[k] = 1 + k / 6;
		CHECK("onset.grid.estimated", !onset_estimate(gx, gy, gu, 18, 2.0, 0, 7, 0.95, &o), "failed");
		CHECK("onset.grid.pooled", o.per_unit == 0 && o.thr == sig_threshold(gx, gy, 18, 2.0), "per_unit %d thr %g",
		      o.per_unit, o.thr);
		onset_res_free(&o);
	}
	gsl_rng_free(r);
	return tl_done();
}
