/* shear.c - the carry-over of the contacts' shear displacements at a list build
 * (core/force/shear.h): every pair of the new list gets the displacement its pair had in
 * the old list, found by the pair's identity (its disks, and whether it meets across the
 * seam), or zero; the padding and a pair without history get zero. Lists are made up
 * here (thousands of pairs, so that the carry-over's table sees collisions), reordered
 * and thinned as a rebuild does, and checked entry by entry against a brute-force search. */
#include <gsl/gsl_rng.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "nlist.h"
#include "shear.h"
#include "testlib.h"

enum { SHIFT = 3, NDISK = 4000 };

/* a list of nf flat pairs (padded with (0, 0) to whole vectors of 8) and ns seam pairs */
static void make_list(sb_nlist *nl, const int *fi, const int *fj, int nf, const int *si, const int *sj, int ns,
		      long builds)
{
	memset(nl, 0, sizeof *nl);
	nl->pshift = SHIFT;
	nl->pi = calloc((size_t)nf + 8, sizeof(int));
	nl->pj = calloc((size_t)nf + 8, sizeof(int));
	for (int p = 0; p < nf; p++) {
		nl->pi[p] = fi[p] << SHIFT;
		nl->pj[p] = fj[p] << SHIFT;
	}
	nl->nflat = nf;
	nl->si = malloc(sizeof(int) * (size_t)(ns + 1));
	nl->sj = malloc(sizeof(int) * (size_t)(ns + 1));
	memcpy(nl->si, si, sizeof(int) * (size_t)ns);
	memcpy(nl->sj, sj, sizeof(int) * (size_t)ns);
	nl->nseam = ns;
	nl->period = ns ? 10 : 0;
	nl->builds = builds;
}

static void free_list(sb_nlist *nl)
{
	free(nl->pi);
	free(nl->pj);
	free(nl->si);
	free(nl->sj);
}

/* the old entry of pair (i, j, seam) by a linear search, 0 if none */
static double old_of(const int *i, const int *j, const int *seam, const double *xi, int n, int a, int b, int s)
{
	for (int p = 0; p < n; p++)
		if (i[p] == a && j[p] == b && seam[p] == s)
			return xi[p];
	return 0;
}

