/* km.c - Kaplan-Meier estimator, Greenwood errors, median with its interval. */
#include "km.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct obs {
	double t;
	int ev;
};

static int cmp_obs(const void *a, const void *b)
{
	const struct obs *p = a, *q = b;
	if (p->t != q->t)
		return p->t < q->t ? -1 : 1;
	return q->ev - p->ev; /* events first at tied times */
}

int km_fit(const double *time, const int *event, size_t n, km_curve *k)
{
	memset(k, 0, sizeof *k);
	for (size_t i = 0; i < n; i++)
		if (!(time[i] >= 0) || !isfinite(time[i]))
			return -1;
	struct obs *o = malloc(sizeof *o * (n ? n : 1));
	k->t = malloc(sizeof *k->t * (n ? n : 1));
	k->n_risk = malloc(sizeof *k->n_risk * (n ? n : 1));
	k->d = malloc(sizeof *k->d * (n ? n : 1));
	k->c = malloc(sizeof *k->c * (n ? n : 1));
	k->s = malloc(sizeof *k->s * (n ? n : 1));
	k->se = malloc(sizeof *k->se * (n ? n : 1));
	if (!o || !k->t || !k->n_risk || !k->d || !k->c || !k->s || !k->se) {
		free(o);
		km_free(k);
		return -1;
	}
	for (size_t i = 0; i < n; i++) {
		o[i].t = time[i];
		o[i].ev = event[i] != 0;
	}
	qsort(o, n, sizeof *o, cmp_obs);
	k->n = (long)n;
	double s = 1, gw = 0; /* gw: Greenwood's sum */
	long risk = (long)n;
	for (size_t i = 0; i < n;) {
		size_t j = i;
		long d = 0, c = 0;
		while (j < n && o[j].t == o[i].t) {
			d += o[j].ev;
			c += !o[j].ev;
			j++;
		}
		size_t m = k->m++;
		k->t[m] = o[i].t;
		k->n_risk[m] = risk;
		k->d[m] = d;
		k->c[m] = c;
		if (d) {
			s *= 1 - (double)d / (double)risk;
			if (risk > d)
				gw += (double)d / ((double)risk * (double)(risk - d));
		}
		k->s[m] = s;
		k->se[m] = s > 0 ? s * sqrt(gw) : 0;
		k->events += d;
		risk -= d + c;
		i = j;
	}
	free(o);
	return 0;
}

void km_free(km_curve *k)
{
	free(k->t);
	free(k->n_risk);
	free(k->d);
	free(k->c);
	free(k->s);
	free(k->se);
	memset(k, 0, sizeof *k);
}

double km_at(const km_curve *k, double t)
{
	double s = 1;
	for (size_t i = 0; i < k->m && k->t[i] <= t; i++)
		s = k->s[i];
	return s;
}

/* First event time at which band(i) <= 0.5. */
static double first_below(const km_curve *k, double z)
{
	for (size_t i = 0; i < k->m; i++) {
		if (!k->d[i])
			continue;
		double v = k->s[i] + z * k->se[i];
		if (v > 1)
			v = 1;
		if (v < 0)
			v = 0;
		if (v <= 0.5)
			return k->t[i];
	}
	return NAN;
}

double km_median(const km_curve *k, double z, double *lo, double *hi)
{
	/* the lower band reaches 0.5 first: it bounds the median from below */
	*lo = first_below(k, -z);
	*hi = first_below(k, z);
	return first_below(k, 0);
}
