/* kvec.c - the force kernel, the fused corrector and the candidate scan, written once
 * over the vector layer (simd.h) and compiled once per instruction set (kvec.h; the
 * Makefile passes -march and SB_KV_NAME). docs/kernel.md tells the design; in short.
 * The kernel takes W pairs a vector (the native width: simd.h), first the listed pairs
 * to find those that touch, then the contacts. Every disk's
 * contact data are one 64-byte record (kvec.h), so a contact's data are two record loads
 * combined lane-wise (differences, sums, R_i, R_j); W contacts are transposed into
 * lanes, with the m_eff = 1 / (1/m_i + 1/m_j) of the list build. Each lane performs the scalar
 * law's operations in its order (forces.c, contact(): no FMA, min and max with the
 * ternaries' operand order, the sign copy exact), so the forces are the scalar law's
 * to the bit. The contacts are compressed out of the list into a chunk buffer; a
 * last pass adds their forces to per-disk accumulators in list order, one 4-double
 * vector per disk and contact - the order of the scalar sums, so the totals are bit-
 * identical too. Gathers are not used: on the AMD cores this was tuned on they cost
 * more than the loads and shuffles they would replace. */
#include "kvec.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "simd.h"

#ifndef SB_KV_NAME
#error "kvec.c is compiled per instruction set with -DSB_KV_NAME=<name> (Makefile)"
#endif
#define SB_STR_(x) #x
#define SB_STR(x) SB_STR_(x)
#define SB_CAT_(a, b) a##b
#define SB_CAT(a, b) SB_CAT_(a, b)
#define KV(name) SB_CAT(name##_, SB_KV_NAME)

/* ---- records ---- */

/* the records of W consecutive disks from vectors of their x, y, vx, vy, w, R, 1/m;
 * only the first count are stored (the walls' records follow the mobile disks'):
 * per W fields, a W x W transpose gives those fields of each of the W records */
SB_INLINE void rec_store(double *rec, sb_vd x, sb_vd y, sb_vd vx, sb_vd vy, sb_vd w, sb_vd R, sb_vd im,
			 const int count)
{
	sb_vd row[8] = {x, y, vx, vy, R * w, im, R, R};
	for (int h = 0; h < 8; h += SB_W) {
		sb_transpose(row + h);
		for (int k = 0; k < count; k++)
			sb_store(rec + 8 * k + h, row[h + k]);
	}
}

/* x, y, vx, vy of W consecutive disks from their records: the first halves of the
 * records only (with eight lanes, records k and k + 4 share a vector) */
SB_INLINE void rec_load(const double *rec, sb_vd *x, sb_vd *y, sb_vd *vx, sb_vd *vy)
{
#if SB_W == 8
	const sb_vl cat = {0, 1, 2, 3, 8, 9, 10, 11}, lo = {0, 8, 2, 10, 4, 12, 6, 14},
		    hi = {1, 9, 3, 11, 5, 13, 7, 15}, lo2 = {0, 1, 8, 9, 4, 5, 12, 13},
		    hi2 = {2, 3, 10, 11, 6, 7, 14, 15};
	sb_vd z[4];
	for (int k = 0; k < 4; k++) /* (x y vx vy) of disk k | of disk k + 4 */
		z[k] = __builtin_shuffle(sb_load(rec + 8 * k), sb_load(rec + 8 * (k + 4)), cat);
	/* t0 = (x0 x1 vx0 vx1 | x4 x5 vx4 vx5), t1 the same of y, t2, t3 of disks 2, 3 | 6, 7 */
	const sb_vd t0 = __builtin_shuffle(z[0], z[1], lo), t1 = __builtin_shuffle(z[0], z[1], hi),
		    t2 = __builtin_shuffle(z[2], z[3], lo), t3 = __builtin_shuffle(z[2], z[3], hi);
	/* (x0 x1 x2 x3 | x4 x5 x6 x7) */
	*x = __builtin_shuffle(t0, t2, lo2);
	*vx = __builtin_shuffle(t0, t2, hi2);
	*y = __builtin_shuffle(t1, t3, lo2);
	*vy = __builtin_shuffle(t1, t3, hi2);
#else
	sb_vd f[4];
	for (int h = 0; h < 4; h += SB_W) {
		for (int k = 0; k < SB_W; k++)
			f[h + k] = sb_load(rec + 8 * k + h);
		sb_transpose(f + h);
	}
	*x = f[0];
	*y = f[1];
	*vx = f[2];
	*vy = f[3];
#endif
}

