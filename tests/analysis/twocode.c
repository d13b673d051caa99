/* twocode.c - the exact statistics of the two-code validation (analysis/measure/twocode.c) on
 * known answers: Clopper-Pearson intervals (R's binom.test), the two-sided sign test,
 * the exact sign-flip and Wilcoxon signed-rank tests (R's wilcox.test example of paired
 * data, exact), and McNemar's power against a case solved by hand. */
#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "testlib.h"
#include "measure/twocode.h"
#include "quantile.h"

int main(void)
{
	double lo, hi;
	/* binom.test(3, 10)$conf.int: 0.06673951 0.65245285 */
	quant_clopper_pearson(3, 10, 0.95, &lo, &hi);
	CHECK_REL("cp.3_of_10.lo", lo, 0.06673951, 1e-6);
	CHECK_REL("cp.3_of_10.hi", hi, 0.65245285, 1e-6);
	/* at k = 0 the upper end is 1 - (alpha/2)^(1/n); at k = n the lower end is (alpha/2)^(1/n) */
	quant_clopper_pearson(0, 16, 0.95, &lo, &hi);
	CHECK("cp.0_of_16.lo", lo == 0, "lo %g", lo);
	CHECK_REL("cp.0_of_16.hi", hi, 1 - pow(0.025, 1.0 / 16), 1e-9);
	quant_clopper_pearson(16, 16, 0.95, &lo, &hi);
	CHECK_REL("cp.16_of_16.lo", lo, pow(0.025, 1.0 / 16), 1e-9);
	CHECK("cp.16_of_16.hi", hi == 1, "hi %g", hi);
	quant_clopper_pearson(5, 4, 0.95, &lo, &hi);
	CHECK("cp.refuses_k_over_n", isnan(lo) && isnan(hi), "%g %g", lo, hi);

	/* binom.test(2, 10)$p.value = 0.109375 = 2 * 56 / 1024; 1 of 9: 2 * 10 / 512 */
	CHECK_REL("sign.2_of_10", tc_sign_p(2, 10), 0.109375, 1e-12);
	CHECK_REL("sign.8_of_10_symmetric", tc_sign_p(8, 10), 0.109375, 1e-12);
	CHECK_REL("sign.1_of_9", tc_sign_p(1, 9), 0.0390625, 1e-12);
	CHECK("sign.middle_is_1", tc_sign_p(5, 10) == 1, "%g", tc_sign_p(5, 10));
	CHECK("sign.none_discordant_is_1", tc_sign_p(0, 0) == 1, "%g", tc_sign_p(0, 0));
	/* 5 of 5 one way: the smallest p of 5 beds, 2 / 32: no sign test over 5 beds reaches 0.05 */
	CHECK_REL("sign.5_of_5", tc_sign_p(5, 5), 0.0625, 1e-12);

	/* wilcox.test(x, y, paired = TRUE) of R's ?wilcox.test (Hollander & Wolfe):
	 * V = 40, p-value = 0.03906 = 20 / 512 */
	const double x[] = {1.83, 0.50, 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.30};
	const double y[] = {0.878, 0.647, 0.598, 2.05, 1.06, 1.29, 1.06, 3.14, 1.29};
	double d[9], p;
	int exact;
	sb_err e = {0};
	for (int i = 0; i < 9; i++)
		d[i] = x[i] - y[i];
	CHECK("wilcoxon.runs", tc_flip_p(d, 9, 1, &p, &exact, &e) == 0, "%s", e.msg);
	CHECK_REL("wilcoxon.hollander_wolfe", p, 20.0 / 512, 1e-12);
	CHECK("wilcoxon.exact", exact == 1, "exact %d", exact);
	/* ties and zeros: d = 1, 1, -1, 0: ranks 2, 2, 2 (mean of 1..3), zero dropped; the
	 * signed sum |2 + 2 - 2| = 2 is reached by every pattern but none: p = 1 */
	const double dt[] = {1, 1, -1, 0};
	tc_flip_p(dt, 4, 1, &p, &exact, &e);
	CHECK("wilcoxon.ties_zero", p == 1, "p %g", p);
	/* sign flip of the mean: 1, 2, 3, 4 all positive: only all + and all - reach 10 */
	const double ds[] = {1, 2, 3, 4};
	tc_flip_p(ds, 4, 0, &p, &exact, &e);
	CHECK_REL("flip.all_positive", p, 2.0 / 16, 1e-12);
	/* 3, -1, -1, -1: |sum| = 0: every pattern reaches it */
	const double dz[] = {3, -1, -1, -1};
	tc_flip_p(dz, 4, 0, &p, &exact, &e);
	CHECK("flip.sum_zero", p == 1, "p %g", p);
	const double d0[] = {0, 0, 0};
	tc_flip_p(d0, 3, 0, &p, &exact, &e);
	CHECK("flip.all_zero_is_1", p == 1, "p %g", p);
	/* more than 20 nonzero: random patterns, flagged; 24 equal positive d: p = 2 / 2^24,
	 * below what 2^20 random patterns can see */
	double dm[24];
	for (int i = 0; i < 24; i++)
		dm[i] = 1;
	tc_flip_p(dm, 24, 0, &p, &exact, &e);
	CHECK("flip.random_beyond_20", exact == 0 && p < 1e-5, "exact %d p %g", exact, p);

	/* McNemar's power when one code never rises (pa = 0): the discordant beds are all
	 * one way, c ~ Bin(n, pb), and the two-sided exact p = 2 / 2^c is below 0.05 from
	 * c = 6 on. So the power is P(Bin(n, pb) >= 6), and the smallest detectable pb is
	 * where that reaches 0.8. */
	const long n = 16;
	const double pb = 0.45;
	CHECK_REL("power.pa0", tc_mcnemar_power(n, 0, pb, 0.05), gsl_cdf_binomial_Q(5, pb, n), 1e-9);
	double want = NAN;
	for (int k = 1; k <= 1000; k++)
		if (gsl_cdf_binomial_Q(5, k * 1e-3, n) >= 0.8) {
			want = k * 1e-3;
			break;
		}
	CHECK_REL("power.detect_from_0", tc_mcnemar_detect(n, 0, 1, 0.05, 0.8), want, 1e-9);
	CHECK("power.detect_down_from_0_none", isnan(tc_mcnemar_detect(n, 0, -1, 0.05, 0.8)), "%g",
	      tc_mcnemar_detect(n, 0, -1, 0.05, 0.8));
	/* equal fractions: the power is the test's size, below alpha */
	const double size = tc_mcnemar_power(n, 0.5, 0.5, 0.05);
	CHECK("power.size_below_alpha", size > 0 && size < 0.05, "size %g", size);
	/* symmetric: up from p0 as down from 1 - p0 */
	CHECK_REL("power.symmetric", tc_mcnemar_detect(n, 0.3, 1, 0.05, 0.8), tc_mcnemar_detect(n, 0.7, -1, 0.05, 0.8),
		  1e-12);
	/* the one sentence across the codes: each wording on known inputs, and the level's
	 * edge both ways (p = alpha is not significant) */
	char t[512];
	CHECK("verdict.differ", tc_verdict_of(0.003, 0.72, 0.01, 0.05) == TC_DIFFER, "%d", tc_verdict_of(0.003, 0.72, 0.01, 0.05));
	CHECK("verdict.both", tc_verdict_of(0.01, 0.02, 0.5, 0.05) == TC_BOTH, "%d", tc_verdict_of(0.01, 0.02, 0.5, 0.05));
	CHECK("verdict.neither", tc_verdict_of(0.3, 0.72, 0.5, 0.05) == TC_NEITHER, "%d", tc_verdict_of(0.3, 0.72, 0.5, 0.05));
	/* the validation of 2026-11-26: shakebox 2/16 vs 11/16 (Fisher 0.00319), LAMMPS 7/16 vs
	 * 9/16 (0.724), McNemar 0.125 and 0.754: not "the codes agree" unqualified */
	CHECK("verdict.one.shakebox", tc_verdict_of(0.00319, 0.724, 0.125, 0.05) == TC_ONE, "%d",
	      tc_verdict_of(0.00319, 0.724, 0.125, 0.05));
	CHECK("verdict.one.lammps", tc_verdict_of(0.724, 0.00319, 0.125, 0.05) == TC_ONE, "%d",
	      tc_verdict_of(0.724, 0.00319, 0.125, 0.05));
	CHECK("verdict.edge.pab_at_alpha_agrees", tc_verdict_of(0.3, 0.3, 0.05, 0.05) == TC_NEITHER, "%d",
	      tc_verdict_of(0.3, 0.3, 0.05, 0.05));
	CHECK("verdict.edge.pab_below_alpha_differs", tc_verdict_of(0.3, 0.3, 0.0499, 0.05) == TC_DIFFER, "%d",
	      tc_verdict_of(0.3, 0.3, 0.0499, 0.05));
	CHECK("verdict.edge.pa_at_alpha_not_shown", tc_verdict_of(0.05, 0.01, 0.5, 0.05) == TC_ONE, "%d",
	      tc_verdict_of(0.05, 0.01, 0.5, 0.05));
	CHECK("verdict.nan_none", tc_verdict_of(NAN, 0.1, 0.1, 0.05) == TC_NONE, "%d", tc_verdict_of(NAN, 0.1, 0.1, 0.05));
	tc_verdict_text(0.00319, 0.724, 0.125, 0.05, "shakebox", "LAMMPS", "the depth effect", "Fisher", "McNemar", t, sizeof t);
	CHECK("verdict.text.one", !strcmp(t, "The codes are not told apart bed by bed (McNemar p = 0.125), but only shakebox "
					    "shows the depth effect (Fisher p = 0.00319 in shakebox, 0.724 in LAMMPS): these beds "
					    "cannot decide whether it is the model's or one code's."),
	      "%s", t);
	CHECK("verdict.text.one_never_plain_agree", !strstr(t, "The codes agree"), "%s", t);
	tc_verdict_text(0.0002, 0.01, 0.6, 0.05, "shakebox", "LAMMPS", "the depth effect", "Fisher", "McNemar", t, sizeof t);
	CHECK("verdict.text.both", !strcmp(t, "The codes agree (McNemar p = 0.6), and each shows the depth effect (Fisher "
					     "p = 2.0e-04 in shakebox, 0.01 in LAMMPS)."),
	      "%s", t);
	tc_verdict_text(0.3, 0.72, 0.5, 0.05, "shakebox", "LAMMPS", "the depth effect", "Fisher", "McNemar", t, sizeof t);
	CHECK("verdict.text.neither", strstr(t, "The codes agree (McNemar p = 0.5), and neither can decide") == t, "%s", t);
	tc_verdict_text(0.003, 0.72, 0.01, 0.05, "shakebox", "LAMMPS", "the depth effect", "Fisher", "McNemar", t, sizeof t);
	CHECK("verdict.text.differ", strstr(t, "The codes differ: McNemar p = 0.01 between shakebox and LAMMPS") == t, "%s", t);
	return tl_done();
}
