/* nlist.c - cell grid + Verlet list construction. */
#include "nlist.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int grow_int(int **p, int *cap, int need, sb_err *e)
{
	if (need <= *cap)
		return 0;
	int nc = *cap ? *cap : 1024;
	while (nc < need)
		nc *= 2;
	int *q = realloc(*p, sizeof(int) * (size_t)nc);
	if (!q)
		return sb_errf(e, SB_ENOMEM, "out of memory in the neighbour list");
	*p = q;
	*cap = nc;
	return 0;
}

static int grow_pairs(int **pj, double **pm, int **pi, int *cap, int need, sb_err *e)
{
	if (need <= *cap)
		return 0;
	int nc = *cap ? *cap : 4096;
	while (nc < need)
		nc *= 2;
	int *a = realloc(*pj, sizeof(int) * (size_t)nc);
	if (a)
		*pj = a;
	double *b = realloc(*pm, sizeof(double) * (size_t)nc);
	if (b)
		*pm = b;
	int ok = a && b;
	if (pi) {
		int *c = realloc(*pi, sizeof(int) * (size_t)nc);
		if (c)
			*pi = c;
		ok = ok && c;
	}
	if (!ok)
		return sb_errf(e, SB_ENOMEM, "out of memory in the neighbour list");
	*cap = nc;
	return 0;
}

int nlist_init(sb_nlist *nl, const sb_state *st, double skin, sb_err *e)
{
	memset(nl, 0, sizeof *nl);
	nl->skin = skin;
	nl->cap = st->n;
	nl->large = calloc((size_t)st->n + 1, 1);
	nl->large_list = malloc(sizeof(int) * ((size_t)st->n + 1));
	nl->cell_of = malloc(sizeof(int) * ((size_t)st->n + 1));
	nl->cell_idx = malloc(sizeof(int) * ((size_t)st->n + 1));
	nl->start = malloc(sizeof(int) * ((size_t)st->nm + 1));
	nl->xref = malloc(sizeof(double) * ((size_t)st->n + 1));
	nl->yref = malloc(sizeof(double) * ((size_t)st->n + 1));
	if (!nl->large || !nl->large_list || !nl->cell_of || !nl->cell_idx || !nl->start ||
	    !nl->xref || !nl->yref)
		return sb_errf(e, SB_ENOMEM, "out of memory in the neighbour list");
	double mean = 0;
	for (int i = 0; i < st->n; i++)
		mean += st->r[i];
	mean = st->n ? mean / st->n : 1;
	nl->r_small = 0;
	for (int i = 0; i < st->n; i++) {
		nl->large[i] = st->r[i] > 1.5 * mean;
		if (nl->large[i])
			nl->large_list[nl->nlarge++] = i;
		else if (st->r[i] > nl->r_small)
			nl->r_small = st->r[i];
	}
	if (nl->r_small == 0)
		nl->r_small = mean;
	return 0;
}

void nlist_free(sb_nlist *nl)
{
	free(nl->cell_start);
	free(nl->cell_pos);
	free(nl->cell_idx);
	free(nl->cell_of);
	free(nl->start);
	free(nl->j);
	free(nl->meff);
	free(nl->bi);
	free(nl->bj);
	free(nl->bmeff);
	free(nl->pi);
	free(nl->pj);
	free(nl->pmeff);
	free(nl->contact);
	free(nl->cd);
	free(nl->cinv);
	free(nl->large);
	free(nl->large_list);
	free(nl->xref);
	free(nl->yref);
	memset(nl, 0, sizeof *nl);
}

static inline double pair_meff(const sb_state *st, int i, int j)
{
	/* A wall of infinite mass has inv_m = 0, so m_eff becomes the grain's mass. */
	return 1.0 / (st->inv_m[i] + st->inv_m[j]);
}

static inline int cell_coord(double v, double v0, double inv, int n)
{
	/* Clamping is safe: it is monotone and only shrinks distances, so disks within
	 * reach still land in the same or adjacent cells. */
	double c = floor((v - v0) * inv);
	if (!(c >= 0))
		return 0;
	if (c > n - 1)
		return n - 1;
	return (int)c;
}

int nlist_build(sb_nlist *nl, const sb_state *st, sb_err *e)
{
	memcpy(nl->xref, st->q[C_X][0], sizeof(double) * (size_t)st->n);
	memcpy(nl->yref, st->q[C_Y][0], sizeof(double) * (size_t)st->n);
	return nlist_build_from_ref(nl, st, e);
}

