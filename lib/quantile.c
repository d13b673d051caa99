/* quantile.c - normal and Student t quantiles, Clopper-Pearson (quantile.h). */
#include "quantile.h"

#include <gsl/gsl_cdf.h>
#include <math.h>

double quant_normal(double level)
{
	return gsl_cdf_ugaussian_Pinv(0.5 + 0.5 * level);
}

double quant_student(double level, double df)
{
	return gsl_cdf_tdist_Pinv(0.5 + 0.5 * level, df);
}

void quant_clopper_pearson(long k, long n, double level, double *lo, double *hi)
{
	if (n < 1 || k < 0 || k > n || !(level > 0 && level < 1)) {
		*lo = *hi = NAN;
		return;
	}
	/* the beta quantiles of the binomial tails */
	const double a = 1 - level;
	*lo = k ? gsl_cdf_beta_Pinv(a / 2, (double)k, (double)(n - k + 1)) : 0;
	*hi = k < n ? gsl_cdf_beta_Pinv(1 - a / 2, (double)(k + 1), (double)(n - k)) : 1;
}
