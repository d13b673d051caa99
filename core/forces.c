/* forces.c - contact law kernel. Conventions (MODEL.md): n = (r_i - r_j)/d,
 * t = n rotated by +90 deg, overlap xi = R_i + R_j - d.
 *   F_N = Y xi + gamma_N m_eff xidot,  xidot = -(v_i - v_j).n          (eq. 2, signed)
 *   v_t = (v_i - v_j).t - (R_i w_i + R_j w_j)   (surface slip of i against j at the
 *         contact point: the contact point is r_i - R_i n, and z x n = t)
 *   F_S = -sign(v_t) min(gamma_S m_eff |v_t|, mu |F_N|)                  (eq. 3)
 *   force on i: F_N n + F_S t, on j the opposite;
 *   torque on i: (-R_i n) x (F_S t) = -R_i F_S, on j: (R_j n) x (-F_S t) = -R_j F_S.
 * Both torques have the sign that reduces the slip; eq. (6) of the paper prints
 * +/- because its orientation convention differs (tests/physics prove this one). */
#include "forces.h"

#include <math.h>
#include <string.h>

static inline __attribute__((always_inline)) void contact(
	const double Y, const double gn, const double gs, const double mu, const int clip,
	const double dx, const double dy, const double d, const double inv, const double ri,
	const double rj, const double dvx, const double dvy, const double wi, const double wj,
	const double meff, double *fx, double *fy, double *fs_out, double *xi_out)
{
	const double nx = dx * inv, ny = dy * inv;
	const double xi = ri + rj - d;
	const double xidot = -(dvx * nx + dvy * ny);
	double fn = Y * xi + gn * meff * xidot;
	if (clip)
		fn = fn > 0 ? fn : 0;
	const double vt = -dvx * ny + dvy * nx - (ri * wi + rj * wj);
	const double fv = gs * meff * fabs(vt), fc = mu * fabs(fn);
	const double fs = copysign(fv < fc ? fv : fc, -vt);
	*fx = fn * nx - fs * ny;
	*fy = fn * ny + fs * nx;
	*fs_out = fs;
	*xi_out = xi;
}

void forces_pair(const sb_law *law, double dx, double dy, double ri, double rj,
		 double dvx, double dvy, double wi, double wj, double meff,
		 double *fx, double *fy, double *ti, double *tj)
{
	double d2 = dx * dx + dy * dy, rs = ri + rj;
	if (d2 >= rs * rs) {
		*fx = *fy = *ti = *tj = 0;
		return;
	}
	double fs, xi, d = sqrt(d2);
	contact(law->Y, law->gn, law->gs, law->mu, law->clip, dx, dy, d, 1.0 / d, ri, rj, dvx, dvy,
		wi, wj, meff, fx, fy, &fs, &xi);
	*ti = -ri * fs;
	*tj = -rj * fs;
}

#if SB_KERNEL_AVX512
/* The force kernel in AVX-512, eight candidate pairs a vector, for CPUs where gathers
 * are slow (they cost more than the scalar loads they replace on the AMD cores this
 * was tuned on). Instead: every disk's contact data is packed once a step into one
 * 64-byte record (x, y, vx, vy, R w, 1/m, R, R; krec.h), a pair's data are two
 * aligned loads combined lane-wise (differences, sums, R_i, R_j), eight pairs are
 * transposed into lanes, and m_eff = 1 / (1/m_i + 1/m_j) is formed there (the
 * formula of the scalar build's per-pair array, which this kernel need not stream).
 * Each lane then performs the scalar code's operations in its order
 * (no FMA in the law; min, max and the sign copy are exact), the contacts are
 * compressed out of the lanes, and a pass per chunk of the list adds their forces to
 * per-disk accumulators (Fx, Fy, torque, 0) in list order, one 4-double vector per
 * disk and contact (a third of the stores of three scalar sums, which bound that
 * pass) - so the forces are bit-identical to the scalar kernel's
 * (tests/integration/regression.sh runs both builds against one reference).
 * The walls' records are packed only when the list is rebuilt: they never move. */
