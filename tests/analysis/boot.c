/* boot.c - the bootstrap is reproducible (same seed, same replicates, bit for bit),
 * depends on the seed, draws in range, and its percentile interval is right on known
 * data and ignores failed replicates; boot_quantile is GSL's quantile to the bit on
 * finite values and infinite where it leans on an unbounded one. */
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <float.h>
#include <math.h>
#include <string.h>

#include "boot.h"
#include "testlib.h"

static void mean_stat(void *ctx, const size_t *idx, size_t n, double *out)
{
	const double *x = ctx;
	double s = 0;
	for (size_t i = 0; i < n; i++)
		s += x[idx[i]];
	out[0] = s / (double)n;
	out[1] = idx[0] % 3 == 0 ? NAN : x[idx[0]]; /* fails a third of the time */
}

int main(void)
{
	double x[20];
	for (int i = 0; i < 20; i++)
		x[i] = (i * 7919) % 23;
	enum { B = 500 };
	static double a[2 * B], b[2 * B], c[2 * B];
	CHECK("boot.run.ok", boot_run(42, 20, B, 2, mean_stat, x, a) == 0, "boot_run failed");
	boot_run(42, 20, B, 2, mean_stat, x, b);
	boot_run(43, 20, B, 2, mean_stat, x, c);
	CHECK("boot.reproducible.same_seed", memcmp(a, b, sizeof a) == 0, "same seed gave different replicates");
	CHECK("boot.seed_matters", memcmp(a, c, sizeof(double) * B) != 0, "seeds 42 and 43 gave the same replicates");
	gsl_rng *r = boot_rng(7);
	size_t idx[1000];
	boot_draw(r, 1000, idx);
	size_t mx = 0, hits0 = 0;
	for (int i = 0; i < 1000; i++) {
		mx = idx[i] > mx ? idx[i] : mx;
		hits0 += idx[i] == 0;
	}
	gsl_rng_free(r);
	CHECK("boot.draw.range", mx < 1000 && hits0 < 10, "max %zu, index 0 drawn %zu times", mx, hits0);
	/* the mean of the resampled means is close to the mean (sd of a mean ~ 6.6/sqrt(20)) */
	double m = 0, xm = 0;
	for (int i = 0; i < B; i++)
		m += a[i] / B;
	for (int i = 0; i < 20; i++)
		xm += x[i] / 20;
	CHECK("boot.mean_of_means", fabs(m - xm) < 0.3, "mean of bootstrap means %g, sample mean %g", m, xm);

	double v[101], lo, hi;
	for (int i = 0; i <= 100; i++)
		v[i] = 100 - i; /* 100 .. 0, unsorted */
	size_t n = boot_percentile(v, 101, 0.9, &lo, &hi);
	CHECK("boot.percentile.known", n == 101 && fabs(lo - 5) < 1e-12 && fabs(hi - 95) < 1e-12, "n %zu [%g, %g], want [5, 95]",
	      n, lo, hi);
	n = boot_percentile(a + B, B, 0.95, &lo, &hi);
	CHECK("boot.percentile.ignores_nan", n > B / 2 && n < B && isfinite(lo) && isfinite(hi) && lo <= hi,
	      "%zu finite of %d, [%g, %g]", n, B, lo, hi);
	double one[2] = {NAN, 3};
	n = boot_percentile(one, 2, 0.95, &lo, &hi);
	CHECK("boot.percentile.too_few", n == 1 && isnan(lo) && isnan(hi), "n %zu [%g, %g]", n, lo, hi);

	/* boot_quantile on finite values, at many levels and sizes: to the bit the
	 * definition GSL documents for gsl_stats_quantile_from_sorted_data (index f (m - 1),
	 * linear between its neighbours), spelt out here and compiled with the project's
	 * flags (no FMA contraction), so that the same bits are wanted on every platform;
	 * and within 2 ulp of GSL itself, whose bits depend on how the platform's library
	 * was built (Debian's arm64 GSL contracts the interpolation into an FMA) */
	int same = 1, near_gsl = 1;
	for (size_t m = 1; m <= 40; m++) {
		double w[40];
		for (size_t i = 0; i < m; i++)
			w[i] = sin(1.3 * (double)(i * i + m));
		gsl_sort(w, 1, m);
		for (double f = 0; f <= 1; f += 0.0125) {
			const double index = f * (double)(m - 1), d = index - floor(index);
			const size_t l = (size_t)index;
			const double want = l + 1 < m && d != 0 ? (1 - d) * w[l] + d * w[l + 1] : w[l];
			const double got = boot_quantile(w, m, f), g = gsl_stats_quantile_from_sorted_data(w, 1, m, f);
			same &= got == want;
			near_gsl &= fabs(got - g) <= 2 * DBL_EPSILON * fmax(fabs(g), DBL_MIN);
		}
	}
	CHECK("boot.quantile.definition_bits", same, "boot_quantile differs from the documented interpolation");
	CHECK("boot.quantile.near_gsl", near_gsl, "boot_quantile more than 2 ulp from gsl_stats_quantile_from_sorted_data");
	/* 10 values 0..9 with the lowest two unbounded below and the top one above:
	 * the 5 % quantile falls between -inf and -inf, 15 % between -inf and 2 (a weight
	 * on -inf), 20 % on 2 exactly, 50 % at 4.5, 95 % between 8 and +inf */
	const double ninf[10] = {-INFINITY, -INFINITY, 2, 3, 4, 5, 6, 7, 8, INFINITY};
	const double q05 = boot_quantile(ninf, 10, 0.05), q15 = boot_quantile(ninf, 10, 0.15),
		     q20 = boot_quantile(ninf, 10, 2.0 / 9), q50 = boot_quantile(ninf, 10, 0.5),
		     q95 = boot_quantile(ninf, 10, 0.95), q80 = boot_quantile(ninf, 10, 8.0 / 9);
	CHECK("boot.quantile.infinite", isinf(q05) && q05 < 0 && isinf(q15) && q15 < 0 && q20 == 2 && q50 == 4.5 &&
						isinf(q95) && q95 > 0 && q80 == 8,
	      "%g %g %g %g %g %g", q05, q15, q20, q50, q80, q95);
	return tl_done();
}
