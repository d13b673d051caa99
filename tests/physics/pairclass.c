/* pairclass.c - materials per pair of kinds (docs/model.md, "Materials per pair of
 * kinds"): a head-on collision of each pair class whose keys are set (mu_grain_wall,
 * gamma_n_grain_intruder, stiffness_..., given as scene keys through params_set) against
 * the analytic linear spring-dashpot solution for that class's coefficients, not the
 * grain-grain ones; a class's keys leave the other classes alone; and a wall of zero
 * friction gives an oblique impact no spin, the grains' own friction some.
 *
 * Relative motion as in collision.c: two mobile disks xi'' = -(Y xi + gN m_eff xi') / m_eff,
 * w0^2 = Y / m_eff, beta = gN / 2; a grain on a wall disk of infinite mass (wall_mass =
 * infinite: m_eff = m_i) the same with m_i. Tolerances as collision.c's at dt = 5e-5 / 4:
 * the contact time to 1e-4, the restitution to 2 beta dt (the force jump at the contact's
 * start; collision.c measures and explains it). The wrong class's coefficients (the
 * grain-grain ones) would miss the analytic values by far more: each case checks that
 * too, so that a table ignored fails. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "collision_analytic.h"
#include "forces.h"
#include "pclass.h"
#include "place.h"
#include "sim.h"
#include "step.h"
#include "testlib.h"
#include "two_disks.h"

static const double V0 = 50.0, DT = 5e-5 / 4;

typedef struct pcase {
	const char *name;
	int ki, kj;         /* kinds: j may be KIND_WALL (then i falls onto it) */
	double ri, rj;
	const char *keys[6]; /* key, value pairs of the class (NULL-terminated) */
	double Y, gn;        /* the coefficients the collision must show */
} pcase;

static const pcase CASES[] = {
	{"grain_wall", KIND_GRAIN, KIND_WALL, 1, 1, {"gamma_n_grain_wall", "300", "stiffness_grain_wall", "1e7", NULL},
	 1e7, 300},
	{"grain_intruder", KIND_GRAIN, KIND_INTRUDER, 1, 2,
	 {"gamma_n_grain_intruder", "20", "stiffness_grain_intruder", "6e6", NULL}, 6e6, 20},
	{"intruder_wall", KIND_INTRUDER, KIND_WALL, 2, 1, {"gamma_n_intruder_wall", "40", NULL}, 3e6, 40},
	{"intruder_intruder", KIND_INTRUDER, KIND_INTRUDER, 2, 2, {"stiffness_intruder_intruder", "1.2e7", NULL}, 1.2e7,
	 100},
	/* the grain_wall class's keys set, a grain pair collides: the grains' own law */
	{"grain_grain_beside_wall_keys", KIND_GRAIN, KIND_GRAIN, 1, 1,
	 {"gamma_n_grain_wall", "300", "stiffness_grain_wall", "1e7", NULL}, 3e6, 100},
};
#define NCASES (sizeof CASES / sizeof CASES[0])

typedef struct res {
	int ok;
	double e, tc, spin; /* measured; spin: i's angular velocity after an oblique impact */
	sb_pclass pc[SB_NPCLASS];
} res;

/* a sim of scene keys kv (pairs, NULL-terminated) and the defaults, gravity off,
 * wall_mass infinite; NULL on a setup error (printed) */
static sb_sim *make(const char *const *kv, sb_scene *sc)
{
	sb_err e = {0};
	params_defaults(sc);
	int bad = params_set(sc, "gravity", "0", "test", &e) || params_set(sc, "wall_mass", "infinite", "test", &e) ||
		  params_set(sc, "dt", "1.25e-05", "test", &e);
	for (; !bad && kv && *kv; kv += 2)
		bad = params_set(sc, kv[0], kv[1], "test", &e);
	sb_sim *s = calloc(1, sizeof *s);
	if (bad || sim_init(s, sc, &e)) {
		printf("# setup: %s\n", e.msg);
		free(s);
		return NULL;
	}
	return s;
}

/* i (kind ki, radius ri) meets j; oblique: i moves at 45 degrees onto a wall disk */
static res collide(const pcase *c, const char *const *kv, int oblique)
{
	res r = {0};
	sb_scene sc;
	sb_sim *s = make(kv, &sc);
	if (!s)
		return r;
	sb_err e = {0};
	const double rs = c->ri + c->rj;
	const int wall = c->kj == KIND_WALL;
	const double mi = place_mass(&sc, c->ri, c->ki), mj = place_mass(&sc, c->rj, c->kj);
	if (two_disks(&sc, s, c->ri, c->rj, c->ki, c->kj, &e)) {
		printf("# derive: %s\n", e.msg);
		goto out;
	}
	sb_state *st = &s->st;
	if (!wall) {
		st->q[C_X][1][0] = V0 * mj / (mi + mj) * DT;
		st->q[C_X][1][1] = -V0 * mi / (mi + mj) * DT;
	} else {
		st->q[C_Y][1][0] = -V0 * DT;
		if (oblique)
			st->q[C_X][1][0] = V0 * DT;
	}
	pclass_of_state(&s->law, &sc, st, r.pc);
	if (step_start(s, 0, &e))
		goto out;
	const double nx = wall ? 0 : -1, ny = wall ? 1 : 0;
#define XI() (rs - hypot(st->q[C_X][0][0] - st->q[C_X][0][1], st->q[C_Y][0][0] - st->q[C_Y][0][1]))
#define XID()                                                                                                   \
	(-(((st->q[C_X][1][0] - (wall ? 0 : st->q[C_X][1][1])) * nx + (st->q[C_Y][1][0] - (wall ? 0 : st->q[C_Y][1][1])) * ny) / DT))
	double xi0 = XI(), xid0 = XID();
	r.tc = NAN;
	for (long k = 1; k <= 20000; k++) {
		if (step_advance(s, 0, &e))
			goto out;
		const double xi1 = XI(), xid1 = XID();
		if (k > 1 && xi0 > 0 && xi1 <= 0) {
			r.tc = (k - 1) * DT + hermite_root(xi0, xid0, xi1, xid1, DT);
			break;
		}
		xi0 = xi1;
		xid0 = xid1;
	}
	for (int m = 0; m < 400; m++)
		if (step_advance(s, 0, &e))
			goto out;
	r.e = -XID() / V0;
	r.spin = st->q[C_TH][1][0] / DT;
	r.ok = isfinite(r.tc);
#undef XI
#undef XID
out:
	sim_free(s);
	free(s);
	return r;
}

