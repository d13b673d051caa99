/* powerfit.c - the power-law fit with known answers both ways: exact power laws give
 * p and c to rounding; synthetic onsets f = 5 A^-0.5 with log-normal noise of known
 * sigma and intervals of that width recover p = -0.5 inside the interval (covariance and
 * bootstrap over replicates), exclude p = -1, and hold the true p in about the level's
 * share of trials; a v-like law (p = -1) excludes -0.5; degenerate input fails. */
#include <gsl/gsl_randist.h>
#include <math.h>

#include "boot.h"
#include "measure/powerfit.h"
#include "quantile.h"
#include "testlib.h"

enum { NA = 4, B = 400 };
static const double AMP[NA] = {0.5, 1, 2, 3};

/* y_i = c A_i^p e^(s eps), its interval at 0.95 of log-width 2 z s, and B replicates
 * around it of the same spread */
static void synth(gsl_rng *r, double c, double p, double s, double *y, double *lo, double *hi, double *rep)
{
	const double z = quant_normal(0.95);
	for (int i = 0; i < NA; i++) {
		y[i] = c * pow(AMP[i], p) * exp(s * gsl_ran_gaussian(r, 1));
		lo[i] = y[i] * exp(-z * s);
		hi[i] = y[i] * exp(z * s);
		for (int b = 0; b < B; b++)
			rep[i * B + b] = y[i] * exp(s * gsl_ran_gaussian(r, 1));
	}
}

int main(void)
{
	double y[NA], lo[NA], hi[NA], rep[NA * B];
	powerfit_res f;
	gsl_rng *r = boot_rng(26);

	/* exact laws: p and c to rounding, unweighted and weighted */
	for (int i = 0; i < NA; i++)
		y[i] = 5 * pow(AMP[i], -0.5);
	CHECK("powerfit.exact.unweighted", !powerfit_fit(AMP, y, NULL, NULL, NA, 0.95, &f) && !f.weighted &&
					     fabs(f.p + 0.5) < 1e-12 && fabs(f.c - 5) < 1e-12 && f.n == NA,
	      "p %.15g c %.15g weighted %d", f.p, f.c, f.weighted);
	for (int i = 0; i < NA; i++)
		lo[i] = 0.9 * y[i], hi[i] = 1.1 * y[i];
	CHECK("powerfit.exact.weighted", !powerfit_fit(AMP, y, lo, hi, NA, 0.95, &f) && f.weighted &&
					   fabs(f.p + 0.5) < 1e-12 && f.chi2 < 1e-20,
	      "p %.15g weighted %d chi2 %g", f.p, f.weighted, f.chi2);
	/* an interval without width: no weights, said so */
	hi[2] = lo[2];
	CHECK("powerfit.zero_width_unweighted", !powerfit_fit(AMP, y, lo, hi, NA, 0.95, &f) && !f.weighted,
	      "weighted %d", f.weighted);
	CHECK("powerfit.sigma", fabs(powerfit_sigma(1, exp(2 * quant_normal(0.95)), 0.95) - 1) < 1e-12 &&
					isnan(powerfit_sigma(1, 1, 0.95)) && isnan(powerfit_sigma(-1, 2, 0.95)),
	      "sigma %g", powerfit_sigma(1, exp(2 * quant_normal(0.95)), 0.95));

	/* one noisy study: p = -0.5 inside both intervals, the v law's -1 outside */
	synth(r, 5, -0.5, 0.03, y, lo, hi, rep);
	int rc = powerfit_fit(AMP, y, lo, hi, NA, 0.95, &f) || powerfit_boot(AMP, lo, hi, rep, NA, B, 0.95, &f);
	CHECK("powerfit.gamma_law.recovered", !rc && f.weighted && f.cov_lo < -0.5 && f.cov_hi > -0.5 &&
						f.boot_lo < -0.5 && f.boot_hi > -0.5 && f.boot_ok == B,
	      "p %g cov [%g, %g] boot [%g, %g] ok %zu", f.p, f.cov_lo, f.cov_hi, f.boot_lo, f.boot_hi, f.boot_ok);
	CHECK("powerfit.gamma_law.excludes_velocity", powerfit_excludes(&f, -1) == 1 && powerfit_excludes(&f, -0.5) == 0,
	      "p %g [%g, %g]", f.p, f.boot_lo, f.boot_hi);
	/* the other way round: a velocity law excludes the Gamma exponent */
	synth(r, 5, -1, 0.03, y, lo, hi, rep);
	rc = powerfit_fit(AMP, y, lo, hi, NA, 0.95, &f) || powerfit_boot(AMP, lo, hi, rep, NA, B, 0.95, &f);
	CHECK("powerfit.velocity_law.excludes_gamma", !rc && powerfit_excludes(&f, -0.5) == 1 &&
							    powerfit_excludes(&f, -1) == 0,
	      "p %g [%g, %g]", f.p, f.boot_lo, f.boot_hi);

	/* coverage: the covariance interval holds the true p in about 95 % of 200 studies
	 * (binomial: 181..198 holds 99.9 %) */
	int cover = 0;
	for (int t = 0; t < 200; t++) {
		synth(r, 5, -0.5, 0.05, y, lo, hi, rep);
		cover += !powerfit_fit(AMP, y, lo, hi, NA, 0.95, &f) && f.cov_lo <= -0.5 && f.cov_hi >= -0.5;
	}
	CHECK("powerfit.coverage", cover >= 181 && cover <= 198, "%d of 200", cover);

	/* degenerate: one point, or two at the same x, or non-positive values */
	const double one[2] = {2, 2}, neg[2] = {-1, 0};
	CHECK("powerfit.degenerate", powerfit_fit(AMP, y, NULL, NULL, 1, 0.95, &f) == -1 &&
					     powerfit_fit(one, y, NULL, NULL, 2, 0.95, &f) == -1 &&
					     powerfit_fit(AMP, neg, NULL, NULL, 2, 0.95, &f) == -1 && f.n == 0 &&
					     powerfit_excludes(&f, -1) == -1,
	      "n %zu", f.n);
	gsl_rng_free(r);
	return tl_done();
}
