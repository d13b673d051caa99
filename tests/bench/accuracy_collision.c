/* accuracy_collision.c - run time against error of every integrator on single
 * two-disk collisions: restitution coefficient and contact
 * duration against the analytic linear spring-dashpot solution (head-on) or against
 * a gear5 run at dt = 1e-7 s (oblique, where the rotating contact normal and the
 * shear force make the 1D solution only approximate), for dt from 1e-5 s up to
 * breakdown. Prints one TSV row per (integrator, dt, case).
 *
 * The analytic solution and the measuring method are those of tests/physics/collision.c
 * (read its header comment): xi'' = -w0^2 xi - 2 beta xi' with w0^2 = Y / m_eff
 * (disk-disk, beta = gN/2) or Y / m_i (disk on an immobile wall disk,
 * 2 beta = gN m_eff / m_i); unclipped contact t_c = pi / w, e = exp(-beta pi / w),
 * w = sqrt(w0^2 - beta^2). The contact end is found by cubic Hermite interpolation of
 * xi between the two steps that bracket xi = 0; e is the relative velocity along the
 * normal at separation, read 400 steps later (the Gear corrector needs a few steps to
 * flush its higher derivatives after the force jumps to zero).
 *
 * Wall time: the integration loop of the contact itself (first step to separation),
 * repeated until 20 ms have been spent, per collision. For two disks this is mostly
 * the fixed per-step overhead, so the paper-scene columns of the bench are the
 * cost that matters; here the step count (steps per contact) is the honest measure. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "collision_analytic.h"
#include "place.h"
#include "sim.h"
#include "step.h"
#include "units.h"

typedef struct ccase {
	const char *name;
	int wall;        /* j is an immobile wall disk */
	double tan_v;    /* tangential / normal approach speed (0 = head-on) */
} ccase;

typedef struct cres {
	double tc, e, et; /* duration, normal restitution, tangential relative speed after / V0 */
	double tc0, e0;   /* analytic (1D) */
	long steps;       /* steps of the contact */
	double sec;       /* wall time of one contact */
	int ok;           /* 0 = blew up / contact never ended */
} cres;

static const double V0 = 50.0; /* cm/s, normal approach speed (a grain falling ~1.3 cm) */

static double now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}


/* xi, xi' and the unit normal n = (r_i - r_j)/d; relative velocity of surfaces along t */
typedef struct kin {
	double xi, xid, nx, ny, vt;
} kin;

static kin measure(const sb_state *st, double rs, int wall, double dt)
{
	kin k;
	double dx = st->q[C_X][0][0] - st->q[C_X][0][1], dy = st->q[C_Y][0][0] - st->q[C_Y][0][1];
	double d = hypot(dx, dy);
	k.nx = dx / d;
	k.ny = dy / d;
	k.xi = rs - d;
	double vx = (st->q[C_X][1][0] - (wall ? 0 : st->q[C_X][1][1])) / dt;
	double vy = (st->q[C_Y][1][0] - (wall ? 0 : st->q[C_Y][1][1])) / dt;
	k.xid = -(vx * k.nx + vy * k.ny);
	double w = (st->q[C_TH][1][0] * st->r[0] + (wall ? 0 : st->q[C_TH][1][1] * st->r[1])) / dt;
	k.vt = vx * -k.ny + vy * k.nx - w;
	return k;
}

static cres run_once(const ccase *c, int integ, double dt, int timed)
{
	cres res = {0};
	sb_scene sc;
	params_defaults(&sc);
	sc.gravity = 0;
	sc.integrator = integ;
	sc.dt = dt;
	sc.max_overlap = 1.0;
	sb_sim *s = calloc(1, sizeof *s);
	sb_err e = {0};
	const double ri = 1, rj = 1, rs = ri + rj;
	const int wall = c->wall;
	double mi = place_mass(&sc, ri, KIND_GRAIN), mj = place_mass(&sc, rj, KIND_GRAIN);
	double w02, beta;
	if (sim_init(s, &sc, &e))
		goto out;
	if (!wall) {
		/* i at the origin, j touching on its right; zero total momentum */
		place_push(&sc, &s->st, 0, 0, ri, KIND_GRAIN, &e);
		place_push(&sc, &s->st, rs, 0, rj, KIND_GRAIN, &e);
	} else {
		/* i on top of the wall disk j at the origin; two far wall disks make the box */
		place_push(&sc, &s->st, 0, rs, ri, KIND_GRAIN, &e);
		place_push(&sc, &s->st, 0, 0, rj, KIND_WALL, &e);
		place_push(&sc, &s->st, -60, 0, rj, KIND_WALL, &e);
		place_push(&sc, &s->st, 60, 0, rj, KIND_WALL, &e);
	}
	if (sim_derive(s, &e))
		goto out;
	sb_state *st = &s->st;
	if (!wall) {
		double meff = mi * mj / (mi + mj);
		/* relative velocity (V0 along +x into j, tan_v V0 along y) */
		double vrx = V0, vry = c->tan_v * V0;
		st->q[C_X][1][0] = vrx * mj / (mi + mj) * dt;
		st->q[C_Y][1][0] = vry * mj / (mi + mj) * dt;
		st->q[C_X][1][1] = -vrx * mi / (mi + mj) * dt;
		st->q[C_Y][1][1] = -vry * mi / (mi + mj) * dt;
		w02 = sc.stiffness / meff;
		beta = 0.5 * sc.gamma_n;
	} else {
		double meff = mi * mj / (mi + mj);
		st->q[C_Y][1][0] = -V0 * dt;
		st->q[C_X][1][0] = c->tan_v * V0 * dt;
		w02 = sc.stiffness / mi;
		beta = 0.5 * sc.gamma_n * meff / mi;
	}
	collision_analytic(w02, beta, 0, V0, &res.tc0, &res.e0);
	if (step_start(s, 0, &e))
		goto out;
	kin k0 = measure(st, rs, wall, dt);
	long maxn = (long)(10 * res.tc0 / dt) + 10, k;
	res.tc = NAN;
	double t0 = timed ? now() : 0;
	for (k = 1; k <= maxn; k++) {
		if (step_advance(s, 0, &e))
			goto out;
		kin k1 = measure(st, rs, wall, dt);
		if (k > 1 && k0.xi > 0 && k1.xi <= 0) {
			res.tc = (k - 1) * dt + hermite_root(k0.xi, k0.xid, k1.xi, k1.xid, dt);
			k0 = k1;
			break;
		}
		k0 = k1;
	}
	res.sec = timed ? now() - t0 : 0;
	res.steps = k;
	if (!isfinite(res.tc))
		goto out;
	for (int m = 0; m < 400; m++)
		if (step_advance(s, 0, &e))
			goto out;
	{
		/* velocities along the separation normal (free flight: constant) */
		double vx = (st->q[C_X][1][0] - (wall ? 0 : st->q[C_X][1][1])) / dt;
		double vy = (st->q[C_Y][1][0] - (wall ? 0 : st->q[C_Y][1][1])) / dt;
		double w = (st->q[C_TH][1][0] * ri + (wall ? 0 : st->q[C_TH][1][1] * rj)) / dt;
		res.e = (vx * k0.nx + vy * k0.ny) / V0;
		res.et = (vx * -k0.ny + vy * k0.nx - w) / V0;
		res.ok = isfinite(res.e) && isfinite(res.et) && res.e > 0 && res.e < 1.5;
	}
out:
	sim_free(s);
	free(s);
	return res;
}

