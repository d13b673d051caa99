/* lowerrow.c - the start one row lower and the Fisher exact test (lowerrow.h). */
#include "lowerrow.h"

#include <gsl/gsl_randist.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* v as a number when all of it is one (as adb.c's an_num), else NaN */
static double num(const char *v)
{
	if (!v || !*v)
		return NAN;
	char *end;
	const double x = strtod(v, &end);
	return *end ? NAN : x;
}

/* two values of one key alike: as numbers when both are, else as text (as the
 * grouping, adb.c, compares them) */
static int same(const char *a, const char *b)
{
	const double x = num(a), y = num(b);
	if (!isnan(x) && !isnan(y))
		return x == y;
	return !strcmp(a ? a : "", b ? b : "");
}

/* The one place that says what "one row lower" is. docs/model.md, "Preparation" (1.
 * Placement): the scene key `depth` is the number of full grain rows beneath the
 * intruder (0 = on the floor), so the paper's "starting the intruder one row lower"
 * is depth - 1. */
static double one_row_lower(double depth)
{
	return depth - 1;
}

int lowerrow_partner_of(const char (*keys)[48], int nk, const char *const *gval, int ng, int j)
{
	int kd = -1;
	for (int k = 0; k < nk; k++)
		if (!strcmp(keys[k], "depth"))
			kd = k;
	if (kd < 0 || !gval || j < 0 || j >= ng)
		return -1;
	const double want = one_row_lower(num(gval[j * nk + kd]));
	if (isnan(want))
		return -1;
	for (int i = 0; i < ng; i++) {
		if (i == j || num(gval[i * nk + kd]) != want)
			continue;
		int k = 0;
		while (k < nk && (k == kd || same(gval[i * nk + k], gval[j * nk + k])))
			k++;
		if (k == nk)
			return i;
	}
	return -1;
}

int lowerrow_partner(const an_tool *t, int j)
{
	return lowerrow_partner_of((const char (*)[48])t->keys, t->nk, (const char *const *)t->gval, t->ng, j);
}

double lowerrow_fisher_p(long k1, long n1, long k2, long n2)
{
	if (n1 <= 0 || n2 <= 0 || k1 < 0 || k2 < 0 || k1 > n1 || k2 > n2 || n1 > INT_MAX / 2 || n2 > INT_MAX / 2)
		return NAN;
	/* given the margins, the risen runs of sample 1 are hypergeometric: n1 drawn from
	 * N = n1 + n2 of which K = k1 + k2 rose */
	const unsigned K = (unsigned)(k1 + k2), F = (unsigned)(n1 + n2) - K, t = (unsigned)n1;
	const long lo = n1 - (long)F > 0 ? n1 - (long)F : 0, hi = (long)K < n1 ? (long)K : n1;
	const double pobs = gsl_ran_hypergeometric_pdf((unsigned)k1, K, F, t) * (1 + 1e-7);
	double p = 0;
	for (long x = lo; x <= hi; x++) {
		const double px = gsl_ran_hypergeometric_pdf((unsigned)x, K, F, t);
		if (px <= pobs)
			p += px;
	}
	return fmin(1, p);
}
