/* ring.c - the ratio with/without intruder and its bootstrap interval (ring.h). */
#include "ring.h"

#include <math.h>
#include <stdlib.h>

#include "boot.h"

/* The mean of v over the units idx[0..n) (all of them when idx is NULL); NaN when n = 0. */
static double mean_of(const double *v, const size_t *idx, size_t n)
{
	if (!n)
		return NAN;
	double s = 0;
	for (size_t i = 0; i < n; i++)
		s += v[idx ? idx[i] : i];
	return s / (double)n;
}

static double ratio(double a, double b, int has_ref)
{
	if (!has_ref)
		return a;
	return b != 0 ? a / b : NAN;
}

int ring_ratio(const double *with, size_t nw, const double *without, size_t nn, size_t k, size_t B,
	       unsigned long seed, double level, ring_est *out)
{
	const int ref = nn > 0;
	for (size_t q = 0; q < k; q++)
		out[q] = (ring_est){ratio(mean_of(with + q * nw, NULL, nw), ref ? mean_of(without + q * nn, NULL, nn) : NAN,
					  ref),
				    NAN, NAN, 0};
	if (!nw || !B)
		return 0;
	gsl_rng *r = boot_rng(seed);
	size_t *iw = malloc(sizeof *iw * nw), *in = malloc(sizeof *in * (nn ? nn : 1));
	double *rep = malloc(sizeof *rep * k * B);
	int rc = r && iw && in && rep ? 0 : -1;
	for (size_t b = 0; !rc && b < B; b++) {
		boot_draw(r, nw, iw);
		if (ref)
			boot_draw(r, nn, in);
		for (size_t q = 0; q < k; q++)
			rep[q * B + b] = ratio(mean_of(with + q * nw, iw, nw),
					       ref ? mean_of(without + q * nn, in, nn) : NAN, ref);
	}
	for (size_t q = 0; !rc && q < k; q++)
		out[q].ok = boot_percentile(rep + q * B, B, level, &out[q].lo, &out[q].hi);
	if (r)
		gsl_rng_free(r);
	free(iw);
	free(in);
	free(rep);
	return rc;
}
