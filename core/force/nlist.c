/* nlist.c - cell grid + Verlet list construction. */
#include "nlist.h"

#include "bigmem.h"

#include <assert.h>
#include <limits.h>
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

/* p grown to cap elements of size elem, its first old kept and p freed; NULL (p kept)
 * when out of memory. bigmem: the kernel streams these every step (huge pages at 10^5
 * disks). */
static void *regrow(void *p, int old, int cap, size_t elem)
{
	void *q = bigmem_alloc(elem * (size_t)cap);
	if (q && old)
		memcpy(q, p, elem * (size_t)old);
	if (q)
		free(p);
	return q;
}

/* The flat list's two arrays grow together. */
static int grow_flat(sb_nlist *nl, int need, sb_err *e)
{
	int cap = nl->fcap ? nl->fcap : 4096;
	while (cap < need)
		cap *= 2;
	int ok = 1;
#define GROW(field)                                                                        \
	do {                                                                               \
		void *q_ = regrow(nl->field, nl->fcap, cap, sizeof *nl->field);            \
		if (q_)                                                                    \
			nl->field = q_;                                                    \
		else                                                                       \
			ok = 0;                                                            \
	} while (0)
	GROW(pi);
	GROW(pj);
#undef GROW
	if (!ok)
		return sb_errf(e, SB_ENOMEM, "out of memory in the neighbour list");
	nl->fcap = cap;
	return 0;
}

/* The plain candidate scan (sb_scan_fn): the reference the vector kernels' scans
 * (kvec.c) give to the pair. */
static int scan_plain(sb_nlist *nl, int i, double xi, double yi, double ri, int k0, int k1, int np)
{
	int *restrict pj = nl->pj, *restrict pi = nl->pi;
	const int *restrict idx = nl->cell_idx;
	const double *restrict xs = nl->xs, *restrict ys = nl->ys, *restrict rs = nl->rs;
	for (int k = k0; k < k1; k++) {
		const int j = idx[k];
		const double ddx = xi - xs[k], ddy = yi - ys[k], rc = ri + rs[k];
		pj[np] = j << nl->pshift;
		pi[np] = i << nl->pshift;
		np += (j > i) & (ddx * ddx + ddy * ddy < rc * rc);
	}
	return np;
}

