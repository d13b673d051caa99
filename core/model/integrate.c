/* integrate.c - time integrators. Gear (1971) in Nordsieck form, scaled variables
 * q_k = dt^k/k! d^k q/dt^k (Allen & Tildesley 1987, app. E). Corrector constants for
 * velocity-dependent forces (docs/model.md, "Integrators"): 6-value c0 = 3/16, 5-value c0 = 19/90. */
#include "integrate.h"

#include <math.h>
#include <stdio.h>

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
