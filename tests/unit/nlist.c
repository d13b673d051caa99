/* nlist.c - the cell/Verlet neighbour list finds exactly the pairs the O(N^2)
 * brute force finds (centre distance < R_i + R_j + skin, no wall-wall pairs), on
 * random polydisperse packings with an intruder (radius ratio 2..8) and walls, after
 * moving the disks and rebuilding, over several seeds, and in degenerate layouts (a
 * tight cluster plus a disk far away, which makes the grid clamp and grow cells).
 * Pair SETS are compared: the flat list's ordinary pairs (i, j > i, rows of ascending
 * i) plus its pairs involving large disks, each normalised to (min, max); every pair
 * must appear exactly once (m_eff per pair: tests/unit/kernel.c). */
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kernel.h"
#include "nlist.h"
#include "place.h"
#include "testlib.h"

static int cmp_pair(const void *a, const void *b)
{
	const long *x = a, *y = b;
	return (*x > *y) - (*x < *y);
}

/* Compare list and brute force; returns 1 if equal, fills a reason otherwise. */
static int compare(const sb_state *st, const sb_nlist *nl, double skin, char *why, size_t len)
{
	long nb = nlist_brute(st, skin, NULL, NULL, 0);
	int *bi = malloc(sizeof(int) * (size_t)(nb + 1)), *bj = malloc(sizeof(int) * (size_t)(nb + 1));
	nlist_brute(st, skin, bi, bj, nb);
	long nl_n = nl->nflat;
	long *a = malloc(sizeof(long) * (size_t)(nl_n + 1)), *b = malloc(sizeof(long) * (size_t)(nb + 1));
	long k = 0;
	int ok = 1;
	why[0] = 0;
	if (nl->npairs + nl->nbig != nl->nflat) {
		snprintf(why, len, "npairs %d + nbig %d != nflat %d", nl->npairs, nl->nbig, nl->nflat);
		ok = 0;
	}
	/* the ordinary pairs: rows of ascending i, j > i, no large disk */
	for (int p = 0; p < nl->npairs; p++) {
		int i = nl->pi[p] >> nl->pshift, j = nl->pj[p] >> nl->pshift;
		if (j <= i || j >= st->n || i >= st->nm || nl->large[i] || nl->large[j] ||
		    (p > 0 && i < nl->pi[p - 1] >> nl->pshift)) {
			snprintf(why, len, "ordinary pair %d = (%d, %d) is not j > i, in rows of ascending i", p, i, j);
			ok = 0;
		}
		a[k++] = (long)i * st->n + j;
	}
	for (int p = nl->npairs; p < nl->nflat; p++) {
		int i = nl->pi[p] >> nl->pshift, j = nl->pj[p] >> nl->pshift;
		if (!nl->large[i] && !nl->large[j] && ok) {
			snprintf(why, len, "big pair (%d, %d) involves no large disk", i, j);
			ok = 0;
		}
		int lo = i < j ? i : j, hi = i < j ? j : i;
		a[k++] = (long)lo * st->n + hi;
	}
	for (long q = 0; q < nb; q++)
		b[q] = (long)bi[q] * st->n + bj[q];
	qsort(a, (size_t)k, sizeof(long), cmp_pair);
	qsort(b, (size_t)nb, sizeof(long), cmp_pair);
	for (long q = 1; q < k && ok; q++)
		if (a[q] == a[q - 1]) {
			snprintf(why, len, "pair (%ld, %ld) listed twice", a[q] / st->n, a[q] % st->n);
			ok = 0;
		}
	/* first difference of the two sorted sets */
	long x = 0, y = 0;
	while (ok && (x < k || y < nb)) {
		if (x < k && y < nb && a[x] == b[y]) {
			x++;
			y++;
		} else if (y >= nb || (x < k && a[x] < b[y])) {
			long p = a[x];
			int i = (int)(p / st->n), j = (int)(p % st->n);
			snprintf(why, len, "list has extra pair (%d, %d) at distance %.6g, cutoff %.6g", i, j,
				 hypot(st->q[C_X][0][i] - st->q[C_X][0][j], st->q[C_Y][0][i] - st->q[C_Y][0][j]),
				 st->r[i] + st->r[j] + skin);
			ok = 0;
		} else {
			long p = b[y];
			int i = (int)(p / st->n), j = (int)(p % st->n);
			snprintf(why, len, "list misses pair (%d, %d) (kinds %d %d, r %.3g %.3g) at distance %.6g, cutoff %.6g",
				 i, j, st->kind[i], st->kind[j], st->r[i], st->r[j],
				 hypot(st->q[C_X][0][i] - st->q[C_X][0][j], st->q[C_Y][0][i] - st->q[C_Y][0][j]),
				 st->r[i] + st->r[j] + skin);
			ok = 0;
		}
	}
	if (ok && k != nb) {
		snprintf(why, len, "%ld listed vs %ld brute-force pairs", k, nb);
		ok = 0;
	}
	free(a);
	free(b);
	free(bi);
	free(bj);
	return ok;
}

/* A box of width W with wall disks (bottom and sides), n grains with radii in
 * [0.85, 1.15] scattered (overlaps allowed: the list does not care) and one intruder
 * of radius ratio*1 near the bottom centre. */
