/* study_auto.c - replicates until the answer is sharp, the pure logic (study/rule/sharp.c)
 * against docs/driver.md, "Replicates until the answer is sharp": the first batch,
 * the median wait's order-statistic interval with right-censoring (a run that did not
 * rise counts as at least its observed time) and its Kaplan-Meier estimate, the rise
 * fraction's and the mean flux's intervals, a point that waits for its runs, and a
 * point driven batch by batch over a synthetic result until it reaches the target or
 * its maximum (interrupted and resumed: the same sequence); then the [campaign] keys
 * of replicates = auto (study/campaign/campaign.c): defaults, and bad input refused with file,
 * line, key and the valid range. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campaign/campaign.h"
#include "rule/sharp.h"
#include "study_files.h"
#include "testlib.h"

static sh_obs rose(double t)
{
	sh_obs o = {SH_USED, 1, t, NAN};
	return o;
}

static sh_obs censored(double t)
{
	sh_obs o = {SH_USED, 0, t, NAN};
	return o;
}

static void test_first(void)
{
	sh_plan p = {SH_MEDIAN_WAIT, 4, 32, 1, 0.95};
	CHECK("auto.first.median_needs_6_at_095", sharp_first(&p) == 6, "got %ld", sharp_first(&p));
	p.batch = 8;
	CHECK("auto.first.batch_when_larger", sharp_first(&p) == 8, "got %ld", sharp_first(&p));
	p.max = 5;
	CHECK("auto.first.at_most_max", sharp_first(&p) == 5, "got %ld", sharp_first(&p));
	sh_plan f = {SH_RISE_FRACTION, 1, 32, 1, 0.95};
	CHECK("auto.first.fraction_from_2", sharp_first(&f) == 2, "got %ld", sharp_first(&f));
}

static void test_median(void)
{
	sh_plan p = {SH_MEDIAN_WAIT, 3, 6, 1, 0.75};
	sh_eval v;
	/* level 0.75 with 6 runs: ranks 2 and 5 (1 - 2 * 7/64 = 0.78) */
	sh_obs all[6] = {rose(0.5), rose(0.1), rose(0.3), rose(0.6), rose(0.2), rose(0.4)};
	sharp_interval(&p, all, 6, &v);
	CHECK("auto.median.order_statistics", v.lo == 0.2 && v.hi == 0.5 && fabs(v.width - 0.3) < 1e-15,
	      "[%g, %g]", v.lo, v.hi);
	CHECK("auto.median.km_estimate", v.est == 0.3, "got %g", v.est); /* S reaches 1/2 at the third */
	/* a run censored above every rise counts as at least its time: the interval is
	 * the one it would have had had it risen later than all of them */
	sh_obs late[6] = {rose(0.5), rose(0.1), rose(0.3), censored(4), rose(0.2), rose(0.4)};
	sharp_interval(&p, late, 6, &v);
	CHECK("auto.median.censored_late_bounds", v.lo == 0.2 && v.hi == 0.5 && v.used == 6, "[%g, %g]", v.lo, v.hi);
	/* half the runs did not rise in 2 s: the median may lie beyond what was watched */
	sh_obs half[6] = {rose(0.5), censored(2), rose(0.3), censored(2), rose(0.2), censored(2)};
	sharp_interval(&p, half, 6, &v);
	CHECK("auto.median.censored_half_unbounded", v.lo == 0.3 && isinf(v.hi) && isinf(v.width),
	      "[%g, %g]", v.lo, v.hi);
	CHECK("auto.median.censored_half_km", v.est == 0.5, "got %g", v.est);
	long want;
	sh_plan big = p;
	big.target = 1e9;
	CHECK("auto.median.unbounded_never_done", sharp_point(&big, half, 6, &v, &want) == SH_MAX,
	      "a finite target reached with an unbounded interval");
	/* a run censored early (failed at 0.05) may have risen at any time after it: the
	 * interval widens (its upper end moves from 0.5 to 0.6) */
	sh_obs early[6] = {rose(0.5), censored(0.05), rose(0.3), rose(0.6), rose(0.2), rose(0.4)};
	sharp_interval(&p, early, 6, &v);
	CHECK("auto.median.censored_early_widens", v.lo == 0.2 && v.hi == 0.6, "[%g, %g]", v.lo, v.hi);
	sh_obs none[3] = {censored(2), censored(2), censored(2)};
	sharp_interval(&p, none, 3, &v);
	CHECK("auto.median.none_rose", isnan(v.est) && v.lo == 2 && isinf(v.hi), "est %g [%g, %g]", v.est, v.lo, v.hi);
	/* a run that finished without a value is left out */
	sh_obs skip[4] = {rose(0.1), {SH_NONE, 0, 0, NAN}, rose(0.2), rose(0.3)};
	sharp_interval(&p, skip, 4, &v);
	CHECK("auto.median.unusable_left_out", v.used == 3 && v.est == 0.2, "used %ld est %g", v.used, v.est);
}

