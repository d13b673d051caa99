/* kernel.c - the force kernel module (core/force/kernel.h), on every path of this build the
 * CPU can run (the others are named on SKIP lines): the forces it gives are those of
 * the contact law applied pair by pair in list order with m_eff = 1 / (1/m_i + 1/m_j)
 * (forces_pair), in st->f and through the fused corrector's path; the ring's |F| sums
 * are those of the same pairs; every path gives the first path's bits (forces, ring
 * sums, fused step, neighbour list); an unknown or unrunnable path is refused. The
 * shear-spring law (tangential = spring) too: its forces are forces_pair_spring's pair
 * by pair from zero shear, the same on every path. */
#include <gsl/gsl_rng.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bigmem.h"
#include "kernel.h"
#include "place.h"
#include "testlib.h"

/* a bed of n grains scattered over W x H (overlapping: every pair a contact candidate)
 * above a floor of wall disks, with random velocities and spins */
static void scene(sb_state *st, gsl_rng *rng, int n, double W, double H, double dt)
{
	sb_scene sc;
	params_defaults(&sc);
	sb_err e = {0};
	for (int i = 0; i < n; i++)
		place_push(&sc, st, W * gsl_rng_uniform(rng), 1 + H * gsl_rng_uniform(rng),
			     0.85 + 0.3 * gsl_rng_uniform(rng), i == 0 ? KIND_INTRUDER : KIND_GRAIN, &e);
	for (double x = -1; x <= W + 1 + 1e-9; x += 2)
		place_push(&sc, st, x, -0.2, 1, KIND_WALL, &e);
	for (int i = 0; i < st->nm; i++) {
		st->q[C_X][1][i] = dt * 50 * (2 * gsl_rng_uniform(rng) - 1);
		st->q[C_Y][1][i] = dt * 50 * (2 * gsl_rng_uniform(rng) - 1);
		st->q[C_TH][1][i] = dt * 20 * (2 * gsl_rng_uniform(rng) - 1);
	}
}

/* the forces pair by pair, in list order, as the kernels add them */
static void reference(const sb_law *law, const sb_state *st, const sb_nlist *nl, double inv_dt, double *f[3],
		      double *fabs_sum)
{
	for (int c = 0; c < 3; c++)
		memset(f[c], 0, sizeof(double) * (size_t)st->n);
	for (int p = 0; p < nl->nflat; p++) {
		const int i = nl->pi[p] >> nl->pshift, j = nl->pj[p] >> nl->pshift;
		double fx, fy, ti, tj, h = 0; /* the spring's: a fresh contact */
		if (law->spring)
			forces_pair_spring(law, st->q[C_X][0][i] - st->q[C_X][0][j], st->q[C_Y][0][i] - st->q[C_Y][0][j],
					   st->r[i], st->r[j], st->q[C_X][1][i] - st->q[C_X][1][j],
					   st->q[C_Y][1][i] - st->q[C_Y][1][j], st->q[C_TH][1][i], st->q[C_TH][1][j],
					   1.0 / (st->inv_m[i] + st->inv_m[j]), inv_dt, &h, 1, &fx, &fy, &ti, &tj);
		else
			forces_pair(law, st->q[C_X][0][i] - st->q[C_X][0][j], st->q[C_Y][0][i] - st->q[C_Y][0][j], st->r[i],
			    st->r[j], (st->q[C_X][1][i] - st->q[C_X][1][j]) * inv_dt,
			    (st->q[C_Y][1][i] - st->q[C_Y][1][j]) * inv_dt, st->q[C_TH][1][i] * inv_dt,
			    st->q[C_TH][1][j] * inv_dt, 1.0 / (st->inv_m[i] + st->inv_m[j]), &fx, &fy, &ti, &tj);
		if (fx == 0 && fy == 0 && ti == 0 && tj == 0)
			continue;
		f[C_X][i] += fx;
		f[C_Y][i] += fy;
		f[C_TH][i] += ti;
		f[C_X][j] -= fx;
		f[C_Y][j] -= fy;
		f[C_TH][j] += tj;
		const double fa = sqrt(fx * fx + fy * fy);
		fabs_sum[i] += fa;
		fabs_sum[j] += fa;
	}
}

