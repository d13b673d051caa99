/* twocode.h - the exact small-sample statistics of the two-code validation
 * (tests/bench/validate_lammps.sh, parts B-D): the same beds shaken by the engine and
 * by LAMMPS, compared bed by bed (bin/dumpflux stats). Binomial counts get the exact
 * Clopper-Pearson interval; paired outcomes the exact sign test (McNemar's exact test on
 * the discordant beds is the same test); paired numbers the exact sign-flip test of the
 * mean difference and the exact Wilcoxon signed-rank test; and the power of McNemar's
 * test, to say what difference a given number of beds can see. */
#ifndef AN_TWOCODE_H
#define AN_TWOCODE_H

#include <stddef.h>

#include "err.h"

/* Two-sided exact binomial test of k of n at probability 1/2 (the sign test; McNemar's
 * exact test with k = the discordant pairs one way, n = all discordant pairs):
 * min(1, 2 min(P(X <= k), P(X >= k))). 1 when n = 0, NaN when k is out of range. */
double tc_sign_p(long k, long n);

/* The exact sign-flip (permutation) test of paired differences d[n]: under "no
 * difference" each d is as likely to have either sign. rank = 0: the statistic is
 * |sum d| (the mean difference); rank = 1: Wilcoxon's signed-rank statistic
 * |W+ - m(m+1)/4| over the m nonzero d ranked by |d| (ties get their mean rank). The
 * p-value is the fraction of sign patterns whose statistic is at least the observed
 * one: all 2^m of them for m <= 20 (*exact = 1), else 2^20 random ones (MT19937, seed 1;
 * *exact = 0). p = 1 when every d is 0. */
int tc_flip_p(const double *d, size_t n, int rank, double *p, int *exact, sb_err *e);

/* The power of McNemar's exact test at level alpha (two-sided, p < alpha) over n beds
 * whose outcome is 1 with probability pa in one code and pb in the other, the two
 * independent given the bed (the least favourable case for a paired test: a shared bed
 * that makes the outcomes agree more only adds power). Exact: the sum over the
 * discordant counts (b, c), trinomial with probabilities pa(1 - pb), pb(1 - pa). */
double tc_mcnemar_power(long n, double pa, double pb, double alpha);

/* The most beds the power is computed for (NaN above): the sum has n^2/2 terms per
 * difference tried, up to 1000 differences; at this n, a few seconds. */
#define TC_MCNEMAR_MAX 1000

/* The smallest difference delta (in steps of 0.001) such that pb = p0 + dir * delta
 * (dir = +1 or -1, pb within [0, 1]) is detected with at least `power`; NaN when no
 * such pb exists. */
double tc_mcnemar_detect(long n, double p0, int dir, double alpha, double power);

/* The one sentence a reader can trust about an effect across the two codes: from each
 * code's own test of the effect (pa, pb: p-values, e.g. Fisher's test of depth 1
 * against depth 0) and the paired test of the codes against each other (pab: the
 * smallest p of the comparisons, e.g. McNemar's per depth), at level alpha:
 *   TC_DIFFER   pab < alpha: the codes differ;
 *   TC_BOTH     they agree (pab >= alpha) and each shows the effect (pa, pb < alpha);
 *   TC_NEITHER  they agree and neither shows it: these beds cannot decide;
 *   TC_ONE      they are not told apart, but one code alone shows the effect: not
 *               "the codes agree" unqualified, since which is right is not decided.
 * NaN in a p-value: TC_NONE (no sentence). */
enum tc_verdict { TC_NONE, TC_DIFFER, TC_BOTH, TC_NEITHER, TC_ONE };
enum tc_verdict tc_verdict_of(double pa, double pb, double pab, double alpha);
/* The verdict as that sentence, naming the codes a and b (e.g. "shakebox", "LAMMPS"),
 * the effect (e.g. "the depth effect") and the p-values (3 significant digits); the
 * paired test's name in test_ab (e.g. "McNemar"), the codes' own in test_own
 * ("Fisher"). Returns the verdict. */
enum tc_verdict tc_verdict_text(double pa, double pb, double pab, double alpha, const char *a, const char *b,
				const char *effect, const char *test_own, const char *test_ab, char *buf, size_t len);

#endif
