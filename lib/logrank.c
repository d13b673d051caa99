/* logrank.c - the log-rank test (logrank.h). */
#include "logrank.h"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct obs {
	double t;
	int ev, g;
} obs;

static int by_time(const void *a, const void *b)
{
	const obs *x = a, *y = b;
	return (x->t > y->t) - (x->t < y->t);
}

int logrank_test(const double *time, const int *event, const int *group, size_t n, int ngroups, logrank *out)
{
	out->k = 0;
	out->df = 0;
	out->chi2 = out->p = NAN;
	if (ngroups < 1 || (n && (!time || !event || !group)))
		return -1;
	obs *o = malloc(sizeof *o * (n ? n : 1));
	long *risk = calloc((size_t)ngroups, sizeof *risk), *dg = calloc((size_t)ngroups, sizeof *dg);
	double *oe = calloc((size_t)ngroups, sizeof *oe), *v = calloc((size_t)ngroups * (size_t)ngroups, sizeof *v);
	int rc = -1;
	if (!o || !risk || !dg || !oe || !v)
		goto out;
	for (size_t i = 0; i < n; i++) {
		if (group[i] < 0 || group[i] >= ngroups || !(time[i] >= 0))
			goto out;
		o[i] = (obs){time[i], event[i] != 0, group[i]};
		risk[group[i]]++;
	}
	for (int g = 0; g < ngroups; g++)
		out->k += risk[g] > 0;
	qsort(o, n, sizeof *o, by_time);
	long nt = (long)n, events = 0;
	for (size_t i = 0; i < n;) {
		/* the observations at this time: events counted against the risk set just
		 * before it, censorings at it leave after the events */
		size_t j = i;
		long d = 0;
		memset(dg, 0, sizeof *dg * (size_t)ngroups);
		while (j < n && o[j].t == o[i].t) {
			if (o[j].ev) {
				dg[o[j].g]++;
				d++;
			}
			j++;
		}
		if (d > 0 && nt > 0) {
			events += d;
			const double f = nt > 1 ? (double)d * (double)(nt - d) / (double)(nt - 1) : 0;
			for (int g = 0; g < ngroups; g++) {
				const double pg = (double)risk[g] / (double)nt;
				oe[g] += (double)dg[g] - (double)d * pg;
				for (int h = 0; h < ngroups; h++)
					v[g * ngroups + h] += f * pg * ((g == h) - (double)risk[h] / (double)nt);
			}
		}
		for (size_t q = i; q < j; q++)
			risk[o[q].g]--;
		nt -= (long)(j - i);
		i = j;
	}
	rc = 0;
	if (out->k < 2 || events == 0)
		goto out;
	/* the groups that have observations, less one (V is singular over all of them) */
	int idx[64], m = 0;
	for (int g = 0; g < ngroups && m < 64; g++) {
		long cnt = 0;
		for (size_t i = 0; i < n; i++)
			cnt += o[i].g == g;
		if (cnt)
			idx[m++] = g;
	}
	const int r = m - 1;
	gsl_matrix *V = gsl_matrix_alloc((size_t)r, (size_t)r);
	gsl_vector *b = gsl_vector_alloc((size_t)r), *x = gsl_vector_alloc((size_t)r);
	gsl_permutation *perm = gsl_permutation_alloc((size_t)r);
	int sign;
	if (V && b && x && perm) {
		for (int a = 0; a < r; a++) {
			gsl_vector_set(b, (size_t)a, oe[idx[a]]);
			for (int c = 0; c < r; c++)
				gsl_matrix_set(V, (size_t)a, (size_t)c, v[idx[a] * ngroups + idx[c]]);
		}
		if (!gsl_linalg_LU_decomp(V, perm, &sign) && fabs(gsl_linalg_LU_det(V, sign)) > 0 &&
		    !gsl_linalg_LU_solve(V, perm, b, x)) {
			double q = 0;
			for (int a = 0; a < r; a++)
				q += gsl_vector_get(b, (size_t)a) * gsl_vector_get(x, (size_t)a);
			out->chi2 = q;
			out->df = r;
			out->p = gsl_cdf_chisq_Q(q, (double)r);
		}
	}
	gsl_matrix_free(V);
	gsl_vector_free(b);
	gsl_vector_free(x);
	gsl_permutation_free(perm);
out:
	free(o);
	free(risk);
	free(dg);
	free(oe);
	free(v);
	return rc;
}
