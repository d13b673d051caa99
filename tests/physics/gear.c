/* gear.c - integrator accuracy: convergence order on an exact harmonic oscillator,
 * and energy conservation of an elastic many-disk gas.
 *
 * Oscillator: a disk of radius 1 rests on an immobile wall disk (wall_mass =
 * infinite, so m_eff = m), pressed down by gy = -g, with gamma_N = gamma_S = 0. While
 * the overlap xi = 2 - y stays positive the force is Y xi, so
 *   y'' = Y (2 - y) / m - g,  y(t) = 2 - xi_eq - a cos(w t),  xi_eq = m g / Y,
 *   w = sqrt(Y / m),
 * started at rest from xi = xi_eq + a with a = xi_eq / 2 (the overlap stays in
 * [xi_eq/2, 3 xi_eq/2] > 0: no contact event, a pure linear ODE). The global error of
 * y at T = 2 periods, relative to a, is measured for dt = T/N with N = 64..1024
 * (w dt = 0.2 .. 0.012) and the order is the slope of log(error) vs log(dt).
 *
 * Gas: 64 disks in a closed box of wall disks, no gravity, gamma_N = gamma_S = 0
 * (so no tangential force and no dissipation), random velocities. The energy
 * E = sum (m v^2 + I w^2)/2 + sum over contacts Y xi^2 / 2 is conserved by the ODE;
 * its drift over 1e5 steps of the paper's dt is the integrator's. */
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fpmode.h"
#include "place.h"
#include "sim.h"
#include "step.h"
#include "testlib.h"
#include "units.h"

static const char *INAME[] = {"gear5", "gear4", "verlet"};

/* The engine's y and v (cm, cm/s) after the oscillator's T = 2.125 periods in nsteps
 * steps; NAN on failure. */
static int exact_start;
static void osc_engine(int integ, long nsteps, double c0, double *yend, double *vend) /* c0 > 0: override */
{
	sb_scene sc;
	params_defaults(&sc);
	sc.gamma_n = 0;
	sc.gamma_s = 0;
	sc.wall_mass = WALLMASS_INFINITE;
	sc.integrator = integ;
	double m = place_mass(&sc, 1.0, KIND_GRAIN), Y = sc.stiffness, g = sc.gravity;
	double w = sqrt(Y / m), T = 2.125 * SB_TWO_PI / w;
	double xeq = m * g / Y, a = 0.5 * xeq;
	sc.dt = T / nsteps;
	*yend = *vend = NAN;
	sb_sim *s = calloc(1, sizeof *s);
	sb_err e = {0};
	sim_init(s, &sc, &e);
	if (c0 > 0)
		s->in.c[0] = c0; /* diagnostic: the position-only corrector value */
	place_push(&sc, &s->st, 0, 2 - xeq - a, 1, KIND_GRAIN, &e);
	place_push(&sc, &s->st, 0, 0, 1, KIND_WALL, &e);
	place_push(&sc, &s->st, -30, 0, 1, KIND_WALL, &e);
	place_push(&sc, &s->st, 30, 0, 1, KIND_WALL, &e);
	if (sim_derive(s, &e) || step_start(s, -g, &e))
		goto out;
	if (exact_start && integ != INTEG_VERLET)
		s->st.q[C_Y][4][0] = -a * pow(w * sc.dt, 4) / 24;
	for (long k = 0; k < nsteps; k++)
		if (step_advance(s, -g, &e))
			goto out;
	*yend = s->st.q[C_Y][0][0];
	*vend = s->st.q[C_Y][1][0] / sc.dt;
out:
	if (e.code)
		printf("# %s N=%ld: %s\n", INAME[integ], nsteps, e.msg);
	sim_free(s);
	free(s);
}

/* Global relative error of the oscillator after T = 2.125 periods with N steps per T. */
static double osc_error(int integ, long nsteps, double c0) /* c0 > 0: override */
{
	sb_scene sc;
	params_defaults(&sc);
	double m = place_mass(&sc, 1.0, KIND_GRAIN), Y = sc.stiffness, g = sc.gravity;
	double w = sqrt(Y / m), T = 2.125 * SB_TWO_PI / w;
	double xeq = m * g / Y, a = 0.5 * xeq, y, v;
	osc_engine(integ, nsteps, c0, &y, &v);
	double yex = 2 - xeq - a * cos(w * T), vex = a * w * sin(w * T);
	return hypot(y - yex, (v - vex) / w) / a;
}

