/* shear.c - the contacts' shear displacements and their carry-over at list builds
 * (shear.h). */
#include "shear.h"

#include <stdlib.h>
#include <string.h>

void shear_init(sb_shear *sh)
{
	memset(sh, 0, sizeof *sh);
	sh->builds = -1;
}

void shear_free(sb_shear *sh)
{
	free(sh->key);
	free(sh->xi);
	free(sh->okey);
	free(sh->oxi);
	shear_init(sh);
}

void shear_clear(sb_shear *sh)
{
	if (sh->n)
		memset(sh->xi, 0, sizeof(double) * (size_t)sh->n);
}

/* A pair's identity: its disks (i, j) and whether it meets across the seam, where the
 * pair (i, j) is i's image at x + period against j (nlist.h); the list's padding
 * (0, 0) gets a key no pair has, and is never in contact. */
static uint64_t key(const sb_nlist *nl, int p)
{
	if (p < nl->nflat) {
		const uint64_t i = (uint64_t)(nl->pi[p] >> nl->pshift), j = (uint64_t)(nl->pj[p] >> nl->pshift);
		return i << 32 | j;
	}
	const uint64_t i = (uint64_t)nl->si[p - nl->nflat], j = (uint64_t)nl->sj[p - nl->nflat];
	return (uint64_t)1 << 63 | i << 32 | j;
}

/* Room for n entries in two arrays of sa and sb bytes an entry (*cap of them so far). */
static int grow2(void **a, size_t sa, void **b, size_t sb, int n, int *cap, sb_err *e)
{
	if (n <= *cap)
		return 0;
	const int c = n + n / 2 + 64;
	void *x = realloc(*a, sa * (size_t)c);
	if (x)
		*a = x;
	void *y = realloc(*b, sb * (size_t)c);
	if (y)
		*b = y;
	if (!x || !y)
		return sb_errf(e, SB_ENOMEM, "out of memory for the contacts' shear displacements");
	*cap = c;
	return 0;
}

static int grow(sb_shear *sh, int n, sb_err *e)
{
	void *k = sh->key, *x = sh->xi;
	const int rc = grow2(&k, sizeof *sh->key, &x, sizeof *sh->xi, n, &sh->cap, e);
	sh->key = k;
	sh->xi = x;
	return rc;
}

static int cmp_key(const void *a, const void *b)
{
	const uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
	return (x > y) - (x < y);
}

int shear_follow(sb_shear *sh, const sb_nlist *nl, sb_err *e)
{
	if (sh->builds == nl->builds)
		return 0;
	/* the old contacts (nonzero entries), sorted by key; their values ride along in
	 * the key's slot order through an index sort of (key, slot) */
	int nold = 0;
	for (int p = 0; p < sh->n; p++)
		nold += sh->xi[p] != 0;
	void *ok = sh->okey, *ox = sh->oxi;
	const int rc = grow2(&ok, 2 * sizeof *sh->okey, &ox, sizeof *sh->oxi, nold, &sh->ocap, e);
	sh->okey = ok;
	sh->oxi = ox;
	if (rc)
		return rc;
	/* okey holds pairs (key, slot): sorted by key (keys are unique) */
	int c = 0;
	for (int p = 0; p < sh->n; p++)
		if (sh->xi[p] != 0) {
			sh->okey[2 * c] = sh->key[p];
			sh->okey[2 * c + 1] = (uint64_t)p;
			c++;
		}
	if (nold)
		qsort(sh->okey, (size_t)nold, 2 * sizeof(uint64_t), cmp_key);
	for (int k = 0; k < nold; k++)
		sh->oxi[k] = sh->xi[sh->okey[2 * k + 1]];
	const int n = nl->nflat + nl->nseam;
	if (grow(sh, n, e))
		return e->code;
	for (int p = 0; p < n; p++) {
		const uint64_t kp = key(nl, p);
		sh->key[p] = kp;
		sh->xi[p] = 0;
		if (p < nl->nflat && nl->pi[p] == nl->pj[p])
			continue; /* padding */
		int lo = 0, hi = nold; /* the first old key >= kp */
		while (lo < hi) {
			const int mid = lo + (hi - lo) / 2;
			if (sh->okey[2 * mid] < kp)
				lo = mid + 1;
			else
				hi = mid;
		}
		if (lo < nold && sh->okey[2 * lo] == kp)
			sh->xi[p] = sh->oxi[lo];
	}
	sh->n = n;
	sh->builds = nl->builds;
	return 0;
}

int shear_restore(sb_shear *sh, const sb_nlist *nl, const double *xi, long n, sb_err *e)
{
	const int np = nl->nflat + nl->nseam;
	if (n != np)
		return sb_errf(e, SB_EIO, "%ld shear displacements for a neighbour list of %d pairs", n, np);
	if (grow(sh, np, e))
		return e->code;
	for (int p = 0; p < np; p++)
		sh->key[p] = key(nl, p);
	if (np)
		memcpy(sh->xi, xi, sizeof(double) * (size_t)np);
	sh->n = np;
	sh->builds = nl->builds;
	return 0;
}

int shear_current(const sb_shear *sh, const sb_nlist *nl)
{
	return sh->builds == nl->builds && sh->n == nl->nflat + nl->nseam;
}