/* largest difference relative to the largest value: the kernels fold 1/dt into the
 * damping constants, forces_pair into the velocities, so the last bits differ */
static double max_rel(const double *a, const double *b, int n)
{
	double worst = 0, scale = 0;
	for (int i = 0; i < n; i++) {
		worst = fmax(worst, fabs(a[i] - b[i]));
		scale = fmax(scale, fabs(b[i]));
	}
	return scale > 0 ? worst / scale : worst;
}

enum { NMODE = 10 };

/* what the first path gave, for the others to equal: per clip, the forces, the ring
 * sums, the fused step's state and the list */
typedef struct firsts {
	int have[NMODE];
	double *f[NMODE][3], *fs[NMODE], *q[NMODE][3][6];
	int *pi[NMODE], *pj[NMODE], np[NMODE];
} firsts;

static int bits_equal(const void *a, const void *b, size_t bytes)
{
	return !memcmp(a, b, bytes);
}

static void *dup_bytes(const void *p, size_t bytes)
{
	void *q = malloc(bytes);
	memcpy(q, p, bytes);
	return q;
}

static void test_forces(const char *path, firsts *fi)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	/* mode: clip_attractive (bit 0); the law (mode / 2): the paper's, the damping per
	 * pair from restitution, Hertz, the shear spring, Hertz with the shear spring */
	for (int mode = 0; mode < NMODE; mode++) {
		const int clip = mode & 1, resti = mode / 2 == 1, hertz = mode / 2 == 2 || mode / 2 == 4,
			  spring = mode / 2 >= 3;
		const char *const rs = resti ? ".restitution" : mode / 2 == 2 ? ".hertz" : mode / 2 == 3 ? ".spring" : mode / 2 == 4 ? ".hertz_spring" : "";
		gsl_rng_set(rng, 7 + (unsigned long)clip);
		sb_state st = {0};
		const double dt = 5e-5, inv_dt = 1 / dt;
		scene(&st, rng, 203, 30, 12, dt); /* 203: a partial last block of eight */
		/* scattered: some overlaps are deep */
		/* the spring's shear damping large enough that some contacts reach the Coulomb cap */
		sb_law law = {.Y = hertz ? 3.15e7 : 3e6, .gn = 100, .gs = spring ? 2000 : 1, .mu = 0.5, .max_overlap = 100,
			      .clip = clip, .resti = resti, .gz = resti ? forces_gz(3e6, 0.7) : 0, .hertz = hertz,
			      .spring = spring, .kt = 2.0 / 7.0 * (hertz ? 3.15e7 : 3e6)};
		sb_nlist nl;
		sb_kernel *k = NULL;
		sb_err e = {0};
		int ok = !kernel_init_path(&k, &st, path, &e) && !nlist_init(&nl, &st, 0.5, kernel_pair_shift(), &e);
		if (ok) {
			nl.scan = kernel_scan(k);
			ok = !nlist_build(&nl, &st, &e);
		}
		char id[128];
		snprintf(id, sizeof id, "kernel.%s.clip%d%s.setup", path, clip, rs);
		CHECK(id, ok, "%s", e.msg);
		if (!ok)
			return;
		double *ref[3], *got[3], *fs_ref = calloc((size_t)st.n, sizeof(double)),
				      *fs_got = calloc((size_t)st.n, sizeof(double));
		for (int c = 0; c < 3; c++) {
			ref[c] = malloc(sizeof(double) * (size_t)st.n);
			got[c] = malloc(sizeof(double) * (size_t)st.n);
		}
		reference(&law, &st, &nl, inv_dt, ref, fs_ref);
		int ncontact = 0;
		for (int i = 0; i < st.n; i++)
			ncontact += fs_ref[i] > 0;
		snprintf(id, sizeof id, "kernel.%s.clip%d%s.scene_has_contacts", path, clip, rs);
		CHECK(id, ncontact > 100, "only %d disks touch", ncontact);
		/* into st->f; each evaluation below from zero shear, as the reference */
		sb_shear *sh = kernel_shear(k);
		int bad = kernel_forces(k, &law, &st, &nl, inv_dt, 0, NULL, &e);
		double w = 0;
		for (int c = 0; c < 3; c++) {
			double r = max_rel(st.f[c], ref[c], st.n);
			w = r > w ? r : w;
		}
		snprintf(id, sizeof id, "kernel.%s.clip%d%s.forces_equal_pair_sums", path, clip, rs);
		/* a wrong m_eff, sign or torque would differ by far more than rounding */
		CHECK(id, bad == 0 && w < 1e-12, "largest relative difference %.3g (kernel returned %d)", w, bad);
		/* the ring's sums */
		for (int c = 0; c < 3; c++)
			memcpy(got[c], st.f[c], sizeof(double) * (size_t)st.n);
		/* a table of materials whose classes all hold the law's own coefficients runs
		 * forces_scalar, the table's path, on every path: the same bits as the vector
		 * kernel (or the spring's pass), so that a table changes only the pairs it names */
		{
			sb_law tab = law;
			tab.table = 1;
			for (int a = 0; a < 3; a++)
				for (int b = 0; b < 3; b++)
					tab.kc[a][b] = (sb_kc){law.Y, resti ? law.gz : law.gn, law.gs, law.mu, law.kt};
			shear_clear(sh);
			const int bad2 = kernel_forces(k, &tab, &st, &nl, inv_dt, 0, NULL, &e);
			int same = bad2 == bad;
			for (int c = 0; c < 3; c++)
				same &= bits_equal(st.f[c], got[c], sizeof(double) * (size_t)st.n);
			snprintf(id, sizeof id, "kernel.%s.clip%d%s.uniform_table_same_bits", path, clip, rs);
			CHECK(id, same, "a table of the law's own coefficients changed the forces");
			/* and a class of its own changes the forces of the disks in that class only */
			tab.kc[KIND_GRAIN][KIND_WALL].mu = tab.kc[KIND_WALL][KIND_GRAIN].mu = 0;
			tab.kc[KIND_GRAIN][KIND_WALL].Y = tab.kc[KIND_WALL][KIND_GRAIN].Y = 2 * law.Y;
			shear_clear(sh);
			kernel_forces(k, &tab, &st, &nl, inv_dt, 0, NULL, &e);
			int moved = 0, leaked = 0;
			for (int i = 0; i < st.nm; i++) {
				int walltouch = 0;
				for (int j = st.nm; j < st.n; j++) {
					const double dx = st.q[C_X][0][i] - st.q[C_X][0][j], dy = st.q[C_Y][0][i] - st.q[C_Y][0][j];
					walltouch |= dx * dx + dy * dy < (st.r[i] + st.r[j]) * (st.r[i] + st.r[j]);
				}
				const int diff = st.f[C_X][i] != got[C_X][i] || st.f[C_Y][i] != got[C_Y][i];
				moved += walltouch && diff;
				leaked += !walltouch && diff;
			}
			snprintf(id, sizeof id, "kernel.%s.clip%d%s.table_class_changes_its_pairs_only", path, clip, rs);
			CHECK(id, moved > 0 && leaked == 0, "%d disks on a wall changed, %d elsewhere changed", moved, leaked);
			/* the vector kernel's table instance gives forces_scalar's bits (the scalar
			 * pass every path ran before it), in the accumulators' order too; and the
			 * coefficients of the pairs are formed again when the table changes */
			if (!spring) {
				double *sc[3];
				for (int c = 0; c < 3; c++)
					sc[c] = calloc((size_t)st.n, sizeof(double));
				const sb_seam_io io = {st.q[C_X][0], st.q[C_Y][0], st.q[C_X][1], st.q[C_Y][1], sc[C_X], sc[C_Y],
						       sc[C_TH], 1, 1};
				const int bads = forces_scalar(&tab, &st, &nl, NULL, &io, inv_dt, NULL);
				int eq = bads == 0;
				for (int c = 0; c < 3; c++)
					eq &= bits_equal(st.f[c], sc[c], sizeof(double) * (size_t)st.n);
				snprintf(id, sizeof id, "kernel.%s.clip%d%s.table_equals_scalar_bits", path, clip, rs);
				CHECK(id, eq, "the table's forces differ from forces_scalar's in some bit");
				tab.kc[KIND_GRAIN][KIND_WALL].mu = tab.kc[KIND_WALL][KIND_GRAIN].mu = 0.25;
				kernel_forces(k, &tab, &st, &nl, inv_dt, 0, NULL, &e);
				for (int c = 0; c < 3; c++)
					memset(sc[c], 0, sizeof(double) * (size_t)st.n);
				forces_scalar(&tab, &st, &nl, NULL, &io, inv_dt, NULL);
				eq = 1;
				for (int c = 0; c < 3; c++)
					eq &= bits_equal(st.f[c], sc[c], sizeof(double) * (size_t)st.n);
				snprintf(id, sizeof id, "kernel.%s.clip%d%s.table_change_reaches_pairs", path, clip, rs);
				CHECK(id, eq, "after a change of the table the kernel used the old pairs' coefficients");
				/* the ring's sums with a table: the vector kernel's, forces_scalar's bits */
				double *fr = calloc((size_t)st.n, sizeof(double)), *fk = calloc((size_t)st.n, sizeof(double));
				for (int c = 0; c < 3; c++)
					memset(sc[c], 0, sizeof(double) * (size_t)st.n);
				forces_scalar(&tab, &st, &nl, NULL, &io, inv_dt, fr);
				kernel_forces(k, &tab, &st, &nl, inv_dt, 0, fk, &e);
				eq = bits_equal(fr, fk, sizeof(double) * (size_t)st.n);
				for (int c = 0; c < 3; c++)
					eq &= bits_equal(st.f[c], sc[c], sizeof(double) * (size_t)st.n);
				snprintf(id, sizeof id, "kernel.%s.clip%d%s.table_ring_sums_equal_scalar_bits", path, clip, rs);
				CHECK(id, eq, "the ring's sums or forces with a table differ from forces_scalar's in some bit");
				free(fr);
				free(fk);
				for (int c = 0; c < 3; c++)
					free(sc[c]);
			}
			for (int c = 0; c < 3; c++)
				memcpy(st.f[c], got[c], sizeof(double) * (size_t)st.n);
		}
		shear_clear(sh);
		kernel_forces(k, &law, &st, &nl, inv_dt, 0, fs_got, &e);
		snprintf(id, sizeof id, "kernel.%s.clip%d%s.ring_sums_equal_pair_sums", path, clip, rs);
		CHECK(id, max_rel(fs_got, fs_ref, st.n) < 1e-12, "largest relative difference %.3g",
		      max_rel(fs_got, fs_ref, st.n));
		/* an overlap beyond the threshold is reported */
		sb_law tight = law;
		tight.max_overlap = 1e-6;
		snprintf(id, sizeof id, "kernel.%s.clip%d%s.overlap_flag", path, clip, rs);
		CHECK(id, kernel_forces(k, &tight, &st, &nl, inv_dt, 0, NULL, &e) == 1, "no overlap beyond 1e-6 R reported");
		if (spring) { /* some contacts slid: the cap's rescaling is on every path */
			int capped = 0;
			for (int p = 0; p < nl.nflat; p++)
				if (sh->xi[p] != 0) {
					const int i = nl.pi[p] >> nl.pshift, j = nl.pj[p] >> nl.pshift;
					double h = 0, fx, fy, ti, tj;
					forces_pair_spring(&law, st.q[C_X][0][i] - st.q[C_X][0][j],
							   st.q[C_Y][0][i] - st.q[C_Y][0][j], st.r[i], st.r[j],
							   st.q[C_X][1][i] - st.q[C_X][1][j], st.q[C_Y][1][i] - st.q[C_Y][1][j],
							   st.q[C_TH][1][i], st.q[C_TH][1][j], 1.0 / (st.inv_m[i] + st.inv_m[j]),
							   inv_dt, &h, 1, &fx, &fy, &ti, &tj);
					/* advanced once from zero, twice now: 2 v_t dt unless rescaled */
					capped += fabs(sh->xi[p] - 2 * h) > 1e-9 * fabs(h);
				}
			snprintf(id, sizeof id, "kernel.%s.clip%d%s.some_contacts_slide", path, clip, rs);
			CHECK(id, capped > 5, "only %d contacts at the Coulomb cap: the rescaling is not exercised", capped);
			/* the vector instances against forces_scalar (the pass every path ran before
			 * them), the law's and a table's whose grain-wall class has a stiffness,
			 * friction and shear stiffness of its own: three evaluations from no history,
			 * each advancing it, the forces and the displacements (capped ones rescaled)
			 * to the bit, then one with the ring's sums */
			sb_law tsp = law;
			tsp.table = 1;
			for (int a = 0; a < 3; a++)
				for (int b = 0; b < 3; b++)
					tsp.kc[a][b] = (sb_kc){law.Y, law.gn, law.gs, law.mu, law.kt};
			tsp.kc[KIND_GRAIN][KIND_WALL] = tsp.kc[KIND_WALL][KIND_GRAIN] =
				(sb_kc){2 * law.Y, law.gn, law.gs, 0.3, 1.5 * law.kt};
			for (int tb = 0; tb < 2; tb++) {
				const sb_law *lw = tb ? &tsp : &law;
				sb_shear rsh;
				shear_init(&rsh);
				shear_follow(&rsh, &nl, &e);
				shear_clear(sh);
				double *sc[3];
				for (int c = 0; c < 3; c++)
					sc[c] = calloc((size_t)st.n, sizeof(double));
				const sb_seam_io io = {st.q[C_X][0], st.q[C_Y][0], st.q[C_X][1], st.q[C_Y][1],
						       sc[C_X],      sc[C_Y],      sc[C_TH],     1, 1};
				int eq = 1, nz = 0;
				for (int it = 0; it < 3; it++) {
					const int bk = kernel_forces(k, lw, &st, &nl, inv_dt, 0, NULL, &e);
					for (int c = 0; c < 3; c++)
						memset(sc[c], 0, sizeof(double) * (size_t)st.n);
					eq &= bk == forces_scalar(lw, &st, &nl, &rsh, &io, inv_dt, NULL);
					for (int c = 0; c < 3; c++)
						eq &= bits_equal(st.f[c], sc[c], sizeof(double) * (size_t)st.n);
					eq &= sh->n == rsh.n && bits_equal(sh->xi, rsh.xi, sizeof(double) * (size_t)rsh.n);
				}
				/* and a fourth with the ring's sums (the spring's instances take them
				 * at run time) */
				double *fr = calloc((size_t)st.n, sizeof(double)), *fk = calloc((size_t)st.n, sizeof(double));
				const int bk = kernel_forces(k, lw, &st, &nl, inv_dt, 0, fk, &e);
				for (int c = 0; c < 3; c++)
					memset(sc[c], 0, sizeof(double) * (size_t)st.n);
				eq &= bk == forces_scalar(lw, &st, &nl, &rsh, &io, inv_dt, fr);
				eq &= bits_equal(fr, fk, sizeof(double) * (size_t)st.n);
				for (int c = 0; c < 3; c++)
					eq &= bits_equal(st.f[c], sc[c], sizeof(double) * (size_t)st.n);
				eq &= sh->n == rsh.n && bits_equal(sh->xi, rsh.xi, sizeof(double) * (size_t)rsh.n);
				free(fr);
				free(fk);
				for (int p = 0; p < rsh.n; p++)
					nz += rsh.xi[p] != 0;
				snprintf(id, sizeof id, "kernel.%s.clip%d%s.%sspring_equals_scalar_bits", path, clip, rs,
					 tb ? "table_" : "");
				CHECK(id, eq && nz > 100, "forces or shear displacements differ from forces_scalar's (%d contacts)",
				      nz);
				for (int c = 0; c < 3; c++)
					free(sc[c]);
				shear_free(&rsh);
			}
		}
		/* the fused path: forces kept, corrected and predicted in one pass, then
		 * synced, equal the reference step (forces into st->f, correct, predict) */
		sb_integ in;
		integ_init(&in, INTEG_GEAR5, dt);
		sb_state st2 = {0};
		gsl_rng_set(rng, 7 + (unsigned long)clip);
		scene(&st2, rng, 203, 30, 12, dt);
		shear_clear(sh);
		kernel_forces(k, &law, &st, &nl, inv_dt, 0, NULL, &e);
		integ_correct_predict(&in, &st, -981);
		sb_kernel *k2 = NULL;
		sb_nlist nl2;
		kernel_init_path(&k2, &st2, path, &e);
		nlist_init(&nl2, &st2, 0.5, kernel_pair_shift(), &e);
		nl2.scan = kernel_scan(k2);
		nlist_build(&nl2, &st2, &e);
		sb_screen scr = {0.0625, -1e9, 1e9, -1e9, 0, 0, 0, 0};
		kernel_forces(k2, &law, &st2, &nl2, inv_dt, 1, NULL, &e);
		kernel_correct_predict(k2, &in, &st2, -981, &nl2, &scr);
		double ymid = kernel_y(k2, &st2, 5);
		kernel_sync(k2, &st2);
		int same = ymid == st2.q[C_Y][0][5];
		for (int c = 0; c < 3; c++)
			for (int o = 0; o < 6; o++)
				same &= !memcmp(st.q[c][o], st2.q[c][o], sizeof(double) * (size_t)st.nm);
		snprintf(id, sizeof id, "kernel.%s.clip%d%s.fused_equals_reference_step", path, clip, rs);
		CHECK(id, same, "the fused corrector's state differs from forces + correct + predict");
		/* every path gives the first path's bits */
		const size_t nb = sizeof(double) * (size_t)st.n, mb = sizeof(double) * (size_t)st.nm;
		if (!fi->have[mode]) {
			fi->have[mode] = 1;
			for (int c = 0; c < 3; c++) {
				fi->f[mode][c] = dup_bytes(got[c], nb);
				for (int o = 0; o < 6; o++)
					fi->q[mode][c][o] = dup_bytes(st2.q[c][o], mb);
			}
			fi->fs[mode] = dup_bytes(fs_got, nb);
			fi->np[mode] = nl.nflat;
			fi->pi[mode] = dup_bytes(nl.pi, sizeof(int) * (size_t)nl.nflat);
			fi->pj[mode] = dup_bytes(nl.pj, sizeof(int) * (size_t)nl.nflat);
		} else {
			int eq = nl.nflat == fi->np[mode] && bits_equal(nl.pi, fi->pi[mode], sizeof(int) * (size_t)nl.nflat) &&
				 bits_equal(nl.pj, fi->pj[mode], sizeof(int) * (size_t)nl.nflat);
			snprintf(id, sizeof id, "kernel.%s.clip%d%s.list_equals_first_path", path, clip, rs);
			CHECK(id, eq, "the candidate scan gave another list (%d pairs against %d)", nl.nflat, fi->np[mode]);
			eq = bits_equal(fs_got, fi->fs[mode], nb);
			for (int c = 0; c < 3; c++)
				eq &= bits_equal(got[c], fi->f[mode][c], nb);
			snprintf(id, sizeof id, "kernel.%s.clip%d%s.forces_equal_first_path_bits", path, clip, rs);
			CHECK(id, eq, "forces or ring sums differ from the first path's in some bit");
			eq = 1;
			for (int c = 0; c < 3; c++)
				for (int o = 0; o < 6; o++)
					eq &= bits_equal(st2.q[c][o], fi->q[mode][c][o], mb);
			snprintf(id, sizeof id, "kernel.%s.clip%d%s.fused_step_equals_first_path_bits", path, clip, rs);
			CHECK(id, eq, "the fused step's state differs from the first path's in some bit");
		}
		nlist_free(&nl2);
		kernel_free(k2);
		state_free(&st2);
		for (int c = 0; c < 3; c++) {
			free(ref[c]);
			free(got[c]);
		}
		free(fs_ref);
		free(fs_got);
		nlist_free(&nl);
		kernel_free(k);
		state_free(&st);
	}
	gsl_rng_free(rng);
}

