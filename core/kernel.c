/* kernel.c - the force evaluation of a step and its fast path (kernel.h). The
 * portable build calls the portable kernel (forces.c) and correctors (integrate.c);
 * the AVX-512 build has its own kernel and fused corrector here, with the per-disk
 * records only they read and write. */
#include "kernel.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "bigmem.h"

#if SB_KERNEL_AVX512
#include "kernel_rec.h"

enum { SB_KCHUNK = 256 };

/* one chunk of the list's contacts: disks 8i, 8j, the force on i and the torques
 * -R_i F_S, R_j F_S (8 spare slots: the kernel stores whole vectors) */
typedef struct sb_kbuf {
	_Alignas(64) double fx[SB_KCHUNK + 8], fy[SB_KCHUNK + 8], ti[SB_KCHUNK + 8], tj[SB_KCHUNK + 8];
	int i[SB_KCHUNK + 8], j[SB_KCHUNK + 8];
	long walls_packed;          /* the build whose wall records rec holds */
} sb_kbuf;
#endif

struct sb_kernel {
#if SB_KERNEL_AVX512
	/* per disk a 64-byte record (x, y, vx, vy, R w, 1/m, R, R) and a force
	 * accumulator (Fx, Fy, torque, 0); one chunk's contacts */
	double *rec, *facc;
	sb_kbuf *kb;
	/* prefetch the far ends of the pairs: set when the per-disk data a step sweeps
	 * outgrow half the last-level cache (5x10^4 disks on a 32 MiB L3), where those
	 * loads come from memory; below, the prefetches only cost (measured: -6 % at
	 * 10^5 disks, +2 % at 10^4, +4.5 % at 10^3) */
	int prefetch;
	int stale;  /* x, y, vx, vy of the mobile disks are in the records only */
	int packed; /* the records hold the current state, the accumulators are clear */
#else
	sb_kscratch ks; /* the portable kernel's per-pair scratch */
	int cap;
	long built;     /* the list build the scratch's m_eff belong to */
#endif
};

int kernel_pair_shift(void)
{
	return SB_KERNEL_AVX512 ? 3 : 0;
}

int kernel_init(sb_kernel **out, const sb_state *st, sb_err *e)
{
	sb_kernel *k = calloc(1, sizeof *k);
	*out = k;
	if (!k)
		return sb_errf(e, SB_ENOMEM, "out of memory for the force kernel");
#if SB_KERNEL_AVX512
	/* whole 64-byte lines, so that a record is one aligned vector load */
	k->rec = bigmem_alloc(sizeof(double) * 8 * ((size_t)st->n + 8));
	k->kb = aligned_alloc(64, sizeof(sb_kbuf));
	k->facc = bigmem_alloc(sizeof(double) * 4 * ((size_t)st->n + 9));
	if (!k->rec || !k->kb || !k->facc)
		return sb_errf(e, SB_ENOMEM, "out of memory for the force kernel");
	k->kb->walls_packed = -1;
	/* ~300 bytes a disk are swept every step (the state's arrays, record,
	 * accumulator, pairs) */
	k->prefetch = 300.0 * st->n > 0.5 * (double)bigmem_llc_bytes();
#else
	(void)st;
	(void)e;
	k->built = -1;
#endif
	return 0;
}

void kernel_free(sb_kernel *k)
{
	if (!k)
		return;
#if SB_KERNEL_AVX512
	free(k->rec);
	free(k->facc);
	free(k->kb);
#else
	free(k->ks.pmeff);
	free(k->ks.contact);
	free(k->ks.cd);
	free(k->ks.cinv);
#endif
	free(k);
}

