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
	int per_unit;  /* the units share no frequency grid: the threshold onset is the
			* median of their own crossings (onsetfit.h) */
	const double *uthr; /* [nu] each unit's own crossing */
	double thr;
	double *xs, *ys;
} gdata;

static int cmp_d(const void *a, const void *b)
{
	const double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* The median of the finite v[idx[i]] (idx NULL: v[0..n)), NaN when none; tmp holds n. */
static double median_of(const double *v, const size_t *idx, size_t n, double *tmp)
{
	size_t m = 0;
	for (size_t i = 0; i < n; i++) {
		const double x = v[idx ? idx[i] : i];
		if (isfinite(x))
			tmp[m++] = x;
	}
	if (!m)
		return NAN;
	qsort(tmp, m, sizeof *tmp, cmp_d);
	return m % 2 ? tmp[m / 2] : 0.5 * (tmp[m / 2 - 1] + tmp[m / 2]);
}

/* Do the units sample the same frequencies (each the same set, as a grid does)? A
 * bisection gives each replicate its own. */
static int common_grid(const double *x, const long *unit, size_t n, const long *units, size_t nu)
{
	for (size_t u = 1; u < nu; u++) {
		/* every x of unit u is an x of unit 0 and the other way round */
		for (int dir = 0; dir < 2; dir++) {
			const long a = dir ? units[0] : units[u], b = dir ? units[u] : units[0];
			for (size_t i = 0; i < n; i++) {
				if (unit[i] != a)
					continue;
				int seen = 0;
				for (size_t j = 0; j < n && !seen; j++)
					seen = unit[j] == b && x[j] == x[i];
				if (!seen)
					return 0;
			}
		}
	}
	return 1;
}

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
	/* per unit: the median of the drawn units' own crossings (xs holds n doubles at least) */
	out[1] = g->per_unit ? median_of(g->uthr, idx, n, g->xs) : sig_threshold(g->xs, g->ys, k, g->thr);
}

int onset_estimate(const double *x, const double *y, const long *unit, size_t n, double threshold, size_t B,
		   unsigned long seed, double level, onset_res *r)
{
	memset(r, 0, sizeof *r);
	r->thr = r->fit_lo = r->fit_hi = r->thr_lo = r->thr_hi = r->seed_sd = NAN;
	size_t cap = n ? n : 1;
	gdata g = {x, y, unit, n, malloc(sizeof(long) * cap), 0, 0, 0, NULL, threshold, NULL, NULL};
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
	/* units without a common grid (a search's replicates): the pooled means' first
	 * crossing would be the lowest frequency any one run reached the threshold at; the
	 * median of each unit's own crossing is set by no lone run */
	if (g.nu >= 2 && !common_grid(x, unit, n, g.units, g.nu)) {
		r->per_unit = 1;
		g.per_unit = 1;
		g.uthr = r->seed_thr;
		r->thr = median_of(r->seed_thr, NULL, g.nu, g.xs);
	}
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