static void build_scene(sb_state *st, gsl_rng *rng, int n, double ratio, double W, double H)
{
	sb_scene sc;
	params_defaults(&sc);
	sb_err e = {0};
	place_push(&sc, st, 0.5 * W, ratio + 0.5, ratio, KIND_INTRUDER, &e);
	for (int i = 0; i < n; i++) {
		double r = 0.85 + 0.3 * gsl_rng_uniform(rng);
		place_push(&sc, st, W * gsl_rng_uniform(rng), H * gsl_rng_uniform(rng), r, KIND_GRAIN, &e);
	}
	for (double x = -1; x <= W + 1 + 1e-9; x += 2)
		place_push(&sc, st, x, -1, 1, KIND_WALL, &e);
	for (double y = 1; y <= H + 1e-9; y += 2) {
		place_push(&sc, st, -1, y, 1, KIND_WALL, &e);
		place_push(&sc, st, W + 1, y, 1, KIND_WALL, &e);
	}
}

static void jiggle(sb_state *st, gsl_rng *rng, double amp)
{
	for (int i = 0; i < st->nm; i++) {
		st->q[C_X][0][i] += amp * (2 * gsl_rng_uniform(rng) - 1);
		st->q[C_Y][0][i] += amp * (2 * gsl_rng_uniform(rng) - 1);
	}
}

int main(void)
{
	char id[160], why[512];
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	const double ratios[] = {2, 3.5, 5, 8};
	const double skins[] = {0.15, 0.5};
	for (int seed = 1; seed <= 4; seed++) {
		gsl_rng_set(rng, (unsigned long)seed);
		double ratio = ratios[seed - 1], skin = skins[seed % 2];
		sb_state st = {0};
		sb_nlist nl;
		sb_err e = {0};
		build_scene(&st, rng, 300, ratio, 40, 30);
		int ok = !nlist_init(&nl, &st, skin, kernel_pair_shift(), &e) && !nlist_build(&nl, &st, &e);
		snprintf(id, sizeof id, "nlist.random.seed%d.intruder_is_large", seed);
		CHECK(id, ok && nl.large[0] && nl.nlarge >= 1, "ratio %g: intruder not classified large", ratio);
		snprintf(id, sizeof id, "nlist.random.seed%d.build", seed);
		CHECK(id, ok && compare(&st, &nl, skin, why, sizeof why), "ratio %g skin %g: %s %s", ratio, skin,
		      why, e.msg);
		/* move everybody (the intruder too) by up to 3 cm and rebuild, three times */
		for (int round = 1; round <= 3; round++) {
			jiggle(&st, rng, 3.0);
			ok = !nlist_build(&nl, &st, &e);
			snprintf(id, sizeof id, "nlist.random.seed%d.rebuild%d", seed, round);
			CHECK(id, ok && compare(&st, &nl, skin, why, sizeof why), "%s %s", why, e.msg);
		}
		nlist_free(&nl);
		state_free(&st);
	}

	/* A tight cluster plus one grain 1e5 cm away: the bounding box is huge, the
	 * cell count cap makes the cells grow; the intruder's reach is clamped. */
	{
		gsl_rng_set(rng, 99);
		sb_state st = {0};
		sb_nlist nl;
		sb_err e = {0};
		build_scene(&st, rng, 120, 4, 12, 12);
		/* grain 1 flies away (stays mobile: nm unchanged) */
		st.q[C_X][0][1] = 1e5;
		st.q[C_Y][0][1] = -3e4;
		int ok = !nlist_init(&nl, &st, 0.3, kernel_pair_shift(), &e) && !nlist_build(&nl, &st, &e);
		CHECK("nlist.flying.build", ok && compare(&st, &nl, 0.3, why, sizeof why), "%s %s", why, e.msg);
		CHECK("nlist.flying.cells_capped", ok && (double)nl.ncx * nl.ncy <= 4.0 * st.n + 64,
		      "%d x %d cells", nl.ncx, nl.ncy);
		/* a second disk right next to the flyer: the pair must be found */
		st.q[C_X][0][2] = 1e5 + 1.5;
		st.q[C_Y][0][2] = -3e4;
		ok = !nlist_build(&nl, &st, &e);
		CHECK("nlist.flying.pair_far_away", ok && compare(&st, &nl, 0.3, why, sizeof why), "%s %s", why, e.msg);
		/* the intruder flies too */
		st.q[C_X][0][0] = -5e4;
		st.q[C_Y][0][0] = 7e4;
		st.q[C_X][0][3] = -5e4 + 4.5;
		st.q[C_Y][0][3] = 7e4;
		ok = !nlist_build(&nl, &st, &e);
		CHECK("nlist.flying.intruder_far_away", ok && compare(&st, &nl, 0.3, why, sizeof why), "%s %s", why, e.msg);
		nlist_free(&nl);
		state_free(&st);
	}

	/* Everything on one spot (zero-size bounding box) and two intruders touching. */
	{
		sb_scene sc;
		params_defaults(&sc);
		sb_state st = {0};
		sb_nlist nl;
		sb_err e = {0};
		place_push(&sc, &st, 0, 0, 6, KIND_INTRUDER, &e);
		place_push(&sc, &st, 11.9, 0, 6, KIND_INTRUDER, &e);
		for (int i = 0; i < 20; i++)
			place_push(&sc, &st, 5, 5, 1, KIND_GRAIN, &e);
		place_push(&sc, &st, 5, 5, 1, KIND_WALL, &e);
		place_push(&sc, &st, 5, 6, 1, KIND_WALL, &e);
		int ok = !nlist_init(&nl, &st, 0.15, kernel_pair_shift(), &e) && !nlist_build(&nl, &st, &e);
		CHECK("nlist.degenerate.same_spot", ok && compare(&st, &nl, 0.15, why, sizeof why), "%s %s", why, e.msg);
		nlist_free(&nl);
		state_free(&st);
	}
	gsl_rng_free(rng);
	return tl_done();
}
