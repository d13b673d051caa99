/* logrank.c - the log-rank test against a published example: the 6-MP leukaemia trial
 * (Freireich et al., Blood 21, 699, 1963; the textbook example of Kleinbaum & Klein,
 * Survival Analysis): remission times in weeks of 21 treated (* censored) and 21
 * placebo patients; log-rank chi-square 16.79 with 1 degree of freedom, p = 4.2e-5.
 * Also: identical groups give 0, three groups give k - 1 degrees of freedom, one group
 * or no events give no test. */
#include <math.h>

#include "logrank.h"
#include "testlib.h"

int main(void)
{
	/* 6-MP: 6,6,6,6*,7,9*,10,10*,11*,13,16,17*,19*,20*,22,23,25*,32*,32*,34*,35*;
	 * placebo: 1,1,2,2,3,4,4,5,5,8,8,8,8,11,11,12,12,15,17,22,23 (all events) */
	const double t6[] = {6, 6, 6, 6, 7, 9, 10, 10, 11, 13, 16, 17, 19, 20, 22, 23, 25, 32, 32, 34, 35};
	const int e6[] = {1, 1, 1, 0, 1, 0, 1, 0, 0, 1, 1, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0};
	const double tp[] = {1, 1, 2, 2, 3, 4, 4, 5, 5, 8, 8, 8, 8, 11, 11, 12, 12, 15, 17, 22, 23};
	double t[42];
	int e[42], g[42];
	for (int i = 0; i < 21; i++) {
		t[i] = t6[i], e[i] = e6[i], g[i] = 0;
		t[21 + i] = tp[i], e[21 + i] = 1, g[21 + i] = 1;
	}
	logrank r;
	CHECK("logrank.runs", logrank_test(t, e, g, 42, 2, &r) == 0, "returned an error");
	CHECK_REL("logrank.leukaemia.chi2", r.chi2, 16.79, 2e-3);
	CHECK("logrank.leukaemia.df_p", r.df == 1 && r.p > 3.5e-5 && r.p < 4.5e-5, "df %d p %g", r.df, r.p);
	/* the same times in two groups: no difference */
	for (int i = 0; i < 21; i++)
		t[21 + i] = t[i], e[21 + i] = e[i];
	logrank_test(t, e, g, 42, 2, &r);
	CHECK("logrank.identical_groups_zero", fabs(r.chi2) < 1e-12 && r.p > 0.999, "chi2 %g p %g", r.chi2, r.p);
	/* three groups */
	for (int i = 0; i < 42; i++)
		g[i] = i % 3;
	logrank_test(t, e, g, 42, 3, &r);
	CHECK("logrank.three_groups_df", r.df == 2 && isfinite(r.chi2) && r.k == 3, "df %d k %d", r.df, r.k);
	/* one group, or no events: no test */
	for (int i = 0; i < 42; i++)
		g[i] = 0;
	logrank_test(t, e, g, 42, 2, &r);
	CHECK("logrank.one_group_no_test", isnan(r.p) && r.k == 1, "p %g k %d", r.p, r.k);
	for (int i = 0; i < 42; i++)
		e[i] = 0, g[i] = i % 2;
	logrank_test(t, e, g, 42, 2, &r);
	CHECK("logrank.no_events_no_test", isnan(r.p), "p %g", r.p);
	CHECK("logrank.bad_group_refused", logrank_test(t, e, (int[]){5}, 1, 2, &r) == -1, "a group index out of range");
	return tl_done();
}
