/* integrate.c - time integrators. Gear (1971) in Nordsieck form, scaled variables
 * q_k = dt^k/k! d^k q/dt^k (Allen & Tildesley 1987, app. E). Corrector constants for
 * velocity-dependent forces (MODEL.md): 6-value c0 = 3/16, 5-value c0 = 19/90. */
#include "integrate.h"

#include <math.h>
#include <stdio.h>

#include "krec.h"
#include "params.h"

void integ_init(sb_integ *in, int kind, double dt)
{
	static const double g5[6] = {3.0 / 16, 251.0 / 360, 1, 11.0 / 18, 1.0 / 6, 1.0 / 60};
	static const double g4[6] = {19.0 / 90, 3.0 / 4, 1, 1.0 / 2, 1.0 / 12, 0};
	in->kind = kind;
	in->dt = dt;
	in->half_dt2 = 0.5 * dt * dt;
	for (int k = 0; k < SB_MAXORDER; k++)
		in->c[k] = kind == INTEG_GEAR5 ? g5[k] : kind == INTEG_GEAR4 ? g4[k] : 0;
	in->nval = kind == INTEG_GEAR5 ? 6 : kind == INTEG_GEAR4 ? 5 : 3;
}

/* Flat loops over one coordinate at a time so that the compiler vectorises them. */
static void predict6(int n, double *restrict q0, double *restrict q1, double *restrict q2,
		     double *restrict q3, double *restrict q4, const double *restrict q5)
{
	for (int i = 0; i < n; i++) {
		const double a1 = q1[i], a2 = q2[i], a3 = q3[i], a4 = q4[i], a5 = q5[i];
		q0[i] += a1 + a2 + a3 + a4 + a5;
		q1[i] = a1 + 2 * a2 + 3 * a3 + 4 * a4 + 5 * a5;
		q2[i] = a2 + 3 * a3 + 6 * a4 + 10 * a5;
		q3[i] = a3 + 4 * a4 + 10 * a5;
		q4[i] = a4 + 5 * a5;
	}
}

static void predict5(int n, double *restrict q0, double *restrict q1, double *restrict q2,
		     double *restrict q3, const double *restrict q4)
{
	for (int i = 0; i < n; i++) {
		const double a1 = q1[i], a2 = q2[i], a3 = q3[i], a4 = q4[i];
		q0[i] += a1 + a2 + a3 + a4;
		q1[i] = a1 + 2 * a2 + 3 * a3 + 4 * a4;
		q2[i] = a2 + 3 * a3 + 6 * a4;
		q3[i] = a3 + 4 * a4;
	}
}

static void predict_verlet(int n, double *restrict q0, double *restrict q1, const double *restrict q2)
{
	/* q1 += q2 is the half kick v += a dt/2; q0 += q1 the drift. Forces are then
	 * evaluated with the half-step velocity, as LAMMPS fix nve/sphere does. */
	for (int i = 0; i < n; i++) {
		q1[i] += q2[i];
		q0[i] += q1[i];
	}
}

void integ_predict(const sb_integ *in, sb_state *st)
{
	for (int c = 0; c < SB_NCOORD; c++) {
		double **q = st->q[c];
		if (in->nval == 6)
			predict6(st->nm, q[0], q[1], q[2], q[3], q[4], q[5]);
		else if (in->nval == 5)
			predict5(st->nm, q[0], q[1], q[2], q[3], q[4]);
		else
			predict_verlet(st->nm, q[0], q[1], q[2]);
	}
}

static void correct6(int n, const double *c, double h, const double *restrict f,
		     const double *restrict inv, double extra, double *restrict q0,
		     double *restrict q1, double *restrict q2, double *restrict q3,
		     double *restrict q4, double *restrict q5)
{
	const double c0 = c[0], c1 = c[1], c3 = c[3], c4 = c[4], c5 = c[5];
	for (int i = 0; i < n; i++) {
		const double a2 = (f[i] * inv[i] + extra) * h;
		const double d = a2 - q2[i];
		q0[i] += c0 * d;
		q1[i] += c1 * d;
		q2[i] = a2; /* c2 = 1 */
		q3[i] += c3 * d;
		q4[i] += c4 * d;
		q5[i] += c5 * d;
	}
}

