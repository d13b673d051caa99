/* periodic.h - the periodic side boundary in x (docs/model.md, "Periodic side
 * boundaries"): the minimum image of a horizontal distance, the wrap of a position
 * into [0, W), and the wrap of the state at a neighbour-list rebuild. A period W <= 0
 * means walls: every function then leaves its number as it is, to the bit. */
#ifndef SB_PERIODIC_H
#define SB_PERIODIC_H

#include <math.h>

#include "state.h"

/* dx shifted by a whole number of periods into [-W/2, W/2] */
static inline double periodic_image(double dx, double W)
{
	return W > 0 ? dx - W * floor(dx / W + 0.5) : dx;
}

/* x shifted by a whole number of periods into [0, W); a position already there is
 * returned unchanged */
static inline double periodic_wrap(double x, double W)
{
	if (!(W > 0) || (x >= 0 && x < W) || !isfinite(x)) /* a NaN stays one */
		return x;
	double r = x - W * floor(x / W);
	return r < W && r >= 0 ? r : 0; /* x = -1e-20 rounds to W */
}

/* The midpoint of two x on the circle of period W (through the minimum image),
 * wrapped into [0, W); with walls, 0.5 (a + b) */
static inline double periodic_mid(double a, double b, double W)
{
	return W > 0 ? periodic_wrap(a + 0.5 * periodic_image(b - a, W), W) : 0.5 * (a + b);
}

/* Wrap the mobile disks' x (Nordsieck q0; the derivatives are unchanged) into
 * [0, W); returns how many moved. Called right before a neighbour-list build only,
 * so that the displacement since the last build never sees a wrap. */
int periodic_wrap_state(sb_state *st, double W);

#endif