/* a path the CPU cannot run, and a name that is none, are refused with the variable's
 * name and the choices */
static void test_refusals(const sb_kpath *p, int n)
{
	sb_state st = {0};
	sb_scene sc;
	params_defaults(&sc);
	sb_err e = {0};
	place_push(&sc, &st, 0, 1, 1, KIND_GRAIN, &e);
	sb_kernel *k = NULL;
	int rc = kernel_init_path(&k, &st, "mmx", &e);
	CHECK("kernel.refuses_unknown_path", rc == SB_EUSAGE && strstr(e.msg, SB_KERNEL_ENV) && strstr(e.msg, p[0].name),
	      "rc %d, message '%s'", rc, e.msg);
	kernel_free(k);
	for (int i = 0; i < n; i++)
		if (!p[i].runnable) {
			e = (sb_err){0};
			k = NULL;
			rc = kernel_init_path(&k, &st, p[i].name, &e);
			CHECK("kernel.refuses_path_the_cpu_lacks", rc == SB_EUSAGE && strstr(e.msg, "cannot run"),
			      "%s: rc %d, message '%s'", p[i].name, rc, e.msg);
			kernel_free(k);
			break;
		}
	/* auto is the widest runnable path that is not for tests only */
	e = (sb_err){0};
	k = NULL;
	rc = kernel_init_path(&k, &st, "auto", &e);
	const char *want = NULL;
	for (int i = 0; i < n && !want; i++)
		if (p[i].runnable && !p[i].test)
			want = p[i].name;
	CHECK("kernel.auto_is_the_widest_runnable", rc == 0 && want && !strcmp(kernel_path(k), want), "auto chose %s, want %s",
	      rc ? "(error)" : kernel_path(k), want ? want : "(none)");
	kernel_free(k);
	state_free(&st);
}

