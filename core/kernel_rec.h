/* kernel_rec.h - private to the kernel module (kernel.c; and its unit test): the
 * AVX-512 force kernel's per-disk data: a 64-byte record (x, y, vx, vy, R w,
 * 1/m, R, R) per disk, read by the kernel two per pair, and a 32-byte accumulator (Fx, Fy,
 * torque, 0) per disk, into which it adds one vector per contact. The corrector
 * consumes the accumulators and writes the next step's records in the same pass over
 * the disks, so neither is a separate sweep over memory. Velocities are the scaled
 * Nordsieck ones (v dt), as everywhere in the kernel. The record's sixth lane is 1/m
 * (0 for walls): the kernel forms m_eff = 1 / (1/m_i + 1/m_j) of a pair from the two
 * records (the scalar kernel's formula) instead of streaming a per-pair array. */
#ifndef SB_KERNEL_REC_H
#define SB_KERNEL_REC_H

#include "kernel.h"

#if SB_KERNEL_AVX512
#include <immintrin.h>

/* rows r[0..7] -> columns, in place: 24 shuffles */
static inline __attribute__((always_inline)) void krec_transpose8(__m512d r[8])
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
static inline __attribute__((always_inline)) void krec_store8(double *rec, __m512d x, __m512d y,
							      __m512d vx, __m512d vy, __m512d w,
							      __m512d R, __m512d inv_m, int count)
{
	__m512d row[8] = {x, y, vx, vy, _mm512_mul_pd(R, w), inv_m, R, R};
	krec_transpose8(row);
	if (count == 8)
		for (int k = 0; k < 8; k++)
			_mm512_store_pd(rec + 8 * k, row[k]);
	else
		for (int k = 0; k < count; k++)
			_mm512_store_pd(rec + 8 * k, row[k]);
}

/* x, y, vx, vy of eight consecutive disks from their records: the low halves of the
 * records paired (disk k with k + 4) and transposed, 12 shuffles */
static inline __attribute__((always_inline)) void krec_load8(const double *rec, __m512d *x,
							     __m512d *y, __m512d *vx, __m512d *vy)
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
static inline __attribute__((always_inline)) void krec_load_acc8(const double *acc, __m512d *fx,
								 __m512d *fy, __m512d *t)
{
	const __m512i ix = _mm512_set_epi64(13, 9, 5, 1, 12, 8, 4, 0),
		      it = _mm512_set_epi64(15, 11, 7, 3, 14, 10, 6, 2);
	const __m512d z0 = _mm512_load_pd(acc), z1 = _mm512_load_pd(acc + 8),
		      z2 = _mm512_load_pd(acc + 16), z3 = _mm512_load_pd(acc + 24);
	/* lo = (x0 x1 x2 x3 y0 y1 y2 y3), hi the same for disks 4..7 */
	const __m512d lo = _mm512_permutex2var_pd(z0, ix, z1), hi = _mm512_permutex2var_pd(z2, ix, z3);
	*fx = _mm512_shuffle_f64x2(lo, hi, 0x44);
	*fy = _mm512_shuffle_f64x2(lo, hi, 0xEE);
	const __m512d tlo = _mm512_permutex2var_pd(z0, it, z1), thi = _mm512_permutex2var_pd(z2, it, z3);
	*t = _mm512_shuffle_f64x2(tlo, thi, 0x44);
}
#endif

#endif