int nlist_init(sb_nlist *nl, const sb_state *st, double skin, int pshift, sb_err *e)
{
	memset(nl, 0, sizeof *nl);
	if (st->n > (INT_MAX - 64) >> pshift) /* the list holds i << pshift in an int */
		return sb_errf(e, SB_EUSAGE, "%d disks: the neighbour list holds at most %d", st->n,
			       (INT_MAX - 64) >> pshift);
	nl->skin = skin;
	nl->pshift = pshift;
	nl->scan = scan_plain;
	nl->cap = st->n;
	nl->large = calloc((size_t)st->n + 1, 1);
	nl->large_list = malloc(sizeof(int) * ((size_t)st->n + 1));
	/* bigmem: the build sweeps these, and the step xref and yref (huge pages at 10^5) */
	nl->cell_of = bigmem_alloc(sizeof(int) * ((size_t)st->n + 1));
	nl->cell_x = bigmem_alloc(sizeof(int) * ((size_t)st->n + 1));
	nl->cell_y = bigmem_alloc(sizeof(int) * ((size_t)st->n + 1));
	nl->cell_idx = bigmem_alloc(sizeof(int) * ((size_t)st->n + 9));
	nl->xs = bigmem_alloc(sizeof(double) * ((size_t)st->n + 9));
	nl->ys = bigmem_alloc(sizeof(double) * ((size_t)st->n + 9));
	nl->rs = bigmem_alloc(sizeof(double) * ((size_t)st->n + 9));
	nl->xref = bigmem_alloc(sizeof(double) * ((size_t)st->n + 1));
	nl->yref = bigmem_alloc(sizeof(double) * ((size_t)st->n + 1));
	if (!nl->large || !nl->large_list || !nl->cell_of || !nl->cell_x || !nl->cell_y ||
	    !nl->cell_idx || !nl->xs || !nl->ys || !nl->rs ||
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

void nlist_set_period(sb_nlist *nl, double W)
{
	nl->period = W > 0 ? W : 0;
}

void nlist_free(sb_nlist *nl)
{
	free(nl->si);
	free(nl->sj);
	free(nl->cell_start);
	free(nl->cell_pos);
	free(nl->cell_idx);
	free(nl->cell_of);
	free(nl->cell_x);
	free(nl->cell_y);
	free(nl->xs);
	free(nl->ys);
	free(nl->rs);
	free(nl->pi);
	free(nl->pj);
	free(nl->large);
	free(nl->large_list);
	free(nl->xref);
	free(nl->yref);
	memset(nl, 0, sizeof *nl);
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

static int seam_push(sb_nlist *nl, int i, int j, sb_err *e)
{
	if (nl->nseam == nl->scap) {
		const int cap = nl->scap ? 2 * nl->scap : 256;
		int *a = realloc(nl->si, sizeof(int) * (size_t)cap);
		if (a)
			nl->si = a;
		int *b = a ? realloc(nl->sj, sizeof(int) * (size_t)cap) : NULL;
		if (!b)
			return sb_errf(e, SB_ENOMEM, "out of memory in the neighbour list");
		nl->sj = b;
		nl->scap = cap;
	}
	nl->si[nl->nseam] = i;
	nl->sj[nl->nseam++] = j;
	return 0;
}

/* The ordinary disks (in the cells) within reach of disk a's image at x_a + shift:
 * as seam pairs (a, b) for shift = +W, (b, a) for shift = -W (b's image at x_b + W
 * meets a). The image may lie beyond the grid: cell_coord clamps, which is safe. */
static int seam_scan(sb_nlist *nl, const sb_state *st, int a, double shift, double reach, sb_err *e)
{
	const double *x = nl->xref, *y = nl->yref, *r = st->r;
	const double px = x[a] + shift, py = y[a], skin = nl->skin;
	/* most disks are far from the seam: their image misses the grid */
	if (px - reach >= nl->x0 + nl->ncx * nl->cell || px + reach < nl->x0)
		return 0;
	const int cx0 = cell_coord(px - reach, nl->x0, nl->inv_cell, nl->ncx),
		  cx1 = cell_coord(px + reach, nl->x0, nl->inv_cell, nl->ncx),
		  cy0 = cell_coord(py - reach, nl->y0, nl->inv_cell, nl->ncy),
		  cy1 = cell_coord(py + reach, nl->y0, nl->inv_cell, nl->ncy);
	const int awall = st->kind[a] == KIND_WALL;
	for (int yy = cy0; yy <= cy1; yy++)
		for (int xx = cx0; xx <= cx1; xx++) {
			const int cc = yy * nl->ncx + xx;
			for (int k = nl->cell_start[cc]; k < nl->cell_start[cc + 1]; k++) {
				const int b = nl->cell_idx[k];
				if (b == a || (awall && st->kind[b] == KIND_WALL))
					continue;
				const double ddx = px - x[b], ddy = py - y[b], rc = r[a] + r[b] + skin;
				if (ddx * ddx + ddy * ddy < rc * rc &&
				    (shift > 0 ? seam_push(nl, a, b, e) : seam_push(nl, b, a, e)))
					return e->code;
			}
		}
	return 0;
}

/* The seam pairs (nlist.h), from the grid of the build: every ordinary disk's image
 * at x + W against the cells; every large disk's images at x + W and x - W against
 * the cells and at x + W against the other large disks. Each ordered pair (i, j) with
 * i's image at x_i + W near j is found once. */
static int seam_build(sb_nlist *nl, const sb_state *st, sb_err *e)
{
	const double W = nl->period, skin = nl->skin, *x = nl->xref, *y = nl->yref, *r = st->r;
	for (int a = 0; a < st->n; a++)
		if (!nl->large[a] && seam_scan(nl, st, a, W, r[a] + nl->r_small + skin, e))
			return e->code;
	for (int k = 0; k < nl->nlarge; k++) {
		const int L = nl->large_list[k];
		const double reach = r[L] + nl->r_small + skin;
		if (seam_scan(nl, st, L, W, reach, e) || seam_scan(nl, st, L, -W, reach, e))
			return e->code;
		for (int m = 0; m < nl->nlarge; m++) {
			const int M = nl->large_list[m];
			if (M == L || (st->kind[L] == KIND_WALL && st->kind[M] == KIND_WALL))
				continue;
			const double ddx = x[L] + W - x[M], ddy = y[L] - y[M], rc = r[L] + r[M] + skin;
			if (ddx * ddx + ddy * ddy < rc * rc && seam_push(nl, L, M, e))
				return e->code;
		}
	}
	return 0;
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
	/* comparisons, not fmin/fmax (library calls here); a NaN never wins either way */
	const unsigned char *restrict large = nl->large;
	for (int i = 0; i < n; i++) {
		const double xi = large[i] ? xmin : x[i], yi = large[i] ? ymin : y[i];
		xmin = xi < xmin ? xi : xmin;
		ymin = yi < ymin ? yi : ymin;
		const double xa = large[i] ? xmax : x[i], ya = large[i] ? ymax : y[i];
		xmax = xa > xmax ? xa : xmax;
		ymax = ya > ymax ? ya : ymax;
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
		const int cx = cell_coord(x[i], nl->x0, nl->inv_cell, nl->ncx),
			  cy = cell_coord(y[i], nl->y0, nl->inv_cell, nl->ncy);
		const int c = cy * nl->ncx + cx;
		nl->cell_of[i] = c;
		nl->cell_x[i] = cx; /* spares the candidate loop two divisions */
		nl->cell_y[i] = cy;
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
	 * in the counting sort, so each row is one contiguous run of candidates, whose
	 * coordinates are copied in that order (xs, ys, rs) so that a run is read
	 * contiguously. A candidate is appended branch-free (written, then kept or not):
	 * whether a near disk is within reach is a coin toss that a branch would
	 * mispredict. j > i keeps each pair once; walls sit above nm, so they always pass.
	 * The pairs go straight into the flat list the force kernel walks: rows of
	 * ascending i, each in cell order, then the pairs of the large disks. */
	const int nsorted = nl->cell_start[nc];
	for (int k = 0; k < nsorted; k++) {
		const int j = nl->cell_idx[k];
		nl->xs[k] = x[j];
		nl->ys[k] = y[j];
		nl->rs[k] = r[j];
	}
	int np = 0;
	const int ncx = nl->ncx, ncy = nl->ncy;
	for (int i = 0; i < nm; i++) {
		if (nl->large[i])
			continue;
		const double xi = x[i], yi = y[i], ri = r[i] + skin;
		const int cx = nl->cell_x[i], cy = nl->cell_y[i];
		const int xa = cx > 0 ? cx - 1 : 0, xb = cx < ncx - 1 ? cx + 1 : ncx - 1;
		const int ya = cy > 0 ? cy - 1 : 0, yb = cy < ncy - 1 ? cy + 1 : ncy - 1;
		for (int yy = ya; yy <= yb; yy++) {
			const int k0 = nl->cell_start[yy * ncx + xa], k1 = nl->cell_start[yy * ncx + xb + 1];
			if (np + (k1 - k0) + 16 > nl->fcap && grow_flat(nl, np + (k1 - k0) + 16, e))
				return e->code;
			np = nl->scan(nl, i, xi, yi, ri, k0, k1, np);
		}
	}
	nl->npairs = np;

	/* large disks: scan the cells within their reach, then each other */
	int nb = np;
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
						if (nb + 16 > nl->fcap && grow_flat(nl, nb + 16, e))
							return e->code;
						nl->pi[nb] = L << nl->pshift;
						nl->pj[nb++] = j << nl->pshift;
					}
				}
			}
		for (int b = a + 1; b < nl->nlarge; b++) {
			int M = nl->large_list[b];
			if (Lwall && st->kind[M] == KIND_WALL)
				continue;
			double ddx = x[L] - x[M], ddy = y[L] - y[M], rc = r[L] + r[M] + skin;
			if (ddx * ddx + ddy * ddy < rc * rc) {
				if (nb + 16 > nl->fcap && grow_flat(nl, nb + 16, e))
					return e->code;
				nl->pi[nb] = L << nl->pshift;
				nl->pj[nb++] = M << nl->pshift;
			}
		}
	}
	nl->nbig = nb - np;
	const int nf = nb;
	if (nf + 8 > nl->fcap && grow_flat(nl, nf + 8, e))
		return e->code;
	/* pad to whole vectors of 8 (the SIMD kernel masks these lanes out) */
	for (int p = nf; p < ((nf + 7) & ~7); p++)
		nl->pi[p] = nl->pj[p] = 0;
	nl->nflat = nf;
	nl->nseam = 0;
	assert(!nlist_check(nl, n, nm));
	return nl->period > 0 ? seam_build(nl, st, e) : 0;
}

