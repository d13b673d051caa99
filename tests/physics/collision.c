/* collision.c - head-on collisions of two disks against the analytic linear
 * spring-dashpot solution (docs/model.md, "Contact law"; gear5).
 *
 * Relative coordinate: xi = R_i + R_j - d. For two mobile disks the force F_N acts on
 * i along n and on j along -n, so xi'' = -F_N / m_eff with
 * F_N = Y xi + gN m_eff xi':   xi'' = -w0^2 xi - 2 beta xi',  w0^2 = Y / m_eff,
 * beta = gN / 2 (independent of the masses).
 * Against an immobile wall disk j only i accelerates: xi'' = -F_N / m_i, so
 * w0^2 = Y / m_i and 2 beta = gN m_eff / m_i (m_eff uses the wall disk's mass, or
 * m_i when wall_mass = infinite, then beta = gN / 2 again).
 * With xi(0) = 0, xi'(0) = v0 and w = sqrt(w0^2 - beta^2):
 *   xi(t)  = v0/w e^{-beta t} sin(w t)
 *   xi'(t) = v0 e^{-beta t} (cos(w t) - beta/w sin(w t))
 * Unclipped: the contact ends at xi = 0, t_c = pi / w, e = exp(-beta pi / w).
 * Clipped: F_N / m = w0^2 xi + 2 beta xi' = 0 when
 *   (w0^2 - 2 beta^2) sin(wt) + 2 beta w cos(wt) = 0, i.e.
 *   w t* = pi - atan(2 beta w / (w0^2 - 2 beta^2))   (in (pi/2, pi) for small beta);
 * afterwards xi'' = 0 and xi' < 0 so F_N stays negative (clipped to zero): the disks
 * drift apart at the constant xi'(t*), e = |xi'(t*)| / v0 and the overlap lasts
 * t_c = t* + xi(t*) / |xi'(t*)|.
 *
 * Measured: the contact end by cubic Hermite interpolation of xi between the two
 * steps that bracket xi = 0 (using xi' from the integrator), e from the relative
 * normal velocity 400 steps after separation (the Gear corrector needs a few steps
 * to flush the higher derivatives after the force jumps to zero). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "collision_analytic.h"
#include "dtguard.h"
#include "forces.h"
#include "place.h"
#include "sim.h"
#include "step.h"
#include "testlib.h"
#include "two_disks.h"
#include "units.h"

typedef struct ccase {
	const char *name;
	double ri, rj;
	int ki, kj;      /* kinds: j may be KIND_WALL */
	int wall_mass;   /* only for walls */
} ccase;

typedef struct cres {
	double tc, e;    /* measured */
	double tc0, e0;  /* analytic */
	int ok;
} cres;

static const double V0 = 50.0; /* cm/s, approach speed */
/* the damping ratio of restitution e, written out here (not dtguard_zeta's): the test's
 * own statement of what the key means */
#define ZETA(e) (-log(e) / sqrt(SB_PI * SB_PI + log(e) * log(e)))

static void analytic(double w02, double beta, int clip, double *tc, double *e)
{
	collision_analytic(w02, beta, clip, V0, tc, e);
}


/* resti > 0: restitution = resti (the normal damping per pair, docs/model.md,
 * "Restitution"): c = 2 zeta sqrt(Y m_eff) in place of gN m_eff */
/* hertz: normal = hertz with damping gamma_n (the analytic solution then the RK4 one of
 * dtguard_hertz, an independent integration of the same equation); *emax gets the
 * largest |E - E0| / E0 of the relative motion's energy (kinetic + the engine's elastic
 * energy) over the contact */
