/* shear.h - the shear displacements of the contacts under tangential = spring
 * (docs/model.md, "Tangential law"): one number per pair of the neighbour list, in
 * the list's order (the flat list, then the seam pairs), zero for a pair not in
 * contact. A list build reorders the pairs; shear_follow carries every nonzero
 * displacement over to its pair's new place by the pair's identity, so a contact keeps
 * its history across builds. */
#ifndef SB_SHEAR_H
#define SB_SHEAR_H

#include <stdint.h>

#include "err.h"
#include "nlist.h"

typedef struct sb_shear {
	long builds;     /* the list build the entries are in the order of (-1: none yet) */
	int n, cap;      /* n = nflat + nseam of that build */
	uint64_t *key;   /* each entry's pair (shear.c, key) */
	double *xi;      /* its shear displacement, cm */
	uint64_t *okey;  /* scratch of the carry-over: the old nonzero entries, a hash table */
	double *oxi;
	int ocap;
} sb_shear;

void shear_init(sb_shear *sh);
void shear_free(sb_shear *sh);
/* All displacements to zero (every contact starts afresh). */
void shear_clear(sb_shear *sh);
/* Into the order of nl's current build, when it is not already: each pair gets the
 * displacement it had in the last build's order, or zero. */
int shear_follow(sb_shear *sh, const sb_nlist *nl, sb_err *e);
/* A checkpoint's entries (n of them, in the order of nl's current build, which was
 * rebuilt exactly as it was when they were written): n must be nl's pair count. */
int shear_restore(sb_shear *sh, const sb_nlist *nl, const double *xi, long n, sb_err *e);
/* Is entry p of sh the pair p of nl's current build? (The scans read sh by index.) */
int shear_current(const sb_shear *sh, const sb_nlist *nl);

#endif
