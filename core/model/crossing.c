/* crossing.c - crossings of the flux lines between two samples (crossing.h). */
#include "crossing.h"

#include <math.h>

void crossing_lines(double surface, int nlines, double *h)
{
	for (int l = 0; l < nlines; l++)
		h[l] = surface * (l + 0.5) / nlines;
}

void crossing_count(int n, const double *xp, const double *yp, const double *x, const double *y, double x0,
		    double x1, double surface, int nlines, const double *h, double *jtop, double *jbot)
{
	const double xc = 0.5 * (x0 + x1), quarter = 0.25 * (x1 - x0);
	const double dh = surface / nlines;
	for (int i = 0; i < n; i++) {
		double y0 = yp[i], y1 = y[i];
		if (y0 == y1)
			continue;
		int up = y1 > y0;
		double lo = up ? y0 : y1, hi = up ? y1 : y0;
		/* lines l with lo < h_l <= hi (for up) or lo < h_l <= hi with roles swapped */
		int l0 = (int)ceil(lo / dh - 0.5), l1 = (int)floor(hi / dh - 0.5);
		if (l0 < 0)
			l0 = 0;
		if (l1 > nlines - 1)
			l1 = nlines - 1;
		double *j = fabs(0.5 * (xp[i] + x[i]) - xc) < quarter ? jtop : jbot;
		for (int l = l0; l <= l1; l++) {
			const double hl = h[l];
			if (up ? (y0 < hl && hl <= y1) : (y1 < hl && hl <= y0))
				j[l] += up ? 1 : -1;
		}
	}
}
