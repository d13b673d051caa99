/* bootdiff.h - the difference of two groups' estimates with a percentile interval
 * from their own bootstraps (each group resampled apart, over its seeds), and whether
 * the interval holds 0 (docs/analysis.md, "Differences between groups"). */
#ifndef AN_BOOTDIFF_H
#define AN_BOOTDIFF_H

#include <stddef.h>

typedef struct bootdiff_res {
	double d;        /* b - a (NaN when either is unknown) */
	double lo, hi;   /* percentile interval at the level (NaN with < 2 replicates;
			  * -inf, +inf: unbounded on that side) */
	size_t ok;       /* replicates where both estimates exist */
	int zero;        /* 1: the interval holds 0; 0: it excludes it; -1: no interval */
} bootdiff_res;

/* a, b: the two estimates; ra[0..B), rb[0..B): their replicates in draw order (NaN:
 * failed). Both bootstraps start from the same seed, so replicate k of either draws
 * the same indices: b's replicate k is paired with a's (k + B/2) mod B, which makes
 * the two resamples independent. Returns 0, or -1 when out of memory. */
int bootdiff_run(double a, double b, const double *ra, const double *rb, size_t B, double level, bootdiff_res *r);

/* The same when a replicate is known only within bounds: a's replicate k lies in
 * [la[k], ha[k]] and b's in [lb[k], hb[k]] (lower ends finite or NaN; an upper end
 * +inf: known only to exceed the lower, as a Kaplan-Meier median the resample's curve
 * never reaches exceeds its longest observation). The interval's lower limit is the
 * percentile of the differences' least values lb - ha, its upper limit that of their
 * greatest hb - la: conservative where a replicate is bounded, and bootdiff_run's
 * interval where every one is known (la = ha, lb = hb). */
int bootdiff_bounds(double a, double b, const double *la, const double *ha, const double *lb, const double *hb,
		    size_t B, double level, bootdiff_res *r);

#endif