/* The invariants the kernel's loads rely on (nlist_check, kernel_check): a good list
 * and a fused step's data pass, each kind of damage is named; and in the test build
 * (no NDEBUG) kernel_forces asserts on a damaged list it has not walked yet: a
 * forked child given one dies of SIGABRT, one given the good list does not. */
#ifndef NDEBUG
static int child_forces(sb_kernel *k, const sb_law *law, sb_state *st, const sb_nlist *nl)
{
	fflush(NULL);
	pid_t pid = fork();
	if (pid == 0) {
		sb_err e = {0};
		kernel_forces(k, law, st, nl, 1e4, 0, NULL, &e);
		_exit(0);
	}
	int ws = 0;
	waitpid(pid, &ws, 0);
	return ws;
}
#endif

static void test_invariants(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 11);
	sb_state st = {0};
	scene(&st, rng, 41, 12, 8, 5e-5);
	sb_law law = {.Y = 3e6, .gn = 100, .gs = 1, .mu = 0.5, .max_overlap = 100};
	sb_nlist nl;
	sb_kernel *k = NULL;
	sb_err e = {0};
	int ok = !kernel_init(&k, &st, &e) && !nlist_init(&nl, &st, 0.5, kernel_pair_shift(), &e);
	if (ok) {
		nl.scan = kernel_scan(k);
		ok = !nlist_build(&nl, &st, &e);
	}
	CHECK("kernel.invariants.setup", ok && nl.npairs > 2, "%s (%d pairs)", e.msg, ok ? nl.npairs : 0);
	if (!ok)
		return;
	const char *why = nlist_check(&nl, st.n, st.nm);
	CHECK("kernel.invariants.good_list_passes", !why, "%s", why);
	struct {
		const char *id, *want;
		int p, v, of_j;
	} dmg[] = {
		{"kernel.invariants.unscaled_index", "multiple", 0, 1, 0},
		{"kernel.invariants.index_past_the_disks", "outside", 0, 1 << 30, 1},
		{"kernel.invariants.pair_reversed", "out of order", 1, 0, 1},
	};
	for (size_t c = 0; c < sizeof dmg / sizeof dmg[0]; c++) {
		int *a = dmg[c].of_j ? nl.pj : nl.pi, keep = a[dmg[c].p];
		a[dmg[c].p] = dmg[c].v;
		why = nlist_check(&nl, st.n, st.nm);
		CHECK(dmg[c].id, why && strstr(why, dmg[c].want), "got '%s', want one naming '%s'", why ? why : "(none)",
		      dmg[c].want);
		a[dmg[c].p] = keep;
	}
	/* a fused step leaves records and accumulators as the next evaluation needs */
	sb_integ in;
	integ_init(&in, INTEG_GEAR5, 5e-5);
	sb_screen scr = {0};
	scr.lim = INFINITY, scr.xlo = -INFINITY, scr.xhi = INFINITY, scr.ylo = -INFINITY;
	kernel_forces(k, &law, &st, &nl, 1 / 5e-5, 1, NULL, &e);
	kernel_correct_predict(k, &in, &st, -981, &nl, &scr);
	why = kernel_check(k, &st);
	CHECK("kernel.invariants.fused_step_passes", !why, "%s", why);
	kernel_sync(k, &st);
	const double r0 = st.r[3];
	st.r[3] *= 1.5; /* the record still holds the old radius */
	why = kernel_check(k, &st);
	CHECK("kernel.invariants.record_radius_named", why && strstr(why, "constant lanes"), "got '%s'",
	      why ? why : "(none)");
	st.r[3] = r0;