/* The oscillator integrated by the test's own code, from the literature's coefficients
 * and not from core/model/integrate.c: Gear's predictor-corrector on the scaled derivatives
 * q_k = dt^k/k! y^(k) (Gear, Numerical Initial Value Problems in ODEs, 1971; the
 * coefficients for forces that depend on the velocity, as Allen & Tildesley, Computer
 * Simulation of Liquids, 1987, app. E list them: 6 values 3/16, 251/360, 1, 11/18, 1/6,
 * 1/60; 5 values 19/90, 3/4, 1, 1/2, 1/12), or velocity Verlet, started as the engine
 * starts (q2 from the force, the higher derivatives 0). For this linear force the
 * engine's trajectory must match it to round-off (docs/engine.md, "Integrators"), so
 * a changed corrector constant, Pascal row or start shows as a difference as large
 * as the integration error itself: far above the tolerance. y and v at the end, as
 * osc_error measures them. */
static void osc_reference(int integ, long nsteps, double *yend, double *vend)
{
	sb_scene sc;
	params_defaults(&sc);
	double m = place_mass(&sc, 1.0, KIND_GRAIN), Y = sc.stiffness, g = sc.gravity;
	double w = sqrt(Y / m), T = 2.125 * SB_TWO_PI / w, h = T / nsteps;
	double xeq = m * g / Y, a = 0.5 * xeq;
#define ACC(y) (Y * (2 - (y)) / m - g)
	double y = 2 - xeq - a;
	if (integ == INTEG_VERLET) {
		double v = 0, acc = ACC(y);
		for (long k = 0; k < nsteps; k++) {
			v += 0.5 * h * acc;
			y += h * v;
			acc = ACC(y);
			v += 0.5 * h * acc;
		}
		*yend = y;
		*vend = v;
		return;
	}
	static const double c6[6] = {3.0 / 16, 251.0 / 360, 1, 11.0 / 18, 1.0 / 6, 1.0 / 60};
	static const double c5[5] = {19.0 / 90, 3.0 / 4, 1, 1.0 / 2, 1.0 / 12};
	const double *c = integ == INTEG_GEAR5 ? c6 : c5;
	int nv = integ == INTEG_GEAR5 ? 6 : 5;
	double q[6] = {y, 0, 0.5 * h * h * ACC(y), 0, 0, 0};
	for (long k = 0; k < nsteps; k++) {
		/* predictor: the Taylor shift of the scaled derivatives (Pascal's triangle) */
		for (int i = 0; i < nv - 1; i++)
			for (int j = nv - 1; j > i; j--)
				q[j - 1] += q[j];
		double d = 0.5 * h * h * ACC(q[0]) - q[2];
		for (int i = 0; i < nv; i++)
			q[i] += c[i] * d;
	}
#undef ACC
	*yend = q[0];
	*vend = q[1] / h;
}

/* ---- gas ---- */

static double energy(const sb_sim *s)
{
	const sb_state *st = &s->st;
	double E = sim_kinetic(s), Y = s->sc.stiffness;
	for (int i = 0; i < st->nm; i++)
		for (int j = i + 1; j < st->n; j++) {
			double d = hypot(st->q[C_X][0][i] - st->q[C_X][0][j], st->q[C_Y][0][i] - st->q[C_Y][0][j]);
			double xi = st->r[i] + st->r[j] - d;
			if (xi > 0)
				E += 0.5 * Y * xi * xi;
		}
	return E;
}

