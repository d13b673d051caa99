/* whale.h - the whale effect in one run (docs/model.md, "The paper's claims", 4): after
 * its rise the intruder does not stay at the top but dives into the bed and comes back,
 * again and again. Its dives are read off the box-frame height y(t) (traj.h) in the
 * window from the rise plus a skip to the end of the trajectory:
 *
 * - y is first averaged over one drive period (a centred running mean over 1/f): the
 *   bed's flight within each period moves the intruder by up to a few cm in the box
 *   frame at Gamma > 1, and would otherwise be taken for a dive;
 * - the top level is the q-quantile (0.9) of the averaged y in the window: where the
 *   intruder is when it is at the top, robust to the time it spends below;
 * - a dive starts when y falls below top - D and ends when y is back at or above
 *   top - D/2 (hysteresis: noise around one threshold does not make two dives); the
 *   window's start counts as "in a dive" until y first reaches top - D/2, so a dive
 *   under way at the start is not counted (its start is unknown);
 * - the period is the mean time between successive dive starts, (last - first) /
 *   (n - 1), with n >= 2 dives; else there is none (NaN);
 * - a dive's depth is top - the lowest y within it; the mean depth is over the dives
 *   that ended within the window (an unfinished last dive's minimum is only a bound);
 * - the rate is dives per minute of window (zero dives counted: a run that stays at the
 *   top has rate 0, and no period);
 * - rms is the standard deviation of the averaged y in the window.
 * Pure computation: no I/O, no printing. */
#ifndef AN_WHALE_H
#define AN_WHALE_H

#include <stddef.h>

typedef struct whale_opts {
	double dive;     /* D (cm): how far below the top level a dive goes, > 0 */
	double top_q;    /* the top level's quantile of y, in (0, 1] (0.9) */
	double drive_f;  /* the drive frequency (Hz) the running mean averages over; 0: none */
} whale_opts;

typedef struct whale_run {
	double t0, t1;      /* the window analysed (s) */
	size_t samples;     /* samples in the window */
	double top;         /* top level (cm, box frame) */
	double lo, hi;      /* the dive threshold top - D and the level ending a dive top - D/2 */
	long dives;         /* dives started within the window */
	long done;          /* ... of which ended within it */
	double period;      /* mean time between dive starts (s); NaN with fewer than 2 dives */
	double depth;       /* mean depth of the ended dives (cm); NaN with none */
	double depth_max;   /* the deepest ended dive (cm); NaN with none */
	double rate;        /* dives per minute of window */
	double mean, rms;   /* mean and rms about it of the averaged y (cm) */
	double first, last; /* the first and the last dive's start (s); NaN when none */
} whale_run;

/* No window yet: t0 and NaN or 0 in every field. */
void whale_run_init(whale_run *r, double t0);

/* The dives of y[0..n) (times t[0..n), increasing) at t >= t0: out filled. Returns 0,
 * 1 when fewer than 3 samples lie in the window (out->samples says how many; the rest
 * NaN or 0), -1 when out of memory. When starts is not NULL, the dive starts are
 * written to *starts (malloc'd, out->dives of them; free by the caller). */
int whale_dives(const double *t, const double *y, size_t n, double t0, const whale_opts *o, whale_run *out,
		double **starts);

/* The centred running mean of y[0..n) over a window of w seconds (t increasing,
 * samples not necessarily evenly spaced: each sample's mean is over the samples within
 * w/2 of it, fewer near the ends); w <= 0 copies y. Returns 0 or -1 (out of memory). */
int whale_smooth(const double *t, const double *y, size_t n, double w, double *out);

/* The q-quantile of v[0..n) (linear between order statistics, as GSL's); v is not
 * changed. NaN when n = 0 or out of memory. */
double whale_quantile(const double *v, size_t n, double q);

#endif