int nlist_build_from_ref(sb_nlist *nl, const sb_state *st, sb_err *e)
{
	const double *x = nl->xref, *y = nl->yref, *r = st->r;
	const int n = st->n, nm = st->nm;
	const double skin = nl->skin;
	nl->builds++;

	/* grid over the bounding box of the ordinary disks */
	double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
	for (int i = 0; i < n; i++) {
		if (nl->large[i])
			continue;
		xmin = fmin(xmin, x[i]);
		xmax = fmax(xmax, x[i]);
		ymin = fmin(ymin, y[i]);
		ymax = fmax(ymax, y[i]);
	}
	if (!(xmin <= xmax)) { /* no ordinary disks (or NaN): one cell */
		xmin = ymin = 0;
		xmax = ymax = 1;
	}
	double cell = 2 * nl->r_small + skin;
	/* A flying grain must not blow up the grid: cap the cell count near 4 n and let
	 * the cells grow instead. */
	double lim = 4.0 * n + 64;
	for (;;) {
		double cx = floor((xmax - xmin) / cell) + 1, cy = floor((ymax - ymin) / cell) + 1;
		if (cx * cy <= lim)
			break;
		cell *= 1.5;
	}
	nl->cell = cell;
	nl->inv_cell = 1.0 / cell;
	nl->x0 = xmin;
	nl->y0 = ymin;
	nl->ncx = (int)floor((xmax - xmin) / cell) + 1;
	nl->ncy = (int)floor((ymax - ymin) / cell) + 1;
	int nc = nl->ncx * nl->ncy;
	if (nc + 1 > nl->ccap) {
		int cap2 = nl->ccap;
		if (grow_int(&nl->cell_start, &nl->ccap, nc + 1, e) ||
		    grow_int(&nl->cell_pos, &cap2, nc + 1, e))
			return e->code;
	}
	memset(nl->cell_start, 0, sizeof(int) * (size_t)(nc + 1));
	for (int i = 0; i < n; i++) {
		if (nl->large[i]) {
			nl->cell_of[i] = -1;
			continue;
		}
		int c = cell_coord(y[i], nl->y0, nl->inv_cell, nl->ncy) * nl->ncx +
			cell_coord(x[i], nl->x0, nl->inv_cell, nl->ncx);
		nl->cell_of[i] = c;
		nl->cell_start[c + 1]++;
	}
	for (int c = 0; c < nc; c++)
		nl->cell_start[c + 1] += nl->cell_start[c];
	/* fill in index order so that each cell lists its disks ascending */
	int *pos = nl->cell_pos;
	memcpy(pos, nl->cell_start, sizeof(int) * (size_t)(nc + 1));
	for (int i = 0; i < n; i++)
		if (nl->cell_of[i] >= 0)
			nl->cell_idx[pos[nl->cell_of[i]]++] = i;

	/* Ordinary mobile disks: the three cells of a row of the 3x3 stencil are adjacent
	 * in the counting sort, so each row is one contiguous run of candidates. A
	 * candidate is appended branch-free (written, then kept or not): whether a near
	 * disk is within reach is a coin toss that a branch would mispredict. j > i
	 * keeps each pair once; walls sit above nm, so they always pass. */
	int np = 0;
	const int ncx = nl->ncx, ncy = nl->ncy;
	for (int i = 0; i < nm; i++) {
		nl->start[i] = np;
		if (nl->large[i])
			continue;
		const double xi = x[i], yi = y[i], ri = r[i] + skin;
		const int c = nl->cell_of[i], cx = c % ncx, cy = c / ncx;
		const int xa = cx > 0 ? cx - 1 : 0, xb = cx < ncx - 1 ? cx + 1 : ncx - 1;
		const int ya = cy > 0 ? cy - 1 : 0, yb = cy < ncy - 1 ? cy + 1 : ncy - 1;
		for (int yy = ya; yy <= yb; yy++) {
			const int k0 = nl->cell_start[yy * ncx + xa], k1 = nl->cell_start[yy * ncx + xb + 1];
			if (np + (k1 - k0) > nl->pcap &&
			    grow_pairs(&nl->j, &nl->meff, NULL, &nl->pcap, np + (k1 - k0), e))
				return e->code;
			int *restrict out = nl->j;
			for (int k = k0; k < k1; k++) {
				const int j = nl->cell_idx[k];
				const double ddx = xi - x[j], ddy = yi - y[j], rc = ri + r[j];
				out[np] = j;
				np += (j > i) & (ddx * ddx + ddy * ddy < rc * rc);
			}
		}
	}
	nl->start[nm] = np;
	nl->npairs = np;
	for (int i = 0; i < nm; i++)
		for (int p = nl->start[i]; p < nl->start[i + 1]; p++)
			nl->meff[p] = pair_meff(st, i, nl->j[p]);

	/* large disks: scan the cells within their reach, then each other */
	int nb = 0;
	for (int a = 0; a < nl->nlarge; a++) {
		int L = nl->large_list[a];
		const double reach = r[L] + nl->r_small + skin;
		int cx0 = cell_coord(x[L] - reach, nl->x0, nl->inv_cell, ncx);
		int cx1 = cell_coord(x[L] + reach, nl->x0, nl->inv_cell, ncx);
		int cy0 = cell_coord(y[L] - reach, nl->y0, nl->inv_cell, ncy);
		int cy1 = cell_coord(y[L] + reach, nl->y0, nl->inv_cell, ncy);
		int Lwall = st->kind[L] == KIND_WALL;
		for (int yy = cy0; yy <= cy1; yy++)
			for (int xx = cx0; xx <= cx1; xx++) {
				int cc = yy * ncx + xx;
				for (int k = nl->cell_start[cc]; k < nl->cell_start[cc + 1]; k++) {
					int j = nl->cell_idx[k];
					if (Lwall && st->kind[j] == KIND_WALL)
						continue;
					double ddx = x[L] - x[j], ddy = y[L] - y[j], rc = r[L] + r[j] + skin;
					if (ddx * ddx + ddy * ddy < rc * rc) {
						if (nb == nl->bcap &&
						    grow_pairs(&nl->bj, &nl->bmeff, &nl->bi, &nl->bcap, nb + 1, e))
							return e->code;
						nl->bi[nb] = L;
						nl->bj[nb] = j;
						nl->bmeff[nb] = pair_meff(st, L, j);
						nb++;
					}
				}
			}
		for (int b = a + 1; b < nl->nlarge; b++) {
			int M = nl->large_list[b];
			if (Lwall && st->kind[M] == KIND_WALL)
				continue;
			double ddx = x[L] - x[M], ddy = y[L] - y[M], rc = r[L] + r[M] + skin;
			if (ddx * ddx + ddy * ddy < rc * rc) {
				if (nb == nl->bcap && grow_pairs(&nl->bj, &nl->bmeff, &nl->bi, &nl->bcap, nb + 1, e))
					return e->code;
				nl->bi[nb] = L;
				nl->bj[nb] = M;
				nl->bmeff[nb] = pair_meff(st, L, M);
				nb++;
			}
		}
	}
	nl->nbig = nb;

	/* Flatten: one loop over pairs without an inner loop per disk, whose varying
	 * trip count costs a mispredicted branch per disk. */
	const int nf = np + nb;
	if (nf > nl->fcap) {
		int cap = nl->fcap ? nl->fcap : 4096;
		while (cap < nf)
			cap *= 2;
		int *a = realloc(nl->pi, sizeof(int) * (size_t)cap);
		if (a)
			nl->pi = a;
		int *b = realloc(nl->pj, sizeof(int) * (size_t)cap);
		if (b)
			nl->pj = b;
		double *c = realloc(nl->pmeff, sizeof(double) * (size_t)cap);
		if (c)
			nl->pmeff = c;
		int *d = realloc(nl->contact, sizeof(int) * (size_t)cap);
		if (d)
			nl->contact = d;
		double *f = realloc(nl->cd, sizeof(double) * (size_t)cap);
		if (f)
			nl->cd = f;
		double *g = realloc(nl->cinv, sizeof(double) * (size_t)cap);
		if (g)
			nl->cinv = g;
		if (!a || !b || !c || !d || !f || !g)
			return sb_errf(e, SB_ENOMEM, "out of memory in the neighbour list");
		nl->fcap = cap;
	}
	for (int i = 0; i < nm; i++)
		for (int p = nl->start[i]; p < nl->start[i + 1]; p++)
			nl->pi[p] = i;
	if (np) {
		memcpy(nl->pj, nl->j, sizeof(int) * (size_t)np);
		memcpy(nl->pmeff, nl->meff, sizeof(double) * (size_t)np);
	}
	if (nb) {
		memcpy(nl->pi + np, nl->bi, sizeof(int) * (size_t)nb);
		memcpy(nl->pj + np, nl->bj, sizeof(int) * (size_t)nb);
		memcpy(nl->pmeff + np, nl->bmeff, sizeof(double) * (size_t)nb);
	}
	nl->nflat = nf;
	return 0;
}

long nlist_brute(const sb_state *st, double skin, int *pi, int *pj, long cap)
{
	long np = 0;
	const double *x = st->q[C_X][0], *y = st->q[C_Y][0];
	for (int i = 0; i < st->n; i++)
		for (int j = i + 1; j < st->n; j++) {
			if (st->kind[i] == KIND_WALL && st->kind[j] == KIND_WALL)
				continue;
			double dx = x[i] - x[j], dy = y[i] - y[j], rc = st->r[i] + st->r[j] + skin;
			if (dx * dx + dy * dy < rc * rc) {
				if (pi && np < cap) {
					pi[np] = i;
					pj[np] = j;
				}
				np++;
			}
		}
	return np;
}
