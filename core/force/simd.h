/* simd.h - the ISA-neutral vector layer of the force kernel (docs/kernel.md). The
 * kernel (kvec.c) is written once over sb_vd, SB_W doubles, with GCC's vector
 * extensions: + - * / and comparisons are the compiler's. What vector extensions
 * cannot say is here, each with a plain-C form beside its per-ISA one: square root,
 * min and max with x86's operand order, a mask's bits, the positions of its set bits;
 * and the transposes, written with __builtin_shuffle, so every ISA gets its own
 * shuffles from one text. Nothing here rounds differently on another ISA: every lane
 * does IEEE double arithmetic, and -ffp-contract=off forbids fused multiply-adds, so
 * all paths give the scalar contact law's bits (tests/unit/kernel.c, regression.sh).
 * Every function is static inline: each kvec.c instance (one per ISA, compiled with
 * its own -march) gets its own copy. */
#ifndef SB_SIMD_H
#define SB_SIMD_H

#include <stdint.h>
#include <string.h>

#define SB_INLINE static inline __attribute__((always_inline))

/* The kernel's width in doubles, SB_W: the native vector's by default (8 with AVX-512,
 * 4 with AVX2, 2 with SSE2 or NEON); an instance may ask for another (kvec.h: the
 * test path "w8", eight lanes in plain code on any CPU). Every operation below is
 * written for any of 2, 4 and 8; the per-ISA forms serve the native width only, and
 * the plain-C forms every other. */
#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512DQ__)
#define SB_NATIVE 8
#define SB_X86 1
#elif defined(__AVX2__)
#define SB_NATIVE 4
#define SB_X86 1
#elif defined(__SSE2__)
#define SB_NATIVE 2
#define SB_X86 1
#else
#define SB_NATIVE 2
#define SB_X86 0
#endif
#ifdef SB_KV_W
#define SB_W SB_KV_W
#else
#define SB_W SB_NATIVE
#endif
#if SB_W != 2 && SB_W != 4 && SB_W != 8
#error "SB_W must be 2, 4 or 8"
#endif
/* the per-ISA forms apply: the width is the native one */
#define SB_X86_NATIVE (SB_X86 && SB_W == SB_NATIVE)
#if defined(__ARM_NEON) && defined(__aarch64__) && SB_W == 2
#define SB_NEON_NATIVE 1
#else
#define SB_NEON_NATIVE 0
#endif
#if SB_X86
#include <immintrin.h>
#elif defined(__ARM_NEON) && defined(__aarch64__)
#include <arm_neon.h>
#endif

/* SB_W doubles, their comparison masks (-1 / 0 per lane), and a per-disk accumulator
 * (Fx, Fy, torque, 0) */
typedef double sb_vd __attribute__((vector_size(8 * SB_W)));
typedef long long sb_vl __attribute__((vector_size(8 * SB_W)));
typedef double sb_v4 __attribute__((vector_size(32)));

/* SB_W ints (pair list indices) and their comparison masks */
typedef int sb_vi __attribute__((vector_size(4 * SB_W)));

SB_INLINE sb_vi sb_loadi(const int *p)
{
	sb_vi v;
	memcpy(&v, p, sizeof v);
	return v;
}

SB_INLINE sb_vd sb_load(const double *p)
{
	sb_vd v;
	memcpy(&v, p, sizeof v);
	return v;
}

SB_INLINE void sb_store(double *p, sb_vd v)
{
	memcpy(p, &v, sizeof v);
}

/* the first n lanes from p, the rest 0; stores the first n lanes only. n is the
 * constant SB_W in every full block, where these are one load or store. */
SB_INLINE sb_vd sb_loadn(const double *p, int n)
{
	if (n == SB_W)
		return sb_load(p);
	double u[SB_W] = {0};
	memcpy(u, p, sizeof(double) * (size_t)n);
	return sb_load(u);
}