/* the records of disks [i0, n) */
static void pack_records(const sb_state *st, double *restrict rec, int i0, int n)
{
	const double *x = st->q[C_X][0], *y = st->q[C_Y][0], *vx = st->q[C_X][1], *vy = st->q[C_Y][1],
		     *w = st->q[C_TH][1], *r = st->r, *im = st->inv_m;
	int i = i0;
	for (; i + SB_W <= n; i += SB_W)
		rec_store(rec + 8 * i, sb_load(x + i), sb_load(y + i), sb_load(vx + i), sb_load(vy + i),
			  sb_load(w + i), sb_load(r + i), sb_load(im + i), SB_W);
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

/* the per-disk accumulators (Fx, Fy, torque, 0) -> st->f */
static void unpack_forces(sb_state *st, const double *restrict facc)
{
	double *restrict fx = st->f[C_X], *restrict fy = st->f[C_Y], *restrict t = st->f[C_TH];
	const int n = st->n;
	int i = 0;
	for (; i + SB_W <= n; i += SB_W) {
		sb_vd a, b, c;
		sb_load_acc(facc + 4 * i, &a, &b, &c);
		sb_store(fx + i, a);
		sb_store(fy + i, b);
		sb_store(t + i, c);
	}
	for (; i < n; i++) {
		fx[i] = facc[4 * i];
		fy[i] = facc[4 * i + 1];
		t[i] = facc[4 * i + 2];
	}
}

static void to_state(const sb_kdata *d, sb_state *st)
{
	double *restrict x = st->q[C_X][0], *restrict y = st->q[C_Y][0], *restrict vx = st->q[C_X][1],
		       *restrict vy = st->q[C_Y][1];
	const double *rec = d->rec;
	const int n = st->nm;
	int i = 0;
	for (; i + SB_W <= n; i += SB_W) {
		sb_vd a, b, c, e;
		rec_load(rec + 8 * i, &a, &b, &c, &e);
		sb_store(x + i, a);
		sb_store(y + i, b);
		sb_store(vx + i, c);
		sb_store(vy + i, e);
	}
	for (; i < n; i++) {
		x[i] = rec[8 * i];
		y[i] = rec[8 * i + 1];
		vx[i] = rec[8 * i + 2];
		vy[i] = rec[8 * i + 3];
	}
}

/* ---- the force kernel ---- */

/* The lane-wise combination of W fields from h of a pair's records a (of i) and b (of
 * j): x, y, vx, vy of i minus j (fields 0-3), R w and 1/m of i plus j (4, 5), R_i (6),
 * R_j (7). Where a vector holds fields of one kind that is one operation; else
 * a wa + b wb, whose products are exact (x 1, -1, 0), so that its one rounding is
 * that of a - b or a + b, and R_i + 0, 0 + R_j are R_i, R_j: the same numbers. */
SB_INLINE sb_vd rec_pair(sb_vd a, sb_vd b, const int h, sb_vd wa, sb_vd wb)
{
	if (h + SB_W <= 4)
		return a - b;
#if SB_W < 8
	(void)wa;
	(void)wb;
#endif
#if SB_W == 2
	if (h == 4)
		return a + b;
	return __builtin_shuffle(a, b, (sb_vl){0, 3});
#elif SB_W == 4
	return __builtin_shuffle(a + b, __builtin_shuffle(a, b, (sb_vl){0, 0, 2, 7}), (sb_vl){0, 1, 6, 7});
#else
	return sb_mul2_exact(a, wa, b, wb);
#endif
}

/* x and y of W listed pairs' first disks minus their second disks', from the first two
 * doubles of their records (one 16-byte load each): the even pairs' differences into a,
 * the odd pairs' into b, (dx, dy) side by side, then one in-lane interleave each
 * (unpcklpd, unpckhpd) */
typedef double sb_v2 __attribute__((vector_size(16)));
SB_INLINE sb_v2 rec_xy(const double *r)
{
	sb_v2 v;
	memcpy(&v, r, sizeof v);
	return v;
}

/* the (x, y) of the records at rec + o[0], rec + o[2], ... (every second offset) side by side */
SB_INLINE sb_vd xy_every2(const double *rec, const int *o)
{
#if SB_W == 8
	const sb_v4 lo = __builtin_shufflevector(rec_xy(rec + o[0]), rec_xy(rec + o[2]), 0, 1, 2, 3),
		    hi = __builtin_shufflevector(rec_xy(rec + o[4]), rec_xy(rec + o[6]), 0, 1, 2, 3);
	return __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
#elif SB_W == 4
	return __builtin_shufflevector(rec_xy(rec + o[0]), rec_xy(rec + o[2]), 0, 1, 2, 3);
#else
	return rec_xy(rec + o[0]);
#endif
}

SB_INLINE void pair_dxy(const double *rec, const int *pi, const int *pj, sb_vd *dx, sb_vd *dy)
{
	const sb_vd a = xy_every2(rec, pi) - xy_every2(rec, pj), b = xy_every2(rec, pi + 1) - xy_every2(rec, pj + 1);
#if SB_W == 8
	*dx = __builtin_shuffle(a, b, (sb_vl){0, 8, 2, 10, 4, 12, 6, 14});
	*dy = __builtin_shuffle(a, b, (sb_vl){1, 9, 3, 11, 5, 13, 7, 15});
#elif SB_W == 4
	*dx = __builtin_shuffle(a, b, (sb_vl){0, 4, 2, 6});
	*dy = __builtin_shuffle(a, b, (sb_vl){1, 5, 3, 7});
#else
	*dx = __builtin_shuffle(a, b, (sb_vl){0, 2});
	*dy = __builtin_shuffle(a, b, (sb_vl){1, 3});
#endif
}

/* Two passes per chunk of the list. The first keeps the pairs that touch: x and y of
 * the two records and R_i + R_j of the pair (sb_kdata), the law's own test in its
 * order, and compresses the touching pairs' disks and m_eff into the chunk buffer, in
 * list order. About half the listed pairs touch (a dense bed at the paper's skin), so
 * the second pass runs the law with every lane a contact, and none of the square roots
 * and divisions of pairs that do not touch. (docs/kernel.md, "Speed") */
SB_INLINE int kernel(sb_kdata *kd, const sb_law *law, sb_state *st, const sb_nlist *nl, double inv_dt,
		     const int clip, const int resti, const int hertz, double *restrict fsum, const int packed,
		     const int keep, const int pf, const int table, const int spring)
{
	const double *rec = kd->rec, *pm = kd->pm, *prs = kd->prs;
	const int *pi = nl->pi, *pj = nl->pj;
	sb_kbuf *restrict kb = kd->kb;
	const int np = nl->nflat;
	/* resti: the normal damping gz sqrt(m_eff) (forces.h), else gamma_N m_eff */
	/* table: each contact's own, from the list build (sb_kdata's pc) */
	const sb_vd Y0 = sb_splat(law->Y), gn0 = sb_splat((resti ? law->gz : law->gn) * inv_dt),
		    gs0 = sb_splat(law->gs * inv_dt), mu0 = sb_splat(law->mu), mo = sb_splat(law->max_overlap),
		    kt0 = sb_splat(law->kt), one = sb_splat(1.0), zero = sb_splat(0.0);
	/* spring: the shear displacements of this build's pairs, and lane l's offset l */
	double *restrict shx = kd->shx;
	sb_vi iota;
	for (int l = 0; l < SB_W; l++)
		iota[l] = l;
	/* the weights of rec_pair's general form */
	const double wa[8] = {1, 1, 1, 1, 1, 1, 1, 0}, wb[8] = {-1, -1, -1, -1, 1, 1, 0, 1};
	double *restrict facc = kd->facc;
	/* packed: the fused corrector of the last step wrote the mobile disks' records
	 * and cleared their accumulators */
	if (!packed) {
		memset(facc, 0, sizeof(double) * 4 * (size_t)st->nm);
		pack_records(st, kd->rec, 0, st->nm);
	}
	memset(facc + 4 * (size_t)st->nm, 0, sizeof(double) * 4 * (size_t)(st->n - st->nm));
	/* the walls' records change only when the list is rebuilt from a new state */
	if (kd->walls_packed != nl->builds) {
		pack_records(st, kd->rec, st->nm, st->n);
		kd->walls_packed = nl->builds;
	}

	unsigned bad = 0;
	for (int p0 = 0; p0 < np; p0 += SB_KCHUNK) {
		const int p1 = p0 + SB_KCHUNK < np ? p0 + SB_KCHUNK : np;
		int nc = 0;
		/* pass 1: the pairs that touch (the list is padded with pairs (0, 0) to whole
		 * vectors: nlist.h) */
		for (int p = p0; p < p1; p += SB_W) {
			if (pf) /* constant per instantiation */
				for (int l = 0; l < SB_W; l++) {
					/* the far ends of the pairs 64 ahead: beyond the cache, their
					 * records are the kernel's latency-bound loads */
					const int q = p + 64 + l < np ? p + 64 + l : p;
					__builtin_prefetch(rec + pj[q]);
				}
			sb_vd dx, dy;
			pair_dxy(rec, pi + p, pj + p, &dx, &dy);
			const sb_vd rs = sb_load(prs + p);
			/* masks become bits at once: combining them as vectors costs a
			 * conversion per operation where the ISA has no 64-bit compares */
			const unsigned live = p1 - p >= SB_W ? (1u << SB_W) - 1 : (1u << (p1 - p)) - 1;
			const unsigned bits = sb_lt(dx * dx + dy * dy, rs * rs) & live;
			if (!bits)
				continue;
			/* whole-vector stores: the slots past the contacts are overwritten by the
			 * next block */
			const sb_cmask cm = sb_cmask_of(bits);
			sb_compressi(kb->i + nc, sb_loadi(pi + p), cm);
			sb_compressi(kb->j + nc, sb_loadi(pj + p), cm);
			sb_compressd(kb->m + nc, sb_load(pm + p), cm);
			if (table) /* constant per instantiation; k_t only for the spring */
				for (int c = 0; c < 4 + spring; c++)
					sb_compressd(kb->c[c] + nc, sb_load(kd->pc[c] + p), cm);
			if (spring) { /* constant per instantiation */
				sb_compressd(kb->h + nc, sb_loadn(shx + p, p1 - p < SB_W ? p1 - p : SB_W), cm);
				sb_compressi(kb->p + nc, p + iota, cm);
			}
			nc += sb_count(bits);
		}
		/* a pair not in contact loses its history (docs/model.md, "Tangential law");
		 * the contacts get theirs back from the second pass */
		if (spring)
			memset(shx + p0, 0, sizeof(double) * (size_t)(p1 - p0));
		/* the lanes past the last contact read disk 0's record; their numbers are
		 * never used */
		for (int l = 0; l < SB_W; l++) {
			kb->i[nc + l] = kb->j[nc + l] = 0;
			kb->m[nc + l] = 1;
			if (spring)
				kb->h[nc + l] = 0;
			for (int c = 0; c < 4 + spring && table; c++)
				kb->c[c][nc + l] = 0;
		}
		/* pass 2: contact(), operation by operation, W contacts a vector */
		for (int k = 0; k < nc; k += SB_W) {
			/* per pair, lane-wise from the two records: x, y, vx, vy of i minus j;
			 * R w and 1/m of i plus j; R_i; R_j. Then, W fields at a time, pairs ->
			 * lanes. */
			sb_vd t[8];
			for (int h = 0; h < 8; h += SB_W) {
				const sb_vd ka = sb_load(wa + h), kb_ = sb_load(wb + h);
				for (int l = 0; l < SB_W; l++)
					t[h + l] = rec_pair(sb_load(rec + kb->i[k + l] + h), sb_load(rec + kb->j[k + l] + h), h, ka,
							    kb_);
				sb_transpose(t + h);
			}
			const sb_vd dx = t[0], dy = t[1], dvx = t[2], dvy = t[3], rw = t[4], ri = t[6], rj = t[7],
				    rs = ri + rj;
			const unsigned live = nc - k >= SB_W ? (1u << SB_W) - 1 : (1u << (nc - k)) - 1;
			const sb_vd Y = table ? sb_load(kb->c[0] + k) : Y0, gn = table ? sb_load(kb->c[1] + k) : gn0,
				    gs = table ? sb_load(kb->c[2] + k) : gs0, mu = table ? sb_load(kb->c[3] + k) : mu0;
			const sb_vd d2 = dx * dx + dy * dy;
			const sb_vd d = sb_sqrt(d2);
			const sb_vd inv = one / d;
			const sb_vd nx = dx * inv, ny = dy * inv;
			const sb_vd xi = rs - d;
			/* -xidot; a + k (-s) is a - k s to the bit */
			const sb_vd mxidot = dvx * nx + dvy * ny;
			const sb_vd meff = sb_load(kb->m + k); /* 1 / (1/m_i + 1/m_j) */
			const sb_vd damp = resti ? gn * sb_sqrt(meff) : gn * meff; /* constant per instantiation */
			sb_vd fn = Y * xi - damp * mxidot;
			/* hertz: times sqrt(xi R_eff) */
			const sb_vd ph = hertz ? sb_sqrt(xi * (ri * rj / rs)) : one;
			if (hertz) /* constant per instantiation */
				fn = ph * fn;
			if (clip) /* fn > 0 ? fn : 0 */
				fn = sb_max(fn, zero);
			const sb_vd vt = (dvy * nx - dvx * ny) - rw;
			sb_vd fs;
			if (spring) { /* constant per instantiation: forces.c, contact_spring, lane by lane */
				const sb_vd s = sb_load(kb->h + k) + vt, damps = gs * meff * vt,
					    kt = table ? sb_load(kb->c[4] + k) : kt0;
				fs = sb_neg(kt * s + damps);
				if (hertz)
					fs = ph * fs;
				const sb_vd fc = mu * sb_abs(fn);
				const sb_vl cap = fc < sb_abs(fs);
				sb_vd sn = s;
				if (sb_bits(cap) & live) { /* sliding: the spring stretched only as far as Coulomb allows */
					const sb_vd q = damps / kt, r = fc / sb_abs(fs);
					const sb_vl nz = s != zero;
					sn = sb_sel(cap & nz, r * (s + q) - q, s);
					fs = sb_sel(cap & nz, fs * r, sb_sel(cap, zero, fs));
				}
				sb_store(kb->h + k, sn);
			} else {
				sb_vd fv = gs * meff * sb_abs(vt);
				if (hertz)
					fv = ph * fv;
				const sb_vd fc = mu * sb_abs(fn);
				fs = sb_copysign_neg(sb_min(fv, fc), vt); /* copysign(fv < fc ? fv : fc, -vt) */
			}
			bad |= sb_lt(mo * sb_min(ri, rj), xi) & live;
			sb_store(kb->fx + k, fn * nx - fs * ny);
			sb_store(kb->fy + k, fn * ny + fs * nx);
			sb_store(kb->ti + k, sb_neg(ri * fs));
			sb_store(kb->tj + k, rj * fs);
		}
		/* the chunk's forces added to the disks in list order, as 4-double vectors:
		 * (Fx, Fy, -R_i F_S, 0) added to i's, (Fx, Fy, R_j F_S, 0) subtracted from j's
		 * (a - b and a + (-b) are the same number) */
		char *const acc = (char *)facc;
		for (int k = 0; k < nc; k++) {
			/* 8 i, 8 j (SB_KSHIFT): disk i's accumulator is 32 i = 4 (8 i) bytes in */
			const ptrdiff_t i8 = kb->i[k], j8 = kb->j[k];
			double *const ai = (double *)(acc + 4 * i8), *const aj = (double *)(acc + 4 * j8);
			const double fx = kb->fx[k], fy = kb->fy[k];
			if (fsum) { /* constant per instantiation: compiled away when NULL */
				const double fa = sqrt(fx * fx + fy * fy);
				fsum[i8 / 8] += fa;
				fsum[j8 / 8] += fa;
			}
			if (spring) /* constant per instantiation */
				shx[kb->p[k]] = kb->h[k];
			const sb_v4 vi = {fx, fy, kb->ti[k], 0}, vj = {fx, fy, kb->tj[k], 0};
			sb_v4 a, b;
			memcpy(&a, ai, sizeof a);
			a += vi;
			memcpy(ai, &a, sizeof a);
			memcpy(&b, aj, sizeof b);
			b -= vj;
			memcpy(aj, &b, sizeof b);
		}
	}
	if (!keep) /* else the fused corrector reads the accumulators */
		unpack_forces(st, facc);
	return bad != 0;
}

/* one instantiation per normal law, clip_attractive, normal damping (gamma_N or
 * restitution) and prefetching: the law is chosen at set-up, not in the loop
 * (docs/kernel.md) */
typedef int (*kernel_fn)(sb_kdata *, const sb_law *, sb_state *, const sb_nlist *, double, int, int);
#define INSTANCE_T(name, hertz, clip, resti, pf, table, spring)                                            \
	static int name(sb_kdata *d, const sb_law *l, sb_state *s, const sb_nlist *n, double inv_dt,      \
			int packed, int keep)                                                              \
	{                                                                                                  \
		return kernel(d, l, s, n, inv_dt, clip, resti, hertz, NULL, packed, keep, pf, table, spring); \
	}
#define INSTANCE(name, hertz, clip, resti, pf) INSTANCE_T(name, hertz, clip, resti, pf, 0, 0)
/* the shear spring's take the ring's sums at run time (a branch per contact, taken the same
 * way all along): one instance for both, where the others have kernel_track's */
typedef int (*kernel_fs_fn)(sb_kdata *, const sb_law *, sb_state *, const sb_nlist *, double, int, int, double *);
#define INSTANCE_ST(name, hertz, clip, resti, pf, table)                                                   \
	static int name(sb_kdata *d, const sb_law *l, sb_state *s, const sb_nlist *n, double inv_dt,      \
			int packed, int keep, double *fsum)                                                \
	{                                                                                                  \
		return kernel(d, l, s, n, inv_dt, clip, resti, hertz, fsum, packed, keep, pf, table, 1);   \
	}
#define INSTANCE_S(name, hertz, clip, resti, pf) INSTANCE_ST(name, hertz, clip, resti, pf, 0)
INSTANCE(kernel_plain, 0, 0, 0, 0)
INSTANCE(kernel_clip, 0, 1, 0, 0)
INSTANCE(kernel_plain_pf, 0, 0, 0, 1)
INSTANCE(kernel_clip_pf, 0, 1, 0, 1)
INSTANCE(kernel_plain_e, 0, 0, 1, 0)
INSTANCE(kernel_clip_e, 0, 1, 1, 0)
INSTANCE(kernel_plain_e_pf, 0, 0, 1, 1)
INSTANCE(kernel_clip_e_pf, 0, 1, 1, 1)
/* hertz with gamma_N only (restitution is for hooke: validate.c) */
INSTANCE(kernel_hz, 1, 0, 0, 0)
INSTANCE(kernel_hz_clip, 1, 1, 0, 0)
INSTANCE(kernel_hz_pf, 1, 0, 0, 1)
INSTANCE(kernel_hz_clip_pf, 1, 1, 0, 1)
/* a table of materials: the coefficients per contact; without prefetching (a mixture's
 * bed large enough to want it runs these at the cost of the far ends' loads) */
INSTANCE_T(kernel_tab, 0, 0, 0, 0, 1, 0)
INSTANCE_T(kernel_tab_clip, 0, 1, 0, 0, 1, 0)
INSTANCE_T(kernel_tab_e, 0, 0, 1, 0, 1, 0)
INSTANCE_T(kernel_tab_clip_e, 0, 1, 1, 0, 1, 0)
INSTANCE_T(kernel_tab_hz, 1, 0, 0, 0, 1, 0)
INSTANCE_T(kernel_tab_hz_clip, 1, 1, 0, 0, 1, 0)
/* tangential = spring (the shear displacement per contact in sb_kdata's shx) */
INSTANCE_S(kernel_spr, 0, 0, 0, 0)
INSTANCE_S(kernel_spr_clip, 0, 1, 0, 0)
INSTANCE_S(kernel_spr_pf, 0, 0, 0, 1)
INSTANCE_S(kernel_spr_clip_pf, 0, 1, 0, 1)
INSTANCE_S(kernel_spr_e, 0, 0, 1, 0)
INSTANCE_S(kernel_spr_clip_e, 0, 1, 1, 0)
INSTANCE_S(kernel_spr_e_pf, 0, 0, 1, 1)
INSTANCE_S(kernel_spr_clip_e_pf, 0, 1, 1, 1)
INSTANCE_S(kernel_spr_hz, 1, 0, 0, 0)
INSTANCE_S(kernel_spr_hz_clip, 1, 1, 0, 0)
INSTANCE_S(kernel_spr_hz_pf, 1, 0, 0, 1)
INSTANCE_S(kernel_spr_hz_clip_pf, 1, 1, 0, 1)
INSTANCE_ST(kernel_tab_spr, 0, 0, 0, 0, 1)
INSTANCE_ST(kernel_tab_spr_clip, 0, 1, 0, 0, 1)
INSTANCE_ST(kernel_tab_spr_e, 0, 0, 1, 0, 1)
INSTANCE_ST(kernel_tab_spr_clip_e, 0, 1, 1, 0, 1)
INSTANCE_ST(kernel_tab_spr_hz, 1, 0, 0, 0, 1)
INSTANCE_ST(kernel_tab_spr_hz_clip, 1, 1, 0, 0, 1)
#undef INSTANCE
#undef INSTANCE_S
#undef INSTANCE_ST
#undef INSTANCE_T
/* [hertz ? 2 : resti][prefetch][clip] */
static const kernel_fn KERNELS[3][2][2] = {{{kernel_plain, kernel_clip}, {kernel_plain_pf, kernel_clip_pf}},
					   {{kernel_plain_e, kernel_clip_e}, {kernel_plain_e_pf, kernel_clip_e_pf}},
					   {{kernel_hz, kernel_hz_clip}, {kernel_hz_pf, kernel_hz_clip_pf}}};
/* the same, the shear spring's, and a table's with it ([hertz ? 2 : resti][clip]) */
static const kernel_fs_fn KERNELS_TAB_SPR[3][2] = {{kernel_tab_spr, kernel_tab_spr_clip},
						{kernel_tab_spr_e, kernel_tab_spr_clip_e},
						{kernel_tab_spr_hz, kernel_tab_spr_hz_clip}};
static const kernel_fs_fn KERNELS_SPR[3][2][2] = {
	{{kernel_spr, kernel_spr_clip}, {kernel_spr_pf, kernel_spr_clip_pf}},
	{{kernel_spr_e, kernel_spr_clip_e}, {kernel_spr_e_pf, kernel_spr_clip_e_pf}},
	{{kernel_spr_hz, kernel_spr_hz_clip}, {kernel_spr_hz_pf, kernel_spr_hz_clip_pf}}};
/* [hertz ? 2 : resti][clip], a table's */
static const kernel_fn KERNELS_TAB[3][2] = {
	{kernel_tab, kernel_tab_clip}, {kernel_tab_e, kernel_tab_clip_e}, {kernel_tab_hz, kernel_tab_hz_clip}};

/* the ring's kernel, compiled apart so that it costs nothing when off; table: a
 * table of materials' instance (tb is constant in each call below) */
SB_INLINE int kernel_track_law(sb_kdata *d, const sb_law *l, sb_state *s, const sb_nlist *n, double inv_dt,
				double *fsum, const int tb)
{
	if (l->hertz)
		return l->clip ? kernel(d, l, s, n, inv_dt, 1, 0, 1, fsum, 0, 0, 0, tb, 0) : kernel(d, l, s, n, inv_dt, 0, 0, 1, fsum, 0, 0, 0, tb, 0);
	if (l->resti)
		return l->clip ? kernel(d, l, s, n, inv_dt, 1, 1, 0, fsum, 0, 0, 0, tb, 0) : kernel(d, l, s, n, inv_dt, 0, 1, 0, fsum, 0, 0, 0, tb, 0);
	return l->clip ? kernel(d, l, s, n, inv_dt, 1, 0, 0, fsum, 0, 0, 0, tb, 0) : kernel(d, l, s, n, inv_dt, 0, 0, 0, fsum, 0, 0, 0, tb, 0);
}

static __attribute__((noinline)) int kernel_track(sb_kdata *d, const sb_law *l, sb_state *s, const sb_nlist *n,
						  double inv_dt, double *fsum)
{
	return l->table ? kernel_track_law(d, l, s, n, inv_dt, fsum, 1) : kernel_track_law(d, l, s, n, inv_dt, fsum, 0);
}

static int forces(sb_kdata *d, const sb_law *law, sb_state *st, const sb_nlist *nl, double inv_dt, int keep,
		  int packed, double *fsum)
{
	if (law->spring) { /* the ring's sums, as kernel_track's: from st, into st->f */
		if (fsum)
			packed = keep = 0;
		if (law->table)
			return KERNELS_TAB_SPR[law->hertz ? 2 : law->resti != 0][law->clip != 0](d, law, st, nl, inv_dt, packed,
												   keep, fsum);
		return KERNELS_SPR[law->hertz ? 2 : law->resti != 0][d->prefetch != 0][law->clip != 0](d, law, st, nl, inv_dt,
												  packed, keep, fsum);
	}
	if (fsum)
		return kernel_track(d, law, st, nl, inv_dt, fsum);
	if (law->table)
		return KERNELS_TAB[law->hertz ? 2 : law->resti != 0][law->clip != 0](d, law, st, nl, inv_dt, packed, keep);
	return KERNELS[law->hertz ? 2 : law->resti != 0][d->prefetch != 0][law->clip != 0](d, law, st, nl, inv_dt, packed,
											       keep);
}

/* ---- the fused corrector ---- */

/* one coordinate's Nordsieck arrays; restrict: the stores into one never change
 * another, nor the pointers (else each store reloads all of them) */
typedef struct qarr {
	double *restrict q0, *restrict q1, *restrict q2, *restrict q3, *restrict q4, *restrict q5;
} qarr;

SB_INLINE qarr qarr_of(const sb_state *st, int c)
{
	return (qarr){st->q[c][0], st->q[c][1], st->q[c][2], st->q[c][3], st->q[c][4], st->q[c][5]};
}

/* One coordinate of W disks from i (integ_correct_predict's operations, element
 * by element). soa01: q0 and q1 are read from and written to the arrays, and *q0, *q1
 * get the predicted ones; else *q0, *q1 are the current ones in and the predicted
 * ones out, the arrays untouched (x and y: the records hold them). */
SB_INLINE void cp_block(const int nval, const double *c, double h, sb_vd f, sb_vd inv, double extra, qarr q,
			int i, const int n, const int soa01, sb_vd *q0, sb_vd *q1)
{
	const sb_vd a2 = (f * inv + extra) * h;
	const sb_vd c0 = soa01 ? sb_loadn(q.q0 + i, n) : *q0, c1 = soa01 ? sb_loadn(q.q1 + i, n) : *q1;
	if (nval == 6) {
		const sb_vd d = a2 - sb_loadn(q.q2 + i, n);
		const sb_vd b0 = c0 + c[0] * d, a1 = c1 + c[1] * d, a3 = sb_loadn(q.q3 + i, n) + c[3] * d,
			    a4 = sb_loadn(q.q4 + i, n) + c[4] * d, a5 = sb_loadn(q.q5 + i, n) + c[5] * d;
		*q0 = b0 + (a1 + a2 + a3 + a4 + a5);
		*q1 = a1 + 2 * a2 + 3 * a3 + 4 * a4 + 5 * a5;
		sb_storen(q.q2 + i, a2 + 3 * a3 + 6 * a4 + 10 * a5, n);
		sb_storen(q.q3 + i, a3 + 4 * a4 + 10 * a5, n);
		sb_storen(q.q4 + i, a4 + 5 * a5, n);
		sb_storen(q.q5 + i, a5, n);
	} else if (nval == 5) {
		const sb_vd d = a2 - sb_loadn(q.q2 + i, n);
		const sb_vd b0 = c0 + c[0] * d, a1 = c1 + c[1] * d, a3 = sb_loadn(q.q3 + i, n) + c[3] * d,
			    a4 = sb_loadn(q.q4 + i, n) + c[4] * d;
		*q0 = b0 + (a1 + a2 + a3 + a4);
		*q1 = a1 + 2 * a2 + 3 * a3 + 4 * a4;
		sb_storen(q.q2 + i, a2 + 3 * a3 + 6 * a4, n);
		sb_storen(q.q3 + i, a3 + 4 * a4, n);
		sb_storen(q.q4 + i, a4, n);
	} else {
		const sb_vd v = c1 + a2;
		*q1 = v + a2;
		*q0 = c0 + (v + a2);
		sb_storen(q.q2 + i, a2, n);
	}
	if (soa01) {
		sb_storen(q.q0 + i, *q0, n);
		sb_storen(q.q1 + i, *q1, n);
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
	unsigned rebuild, bad, out;
} cpa_flags;

SB_INLINE void cpa_block(const int nval, const cpa_args *a, int i, const int count, cpa_flags *fl)
{
	sb_vd fx, fy, ft, x0, x1, y0, y1, t0, t1;
	sb_load_acc(a->facc + 4 * i, &fx, &fy, &ft);
	/* the next kernel adds into them; beyond count are walls, which it clears */
	for (int k = 0; k < 4; k++) /* stores, not memset: a call or rep stos per block */
		sb_store(a->facc + 4 * i + SB_W * k, sb_splat(0));
	/* x, y and their velocities live in the records between fused passes: the kernel
	 * of this step read them there, and this pass writes them only there - four
	 * arrays fewer to stream. kernel_sync() brings st up to date for everyone else. */
	rec_load(a->rec + 8 * i, &x0, &y0, &x1, &y1);
	const sb_vd im = sb_loadn(a->inv_m + i, count), R = sb_loadn(a->r + i, count);
	cp_block(nval, a->c, a->h, fx, im, 0, a->x, i, count, 0, &x0, &x1);
	cp_block(nval, a->c, a->h, fy, im, a->gy, a->y, i, count, 0, &y0, &y1);
	cp_block(nval, a->c, a->h, ft, sb_loadn(a->inv_i + i, count), 0, a->t, i, count, 1, &t0, &t1);
	rec_store(a->rec + 8 * i, x0, y0, x1, y1, t1, R, im, count);
	/* the step's check of the state (step.c, check_state), operation by operation */
	const sb_vd dx = x0 - sb_loadn(a->xref + i, count), dy = y0 - sb_loadn(a->yref + i, count);
	const sb_vd d2 = dx * dx + dy * dy;
	const unsigned live = (1u << count) - 1;
	fl->rebuild |= sb_lt(sb_splat(a->lim), d2) & live;
	fl->bad |= ~sb_lt(d2 + sb_abs(t0), sb_splat(INFINITY)) & live;
	fl->out |= (sb_lt(x0, sb_splat(a->xlo)) | sb_lt(sb_splat(a->xhi), x0) | sb_lt(y0, sb_splat(a->ylo))) & live;
}

SB_INLINE void cpa(sb_kdata *d, const int nval, const sb_integ *in, sb_state *st, double gy, const sb_nlist *nl,
		   sb_screen *scr)
{
	cpa_args a = {qarr_of(st, C_X), qarr_of(st, C_Y), qarr_of(st, C_TH), st->inv_m, st->inv_i,
		      st->r, nl->xref, nl->yref, d->facc, d->rec, {0}, in->half_dt2, gy,
		      scr->lim, scr->xlo, scr->xhi, scr->ylo};
	for (int o = 0; o < SB_MAXORDER; o++)
		a.c[o] = in->c[o];
	cpa_flags fl = {0, 0, 0};
	const int n = st->nm;
	int i = 0;
	for (; i + SB_W <= n; i += SB_W)
		cpa_block(nval, &a, i, SB_W, &fl);
	if (i < n)
		cpa_block(nval, &a, i, n - i, &fl);
	scr->done = 1;
	scr->rebuild = fl.rebuild != 0;
	scr->bad = fl.bad != 0;
	scr->out = fl.out != 0;
}

/* AVX-512 at its native width keeps an intrinsics form of cpa, for speed only
 * (kvec_cp512.h says by how much and why) */
#if SB_X86_NATIVE && SB_W == 8 && !defined(SB_NO_CP512)
#include "kvec_cp512.h"
#define CPA cpa512
#else
#define CPA cpa
#endif

static void correct_predict(sb_kdata *d, const sb_integ *in, sb_state *st, double gy, const sb_nlist *nl,
			    sb_screen *scr)
{
	if (in->nval == 6)
		CPA(d, 6, in, st, gy, nl, scr);
	else if (in->nval == 5)
		CPA(d, 5, in, st, gy, nl, scr);
	else
		CPA(d, 3, in, st, gy, nl, scr);
}

/* ---- the candidate scan ---- */

/* Appends to the list the candidates k0..k1 (cell order) of disk i within reach ri
 * (nlist.c tells the rest): W at a time, the kept ones in order. */
static int scan(sb_nlist *nl, int i, double xi, double yi, double ri, int k0, int k1, int np)
{
	int *restrict pj = nl->pj, *restrict pi = nl->pi;
	const int *restrict idx = nl->cell_idx;
	const int sh = nl->pshift, i8 = i << sh;
	const sb_vd X = sb_splat(xi), Yv = sb_splat(yi), R = sb_splat(ri);
	for (int k = k0; k < k1; k += SB_W) {
		const unsigned live = k1 - k >= SB_W ? (1u << SB_W) - 1 : (1u << (k1 - k)) - 1;
		/* xs, ys, rs have spare slots past the last disk: whole vectors */
		const sb_vd dx = X - sb_load(nl->xs + k), dy = Yv - sb_load(nl->ys + k), rc = R + sb_load(nl->rs + k);
		const sb_vi j = sb_loadi(idx + k);
		/* j > i keeps each pair once (walls sit above the mobile disks) */
		const unsigned bits = sb_lt(dx * dx + dy * dy, rc * rc) & live & sb_bitsi(j > i);
		const sb_vi I8 = i8 - (sb_vi){0};
		memcpy(pi + np, &I8, sizeof I8); /* whole vectors: the list has room (nlist.c) */
		sb_compressi(pj + np, j << sh, sb_cmask_of(bits));
		np += sb_count(bits);
	}
	return np;
}

const sb_kvec KV(sb_kvec) = {SB_STR(SB_KV_NAME), forces, correct_predict, to_state, scan};