int main(void)
{
	char id[160];
	for (size_t k = 0; k < NCASES; k++) {
		const pcase *c = &CASES[k];
		const res r = collide(c, c->keys, 0);
		snprintf(id, sizeof id, "pairclass.%s.completes", c->name);
		CHECK(id, r.ok, "the collision did not end within 20000 steps");
		if (!r.ok)
			continue;
		sb_scene def;
		params_defaults(&def);
		const double mi = place_mass(&def, c->ri, c->ki), mj = place_mass(&def, c->rj, c->kj);
		const double m = c->kj == KIND_WALL ? mi : mi * mj / (mi + mj);
		double tc0, e0, tcg, eg;
		collision_analytic(c->Y / m, 0.5 * c->gn, 0, V0, &tc0, &e0);
		collision_analytic(def.stiffness / m, 0.5 * def.gamma_n, 0, V0, &tcg, &eg);
		const double tol_e = 2 * 0.5 * c->gn * DT;
		printf("# %s: e %.8f (analytic %.8f; grain-grain law %.8f), t_c %.8e (analytic %.8e; grain-grain %.8e)\n",
		       c->name, r.e, e0, eg, r.tc, tc0, tcg);
		snprintf(id, sizeof id, "pairclass.%s.contact_time", c->name);
		CHECK(id, fabs(r.tc - tc0) <= 1e-4 * tc0, "t_c %.8e, the class's analytic %.8e", r.tc, tc0);
		snprintf(id, sizeof id, "pairclass.%s.restitution", c->name);
		CHECK(id, fabs(r.e - e0) <= tol_e * e0, "e %.8f, the class's analytic %.8f (tolerance %.2e)", r.e, e0, tol_e);
		/* the other direction: where the class differs from the grains' law, the
		 * measurement tells them apart (a table ignored would fail here) */
		if (c->Y != def.stiffness || c->gn != def.gamma_n) {
			snprintf(id, sizeof id, "pairclass.%s.not_the_grain_law", c->name);
			CHECK(id, fabs(r.tc - tcg) > 100 * 1e-4 * tcg || fabs(r.e - eg) > 100 * tol_e * eg,
			      "e %.8f and t_c %.8e are the grain-grain law's too (%.8f, %.8e)", r.e, r.tc, eg, tcg);
		}
		/* the recorded pair classes (run file, shake --contacts) show the class's e */
		const int pc = c->ki == KIND_GRAIN && c->kj == KIND_WALL ? 2 : c->ki == KIND_GRAIN && c->kj == KIND_INTRUDER ? 1
										       : c->ki == KIND_GRAIN ? 0 : -1;
		if (pc >= 0) {
			snprintf(id, sizeof id, "pairclass.%s.recorded_restitution", c->name);
			CHECK(id, r.pc[pc].present && fabs(r.pc[pc].e - e0) <= 1e-9 * e0, "recorded %s e %.10f, analytic %.10f",
			      r.pc[pc].name, r.pc[pc].e, e0);
		}
	}
	/* friction per class: an oblique grain on a wall disk spins by the tangential
	 * force alone; mu_grain_wall = 0 leaves it none, the grains' mu = 0.5 some */
	const pcase *gw = &CASES[0];
	const char *const nofric[] = {"mu_grain_wall", "0", NULL};
	const char *const grains_mu0[] = {"mu", "0", "mu_grain_wall", "0.5", NULL};
	const res r0 = collide(gw, nofric, 1), r1 = collide(gw, NULL, 1), r2 = collide(gw, grains_mu0, 1);
	printf("# oblique grain on a wall: spin %.6g (mu_grain_wall 0), %.6g (same as mu 0.5), %.6g (mu 0, "
	       "mu_grain_wall 0.5) rad/s\n", r0.spin, r1.spin, r2.spin);
	CHECK("pairclass.friction.wall_mu0_no_spin", r0.ok && r0.spin == 0, "spin %g rad/s", r0.spin);
	CHECK("pairclass.friction.same_mu_spins", r1.ok && fabs(r1.spin) > 1e-3, "spin %g rad/s", r1.spin);
	CHECK("pairclass.friction.wall_mu_own_spins", r2.ok && r2.spin == r1.spin, "spin %g rad/s, with mu 0.5 %g",
	      r2.spin, r1.spin);
	return tl_done();
}
