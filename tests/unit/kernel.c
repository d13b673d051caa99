/* kernel.c - the force kernel module (core/kernel.h): the forces it gives are, to the
 * bit, those of the contact law applied pair by pair in list order with m_eff =
 * 1 / (1/m_i + 1/m_j) (forces_pair), in st->f and through the fused corrector's path;
 * the ring's |F| sums are those of the same pairs; and, in the AVX-512 build, the
 * per-disk records and accumulators give back exactly what went in. */
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bigmem.h"
#include "kernel.h"
#include "prepare.h"
#include "testlib.h"
#if SB_KERNEL_AVX512
#include "kernel_rec.h"
#endif

/* a bed of n grains scattered over W x H (overlapping: every pair a contact candidate)
 * above a floor of wall disks, with random velocities and spins */
static void scene(sb_state *st, gsl_rng *rng, int n, double W, double H, double dt)
{
	sb_scene sc;
	params_defaults(&sc);
	sb_err e = {0};
	for (int i = 0; i < n; i++)
		prepare_push(&sc, st, W * gsl_rng_uniform(rng), 1 + H * gsl_rng_uniform(rng),
			     0.85 + 0.3 * gsl_rng_uniform(rng), i == 0 ? KIND_INTRUDER : KIND_GRAIN, &e);
	for (double x = -1; x <= W + 1 + 1e-9; x += 2)
		prepare_push(&sc, st, x, -0.2, 1, KIND_WALL, &e);
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
		double fx, fy, ti, tj;
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

static void test_forces(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	for (int clip = 0; clip <= 1; clip++) {
		gsl_rng_set(rng, 7 + (unsigned long)clip);
		sb_state st = {0};
		const double dt = 5e-5, inv_dt = 1 / dt;
		scene(&st, rng, 203, 30, 12, dt); /* 203: a partial last block of eight */
		sb_law law = {3e6, 100, 1, 0.5, 100, clip}; /* scattered: some overlaps are deep */
		sb_nlist nl;
		sb_kernel *k = NULL;
		sb_err e = {0};
		int ok = !kernel_init(&k, &st, &e) && !nlist_init(&nl, &st, 0.5, kernel_pair_shift(), &e) &&
			 !nlist_build(&nl, &st, &e);
		char id[96];
		snprintf(id, sizeof id, "kernel.clip%d.setup", clip);
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
		snprintf(id, sizeof id, "kernel.clip%d.scene_has_contacts", clip);
		CHECK(id, ncontact > 100, "only %d disks touch", ncontact);
		/* into st->f */
		int bad = kernel_forces(k, &law, &st, &nl, inv_dt, 0, NULL, &e);
		double w = 0;
		for (int c = 0; c < 3; c++) {
			double r = max_rel(st.f[c], ref[c], st.n);
			w = r > w ? r : w;
		}
		snprintf(id, sizeof id, "kernel.clip%d.forces_equal_pair_sums", clip);
		/* a wrong m_eff, sign or torque would differ by far more than rounding */
		CHECK(id, bad == 0 && w < 1e-12, "largest relative difference %.3g (kernel returned %d)", w, bad);
		/* the ring's sums */
		kernel_forces(k, &law, &st, &nl, inv_dt, 0, fs_got, &e);
		snprintf(id, sizeof id, "kernel.clip%d.ring_sums_equal_pair_sums", clip);
		CHECK(id, max_rel(fs_got, fs_ref, st.n) < 1e-12, "largest relative difference %.3g",
		      max_rel(fs_got, fs_ref, st.n));
		/* an overlap beyond the threshold is reported */
		sb_law tight = law;
		tight.max_overlap = 1e-6;
		snprintf(id, sizeof id, "kernel.clip%d.overlap_flag", clip);
		CHECK(id, kernel_forces(k, &tight, &st, &nl, inv_dt, 0, NULL, &e) == 1, "no overlap beyond 1e-6 R reported");
		/* the fused path: forces kept, corrected and predicted in one pass, then
		 * synced, equal the reference step (forces into st->f, correct, predict) */
		sb_integ in;
		integ_init(&in, INTEG_GEAR5, dt);
		sb_state st2 = {0};
		gsl_rng_set(rng, 7 + (unsigned long)clip);
		scene(&st2, rng, 203, 30, 12, dt);
		kernel_forces(k, &law, &st, &nl, inv_dt, 0, NULL, &e);
		integ_correct_predict(&in, &st, -981);
		sb_kernel *k2 = NULL;
		sb_nlist nl2;
		kernel_init(&k2, &st2, &e);
		nlist_init(&nl2, &st2, 0.5, kernel_pair_shift(), &e);
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
		snprintf(id, sizeof id, "kernel.clip%d.fused_equals_reference_step", clip);
		CHECK(id, same, "the fused corrector's state differs from forces + correct + predict");
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

#if SB_KERNEL_AVX512
/* a distinct, exactly representable value per disk and field */
static double val(int disk, int field) { return 1000.0 * disk + field + 0.25; }

static void test_records(void)
{
	double *rec = bigmem_alloc(sizeof(double) * 8 * 16), *acc = bigmem_alloc(sizeof(double) * 4 * 16);
	double f[7][8];
	for (int k = 0; k < 8; k++)
		for (int c = 0; c < 7; c++)
			f[c][k] = val(k, c);
	for (int i = 0; i < 8 * 16; i++)
		rec[i] = -1;
	__m512d v[7];
	for (int c = 0; c < 7; c++)
		v[c] = _mm512_loadu_pd(f[c]);
	/* fields: x y vx vy w R 1/m -> record (x, y, vx, vy, R w, 1/m, R, R) */
	krec_store8(rec, v[0], v[1], v[2], v[3], v[4], v[5], v[6], 8);
	int ok = 1;
	for (int k = 0; k < 8; k++) {
		const double *q = rec + 8 * k;
		ok &= q[0] == f[0][k] && q[1] == f[1][k] && q[2] == f[2][k] && q[3] == f[3][k] &&
		      q[4] == f[5][k] * f[4][k] && q[5] == f[6][k] && q[6] == f[5][k] && q[7] == f[5][k];
	}
	CHECK("kernel.rec.store8.layout", ok, "a record is not (x, y, vx, vy, R w, 1/m, R, R)");
	__m512d x, y, vx, vy;
	krec_load8(rec, &x, &y, &vx, &vy);
	double g[4][8];
	_mm512_storeu_pd(g[0], x);
	_mm512_storeu_pd(g[1], y);
	_mm512_storeu_pd(g[2], vx);
	_mm512_storeu_pd(g[3], vy);
	ok = 1;
	for (int k = 0; k < 8; k++)
		for (int c = 0; c < 4; c++)
			ok &= g[c][k] == f[c][k];
	CHECK("kernel.rec.load8.round_trip", ok, "x, y, vx, vy do not come back from the records");
	/* a partial block writes its first records only (the walls' follow) */
	krec_store8(rec + 64, v[0], v[1], v[2], v[3], v[4], v[5], v[6], 3);
	ok = rec[64 + 8 * 2] == f[0][2];
	for (int i = 64 + 8 * 3; i < 8 * 16; i++)
		ok &= rec[i] == -1;
	CHECK("kernel.rec.store8.partial_leaves_the_rest", ok, "a partial store wrote past its count");
	/* accumulators (Fx, Fy, T, pad) -> three vectors */
	for (int k = 0; k < 8; k++)
		for (int c = 0; c < 4; c++)
			acc[4 * k + c] = val(k, 10 + c);
	__m512d fx, fy, t;
	krec_load_acc8(acc, &fx, &fy, &t);
	_mm512_storeu_pd(g[0], fx);
	_mm512_storeu_pd(g[1], fy);
	_mm512_storeu_pd(g[2], t);
	ok = 1;
	for (int k = 0; k < 8; k++)
		for (int c = 0; c < 3; c++)
			ok &= g[c][k] == val(k, 10 + c);
	CHECK("kernel.rec.load_acc8.fx_fy_torque", ok, "the accumulators do not unpack to Fx, Fy, T");
	free(rec);
	free(acc);
}
#endif

int main(void)
{
	test_forces();
#if SB_KERNEL_AVX512
	test_records();
#endif
	return tl_done();
}