#include "krec.h"

/* the per-disk accumulators (Fx, Fy, torque, 0) -> st->f[C_X], f[C_Y], f[C_TH] */
static void unpack_forces(sb_state *st, const double *restrict facc)
{
	double *restrict fx = st->f[C_X], *restrict fy = st->f[C_Y], *restrict t = st->f[C_TH];
	const int n = st->n;
	int i = 0;
	for (; i + 8 <= n; i += 8) {
		__m512d vx, vy, vt;
		krec_load_acc8(facc + 4 * i, &vx, &vy, &vt);
		_mm512_storeu_pd(fx + i, vx);
		_mm512_storeu_pd(fy + i, vy);
		_mm512_storeu_pd(t + i, vt);
	}
	for (; i < n; i++) {
		fx[i] = facc[4 * i];
		fy[i] = facc[4 * i + 1];
		t[i] = facc[4 * i + 2];
	}
}

/* the records of disks [i0, n) */
static void pack_records(const sb_state *st, double *restrict rec, int i0, int n)
{
	const double *x = st->q[C_X][0], *y = st->q[C_Y][0], *vx = st->q[C_X][1],
		     *vy = st->q[C_Y][1], *w = st->q[C_TH][1], *r = st->r, *im = st->inv_m;
	int i = i0;
	for (; i + 8 <= n; i += 8) {
		krec_store8(rec + 8 * i, _mm512_loadu_pd(x + i), _mm512_loadu_pd(y + i), _mm512_loadu_pd(vx + i),
			    _mm512_loadu_pd(vy + i), _mm512_loadu_pd(w + i), _mm512_loadu_pd(r + i),
			    _mm512_loadu_pd(im + i), 8);
	}
	for (; i < n; i++) {
		double *q = rec + 8 * i;
		q[0] = x[i];
		q[1] = y[i];
		q[2] = vx[i];
		q[3] = vy[i];
		q[4] = r[i] * w[i];
		q[5] = im[i];
		q[6] = q[7] = r[i];
	}
}