#ifdef NDEBUG
	printf("SKIP kernel.invariants.assert_fires: assert() is compiled out of this build (NDEBUG)\n");
#else
	/* a new build: the kernel has not walked it */
	nlist_build(&nl, &st, &e);
	int ws = child_forces(k, &law, &st, &nl);
	CHECK("kernel.invariants.good_list_no_assert", WIFEXITED(ws) && WEXITSTATUS(ws) == 0, "child status %#x", ws);
	nlist_build(&nl, &st, &e);
	nl.pi[0] += 1;
	ws = child_forces(k, &law, &st, &nl);
	CHECK("kernel.invariants.damaged_list_asserts", WIFSIGNALED(ws) && WTERMSIG(ws) == SIGABRT,
	      "child status %#x (want SIGABRT)", ws);
	nl.pi[0] -= 1;
#endif
	kernel_free(k);
	nlist_free(&nl);
	state_free(&st);
	gsl_rng_free(rng);
}

int main(void)
{
	sb_kpath p[SB_KPATHS_MAX];
	const int n = kernel_paths(p);
	firsts fi;
	memset(&fi, 0, sizeof fi);
	for (int i = 0; i < n; i++) {
		if (p[i].runnable)
			test_forces(p[i].name, &fi);
		else
			printf("SKIP kernel.%s: this CPU cannot run it (it needs %s)\n", p[i].name, p[i].needs);
	}
	test_refusals(p, n);
	test_invariants();
	for (int c = 0; c < NMODE; c++) {
		for (int d = 0; d < 3; d++) {
			free(fi.f[c][d]);
			for (int o = 0; o < 6; o++)
				free(fi.q[c][d][o]);
		}
		free(fi.fs[c]);
		free(fi.pi[c]);
		free(fi.pj[c]);
	}
	return tl_done();
}