static void correct5(int n, const double *c, double h, const double *restrict f,
		     const double *restrict inv, double extra, double *restrict q0,
		     double *restrict q1, double *restrict q2, double *restrict q3,
		     double *restrict q4)
{
	const double c0 = c[0], c1 = c[1], c3 = c[3], c4 = c[4];
	for (int i = 0; i < n; i++) {
		const double a2 = (f[i] * inv[i] + extra) * h;
		const double d = a2 - q2[i];
		q0[i] += c0 * d;
		q1[i] += c1 * d;
		q2[i] = a2;
		q3[i] += c3 * d;
		q4[i] += c4 * d;
	}
}

static void correct_verlet(int n, double h, const double *restrict f, const double *restrict inv,
			   double extra, double *restrict q1, double *restrict q2)
{
	for (int i = 0; i < n; i++) {
		const double a2 = (f[i] * inv[i] + extra) * h;
		q2[i] = a2;
		q1[i] += a2; /* second half kick */
	}
}

/* Corrector of this step and predictor of the next in one pass: the Nordsieck
 * arrays are read and written once per step instead of twice. The operations per
 * element are exactly those of correct6 followed by predict6. */
static void correct_predict6(int n, const double *c, double h, const double *restrict f,
			     const double *restrict inv, double extra, double *restrict q0,
			     double *restrict q1, double *restrict q2, double *restrict q3,
			     double *restrict q4, double *restrict q5)
{
	const double c0 = c[0], c1 = c[1], c3 = c[3], c4 = c[4], c5 = c[5];
	for (int i = 0; i < n; i++) {
		const double a2 = (f[i] * inv[i] + extra) * h;
		const double d = a2 - q2[i];
		const double b0 = q0[i] + c0 * d, a1 = q1[i] + c1 * d, a3 = q3[i] + c3 * d,
			     a4 = q4[i] + c4 * d, a5 = q5[i] + c5 * d;
		q0[i] = b0 + (a1 + a2 + a3 + a4 + a5);
		q1[i] = a1 + 2 * a2 + 3 * a3 + 4 * a4 + 5 * a5;
		q2[i] = a2 + 3 * a3 + 6 * a4 + 10 * a5;
		q3[i] = a3 + 4 * a4 + 10 * a5;
		q4[i] = a4 + 5 * a5;
		q5[i] = a5;
	}
}

static void correct_predict5(int n, const double *c, double h, const double *restrict f,
			     const double *restrict inv, double extra, double *restrict q0,
			     double *restrict q1, double *restrict q2, double *restrict q3,
			     double *restrict q4)
{
	const double c0 = c[0], c1 = c[1], c3 = c[3], c4 = c[4];
	for (int i = 0; i < n; i++) {
		const double a2 = (f[i] * inv[i] + extra) * h;
		const double d = a2 - q2[i];
		const double b0 = q0[i] + c0 * d, a1 = q1[i] + c1 * d, a3 = q3[i] + c3 * d,
			     a4 = q4[i] + c4 * d;
		q0[i] = b0 + (a1 + a2 + a3 + a4);
		q1[i] = a1 + 2 * a2 + 3 * a3 + 4 * a4;
		q2[i] = a2 + 3 * a3 + 6 * a4;
		q3[i] = a3 + 4 * a4;
		q4[i] = a4;
	}
}

static void correct_predict_verlet(int n, double h, const double *restrict f,
				   const double *restrict inv, double extra, double *restrict q0,
				   double *restrict q1, double *restrict q2)
{
	for (int i = 0; i < n; i++) {
		const double a2 = (f[i] * inv[i] + extra) * h;
		const double v = q1[i] + a2;
		q2[i] = a2;
		q1[i] = v + a2;
		q0[i] += v + a2;
	}
}