static inline __attribute__((always_inline)) int kernel_avx512(const sb_law *law, sb_state *st,
							       const sb_nlist *nl, double inv_dt,
							       const int clip, double *restrict fsum,
							       const int packed, const int keep, const int pf)
{
	const double *rec = nl->rec;
	const int *pi = nl->pi, *pj = nl->pj;
	sb_kbuf *restrict kb = nl->kbuf;
	const int np = nl->nflat;
	const __m512d Y = _mm512_set1_pd(law->Y), gn = _mm512_set1_pd(law->gn * inv_dt),
		      gs = _mm512_set1_pd(law->gs * inv_dt), mu = _mm512_set1_pd(law->mu),
		      mo = _mm512_set1_pd(law->max_overlap), one = _mm512_set1_pd(1.0),
		      zero = _mm512_setzero_pd();
	const __m512i sign = _mm512_set1_epi64((long long)0x8000000000000000ULL);
	/* the lane-wise combination of a pair's records a (of i) and b (of j) as
	 * b wb + a wa, one multiply and one fused multiply-add (two dependent operations
	 * where a blend and two masked ones took three): every product is exact (x 1,
	 * -1, 0), so the single rounding of the FMA is that of a - b or a + b, and lanes
	 * 6 and 7 are R_i + 0 and R_j + 0 - the scalar kernel's numbers to the bit */
	const __m512d wa = _mm512_set_pd(0, 1, 1, 1, 1, 1, 1, 1), wb = _mm512_set_pd(1, 0, 1, 1, -1, -1, -1, -1);
#define NEG(a) _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(a), sign))
#define ABS(a) _mm512_castsi512_pd(_mm512_andnot_si512(sign, _mm512_castpd_si512(a)))

	double *restrict facc = nl->facc;
	/* packed: the fused corrector (integ_correct_predict_acc) of the last step wrote
	 * the mobile disks' records and cleared their accumulators */
	if (!packed) {
		memset(facc, 0, sizeof(double) * 4 * (size_t)st->nm);
		pack_records(st, nl->rec, 0, st->nm);
	}
	memset(facc + 4 * (size_t)st->nm, 0, sizeof(double) * 4 * (size_t)(st->n - st->nm));
	/* the walls' records change only when the list is rebuilt from a new state */
	if (kb->walls_packed != nl->builds) {
		pack_records(st, nl->rec, st->nm, st->n);
		kb->walls_packed = nl->builds;
	}

	__mmask8 bad = 0;
	for (int p0 = 0; p0 < np; p0 += SB_KCHUNK) {
		const int p1 = p0 + SB_KCHUNK < np ? p0 + SB_KCHUNK : np;
		int nc = 0;
		for (int p = p0; p < p1; p += 8) {
			if (pf) /* constant per instantiation */
				for (int l = 0; l < 8; l++) {
					/* the far ends of the pairs 8 blocks ahead: beyond the cache,
					 * their records are the kernel's latency-bound loads */
					const int q = p + 64 + l < np ? p + 64 + l : p;
					_mm_prefetch((const char *)(rec + pj[q]), _MM_HINT_T0);
				}
			const __mmask8 live = p1 - p >= 8 ? 0xff : (__mmask8)((1u << (p1 - p)) - 1);
			/* per pair, lane-wise from the two records: x, y, vx, vy of i minus j;
			 * R w and 1/m of i plus j; R_i; R_j. Then pairs -> lanes. */
			__m512d c[8];
			for (int l = 0; l < 8; l++) {
				const __m512d a = _mm512_load_pd(rec + pi[p + l]); /* 8 i: nlist.h */
				const __m512d b = _mm512_load_pd(rec + pj[p + l]);
				c[l] = _mm512_fmadd_pd(b, wb, _mm512_mul_pd(a, wa));
			}
			krec_transpose8(c);
			const __m512d dx = c[0], dy = c[1], dvx = c[2], dvy = c[3], rw = c[4], ims = c[5],
				      ri = c[6], rj = c[7], rs = _mm512_add_pd(ri, rj);
			const __m512d d2 = _mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy));
			const __mmask8 in = _mm512_mask_cmp_pd_mask(live, d2, _mm512_mul_pd(rs, rs), _CMP_LT_OQ);
			if (!in)
				continue;
			/* contact(), operation by operation; the lanes not in contact compute
			 * numbers that are never stored (their d may be 0) */
			const __m512d d = _mm512_sqrt_pd(d2);
			const __m512d inv = _mm512_div_pd(one, d);
			const __m512d nx = _mm512_mul_pd(dx, inv), ny = _mm512_mul_pd(dy, inv);
			const __m512d xi = _mm512_sub_pd(rs, d);
			/* -xidot; a + k (-s) is a - k s to the bit, and so is (-a) b + c = c - a b */
			const __m512d mxidot = _mm512_add_pd(_mm512_mul_pd(dvx, nx), _mm512_mul_pd(dvy, ny));
			const __m512d meff = _mm512_div_pd(one, ims); /* 1 / (1/m_i + 1/m_j) */
			__m512d fn = _mm512_sub_pd(_mm512_mul_pd(Y, xi), _mm512_mul_pd(_mm512_mul_pd(gn, meff), mxidot));
			if (clip) /* fn > 0 ? fn : 0 (max returns its second operand for NaN, -0) */
				fn = _mm512_max_pd(fn, zero);
			const __m512d vt = _mm512_sub_pd(
				_mm512_sub_pd(_mm512_mul_pd(dvy, nx), _mm512_mul_pd(dvx, ny)), rw);
			const __m512d fv = _mm512_mul_pd(_mm512_mul_pd(gs, meff), ABS(vt));
			const __m512d fc = _mm512_mul_pd(mu, ABS(fn));
			/* copysign(fv < fc ? fv : fc, -vt); min returns its second operand
			 * unless fv < fc */
			const __m512d fs = _mm512_castsi512_pd(_mm512_or_si512(
				_mm512_andnot_si512(sign, _mm512_castpd_si512(_mm512_min_pd(fv, fc))),
				_mm512_andnot_si512(_mm512_castpd_si512(vt), sign)));
			const __m512d fx = _mm512_sub_pd(_mm512_mul_pd(fn, nx), _mm512_mul_pd(fs, ny));
			const __m512d fy = _mm512_add_pd(_mm512_mul_pd(fn, ny), _mm512_mul_pd(fs, nx));
			bad |= _mm512_mask_cmp_pd_mask(in, xi, _mm512_mul_pd(mo, _mm512_min_pd(ri, rj)), _CMP_GT_OQ);
			/* the contacts compressed out of the lanes; whole-vector stores, the
			 * slots past the contacts are overwritten by the next block */
			_mm256_storeu_si256((__m256i *)(kb->i + nc), _mm256_maskz_compress_epi32(
				in, _mm256_loadu_si256((const __m256i *)(pi + p))));
			_mm256_storeu_si256((__m256i *)(kb->j + nc), _mm256_maskz_compress_epi32(
				in, _mm256_loadu_si256((const __m256i *)(pj + p))));
			_mm512_storeu_pd(kb->fx + nc, _mm512_maskz_compress_pd(in, fx));
			_mm512_storeu_pd(kb->fy + nc, _mm512_maskz_compress_pd(in, fy));
			_mm512_storeu_pd(kb->ti + nc, _mm512_maskz_compress_pd(in, NEG(_mm512_mul_pd(ri, fs))));
			_mm512_storeu_pd(kb->tj + nc, _mm512_maskz_compress_pd(in, _mm512_mul_pd(rj, fs)));
			nc += __builtin_popcount(in);
		}
		/* the chunk's forces added to the disks in list order, as 4-double vectors:
		 * (Fx, Fy, -R_i F_S, 0) added to i's, (Fx, Fy, R_j F_S, 0) subtracted from j's
		 * (a - b and a + (-b) are the same number) */
		char *const acc = (char *)facc;
		for (int k = 0; k < nc; k++) {
			/* 8 i, 8 j (nlist.h): disk i's accumulator is 32 i = 4 (8 i) bytes in */
			const ptrdiff_t i8 = kb->i[k], j8 = kb->j[k];
			double *const ai = (double *)(acc + 4 * i8), *const aj = (double *)(acc + 4 * j8);
			const double fx = kb->fx[k], fy = kb->fy[k];
			if (fsum) { /* constant per instantiation: compiled away when NULL */
				const double fa = sqrt(fx * fx + fy * fy);
				fsum[i8 / SB_PSCALE] += fa;
				fsum[j8 / SB_PSCALE] += fa;
			}
			const __m128d xy = _mm_loadh_pd(_mm_load_sd(kb->fx + k), kb->fy + k);
			const __m256d vi = _mm256_insertf128_pd(_mm256_castpd128_pd256(xy), _mm_load_sd(kb->ti + k), 1);
			const __m256d vj = _mm256_insertf128_pd(_mm256_castpd128_pd256(xy), _mm_load_sd(kb->tj + k), 1);
			_mm256_store_pd(ai, _mm256_add_pd(_mm256_load_pd(ai), vi));
			_mm256_store_pd(aj, _mm256_sub_pd(_mm256_load_pd(aj), vj));
		}
	}
	if (!keep) /* else the fused corrector reads the accumulators */
		unpack_forces(st, facc);
	return bad != 0;
