/* hyst.c - legs of frequency ramps, smoothing, up/down transitions with a paired bootstrap. */
#include "hyst.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "boot.h"

int hyst_legs(const flux_data *d, int updown, double from, double to, double hold, hyst_leg leg[2])
{
	/* period p spans t[p-1] .. t[p] (the first from 0); the samples fall on the first
	 * step after each phase-0 crossing, so compare midpoints, not ends, with the hold */
	size_t a = 0;
	while (a < d->P && 0.5 * ((a ? d->t[a - 1] : 0) + d->t[a]) < hold)
		a++;
	if (a >= d->P)
		return 0;
	int rising = !(to < from);
	int first = rising ? HYST_UP : HYST_DOWN;
	if (!updown) {
		leg[0] = (hyst_leg){a, d->P, first};
		return 1;
	}
	size_t best = a;
	for (size_t p = a + 1; p < d->P; p++)
		if (rising ? d->f[p] > d->f[best] : d->f[p] < d->f[best])
			best = p;
	leg[0] = (hyst_leg){a, best + 1, first};
	if (best + 1 >= d->P)
		return 1;
	leg[1] = (hyst_leg){best + 1, d->P, rising ? HYST_DOWN : HYST_UP};
	return 2;
}

void hyst_smooth(const double *v, size_t a, size_t b, long K, double *out)
{
	size_t h = K > 1 ? (size_t)(K / 2) : 0;
	for (size_t p = a; p < b; p++) {
		size_t q0 = p >= a + h ? p - h : a, q1 = p + h + 1 < b ? p + h + 1 : b;
		double s = 0;
		for (size_t q = q0; q < q1; q++)
			s += v[q];
		out[p] = s / (double)(q1 - q0);
	}
}

static int grow(hyst_pts *p)
{
	size_t cap = p->cap ? 2 * p->cap : 256;
	double *x = realloc(p->x, sizeof *x * cap);
	if (!x)
		return -1;
	p->x = x;
	double *y = realloc(p->y, sizeof *y * cap);
	if (!y)
		return -1;
	p->y = y;
	long *u = realloc(p->u, sizeof *u * cap);
	if (!u)
		return -1;
	p->u = u;
	p->cap = cap;
	return 0;
}

void hyst_init(hyst_data *h, double thr)
{
	memset(h, 0, sizeof *h);
	h->thr = thr;
}

int hyst_add_run(hyst_data *h, long unit)
{
	size_t u = 0;
	while (u < h->nu && h->units[u] != unit)
		u++;
	if (u == h->nu) {
		if (h->nu == h->ucap) {
			size_t cap = h->ucap ? 2 * h->ucap : 16;
			long *p = realloc(h->units, sizeof *p * cap);
			if (!p)
				return -1;
			h->units = p;
			h->ucap = cap;
		}
		h->units[h->nu++] = unit;
	}
	h->nruns++;
	return 0;
}

int hyst_add(hyst_data *h, int branch, double f, double phi, long unit)
{
	hyst_pts *p = &h->br[branch ? 1 : 0];
	if (p->n == p->cap && grow(p))
		return -1;
	p->x[p->n] = f;
	p->y[p->n] = phi;
	p->u[p->n++] = unit;
	return 0;
}

void hyst_free(hyst_data *h)
{
	for (int b = 0; b < 2; b++) {
		free(h->br[b].x);
		free(h->br[b].y);
		free(h->br[b].u);
	}
	free(h->units);
	free(h->xs);
	free(h->ys);
	memset(h, 0, sizeof *h);
}

/* The points of branch b of the seeds idx[0..n) (indices into h->units, repeated
 * when drawn more than once) into h->xs, h->ys. */
static size_t gather(hyst_data *h, int b, const size_t *idx, size_t n)
{
	size_t k = 0;
	const hyst_pts *p = &h->br[b];
	for (size_t i = 0; i < n; i++)
		for (size_t j = 0; j < p->n; j++)
			if (p->u[j] == h->units[idx[i]]) {
				h->xs[k] = p->x[j];
				h->ys[k++] = p->y[j];
			}
	return k;
}

static void stat6(void *ctx, const size_t *idx, size_t n, double *out)
{
	hyst_data *h = ctx;
	for (int b = 0; b < 2; b++) {
		size_t k = gather(h, b, idx, n);
		sig_fit s;
		out[b] = sig_fit_data(h->xs, h->ys, k, &s) ? s.x0 : NAN;
		out[3 + b] = sig_threshold(h->xs, h->ys, k, h->thr);
	}
	out[2] = out[0] - out[1];
	out[5] = out[3] - out[4];
}

int hyst_estimate(hyst_data *h, size_t B, unsigned long seed, double level, hyst_res *r)
{
	memset(r, 0, sizeof *r);
	for (int q = 0; q < 6; q++)
		r->v[q] = r->lo[q] = r->hi[q] = NAN;
	/* a resample holds at most (seeds) x (points of the branch) points */
	size_t most = h->br[0].n > h->br[1].n ? h->br[0].n : h->br[1].n;
	size_t cap = most * (h->nu ? h->nu : 1) + 1;
	free(h->xs);
	free(h->ys);
	h->xs = malloc(sizeof *h->xs * cap);
	h->ys = malloc(sizeof *h->ys * cap);
	size_t *all = malloc(sizeof *all * (h->nu + 1));
	double *bo = B > 1 && h->nu > 1 ? malloc(sizeof *bo * 6 * B) : NULL;
	int rc = -1;
	if (!h->xs || !h->ys || !all || (B > 1 && h->nu > 1 && !bo))
		goto out;
	for (size_t u = 0; u < h->nu; u++)
		all[u] = u;
	stat6(h, all, h->nu, r->v);
	for (int b = 0; b < 2; b++)
		sig_fit_data(h->xs, h->ys, gather(h, b, all, h->nu), &r->fit[b]);
	if (bo) {
		if (boot_run(seed, h->nu, B, 6, stat6, h, bo))
			goto out;
		for (int q = 0; q < 6; q++) {
			size_t ok = boot_percentile(bo + (size_t)q * B, B, level, &r->lo[q], &r->hi[q]);
			if (q == 2)
				r->boot_ok = ok;
		}
	}
	rc = 0;
out:
	free(all);
	free(bo);
	return rc;
}
