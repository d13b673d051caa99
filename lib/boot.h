/* boot.h - the nonparametric bootstrap with explicit random state: an MT19937 seeded
 * by the caller (the tools take --seed), so a result is reproducible bit for bit;
 * percentile confidence intervals that ignore failed (NaN) replicates. */
#ifndef LIB_BOOT_H
#define LIB_BOOT_H

#include <gsl/gsl_rng.h>
#include <stddef.h>

/* k statistics of a resample: idx[0..n) are indices into the caller's units (with
 * repetition); writes out[0..k) (NaN when one cannot be computed, e.g. a fit failed). */
typedef void (*boot_stat)(void *ctx, const size_t *idx, size_t n, double *out);

gsl_rng *boot_rng(unsigned long seed);
/* n indices drawn uniformly with replacement from [0, n). */
void boot_draw(gsl_rng *r, size_t n, size_t *idx);
/* B replicates of the k statistics over n units: out[j * B + b] is statistic j of
 * replicate b. Returns 0, or -1 when out of memory. Same seed, same out. */
int boot_run(unsigned long seed, size_t n, size_t B, size_t k, boot_stat stat, void *ctx, double *out);
/* Percentile interval at level (0.95) of the finite values of v[0..n) (v is sorted
 * in place, NaNs moved to the end); returns their count, lo = hi = NaN when < 2. */
size_t boot_percentile(double *v, size_t n, double level, double *lo, double *hi);
/* The quantile f of m >= 1 sorted values that may hold -inf and +inf (a replicate known
 * only to lie beyond every finite one, e.g. a censored median): GSL's interpolation
 * (gsl_stats_quantile_from_sorted_data, to the bit on finite values), infinite when it
 * falls on an infinite value or between one and its neighbour. */
double boot_quantile(const double *sorted, size_t m, double f);

#endif