static cres run_law(const ccase *c, int clip, double dt, double resti, int hertz, double gamma_n, double *beta_out,
		    double *emax)
{
	cres res = {0};
	sb_scene sc;
	params_defaults(&sc);
	sc.gravity = 0;
	sc.clip_attractive = clip;
	sc.integrator = INTEG_GEAR5;
	sc.dt = dt;
	sc.wall_mass = c->wall_mass;
	sc.restitution = resti;
	sc.normal = hertz ? NORMAL_HERTZ : NORMAL_HOOKE;
	if (hertz)
		sc.gamma_n = gamma_n;
	sb_sim *s = calloc(1, sizeof *s);
	sb_err e = {0};
	sim_init(s, &sc, &e);
	const double rs = c->ri + c->rj;
	int wall = c->kj == KIND_WALL;
	double mi = place_mass(&sc, c->ri, KIND_GRAIN), mj = place_mass(&sc, c->rj, KIND_GRAIN);
	/* i at the origin moving +x, j touching on its right moving -x (zero momentum), or
	 * i falling onto the wall disk j */
	if (two_disks(&sc, s, c->ri, c->rj, c->ki, c->kj, &e)) {
		printf("# setup failed: %s\n", e.msg);
		goto out;
	}
	sb_state *st = &s->st;
	double w02, beta;
	if (!wall) {
		double meff = mi * mj / (mi + mj);
		st->q[C_X][1][0] = V0 * mj / (mi + mj) * dt;
		st->q[C_X][1][1] = -V0 * mi / (mi + mj) * dt;
		w02 = sc.stiffness / meff;
		beta = resti > 0 ? ZETA(resti) * sqrt(w02) : 0.5 * sc.gamma_n;
	} else {
		double meff = c->wall_mass == WALLMASS_INFINITE ? mi : mi * mj / (mi + mj);
		st->q[C_Y][1][0] = -V0 * dt;
		w02 = sc.stiffness / mi;
		beta = resti > 0 ? ZETA(resti) * sqrt(sc.stiffness * meff) / mi : 0.5 * sc.gamma_n * meff / mi;
	}
	*beta_out = beta;
	analytic(w02, beta, clip, &res.tc0, &res.e0);
	const double mi_ = mi, meff_ = wall ? (c->wall_mass == WALLMASS_INFINITE ? mi : mi * mj / (mi + mj)) : mi * mj / (mi + mj);
	if (hertz)
		dtguard_hertz(sc.hertz_stiffness, c->ri * c->rj / (c->ri + c->rj), sc.gamma_n * meff_, wall ? mi_ : meff_, V0,
			      &res.e0, &res.tc0);
	if (emax)
		*emax = 0;
	if (step_start(s, 0, &e)) {
		printf("# start failed: %s\n", e.msg);
		goto out;
	}
	/* xi and xi' from the state (j may be a wall: its velocity is zero) */
#define XI() (rs - hypot(st->q[C_X][0][0] - st->q[C_X][0][1], st->q[C_Y][0][0] - st->q[C_Y][0][1]))
#define XID()                                                                          \
	(-(((st->q[C_X][1][0] - (wall ? 0 : st->q[C_X][1][1])) * nx +                   \
	    (st->q[C_Y][1][0] - (wall ? 0 : st->q[C_Y][1][1])) * ny) / dt))
	double nx = wall ? 0 : -1, ny = wall ? 1 : 0;
	double xi0 = XI(), xid0 = XID();
	long maxn = (long)(10 * res.tc0 / dt) + 10, k;
	res.tc = NAN;
	for (k = 1; k <= maxn; k++) {
		if (step_advance(s, 0, &e)) {
			printf("# step failed: %s\n", e.msg);
			goto out;
		}
		double xi1 = XI(), xid1 = XID();
		if (emax && !wall && xi1 > 0) { /* two mobile disks: E of the relative motion */
			double el, mo;
			long nc;
			forces_contact_energy(&s->law, st, &s->nl, kernel_shear(s->kern), &el, &mo, &nc);
			const double E0 = 0.5 * meff_ * V0 * V0, E = 0.5 * meff_ * xid1 * xid1 + el;
			*emax = fmax(*emax, fabs(E - E0) / E0);
		}
		if (k > 1 && xi0 > 0 && xi1 <= 0) {
			res.tc = (k - 1) * dt + hermite_root(xi0, xid0, xi1, xid1, dt);
			break;
		}
		xi0 = xi1;
		xid0 = xid1;
	}
	if (!isfinite(res.tc))
		goto out;
	for (int m = 0; m < 400; m++)
		if (step_advance(s, 0, &e)) {
			printf("# step failed: %s\n", e.msg);
			goto out;
		}
	res.e = -XID() / V0;
	res.ok = 1;
out:
	sim_free(s);
	free(s);
	return res;
}

static cres run(const ccase *c, int clip, double dt, double resti, double *beta_out)
{
	return run_law(c, clip, dt, resti, 0, 0, beta_out, NULL);
}

static const ccase CASES[] = {
	{"equal", 1, 1, KIND_GRAIN, KIND_GRAIN, WALLMASS_DISK},
	{"unequal_1_2", 1, 2, KIND_GRAIN, KIND_GRAIN, WALLMASS_DISK},
	/* radius 4 vs 1 makes the intruder a "large" disk: the big-pair force path */
	{"intruder_grain", 4, 1, KIND_INTRUDER, KIND_GRAIN, WALLMASS_DISK},
	{"wall_disk", 1, 1, KIND_GRAIN, KIND_WALL, WALLMASS_DISK},
	{"wall_infinite", 1, 1, KIND_GRAIN, KIND_WALL, WALLMASS_INFINITE},
};
#define NCASES (sizeof CASES / sizeof CASES[0])

