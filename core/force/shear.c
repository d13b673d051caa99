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

/* the slot of a key in a table of 1 << b slots (Fibonacci hashing) */
static inline size_t slot(uint64_t k, int b)
{
	return (size_t)((k * 0x9E3779B97F4A7C15ull) >> (64 - b));
}

int shear_follow(sb_shear *sh, const sb_nlist *nl, sb_err *e)
{
	if (sh->builds == nl->builds)
		return 0;
	/* the old contacts (nonzero entries) in an open-addressing table at most half
	 * full, keyed by the pair: each pair of the new list finds its history in a probe
	 * or two (a sort and a binary search per pair cost 12 % of a spring run). Key 0,
	 * the padding's, is the empty slot: the padding is never in contact. */
	int nold = 0;
	for (int p = 0; p < sh->n; p++)
		nold += sh->xi[p] != 0;
	int b = 4;
	while ((1 << b) < 2 * nold)
		b++;
	const size_t mask = ((size_t)1 << b) - 1;
	void *ok = sh->okey, *ox = sh->oxi;
	const int rc = grow2(&ok, sizeof *sh->okey, &ox, sizeof *sh->oxi, 1 << b, &sh->ocap, e);
	sh->okey = ok;
	sh->oxi = ox;
	if (rc)
		return rc;
	memset(sh->okey, 0, sizeof *sh->okey * (mask + 1));
	for (int p = 0; p < sh->n; p++)
		if (sh->xi[p] != 0) {
			size_t h = slot(sh->key[p], b);
			while (sh->okey[h]) /* keys are unique: no match to look for */
				h = (h + 1) & mask;
			sh->okey[h] = sh->key[p];
			sh->oxi[h] = sh->xi[p];
		}
	const int n = nl->nflat + nl->nseam;
	if (grow(sh, n, e))
		return e->code;
	for (int p = 0; p < n; p++) {
		const uint64_t kp = key(nl, p);
		sh->key[p] = kp;
		sh->xi[p] = 0;
		if (!nold || (p < nl->nflat && nl->pi[p] == nl->pj[p]))
			continue; /* no history, or the padding */
		for (size_t h = slot(kp, b); sh->okey[h]; h = (h + 1) & mask)
			if (sh->okey[h] == kp) {
				sh->xi[p] = sh->oxi[h];
				break;
			}
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
