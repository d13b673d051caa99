/* onsetfit.c - transition frequency with a bootstrap over seeds. */
#include "onsetfit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "boot.h"

typedef struct gdata {
	const double *x, *y;
	const long *unit;
	size_t n;
	long *units;
	size_t nu;
	int by_point;  /* one seed: units are the points themselves */
	double thr;
	double *xs, *ys;
} gdata;

static size_t gather(gdata *g, const size_t *idx, size_t n)
{
	size_t k = 0;
	for (size_t i = 0; i < n; i++) {
		if (g->by_point) {
			g->xs[k] = g->x[idx[i]];
			g->ys[k++] = g->y[idx[i]];
			continue;
		}
		for (size_t j = 0; j < g->n; j++)
			if (g->unit[j] == g->units[idx[i]]) {
				g->xs[k] = g->x[j];
				g->ys[k++] = g->y[j];
			}
	}
	return k;
}

static void stat2(void *ctx, const size_t *idx, size_t n, double *out)
{
	gdata *g = ctx;
	size_t k = gather(g, idx, n);
	sig_fit s;
	out[0] = sig_fit_data(g->xs, g->ys, k, &s) ? s.x0 : NAN;
	out[1] = sig_threshold(g->xs, g->ys, k, g->thr);
}

int onset_estimate(const double *x, const double *y, const long *unit, size_t n, double threshold, size_t B,
		   unsigned long seed, double level, onset_res *r)
{
	memset(r, 0, sizeof *r);
	r->thr = r->fit_lo = r->fit_hi = r->thr_lo = r->thr_hi = r->seed_sd = NAN;
	size_t cap = n ? n : 1;
	gdata g = {x, y, unit, n, malloc(sizeof(long) * cap), 0, 0, threshold, NULL, NULL};
	size_t *idx = malloc(sizeof *idx * cap);
	double *bo = malloc(sizeof *bo * 2 * (B ? B : 1));
	r->seed_fit = malloc(sizeof(double) * cap);
	r->seed_thr = malloc(sizeof(double) * cap);
	r->unit_id = malloc(sizeof(long) * cap);
	int rc = -1;
	if (!g.units || !idx || !bo || !r->seed_fit || !r->seed_thr || !r->unit_id)
		goto out;
	for (size_t i = 0; i < n; i++) {
		size_t u = 0;
		while (u < g.nu && g.units[u] != unit[i])
			u++;
		if (u == g.nu)
			g.units[g.nu++] = unit[i];
	}
	/* a resample holds at most (units) x (points of the largest unit) points */
	size_t most = 1;
	for (size_t u = 0; u < g.nu; u++) {
		size_t c = 0;
		for (size_t i = 0; i < n; i++)
			c += unit[i] == g.units[u];
		most = c > most ? c : most;
	}
	g.xs = malloc(sizeof(double) * (g.nu * most > cap ? g.nu * most : cap));
	g.ys = malloc(sizeof(double) * (g.nu * most > cap ? g.nu * most : cap));
	if (!g.xs || !g.ys)
		goto out;
	for (size_t u = 0; u < g.nu; u++)
		idx[u] = u;
	size_t m = gather(&g, idx, g.nu);
	sig_fit_data(g.xs, g.ys, m, &r->fit);
	r->thr = sig_threshold(g.xs, g.ys, m, threshold);
	double sum = 0, sum2 = 0;
	long ns = 0;
	for (size_t u = 0; u < g.nu; u++) {
		size_t one = u, k = gather(&g, &one, 1);
		sig_fit sf;
		r->unit_id[u] = g.units[u];
		r->seed_fit[u] = sig_fit_data(g.xs, g.ys, k, &sf) ? sf.x0 : NAN;
		r->seed_thr[u] = sig_threshold(g.xs, g.ys, k, threshold);
		if (isfinite(r->seed_thr[u])) {
			sum += r->seed_thr[u];
			sum2 += r->seed_thr[u] * r->seed_thr[u];
			ns++;
		}
	}
	r->units = g.nu;
	if (ns > 1)
		r->seed_sd = sqrt(fmax(0, (sum2 - sum * sum / (double)ns) / (double)(ns - 1)));
	size_t nunits = g.nu;
	if (g.nu < 2) {
		g.by_point = 1;
		nunits = n;
	}
	if (B > 1 && nunits > 1) {
		if (boot_run(seed, nunits, B, 2, stat2, &g, bo) || !(r->boot = malloc(sizeof *bo * 2 * B)))
			goto out;
		memcpy(r->boot, bo, sizeof *bo * 2 * B); /* boot_percentile sorts bo */
		r->B = B;
		r->boot_ok = boot_percentile(bo, B, level, &r->fit_lo, &r->fit_hi);
		boot_percentile(bo + B, B, level, &r->thr_lo, &r->thr_hi);
	}
	rc = 0;
out:
	free(g.units);
	free(g.xs);
	free(g.ys);
	free(idx);
	free(bo);
	if (rc)
		onset_res_free(r);
	return rc;
}

void onset_res_free(onset_res *r)
{
	free(r->seed_fit);
	free(r->seed_thr);
	free(r->unit_id);
	free(r->boot);
	r->boot = NULL;
	r->B = 0;
	r->seed_fit = r->seed_thr = NULL;
	r->unit_id = NULL;
}
