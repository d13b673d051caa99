/* lowerrow.c - the start one row lower (depth - 1, docs/model.md "Preparation") and the
 * two-sided Fisher exact test, against known answers.
 *
 * Fisher, 2 of 16 against 10 of 16: the margins are N = 32 runs, K = 12 risen, 16 in
 * sample 1; the risen runs X of sample 1 are hypergeometric, P(X = x) = C(12, x)
 * C(20, 16 - x) / C(32, 16), C(32, 16) = 601080390. The numerators for x = 0..12 are
 * 4845, 186048, 2558160, 17054400, 62355150, 133024320, 170714544 and back
 * symmetrically; the tables no more likely than x = 2 are x = 0, 1, 2, 10, 11, 12, so
 * p = 2 (4845 + 186048 + 2558160) / 601080390 = 5498106 / 601080390 = 0.0091470394
 * (checked independently: python3 with math.comb, summing the pdf <= the observed one
 * times 1 + 1e-7). 0 of 10 against 10 of 10: only x = 0 and x = 10 are as unlikely,
 * each 1 / C(20, 10): p = 2 / 184756 = 1.0825088e-5.
 *
 * The partner: with depth + 1 in place of depth - 1 (lowerrow.c, one_row_lower) the
 * partner of (2.7, 1) would be (2.7, 2) and that of (2.7, 0) would be (2.7, 1): the
 * checks partner.one_lower, .floor_has_none, .two_rows_up, .numeric, .tool and others
 * fail (verified by flipping it: 7 of the 23 checks fail). */
#include <math.h>

#include "measure/lowerrow.h"
#include "testlib.h"