void integ_correct_predict(const sb_integ *in, sb_state *st, double gy)
{
	for (int c = 0; c < SB_NCOORD; c++) {
		double **q = st->q[c];
		const double *inv = c == C_TH ? st->inv_i : st->inv_m;
		const double extra = c == C_Y ? gy : 0;
		if (in->nval == 6)
			correct_predict6(st->nm, in->c, in->half_dt2, st->f[c], inv, extra, q[0], q[1], q[2],
					 q[3], q[4], q[5]);
		else if (in->nval == 5)
			correct_predict5(st->nm, in->c, in->half_dt2, st->f[c], inv, extra, q[0], q[1], q[2],
					 q[3], q[4]);
		else
			correct_predict_verlet(st->nm, in->half_dt2, st->f[c], inv, extra, q[0], q[1], q[2]);
	}
}

#if SB_KERNEL_AVX512
/* The fused pass of the AVX-512 build: per block of eight disks, the forces from the
 * kernel's accumulators, the three coordinates' correct_predict (the same operations
 * element by element, written with vector operators; no FMA is formed, as
 * -ffp-contract=off holds for them too), sim.c's screening of the predicted state,
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
	 * of this step read them there (forces_compute_acc packs them if the last step
	 * was not fused), and this pass writes them only there - four arrays fewer to
	 * stream, where the pass is bound by moving lines between L1 and L2 (or L3).
	 * forces_records_to_state() brings st up to date for everyone else. */
	krec_load8(a->rec + 8 * i, &x0, &y0, &x1, &y1);
	const v8 im = vload(a->inv_m + i, full, m), R = vload(a->r + i, full, m);
	cp_block(nval, a->c, a->h, fx, im, 0, a->x, i, full, m, 0, &x0, &x1);
	cp_block(nval, a->c, a->h, fy, im, a->gy, a->y, i, full, m, 0, &y0, &y1);
	cp_block(nval, a->c, a->h, ft, vload(a->inv_i + i, full, m), 0, a->t, i, full, m, 1, &t0, &t1);
	krec_store8(a->rec + 8 * i, x0, y0, x1, y1, t1, R, im, count);
	/* sim.c's check_state, operation by operation */
	const v8 dx = x0 - vload(a->xref + i, full, m), dy = y0 - vload(a->yref + i, full, m);
	const v8 d2 = dx * dx + dy * dy;
	const v8 at = _mm512_abs_pd(t0);
	fl->rebuild |= _mm512_mask_cmp_pd_mask(m, d2, _mm512_set1_pd(a->lim), _CMP_GT_OQ);
	fl->bad |= _mm512_mask_cmp_pd_mask(m, d2 + at, _mm512_set1_pd(INFINITY), _CMP_NLT_UQ);
	fl->out |= _mm512_mask_cmp_pd_mask(m, x0, _mm512_set1_pd(a->xlo), _CMP_LT_OQ) |
		   _mm512_mask_cmp_pd_mask(m, x0, _mm512_set1_pd(a->xhi), _CMP_GT_OQ) |
		   _mm512_mask_cmp_pd_mask(m, y0, _mm512_set1_pd(a->ylo), _CMP_LT_OQ);
}