const char *nlist_check(const sb_nlist *nl, int n, int nm)
{
	const int sh = nl->pshift, m = (1 << sh) - 1;
	for (int p = 0; p < nl->nflat; p++) {
		const int a = nl->pi[p], b = nl->pj[p];
		if ((a & m) || (b & m))
			return "an index is not a multiple of 1 << pshift (the kernel reads records at pi, pj)";
		if (a < 0 || b < 0 || a >> sh >= n || b >> sh >= n)
			return "an index outside the state's disks";
		if (p < nl->npairs && (a >= b || a >> sh >= nm || (p > 0 && nl->pi[p - 1] > a)))
			return "an ordinary pair out of order (i < j, i mobile, rows of ascending i)";
	}
	for (int p = nl->nflat; p < ((nl->nflat + 7) & ~7); p++)
		if (nl->pi[p] || nl->pj[p])
			return "the padding to a whole vector of 8 pairs is not (0, 0)";
	return NULL;
}

/* The pairs within reach by the brute force of all pairs: i's position shifted by
 * `shift` in x (0: the box; W: i's image across the seam, then i and j in either order). */
static long brute(const sb_state *st, double skin, double shift, int *pi, int *pj, long cap)
{
	long np = 0;
	const double *x = st->q[C_X][0], *y = st->q[C_Y][0];
	for (int i = 0; i < st->n; i++)
		for (int j = shift != 0 ? 0 : i + 1; j < st->n; j++) {
			if (i == j || (st->kind[i] == KIND_WALL && st->kind[j] == KIND_WALL))
				continue;
			double dx = x[i] + shift - x[j], dy = y[i] - y[j], rc = st->r[i] + st->r[j] + skin;
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

long nlist_brute(const sb_state *st, double skin, int *pi, int *pj, long cap)
{
	return brute(st, skin, 0, pi, pj, cap);
}

long nlist_brute_seam(const sb_state *st, double skin, double W, int *pi, int *pj, long cap)
{
	return brute(st, skin, W, pi, pj, cap);
}
