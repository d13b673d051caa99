/* periodic.c - periodic side boundaries (docs/model.md, "Periodic side boundaries").
 *
 * (a) Two disks touching across the seam (x = 0 / W) feel the forces and torques of
 *     the same pair placed in the middle of the box, to the bit, equal and opposite;
 *     the seam list holds exactly the pairs a brute-force search over the images
 *     finds (a crowded box with a large disk on the seam).
 * (b) A disk moving horizontally through the seam over a bottom row of wall disks
 *     keeps its velocity exactly and ends at the wrapped position of free flight;
 *     nothing stops it there (no wall, no "left the box").
 * (c) A dense periodic gas without gravity and walls, friction on, many seam
 *     crossings and seam contacts: total momentum is conserved to round-off; without
 *     damping or friction kinetic + elastic energy is conserved (the seam contacts'
 *     elastic energy counted); the fused steps give the reference steps' bits.
 * (d) The observables through the seam: a disk crossing it between two samples adds
 *     its minimum-image displacement to the cell at the seam; a grain on the other
 *     side of the seam is in a ring whose centre is near x = 0.
 * The walls case's bits are held by tests/integration/regression.sh. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "observe.h"
#include "periodic.h"
#include "place.h"
#include "sample.h"
#include "sim.h"
#include "simtest.h"
#include "step.h"
#include "testlib.h"

static sb_scene periodic_scene(double W)
{
	sb_scene sc;
	params_defaults(&sc);
	sc.sides = SIDES_PERIODIC;
	sc.width = W;
	return sc;
}

/* A pair of disks at x0 and x1 (y = 5), with velocities and spins, and the forces of
 * step_start into f[6] (fx, fy, torque of disk 0, then of disk 1). law: bit 0, the
 * second disk an intruder with a grain-intruder material of its own (a table of
 * materials); bit 1, tangential = spring. */
static int pair_forces_law(double W, double x0, double x1, double f[6], int law)
{
	sb_scene sc = periodic_scene(W);
	if (law & 1) {
		sc.mu_grain_intruder = 0.2;
		sc.stiffness_grain_intruder = 2 * sc.stiffness;
	}
	if (law & 2)
		sc.tangential = TANGENTIAL_SPRING;
	sb_sim *s = new_sim(&sc);
	sb_err e = {0};
	place_push(&sc, &s->st, x0, 5, 1, KIND_GRAIN, &e);
	place_push(&sc, &s->st, x1, 5.25, 0.75, law & 1 ? KIND_INTRUDER : KIND_GRAIN, &e);
	int ok = !e.code && !sim_derive(s, &e);
	if (ok) {
		sb_state *st = &s->st;
		const double dt = sc.dt;
		st->q[C_X][1][0] = 30 * dt;
		st->q[C_Y][1][0] = -4 * dt;
		st->q[C_TH][1][0] = 7 * dt;
		st->q[C_X][1][1] = -12.5 * dt;
		st->q[C_Y][1][1] = 2 * dt;
		st->q[C_TH][1][1] = -3 * dt;
		ok = !step_start(s, 0, &e);
		for (int c = 0; c < 3 && ok; c++) {
			f[c] = st->f[c][0];
			f[3 + c] = st->f[c][1];
		}
	}
	if (!ok)
		printf("# pair setup failed: %s\n", e.msg);
	del_sim(s);
	return ok;
}

static int pair_forces(double W, double x0, double x1, double f[6])
{
	return pair_forces_law(W, x0, x1, f, 0);
}

/* The same with a table of materials and with the shear spring: the seam pair's law
 * (forces_seam) is the flat list's (the vector kernel's instances), the pair's own
 * coefficients included */
