/* hyst.h - hysteresis of a transition during frequency ramps: one run's /flux periods
 * split into legs (updown: the first leg ends with the period of the extreme
 * frequency; linear: one leg), the hold at ramp_from before the ramp left out, the
 * plane's Phi smoothed within each leg; the legs of several seeds pooled per branch
 * (up, down), each branch's transition frequency (sigmoid midpoint and threshold
 * crossing, sigmoid.h) and the difference up - down with a paired percentile
 * bootstrap over seeds (a drawn seed brings both of its branches). */
#ifndef AN_HYST_H
#define AN_HYST_H

#include <stddef.h>

#include "flux.h"
#include "sigmoid.h"

enum { HYST_UP = 0, HYST_DOWN = 1 };

typedef struct hyst_leg {
	size_t a, b; /* periods [a, b) */
	int branch;  /* HYST_UP or HYST_DOWN */
} hyst_leg;

/* The legs of one run (at most 2; returns their number, 0 when no period is left).
 * updown != 0: ramp_from -> ramp_to -> ramp_from, else one linear leg (up when
 * to >= from). Periods whose midpoint lies in the hold (t < hold s, the bed shaken at
 * ramp_from before the ramp starts) belong to no leg: they carry the start-of-shaking
 * transient at one frequency. */
int hyst_legs(const flux_data *d, int updown, double from, double to, double hold, hyst_leg leg[2]);

/* Centred running mean over K periods (K/2 either side, cut at the leg's ends):
 * out[p] for p in [a, b) from v[a .. b). */
void hyst_smooth(const double *v, size_t a, size_t b, long K, double *out);

typedef struct hyst_pts {
	double *x, *y; /* frequency, smoothed Phi */
	long *u;       /* seed (replicate) of the point */
	size_t n, cap;
} hyst_pts;

typedef struct hyst_data {
	hyst_pts br[2]; /* HYST_UP, HYST_DOWN */
	long *units;    /* distinct seeds, in order of appearance */
	size_t nu, ucap, nruns;
	double thr;     /* threshold for the crossing (NaN: midpoint of each branch) */
	double *xs, *ys; /* resample scratch (hyst_estimate) */
} hyst_data;

/* Empty data; thr: the threshold of the crossings (NaN: midpoint of each branch). */
void hyst_init(hyst_data *h, double thr);
/* One run of seed unit joins (counts runs and distinct seeds); then its points. */
int hyst_add_run(hyst_data *h, long unit);
int hyst_add(hyst_data *h, int branch, double f, double phi, long unit);
void hyst_free(hyst_data *h);

typedef struct hyst_res {
	/* 0 up sigmoid f0, 1 down sigmoid f0, 2 their difference, 3 up threshold
	 * crossing, 4 down threshold crossing, 5 their difference */
	double v[6], lo[6], hi[6];
	sig_fit fit[2];  /* the sigmoids of all points, per branch */
	size_t boot_ok;  /* replicates with both sigmoid midpoints */
} hyst_res;

/* Estimates on all points, intervals at level from B replicates seeded by seed
 * (NaN without a bootstrap: B < 2 or one seed). Returns 0, or -1 when out of memory. */
int hyst_estimate(hyst_data *h, size_t B, unsigned long seed, double level, hyst_res *r);

#endif
