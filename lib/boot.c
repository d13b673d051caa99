/* boot.c - resampling with a seeded MT19937 and percentile intervals. */
#include "boot.h"

#include <gsl/gsl_sort.h>
#include <math.h>
#include <stdlib.h>

gsl_rng *boot_rng(unsigned long seed)
{
	gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
	if (r)
		gsl_rng_set(r, seed);
	return r;
}

void boot_draw(gsl_rng *r, size_t n, size_t *idx)
{
	for (size_t i = 0; i < n; i++)
		idx[i] = (size_t)gsl_rng_uniform_int(r, n);
}

int boot_run(unsigned long seed, size_t n, size_t B, size_t k, boot_stat stat, void *ctx, double *out)
{
	gsl_rng *r = boot_rng(seed);
	size_t *idx = malloc(sizeof *idx * (n ? n : 1));
	double *v = malloc(sizeof *v * (k ? k : 1));
	if (!r || !idx || !v) {
		if (r)
			gsl_rng_free(r);
		free(idx);
		free(v);
		return -1;
	}
	for (size_t b = 0; b < B; b++) {
		boot_draw(r, n, idx);
		stat(ctx, idx, n, v);
		for (size_t j = 0; j < k; j++)
			out[j * B + b] = v[j];
	}
	gsl_rng_free(r);
	free(idx);
	free(v);
	return 0;
}

size_t boot_percentile(double *v, size_t n, double level, double *lo, double *hi)
{
	size_t m = 0;
	for (size_t i = 0; i < n; i++)
		if (isfinite(v[i])) {
			double t = v[m];
			v[m++] = v[i];
			v[i] = t;
		}
	*lo = *hi = NAN;
	if (m < 2)
		return m;
	gsl_sort(v, 1, m);
	double a = 0.5 * (1 - level);
	*lo = boot_quantile(v, m, a);
	*hi = boot_quantile(v, m, 1 - a);
	return m;
}

double boot_quantile(const double *v, size_t m, double f)
{
	const double index = f * (double)(m - 1);
	const size_t l = (size_t)index;
	const double d = index - (double)l;
	if (l >= m - 1 || d == 0 || isinf(v[l]))
		return v[l < m ? l : m - 1];
	if (isinf(v[l + 1])) /* a weight on an unbounded value: the limit is unbounded */
		return v[l + 1];
	return (1 - d) * v[l] + d * v[l + 1];
}
