/* ring.c - claim 3's ratio with/without intruder and its bootstrap interval on
 * synthetic data with a known answer: exact ratios, constant sets (no spread), the
 * mean alone, a zero mean below the line, one draw sequence for every quantity, the
 * seed, the interval's width against the delta method's standard error, and its
 * coverage of a known ratio over many synthetic experiments. */
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <string.h>

#include "measure/ring.h"
#include "testlib.h"

/* n draws of N(mu, sd) */
static void normal(gsl_rng *r, double *x, size_t n, double mu, double sd)
{
	for (size_t i = 0; i < n; i++)
		x[i] = mu + gsl_ran_gaussian(r, sd);
}

static void mean_sd(const double *x, size_t n, double *m, double *s)
{
	double a = 0, b = 0;
	for (size_t i = 0; i < n; i++)
		a += x[i];
	a /= (double)n;
	for (size_t i = 0; i < n; i++)
		b += (x[i] - a) * (x[i] - a);
	*m = a;
	*s = sqrt(b / (double)(n - 1));
}

int main(void)
{
	ring_est e[2], f[2];

	/* a known ratio: (1.1 + 1.2 + 1.3) / 3 over 1 */
	const double w1[3] = {1.1, 1.2, 1.3}, n1[3] = {1, 1, 1};
	CHECK("ring.ratio.ok", ring_ratio(w1, 3, n1, 3, 1, 1000, 1, 0.95, e) == 0, "failed");
	CHECK_REL("ring.ratio.value", e[0].value, 1.2, 1e-15);
	CHECK("ring.ratio.interval_in_range", e[0].lo >= 1.1 - 1e-15 && e[0].hi <= 1.3 + 1e-15 && e[0].lo < 1.2 &&
						    e[0].hi > 1.2 && e[0].ok == 1000,
	      "[%g, %g] of %zu", e[0].lo, e[0].hi, e[0].ok);

	/* no spread: the interval is the point */
	const double w2[4] = {2, 2, 2, 2}, n2[2] = {1.6, 1.6};
	ring_ratio(w2, 4, n2, 2, 1, 200, 1, 0.95, e);
	CHECK("ring.ratio.constant", fabs(e[0].value - 1.25) < 1e-15 && fabs(e[0].lo - 1.25) < 1e-15 &&
					     fabs(e[0].hi - 1.25) < 1e-15,
	      "%g [%g, %g]", e[0].value, e[0].lo, e[0].hi);

	/* no reference: the mean and its interval */
	ring_ratio(w1, 3, NULL, 0, 1, 1000, 1, 0.95, e);
	CHECK("ring.mean.value", fabs(e[0].value - 1.2) < 1e-15 && e[0].lo >= 1.1 - 1e-15 && e[0].hi <= 1.3 + 1e-15,
	      "%g [%g, %g]", e[0].value, e[0].lo, e[0].hi);

	/* a zero mean below the line: no ratio, no interval */
	const double z[2] = {0, 0};
	ring_ratio(w1, 3, z, 2, 1, 100, 1, 0.95, e);
	CHECK("ring.ratio.zero_reference", isnan(e[0].value) && isnan(e[0].lo) && e[0].ok == 0, "%g ok %zu",
	      e[0].value, e[0].ok);
	/* no runs with the intruder: NaN */
	ring_ratio(w1, 0, n1, 3, 1, 100, 1, 0.95, e);
	CHECK("ring.ratio.no_runs", isnan(e[0].value) && isnan(e[0].lo), "%g", e[0].value);

	/* synthetic runs: 1.15 +- 0.05 with, 1 +- 0.05 without */
	gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(r, 2026);
	enum { N = 400 };
	static double w[2 * N], n[2 * N];
	normal(r, w, N, 1.15, 0.05);
	normal(r, n, N, 1.0, 0.05);
	for (int i = 0; i < N; i++) { /* quantity 1: quantity 0 scaled, so its ratio is the same */
		w[N + i] = 3 * w[i];
		n[N + i] = 3 * n[i];
	}
	ring_ratio(w, N, n, N, 2, 2000, 7, 0.95, e);
	double mw, sw, mn, sn;
	mean_sd(w, N, &mw, &sw);
	mean_sd(n, N, &mn, &sn);
	CHECK_REL("ring.ratio.synthetic_value", e[0].value, mw / mn, 1e-14);
	CHECK("ring.ratio.synthetic_near_truth", fabs(e[0].value - 1.15) < 0.01, "%g", e[0].value);
	/* the delta method: se(mw / mn) = (mw / mn) sqrt(sw^2 / (N mw^2) + sn^2 / (N mn^2)) */
	const double se = mw / mn * sqrt(sw * sw / (N * mw * mw) + sn * sn / (N * mn * mn));
	const double half = 0.5 * (e[0].hi - e[0].lo);
	CHECK("ring.ratio.width_as_delta_method", half > 0.85 * 1.96 * se && half < 1.15 * 1.96 * se,
	      "half-width %g, 1.96 se %g", half, 1.96 * se);
	CHECK("ring.ratio.one_draw_sequence", fabs(e[1].value - e[0].value) < 1e-14 && fabs(e[1].lo - e[0].lo) < 1e-14 &&
						      fabs(e[1].hi - e[0].hi) < 1e-14,
	      "scaled quantity %g [%g, %g] vs %g [%g, %g]", e[1].value, e[1].lo, e[1].hi, e[0].value, e[0].lo, e[0].hi);
	ring_ratio(w, N, n, N, 2, 2000, 7, 0.95, f);
	CHECK("ring.ratio.reproducible", memcmp(e, f, sizeof e) == 0, "same seed, different result");
	ring_ratio(w, N, n, N, 2, 2000, 8, 0.95, f);
	CHECK("ring.ratio.seed_matters", f[0].lo != e[0].lo || f[0].hi != e[0].hi, "seeds 7 and 8 gave the same interval");

	/* coverage: 300 experiments of 30 runs each side, true ratio 1.15; a 95 % interval
	 * holds it in about 95 % of them (the percentile bootstrap runs a little narrow
	 * at n = 30: accept 88-99 %) */
	int hit = 0;
	enum { E = 300, M = 30 };
	for (int x = 0; x < E; x++) {
		normal(r, w, M, 1.15, 0.1);
		normal(r, n, M, 1.0, 0.1);
		ring_ratio(w, M, n, M, 1, 400, (unsigned long)x + 1, 0.95, e);
		hit += e[0].lo <= 1.15 && 1.15 <= e[0].hi;
	}
	CHECK("ring.ratio.coverage", hit >= 0.88 * E && hit <= 0.99 * E, "%d of %d intervals hold the true ratio", hit, E);
	gsl_rng_free(r);
	return tl_done();
}