static void seam_pair_laws(void)
{
	const double W = 20;
	double plain[6];
	int ok = pair_forces_law(W, 10.5, 9.25, plain, 0);
	const char *const name[4] = {"", "table", "spring", "table_spring"};
	for (int law = 1; law < 4; law++) {
		double mid[6], seam[6];
		ok = ok && pair_forces_law(W, 0.5, W - 0.75, seam, law) && pair_forces_law(W, 10.5, 9.25, mid, law);
		char id[80];
		snprintf(id, sizeof id, "periodic.seam_pair.%s.setup", name[law]);
		CHECK(id, ok, "see above");
		if (!ok)
			return;
		snprintf(id, sizeof id, "periodic.seam_pair.%s.law_changes_forces", name[law]);
		CHECK(id, memcmp(mid, plain, sizeof mid) != 0, "the %s law gave the plain law's forces", name[law]);
		snprintf(id, sizeof id, "periodic.seam_pair.%s.same_as_middle", name[law]);
		CHECK(id, !memcmp(mid, seam, sizeof mid), "seam F0 (%.17g, %.17g, %.17g) vs middle (%.17g, %.17g, %.17g)",
		      seam[0], seam[1], seam[2], mid[0], mid[1], mid[2]);
	}
}

static void seam_pair(void)
{
	const double W = 20;
	double mid[6], seam[6], mid2[6], seam2[6];
	/* the same relative geometry: x0 - x1 = 1.25 through the seam and in the middle;
	 * the numbers are exact in binary, so the distances are the same doubles */
	int ok = pair_forces(W, 0.5, W - 0.75, seam) && pair_forces(W, 10.5, 9.25, mid);
	/* and with the disks' order the other way round the seam (disk 0 on the right) */
	ok = ok && pair_forces(W, W - 0.75, 0.5, seam2) && pair_forces(W, 9.25, 10.5, mid2);
	CHECK("periodic.seam_pair.setup", ok, "see above");
	if (!ok)
		return;
	printf("# middle: F0 = (%.17g, %.17g) tau0 %.17g; seam: F0 = (%.17g, %.17g) tau0 %.17g\n", mid[0], mid[1],
	       mid[2], seam[0], seam[1], seam[2]);
	CHECK("periodic.seam_pair.touching", mid[0] != 0 && mid[1] != 0 && mid[2] != 0, "no force in the middle");
	CHECK("periodic.seam_pair.same_as_middle", !memcmp(mid, seam, sizeof mid),
	      "seam F0 (%.17g, %.17g, %.17g) F1 (%.17g, %.17g, %.17g) vs middle (%.17g, %.17g, %.17g) (%.17g, %.17g, %.17g)",
	      seam[0], seam[1], seam[2], seam[3], seam[4], seam[5], mid[0], mid[1], mid[2], mid[3], mid[4], mid[5]);
	CHECK("periodic.seam_pair.same_as_middle_reversed", !memcmp(mid2, seam2, sizeof mid2),
	      "seam F0 (%.17g, %.17g) vs middle (%.17g, %.17g)", seam2[0], seam2[1], mid2[0], mid2[1]);
	CHECK("periodic.seam_pair.equal_and_opposite",
	      seam[0] == -seam[3] && seam[1] == -seam[4] && seam2[0] == -seam2[3] && seam2[1] == -seam2[4],
	      "F0 (%.17g, %.17g) F1 (%.17g, %.17g)", seam[0], seam[1], seam[3], seam[4]);
	/* the pair is pushed apart through the seam: disk 0 (at x = 0.5) to +x */
	CHECK("periodic.seam_pair.pushes_apart", seam[0] > 0 && seam2[0] < 0, "F0x %.6g, reversed %.6g", seam[0],
	      seam2[0]);
}

static int cmp_pair(const void *a, const void *b)
{
	const int *p = a, *q = b;
	return p[0] != q[0] ? (p[0] > q[0]) - (p[0] < q[0]) : (p[1] > q[1]) - (p[1] < q[1]);
}

/* The seam list against a brute-force search of the images: a crowded box of random
 * grains (overlaps allowed, it is only a list), a bottom row of walls, a large disk
 * across the seam. */