static void test_fraction_and_flux(void)
{
	sh_plan p = {SH_RISE_FRACTION, 3, 6, 1, 0.95};
	sh_eval v;
	sh_obs h[6] = {rose(1), censored(2), rose(1), censored(2), rose(1), censored(2)};
	sharp_interval(&p, h, 6, &v);
	/* Clopper-Pearson, 3 of 6 at 95 %: [0.118117, 0.881883] (symmetric) */
	CHECK("auto.fraction.clopper_pearson", v.est == 0.5 && fabs(v.lo - 0.118117) < 1e-6 &&
	      fabs(v.hi + v.lo - 1) < 1e-12, "%g [%.6g, %.6g]", v.est, v.lo, v.hi);
	sh_obs a[6] = {rose(1), rose(1), rose(1), rose(1), rose(1), rose(1)};
	sharp_interval(&p, a, 6, &v);
	CHECK("auto.fraction.all_rose", v.hi == 1 && fabs(v.lo - pow(0.025, 1.0 / 6)) < 1e-9, "[%.9g, %g]", v.lo, v.hi);
	sh_plan f = {SH_MEAN_FLUX, 3, 6, 1, 0.95};
	sh_obs x[3] = {{SH_USED, 0, 0, 1}, {SH_USED, 0, 0, 2}, {SH_USED, 0, 0, 3}};
	sharp_interval(&f, x, 3, &v);
	/* mean 2, s = 1, t(0.975, 2) = 4.302653 */
	CHECK("auto.flux.student_t", v.est == 2 && fabs(v.width - 2 * 4.302653 / sqrt(3)) < 1e-5, "%g width %.9g",
	      v.est, v.width);
	sharp_interval(&f, x, 1, &v);
	CHECK("auto.flux.one_run_unbounded", v.est == 1 && isinf(v.width), "width %g", v.width);
}

/* A synthetic result: replicate k's wait, exponential with mean 1 from a fixed
 * sequence (a run's result depends on its replicate alone, as the engine's does). */
static double wait_of(long k)
{
	unsigned long long z = (unsigned long long)k * 0x9e3779b97f4a7c15ULL;
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z ^= z >> 31;
	return -log(((double)(z >> 11) + 0.5) / 9007199254740992.0);
}

/* The driver's loop over one point: the replicates the plan asks for, run (their
 * results known) up to `finished` of them; the state, the replicates and the widths
 * after every batch. */
static int drive(const sh_plan *p, long finished, long *n, double *widths, int *nb)
{
	sh_obs obs[1000];
	sh_eval v;
	long want;
	*n = sharp_first(p);
	*nb = 0;
	for (;;) {
		for (long i = 0; i < *n; i++)
			obs[i] = i < finished ? rose(wait_of(i + 1)) : (sh_obs){SH_WAIT, 0, 0, NAN};
		int st = sharp_point(p, obs, *n, &v, &want);
		if (st != SH_RUNNING)
			widths[(*nb)++] = v.width;
		if (st != SH_MORE)
			return st;
		*n = want;
	}
}

static void test_point(void)
{
	double w[64];
	int nb;
	long n;
	sh_plan p = {SH_MEDIAN_WAIT, 4, 32, 0, 0.95};
	/* the widths batch by batch, to the maximum: 6, 10, ..., 30, 32 */
	p.target = 1e-9;
	int st = drive(&p, 1000, &n, w, &nb);
	CHECK("auto.point.stops_at_max", st == SH_MAX && n == 32 && nb == 8, "state %d, %ld replicates, %d batches", st,
	      n, nb);
	/* a target between two batches' widths: the point stops at the first batch whose
	 * interval reaches it */
	int at = -1;
	for (int i = 1; i < nb && at < 0; i++)
		if (w[i] < w[0])
			at = i;
	p.target = w[at];
	st = drive(&p, 1000, &n, w, &nb);
	CHECK("auto.point.stops_at_target", at > 0 && st == SH_DONE && nb == at + 1 && n == 6 + 4 * at &&
	      w[nb - 1] <= p.target, "state %d, %ld replicates after %d batches (target reached at batch %d)", st, n, nb,
	      at + 1);
	for (int i = 0; i + 1 < nb; i++)
		CHECK("auto.point.earlier_batches_wider", w[i] > p.target, "batch %d width %g", i + 1, w[i]);
	/* loose: the first batch */
	p.target = 1e9;
	st = drive(&p, 1000, &n, w, &nb);
	CHECK("auto.point.loose_first_batch", st == SH_DONE && n == 6, "state %d, %ld", st, n);
	/* a run not finished holds the point: no batch added while the earlier one runs */
	p.target = 1e-9;
	st = drive(&p, 9, &n, w, &nb);
	CHECK("auto.point.waits_for_runs", st == SH_RUNNING && n == 10, "state %d, %ld replicates", st, n);
	/* the runs of an interrupted driver finished later: the same sequence */
	long n1, n2;
	double w1[64], w2[64];
	int b1, b2;
	p.target = 0.9;
	drive(&p, 7, &n1, w1, &b1);
	int s1 = drive(&p, 1000, &n1, w1, &b1), s2 = drive(&p, 1000, &n2, w2, &b2);
	CHECK("auto.point.resumed_same_sequence", s1 == s2 && n1 == n2 && b1 == b2 && !memcmp(w1, w2, sizeof *w1 * (size_t)b1),
	      "%ld vs %ld replicates", n1, n2);
}

