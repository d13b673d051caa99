/* kvec_cp512.h - the fused corrector of the avx512 instance, in AVX-512 intrinsics;
 * included by kvec.c only where it is built for AVX-512 at its native width.
 *
 * kvec.c's own corrector (cpa, written once over simd.h) gives the same bits, and
 * tests/unit/kernel.c compares this one bit for bit with every other path. It is kept
 * for this one instruction set because, compiled by GCC 12, it is the faster of the
 * two: the corrector phase of the paper scene takes 0.079 s per simulated second
 * against 0.089 s for cpa (Zen 5, docs/kernel.md "The AVX-512 corrector"). The
 * arithmetic and the instruction mix are the same; what differs is GCC's schedule
 * and register allocation of the loop. To time cpa in its place, build with
 * XFLAGS=-DSB_NO_CP512; should cpa catch up with a later compiler, this file goes. */
#ifndef SB_KVEC_CP512_H
#define SB_KVEC_CP512_H

#include <immintrin.h>

SB_INLINE void k512_transpose(__m512d r[8])
{
	__m512d t[8], u[8];
	for (int k = 0; k < 8; k += 2) {
		t[k] = _mm512_unpacklo_pd(r[k], r[k + 1]);
		t[k + 1] = _mm512_unpackhi_pd(r[k], r[k + 1]);
	}
	for (int k = 0; k < 8; k += 4) {
		u[k] = _mm512_shuffle_f64x2(t[k], t[k + 2], 0x88);
		u[k + 1] = _mm512_shuffle_f64x2(t[k + 1], t[k + 3], 0x88);
		u[k + 2] = _mm512_shuffle_f64x2(t[k], t[k + 2], 0xDD);
		u[k + 3] = _mm512_shuffle_f64x2(t[k + 1], t[k + 3], 0xDD);
	}
	for (int k = 0; k < 4; k++) {
		r[k] = _mm512_shuffle_f64x2(u[k], u[k + 4], 0x88);
		r[k + 4] = _mm512_shuffle_f64x2(u[k], u[k + 4], 0xDD);
	}
}

/* The records of eight consecutive disks from vectors of their x, y, vx, vy, w, R;
 * only the first `count` are stored (a partial block must not overwrite the walls,
 * whose records follow the mobile disks'). */
SB_INLINE void k512_rec_store(double *rec, __m512d x, __m512d y, __m512d vx, __m512d vy, __m512d w, __m512d R,
                              __m512d inv_m, int count)
{
	__m512d row[8] = {x, y, vx, vy, _mm512_mul_pd(R, w), inv_m, R, R};
	k512_transpose(row);
	if (count == 8)
		for (int k = 0; k < 8; k++)
			_mm512_store_pd(rec + 8 * k, row[k]);
	else
		for (int k = 0; k < count; k++)
			_mm512_store_pd(rec + 8 * k, row[k]);
}

/* x, y, vx, vy of eight consecutive disks from their records: the low halves of the
 * records paired (disk k with k + 4) and transposed, 12 shuffles */
SB_INLINE void k512_rec_load(const double *rec, __m512d *x, __m512d *y, __m512d *vx, __m512d *vy)
{
	__m512d z[4];
	for (int k = 0; k < 4; k++) /* (x y vx vy) of disk k | of disk k + 4 */
		z[k] = _mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_load_pd(rec + 8 * k)),
		                          _mm256_load_pd(rec + 8 * (k + 4)), 1);
	/* t0 = (x0 x1 vx0 vx1 | x4 x5 vx4 vx5), t1 the same of y, t2 and t3 of disks 2, 3 | 6, 7 */
	const __m512d t0 = _mm512_unpacklo_pd(z[0], z[1]), t1 = _mm512_unpackhi_pd(z[0], z[1]),
	              t2 = _mm512_unpacklo_pd(z[2], z[3]), t3 = _mm512_unpackhi_pd(z[2], z[3]);
	const __m512i lo = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0),
	              hi = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
	*x = _mm512_permutex2var_pd(t0, lo, t2);
	*vx = _mm512_permutex2var_pd(t0, hi, t2);
	*y = _mm512_permutex2var_pd(t1, lo, t3);
	*vy = _mm512_permutex2var_pd(t1, hi, t3);
}

/* Fx, Fy and the torque of eight consecutive disks from their accumulators */
SB_INLINE void k512_load_acc(const double *acc, __m512d *fx, __m512d *fy, __m512d *t)
{
	const __m512i ix = _mm512_set_epi64(13, 9, 5, 1, 12, 8, 4, 0),
	              it = _mm512_set_epi64(15, 11, 7, 3, 14, 10, 6, 2);
	const __m512d z0 = _mm512_load_pd(acc), z1 = _mm512_load_pd(acc + 8), z2 = _mm512_load_pd(acc + 16),
	              z3 = _mm512_load_pd(acc + 24);
	/* lo = (x0 x1 x2 x3 y0 y1 y2 y3), hi the same for disks 4..7 */
	const __m512d lo = _mm512_permutex2var_pd(z0, ix, z1), hi = _mm512_permutex2var_pd(z2, ix, z3);
	*fx = _mm512_shuffle_f64x2(lo, hi, 0x44);
	*fy = _mm512_shuffle_f64x2(lo, hi, 0xEE);
	const __m512d tlo = _mm512_permutex2var_pd(z0, it, z1), thi = _mm512_permutex2var_pd(z2, it, z3);
	*t = _mm512_shuffle_f64x2(tlo, thi, 0x44);
}