/* Tolerances.
 * Duration: the 1e-4 at the paper's dt (measured <= 1e-5 for every case).
 * Restitution: every contact starts with a force jump (F_N = gN m_eff xi' = 2 beta
 * m v0 the moment xi > 0; clipping does not remove it) and, unclipped, ends with one
 * (-2 beta m v0 e to 0). A Gear step straddling an acceleration jump J mis-integrates
 * the velocity by O(J dt), so |de/e| ~ beta dt: at the paper's dt that is 2.5e-3 for
 * beta = 50/s, which no tolerance of 1e-4 can absorb (measured: 0.4..1.1 beta dt;
 * starting the same collision just inside the contact, clipped, drops the error to
 * 2e-4, confirming the start jump is the cause). So we check
 *   paper dt:         |de/e| <= 2 beta dt  (twice the worst measured ratio 1.1)
 *   dt = paper/64:    |de/e| <= 1e-4       (the accuracy; 2 beta dt = 7.8e-5
 *                                           there, so the bound above implies it)
 *   convergence:      clipped (only the start jump): each halving of dt shrinks the
 *                     error by >= 1.6 (first order gives 2, measured 1.97..2.08);
 *                     unclipped (the end jump adds a term whose size and sign depend
 *                     on where in the step the contact ends, so single halvings are
 *                     erratic): the first-order envelope |de/e| <= 2 beta dt holds at
 *                     every one of the 7 step sizes. */