static void seam_list(void)
{
	const double W = 16;
	sb_scene sc = periodic_scene(W);
	sb_sim *s = new_sim(&sc);
	sb_err e = {0};
	srand(7);
	place_push(&sc, &s->st, 0.7, 6, 3.4, KIND_INTRUDER, &e); /* reaches across x = 0 */
	for (int k = 0; k < 120; k++) {
		const double x = W * rand() / ((double)RAND_MAX + 1), y = 15.0 * rand() / ((double)RAND_MAX + 1);
		place_push(&sc, &s->st, x, y, 0.85 + 0.3 * rand() / RAND_MAX, KIND_GRAIN, &e);
	}
	for (int k = 0; k < 8; k++)
		place_push(&sc, &s->st, W * (k + 0.5) / 8, -1, 1, KIND_WALL, &e);
	int ok = !e.code && !sim_derive(s, &e) && !nlist_build(&s->nl, &s->st, &e);
	CHECK("periodic.seam_list.setup", ok, "%s", e.msg);
	if (!ok) {
		del_sim(s);
		return;
	}
	const long cap = 100000;
	int *bi = malloc(sizeof(int) * cap), *bj = malloc(sizeof(int) * cap);
	const long nb = nlist_brute_seam(&s->st, sc.skin, W, bi, bj, cap);
	int *got = malloc(sizeof(int) * 2 * (size_t)(s->nl.nseam + 1)), *want = malloc(sizeof(int) * 2 * (size_t)(nb + 1));
	for (int k = 0; k < s->nl.nseam; k++) {
		got[2 * k] = s->nl.si[k];
		got[2 * k + 1] = s->nl.sj[k];
	}
	for (long k = 0; k < nb; k++) {
		want[2 * k] = bi[k];
		want[2 * k + 1] = bj[k];
	}
	qsort(got, (size_t)s->nl.nseam, 2 * sizeof(int), cmp_pair);
	qsort(want, (size_t)nb, 2 * sizeof(int), cmp_pair);
	int large = 0;
	for (long k = 0; k < nb; k++)
		large += want[2 * k] == 0 || want[2 * k + 1] == 0;
	printf("# %d seam pairs listed, %ld found by brute force, %d with the large disk\n", s->nl.nseam, nb, large);
	CHECK("periodic.seam_list.has_pairs", nb > 10 && large > 3, "%ld pairs, %d with the large disk", nb, large);
	CHECK("periodic.seam_list.equals_brute_force",
	      s->nl.nseam == nb && !memcmp(got, want, sizeof(int) * 2 * (size_t)nb), "%d listed vs %ld", s->nl.nseam,
	      nb);
	/* and the flat list is the plain one (no image there) */
	const long nflat = nlist_brute(&s->st, sc.skin, NULL, NULL, 0);
	CHECK("periodic.seam_list.flat_list_unchanged", nflat == s->nl.nflat, "%d vs %ld", s->nl.nflat, nflat);
	free(bi);
	free(bj);
	free(got);
	free(want);
	del_sim(s);
}