static const char *HEAD = "[campaign]\nname = a\nseed = 1\n";
static const char *SCENE = "[scene]\nradius_ratio = 2\nduration = 1\n";

static void bad(const char *id, const char *keys, const char *want)
{
	char text[2048];
	snprintf(text, sizeof text, "%s%s%s", HEAD, keys, SCENE);
	campaign c;
	sb_err e;
	int rc = sf_load(text, &c, &e);
	CHECK(id, rc && strstr(e.msg, want), "%s", rc ? e.msg : "accepted");
	if (!rc)
		campaign_free(&c);
}

static void test_keys(void)
{
	char text[2048];
	snprintf(text, sizeof text, "%sreplicates = auto\nresult = median_wait\ntarget = 2\n%s", HEAD, SCENE);
	campaign c;
	sb_err e;
	int rc = sf_load(text, &c, &e);
	const cp_auto *a = &c.autorep;
	CHECK("auto.keys.defaults", !rc && a->on && a->result == CP_RES_MEDIAN_WAIT && a->target == 2 && a->batch == 4 &&
	      a->max_replicates == 32 && a->level == 0.95 && c.replicates == 0 && c.naxes == 0,
	      "%s", rc ? e.msg : "a default differs");
	if (!rc)
		campaign_free(&c);
	/* the file's lines: [campaign] 1-3, its keys from 4 */
	bad("auto.keys.no_result", "replicates = auto\ntarget = 1\n", ":4: replicates: auto needs result");
	bad("auto.keys.bad_result", "replicates = auto\nresult = mean\n",
	    ":5: result: expected one of median_wait|rise_fraction|mean_flux, got 'mean'");
	bad("auto.keys.bad_target", "replicates = auto\nresult = median_wait\ntarget = -1\n",
	    ":6: target: expected a number in (0, 1e+09], got '-1'");
	bad("auto.keys.bad_max", "replicates = auto\nresult = median_wait\ntarget = 1\nmax_replicates = 1001\n",
	    ":7: max_replicates: expected an integer in [1, 1000], got '1001'");
	bad("auto.keys.max_too_small", "replicates = auto\nresult = median_wait\ntarget = 1\nmax_replicates = 5\n",
	    ":7: max_replicates: at least 6 replicates are needed for an interval of the median wait at level 0.95, got 5");
	bad("auto.keys.only_with_auto", "target = 1\n", ":4: target: only with replicates = auto under [campaign]");
	/* the points: every axis but the replicate, no run before the driver's pass; each
	 * point fits the result */
	grid g;
	snprintf(text, sizeof text, "%sreplicates = auto\nresult = median_wait\ntarget = 2\n%s[grid]\nfrequency = 8, 9\n",
		 HEAD, SCENE);
	rc = sf_expand(text, &c, &g, &e);
	CHECK("auto.grid.points_no_runs", !rc && g.points == 2 && g.n == 0, "%s", rc ? e.msg : "runs made");
	if (!rc)
		sf_free(&c, &g);
	snprintf(text, sizeof text, "%sreplicates = auto\nresult = rise_fraction\ntarget = 2\n%s[grid]\nradius_ratio = 0, 2\n",
		 HEAD, "[scene]\nduration = 1\n");
	rc = sf_expand(text, &c, &g, &e);
	CHECK("auto.grid.needs_intruder", rc && strstr(e.msg, ":5: result: rise_fraction needs an intruder, but grid point "
	      "radius_ratio=0 has radius_ratio = 0"), "%s", rc ? e.msg : "accepted");
	if (!rc)
		sf_free(&c, &g);
	bad("auto.keys.twice", "replicates = auto\nreplicates = 3\n", ":5: replicates: given twice (first on line 4)");
}

int main(void)
{
	if (sf_init()) {
		printf("FAIL auto.setup: cannot make a temporary directory\n");
		return 1;
	}
	test_first();
	test_median();
	test_fraction_and_flux();
	test_point();
	test_keys();
	sf_cleanup();
	return tl_done();
}
