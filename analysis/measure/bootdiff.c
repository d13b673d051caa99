/* bootdiff.c - a difference of two groups' estimates from their bootstraps (bootdiff.h). */
#include "bootdiff.h"

#include <gsl/gsl_sort.h>
#include <math.h>
#include <stdlib.h>

#include "boot.h"

int bootdiff_run(double a, double b, const double *ra, const double *rb, size_t B, double level, bootdiff_res *r)
{
	return bootdiff_bounds(a, b, ra, ra, rb, rb, B, level, r);
}

int bootdiff_bounds(double a, double b, const double *la, const double *ha, const double *lb, const double *hb,
		    size_t B, double level, bootdiff_res *r)
{
	r->d = b - a;
	r->lo = r->hi = NAN;
	r->ok = 0;
	r->zero = -1;
	if (B < 2 || !la || !ha || !lb || !hb)
		return 0;
	double *lo = malloc(sizeof *lo * B), *hi = malloc(sizeof *hi * B);
	if (!lo || !hi) {
		free(lo);
		free(hi);
		return -1;
	}
	/* the pairs where both replicates exist (an infinite end is an unbounded one, kept
	 * in the order; NaN a failed replicate, left out) */
	size_t m = 0;
	for (size_t k = 0; k < B; k++) {
		const size_t j = (k + B / 2) % B;
		const double l = lb[k] - ha[j], h = hb[k] - la[j];
		if (isnan(l) || isnan(h))
			continue;
		lo[m] = l;
		hi[m++] = h;
	}
	r->ok = m;
	if (m >= 2) {
		gsl_sort(lo, 1, m);
		gsl_sort(hi, 1, m);
		const double q = 0.5 * (1 - level);
		r->lo = boot_quantile(lo, m, q);
		r->hi = boot_quantile(hi, m, 1 - q);
		r->zero = r->lo <= 0 && r->hi >= 0;
	}
	free(lo);
	free(hi);
	return 0;
}
