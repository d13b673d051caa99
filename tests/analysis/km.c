/* km.c - Kaplan-Meier against a hand-computed censored example, its Greenwood
 * errors, the median and its Brookmeyer-Crowley interval, ties, all-censored data. */
#include <math.h>

#include "km.h"
#include "testlib.h"

int main(void)
{
	/* times 1, 2+, 3, 4, 4, 5+, 6, 7+, 8 (+ censored), by hand:
	 *   t=1: n=9 d=1  S = 8/9
	 *   t=3: n=7 d=1  S = 8/9 * 6/7          = 16/21
	 *   t=4: n=6 d=2  S = 16/21 * 4/6        = 32/63
	 *   t=6: n=3 d=1  S = 32/63 * 2/3        = 64/189
	 *   t=8: n=1 d=1  S = 0
	 * Greenwood at t=4: S^2 (1/(9*8) + 1/(7*6) + 2/(6*4)) */
	const double t[] = {4, 1, 8, 2, 6, 4, 7, 3, 5};
	const int ev[] = {1, 1, 1, 0, 1, 1, 0, 1, 0};
	km_curve k;
	CHECK("km.fit.ok", km_fit(t, ev, 9, &k) == 0, "km_fit failed");
	CHECK("km.fit.distinct_times", k.m == 8, "m = %zu, want 8", k.m);
	CHECK("km.fit.events", k.events == 6 && k.n == 9, "events %ld n %ld", k.events, k.n);
	CHECK_REL("km.s.t1", km_at(&k, 1), 8.0 / 9, 1e-14);
	CHECK_REL("km.s.censored_time_keeps_S", km_at(&k, 2.5), 8.0 / 9, 1e-14);
	CHECK_REL("km.s.t3", km_at(&k, 3), 16.0 / 21, 1e-14);
	CHECK_REL("km.s.t4_tied_events", km_at(&k, 4), 32.0 / 63, 1e-14);
	CHECK_REL("km.s.t6", km_at(&k, 6.5), 64.0 / 189, 1e-14);
	CHECK("km.s.t8_zero", km_at(&k, 8) == 0, "S(8) = %g", km_at(&k, 8));
	CHECK("km.s.before_first", km_at(&k, 0.5) == 1, "S(0.5) = %g", km_at(&k, 0.5));
	/* n at risk just before 4: 9 - (1 event + 1 censored + 1 event) = 6 */
	CHECK("km.n_risk.t4", k.t[3] == 4 && k.n_risk[3] == 6 && k.d[3] == 2, "t %g n %ld d %ld", k.t[3], k.n_risk[3],
	      k.d[3]);
	double s4 = 32.0 / 63, gw = 1.0 / 72 + 1.0 / 42 + 2.0 / 24;
	CHECK_REL("km.greenwood.t4", k.se[3], s4 * sqrt(gw), 1e-12);
	double lo, hi, med = km_median(&k, 1.959964, &lo, &hi);
	CHECK("km.median", med == 6, "median %g, want 6 (first t with S <= 0.5)", med);
	/* lower band S - z se reaches 0.5 at t = 3 (0.762 - 1.96*0.148 = 0.472), at t = 1 it
	 * is 0.889 - 1.96*0.105 = 0.683; the upper band at t = 6 is 0.339 + 1.96*0.173 > 0.5
	 * and at t = 8 it is 0: the interval is [3, 8] */
	double se1 = (8.0 / 9) * sqrt(1.0 / 72), se3 = (16.0 / 21) * sqrt(1.0 / 72 + 1.0 / 42);
	/* the code's standard errors at t = 1 and 3 are the hand-computed ones that place
	 * the interval's lower end at 3 */
	CHECK_REL("km.greenwood.t1", k.se[0], se1, 1e-12);
	CHECK_REL("km.greenwood.t3", k.se[2], se3, 1e-12);
	CHECK("km.bands.lower_crosses_at_t3", km_at(&k, 1) - 1.959964 * k.se[0] > 0.5 && km_at(&k, 3) - 1.959964 * k.se[2] < 0.5,
	      "bands from the fit: %g at t=1, %g at t=3", km_at(&k, 1) - 1.959964 * k.se[0],
	      km_at(&k, 3) - 1.959964 * k.se[2]);
	CHECK("km.median.ci", lo == 3 && hi == 8, "interval [%g, %g], want [3, 8]", lo, hi);
	km_free(&k);

	/* all censored: S stays 1, no median, no interval */
	const double tc[] = {5, 5, 5};
	const int ec[] = {0, 0, 0};
	CHECK("km.censored.fit", km_fit(tc, ec, 3, &k) == 0, "km_fit failed");
	med = km_median(&k, 1.96, &lo, &hi);
	CHECK("km.censored.no_median", isnan(med) && isnan(lo) && isnan(hi) && km_at(&k, 100) == 1,
	      "median %g [%g, %g] S %g", med, lo, hi, km_at(&k, 100));
	km_free(&k);

	/* an event and a censoring at the same time: the event counts first (n = 2 at risk) */
	const double tt[] = {2, 2, 3};
	const int et[] = {0, 1, 1};
	km_fit(tt, et, 3, &k);
	CHECK_REL("km.tie.event_before_censoring", km_at(&k, 2), 2.0 / 3, 1e-14);
	km_free(&k);

	/* bad input is refused */
	const double tb[] = {1, -1};
	const int eb[] = {1, 1};
	CHECK("km.bad.negative_time", km_fit(tb, eb, 2, &k) == -1, "accepted a negative time");
	return tl_done();
}