SB_INLINE void sb_storen(double *p, sb_vd v, int n)
{
	if (n == SB_W) {
		sb_store(p, v);
		return;
	}
	double u[SB_W];
	sb_store(u, v);
	memcpy(p, u, sizeof(double) * (size_t)n);
}

SB_INLINE sb_vd sb_splat(double a)
{
	return a - (sb_vd){0};
}

SB_INLINE sb_vd sb_sel(sb_vl m, sb_vd a, sb_vd b)
{
	return (sb_vd)(((sb_vl)a & m) | ((sb_vl)b & ~m));
}

#define SB_SIGN ((long long)0x8000000000000000ULL)

SB_INLINE sb_vd sb_abs(sb_vd a)
{
	return (sb_vd)((sb_vl)a & ~SB_SIGN);
}

/* |a| with the sign of -s: copysign(a, -s) */
SB_INLINE sb_vd sb_copysign_neg(sb_vd a, sb_vd s)
{
	return (sb_vd)(((sb_vl)a & ~SB_SIGN) | (~(sb_vl)s & SB_SIGN));
}

SB_INLINE sb_vd sb_neg(sb_vd a)
{
	return (sb_vd)((sb_vl)a ^ SB_SIGN);
}

/* a < b ? a : b and a > b ? a : b, lane by lane (x86's minpd and maxpd: the second
 * operand for NaN and for equal zeros of either sign, which is what the scalar law's
 * ternaries give) */
SB_INLINE sb_vd sb_min(sb_vd a, sb_vd b)
{
#if SB_X86_NATIVE && SB_W == 8
	return (sb_vd)_mm512_min_pd((__m512d)a, (__m512d)b);
#elif SB_X86_NATIVE && SB_W == 4
	return (sb_vd)_mm256_min_pd((__m256d)a, (__m256d)b);
#elif SB_X86_NATIVE
	return (sb_vd)_mm_min_pd((__m128d)a, (__m128d)b);
#else
	return sb_sel(a < b, a, b);
#endif
}

SB_INLINE sb_vd sb_max(sb_vd a, sb_vd b)
{
#if SB_X86_NATIVE && SB_W == 8
	return (sb_vd)_mm512_max_pd((__m512d)a, (__m512d)b);
#elif SB_X86_NATIVE && SB_W == 4
	return (sb_vd)_mm256_max_pd((__m256d)a, (__m256d)b);
#elif SB_X86_NATIVE
	return (sb_vd)_mm_max_pd((__m128d)a, (__m128d)b);
#else
	return sb_sel(a > b, a, b);
#endif
}

/* the correctly rounded square root (IEEE: the same bits on every ISA) */
SB_INLINE sb_vd sb_sqrt(sb_vd a)
{
#if SB_X86_NATIVE && SB_W == 8
	return (sb_vd)_mm512_sqrt_pd((__m512d)a);
#elif SB_X86_NATIVE && SB_W == 4
	return (sb_vd)_mm256_sqrt_pd((__m256d)a);
#elif SB_X86_NATIVE
	return (sb_vd)_mm_sqrt_pd((__m128d)a);
#elif SB_NEON_NATIVE
	return (sb_vd)vsqrtq_f64((float64x2_t)a);
#else
	double u[SB_W];
	sb_store(u, a);
	for (int l = 0; l < SB_W; l++)
		u[l] = __builtin_sqrt(u[l]);
	return sb_load(u);
#endif
}

/* bit l set when lane l of the mask is */
SB_INLINE unsigned sb_bits(sb_vl m)
{
#if SB_X86_NATIVE && SB_W == 8
	return _mm512_movepi64_mask((__m512i)m);
#elif SB_X86_NATIVE && SB_W == 4
	return (unsigned)_mm256_movemask_pd((__m256d)m);
#elif SB_X86_NATIVE
	return (unsigned)_mm_movemask_pd((__m128d)m);
#else
	unsigned b = 0;
	for (int l = 0; l < SB_W; l++)
		b |= (unsigned)(m[l] & 1) << l;
	return b;
#endif
}

