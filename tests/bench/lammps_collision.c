/* lammps_collision.c - the engine's side of tests/bench/lammps_collisions.sh: one
 * two-disk collision with the engine's own force and integration code (verlet, as
 * LAMMPS's nve/sphere), printing the trajectory of both disks at the end of every step
 * in the columns of the LAMMPS side's dump, so that one analysis measures both codes.
 *
 * usage: lammps_collision LAW CASE DT [KEY=VALUE ...]
 *   LAW  hooke | restitution | hertz  (docs/model.md "Contact law", "Normal law", "Restitution"),
 *        spring | hertz_spring: hooke or hertz with tangential = spring ("Tangential law")
 *   CASE equal    two unit disks head-on
 *        intruder a unit grain head-on against the intruder of radius 4
 *        oblique  two unit disks, impact parameter (R_i + R_j)/2, no spin before
 *        wall     a unit grain onto a fixed wall disk of radius 1 (wall_mass = disk)
 *        glancing the same with a tangential speed V/2 along x: the rebound spin
 *   KEY  gamma_n, gamma_s, mu, stiffness, hertz_stiffness, restitution, shear_stiffness: override the law's
 *        value (the script's check that a change on one side is caught).
 * Gravity is off; the relative approach speed is V = 50 cm/s along x (along -y onto the
 * wall), the disks start GAP apart. Output: "step x0 y0 vx0 vy0 w0 x1 y1 vx1 vy1 w1". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dtguard.h"
#include "params.h"
#include "place.h"
#include "sim.h"
#include "step.h"

static const double V = 50.0, GAP = 0.01, T_END = 0.012; /* cm/s, cm, s */

static int fail(const char *m)
{
	fprintf(stderr, "lammps_collision: %s\n", m);
	return 1;
}