#undef NEG
#undef ABS
}
#else
/* Three passes over the flat pair list:
 *  1. "in contact?" for every pair, appended branch-free to a list (with d^2), so the
 *     pairs that are near but not touching cost no mispredicted branch;
 *  2. d and 1/d for the contacts in one contiguous loop, which the compiler
 *     vectorises: square root and division are the slowest operations of a contact
 *     and four lanes do them at nearly the cost of one;
 *  3. the contact forces, in a loop without data-dependent branches.
 * The kernel is instantiated once per value of clip, so that choice is made at setup
 * and costs nothing inside the loops. */
static inline __attribute__((always_inline)) int kernel(const sb_law *law, sb_state *st,
							const sb_nlist *nl, double inv_dt,
							const int clip, double *restrict fsum,
							const int packed, const int keep, const int pf)
{
	(void)packed; /* there are no records or accumulators: forces go to st->f */
	(void)keep;
	(void)pf;
	/* Velocities stay scaled (q1 = v dt): the 1/dt goes into the damping constants,
	 * which saves four multiplications per contact. */
	const double Y = law->Y, gn = law->gn * inv_dt, gs = law->gs * inv_dt, mu = law->mu,
		     mo = law->max_overlap;
	const double *restrict x = st->q[C_X][0], *restrict y = st->q[C_Y][0];
	const double *restrict vx = st->q[C_X][1], *restrict vy = st->q[C_Y][1],
		     *restrict w = st->q[C_TH][1];
	const double *restrict r = st->r;
	double *restrict fxa = st->f[C_X], *restrict fya = st->f[C_Y], *restrict ta = st->f[C_TH];
	const int *restrict pi = nl->pi, *restrict pj = nl->pj;
	const double *restrict pmeff = nl->pmeff;
	int *restrict clist = nl->contact;
	double *restrict cd = nl->cd, *restrict cinv = nl->cinv;
	const int np = nl->nflat;
	int bad = 0;

	memset(fxa, 0, sizeof(double) * (size_t)st->n);
	memset(fya, 0, sizeof(double) * (size_t)st->n);
	memset(ta, 0, sizeof(double) * (size_t)st->n);

	int nc = 0;
	for (int p = 0; p < np; p++) {
		const int i = pi[p], j = pj[p];
		const double dx = x[i] - x[j], dy = y[i] - y[j], rs = r[i] + r[j];
		const double d2 = dx * dx + dy * dy;
		clist[nc] = p;
		cd[nc] = d2;
		nc += d2 < rs * rs;
	}

	for (int k = 0; k < nc; k++) {
		const double d = sqrt(cd[k]);
		cd[k] = d;
		cinv[k] = 1.0 / d;
	}

	for (int k = 0; k < nc; k++) {
		const int p = clist[k];
		const int i = pi[p], j = pj[p];
		const double ri = r[i], rj = r[j];
		double fx, fy, fs, xi;
		contact(Y, gn, gs, mu, clip, x[i] - x[j], y[i] - y[j], cd[k], cinv[k], ri, rj,
			vx[i] - vx[j], vy[i] - vy[j], w[i], w[j], pmeff[p], &fx, &fy, &fs, &xi);
		bad |= xi > mo * (ri < rj ? ri : rj);
		if (fsum) { /* constant per instantiation: compiled away when NULL */
			const double fa = sqrt(fx * fx + fy * fy);
			fsum[i] += fa;
			fsum[j] += fa;
		}
		fxa[i] += fx;
		fya[i] += fy;
		ta[i] -= ri * fs;
		fxa[j] -= fx;
		fya[j] -= fy;
		ta[j] -= rj * fs;
	}
	return bad;
}