/* the bits of a < b, lane by lane (false for NaN): AVX-512 compares into a mask
 * register, where the vector form would be converted there and back */
SB_INLINE unsigned sb_lt(sb_vd a, sb_vd b)
{
#if SB_X86_NATIVE && SB_W == 8
	return _mm512_cmp_pd_mask((__m512d)a, (__m512d)b, _CMP_LT_OQ);
#else
	return sb_bits(a < b);
#endif
}

/* a * wa + b * wb where one of the two products is exact (x 1, -1 or 0) and so
 * the sum is rounded once either way: one fused multiply-add where the ISA has it
 * (x86-64-v3 and up), the same number (-ffp-contract=off forbids the compiler to
 * form it by itself) */
SB_INLINE sb_vd sb_mul2_exact(sb_vd a, sb_vd wa, sb_vd b, sb_vd wb)
{
#if SB_X86_NATIVE && SB_W == 8
	return (sb_vd)_mm512_fmadd_pd((__m512d)b, (__m512d)wb, (__m512d)(a * wa));
#elif SB_X86_NATIVE && SB_W == 4 && defined(__FMA__)
	return (sb_vd)_mm256_fmadd_pd((__m256d)b, (__m256d)wb, (__m256d)(a * wa));
#else
	return a * wa + b * wb;
#endif
}

/* the same of an int mask */
SB_INLINE unsigned sb_bitsi(sb_vi m)
{
#if SB_X86_NATIVE && SB_W == 8
	return (unsigned)_mm256_movemask_ps((__m256)m);
#elif SB_X86_NATIVE && SB_W == 4
	return (unsigned)_mm_movemask_ps((__m128)m);
#else
	unsigned b = 0;
	for (int l = 0; l < SB_W; l++)
		b |= (unsigned)(m[l] & 1) << l;
	return b;
#endif
}

/* The positions (0..7) of the set bits of a mask of at most 8 bits, in order, one per
 * byte from the lowest: BMI2's pdep and pext where the ISA has them (x86-64-v3 and
 * up), else a loop. */
SB_INLINE uint64_t sb_positions(unsigned bits)
{
#if defined(__BMI2__)
	const uint64_t bytes = _pdep_u64(bits, 0x0101010101010101ULL) * 0xFF;
	return _pext_u64(0x0706050403020100ULL, bytes);
#else
	uint64_t r = 0;
	int n = 0;
	for (int l = 0; l < SB_W; l++)
		if (bits >> l & 1)
			r |= (uint64_t)l << (8 * n++);
	return r;
#endif
}

/* the number of set bits of a mask of at most 8 bits (baseline x86-64 has no popcnt:
 * GCC would call libgcc) */
SB_INLINE int sb_count(unsigned bits)
{
#if defined(__POPCNT__) || defined(__aarch64__)
	return __builtin_popcount(bits);
#else
	bits = bits - (bits >> 1 & 0x55);
	bits = (bits & 0x33) + (bits >> 2 & 0x33);
	return (int)((bits + (bits >> 4)) & 0x0F);
#endif
}

/* Compressing lanes out of vectors: the lanes of the set bits of a mask, in order,
 * to dst[0..] (whole vectors are stored: dst has room for SB_W). sb_cmask holds what
 * one mask's compressions share (AVX2: the permutation; AVX-512: nothing, the
 * instruction takes the mask). */
#if SB_X86_NATIVE && SB_W == 4
/* the permutations of sb_cmask_of on AVX2, by mask: the positions of its set bits, in
 * order, as ints (pi) and as the int pairs of doubles (pd); the rest 0. SB_NTH(b, k): the
 * position of the k-th set bit of the 4-bit mask b (0 past the last) */
#define SB_POP3(x) (((x) & 1) + ((x) >> 1 & 1) + ((x) >> 2 & 1))
#define SB_NTH(b, k)                                                                                \
	(((b) & 1) && (k) == 0                          ? 0                                        \
	 : ((b) >> 1 & 1) && SB_POP3((b) & 1) == (k) ? 1                                        \
	 : ((b) >> 2 & 1) && SB_POP3((b) & 3) == (k) ? 2                                        \
	 : ((b) >> 3 & 1) && SB_POP3((b) & 7) == (k) ? 3                                        \
						       : 0)
