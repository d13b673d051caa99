/* powerfit.h - a power law y = c x^p fitted to estimates with intervals (onsets
 * against a swept parameter): weighted least squares on log y against log x (GSL
 * gsl_fit_wlinear), each point weighted by its interval (sigma of log y = the
 * interval's width in log y over 2 z); the interval of p from a bootstrap over the
 * points' own bootstrap replicates, and from the fit's covariance beside it; whether
 * an interval excludes a reference exponent (docs/analysis.md, "Power-law fit"). */
#ifndef AN_POWERFIT_H
#define AN_POWERFIT_H

#include <stddef.h>

typedef struct powerfit_res {
	size_t n;              /* points used (x > 0 and y > 0, finite) */
	int weighted;          /* 1: weights from the intervals; 0: an interval had no width
				* (or none was given): ordinary least squares */
	double p, c;           /* y = c x^p */
	double se;             /* standard error of p from the covariance: with weights the
				* intervals' (not scaled by the scatter), without it the
				* residuals' (NaN with fewer than 3 points) */
	double cov_lo, cov_hi; /* p -+ z se at the level */
	double chi2;           /* weighted sum of squared residuals (n - 2 degrees of freedom) */
	double boot_lo, boot_hi; /* percentile interval of p over the replicates' fits */
	size_t boot_ok;        /* replicates whose fit had every point */
} powerfit_res;

/* sigma of ln y from an interval [lo, hi] of y at level (two-sided normal): NaN when
 * the interval is not finite, not positive or has no width. */
double powerfit_sigma(double lo, double hi, double level);

/* Fits y = c x^p to the points with x > 0 and y > 0; lo, hi (may be NULL) their
 * intervals at level. Returns 0, or -1 when fewer than 2 points (or 2 equal x)
 * remain (r->n says how many). */
int powerfit_fit(const double *x, const double *y, const double *lo, const double *hi, size_t n, double level,
		 powerfit_res *r);

/* The bootstrap interval of p: rep[i * B + b] is replicate b of point i's estimate
 * (bootstraps of independent groups, each from the same seed: point i takes its
 * replicate (b + i floor(B / n)) mod B, so that no two points share a draw), each
 * replicate fitted with the weights of powerfit_fit (r from it, same x, lo, hi);
 * sets boot_lo, boot_hi and boot_ok. A replicate with a point that is no positive
 * number is left out. Returns 0, or -1 when out of memory. */
int powerfit_boot(const double *x, const double *lo, const double *hi, const double *rep, size_t n, size_t B,
		  double level, powerfit_res *r);

/* The interval a verdict uses: the bootstrap's when it has one, else the covariance's. */
void powerfit_interval(const powerfit_res *r, double *lo, double *hi);

/* 1 when that interval excludes p0, 0 when it holds it, -1 when there is none. */
int powerfit_excludes(const powerfit_res *r, double p0);

#endif
