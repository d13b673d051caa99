/* ring.h - claim 3's comparison (docs/model.md, "Ring force"): a quantity's mean over
 * the runs with an intruder divided by its mean over the runs without, with a
 * bootstrap percentile interval. The two sets are different systems (another packing,
 * another bed), so nothing pairs a run with one of the other set: each replicate
 * resamples the runs of each set apart, with replacement. */
#ifndef AN_RING_H
#define AN_RING_H

#include <stddef.h>

typedef struct ring_est {
	double value;  /* the ratio of the means (or the mean, without a reference) */
	double lo, hi; /* its percentile interval; NaN when fewer than 2 replicates are finite */
	size_t ok;     /* replicates that gave a finite value */
} ring_est;

/* k quantities at once, one draw sequence for all: with[q * nw + i] is quantity q of
 * run i with the intruder, without[q * nn + i] likewise without. out[q]: mean(with) /
 * mean(without), or the mean of with alone when nn = 0; B replicates, interval at
 * level, MT19937 seeded by seed (each replicate draws the nw runs, then the nn). A
 * mean of zero below the line gives NaN (left out of the interval). Returns 0, or -1
 * when out of memory. */
int ring_ratio(const double *with, size_t nw, const double *without, size_t nn, size_t k, size_t B,
	       unsigned long seed, double level, ring_est *out);

#endif