#endif

#if SB_KERNEL_AVX512
#define KERNEL kernel_avx512
#else
#define KERNEL kernel
#endif

/* one instantiation per clip_attractive and prefetching (nlist.h: prefetch) */
#define INSTANCE(name, clip, pf)                                                                   \
	static int name(const sb_law *l, sb_state *s, const sb_nlist *n, double inv_dt, int packed, \
			int keep)                                                                   \
	{                                                                                           \
		return KERNEL(l, s, n, inv_dt, clip, NULL, packed, keep, pf);                       \
	}
INSTANCE(kernel_plain, 0, 0)
INSTANCE(kernel_clip, 1, 0)
#if SB_KERNEL_AVX512
INSTANCE(kernel_plain_pf, 0, 1)
INSTANCE(kernel_clip_pf, 1, 1)
#else
#define kernel_plain_pf kernel_plain
#define kernel_clip_pf kernel_clip
#endif

static int dispatch(const sb_law *law, sb_state *st, const sb_nlist *nl, double inv_dt, int packed,
		    int keep)
{
	if (nl->prefetch)
		return law->clip ? kernel_clip_pf(law, st, nl, inv_dt, packed, keep)
				 : kernel_plain_pf(law, st, nl, inv_dt, packed, keep);
	return law->clip ? kernel_clip(law, st, nl, inv_dt, packed, keep)
			 : kernel_plain(law, st, nl, inv_dt, packed, keep);
}