static inline __attribute__((always_inline)) void cpa(const int nval, const sb_integ *in,
						      sb_state *st, double gy, sb_nlist *nl,
						      sb_screen *scr)
{
	cpa_args a = {qarr_of(st, C_X), qarr_of(st, C_Y), qarr_of(st, C_TH), st->inv_m, st->inv_i,
		      st->r, nl->xref, nl->yref, nl->facc, nl->rec, {0}, in->half_dt2, gy,
		      scr->lim, scr->xlo, scr->xhi, scr->ylo};
	for (int k = 0; k < SB_MAXORDER; k++)
		a.c[k] = in->c[k];
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

int integ_correct_predict_acc(const sb_integ *in, sb_state *st, double gy, sb_nlist *nl,
			      sb_screen *scr)
{
	if (in->nval == 6)
		cpa(6, in, st, gy, nl, scr);
	else if (in->nval == 5)
		cpa(5, in, st, gy, nl, scr);
	else
		cpa(3, in, st, gy, nl, scr);
	return 1;
}
#else
int integ_correct_predict_acc(const sb_integ *in, sb_state *st, double gy, sb_nlist *nl,
			      sb_screen *scr)
{
	(void)nl;
	scr->done = 0;
	integ_correct_predict(in, st, gy);
	return 0;
}
#endif

void integ_correct(const sb_integ *in, sb_state *st, double gy)
{
	for (int c = 0; c < SB_NCOORD; c++) {
		double **q = st->q[c];
		const double *inv = c == C_TH ? st->inv_i : st->inv_m;
		const double extra = c == C_Y ? gy : 0;
		if (in->nval == 6)
			correct6(st->nm, in->c, in->half_dt2, st->f[c], inv, extra, q[0], q[1], q[2], q[3],
				 q[4], q[5]);
		else if (in->nval == 5)
			correct5(st->nm, in->c, in->half_dt2, st->f[c], inv, extra, q[0], q[1], q[2], q[3],
				 q[4]);
		else
			correct_verlet(st->nm, in->half_dt2, st->f[c], inv, extra, q[1], q[2]);
	}
}

void integ_start(const sb_integ *in, sb_state *st, double gy)
{
	for (int c = 0; c < SB_NCOORD; c++) {
		const double *inv = c == C_TH ? st->inv_i : st->inv_m;
		const double extra = c == C_Y ? gy : 0;
		for (int i = 0; i < st->nm; i++) {
			st->q[c][2][i] = (st->f[c][i] * inv[i] + extra) * in->half_dt2;
			for (int k = 3; k < SB_MAXORDER; k++)
				st->q[c][k][i] = 0;
		}
	}
}

double integ_dt_limit(int kind, double Y, double gamma_n, double m_min, double *tc)
{
	/* k and the absolute bound from the bisection of `make stress` (Y = 3e5 .. 3e8,
	 * a shaken 240-grain bed), rounded down: gear5 0.15 t_c, gear4 0.2 t_c, verlet
	 * 0.4 t_c. At soft contacts the Gear schemes do not gain beyond 4e-4 s. */
	static const double k[3] = {0.15, 0.2, 0.4}, cap[3] = {4e-4, 4e-4, 1.2e-3};
	const double meff = 0.5 * m_min, w0sq = Y / meff, b = 0.5 * gamma_n;
	const double w = w0sq > b * b ? sqrt(w0sq - b * b) : sqrt(w0sq);
	*tc = 3.14159265358979323846 / w;
	const double lim = k[kind] * *tc;
	return lim < cap[kind] ? lim : cap[kind];
}

int integ_dt_check(const sb_scene *sc, double m_min, char *warn, size_t len, sb_err *e)
{
	static const char *names[3] = {"gear5", "gear4", "verlet"};
	warn[0] = 0;
	if (sc->dt_guard == 2 || !(m_min > 0))
		return 0;
	double tc, lim = integ_dt_limit(sc->integrator, sc->stiffness, sc->gamma_n, m_min, &tc);
	if (sc->dt > lim && sc->dt_guard == 0)
		return sb_errf(e, SB_EUSAGE,
			       "%s: dt: %g s is beyond the stability limit %.3g s of %s at this stiffness "
			       "(contact time %.3g s; make stress measures the limits); a smaller dt, or "
			       "dt_guard = warn to run anyway", params_where(sc, "dt"), sc->dt, lim,
			       names[sc->integrator], tc);
	if (sc->dt > 0.5 * lim)
		snprintf(warn, len, "dt = %g s is %s the stability limit %.3g s of %s at this stiffness "
				    "(contact time %.3g s)", sc->dt, sc->dt > lim ? "beyond" : "close to", lim,
			 names[sc->integrator], tc);
	return 0;
}
