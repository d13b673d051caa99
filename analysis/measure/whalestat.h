/* whalestat.h - statistics over runs for bin/whale: a mean with its bootstrap
 * percentile interval (the runs of a group are independent replicates: each
 * replicate draws them with replacement), and Spearman's rank correlation of a run's
 * number with its radius ratio, with a permutation p-value. Many runs share one 𝓡, so
 * the ranks are tied: mid-ranks, and a p-value from permuting the numbers over the
 * runs (exact in distribution under ties and small n, where the t approximation is
 * not), two-sided, (1 + #{|rho*| >= |rho|}) / (1 + B). */
#ifndef AN_WHALESTAT_H
#define AN_WHALESTAT_H

#include <stddef.h>

typedef struct whale_ci {
	double mean;   /* NaN when n = 0 */
	double lo, hi; /* percentile interval; NaN when fewer than 2 runs or replicates */
	size_t n;      /* the runs it rests on */
} whale_ci;

/* The mean of v[0..n) and its interval at level over B replicates, MT19937 seeded by
 * seed. Returns 0, -1 when out of memory. */
int whale_mean_ci(const double *v, size_t n, size_t B, unsigned long seed, double level, whale_ci *out);

/* Mid-ranks (1-based) of v[0..n) into r. Returns 0, -1 when out of memory. */
int whale_ranks(const double *v, size_t n, double *r);

typedef struct whale_trend {
	double rho;  /* Spearman's rank correlation; NaN when it does not exist (n < 3, or x
		      * or y constant) */
	double p;    /* two-sided permutation p-value; NaN with rho */
	size_t n;    /* the runs */
	size_t B;    /* permutations */
} whale_trend;

/* rho of x[0..n) and y[0..n) (Pearson's correlation of their mid-ranks) and its
 * permutation p-value over B shuffles of y, MT19937 seeded by seed. Returns 0, -1
 * when out of memory. */
int whale_spearman(const double *x, const double *y, size_t n, size_t B, unsigned long seed, whale_trend *out);

#endif