int main(void)
{
	/* ---- Fisher ---- */
	CHECK_REL("fisher.2of16_vs_10of16", lowerrow_fisher_p(2, 16, 10, 16), 5498106.0 / 601080390.0, 1e-4);
	CHECK_REL("fisher.2of16_vs_10of16_value", lowerrow_fisher_p(2, 16, 10, 16), 0.0091470394, 1e-4);
	const double p = lowerrow_fisher_p(2, 16, 10, 16);
	CHECK_REL("fisher.swapped_samples", lowerrow_fisher_p(10, 16, 2, 16), p, 1e-12);
	CHECK_REL("fisher.swapped_outcomes", lowerrow_fisher_p(14, 16, 6, 16), p, 1e-12);
	CHECK_REL("fisher.equal_is_1", lowerrow_fisher_p(8, 16, 8, 16), 1, 1e-12);
	CHECK_REL("fisher.none_vs_all", lowerrow_fisher_p(0, 10, 10, 10), 2 / 184756.0, 1e-6);
	CHECK_REL("fisher.none_vs_all_swapped", lowerrow_fisher_p(10, 10, 0, 10), 2 / 184756.0, 1e-6);
	/* unequal sizes, 3 of 5 against 1 of 9: N = 14, K = 4, P(X = x) = C(4, x) C(10, 5 - x) /
	 * C(14, 5), numerators 252, 840, 720, 180, 10 over 2002; as unlikely as x = 3 or less:
	 * x = 3, 4: p = 190 / 2002 (python3 math.comb: 0.0949050949) */
	CHECK_REL("fisher.unequal_sizes", lowerrow_fisher_p(3, 5, 1, 9), 190.0 / 2002.0, 1e-9);
	CHECK_REL("fisher.unequal_sizes_swapped", lowerrow_fisher_p(1, 9, 3, 5), 190.0 / 2002.0, 1e-9);
	CHECK("fisher.empty_sample_nan",
	      isnan(lowerrow_fisher_p(0, 0, 3, 5)) && isnan(lowerrow_fisher_p(3, 5, 0, 0)) &&
		      isnan(lowerrow_fisher_p(0, 0, 0, 0)),
	      "%g %g", lowerrow_fisher_p(0, 0, 3, 5), lowerrow_fisher_p(3, 5, 0, 0));
	CHECK("fisher.bad_count_nan", isnan(lowerrow_fisher_p(6, 5, 1, 9)) && isnan(lowerrow_fisher_p(-1, 5, 1, 9)),
	      "a count outside 0..n");
	CHECK_REL("fisher.nobody_rose", lowerrow_fisher_p(0, 7, 0, 4), 1, 1e-12);

	/* ---- the partner one row lower ---- */
	const char keys[2][48] = {"frequency", "depth"};
	/* groups 0..3: (2.7, 0), (2.7, 1), (2.75, 0), (2.75, 1); group 4: (2.7, 2) */
	const char *gv[] = {"2.7", "0", "2.7", "1", "2.75", "0", "2.75", "1", "2.7", "2"};
	CHECK("partner.one_lower", lowerrow_partner_of(keys, 2, gv, 5, 1) == 0, "partner of (2.7, 1) is %d, not 0",
	      lowerrow_partner_of(keys, 2, gv, 5, 1));
	CHECK("partner.one_lower_other_frequency", lowerrow_partner_of(keys, 2, gv, 5, 3) == 2, "partner of (2.75, 1) is %d",
	      lowerrow_partner_of(keys, 2, gv, 5, 3));
	CHECK("partner.two_rows_up", lowerrow_partner_of(keys, 2, gv, 5, 4) == 1, "partner of (2.7, 2) is %d",
	      lowerrow_partner_of(keys, 2, gv, 5, 4));
	CHECK("partner.floor_has_none",
	      lowerrow_partner_of(keys, 2, gv, 5, 0) == -1 && lowerrow_partner_of(keys, 2, gv, 5, 2) == -1,
	      "partner of (2.7, 0) is %d, of (2.75, 0) %d", lowerrow_partner_of(keys, 2, gv, 5, 0),
	      lowerrow_partner_of(keys, 2, gv, 5, 2));
	/* only the four groups: (2.7, 1) still finds (2.7, 0), not (2.75, 0) */
	CHECK("partner.same_other_keys", lowerrow_partner_of(keys, 2, gv, 4, 1) == 0, "got %d",
	      lowerrow_partner_of(keys, 2, gv, 4, 1));
	/* (2.7, 1) with only (2.75, 0) below it: no partner */
	const char *gv2[] = {"2.75", "0", "2.7", "1"};
	CHECK("partner.other_frequency_is_none", lowerrow_partner_of(keys, 2, gv2, 2, 1) == -1, "got %d",
	      lowerrow_partner_of(keys, 2, gv2, 2, 1));
	/* numbers compared as numbers: depth "1.0" finds "0", frequency "2.70" is "2.7" */
	const char *gv3[] = {"2.7", "0", "2.70", "1.0"};
	CHECK("partner.numeric", lowerrow_partner_of(keys, 2, gv3, 2, 1) == 0, "got %d",
	      lowerrow_partner_of(keys, 2, gv3, 2, 1));
	/* no depth key: no comparison */
	const char keys_nd[2][48] = {"frequency", "radius_ratio"};
	CHECK("partner.no_depth_key",
	      lowerrow_partner_of(keys_nd, 2, gv, 5, 1) == -1 && lowerrow_partner_of(keys_nd, 2, gv, 5, 0) == -1,
	      "got %d", lowerrow_partner_of(keys_nd, 2, gv, 5, 1));
	/* a depth that is not a number, an index out of range */
	const char *gv4[] = {"2.7", "", "2.7", "x"};
	CHECK("partner.no_numeric_depth",
	      lowerrow_partner_of(keys, 2, gv4, 2, 1) == -1 && lowerrow_partner_of(keys, 2, gv4, 2, 0) == -1,
	      "a depth that is not a number");
	CHECK("partner.out_of_range",
	      lowerrow_partner_of(keys, 2, gv, 5, 5) == -1 && lowerrow_partner_of(keys, 2, gv, 5, -1) == -1,
	      "j outside the groups");

	/* the same over a tool's groups: depth first, text keys */
	an_tool t = {0};
	snprintf(t.keys[0], sizeof t.keys[0], "depth");
	snprintf(t.keys[1], sizeof t.keys[1], "integrator");
	t.nk = 2;
	t.ng = 3;
	char d2[] = "2", d1[] = "1", d1b[] = "1", v[] = "verlet", vb[] = "verlet", g[] = "gear5";
	char *tv[] = {d2, v, d1, g, d1b, vb};
	t.gval = tv;
	const int p0 = lowerrow_partner(&t, 0), p1 = lowerrow_partner(&t, 1), p2 = lowerrow_partner(&t, 2);
	CHECK("partner.tool", p0 == 2 && p1 == -1 && p2 == -1, "got %d %d %d", p0, p1, p2);
	return tl_done();
}
