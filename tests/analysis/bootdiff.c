/* bootdiff.c - a difference between two groups' onsets from their bootstraps, both
 * ways: synthetic sigmoid onsets at 2.8 and 2.9 Hz (6 seeds each, little noise) give a
 * difference near 0.1 whose interval excludes 0; two groups at the same onset give an
 * interval that holds 0 in most trials; the pairing makes equal replicates of one group a zero-width
 * difference only when the draws coincide (they must not). Replicates known within
 * bounds (bootdiff_bounds): exact ones give bootdiff_run's interval to the bit, a tenth
 * unbounded above leaves the upper limit unbounded and the lower one where the known
 * ends put it, both ways round. */
#include <gsl/gsl_randist.h>
#include <math.h>

#include "boot.h"
#include "measure/bootdiff.h"
#include "measure/onsetfit.h"
#include "testlib.h"

enum { NF = 13, NS = 6, B = 300 };

static void synth(gsl_rng *r, double x0, double *x, double *y, long *u)
{
	for (int s = 0; s < NS; s++)
		for (int i = 0; i < NF; i++) {
			const int k = s * NF + i;
			x[k] = 2.5 + 0.05 * i;
			y[k] = 10 / (1 + exp(-(x[k] - x0) / 0.03)) + gsl_ran_gaussian(r, 0.8);
			u[k] = s;
		}
}

/* the onset difference b - a of two synthetic groups at x0a and x0b (threshold crossing) */
static int diff(gsl_rng *g, double x0a, double x0b, bootdiff_res *d)
{
	double x[NS * NF], y[NS * NF];
	long u[NS * NF];
	onset_res a, b;
	synth(g, x0a, x, y, u);
	if (onset_estimate(x, y, u, NS * NF, NAN, B, 1, 0.95, &a))
		return -1;
	synth(g, x0b, x, y, u);
	if (onset_estimate(x, y, u, NS * NF, NAN, B, 1, 0.95, &b))
		return -1;
	const int rc = a.B == B && b.B == B ? bootdiff_run(a.thr, b.thr, a.boot + B, b.boot + B, B, 0.95, d) : -1;
	onset_res_free(&a);
	onset_res_free(&b);
	return rc;
}

int main(void)
{
	gsl_rng *g = boot_rng(7);
	bootdiff_res d;
	int rc = diff(g, 2.8, 2.9, &d);
	CHECK("bootdiff.shifted.excludes_zero", !rc && fabs(d.d - 0.1) < 0.03 && d.zero == 0 && d.lo > 0 &&
							d.ok > B * 9 / 10,
	      "rc %d d %g [%g, %g] ok %zu", rc, d.d, d.lo, d.hi, d.ok);
	/* equal onsets: the interval holds 0 in about 95 % of 20 trials (at least 16 holds
	 * 99.6 %), and is never a point */
	int hold = 0, wide = 1;
	for (int t = 0; t < 20 && !rc; t++) {
		rc = diff(g, 2.8, 2.8, &d);
		hold += d.zero == 1;
		wide &= d.hi > d.lo;
	}
	CHECK("bootdiff.equal.holds_zero", !rc && hold >= 16 && wide, "rc %d: %d of 20 hold 0", rc, hold);
	/* the same replicates on both sides: paired at an offset, not draw for draw */
	double r[B];
	for (int k = 0; k < B; k++)
		r[k] = k;
	rc = bootdiff_run(0, 0, r, r, B, 0.95, &d);
	CHECK("bootdiff.pairing_offset", !rc && d.hi - d.lo > 100 && d.zero == 1, "[%g, %g]", d.lo, d.hi);
	rc = bootdiff_run(1, 2, NULL, r, B, 0.95, &d);
	CHECK("bootdiff.no_replicates", !rc && d.d == 1 && d.zero == -1 && isnan(d.lo), "d %g zero %d", d.d, d.zero);

	/* bounds equal to the values: bootdiff_run's interval, bit for bit */
	double sa[B], sb[B];
	for (int k = 0; k < B; k++) {
		sa[k] = sin(k);
		sb[k] = 0.3 + cos(3.0 * k);
	}
	bootdiff_res e;
	rc = bootdiff_run(0.1, 0.4, sa, sb, B, 0.9, &d) || bootdiff_bounds(0.1, 0.4, sa, sa, sb, sb, B, 0.9, &e);
	CHECK("bootdiff.bounds.exact_is_run", !rc && d.lo == e.lo && d.hi == e.hi && d.ok == e.ok && d.zero == e.zero &&
						      d.d == e.d,
	      "[%g, %g] %zu against [%g, %g] %zu", d.lo, d.hi, d.ok, e.lo, e.hi, e.ok);
	/* a exactly 0; b's replicate k at 1 + k/100, the last tenth known only to exceed
	 * it: lower limit the 5 % quantile of 1..1.99 (1.0495), upper unbounded, 0 excluded */
	enum { C = 100 };
	double z0[C], lb[C], hb[C];
	for (int k = 0; k < C; k++) {
		z0[k] = 0;
		lb[k] = 1 + k / 100.0;
		hb[k] = k >= 90 ? INFINITY : lb[k];
	}
	rc = bootdiff_bounds(0, NAN, z0, z0, lb, hb, C, 0.9, &d);
	CHECK("bootdiff.bounds.upper_unbounded", !rc && fabs(d.lo - 1.0495) < 1e-9 && isinf(d.hi) && d.hi > 0 &&
							 d.zero == 0 && d.ok == C && isnan(d.d),
	      "d %g [%g, %g] zero %d ok %zu", d.d, d.lo, d.hi, d.zero, d.ok);
	/* the other way round (a bounded, b exactly 0): the mirror image */
	rc = bootdiff_bounds(NAN, 0, lb, hb, z0, z0, C, 0.9, &d);
	CHECK("bootdiff.bounds.lower_unbounded", !rc && fabs(d.hi + 1.0495) < 1e-9 && isinf(d.lo) && d.lo < 0 &&
							 d.zero == 0,
	      "[%g, %g] zero %d", d.lo, d.hi, d.zero);
	/* every b replicate only known to exceed 0.5, a exactly 1: [-0.5, +inf] holds 0 */
	for (int k = 0; k < C; k++) {
		lb[k] = 0.5;
		hb[k] = INFINITY;
		z0[k] = 1;
	}
	rc = bootdiff_bounds(1, NAN, z0, z0, lb, hb, C, 0.95, &d);
	CHECK("bootdiff.bounds.censored_holds_zero", !rc && d.lo == -0.5 && isinf(d.hi) && d.zero == 1,
	      "[%g, %g] zero %d", d.lo, d.hi, d.zero);
	gsl_rng_free(g);
	return tl_done();
}
