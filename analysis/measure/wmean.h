/* wmean.h - the mean of runs' values pooled by their weights (their periods after the
 * transient: a failed run weighs what it recorded) and its interval across the runs,
 * as Fig. 3 draws its band around each curve (docs/analysis.md, "figures").
 *
 * With x_i the runs' values and w_i > 0 their weights, the pooled mean is
 * m = sum w_i x_i / sum w_i, summed in the runs' order. Its standard error treats the
 * runs as independent replicates (the ratio estimator's, Cochran, Sampling
 * Techniques, 3rd ed., eq. 6.9, with the n/(n-1) small-sample factor):
 *   se^2 = n/(n-1) * sum w_i^2 (x_i - m)^2 / (sum w_i)^2,
 * which is s^2/n for equal weights; the interval is m -+ t se with Student's t at the
 * level and n - 1 degrees of freedom. */
#ifndef AN_WMEAN_H
#define AN_WMEAN_H

#include <stddef.h>

typedef struct wmean_res {
	size_t n;            /* runs with weight > 0 */
	double mean, se, lo, hi; /* lo, hi, se NaN when n < 2; mean NaN when n = 0 */
} wmean_res;

/* x[i * stride] and w[i] for i < n; runs of weight <= 0 are left out. */
void wmean_ci(const double *x, size_t stride, const double *w, size_t n, double level, wmean_res *m);

#endif
