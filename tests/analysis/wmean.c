/* wmean.c - the weighted pooled mean and its interval across runs against hand-computed
 * values (t quantiles from tables): equal weights give Student's s/sqrt(n) interval,
 * unequal ones the ratio estimator's; one run has no interval, runs that agree a zero
 * one, runs of weight 0 do not count, and a wider spread widens it. */
#include <math.h>
#include <stdio.h>

#include "measure/wmean.h"
#include "testlib.h"

int main(void)
{
	wmean_res m;
	/* equal weights: 1, 2, 3, 4 -> mean 2.5, s = sqrt(5/3), se = s / 2; t(0.95, 3) = 3.182446305284263 */
	const double x4[] = {1, 2, 3, 4}, w2[] = {2, 2, 2, 2};
	wmean_ci(x4, 1, w2, 4, 0.95, &m);
	const double se4 = sqrt(5.0 / 3) / 2, h4 = 3.182446305284263 * se4;
	CHECK("wmean.equal_weights.n", m.n == 4, "n %zu", m.n);
	CHECK_REL("wmean.equal_weights.mean", m.mean, 2.5, 1e-15);
	CHECK_REL("wmean.equal_weights.se_is_s_over_sqrt_n", m.se, se4, 1e-13);
	CHECK_REL("wmean.equal_weights.lo", m.lo, 2.5 - h4, 1e-9);
	CHECK_REL("wmean.equal_weights.hi", m.hi, 2.5 + h4, 1e-9);
	/* weights 1, 1, 2 on 1, 2, 6: mean 15/4; sum w^2 (x - m)^2 = 2.75^2 + 1.75^2 + 4 * 2.25^2
	 * = 30.875, se^2 = 3/2 * 30.875 / 16; t(0.95, 2) = 4.302652729911275 */
	const double x3[] = {1, 2, 6}, w3[] = {1, 1, 2};
	wmean_ci(x3, 1, w3, 3, 0.95, &m);
	const double se3 = sqrt(1.5 * 30.875 / 16);
	CHECK_REL("wmean.weighted.mean", m.mean, 3.75, 1e-15);
	CHECK_REL("wmean.weighted.se", m.se, se3, 1e-13);
	CHECK_REL("wmean.weighted.hi", m.hi, 3.75 + 4.302652729911275 * se3, 1e-9);
	/* the same values at level 0.9: t(0.9, 2) = 2.919985580355516, a narrower interval */
	wmean_ci(x3, 1, w3, 3, 0.9, &m);
	CHECK_REL("wmean.weighted.level_0_9", m.hi - m.mean, 2.919985580355516 * se3, 1e-9);
	/* a strided column (x[i * 2]), a run of weight 0 left out: {1, 2, 3, 4} again */
	const double xs[] = {1, -9, 2, -9, 99, -9, 3, -9, 4, -9}, ws[] = {2, 2, 0, 2, 2};
	wmean_ci(xs, 2, ws, 5, 0.95, &m);
	CHECK("wmean.zero_weight_left_out", m.n == 4 && fabs(m.mean - 2.5) < 1e-15 && fabs(m.hi - (2.5 + h4)) < 1e-9,
	      "n %zu mean %g hi %g", m.n, m.mean, m.hi);
	/* runs that agree: an interval of width 0 */
	const double xe[] = {7, 7, 7};
	wmean_ci(xe, 1, w3, 3, 0.95, &m);
	CHECK("wmean.agreeing_runs_zero_width", m.mean == 7 && m.lo == 7 && m.hi == 7, "[%g, %g]", m.lo, m.hi);
	/* a wider spread about the same mean: a wider interval, both directions of the check */
	const double xw[] = {-2, 2, 3, 7};
	wmean_res mw;
	wmean_ci(x4, 1, w2, 4, 0.95, &m);
	wmean_ci(xw, 1, w2, 4, 0.95, &mw);
	CHECK("wmean.wider_spread_wider_band", mw.mean == m.mean && mw.hi - mw.lo > m.hi - m.lo,
	      "%g vs %g", mw.hi - mw.lo, m.hi - m.lo);
	CHECK("wmean.band_holds_mean", m.lo < m.mean && m.mean < m.hi && !(mw.lo > 2.5 || mw.hi < 2.5), "[%g, %g]", m.lo,
	      m.hi);
	/* one run: its value, no interval; none: nothing */
	wmean_ci(x4, 1, w2, 1, 0.95, &m);
	CHECK("wmean.one_run_no_band", m.n == 1 && m.mean == 1 && isnan(m.lo) && isnan(m.hi) && isnan(m.se), "n %zu [%g, %g]",
	      m.n, m.lo, m.hi);
	wmean_ci(x4, 1, w2, 0, 0.95, &m);
	CHECK("wmean.no_run", m.n == 0 && isnan(m.mean), "n %zu mean %g", m.n, m.mean);
	return tl_done();
}