int main(int argc, char **argv)
{
	if (argc < 4)
		return fail("usage: lammps_collision hooke|restitution|hertz|spring|hertz_spring "
			    "equal|intruder|oblique|wall|glancing DT [KEY=VALUE...]");
	sb_scene sc;
	params_defaults(&sc);
	sc.gravity = 0;
	sc.integrator = INTEG_VERLET;
	char *end;
	sc.dt = strtod(argv[3], &end);
	if (*end)
		return fail("DT is not a number");
	sc.max_overlap = 1.0;
	sc.dt_guard = 2;
	if (!(sc.dt > 0))
		return fail("DT must be > 0");
	if (!strcmp(argv[1], "restitution"))
		sc.restitution = 0.8;
	else if (!strcmp(argv[1], "hertz") || !strcmp(argv[1], "hertz_spring"))
		sc.normal = NORMAL_HERTZ;
	else if (strcmp(argv[1], "hooke") && strcmp(argv[1], "spring"))
		return fail("LAW must be hooke, restitution, hertz, spring or hertz_spring");
	if (strstr(argv[1], "spring"))
		sc.tangential = TANGENTIAL_SPRING;
	const char *cs = argv[2];
	const int glance = !strcmp(cs, "glancing"), wall = glance || !strcmp(cs, "wall"), intr = !strcmp(cs, "intruder"),
		  obl = !strcmp(cs, "oblique");
	if (!wall && !intr && !obl && strcmp(cs, "equal"))
		return fail("CASE must be equal, intruder, oblique, wall or glancing");
	const double vx_wall = glance ? 0.5 * V : 0; /* the grain's speed along the wall */
	double r0 = 1, r1 = intr ? 4 : 1, rs = r0 + r1;
	int k1 = intr ? KIND_INTRUDER : wall ? KIND_WALL : KIND_GRAIN;
	double m0 = place_mass(&sc, r0, KIND_GRAIN), m1 = place_mass(&sc, r1, k1);
	/* the law and the disks before any override: what the LAMMPS side is given */
	printf("# stiffness=%.17g gamma_n=%.17g gamma_s=%.17g mu=%.17g hertz_stiffness=%.17g restitution=%.17g"
	       " shear_stiffness=%.17g r0=%.17g r1=%.17g m0=%.17g m1=%.17g wall=%d gap=%.17g v=%.17g vx_wall=%.17g\n",
	       sc.stiffness, sc.gamma_n, sc.gamma_s, sc.mu, sc.hertz_stiffness, sc.restitution, dtguard_kt(&sc), r0, r1,
	       m0, m1, wall, GAP, V, vx_wall);
	for (int a = 4; a < argc; a++) {
		const char *eq = strchr(argv[a], '=');
		double *p = NULL;
		if (eq) {
			size_t n = (size_t)(eq - argv[a]);
			static const char *K[] = {"gamma_n",	 "gamma_s",	"mu", "stiffness", "hertz_stiffness",
						  "restitution", "shear_stiffness"};
			double *P[] = {&sc.gamma_n,	    &sc.gamma_s,     &sc.mu,
				       &sc.stiffness,	    &sc.hertz_stiffness, &sc.restitution,
				       &sc.shear_stiffness};
			for (int k = 0; k < 7; k++)
				if (strlen(K[k]) == n && !strncmp(argv[a], K[k], n))
					p = P[k];
		}
		if (!p)
			return fail("unknown KEY=VALUE argument (keys: gamma_n gamma_s mu stiffness hertz_stiffness restitution "
				    "shear_stiffness)");
		*p = strtod(eq + 1, &end);
		if (!eq[1] || *end)
			return fail("a KEY=VALUE argument's value is not a number");
	}
	sb_sim *s = calloc(1, sizeof *s);
	sb_err e = {0};
	if (!s || sim_init(s, &sc, &e))
		return fail("sim_init failed");
	if (wall) {
		/* the grain above the wall disk at the origin; two far wall disks make the box */
		place_push(&sc, &s->st, 0, rs + GAP, r0, KIND_GRAIN, &e);
		place_push(&sc, &s->st, 0, 0, r1, KIND_WALL, &e);
		place_push(&sc, &s->st, -60, 0, 1, KIND_WALL, &e);
		place_push(&sc, &s->st, 60, 0, 1, KIND_WALL, &e);
	} else {
		/* disk 1 to the right of disk 0, offset by the impact parameter b in y */
		double b = obl ? 0.5 * rs : 0;
		place_push(&sc, &s->st, 0, 0, r0, KIND_GRAIN, &e);
		place_push(&sc, &s->st, sqrt((rs + GAP) * (rs + GAP) - b * b), -b, r1, k1, &e);
	}
	if (e.code || sim_derive(s, &e))
		return fail("placing the disks failed");
	sb_state *st = &s->st;
	double dt = sc.dt;
	if (wall) {
		st->q[C_Y][1][0] = -V * dt;
		st->q[C_X][1][0] = vx_wall * dt;
	} else {
		/* zero total momentum */
		st->q[C_X][1][0] = V * m1 / (m0 + m1) * dt;
		st->q[C_X][1][1] = -V * m0 / (m0 + m1) * dt;
	}
	if (step_start(s, 0, &e))
		return fail("step_start failed");
	long n = (long)(T_END / dt + 0.5);
	for (long k = 0; k <= n; k++) {
		if (k && step_advance(s, 0, &e))
			return fail("step_advance failed");
		printf("%ld", k);
		for (int i = 0; i < 2; i++) {
			int mob = !(wall && i == 1);
			printf(" %.17g %.17g %.17g %.17g %.17g", st->q[C_X][0][i], st->q[C_Y][0][i],
			       mob ? st->q[C_X][1][i] / dt : 0.0, mob ? st->q[C_Y][1][i] / dt : 0.0,
			       mob ? st->q[C_TH][1][i] / dt : 0.0);
		}
		printf("\n");
	}
	sim_free(s);
	free(s);
	return 0;
}