#if SB_KERNEL_AVX512
/* The force kernel in AVX-512, eight candidate pairs a vector, for CPUs where gathers
 * are slow (they cost more than the scalar loads they replace on the AMD cores this
 * was tuned on). Instead: every disk's contact data is packed once a step into one
 * 64-byte record (x, y, vx, vy, R w, 1/m, R, R; kernel_rec.h), a pair's data are two
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

static inline __attribute__((always_inline)) int kernel_avx512(sb_kernel *k, const sb_law *law, sb_state *st,
							       const sb_nlist *nl, double inv_dt,
							       const int clip, double *restrict fsum,
							       const int packed, const int keep, const int pf)
{
	const double *rec = k->rec;
	const int *pi = nl->pi, *pj = nl->pj;
	sb_kbuf *restrict kb = k->kb;
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

	double *restrict facc = k->facc;
	/* packed: the fused corrector (integ_correct_predict_acc) of the last step wrote
	 * the mobile disks' records and cleared their accumulators */
	if (!packed) {
		memset(facc, 0, sizeof(double) * 4 * (size_t)st->nm);
		pack_records(st, k->rec, 0, st->nm);
	}
	memset(facc + 4 * (size_t)st->nm, 0, sizeof(double) * 4 * (size_t)(st->n - st->nm));
	/* the walls' records change only when the list is rebuilt from a new state */
	if (kb->walls_packed != nl->builds) {
		pack_records(st, k->rec, st->nm, st->n);
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
				const __m512d a = _mm512_load_pd(rec + pi[p + l]); /* 8 i: kernel_pair_shift */
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
			/* 8 i, 8 j (kernel_pair_shift): disk i's accumulator is 32 i = 4 (8 i) bytes in */
			const ptrdiff_t i8 = kb->i[k], j8 = kb->j[k];
			double *const ai = (double *)(acc + 4 * i8), *const aj = (double *)(acc + 4 * j8);
			const double fx = kb->fx[k], fy = kb->fy[k];
			if (fsum) { /* constant per instantiation: compiled away when NULL */
				const double fa = sqrt(fx * fx + fy * fy);
				fsum[i8 / 8] += fa;
				fsum[j8 / 8] += fa;
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

/* one instantiation per clip_attractive and prefetching */
#define INSTANCE(name, clip, pf)                                                                          \
	static int name(sb_kernel *k, const sb_law *l, sb_state *s, const sb_nlist *n, double inv_dt,      \
			int packed, int keep)                                                              \
	{                                                                                                  \
		return kernel_avx512(k, l, s, n, inv_dt, clip, NULL, packed, keep, pf);                    \
	}
INSTANCE(kernel_plain, 0, 0)
INSTANCE(kernel_clip, 1, 0)
INSTANCE(kernel_plain_pf, 0, 1)
INSTANCE(kernel_clip_pf, 1, 1)
#undef INSTANCE

/* the ring's kernel, compiled separately so that it costs nothing when off */
static __attribute__((noinline)) int kernel_track(sb_kernel *k, const sb_law *l, sb_state *s, const sb_nlist *n,
						  double inv_dt, double *fsum)
{
	return l->clip ? kernel_avx512(k, l, s, n, inv_dt, 1, fsum, 0, 0, 0)
		       : kernel_avx512(k, l, s, n, inv_dt, 0, fsum, 0, 0, 0);
}

static void records_to_state(const sb_kernel *k, sb_state *st)
{
	double *restrict x = st->q[C_X][0], *restrict y = st->q[C_Y][0], *restrict vx = st->q[C_X][1],
		       *restrict vy = st->q[C_Y][1];
	const double *rec = k->rec;
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
}

/* The fused pass of the AVX-512 build: per block of eight disks, the forces from the
 * kernel's accumulators, the three coordinates' correct_predict (the same operations
 * element by element, written with vector operators; no FMA is formed, as
 * -ffp-contract=off holds for them too), the step's screening of the predicted state,
 * and the records of that state for the next force evaluation - which are also where
 * x, y and their velocities are kept between such passes. The Nordsieck arrays, the
 * accumulators and the records are then each touched once a step, where separate
 * passes swept the state four more times. A partial last block masks its loads and
 * stores. */
typedef __m512d v8;

static inline __attribute__((always_inline)) v8 vload(const double *p, int full, __mmask8 m)
{
	return full ? _mm512_loadu_pd(p) : _mm512_maskz_loadu_pd(m, p);
}

static inline __attribute__((always_inline)) void vstore(double *p, v8 v, int full, __mmask8 m)
{
	if (full)
		_mm512_storeu_pd(p, v);
	else
		_mm512_mask_storeu_pd(p, m, v);
}

/* one coordinate's Nordsieck arrays; restrict: the stores into one never change
 * another, nor the pointers (else each store reloads all of them) */
typedef struct qarr {
	double *restrict q0, *restrict q1, *restrict q2, *restrict q3, *restrict q4, *restrict q5;
} qarr;

static inline __attribute__((always_inline)) qarr qarr_of(const sb_state *st, int c)
{
	return (qarr){st->q[c][0], st->q[c][1], st->q[c][2], st->q[c][3], st->q[c][4], st->q[c][5]};
}

/* One coordinate of eight disks from i. soa01: q0 and q1 are read from and written to
 * the arrays, and *q0, *q1 get the predicted ones; else *q0, *q1 are the current ones
 * in and the predicted ones out, the arrays untouched (x and y: the records hold
 * them, see cpa_block). */
static inline __attribute__((always_inline)) void cp_block(const int nval, const double *c, double h,
							   v8 f, v8 inv, double extra, qarr q, int i,
							   int full, __mmask8 m, const int soa01, v8 *q0,
							   v8 *q1)
{
	const v8 a2 = (f * inv + extra) * h;
	const v8 c0 = soa01 ? vload(q.q0 + i, full, m) : *q0, c1 = soa01 ? vload(q.q1 + i, full, m) : *q1;
	if (nval == 6) {
		const v8 d = a2 - vload(q.q2 + i, full, m);
		const v8 b0 = c0 + c[0] * d, a1 = c1 + c[1] * d, a3 = vload(q.q3 + i, full, m) + c[3] * d,
			 a4 = vload(q.q4 + i, full, m) + c[4] * d, a5 = vload(q.q5 + i, full, m) + c[5] * d;
		*q0 = b0 + (a1 + a2 + a3 + a4 + a5);
		*q1 = a1 + 2 * a2 + 3 * a3 + 4 * a4 + 5 * a5;
		vstore(q.q2 + i, a2 + 3 * a3 + 6 * a4 + 10 * a5, full, m);
		vstore(q.q3 + i, a3 + 4 * a4 + 10 * a5, full, m);
		vstore(q.q4 + i, a4 + 5 * a5, full, m);
		vstore(q.q5 + i, a5, full, m);
	} else if (nval == 5) {
		const v8 d = a2 - vload(q.q2 + i, full, m);
		const v8 b0 = c0 + c[0] * d, a1 = c1 + c[1] * d, a3 = vload(q.q3 + i, full, m) + c[3] * d,
			 a4 = vload(q.q4 + i, full, m) + c[4] * d;
		*q0 = b0 + (a1 + a2 + a3 + a4);
		*q1 = a1 + 2 * a2 + 3 * a3 + 4 * a4;
		vstore(q.q2 + i, a2 + 3 * a3 + 6 * a4, full, m);
		vstore(q.q3 + i, a3 + 4 * a4, full, m);
		vstore(q.q4 + i, a4, full, m);
	} else {
		const v8 v = c1 + a2;
		*q1 = v + a2;
		*q0 = c0 + (v + a2);
		vstore(q.q2 + i, a2, full, m);
	}
	if (soa01) {
		vstore(q.q0 + i, *q0, full, m);
		vstore(q.q1 + i, *q1, full, m);
	}
}

typedef struct cpa_args {
	qarr x, y, t;
	const double *restrict inv_m, *restrict inv_i, *restrict r, *restrict xref, *restrict yref;
	double *restrict facc, *restrict rec;
	double c[SB_MAXORDER], h, gy;
	double lim, xlo, xhi, ylo;
} cpa_args;

/* the flags of sb_screen, lane by lane */
typedef struct cpa_flags {
	__mmask8 rebuild, bad, out;
} cpa_flags;

static inline __attribute__((always_inline)) void cpa_block(const int nval, const cpa_args *a,
							    int i, int count, cpa_flags *fl)
{
	const int full = count == 8;
	const __mmask8 m = (__mmask8)((1u << count) - 1);
	v8 fx, fy, ft, x0, x1, y0, y1, t0, t1;
	krec_load_acc8(a->facc + 4 * i, &fx, &fy, &ft);
	for (int k = 0; k < 4; k++) /* the next kernel adds into them: beyond count are walls, */
		_mm512_store_pd(a->facc + 4 * i + 8 * k, _mm512_setzero_pd()); /* which it clears */
	/* x, y and their velocities live in the records between fused passes: the kernel
	 * of this step read them there (kernel_forces packs them if the last step was
	 * not fused), and this pass writes them only there - four arrays fewer to
	 * stream, where the pass is bound by moving lines between L1 and L2 (or L3).
	 * kernel_sync() brings st up to date for everyone else. */
	krec_load8(a->rec + 8 * i, &x0, &y0, &x1, &y1);
	const v8 im = vload(a->inv_m + i, full, m), R = vload(a->r + i, full, m);
	cp_block(nval, a->c, a->h, fx, im, 0, a->x, i, full, m, 0, &x0, &x1);
	cp_block(nval, a->c, a->h, fy, im, a->gy, a->y, i, full, m, 0, &y0, &y1);
	cp_block(nval, a->c, a->h, ft, vload(a->inv_i + i, full, m), 0, a->t, i, full, m, 1, &t0, &t1);
	krec_store8(a->rec + 8 * i, x0, y0, x1, y1, t1, R, im, count);
	/* the step's check of the state (sim.c), operation by operation */
	const v8 dx = x0 - vload(a->xref + i, full, m), dy = y0 - vload(a->yref + i, full, m);
	const v8 d2 = dx * dx + dy * dy;
	const v8 at = _mm512_abs_pd(t0);
	fl->rebuild |= _mm512_mask_cmp_pd_mask(m, d2, _mm512_set1_pd(a->lim), _CMP_GT_OQ);
	fl->bad |= _mm512_mask_cmp_pd_mask(m, d2 + at, _mm512_set1_pd(INFINITY), _CMP_NLT_UQ);
	fl->out |= _mm512_mask_cmp_pd_mask(m, x0, _mm512_set1_pd(a->xlo), _CMP_LT_OQ) |
		   _mm512_mask_cmp_pd_mask(m, x0, _mm512_set1_pd(a->xhi), _CMP_GT_OQ) |
		   _mm512_mask_cmp_pd_mask(m, y0, _mm512_set1_pd(a->ylo), _CMP_LT_OQ);
}

static inline __attribute__((always_inline)) void cpa(sb_kernel *k, const int nval, const sb_integ *in,
						      sb_state *st, double gy, const sb_nlist *nl,
						      sb_screen *scr)
{
	cpa_args a = {qarr_of(st, C_X), qarr_of(st, C_Y), qarr_of(st, C_TH), st->inv_m, st->inv_i,
		      st->r, nl->xref, nl->yref, k->facc, k->rec, {0}, in->half_dt2, gy,
		      scr->lim, scr->xlo, scr->xhi, scr->ylo};
	for (int o = 0; o < SB_MAXORDER; o++)
		a.c[o] = in->c[o];
	cpa_flags fl = {0, 0, 0};
	const int n = st->nm;
	int i = 0;
	for (; i + 8 <= n; i += 8)
		cpa_block(nval, &a, i, 8, &fl);
	if (i < n)
		cpa_block(nval, &a, i, n - i, &fl);
	scr->done = 1;
	scr->rebuild = fl.rebuild != 0;
	scr->bad = fl.bad != 0;
	scr->out = fl.out != 0;
}

void kernel_sync(sb_kernel *k, sb_state *st)
{
	if (k->stale) {
		records_to_state(k, st);
		k->stale = 0;
	}
}

double kernel_y(const sb_kernel *k, const sb_state *st, int i)
{
	return k->stale ? k->rec[8 * (size_t)i + 1] : st->q[C_Y][0][i];
}

/* The flat list's kernel (one instantiation per case) */
static int kernel_flat(sb_kernel *k, const sb_law *law, sb_state *st, const sb_nlist *nl, double inv_dt,
		       int keep, double *fabs_sum, int packed)
{
	if (fabs_sum)
		return kernel_track(k, law, st, nl, inv_dt, fabs_sum);
	if (k->prefetch)
		return law->clip ? kernel_clip_pf(k, law, st, nl, inv_dt, packed, keep)
				 : kernel_plain_pf(k, law, st, nl, inv_dt, packed, keep);
	return law->clip ? kernel_clip(k, law, st, nl, inv_dt, packed, keep)
			 : kernel_plain(k, law, st, nl, inv_dt, packed, keep);
}

int kernel_forces(sb_kernel *k, const sb_law *law, sb_state *st, const sb_nlist *nl, double inv_dt,
		  int keep, double *fabs_sum, sb_err *e)
{
	(void)e; /* the records were sized at kernel_init */
	/* packed: the last fused corrector wrote this state's records and cleared the
	 * accumulators; anything else packs the records from st, which must be current */
	const int packed = keep && !fabs_sum && k->packed;
	k->packed = 0;
	if (!packed)
		kernel_sync(k, st);
	int bad = kernel_flat(k, law, st, nl, inv_dt, keep, fabs_sum, packed);
	if (nl->nseam) { /* periodic sides only: the records hold this state either way */
		const double *rec = k->rec;
		const sb_seam_io io = keep ? (sb_seam_io){rec, rec + 1, rec + 2, rec + 3, k->facc, k->facc + 1,
							  k->facc + 2, 8, 4}
					   : (sb_seam_io){rec, rec + 1, rec + 2, rec + 3, st->f[C_X], st->f[C_Y],
							  st->f[C_TH], 8, 1};
		bad |= forces_seam(law, st, nl, &io, inv_dt, fabs_sum);
	}
	return bad;
}

void kernel_state_changed(sb_kernel *k)
{
	k->packed = 0;
}

void kernel_correct_predict(sb_kernel *k, const sb_integ *in, sb_state *st, double gy, const sb_nlist *nl,
			    sb_screen *scr)
{
	if (in->nval == 6)
		cpa(k, 6, in, st, gy, nl, scr);
	else if (in->nval == 5)
		cpa(k, 5, in, st, gy, nl, scr);
	else
		cpa(k, 3, in, st, gy, nl, scr);
	k->stale = 1;
	k->packed = 1;
}
#else
void kernel_sync(sb_kernel *k, sb_state *st)
{
	(void)k;
	(void)st;
}

double kernel_y(const sb_kernel *k, const sb_state *st, int i)
{
	(void)k;
	return st->q[C_Y][0][i];
}

/* The per-pair data of the list the portable kernel streams: m_eff of each pair (it
 * vectorises, a division per pair), and the scratch it fills, as long as the list. */
static int scratch(sb_kernel *k, const sb_state *st, const sb_nlist *nl, sb_err *e)
{
	if (k->cap < nl->fcap) {
		sb_kscratch *s = &k->ks;
		free(s->pmeff);
		free(s->contact);
		free(s->cd);
		free(s->cinv);
		/* bigmem: streamed every step (huge pages at 10^5 disks) */
		s->pmeff = bigmem_alloc(sizeof(double) * (size_t)nl->fcap);
		s->cd = bigmem_alloc(sizeof(double) * (size_t)nl->fcap);
		s->cinv = bigmem_alloc(sizeof(double) * (size_t)nl->fcap);
		s->contact = bigmem_alloc(sizeof(int) * (size_t)nl->fcap);
		k->cap = nl->fcap;
		if (!s->pmeff || !s->cd || !s->cinv || !s->contact) {
			k->cap = 0;
			return sb_errf(e, SB_ENOMEM, "out of memory for the force kernel");
		}
		k->built = -1;
	}
	if (k->built != nl->builds) {
		const double *restrict im = st->inv_m;
		const int *restrict pi = nl->pi, *restrict pj = nl->pj;
		double *restrict pm = k->ks.pmeff;
		for (int p = 0; p < nl->nflat; p++)
			pm[p] = 1.0 / (im[pi[p]] + im[pj[p]]); /* a wall of infinite mass: the grain's */
		k->built = nl->builds;
	}
	return 0;
}

int kernel_forces(sb_kernel *k, const sb_law *law, sb_state *st, const sb_nlist *nl, double inv_dt,
		  int keep, double *fabs_sum, sb_err *e)
{
	(void)keep; /* the portable corrector reads st->f */
	if (scratch(k, st, nl, e))
		return -1;
	int bad = forces_compute(law, st, nl, &k->ks, inv_dt, fabs_sum);
	if (nl->nseam) { /* periodic sides only */
		const sb_seam_io io = {st->q[C_X][0], st->q[C_Y][0], st->q[C_X][1], st->q[C_Y][1],
				       st->f[C_X], st->f[C_Y], st->f[C_TH], 1, 1};
		bad |= forces_seam(law, st, nl, &io, inv_dt, fabs_sum);
	}
	return bad;
}

void kernel_state_changed(sb_kernel *k)
{
	(void)k; /* the portable kernel reads st itself */
}

void kernel_correct_predict(sb_kernel *k, const sb_integ *in, sb_state *st, double gy, const sb_nlist *nl,
			    sb_screen *scr)
{
	(void)k;
	(void)nl;
	scr->done = 0;
	integ_correct_predict(in, st, gy);
}
#endif
