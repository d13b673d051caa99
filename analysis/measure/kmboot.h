/* kmboot.h - the bootstrap of a Kaplan-Meier median over runs: each replicate a resample
 * of the group's runs with replacement, its median known exactly when the resample's
 * curve reaches 1/2 and else only bounded below by its longest observation (a censored
 * median), as bootdiff_bounds takes them (docs/analysis.md, "Waiting times"). */
#ifndef AN_KMBOOT_H
#define AN_KMBOOT_H

#include <stddef.h>

/* The n runs' times t[i] and events ev[i] (1 risen, 0 censored), B replicates from
 * seed (boot_run: the same seed draws the same indices for groups of the same size):
 * replicate k's median lies in [lo[k], hi[k]]: lo = hi = the median when the resample's
 * curve reaches 1/2; else lo = its longest observation, hi = +inf. *censored: the
 * replicates of the second kind. Returns 0, or -1 when out of memory or n = 0. */
int kmboot_median(const double *t, const int *ev, size_t n, size_t B, unsigned long seed, double *lo, double *hi,
		  size_t *censored);

#endif