/* (b) */
static void crossing(void)
{
	const double W = 20, v = 150; /* 8 crossings in 1 s */
	sb_scene sc = periodic_scene(W);
	sb_sim *s = new_sim(&sc);
	sb_err e = {0};
	const double x0 = W - 3;
	place_push(&sc, &s->st, x0, 4, 1, KIND_GRAIN, &e);
	for (int k = 0; k < 10; k++)
		place_push(&sc, &s->st, W * (k + 0.5) / 10, -1, 1, KIND_WALL, &e);
	int ok = !e.code && !sim_derive(s, &e);
	const double dt = sc.dt;
	const long n = lround(1.0 / dt);
	if (ok) {
		s->st.q[C_X][1][0] = v * dt;
		ok = !step_start(s, 0, &e);
	}
	int wraps = 0;
	double xmin = INFINITY, xmax = -INFINITY, xprev = x0;
	/* fused steps (the run loop's), the last one a reference step so the state is read */
	for (long k = 1; k <= n && ok; k++) {
		ok = !step_once(s, k, 0, 0, k < n, NULL, &e);
		if (k == n || !(k % 50)) {
			kernel_sync(s->kern, &s->st);
			const double x = s->st.q[C_X][0][0];
			wraps += x < xprev - 0.5 * W;
			xprev = x;
			xmin = fmin(xmin, x);
			xmax = fmax(xmax, x);
		}
	}
	CHECK("periodic.crossing.runs", ok, "%s", e.msg);
	const sb_state *st = &s->st;
	const double x = st->q[C_X][0][0], want = fmod(x0 + v * n * dt, W);
	printf("# after 1 s: x %.12g (free flight, wrapped: %.12g), vx %.17g, %d wraps, x in [%.4g, %.4g]\n", x, want,
	       st->q[C_X][1][0] / dt, wraps, xmin, xmax);
	CHECK("periodic.crossing.keeps_velocity", st->q[C_X][1][0] == v * dt && st->q[C_Y][1][0] == 0,
	      "vx %.17g vy %.17g (want %.17g, 0)", st->q[C_X][1][0] / dt, st->q[C_Y][1][0] / dt, v);
	CHECK("periodic.crossing.wrapped_position", fabs(periodic_image(x - want, W)) < 1e-9 && x > -sc.skin &&
									 x < W + sc.skin,
	      "x %.15g, want %.15g", x, want);
	const int nwrap = (int)floor((x0 + v * n * dt) / W);
	CHECK("periodic.crossing.crossed_the_seam", wraps == nwrap, "%d wraps (%d expected)", wraps, nwrap);
	CHECK("periodic.crossing.stays_in_period", xmin > -sc.skin && xmax < W + sc.skin,
	      "x in [%g, %g]: beyond a skin of [0, %g)", xmin, xmax, W);
	del_sim(s);
}

/* (c): a dense gas, n grains at random in [0, W) x [0, H), random velocities */
static sb_sim *gas(double W, double mu, double gn, double gs, int n)
{
	sb_scene sc = periodic_scene(W);
	sc.mu = mu;
	sc.gamma_n = gn;
	sc.gamma_s = gs;
	sb_sim *s = new_sim(&sc);
	sb_err e = {0};
	srand(3);
	const int cols = (int)(W / 2.4);
	for (int k = 0; k < n; k++) { /* a loose lattice, so that nobody starts deep inside another */
		const double x = 2.4 * (k % cols) + 1.2, y = 2.4 * (k / cols) + 1.2;
		place_push(&sc, &s->st, x, y, 0.85 + 0.3 * rand() / RAND_MAX, KIND_GRAIN, &e);
	}
	if (e.code || sim_derive(s, &e)) {
		printf("# gas setup failed: %s\n", e.msg);
		del_sim(s);
		return NULL;
	}
	for (int i = 0; i < s->st.nm; i++) {
		s->st.q[C_X][1][i] = (200.0 * rand() / RAND_MAX - 100) * sc.dt;
		s->st.q[C_Y][1][i] = (200.0 * rand() / RAND_MAX - 100) * sc.dt;
		s->st.q[C_TH][1][i] = (20.0 * rand() / RAND_MAX - 10) * sc.dt;
	}
	return s;
}

static void momentum(const sb_sim *s, double p[3])
{
	p[0] = p[1] = p[2] = 0;
	for (int i = 0; i < s->st.nm; i++) {
		p[0] += s->st.m[i] * s->st.q[C_X][1][i] / s->sc.dt;
		p[1] += s->st.m[i] * s->st.q[C_Y][1][i] / s->sc.dt;
		p[2] += s->st.m[i] * fabs(s->st.q[C_X][1][i]) / s->sc.dt; /* the scale of round-off */
	}
}

static double energy(sb_sim *s)
{
	double el, ov;
	long nc;
	forces_contact_energy(&s->law, &s->st, &s->nl, kernel_shear(s->kern), &el, &ov, &nc);
	return sim_kinetic(s) + el;
}

/* Run n steps (fused where fuse), counting wraps of disk positions and steps with a
 * seam contact. */