#define NDT 7
int main(void)
{
	char id[256];
	double dts[NDT];
	for (int d = 0; d < NDT; d++)
		dts[d] = 5e-5 / (1 << d);
	for (size_t ci = 0; ci < NCASES; ci++)
		for (int clip = 0; clip <= 1; clip++) {
			const ccase *c = &CASES[ci];
			const char *cl = clip ? "clipped" : "unclipped";
			double ee[NDT], et[NDT], beta = 0;
			int all = 1;
			for (int d = 0; d < NDT; d++) {
				cres r = run(c, clip, dts[d], 0, &beta);
				all &= r.ok;
				ee[d] = r.ok ? (r.e - r.e0) / r.e0 : NAN;
				et[d] = r.ok ? (r.tc - r.tc0) / r.tc0 : NAN;
				printf("# %s %s dt=%g: e=%.10f (analytic %.10f, rel %.3e)  tc=%.10e (analytic %.10e, rel %.3e)\n",
				       c->name, cl, dts[d], r.e, r.e0, ee[d], r.tc, r.tc0, et[d]);
			}
			snprintf(id, sizeof id, "contact.head_on.%s.%s.completes", c->name, cl);
			CHECK(id, all, "a run blew up or the contact did not end within 10 analytic durations");
			if (!all)
				continue;
			snprintf(id, sizeof id, "contact.head_on.%s.%s.duration.paper_dt", c->name, cl);
			CHECK(id, fabs(et[0]) <= 1e-4, "rel err of the duration %.3e > 1e-4", et[0]);
			snprintf(id, sizeof id, "contact.head_on.%s.%s.duration.fine_dt", c->name, cl);
			CHECK(id, fabs(et[NDT - 1]) <= 1e-5, "rel err of the duration %.3e > 1e-5 at dt %g",
			      et[NDT - 1], dts[NDT - 1]);
			snprintf(id, sizeof id, "contact.head_on.%s.%s.restitution.paper_dt", c->name, cl);
			CHECK(id, fabs(ee[0]) <= 2 * beta * dts[0],
			      "rel err of e %.3e > 2 beta dt = %.3e", ee[0], 2 * beta * dts[0]);
			snprintf(id, sizeof id, "contact.head_on.%s.%s.restitution.fine_dt", c->name, cl);
			CHECK(id, fabs(ee[NDT - 1]) <= 1e-4, "rel err of e %.3e > 1e-4 at dt %g",
			      ee[NDT - 1], dts[NDT - 1]);
			snprintf(id, sizeof id, "contact.head_on.%s.%s.restitution.converges", c->name, cl);
			if (clip) {
				int okc = 1;
				double worst = INFINITY;
				for (int d = 0; d + 1 < NDT; d++) {
					double q = fabs(ee[d]) / fabs(ee[d + 1]);
					worst = fmin(worst, q);
					okc &= q >= 1.6;
				}
				CHECK(id, okc, "an error ratio per halving of dt is %.3f < 1.6 (not first order)", worst);
			} else {
				int okc = 1, bad = 0;
				for (int d = 0; d < NDT; d++)
					if (!(fabs(ee[d]) <= 2 * beta * dts[d]) && okc) {
						okc = 0;
						bad = d;
					}
				CHECK(id, okc, "rel err of e %.3e > 2 beta dt = %.3e at dt %g", ee[bad],
				      2 * beta * dts[bad], dts[bad]);
			}
		}
	/* restitution = 0.7: every pair of two mobile disks, whatever their masses, and a
	 * disk on a wall of infinite mass rebounds with e = 0.7 (the analytic solution at
	 * the damping the key sets, then the engine against it); a disk on a wall disk of
	 * finite mass, which does not move, does not: its e is the one recorded */
	for (size_t ci = 0; ci < NCASES; ci++) {
		const ccase *c = &CASES[ci];
		const int exact = c->kj != KIND_WALL || c->wall_mass == WALLMASS_INFINITE;
		double beta = 0;
		cres fine = run(c, 0, 5e-5 / 64, 0.7, &beta), paper = run(c, 0, 5e-5, 0.7, &beta);
		printf("# restitution 0.7, %s: analytic e %.10f, measured %.10f (dt/64), %.10f (paper dt); beta %.2f/s\n",
		       c->name, fine.e0, fine.e, paper.e, beta);
		snprintf(id, sizeof id, "contact.restitution_key.%s.analytic", c->name);
		if (exact)
			CHECK(id, fine.ok && fabs(fine.e0 - 0.7) <= 1e-12, "analytic e %.15f, not 0.7", fine.e0);
		else /* the wall disk's own mass in m_eff, the grain's in the motion: less damped */
			CHECK(id, fine.ok && fine.e0 > 0.7 + 1e-3, "analytic e %.15f, not above 0.7", fine.e0);
		snprintf(id, sizeof id, "contact.restitution_key.%s.measured", c->name);
		/* the first-order envelope of the head-on cases above: |de/e| <= 2 beta dt */
		CHECK(id, fine.ok && paper.ok && fabs(fine.e - fine.e0) <= 2 * beta * 5e-5 / 64 * fine.e0 &&
			      fabs(paper.e - paper.e0) <= 2 * beta * 5e-5 * paper.e0,
		      "e %.10f (dt/64), %.10f (paper dt) against %.10f", fine.e, paper.e, fine.e0);
	}
	/* normal = hertz: contact time and restitution against the same equation integrated
	 * by RK4 (dtguard_hertz), undamped and at gamma_n = 100 and 1000 (e 0.99 and 0.89
	 * for equal grains); undamped, the relative motion's energy (the engine's elastic
	 * energy, 2/5 K sqrt(R_eff) xi^5/2) is conserved through the contact */
	for (size_t ci = 0; ci < NCASES; ci++) {
		const ccase *c = &CASES[ci];
		const double gams[3] = {0, 100, 1000};
		for (int g = 0; g < 3; g++) {
			double beta = 0, emax = 0;
			cres fine = run_law(c, 0, 5e-5 / 16, 0, 1, gams[g], &beta, &emax), paper = run_law(c, 0, 5e-5, 0, 1, gams[g], &beta, NULL);
			printf("# hertz, gamma_n %g, %s: e %.8f t_c %.8e (RK4) | %.8f %.8e (dt/16) | %.8f %.8e (paper dt); energy %.2e\n",
			       gams[g], c->name, fine.e0, fine.tc0, fine.e, fine.tc, paper.e, paper.tc, emax);
			snprintf(id, sizeof id, "contact.hertz.%s.gamma%g", c->name, gams[g]);
			CHECK(id, fine.ok && paper.ok && fabs(fine.tc - fine.tc0) <= 1e-4 * fine.tc0 &&
				      fabs(fine.e - fine.e0) <= 1e-4 && fabs(paper.tc - paper.tc0) <= 1e-3 * paper.tc0 &&
				      fabs(paper.e - paper.e0) <= 5e-3,
			      "t_c %.8e / %.8e (dt/16, paper dt) against %.8e; e %.8f / %.8f against %.8f", fine.tc, paper.tc,
			      fine.tc0, fine.e, paper.e, fine.e0);
			if (g == 0 && c->kj != KIND_WALL) {
				snprintf(id, sizeof id, "contact.hertz.%s.energy_conserved", c->name);
				CHECK(id, fine.ok && emax > 0 && emax <= 1e-6, "largest |E - E0| / E0 %.3e over the contact", emax);
			}
		}
	}
	return tl_done();
}
