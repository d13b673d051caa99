/* resolve.c - the precision floor of an onset's interval (resolve.h). */
#include "resolve.h"

#include <math.h>

int resolve_neighbours(const double *x, size_t n, double t, double *a, double *b)
{
	double below = -INFINITY, above = INFINITY;
	int any = 0;
	*a = *b = NAN;
	if (!isfinite(t))
		return 1;
	for (size_t i = 0; i < n; i++) {
		if (!isfinite(x[i]))
			continue;
		any = 1;
		if (x[i] < t)
			below = fmax(below, x[i]);
		else
			above = fmin(above, x[i]);
	}
	if (!any)
		return 1;
	*a = isfinite(below) ? below : t;
	*b = isfinite(above) ? above : t;
	return 0;
}

int resolve_widen(double *lo, double *hi, double a, double b)
{
	if (isnan(*lo) || isnan(*hi) || isnan(a) || isnan(b))
		return 0;
	int w = 0;
	if (a < *lo) {
		*lo = a;
		w = 1;
	}
	if (b > *hi) {
		*hi = b;
		w = 1;
	}
	return w;
}

int resolve_overlap(double lo1, double hi1, double lo2, double hi2)
{
	return isfinite(lo1) && isfinite(hi1) && isfinite(lo2) && isfinite(hi2) && lo1 <= hi2 && lo2 <= hi1;
}

int resolve_grid(double t, double *lo, double *hi, const double *x, size_t n)
{
	double a, b;
	if (resolve_neighbours(x, n, t, &a, &b))
		return 0;
	return resolve_widen(lo, hi, a, b);
}
