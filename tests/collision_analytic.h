/* collision_analytic.h - the linear spring-dashpot collision solved exactly, and the
 * contact-end interpolation, shared by the collision test and the accuracy benchmark. */
#ifndef SB_COLLISION_ANALYTIC_H
#define SB_COLLISION_ANALYTIC_H

#include <math.h>

#include "units.h"

/* Relative coordinate xi'' = -w02 xi - 2 beta xi', xi(0) = 0, xi'(0) = v0: contact
 * duration and restitution. Unclipped: the contact ends at xi = 0 after pi / w.
 * Clipped: the force w02 xi + 2 beta xi' reaches zero at w t* = pi - atan(2 beta w /
 * (w02 - 2 beta^2)); the disks then part force-free, so e = |xi'(t*)| / v0 and the
 * overlap lasts t* + xi(t*) / |xi'(t*)|. */
static inline void collision_analytic(double w02, double beta, int clip, double v0, double *tc,
				      double *e)
{
	double w = sqrt(w02 - beta * beta);
	if (!clip) {
		*tc = SB_PI / w;
		*e = exp(-beta * SB_PI / w);
		return;
	}
	double ts = (SB_PI - atan(2 * beta * w / (w02 - 2 * beta * beta))) / w;
	double xi = v0 / w * exp(-beta * ts) * sin(w * ts);
	double xid = v0 * exp(-beta * ts) * (cos(w * ts) - beta / w * sin(w * ts));
	*e = fabs(xid) / v0;
	*tc = ts + xi / fabs(xid);
}

/* Root in [0, h] of the cubic Hermite through (0, a, da) and (h, b, db), a > 0 >= b:
 * where the overlap ends between two steps, to O(h^4). */
static inline double hermite_root(double a, double da, double b, double db, double h)
{
	double lo = 0, hi = h;
	for (int it = 0; it < 200; it++) {
		double mid = 0.5 * (lo + hi), s = mid / h;
		double h00 = 2 * s * s * s - 3 * s * s + 1, h10 = s * s * s - 2 * s * s + s;
		double h01 = -2 * s * s * s + 3 * s * s, h11 = s * s * s - s * s;
		double p = h00 * a + h10 * h * da + h01 * b + h11 * h * db;
		if (p > 0)
			lo = mid;
		else
			hi = mid;
	}
	return 0.5 * (lo + hi);
}

#endif