static unsigned long gseed = 7;
static void gas(double dt, long nsteps, double *drift, double *maxdev, long *ncoll, int *ok)
{
	sb_scene sc;
	params_defaults(&sc);
	sc.gravity = 0;
	sc.gamma_n = 0;
	sc.gamma_s = 0;
	sc.integrator = INTEG_GEAR5;
	sc.dt = dt;
	sb_sim *s = calloc(1, sizeof *s);
	sb_err e = {0};
	sim_init(s, &sc, &e);
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, gseed);
	const int nx = 8, ny = 8;
	const double pitch = 3.0, W = nx * pitch, H = ny * pitch;
	for (int a = 0; a < nx; a++)
		for (int b = 0; b < ny; b++) {
			double r = 0.85 + 0.3 * gsl_rng_uniform(rng);
			place_push(&sc, &s->st, (a + 0.5) * pitch, (b + 0.5) * pitch, r, KIND_GRAIN, &e);
		}
	/* closed box: wall disks of radius 1 touching (spacing 2), centres on the
	 * rectangle [-1, W+1] x [-1, H+1] */
	int nwx = (int)ceil((W + 2) / 2), nwy = (int)ceil((H + 2) / 2);
	for (int k = 0; k <= nwx; k++) {
		double x = -1 + (W + 2) * k / nwx;
		place_push(&sc, &s->st, x, -1, 1, KIND_WALL, &e);
		place_push(&sc, &s->st, x, H + 1, 1, KIND_WALL, &e);
	}
	for (int k = 1; k < nwy; k++) {
		double y = -1 + (H + 2) * k / nwy;
		place_push(&sc, &s->st, -1, y, 1, KIND_WALL, &e);
		place_push(&sc, &s->st, W + 1, y, 1, KIND_WALL, &e);
	}
	*ok = 0;
	if (sim_derive(s, &e))
		goto out;
	for (int i = 0; i < s->st.nm; i++) {
		double v = 30 + 40 * gsl_rng_uniform(rng), phi = SB_TWO_PI * gsl_rng_uniform(rng);
		s->st.q[C_X][1][i] = v * cos(phi) * sc.dt;
		s->st.q[C_Y][1][i] = v * sin(phi) * sc.dt;
	}
	if (step_start(s, 0, &e))
		goto out;
	double E0 = energy(s), Emax = E0, Emin = E0;
	long builds0 = s->nl.builds;
	*ncoll = 0;
	for (long k = 1; k <= nsteps; k++) {
		if (step_advance(s, 0, &e))
			goto out;
		if (k % 100 == 0) {
			double E = energy(s);
			Emax = fmax(Emax, E);
			Emin = fmin(Emin, E);
		}
	}
	double E1 = energy(s);
	*drift = (E1 - E0) / E0;
	*maxdev = fmax(Emax - E0, E0 - Emin) / E0;
	*ncoll = s->nl.builds - builds0;
	*ok = 1;
out:
	if (e.code)
		printf("# gas: %s\n", e.msg);
	gsl_rng_free(rng);
	sim_free(s);
	free(s);
}

/* Observed orders (slopes of log2 error per halving of dt, w dt from 0.2 to 0.012):
 *   gear5 (c0 = 3/16): 5.1, 4.8, 4.5, 4.3 - falling towards 4. The cause is the
 *     start, not the corrector: integ_start sets q3..q5 = 0, an O(dt^4) error in the
 *     scaled 4th derivative that persists as an O(dt^4) global error. Given the
 *     exact q4 at the start, the slopes are 5.32, 5.13, 5.04, 4.95 (checked below,
 *     >= 4.7); so the scheme is 5th order, the engine's start makes it 4th;
 *   gear4 (c0 = 19/90): 4.14, 4.04, 4.01, 4.00;
 *   verlet: 2.005, 2.001, 2.000, 2.000.
 * Asserted: the slope of the two finest halvings >= 3.8 (gear5, gear4), >= 1.9
 * (verlet), i.e. the theoretical order minus 5 % for the pre-asymptotic wiggle; an
 * integrator that lost an order (a wrong corrector coefficient or Pascal row) fails.
 *
 * Gas, gear5, 64 disks, 1e5 steps of 5e-5 s (5 s, ~7000 list rebuilds): each
 *   contact leaves an energy error whose sign depends on where the contact starts
 *   and ends within a step, so the drift is a random walk over thousands of
 *   contacts and depends on the (chaotic) trajectory: over seeds 1..8 the drift
 *   (E_end - E_0)/E_0 was -5.4e-4 .. +2.7e-4 and the largest deviation (sampled
 *   every 100 steps) 3.2e-4 .. 8.5e-4. Asserted: |drift| <= 1.5e-3 and deviation
 *   <= 2e-3 (about 2.5x the worst seed, so a round-off change of the trajectory
 *   cannot trip them; a force/reaction mismatch, lost dissipation-free-ness or a
 *   scheme that lost an order does: dt = 1e-4 already gives 2.3e-3), and the
 *   deviation at dt/2 is at least 2x smaller (measured 4.0 and 9.4 on two builds
 *   that differ only in round-off; 2 = first order at least). */