int forces_compute(const sb_law *law, sb_state *st, const sb_nlist *nl, double inv_dt)
{
	return dispatch(law, st, nl, inv_dt, 0, 0);
}

int forces_compute_acc(const sb_law *law, sb_state *st, const sb_nlist *nl, double inv_dt, int packed)
{
	return dispatch(law, st, nl, inv_dt, packed, 1);
}

static __attribute__((noinline)) int kernel_track(const sb_law *l, sb_state *s, const sb_nlist *n,
						  double inv_dt, double *fsum)
{
	return l->clip ? KERNEL(l, s, n, inv_dt, 1, fsum, 0, 0, 0) : KERNEL(l, s, n, inv_dt, 0, fsum, 0, 0, 0);
}

int forces_compute_track(const sb_law *law, sb_state *st, const sb_nlist *nl, double inv_dt,
			 double *fabs_sum)
{
	return kernel_track(law, st, nl, inv_dt, fabs_sum);
}

void forces_records_to_state(const sb_nlist *nl, sb_state *st)
{
#if SB_KERNEL_AVX512
	double *restrict x = st->q[C_X][0], *restrict y = st->q[C_Y][0], *restrict vx = st->q[C_X][1],
		       *restrict vy = st->q[C_Y][1];
	const double *rec = nl->rec;
	const int n = st->nm;
	int i = 0;
	for (; i + 8 <= n; i += 8) {
		__m512d a, b, c, d;
		krec_load8(rec + 8 * i, &a, &b, &c, &d);
		_mm512_storeu_pd(x + i, a);
		_mm512_storeu_pd(y + i, b);
		_mm512_storeu_pd(vx + i, c);
		_mm512_storeu_pd(vy + i, d);
	}
	for (; i < n; i++) {
		x[i] = rec[8 * i];
		y[i] = rec[8 * i + 1];
		vx[i] = rec[8 * i + 2];
		vy[i] = rec[8 * i + 3];
	}
#else
	(void)nl;
	(void)st;
#endif
}

double forces_max_overlap(const sb_state *st, const sb_nlist *nl, int *wi, int *wj)
{
	double worst = 0;
	const double *x = st->q[C_X][0], *y = st->q[C_Y][0], *r = st->r;
	for (int p = 0; p < nl->nflat; p++) {
		const int i = nl->pi[p] / SB_PSCALE, j = nl->pj[p] / SB_PSCALE;
		const double f = (r[i] + r[j] - hypot(x[i] - x[j], y[i] - y[j])) / fmin(r[i], r[j]);
		if (f > worst) {
			worst = f;
			*wi = i;
			*wj = j;
		}
	}
	return worst;
}