static cres run(const ccase *c, int integ, double dt)
{
	cres r = run_once(c, integ, dt, 1);
	if (!r.ok)
		return r;
	double tot = r.sec;
	int n = 1;
	while (tot < 0.02 && n < 100000) {
		cres q = run_once(c, integ, dt, 1);
		tot += q.sec;
		n++;
	}
	r.sec = tot / n;
	return r;
}

static const ccase CASES[] = {
	{"disk_disk_head_on", 0, 0.0},
	{"disk_disk_oblique", 0, 1.0},  /* 45 degrees */
	{"disk_wall_head_on", 1, 0.0},
	{"disk_wall_oblique", 1, 1.0},
};
#define NCASES (int)(sizeof CASES / sizeof CASES[0])

static const char *INAME[] = {"gear5", "gear4", "verlet"};

int main(int argc, char **argv)
{
	/* dt ladder from 1e-5 s to beyond breakdown (t_c = 3.3 ms for two unit disks) */
	static const double DTS[] = {1e-5, 2e-5, 3e-5, 5e-5, 7e-5, 1e-4, 1.5e-4, 2e-4, 3e-4,
				     5e-4, 7e-4, 1e-3, 1.5e-3, 2e-3, 3e-3};
	int ndt = (int)(sizeof DTS / sizeof DTS[0]);
	if (argc > 1 && !strcmp(argv[1], "quick"))
		ndt = 10;
	cres ref[NCASES];
	for (int c = 0; c < NCASES; c++)
		ref[c] = run_once(&CASES[c], INTEG_GEAR5, 1e-7, 0);
	printf("# reference (gear5, dt 1e-7):");
	for (int c = 0; c < NCASES; c++)
		printf(" %s e=%.9f tc=%.9e et=%.6f (analytic e=%.9f tc=%.9e);", CASES[c].name, ref[c].e,
		       ref[c].tc, ref[c].et, ref[c].e0, ref[c].tc0);
	printf("\n");
	printf("integrator\tdt\tcase\tsteps_per_contact\twall_us\te\te_ref\ttc\ttc_ref\trel_err_e\trel_err_tc\terr_et\tstatus\n");
	for (int in = 0; in < 3; in++)
		for (int d = 0; d < ndt; d++)
			for (int c = 0; c < NCASES; c++) {
				const ccase *cc = &CASES[c];
				cres r = run(cc, in, DTS[d]);
				/* head-on: the analytic value; oblique: the fine gear5 run */
				double eref = cc->tan_v == 0 ? r.e0 : ref[c].e;
				double tref = cc->tan_v == 0 ? r.tc0 : ref[c].tc;
				double ee = (r.e - eref) / eref, et = (r.tc - tref) / tref;
				double ev = cc->tan_v == 0 ? 0 : r.et - ref[c].et;
				printf("%s\t%g\t%s\t%ld\t%.3f\t%.9f\t%.9f\t%.9e\t%.9e\t%.3e\t%.3e\t%.3e\t%s\n", INAME[in],
				       DTS[d], cc->name, r.steps, r.sec * 1e6, r.ok ? r.e : NAN, eref,
				       r.ok ? r.tc : NAN, tref, r.ok ? fabs(ee) : NAN, r.ok ? fabs(et) : NAN,
				       r.ok ? fabs(ev) : NAN, r.ok ? "ok" : "broken");
				fflush(stdout);
			}
	return 0;
}
