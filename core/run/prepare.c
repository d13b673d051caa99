/* prepare.c - preparation: the disks placed or read, the bed settled without vibration
 * until its kinetic energy has decayed, the settled state made canonical (what a
 * particle file of it holds) and put into the box frame (docs/model.md, "Preparation"). */
#include "prepare.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "clock.h"
#include "dtguard.h"
#include "pfile.h"
#include "place.h"
#include "step.h"

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* Free-surface height: the median over columns one mean diameter wide of the highest
 * grain top in each column (robust to a few loose grains on top). */
static double surface_height(const sb_sim *s)
{
	const sb_state *st = &s->st;
	double xmin = INFINITY, xmax = -INFINITY;
	for (int i = 0; i < st->nm; i++)
		if (st->kind[i] == KIND_GRAIN) {
			xmin = fmin(xmin, st->q[C_X][0][i]);
			xmax = fmax(xmax, st->q[C_X][0][i]);
		}
	if (!(xmin <= xmax))
		return 0;
	const double cols = floor((xmax - xmin) / (2 * s->rmean));
	int nc = cols < 1e7 ? (int)cols : 10000000; /* far-flung grains cannot overflow the count */
	if (nc < 1)
		nc = 1;
	double *top = malloc(sizeof(double) * (size_t)nc);
	if (!top)
		return NAN;
	for (int c = 0; c < nc; c++)
		top[c] = -INFINITY;
	for (int i = 0; i < st->nm; i++) {
		if (st->kind[i] != KIND_GRAIN)
			continue;
		int c = (int)floor((st->q[C_X][0][i] - xmin) / (xmax - xmin + 1e-12) * nc);
		c = c < 0 ? 0 : c >= nc ? nc - 1 : c;
		top[c] = fmax(top[c], st->q[C_Y][0][i] + st->r[i]);
	}
	int k = 0;
	for (int c = 0; c < nc; c++)
		if (isfinite(top[c]))
			top[k++] = top[c];
	qsort(top, (size_t)k, sizeof(double), cmp_double);
	double h = k ? top[k / 2] : 0;
	free(top);
	return h;
}

static int settle(sb_sim *s, sb_err *e)
{
	const sb_scene *sc = &s->sc;
	const double gy = -sc->gravity;
	const long every = lround(fmax(1.0, 0.01 / sc->dt)); /* test the energy every 10 ms */
	const long nmin = llround(sc->settle_min / sc->dt), nmax = llround(sc->settle_max / sc->dt);
	if (step_start(s, gy, e))
		return e->code;
	s->stage = "settling";
	double wlast = sb_now();
	for (long k = 1;; k++) {
		double t = k * sc->dt;
		/* A viscous drag lets the loose lattice collapse at a terminal speed
		 * g / settle_drag instead of slamming down, and brings the bouncing grains of
		 * the surface to rest in a time 1 / settle_drag instead of a long series of
		 * bounces; it does not change what a static packing is. */
		const int look = (k % every == 0 && k >= nmin) || k >= nmax;
		if (step_once(s, k, gy, sc->settle_drag, !look, NULL, e))
			return e->code;
		if (k % every == 0 && k >= nmin) {
			double ke = s->st.nm ? sim_kinetic(s) / s->st.nm : 0;
			if (s->progress && sb_now() - wlast >= 1.0) { /* a 10^5-grain bed takes minutes */
				wlast = sb_now();
				s->progress(s->progress_ctx,
					    &(sb_progress){PROG_SETTLING, .t = t, .ke = ke, .ke_settled = sc->settle_ke});
			}
			if (ke < sc->settle_ke) {
				if (s->progress)
					s->progress(s->progress_ctx, &(sb_progress){PROG_SETTLED, .t = t});
				s->settle_steps = k;
				s->settle_time = t;
				return 0;
			}
		}
		if (k >= nmax) {
			double ke = s->st.nm ? sim_kinetic(s) / s->st.nm : 0;
			sim_fail(s, SB_ESETTLE, t, k,
				 "settling: mean kinetic energy %.3g erg per disk still above settle_ke = %g after settle_max = %g s",
				 ke, sc->settle_ke, sc->settle_max);
			return sb_errf(e, SB_ESETTLE, "%s", s->status_msg);
		}
		if (s->stop && *s->stop)
			return sb_errf(e, SB_EINTR, "interrupted while settling");
	}
}

int prepare_run(sb_sim *s, sb_err *e)
{
	const sb_scene *sc = &s->sc;
	int err = sc->particles[0] ? pfile_read(sc, sc->particles, &s->st, e) : place_scene(sc, &s->st, e);
	if (err)
		return err;
	if (sim_derive(s, e))
		return e->code;
	double m_min = INFINITY;
	for (int i = 0; i < s->st.nm; i++)
		m_min = fmin(m_min, s->st.m[i]);
	if (dtguard_check(sc, m_min, s->warning, sizeof s->warning, e))
		return e->code;

	int do_settle = sc->settle == TRI_YES || (sc->settle == TRI_AUTO && !sc->particles[0]);
	if (do_settle) {
		/* settling runs in the lab frame with the box at rest */
		if (settle(s, e))
			return e->code;
		s->stage = "step";
	}
	s->surface0 = surface_height(s);
	s->intruder_y0 = s->intruder >= 0 ? s->st.q[C_Y][0][s->intruder] : NAN;

	/* t = 0 of shaking: the lab-frame state is the prepared one (y_box(0) = 0), the
	 * box starts moving with v_box(0) = A omega. */
	const double vbox0 = sim_box_v(s, 0);
	if (sc->write_particles[0] &&
	    pfile_write_text(&s->st, sc->write_particles, 1.0 / sc->dt, 0, vbox0, e))
		return e->code;
	if (sc->write_lammps[0] && pfile_write_lammps(&s->st, sc->write_lammps, 1.0 / sc->dt, 0, vbox0, s->nl.period, e))
		return e->code;

	/* Canonical state at t = 0: exactly what a particle file of this state holds, so
	 * that a run started from the file just written (e.g. the study driver's packing cache) is
	 * bit-identical to one that settled itself. Velocities take the same round trip
	 * a file does (v = q1/dt, then q1 = v dt), angles restart at zero, and below the
	 * integrator restarts from forces (higher derivatives zero). A state just read
	 * from a file is canonical already (applying the round trip twice is not exact). */
	if (do_settle) {
		const double idt = 1.0 / sc->dt;
		for (int c = 0; c < SB_NCOORD; c++)
			for (int i = 0; i < s->st.nm; i++)
				s->st.q[c][1][i] = (s->st.q[c][1][i] * idt) * sc->dt;
		for (int i = 0; i < s->st.nm; i++)
			s->st.q[C_TH][0][i] = 0;
	}

	/* Into the box frame: every mobile disk gets -v_box(0) in y. */
	const double vb = sim_box_v(s, 0) * sc->dt;
	for (int i = 0; i < s->st.nm; i++)
		s->st.q[C_Y][1][i] -= vb;
	s->nl.builds = 0; /* count the shaking phase only */
	if (step_start(s, -sc->gravity - sim_box_a(s, 0), e))
		return e->code;
	return sim_obs_init(s, e);
}