#define SB_PI_ROW(b) {SB_NTH(b, 0), SB_NTH(b, 1), SB_NTH(b, 2), SB_NTH(b, 3), 0, 0, 0, 0}
#define SB_PD_ROW(b)                                                                                \
	{2 * SB_NTH(b, 0), 2 * SB_NTH(b, 0) + 1, 2 * SB_NTH(b, 1), 2 * SB_NTH(b, 1) + 1,            \
	 2 * SB_NTH(b, 2), 2 * SB_NTH(b, 2) + 1, 2 * SB_NTH(b, 3), 2 * SB_NTH(b, 3) + 1}
#define SB_ROWS16(R) {R(0), R(1), R(2), R(3), R(4), R(5), R(6), R(7), R(8), R(9), R(10), R(11), R(12), R(13), R(14), R(15)}
static const int SB_CPERM_PI[16][8] __attribute__((aligned(32))) = SB_ROWS16(SB_PI_ROW);
static const int SB_CPERM_PD[16][8] __attribute__((aligned(32))) = SB_ROWS16(SB_PD_ROW);
#endif

typedef struct sb_cmask {
	unsigned bits;
#if SB_X86_NATIVE && SB_W == 4
	__m256i pd, pi; /* the permutations of 4 doubles and of 4 ints as 8 ints */
#endif
} sb_cmask;

SB_INLINE sb_cmask sb_cmask_of(unsigned bits)
{
	sb_cmask c;
	c.bits = bits;
#if SB_X86_NATIVE && SB_W == 4
	c.pi = _mm256_load_si256((const __m256i *)SB_CPERM_PI[bits & 15]);
	c.pd = _mm256_load_si256((const __m256i *)SB_CPERM_PD[bits & 15]);
#endif
	return c;
}

SB_INLINE void sb_compressd(double *dst, sb_vd v, sb_cmask c)
{
#if SB_X86_NATIVE && SB_W == 8
	_mm512_storeu_pd(dst, _mm512_maskz_compress_pd((__mmask8)c.bits, (__m512d)v));
#elif SB_X86_NATIVE && SB_W == 4
	_mm256_storeu_pd(dst, _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps((__m256d)v), c.pd)));
#else
	int n = 0;
	for (int l = 0; l < SB_W; l++) {
		dst[n] = v[l];
		n += c.bits >> l & 1;
	}
#endif
}

SB_INLINE void sb_compressi(int *dst, sb_vi v, sb_cmask c)
{
#if SB_X86_NATIVE && SB_W == 8
	_mm256_storeu_si256((__m256i *)dst, _mm256_maskz_compress_epi32((__mmask8)c.bits, (__m256i)v));
#elif SB_X86_NATIVE && SB_W == 4
	const __m256i w = _mm256_castsi128_si256((__m128i)v);
	_mm_storeu_si128((__m128i *)dst, _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(w, c.pi)));
#else
	int n = 0;
	for (int l = 0; l < SB_W; l++) {
		dst[n] = v[l];
		n += c.bits >> l & 1;
	}
#endif
}

/* ---- transposes (__builtin_shuffle: each ISA gets its own shuffles) ---- */

/* r[0..W-1] transposed in place (lane l of r[k] <-> lane k of r[l]): log2(W) stages,
 * each swapping the off-diagonal sub-blocks of size s between rows k and k + s */
