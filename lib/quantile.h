/* quantile.h - the quantiles and the exact binomial interval every statistic shares,
 * on GSL's distributions (gsl_cdf): two-sided normal and Student t quantiles, and
 * Clopper-Pearson (Clopper & Pearson, Biometrika 26, 404, 1934). */
#ifndef LIB_QUANTILE_H
#define LIB_QUANTILE_H

/* z with P(|Z| <= z) = level for a standard normal Z (1.96 at 0.95). */
double quant_normal(double level);
/* t with P(|T| <= t) = level for Student's T with df degrees of freedom: the
 * half-width of a mean's interval is t times its standard error. */
double quant_student(double level, double df);
/* Clopper-Pearson interval of k of n at level (0 < level < 1): exact, never narrower
 * than its level; [0, hi] at k = 0, [lo, 1] at k = n. NaN when n < 1 or k is out of
 * range. */
void quant_clopper_pearson(long k, long n, double level, double *lo, double *hi);

#endif