int main(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	for (int trial = 0; trial < 4; trial++) {
		gsl_rng_set(rng, 11 + (unsigned long)trial);
		/* the old list: distinct pairs, flat (i < j) then seam; the seam pairs repeat
		 * some flat pairs' disks, whose history must not be confused with theirs */
		const int nf = trial == 3 ? 0 : 3000 + trial, ns = trial == 3 ? 5 : 300;
		int *oi = malloc(sizeof(int) * (size_t)(nf + ns)), *oj = malloc(sizeof(int) * (size_t)(nf + ns)),
		    *os = calloc((size_t)(nf + ns), sizeof(int));
		for (int p = 0; p < nf + ns; p++) {
			int a, b, dup;
			do {
				a = 1 + (int)gsl_rng_uniform_int(rng, NDISK - 1);
				b = p >= nf && p < nf + 40 && nf ? -1 : (int)gsl_rng_uniform_int(rng, NDISK);
				if (b < 0) { /* a flat pair's disks, across the seam */
					const int q = (int)gsl_rng_uniform_int(rng, (unsigned long)nf);
					a = oi[q];
					b = oj[q];
				}
				dup = a == b;
				for (int q = nf; q < p && !dup; q++)
					dup = oi[q] == a && oj[q] == b;
				for (int q = 0; q < p && q < nf && !dup && p < nf; q++)
					dup = oi[q] == a && oj[q] == b;
			} while (dup);
			oi[p] = a;
			oj[p] = b;
			os[p] = p >= nf;
		}
		sb_nlist old;
		make_list(&old, oi, oj, nf, oi + nf, oj + nf, ns, 1);
		sb_shear sh;
		shear_init(&sh);
		sb_err e = {0};
		int ok = !shear_follow(&sh, &old, &e) && sh.n == nf + ns;
		int zero = 1;
		for (int p = 0; p < sh.n; p++)
			zero &= sh.xi[p] == 0;
		char id[96];
		snprintf(id, sizeof id, "shear.follow.trial%d.first_build_all_zero", trial);
		CHECK(id, ok && zero, "n %d of %d pairs, %s", sh.n, nf + ns, e.msg);
		/* half of them in contact, with history (one of either sign zero: no history) */
		double *oxi = calloc((size_t)(nf + ns), sizeof(double));
		for (int p = 0; p < nf + ns; p++) {
			const double u = gsl_rng_uniform(rng);
			oxi[p] = u < 0.5 ? (u - 0.25) * 1e-3 : u < 0.52 ? -0.0 : 0;
			sh.xi[p] = oxi[p];
		}
		/* the same list again: nothing moves */
		ok = !shear_follow(&sh, &old, &e) && !memcmp(sh.xi, oxi, sizeof(double) * (size_t)(nf + ns));
		snprintf(id, sizeof id, "shear.follow.trial%d.same_build_untouched", trial);
		CHECK(id, ok, "entries changed without a new build");
		/* the new build: the old pairs shuffled, a fifth dropped, new pairs (some with
		 * the disks of an old seam pair, flat) among them */
		const int cap = nf + ns + 600;
		int *ni = malloc(sizeof(int) * (size_t)cap), *nj = malloc(sizeof(int) * (size_t)cap),
		    *nsm = calloc((size_t)cap, sizeof(int));
		int nn = 0;
		for (int p = 0; p < nf + ns; p++)
			if (gsl_rng_uniform(rng) < 0.8) {
				ni[nn] = oi[p];
				nj[nn] = oj[p];
				nsm[nn++] = os[p];
			}
		for (int k = 0; k < 500; k++) {
			const int a = 1 + (int)gsl_rng_uniform_int(rng, NDISK - 1), b = (int)gsl_rng_uniform_int(rng, NDISK);
			int dup = a == b;
			for (int q = 0; q < nn && !dup; q++)
				dup = ni[q] == a && nj[q] == b && !nsm[q];
			if (!dup) {
				ni[nn] = a;
				nj[nn] = b;
				nsm[nn++] = 0;
			}
		}
		for (int k = 0; k < ns && k < 20; k++) { /* a seam pair's disks, now flat */
			int dup = 0;
			for (int q = 0; q < nn && !dup; q++)
				dup = ni[q] == oi[nf + k] && nj[q] == oj[nf + k] && !nsm[q];
			if (!dup) {
				ni[nn] = oi[nf + k];
				nj[nn] = oj[nf + k];
				nsm[nn++] = 0;
			}
		}
		for (int p = nn - 1; p > 0; p--) { /* shuffled */
			const int q = (int)gsl_rng_uniform_int(rng, (unsigned long)p + 1);
			int t = ni[p];
			ni[p] = ni[q];
			ni[q] = t;
			t = nj[p];
			nj[p] = nj[q];
			nj[q] = t;
			t = nsm[p];
			nsm[p] = nsm[q];
			nsm[q] = t;
		}
		/* flat first, then seam */
		int *fi = malloc(sizeof(int) * (size_t)nn), *fj = malloc(sizeof(int) * (size_t)nn),
		    *si = malloc(sizeof(int) * (size_t)nn), *sj = malloc(sizeof(int) * (size_t)nn);
		int nnf = 0, nns = 0;
		for (int p = 0; p < nn; p++)
			if (nsm[p]) {
				si[nns] = ni[p];
				sj[nns++] = nj[p];
			} else {
				fi[nnf] = ni[p];
				fj[nnf++] = nj[p];
			}
		sb_nlist nw;
		make_list(&nw, fi, fj, nnf, si, sj, nns, 2);
		ok = !shear_follow(&sh, &nw, &e) && sh.n == nnf + nns && shear_current(&sh, &nw);
		int wrong = 0, carried = 0, first = -1;
		for (int p = 0; p < nnf + nns && ok; p++) {
			const int s = p >= nnf, a = s ? si[p - nnf] : fi[p], b = s ? sj[p - nnf] : fj[p];
			const double want = old_of(oi, oj, os, oxi, nf + ns, a, b, s);
			/* a zero of either sign is no history: zero */
			const double w = want != 0 ? want : 0;
			if (memcmp(&sh.xi[p], &w, sizeof w)) {
				wrong++;
				first = first < 0 ? p : first;
			}
			carried += w != 0;
		}
		snprintf(id, sizeof id, "shear.follow.trial%d.carried_by_identity", trial);
		CHECK(id, ok && wrong == 0 && (carried > 20 || trial == 3),
		      "%d of %d entries wrong (the first at %d), %d carried; %s", wrong, nnf + nns, first, carried, e.msg);
		free_list(&old);
		free_list(&nw);
		shear_free(&sh);
		free(oi);
		free(oj);
		free(os);
		free(oxi);
		free(ni);
		free(nj);
		free(nsm);
		free(fi);
		free(fj);
		free(si);
		free(sj);
	}
	gsl_rng_free(rng);
	return tl_done();
}