static int run_gas(sb_sim *s, long n, int fuse, int *wraps, long *seam_contacts, double *emax_dev, sb_err *e)
{
	const double W = s->sc.width;
	double *xp = malloc(sizeof(double) * (size_t)s->st.nm);
	memcpy(xp, s->st.q[C_X][0], sizeof(double) * (size_t)s->st.nm);
	const double e0 = emax_dev ? energy(s) : 0;
	int ok = 1;
	for (long k = 1; k <= n && ok; k++) {
		const int f = fuse && k < n && k % 100;
		ok = !step_once(s, k, 0, 0, f, NULL, e);
		if (f)
			continue;
		kernel_sync(s->kern, &s->st);
		const sb_state *st = &s->st;
		for (int i = 0; i < st->nm; i++) {
			*wraps += fabs(st->q[C_X][0][i] - xp[i]) > 0.5 * W;
			xp[i] = st->q[C_X][0][i];
		}
		for (int p = 0; p < s->nl.nseam; p++) {
			const int i = s->nl.si[p], j = s->nl.sj[p];
			*seam_contacts += hypot(st->q[C_X][0][i] + W - st->q[C_X][0][j], st->q[C_Y][0][i] - st->q[C_Y][0][j]) <
					  st->r[i] + st->r[j];
		}
		if (emax_dev)
			*emax_dev = fmax(*emax_dev, fabs(energy(s) - e0) / e0);
	}
	free(xp);
	return ok;
}

static void conservation(void)
{
	const double W = 12;
	sb_err e = {0};
	/* momentum with friction and damping: every force acts on two disks oppositely */
	sb_sim *s = gas(W, 0.5, 100, 1, 40);
	int ok = s && !step_start(s, 0, &e);
	double p0[3], p1[3];
	int wraps = 0;
	long seam = 0;
	if (ok) {
		momentum(s, p0);
		ok = run_gas(s, lround(1.0 / s->sc.dt), 1, &wraps, &seam, NULL, &e);
		momentum(s, p1);
	}
	CHECK("periodic.momentum.runs", ok, "%s", e.msg);
	if (ok) {
		printf("# momentum (%.10g, %.10g) -> (%.10g, %.10g), scale %.4g; %d seam crossings, %ld seam contacts (checked every 100 steps)\n",
		       p0[0], p0[1], p1[0], p1[1], p0[2], wraps, seam);
		CHECK("periodic.momentum.many_crossings", wraps >= 20 && seam >= 5, "%d crossings, %ld seam contacts",
		      wraps, seam);
		CHECK("periodic.momentum.conserved", fabs(p1[0] - p0[0]) < 1e-11 * p0[2] && fabs(p1[1] - p0[1]) < 1e-11 * p0[2],
		      "dPx %.3g dPy %.3g (scale %.3g)", p1[0] - p0[0], p1[1] - p0[1], p0[2]);
	}
	if (s)
		del_sim(s);

	/* energy without damping or friction: the seam contacts store and return it */
	s = gas(W, 0, 0, 0, 40);
	double dev = 0;
	wraps = 0;
	seam = 0;
	ok = s && !step_start(s, 0, &e) && run_gas(s, lround(0.5 / s->sc.dt), 0, &wraps, &seam, &dev, &e);
	CHECK("periodic.energy.runs", ok, "%s", e.msg);
	if (ok) {
		printf("# energy: largest relative deviation %.3g over 0.5 s; %d crossings, %ld seam contacts\n", dev,
		       wraps, seam);
		CHECK("periodic.energy.conserved", dev < 1e-3 && seam > 0, "deviation %.3g, %ld seam contacts", dev, seam);
	}
	if (s)
		del_sim(s);

	/* fused steps (the kernel's records, repacked after a wrap) = reference steps */
	sb_sim *a = gas(W, 0.5, 100, 1, 40), *b = gas(W, 0.5, 100, 1, 40);
	int wa = 0, wb = 0;
	long sa = 0, sb = 0;
	ok = a && b && !step_start(a, 0, &e) && !step_start(b, 0, &e) &&
	     run_gas(a, 4000, 1, &wa, &sa, NULL, &e) && run_gas(b, 4000, 0, &wb, &sb, NULL, &e);
	int same = ok;
	for (int c = 0; c < SB_NCOORD && same; c++)
		for (int k = 0; k < a->in.nval && same; k++)
			same = !memcmp(a->st.q[c][k], b->st.q[c][k], sizeof(double) * (size_t)a->st.nm);
	CHECK("periodic.fused_equals_reference", same && wb > 0, "%s (%d crossings)", ok ? "states differ" : e.msg, wb);
	if (a)
		del_sim(a);
	if (b)
		del_sim(b);
}