SB_INLINE void sb_transpose(sb_vd r[SB_W])
{
#if SB_W == 8
	/* pairs interleaved, then 128-bit blocks gathered twice: every shuffle of the last
	 * two stages takes whole 128-bit blocks, one instruction without an index vector
	 * on AVX-512 (vshuff64x2) */
	const sb_vl lo1 = {0, 8, 2, 10, 4, 12, 6, 14}, hi1 = {1, 9, 3, 11, 5, 13, 7, 15};
	const sb_vl ev = {0, 1, 4, 5, 8, 9, 12, 13}, od = {2, 3, 6, 7, 10, 11, 14, 15};
	sb_vd t[8], u[8];
	for (int k = 0; k < 8; k += 2) {
		t[k] = __builtin_shuffle(r[k], r[k + 1], lo1);
		t[k + 1] = __builtin_shuffle(r[k], r[k + 1], hi1);
	}
	for (int k = 0; k < 8; k += 4) {
		u[k] = __builtin_shuffle(t[k], t[k + 2], ev);
		u[k + 1] = __builtin_shuffle(t[k + 1], t[k + 3], ev);
		u[k + 2] = __builtin_shuffle(t[k], t[k + 2], od);
		u[k + 3] = __builtin_shuffle(t[k + 1], t[k + 3], od);
	}
	for (int k = 0; k < 4; k++) {
		r[k] = __builtin_shuffle(u[k], u[k + 4], ev);
		r[k + 4] = __builtin_shuffle(u[k], u[k + 4], od);
	}
#elif SB_W == 4
	const sb_vl lo1 = {0, 4, 2, 6}, hi1 = {1, 5, 3, 7}, lo2 = {0, 1, 4, 5}, hi2 = {2, 3, 6, 7};
	const sb_vd t0 = __builtin_shuffle(r[0], r[1], lo1), t1 = __builtin_shuffle(r[0], r[1], hi1),
		    t2 = __builtin_shuffle(r[2], r[3], lo1), t3 = __builtin_shuffle(r[2], r[3], hi1);
	r[0] = __builtin_shuffle(t0, t2, lo2);
	r[1] = __builtin_shuffle(t1, t3, lo2);
	r[2] = __builtin_shuffle(t0, t2, hi2);
	r[3] = __builtin_shuffle(t1, t3, hi2);
#else
	const sb_vl lo1 = {0, 2}, hi1 = {1, 3};
	const sb_vd t0 = __builtin_shuffle(r[0], r[1], lo1), t1 = __builtin_shuffle(r[0], r[1], hi1);
	r[0] = t0;
	r[1] = t1;
#endif
}

/* Fx, Fy and the torque of W disks from their accumulators (Fx, Fy, T, 0) at acc[4 k]:
 * a W x 4 transpose */
SB_INLINE void sb_load_acc(const double *acc, sb_vd *fx, sb_vd *fy, sb_vd *t)
{
#if SB_W == 8
	/* two disks a vector: (x0 y0 t0 0 x1 y1 t1 0) */
	sb_vd z[4];
	for (int k = 0; k < 4; k++)
		z[k] = sb_load(acc + 8 * k);
	const sb_vl ixy = {0, 4, 8, 12, 1, 5, 9, 13}, it = {2, 6, 10, 14, 2, 6, 10, 14},
		    lo = {0, 1, 2, 3, 8, 9, 10, 11}, hi = {4, 5, 6, 7, 12, 13, 14, 15};
	const sb_vd a = __builtin_shuffle(z[0], z[1], ixy), b = __builtin_shuffle(z[2], z[3], ixy);
	*fx = __builtin_shuffle(a, b, lo);
	*fy = __builtin_shuffle(a, b, hi);
	*t = __builtin_shuffle(__builtin_shuffle(z[0], z[1], it), __builtin_shuffle(z[2], z[3], it), lo);
#elif SB_W == 4
	sb_vd z[4];
	for (int k = 0; k < 4; k++)
		z[k] = sb_load(acc + 4 * k);
	sb_transpose(z);
	*fx = z[0];
	*fy = z[1];
	*t = z[2];
#else
	sb_vd a[2] = {sb_load(acc), sb_load(acc + 4)}, b[2] = {sb_load(acc + 2), sb_load(acc + 6)};
	sb_transpose(a);
	sb_transpose(b);
	*fx = a[0];
	*fy = a[1];
	*t = b[0];
#endif
}

#endif
