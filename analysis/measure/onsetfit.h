/* onsetfit.h - a transition frequency from runs of several seeds: y(f) pooled over
 * the seeds, the sigmoid midpoint and the threshold crossing (sigmoid.h), percentile
 * bootstrap intervals over seeds (all points of a drawn seed together; over points
 * when there is only one seed), and the spread of the per-seed threshold estimates.
 * Shared by bin/onset (Phi per run vs frequency) and bin/hysteresis (Phi per period
 * vs the ramp's frequency). */
#ifndef AN_ONSETFIT_H
#define AN_ONSETFIT_H

#include <stddef.h>

#include "sigmoid.h"

typedef struct onset_res {
	sig_fit fit;               /* all points */
	double thr;                /* threshold crossing, all points */
	double fit_lo, fit_hi;     /* bootstrap interval of fit.x0 */
	double thr_lo, thr_hi;     /* ... of thr */
	double seed_sd;            /* sd of the per-seed threshold crossings (NaN if < 2) */
	int per_unit;              /* the units share no frequency grid (a search's
				    * replicates, each its own bisection): thr and its bootstrap
				    * are the median of the units' own crossings, not the pooled
				    * means' crossing, which one run could set */
	size_t units, boot_ok;     /* bootstrap units; replicates whose fit succeeded */
	double *seed_fit, *seed_thr; /* [units] per-unit estimates (malloc'd) */
	long *unit_id;             /* [units] */
	double *boot;              /* [2 B] the replicates in draw order: fit.x0's, then thr's
				    * (NaN: failed), for differences and fits across groups;
				    * NULL without a bootstrap */
	size_t B;
} onset_res;

/* x[i], y[i] from unit[i] (seed / replicate id). threshold NaN: midpoint of the means.
 * Units that sample the same frequencies (a grid): thr is the pooled means' crossing;
 * units that do not (per_unit): the median of their own crossings.
 * B < 2: no bootstrap (intervals NaN). Returns 0, or -1 when out of memory. */
int onset_estimate(const double *x, const double *y, const long *unit, size_t n, double threshold, size_t B,
		   unsigned long seed, double level, onset_res *r);
void onset_res_free(onset_res *r);

#endif