/* The fused pass, as cpa in kvec.c: per block of eight disks, the forces from the
 * kernel's accumulators, the three coordinates' correct_predict (the same operations
 * element by element, written with vector operators; no FMA is formed, as
 * -ffp-contract=off holds for them too), the step's screening of the predicted state,
 * and the records of that state for the next force evaluation - which are also where
 * x, y and their velocities are kept between such passes. The Nordsieck arrays, the
 * accumulators and the records are then each touched once a step, where separate
 * passes swept the state four more times. A partial last block masks its loads and
 * stores. */
typedef __m512d v8;

SB_INLINE v8 vload(const double *p, int full, __mmask8 m)
{
	return full ? _mm512_loadu_pd(p) : _mm512_maskz_loadu_pd(m, p);
}

SB_INLINE void vstore(double *p, v8 v, int full, __mmask8 m)
{
	if (full)
		_mm512_storeu_pd(p, v);
	else
		_mm512_mask_storeu_pd(p, m, v);
}

/* One coordinate of eight disks from i. soa01: q0 and q1 are read from and written to
 * the arrays, and *q0, *q1 get the predicted ones; else *q0, *q1 are the current ones
 * in and the predicted ones out, the arrays untouched (x and y: the records hold
 * them, see cpa512_block). */
SB_INLINE void cp512_block(const int nval, const double *c, double h, v8 f, v8 inv, double extra, qarr q,
                           int i, int full, __mmask8 m, const int soa01, v8 *q0, v8 *q1)
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

SB_INLINE void cpa512_block(const int nval, const cpa_args *a, int i, int count, cpa_flags *fl)
{
	const int full = count == 8;
	const __mmask8 m = (__mmask8)((1u << count) - 1);
	v8 fx, fy, ft, x0, x1, y0, y1, t0, t1;
	k512_load_acc(a->facc + 4 * i, &fx, &fy, &ft);
	for (int k = 0; k < 4; k++) /* the next kernel adds into them: beyond count are walls, */
		_mm512_store_pd(a->facc + 4 * i + 8 * k, _mm512_setzero_pd()); /* which it clears */
	/* x, y and their velocities live in the records between fused passes: the kernel
	 * of this step read them there (kernel_forces packs them if the last step was
	 * not fused), and this pass writes them only there - four arrays fewer to
	 * stream, where the pass is bound by moving lines between L1 and L2 (or L3).
	 * kernel_sync() brings st up to date for everyone else. */
	k512_rec_load(a->rec + 8 * i, &x0, &y0, &x1, &y1);
	const v8 im = vload(a->inv_m + i, full, m), R = vload(a->r + i, full, m);
	cp512_block(nval, a->c, a->h, fx, im, 0, a->x, i, full, m, 0, &x0, &x1);
	cp512_block(nval, a->c, a->h, fy, im, a->gy, a->y, i, full, m, 0, &y0, &y1);
	cp512_block(nval, a->c, a->h, ft, vload(a->inv_i + i, full, m), 0, a->t, i, full, m, 1, &t0, &t1);
	k512_rec_store(a->rec + 8 * i, x0, y0, x1, y1, t1, R, im, count);
	/* the step's check of the state (step.c, check_state), operation by operation */
	const v8 dx = x0 - vload(a->xref + i, full, m), dy = y0 - vload(a->yref + i, full, m);
	const v8 d2 = dx * dx + dy * dy;
	const v8 at = _mm512_abs_pd(t0);
	fl->rebuild |= _mm512_mask_cmp_pd_mask(m, d2, _mm512_set1_pd(a->lim), _CMP_GT_OQ);
	fl->bad |= _mm512_mask_cmp_pd_mask(m, d2 + at, _mm512_set1_pd(INFINITY), _CMP_NLT_UQ);
	fl->out |= _mm512_mask_cmp_pd_mask(m, x0, _mm512_set1_pd(a->xlo), _CMP_LT_OQ) |
	           _mm512_mask_cmp_pd_mask(m, x0, _mm512_set1_pd(a->xhi), _CMP_GT_OQ) |
	           _mm512_mask_cmp_pd_mask(m, y0, _mm512_set1_pd(a->ylo), _CMP_LT_OQ);
}

SB_INLINE void cpa512(sb_kdata *k, const int nval, const sb_integ *in, sb_state *st, double gy,
                      const sb_nlist *nl, sb_screen *scr)
{
	cpa_args a = {qarr_of(st, C_X),
	              qarr_of(st, C_Y),
	              qarr_of(st, C_TH),
	              st->inv_m,
	              st->inv_i,
	              st->r,
	              nl->xref,
	              nl->yref,
	              k->facc,
	              k->rec,
	              {0},
	              in->half_dt2,
	              gy,
	              scr->lim,
	              scr->xlo,
	              scr->xhi,
	              scr->ylo};
	for (int o = 0; o < SB_MAXORDER; o++)
		a.c[o] = in->c[o];
	cpa_flags fl = {0, 0, 0};
	const int n = st->nm;
	int i = 0;
	for (; i + 8 <= n; i += 8)
		cpa512_block(nval, &a, i, 8, &fl);
	if (i < n)
		cpa512_block(nval, &a, i, n - i, &fl);
	scr->done = 1;
	scr->rebuild = fl.rebuild != 0;
	scr->bad = fl.bad != 0;
	scr->out = fl.out != 0;
}

#endif
