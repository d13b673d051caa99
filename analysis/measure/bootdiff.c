/* bootdiff.c - a difference of two groups' estimates from their bootstraps (bootdiff.h). */
#include "bootdiff.h"

#include <math.h>
#include <stdlib.h>

#include "boot.h"

int bootdiff_run(double a, double b, const double *ra, const double *rb, size_t B, double level, bootdiff_res *r)
{
	r->d = b - a;
	r->lo = r->hi = NAN;
	r->ok = 0;
	r->zero = -1;
	if (B < 2 || !ra || !rb)
		return 0;
	double *v = malloc(sizeof *v * B);
	if (!v)
		return -1;
	for (size_t k = 0; k < B; k++)
		v[k] = rb[k] - ra[(k + B / 2) % B];
	r->ok = boot_percentile(v, B, level, &r->lo, &r->hi);
	if (isfinite(r->lo) && isfinite(r->hi))
		r->zero = r->lo <= 0 && r->hi >= 0;
	free(v);
	return 0;
}
