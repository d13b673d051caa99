/* cost.h - what a campaign will cost before it starts: its runs, the simulated seconds
 * of shaking and settling and the CPU time at this machine's measured rates (calib.h),
 * per group and in total; upper bounds where the runs depend on the results (an
 * [onset] search, replicates = auto) or a stop rule may end a run early
 * (docs/campaigns.md, "Cost before the start"). */
#ifndef ST_COST_H
#define ST_COST_H

#include <stdio.h>

#include "campaign/campaign.h"
#include "campaign/grid.h"
#include "report/calib.h"

enum { COST_NINTEG = 3 }; /* enum sb_integrator's values */

typedef struct cost_sum {
	long runs;        /* exact, or at most this many (bound) */
	int bound;        /* the runs depend on the results: runs is an upper bound */
	int stop_rule;    /* some run has a stop rule: its duration is an upper bound */
	long packings;    /* settlings (shared packings, or each run's own) */
	double sim;       /* simulated seconds of shaking */
	double settle_grains[COST_NINTEG]; /* grains settled, per integrator */
	double grain_steps[COST_NINTEG];   /* grains x shaking steps, per integrator */
	/* at least (bound or stop_rule): the fewest runs (a search's chains by bisection
	 * alone, the first batch of replicates; no run failing) and each run's shortest
	 * duration under its stop rule (stop_skip for flux, stop_after for risen); no
	 * settling */
	long runs_lo;
	double sim_lo;
	double grain_steps_lo[COST_NINTEG];
} cost_sum;

/* Runs a replicate's chain of an [onset] search takes at most: the two ends and one
 * bisection per halving of [from, to] down to the tolerance. */
long cost_chain_max(double from, double to, double tolerance);
/* ... and at least: one bisection per halving, the ends not run. */
long cost_chain_min(double from, double to, double tolerance);

/* The campaign's cost per grid point (groups[p], g->points of them) and in total,
 * counted over g (an expanded grid: for a plain grid every run; for an [onset] search
 * or replicates = auto its groups, at their maximum of runs and replicates). use_cache:
 * runs with the same preparation settle once. groups may be NULL. */
void cost_count(const campaign *c, const grid *g, int use_cache, cost_sum *groups, cost_sum *total);

/* CPU seconds of s at the rates of each integrator (rates[i] for integrator i; only
 * those with work are read). */
double cost_cpu(const cost_sum *s, const calib *rates);

/* The summary: runs, simulated seconds, CPU, where the rates came from; per group for a
 * search or replicates = auto. */
void cost_print(FILE *out, const campaign *c, const cost_sum *groups, long ngroups, const cost_sum *total,
		const calib *rates);

#endif