/* Subnormals (core/base/fpmode.h): a disk in free flight whose higher derivatives
 * start non-zero (as after a collision). With no force the corrector pulls them
 * towards zero geometrically; unflushed they pass through the subnormal range (and
 * on Intel CPUs each operation on them costs a microcode assist), flushed they jump
 * from normal to zero. Checked after every step, fused (the run loop's) and
 * reference, with the caller's floating-point mode back after each step. */
static volatile double tiny_a = 0x1p-1000, tiny_b = 0x1p-40; /* volatile: computed at run time */
static void subnormals(int fuse, int *ok, long *first_sub, long *all_zero, int *mode_kept)
{
	sb_scene sc;
	params_defaults(&sc);
	sc.gravity = 0;
	sb_sim *s = calloc(1, sizeof *s);
	sb_err e = {0};
	sim_init(s, &sc, &e);
	place_push(&sc, &s->st, 0, 20, 1, KIND_GRAIN, &e);
	place_push(&sc, &s->st, -30, 0, 1, KIND_WALL, &e);
	place_push(&sc, &s->st, 30, 0, 1, KIND_WALL, &e);
	*ok = !e.code && !sim_derive(s, &e) && !step_start(s, 0, &e);
	*first_sub = *all_zero = -1;
	*mode_kept = 1;
	const long n = 20000;
	for (int c = 0; c < 3 && *ok; c++)
		for (int k = 3; k < s->in.nval; k++)
			s->st.q[c][k][0] = 1e-3 / k; /* after step_start, which clears them */
	for (long k = 1; k <= n && *ok; k++) {
		*ok = !step_once(s, k, 0, 0, fuse && k < n, NULL, &e);
		if (fuse && k < n)
			kernel_sync(s->kern, &s->st);
		/* the caller's mode (IEEE: subnormals kept) is back after the step */
		*mode_kept &= fpclassify(tiny_a * tiny_b) == FP_SUBNORMAL;
		int nz = 0;
		for (int c = 0; c < 3; c++)
			for (int j = 2; j < s->in.nval; j++) {
				const double q = s->st.q[c][j][0];
				if (fpclassify(q) == FP_SUBNORMAL && *first_sub < 0)
					*first_sub = k;
				nz += q != 0;
			}
		if (!nz && *all_zero < 0)
			*all_zero = k;
	}
	if (e.code)
		printf("# subnormals: %s\n", e.msg);
	sim_free(s);
	free(s);
}

