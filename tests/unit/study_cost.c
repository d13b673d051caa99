/* study_cost.c - a campaign's cost before the start (study/report/cost.c, calib.c):
 * the most runs a bisection chain takes, the rates fitted from two calibration runs,
 * and the counts of a plain grid (exact: runs, shared packings, grain-steps) and of an
 * [onset] search (upper bounds: chain x replicates), each against numbers worked out
 * by hand; a stop rule makes the duration an upper bound. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "report/calib.h"
#include "report/cost.h"
#include "study_files.h"
#include "testlib.h"

int main(void)
{
	/* [2.5, 3.2] to 0.02: 0.7 / 0.02 = 35 -> 6 halvings (0.7/64 < 0.02 < 0.7/32), plus both ends */
	CHECK("cost.chain.claim1", cost_chain_max(2.5, 3.2, 0.02) == 8, "got %ld", cost_chain_max(2.5, 3.2, 0.02));
	/* exactly a power of two: 1 / 0.25 = 4 -> 2 halvings */
	CHECK("cost.chain.power_of_two", cost_chain_max(0, 1, 0.25) == 4, "got %ld", cost_chain_max(0, 1, 0.25));
	CHECK("cost.chain.already_narrow", cost_chain_max(0, 1, 2) == 2, "got %ld", cost_chain_max(0, 1, 2));

	/* 100 grains: 1 s for 1000 steps, 3 s for 3000 -> 1e-3 s per step = 1e-5 per grain-step,
	 * and 0 s left for the settling; with 0.5 s more at both, 5e-3 per grain */
	calib k;
	calib_fit(1, 1000, 3, 3000, 100, &k);
	CHECK_REL("cost.fit.step", k.step, 1e-5, 1e-12);
	CHECK("cost.fit.no_settle", fabs(k.settle) < 1e-15, "got %g", k.settle);
	calib_fit(1.5, 1000, 3.5, 3000, 100, &k);
	CHECK_REL("cost.fit.settle", k.settle, 5e-3, 1e-12);
	calib_fit(3, 1000, 1, 3000, 100, &k); /* a noisy clock: never a negative cost */
	CHECK("cost.fit.clamped", k.step > 0 && k.settle >= 0, "step %g settle %g", k.step, k.settle);

	if (sf_init()) {
		CHECK("cost.setup", 0, "mkdtemp failed");
		return tl_done();
	}
	/* a grid: 2 frequencies x 3 replicates, 200 grains, dt 2e-4 (fast), 1 s: 5000 steps a
	 * run; the frequency is no preparation key: 3 packings shared (6 without the cache) */
	campaign c;
	grid g;
	sb_err e;
	const char *grid_text = "[campaign]\nname = g\nseed = 1\nreplicates = 3\n[scene]\nn_grains = 200\npreset = fast\n"
				"duration = 1\n[grid]\nfrequency = 3, 4\n";
	if (sf_expand(grid_text, &c, &g, &e)) {
		CHECK("cost.grid.setup", 0, "%s", e.msg);
	} else {
		cost_sum groups[6], t;
		const long points = g.points; /* the replicates are points of a plain grid */
		cost_count(&c, &g, 1, points <= 6 ? groups : NULL, &t);
		CHECK("cost.grid.exact", t.runs == 6 && !t.bound && !t.stop_rule && t.packings == 3 && t.sim == 6,
		      "runs %ld bound %d stop %d packings %ld sim %g", t.runs, t.bound, t.stop_rule, t.packings, t.sim);
		CHECK_REL("cost.grid.grain_steps", t.grain_steps[INTEG_VERLET], 6.0 * 5000 * 200, 1e-12);
		long sum = 0;
		for (long p = 0; p < points && points <= 6; p++)
			sum += groups[p].runs;
		CHECK("cost.grid.per_point", points == 6 && sum == 6 && groups[0].runs == 1, "points %ld, runs %ld", points,
		      sum);
		calib rates[COST_NINTEG] = {{0}};
		rates[INTEG_VERLET].step = 1e-8;
		rates[INTEG_VERLET].settle = 1e-3;
		CHECK_REL("cost.grid.cpu", cost_cpu(&t, rates), 6.0 * 5000 * 200 * 1e-8 + 3 * 200 * 1e-3, 1e-12);
		cost_count(&c, &g, 0, NULL, &t);
		CHECK("cost.grid.no_cache", t.packings == 6, "packings %ld", t.packings);
		sf_free(&c, &g);
	}
	/* an [onset] search: 2 replicates, each chain at most 8 runs, 120 s each (a bound) */
	const char *onset_text = "[campaign]\nname = o\nseed = 1\n[scene]\nradius_ratio = 0\nduration = 120\nflux = yes\n"
				 "[onset]\nobservable = flux\nfrom = 2.5\nto = 3.2\ntolerance = 0.02\nthreshold = 2\n"
				 "band = 0.4:0.6\nreplicates = 2\n";
	if (sf_expand(onset_text, &c, &g, &e)) {
		CHECK("cost.onset.setup", 0, "%s", e.msg);
	} else {
		cost_sum t;
		cost_count(&c, &g, 1, NULL, &t);
		CHECK("cost.onset.bound", t.bound && t.runs == 16 && t.packings == 2 && t.sim == 16 * 120.0,
		      "bound %d runs %ld packings %ld sim %g", t.bound, t.runs, t.packings, t.sim);
		CHECK_REL("cost.onset.grain_steps", t.grain_steps[INTEG_GEAR5], 16.0 * (120 / 5e-5) * 950, 1e-9);
		sf_free(&c, &g);
	}
	/* a stop rule: the duration is only the longest a run may take */
	const char *stop_text = "[campaign]\nname = s\nseed = 1\n[scene]\nduration = 30\nstop = risen\n[grid]\n"
				"frequency = 3\n";
	if (sf_expand(stop_text, &c, &g, &e)) {
		CHECK("cost.stop.setup", 0, "%s", e.msg);
	} else {
		cost_sum t;
		cost_count(&c, &g, 1, NULL, &t);
		CHECK("cost.stop.upper", t.stop_rule && !t.bound && t.runs == 1, "stop %d bound %d runs %ld", t.stop_rule,
		      t.bound, t.runs);
		sf_free(&c, &g);
	}
	sf_cleanup();
	return tl_done();
}
