/* whalestat.c - bootstrap means and Spearman's trend with a permutation p (whalestat.h). */
#include "whalestat.h"

#include <gsl/gsl_randist.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>

#include "boot.h"

static void mean_stat(void *ctx, const size_t *idx, size_t n, double *out)
{
	const double *v = ctx;
	double s = 0;
	for (size_t i = 0; i < n; i++)
		s += v[idx[i]];
	out[0] = n ? s / (double)n : NAN;
}

int whale_mean_ci(const double *v, size_t n, size_t B, unsigned long seed, double level, whale_ci *out)
{
	*out = (whale_ci){n ? gsl_stats_mean(v, 1, n) : NAN, NAN, NAN, n};
	if (n < 2 || B < 2)
		return 0;
	double *rep = malloc(sizeof *rep * B);
	if (!rep || boot_run(seed, n, B, 1, mean_stat, (void *)v, rep)) {
		free(rep);
		return -1;
	}
	boot_percentile(rep, B, level, &out->lo, &out->hi);
	free(rep);
	return 0;
}

int whale_ranks(const double *v, size_t n, double *r)
{
	size_t *p = malloc(sizeof *p * (n ? n : 1));
	if (!p)
		return -1;
	gsl_sort_index(p, v, 1, n);
	for (size_t i = 0; i < n;) {
		size_t j = i + 1;
		while (j < n && v[p[j]] == v[p[i]])
			j++;
		const double mid = 0.5 * (double)(i + 1 + j); /* the mean of ranks i+1 .. j */
		for (size_t k = i; k < j; k++)
			r[p[k]] = mid;
		i = j;
	}
	free(p);
	return 0;
}

/* Pearson's correlation; NaN when either has no spread */
static double pearson(const double *a, const double *b, size_t n)
{
	const double sa = gsl_stats_sd(a, 1, n), sb = gsl_stats_sd(b, 1, n);
	if (!(sa > 0) || !(sb > 0))
		return NAN;
	return gsl_stats_correlation(a, 1, b, 1, n);
}

int whale_spearman(const double *x, const double *y, size_t n, size_t B, unsigned long seed, whale_trend *out)
{
	*out = (whale_trend){NAN, NAN, n, B};
	if (n < 3)
		return 0;
	double *rx = malloc(sizeof *rx * n), *ry = malloc(sizeof *ry * n);
	int rc = rx && ry && !whale_ranks(x, n, rx) && !whale_ranks(y, n, ry) ? 0 : -1;
	if (!rc)
		out->rho = pearson(rx, ry, n);
	if (!rc && isfinite(out->rho) && B > 0) {
		gsl_rng *r = boot_rng(seed);
		if (!r)
			rc = -1;
		size_t ge = 0;
		for (size_t b = 0; !rc && b < B; b++) {
			gsl_ran_shuffle(r, ry, n, sizeof *ry);
			/* a tolerance, so that a permutation equal to the data in rho counts as
			 * at least as extreme despite rounding */
			ge += fabs(pearson(rx, ry, n)) >= fabs(out->rho) - 1e-12;
		}
		if (!rc)
			out->p = (1.0 + (double)ge) / (1.0 + (double)B);
		if (r)
			gsl_rng_free(r);
	}
	free(rx);
	free(ry);
	return rc;
}