int main(void)
{
	char id[128];

	const long NS[] = {64, 128, 256, 512, 1024};
	enum { NN = sizeof NS / sizeof NS[0] };
	const double want[3] = {3.8, 3.8, 1.9};
	for (int it = 0; it < 3; it++) {
		double err[NN];
		for (int k = 0; k < NN; k++) {
			err[k] = osc_error(it, NS[k], 0);
			printf("# oscillator %s N=%ld: rel err %.3e\n", INAME[it], NS[k], err[k]);
		}
		double smin = INFINITY;
		for (int k = 0; k + 1 < NN; k++) {
			double sl = log2(err[k] / err[k + 1]);
			printf("#   slope %ld->%ld: %.3f\n", NS[k], NS[k + 1], sl);
			/* not fmin: fmin(INFINITY, NaN) is INFINITY, and a failed run's NaN
			 * must fail the check, not vanish from it */
			if (k >= NN - 3 && !(sl >= smin))
				smin = sl;
		}
		snprintf(id, sizeof id, "integrator.%s.order.oscillator", INAME[it]);
		CHECK(id, smin >= want[it], "observed order %.3f < %.1f", smin, want[it]);
	}
	/* The engine's trajectory is the literature scheme's to round-off: |difference| /
	 * amplitude <= 1e-9 at N = 64 and 256, where the integration errors themselves are
	 * 7e-5 .. 2e-2 (N = 64) and 8e-8 .. 1.4e-3 (N = 256). Planted in core/model/integrate.c,
	 * gear5's corrector 3/20 instead of 3/16 moved the end by 5.0e-5 (N = 64) and 5.1e-8
	 * (N = 256) of the amplitude, gear4's 19/9 instead of 19/90 by 1.2e-2 and 4.5e-5 (the
	 * order checks above let gear4's pass); round-off was <= 2.4e-15. */
	for (int it = 0; it < 3; it++)
		for (long N = 64; N <= 256; N *= 4) {
			sb_scene sc0;
			params_defaults(&sc0);
			double m0 = place_mass(&sc0, 1.0, KIND_GRAIN), a0 = 0.5 * m0 * sc0.gravity / sc0.stiffness;
			double w0 = sqrt(sc0.stiffness / m0);
			double ye, ve, yr, vr;
			osc_engine(it, N, 0, &ye, &ve);
			osc_reference(it, N, &yr, &vr);
			double d = hypot(ye - yr, (ve - vr) / w0) / a0;
			printf("# %s N=%ld: engine - reference = %.2e of the amplitude\n", INAME[it], N, d);
			snprintf(id, sizeof id, "integrator.%s.matches_literature_scheme.N%ld", INAME[it], N);
			CHECK(id, d <= 1e-9, "engine vs reference scheme: %.3e of the amplitude (y %.17g vs %.17g)", d,
			      ye, yr);
		}
	/* Starting with the exact 4th derivative (integ_start clears q3..q5; for this
	 * oscillator started at rest only q4 is non-zero) restores 5th order. */
	{
		exact_start = 1;
		double e1 = osc_error(INTEG_GEAR5, 256, 0), e2 = osc_error(INTEG_GEAR5, 512, 0),
		       e3 = osc_error(INTEG_GEAR5, 1024, 0);
		exact_start = 0;
		double s1 = log2(e1 / e2), s2 = log2(e2 / e3);
		double sl = s1 < s2 || s1 != s1 ? s1 : s2; /* a NaN of either fails below */
		printf("# gear5 exact start: N=256 %.3e N=512 %.3e N=1024 %.3e, slopes %.3f %.3f\n", e1, e2,
		       e3, log2(e1 / e2), log2(e2 / e3));
		CHECK("integrator.gear5.order.exact_start", sl >= 4.7, "slope %.3f < 4.7", sl);
	}

	for (int fuse = 0; fuse < 2; fuse++) {
		int sok, kept;
		long first_sub, all_zero;
		const char *how = fuse ? "fused" : "reference";
		subnormals(fuse, &sok, &first_sub, &all_zero, &kept);
		printf("# subnormals, %s steps: first subnormal at step %ld, derivatives all zero from step %ld\n", how,
		       first_sub, all_zero);
		snprintf(id, sizeof id, "integrator.gear5.subnormals.%s.runs", how);
		CHECK(id, sok, "the free-flight run stopped (see the # line above)");
		snprintf(id, sizeof id, "integrator.gear5.subnormals.%s.decays_to_zero", how);
		CHECK(id, all_zero > 0, "the derivatives never reached zero (still subnormal, or no decay: then the check below tests nothing)");
		snprintf(id, sizeof id, "integrator.gear5.subnormals.%s.flushed", how);
		CHECK(id, first_sub < 0 || !fpmode_flushes(), "a subnormal derivative at step %ld (core/base/fpmode.h)", first_sub);
		snprintf(id, sizeof id, "integrator.gear5.subnormals.%s.caller_mode_restored", how);
		CHECK(id, kept, "after step_once the caller's floating-point mode flushes subnormals");
	}

	double drift, maxdev, drift2, maxdev2;
	long nb, nb2;
	int ok, ok2;
	gas(5e-5, 100000, &drift, &maxdev, &nb, &ok);
	printf("# gas dt=5e-5 1e5 steps: drift %.3e maxdev %.3e nlist builds %ld\n", drift, maxdev, nb);
	gas(2.5e-5, 200000, &drift2, &maxdev2, &nb2, &ok2);
	printf("# gas dt=2.5e-5 2e5 steps: drift %.3e maxdev %.3e nlist builds %ld\n", drift2, maxdev2, nb2);
	CHECK("integrator.gear5.energy.gas.runs", ok && ok2, "the gas run stopped (see the # line above)");
	CHECK("integrator.gear5.energy.gas.list_rebuilds", nb > 1000,
	      "only %ld neighbour-list builds: the gas did not move enough to test anything", nb);
	CHECK("integrator.gear5.energy.gas.drift", fabs(drift) <= 1.5e-3, "drift %.3e > 1.5e-3", drift);
	CHECK("integrator.gear5.energy.gas.deviation", maxdev <= 2e-3, "deviation %.3e > 2e-3", maxdev);
	CHECK("integrator.gear5.energy.gas.deviation_converges", maxdev2 * 2 <= maxdev,
	      "deviation %.3e at dt/2 is not 2x below %.3e", maxdev2, maxdev);
	return tl_done();
}