/* (d) */
static void observables(void)
{
	const double W = 20;
	sb_scene sc = periodic_scene(W);
	sc.field = 1;
	sc.field_periods = 1000; /* nothing is journaled: the sums are read here */
	sc.ring = 1;
	sc.ring_centre = RING_FIXED;
	sc.ring_x = 0.5;
	sc.ring_y = 5;
	sb_state st = {0};
	sb_err e = {0};
	place_push(&sc, &st, W - 0.5, 3.1, 1, KIND_GRAIN, &e); /* will cross the seam */
	place_push(&sc, &st, W - 5.5, 5, 1, KIND_GRAIN, &e);  /* 6 cm from the ring centre, through the seam */
	place_push(&sc, &st, 10, 5, 1, KIND_GRAIN, &e);       /* 9.5 cm: outside */
	sb_obs o;
	int ok = !e.code && !obs_init(&o, &sc, &st, -1, 10, 0, W, &e);
	CHECK("periodic.observables.setup", ok, "%s", e.msg);
	if (!ok) {
		state_free(&st);
		return;
	}
	long nf = 0, nd = 0;
	ok = !sample_obs_strobe(&o, &st, 0, 4, NULL, &nf, &nd, &e);
	st.q[C_X][0][0] = 0.5; /* +1 cm through the seam */
	ok = ok && !sample_obs_strobe(&o, &st, 0.25, 4, NULL, &nf, &nd, &e);
	/* the midpoint is x = 0 (wrapped), y = 3.1: column 0, row 3.1 / cell */
	const int row = (int)floor(3.1 / o.cell);
	const size_t c0 = (size_t)row * o.nx;
	double total = 0;
	for (size_t c = 0; c < (size_t)o.nx * o.ny; c++)
		total += o.cnt[c];
	CHECK("periodic.field.minimum_image", ok && o.cnt[c0] == 1 && o.sx[c0] == 1 && total == 3,
	      "cell (0, %d): count %g, sum ux %g (want 1, 1); %g samples in all (want 3)", row, o.cnt[c0], o.sx[c0],
	      total);
	double r[OBS_RING_COLS];
	obs_ring_sample(&o, &st, -1, 0.1, 1.0 / sc.dt, r);
	CHECK("periodic.ring.minimum_image", r[OBS_RR_N] == 1, "%g grains in the ring (want 1, across the seam)",
	      r[OBS_RR_N]);
	obs_free(&o);
	state_free(&st);
}

static void refused(void)
{
	sb_scene sc = periodic_scene(3); /* less than a grain's reach around */
	sb_sim *s = new_sim(&sc);
	sb_err e = {0};
	place_push(&sc, &s->st, 1, 5, 1.6, KIND_GRAIN, &e);
	int rc = sim_derive(s, &e);
	printf("# %s\n", e.msg);
	CHECK("periodic.refused.disk_meets_own_image", rc == SB_EUSAGE && strstr(e.msg, "sides = periodic") &&
							       strstr(e.msg, "width"),
	      "rc %d: %s", rc, e.msg);
	del_sim(s);
}

int main(void)
{
	seam_pair();
	seam_pair_laws();
	seam_list();
	crossing();
	conservation();
	observables();
	refused();
	return tl_done();
}
