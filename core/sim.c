/* sim.c - the run: preparation, settling and the shaking loop. The step reads as a
 * recipe: predict -> check -> neighbours -> forces -> correct -> record. */
#include "sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "pfile.h"
#include "prepare.h"
#include "units.h"

static double now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

double sim_box_y(const sb_sim *s, double t) { return drive_y(&s->drive, t); }
double sim_box_v(const sb_sim *s, double t) { return drive_v(&s->drive, t); }
double sim_box_a(const sb_sim *s, double t) { return drive_a(&s->drive, t); }

int sim_init(sb_sim *s, const sb_scene *sc, sb_err *e)
{
	memset(s, 0, sizeof *s);
	s->sc = *sc;
	s->law = (sb_law){sc->stiffness, sc->gamma_n, sc->gamma_s, sc->mu, sc->max_overlap,
			  sc->clip_attractive};
	integ_init(&s->in, sc->integrator, sc->dt);
	s->drive = (sb_drive){sc->ramp, sc->amplitude, sc->frequency, sc->ramp_from, sc->ramp_to,
			      sc->duration - sc->ramp_hold, sc->ramp_hold};
	s->intruder = -1;
	s->nsteps = llround(sc->duration / sc->dt);
	snprintf(s->journal_path, sizeof s->journal_path, "%s.journal", sc->output);
	if (sc->checkpoint[0])
		snprintf(s->ckpt_path, sizeof s->ckpt_path, "%s", sc->checkpoint);
	else
		snprintf(s->ckpt_path, sizeof s->ckpt_path, "%s.ckpt", sc->output);
	prov_init(&s->prov);
	(void)e;
	return 0;
}

void sim_free(sb_sim *s)
{
	obs_free(&s->obs);
	journal_close(&s->jr);
	nlist_free(&s->nl);
	kernel_free(s->kern);
	s->kern = NULL;
	state_free(&s->st);
}

double sim_kinetic(const sb_sim *s)
{
	const sb_state *st = &s->st;
	double ke = 0, idt2 = 1.0 / (s->sc.dt * s->sc.dt);
	for (int i = 0; i < st->nm; i++) {
		double vx = st->q[C_X][1][i], vy = st->q[C_Y][1][i], w = st->q[C_TH][1][i];
		ke += 0.5 * st->m[i] * (vx * vx + vy * vy) + 0.5 * (1.0 / st->inv_i[i]) * w * w;
	}
	return ke * idt2;
}

/* Where the walls are, a grain must stay: the box is the hull of the wall disks in x
 * and above their lowest centre. Without walls there is no box to leave. */
static void set_bounds(sb_sim *s)
{
	const sb_state *st = &s->st;
	s->xlo = -INFINITY;
	s->xhi = INFINITY;
	s->ylo = -INFINITY;
	if (st->n == st->nm)
		return;
	s->xlo = INFINITY;
	s->xhi = -INFINITY;
	s->ylo = INFINITY;
	for (int i = st->nm; i < st->n; i++) {
		s->xlo = fmin(s->xlo, st->q[C_X][0][i]);
		s->xhi = fmax(s->xhi, st->q[C_X][0][i]);
		s->ylo = fmin(s->ylo, st->q[C_Y][0][i]);
	}
}

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
	int nc = (int)floor((xmax - xmin) / (2 * s->rmean));
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

/* ---- the step ---- */

typedef struct scan {
	int rebuild, bad_num, out;
	int where;
} scan;

/* One pass over the mobile disks after the predictor: largest displacement since the
 * last neighbour build, non-finite numbers, disks outside the box. */
static scan check_state(const sb_sim *s)
{
	const sb_state *st = &s->st;
	const double *x = st->q[C_X][0], *y = st->q[C_Y][0], *th = st->q[C_TH][0];
	const double *xr = s->nl.xref, *yr = s->nl.yref;
	const double xlo = s->xlo, xhi = s->xhi, ylo = s->ylo;
	const double half = 0.5 * s->sc.skin, lim = half * half;
	int rebuild = 0, out = 0, bad = 0;
	/* only comparisons and integer ors, so the loop vectorises: a NaN or Inf fails
	 * "< INFINITY", and so does the sum of a NaN angle with d2 */
	for (int i = 0; i < st->nm; i++) {
		const double dx = x[i] - xr[i], dy = y[i] - yr[i];
		const double d2 = dx * dx + dy * dy;
		rebuild |= d2 > lim;
		bad |= !(d2 + fabs(th[i]) < INFINITY);
		out |= (x[i] < xlo) | (x[i] > xhi) | (y[i] < ylo);
	}
	scan r = {rebuild, bad, out, -1};
	if (r.bad_num || r.out)
		for (int i = 0; i < st->nm; i++) {
			double v = x[i] + y[i] + th[i] + st->q[C_X][1][i] + st->q[C_Y][1][i];
			if (!isfinite(v) || x[i] < xlo || x[i] > xhi || y[i] < ylo) {
				r.where = i;
				break;
			}
		}
	return r;
}

static int fail(sb_sim *s, sb_err *e, int code, double t, long step, const char *fmt, const char *what)
{
	s->status = code;
	s->status_time = t;
	s->status_step = step;
	snprintf(s->status_msg, sizeof s->status_msg, fmt, what, t, step);
	return sb_errf(e, code, "%s", s->status_msg);
}

#define TIC(ph) double t0_##ph = s->profile ? now() : 0
#define TOC(ph) if (s->profile) s->tphase[ph] += now() - t0_##ph

/* One step of length dt; gy is the uniform acceleration in y at the new time.
 * t and step name the new time in messages. */
static void add_drag(sb_state *st, double gamma, double inv_dt)
{
	const double k = gamma * inv_dt;
	for (int i = 0; i < st->nm; i++) {
		st->f[C_X][i] -= k * st->m[i] * st->q[C_X][1][i];
		st->f[C_Y][i] -= k * st->m[i] * st->q[C_Y][1][i];
	}
}

/* The largest overlap of the shaking is recorded without a cost per step: the force
 * kernel's overlap flag, which stops a run past max_overlap, is armed at the record so
 * far instead, and only a step that beats the record scans the pairs (a few hundred
 * steps of a run). The forces do not depend on the threshold. The kernel and the scan
 * round the overlap differently, so the threshold sits a relative 1e-9 above the
 * record: a contact at the record does not trigger a scan every step. */
static void new_overlap_record(sb_sim *s, double f, int a, int b, double t)
{
	const sb_state *st = &s->st;
	if (f > s->obs.ov_max) {
		s->obs.ov_max = f;
		s->obs.ov_t = t;
		s->obs.ov_i = st->id[a];
		s->obs.ov_j = st->id[b];
		s->obs.ov_x = 0.5 * (st->q[C_X][0][a] + st->q[C_X][0][b]);
		s->obs.ov_y = 0.5 * (st->q[C_Y][0][a] + st->q[C_Y][0][b]);
	}
	s->law.max_overlap = fmin(s->obs.ov_max * (1 + 1e-9), s->sc.max_overlap);
}

/* The state after the predictor, screened: rebuild the list, or stop the run on a
 * non-finite number or a disk outside the box. The fused corrector of the last step
 * may have screened it already (scr.done). */
static int check(sb_sim *s, const char *stage, double t, long step, int *rebuild, sb_err *e)
{
	sb_state *st = &s->st;
	scan c = {s->screen.rebuild, s->screen.bad, s->screen.out, -1};
	if (!s->screen.done || c.bad_num || c.out) { /* the scan also finds where */
		kernel_sync(s->kern, st);
		c = check_state(s);
	}
	s->screen.done = 0;
	*rebuild = c.rebuild;
	if (!c.bad_num && !c.out)
		return 0;
	char what[256];
	int i = c.where < 0 ? 0 : c.where;
	if (c.bad_num) {
		snprintf(what, sizeof what, "%s: non-finite position or velocity of disk %d", stage, st->id[i]);
		return fail(s, e, SB_ENAN, t, step, "%s at t = %.6f s, step %ld (time step too large?)", what);
	}
	snprintf(what, sizeof what, "%s: disk %d left the box at (%.3f, %.3f) cm", stage, st->id[i],
		 st->q[C_X][0][i], st->q[C_Y][0][i]);
	return fail(s, e, SB_ELEFT, t, step, "%s at t = %.6f s, step %ld", what);
}

/* The waiting time (docs/model.md, "Waiting time"): the first time the intruder's
 * centre is one diameter above its settled height, on the positions the forces are
 * evaluated at. */
static void watch_rise(sb_sim *s, double t, long step)
{
	if (s->intruder >= 0 && !s->obs.risen && step > 0 && s->obs.rise_height > 0 &&
	    kernel_y(s->kern, &s->st, s->intruder) - s->intruder_y0 > s->obs.rise_height) {
		s->obs.risen = 1;
		s->obs.wait_time = t;
	}
}

static int neighbours(sb_sim *s, sb_err *e)
{
	kernel_sync(s->kern, &s->st);
	return nlist_build(&s->nl, &s->st, e);
}

/* Forces at the predicted state (keep: for the fused corrector; track: the ring's
 * per-disk |F| sums; drag: settling's viscous drag). An overlap past the kernel's
 * threshold beats the run's record (kept, the step goes on) or the stop (it ends). */
static int forces(sb_sim *s, int keep, double *track, double drag, const char *stage, double t, long step,
		  sb_err *e)
{
	sb_state *st = &s->st;
	const double inv_dt = 1.0 / s->sc.dt;
	int bad = kernel_forces(s->kern, &s->law, st, &s->nl, inv_dt, keep, track, e);
	if (bad < 0)
		return e->code;
	if (drag > 0) /* settling only */
		add_drag(st, drag, inv_dt);
	if (!bad)
		return 0;
	/* measured on the positions the kernel saw, before the correction */
	kernel_sync(s->kern, st);
	int a = 0, b = 0;
	double f = forces_max_overlap(st, &s->nl, &a, &b);
	if (s->ov_track && f <= s->sc.max_overlap) {
		new_overlap_record(s, f, a, b, t);
		return 0;
	}
	char what[256];
	snprintf(what, sizeof what, "%s: overlap of disks %d and %d is %.3f of the smaller radius (max_overlap %g)",
		 stage, st->id[a], st->id[b], f, s->sc.max_overlap);
	return fail(s, e, SB_EOVERLAP, t, step, "%s at t = %.6f s, step %ld", what);
}

/* The reference step, as in a textbook MD code: predict, check, neighbours, forces,
 * correct (record: sim_run). gy is the uniform acceleration in y at the new time t
 * (step). Its corrected state is in st for whoever reads it next. */
static int step_reference(sb_sim *s, double gy, double drag, double t, long step, const char *stage,
			  double *track, sb_err *e)
{
	int rebuild;
	if (!s->predicted) {
		TIC(PH_PREDICT);
		integ_predict(&s->in, &s->st);
		TOC(PH_PREDICT);
	}
	s->predicted = 0;
	TIC(PH_CHECK);
	int rc = check(s, stage, t, step, &rebuild, e);
	TOC(PH_CHECK);
	if (rc)
		return rc;
	watch_rise(s, t, step);
	if (rebuild) {
		TIC(PH_NEIGH);
		rc = neighbours(s, e);
		TOC(PH_NEIGH);
		if (rc)
			return rc;
	}
	TIC(PH_FORCE);
	rc = forces(s, 0, track, drag, stage, t, step, e);
	TOC(PH_FORCE);
	if (rc)
		return rc;
	TIC(PH_CORRECT);
	integ_correct(&s->in, &s->st, gy);
	TOC(PH_CORRECT);
	return 0;
}

/* The fused step, for a step whose corrected state nobody reads: the same recipe, but
 * the corrector also predicts the next step (s->predicted), and without settling's
 * drag it takes the forces straight from the kernel and screens the predicted state
 * (kernel_correct_predict). Bit-identical to step_reference followed by a predictor. */
static int step_fused(sb_sim *s, double gy, double drag, double t, long step, const char *stage, sb_err *e)
{
	int rebuild;
	if (!s->predicted) {
		TIC(PH_PREDICT);
		integ_predict(&s->in, &s->st);
		TOC(PH_PREDICT);
	}
	s->predicted = 0;
	TIC(PH_CHECK);
	int rc = check(s, stage, t, step, &rebuild, e);
	TOC(PH_CHECK);
	if (rc)
		return rc;
	watch_rise(s, t, step);
	if (rebuild) {
		TIC(PH_NEIGH);
		rc = neighbours(s, e);
		TOC(PH_NEIGH);
		if (rc)
			return rc;
	}
	const int keep = drag == 0; /* the drag acts on st->f, which a kept force skips */
	TIC(PH_FORCE);
	rc = forces(s, keep, NULL, drag, stage, t, step, e);
	TOC(PH_FORCE);
	if (rc)
		return rc;
	TIC(PH_CORRECT);
	if (keep) {
		const double half = 0.5 * s->sc.skin;
		s->screen = (sb_screen){half * half, s->xlo, s->xhi, s->ylo, 0, 0, 0, 0};
		kernel_correct_predict(s->kern, &s->in, &s->st, gy, &s->nl, &s->screen);
	} else {
		integ_correct_predict(&s->in, &s->st, gy);
	}
	s->predicted = 1;
	TOC(PH_CORRECT);
	return 0;
}

static int step_once(sb_sim *s, double gy, double drag, double t, long step, const char *stage, int fuse,
		     double *track, sb_err *e)
{
	return fuse && !track ? step_fused(s, gy, drag, t, step, stage, e)
			      : step_reference(s, gy, drag, t, step, stage, track, e);
}

int sim_step(sb_sim *s, double gy, sb_err *e)
{
	s->step++;
	return step_once(s, gy, 0, s->step * s->sc.dt, s->step, "step", 0, NULL, e);
}

/* Forces at the current state and the integrator's acceleration term from them. */
int sim_start(sb_sim *s, double gy, sb_err *e)
{
	if (nlist_build(&s->nl, &s->st, e))
		return e->code;
	if (kernel_forces(s->kern, &s->law, &s->st, &s->nl, 1.0 / s->sc.dt, 0, NULL, e) < 0)
		return e->code;
	integ_start(&s->in, &s->st, gy);
	return 0;
}

static int settle(sb_sim *s, sb_err *e)
{
	const sb_scene *sc = &s->sc;
	const double gy = -sc->gravity;
	const long every = lround(fmax(1.0, 0.01 / sc->dt)); /* test the energy every 10 ms */
	const long nmin = llround(sc->settle_min / sc->dt), nmax = llround(sc->settle_max / sc->dt);
	if (sim_start(s, gy, e))
		return e->code;
	double wlast = now();
	for (long k = 1;; k++) {
		double t = k * sc->dt;
		/* A viscous drag lets the loose lattice collapse at a terminal speed
		 * g / settle_drag instead of slamming down, and brings the bouncing grains of
		 * the surface to rest in a time 1 / settle_drag instead of a long series of
		 * bounces; it does not change what a static packing is. */
		const int look = (k % every == 0 && k >= nmin) || k >= nmax;
		if (step_once(s, gy, sc->settle_drag, t, k, "settling", !look, NULL, e))
			return e->code;
		if (k % every == 0 && k >= nmin) {
			double ke = s->st.nm ? sim_kinetic(s) / s->st.nm : 0;
			if (s->progress && now() - wlast >= 1.0) { /* a 10^5-grain bed takes minutes */
				wlast = now();
				fprintf(stderr, "\rshake: settling, t = %.2f s, kinetic energy %.3g erg per disk (settled below %g) ",
					t, ke, sc->settle_ke);
				fflush(stderr);
			}
			if (ke < sc->settle_ke) {
				if (s->progress)
					fprintf(stderr, "\rshake: settled after %.2f s%60s\n", t, "");
				s->settle_steps = k;
				s->settle_time = t;
				return 0;
			}
		}
		if (k >= nmax) {
			double ke = s->st.nm ? sim_kinetic(s) / s->st.nm : 0;
			s->status = SB_ESETTLE;
			s->status_time = t;
			s->status_step = k;
			snprintf(s->status_msg, sizeof s->status_msg,
				 "settling: mean kinetic energy %.3g erg per disk still above settle_ke = %g after settle_max = %g s",
				 ke, sc->settle_ke, sc->settle_max);
			return sb_errf(e, SB_ESETTLE, "%s", s->status_msg);
		}
		if (s->stop && *s->stop)
			return sb_errf(e, SB_EINTR, "interrupted while settling");
	}
}

int sim_derive(sb_sim *s, sb_err *e)
{
	if (s->st.nm == 0)
		return sb_errf(e, SB_EUSAGE, "%s%sthe scene has no mobile disks (grains or an intruder): nothing to shake",
			       s->sc.particles[0] ? s->sc.particles : "", s->sc.particles[0] ? ": " : "");
	double rs = 0;
	int ng = 0;
	for (int i = 0; i < s->st.nm; i++)
		if (s->st.kind[i] == KIND_GRAIN) {
			rs += s->st.r[i];
			ng++;
		}
	s->rmean = ng ? rs / ng : 0.5 * (s->sc.r_min + s->sc.r_max);
	s->intruder = state_find_intruder(&s->st);
	set_bounds(s);
	if (kernel_init(&s->kern, &s->st, e))
		return e->code;
	return nlist_init(&s->nl, &s->st, s->sc.skin, kernel_pair_shift(), e);
}

/* The inner faces of the side walls: the hull of the wall disks less their radii
 * (x = 0 and width for a generated scene). */
int sim_obs_init(sb_sim *s, sb_err *e)
{
	const sb_state *st = &s->st;
	double x0 = INFINITY, x1 = -INFINITY;
	for (int i = st->nm; i < st->n; i++) {
		x0 = fmin(x0, st->q[C_X][0][i] + st->r[i]);
		x1 = fmax(x1, st->q[C_X][0][i] - st->r[i]);
	}
	if (!(x0 < x1)) { /* no walls: the extent of the disks */
		x0 = INFINITY;
		x1 = -INFINITY;
		for (int i = 0; i < st->nm; i++) {
			x0 = fmin(x0, st->q[C_X][0][i] - st->r[i]);
			x1 = fmax(x1, st->q[C_X][0][i] + st->r[i]);
		}
	}
	return obs_init(&s->obs, &s->sc, st, s->intruder, s->surface0, x0, x1, e);
}

int sim_prepare(sb_sim *s, sb_err *e)
{
	const sb_scene *sc = &s->sc;
	int err = sc->particles[0] ? pfile_read(sc, sc->particles, &s->st, e) : prepare_place(sc, &s->st, e);
	if (err)
		return err;
	if (sim_derive(s, e))
		return e->code;
	double m_min = INFINITY;
	for (int i = 0; i < s->st.nm; i++)
		m_min = fmin(m_min, s->st.m[i]);
	if (integ_dt_check(sc, m_min, s->warning, sizeof s->warning, e))
		return e->code;

	int do_settle = sc->settle == TRI_YES || (sc->settle == TRI_AUTO && !sc->particles[0]);
	if (do_settle) {
		/* settling runs in the lab frame with the box at rest */
		if (settle(s, e))
			return e->code;
	}
	s->surface0 = surface_height(s);
	s->intruder_y0 = s->intruder >= 0 ? s->st.q[C_Y][0][s->intruder] : NAN;

	/* t = 0 of shaking: the lab-frame state is the prepared one (y_box(0) = 0), the
	 * box starts moving with v_box(0) = A omega. */
	const double vbox0 = sim_box_v(s, 0);
	if (sc->write_particles[0] &&
	    pfile_write_text(&s->st, sc->write_particles, 1.0 / sc->dt, 0, vbox0, e))
		return e->code;
	if (sc->write_lammps[0] && pfile_write_lammps(&s->st, sc->write_lammps, 1.0 / sc->dt, 0, vbox0, e))
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
	if (sim_start(s, -sc->gravity - sim_box_a(s, 0), e))
		return e->code;
	return sim_obs_init(s, e);
}

/* ---- recording ---- */

/* First step at or after time k * interval: integer schedule, no drift. */
static long due_step(long k, double interval, double dt)
{
	return (long)ceil(k * interval / dt - 1e-6);
}

static int record_traj(sb_sim *s, double t, sb_err *e)
{
	const sb_state *st = &s->st;
	int i = s->intruder;
	double idt = 1.0 / s->sc.dt;
	double row[JR_TRAJ_COLS] = {t,
				    st->q[C_X][0][i],
				    st->q[C_Y][0][i] + sim_box_y(s, t),
				    st->q[C_X][1][i] * idt,
				    st->q[C_Y][1][i] * idt + sim_box_v(s, t),
				    st->q[C_TH][1][i] * idt};
	if (journal_traj(&s->jr, row, e))
		return e->code;
	s->n_traj++;
	return 0;
}

static int record_snap(sb_sim *s, double t, sb_err *e)
{
	sb_state *st = &s->st;
	/* lab frame: shift y by y_box(t); f[C_Y] is free scratch between steps */
	double yb = sim_box_y(s, t);
	double *ylab = st->f[C_Y];
	for (int i = 0; i < st->nm; i++)
		ylab[i] = st->q[C_Y][0][i] + yb;
	if (journal_snap(&s->jr, t, st->q[C_X][0], ylab, st->q[C_TH][0], e))
		return e->code;
	s->n_snap++;
	return 0;
}

/* Stroboscopic samples (phase 0 of each period) feed the snapshots, the flux and
 * the displacement field; without any of them there are none. */
static int strobe_on(const sb_sim *s)
{
	return (s->sc.snapshots || s->obs.flux_on || s->obs.field_on) &&
	       (s->sc.ramp != RAMP_NONE || s->sc.frequency > 0);
}

/* Is sample number n_strobe due at step n? Constant frequency: an integer schedule
 * (no drift); a ramp: the phase has passed 2 pi n_strobe. */
static int strobe_due(const sb_sim *s, long n)
{
	if (!strobe_on(s))
		return 0;
	if (s->sc.ramp == RAMP_NONE)
		return n >= s->next_snap_step;
	return drive_cycles(&s->drive, n * s->sc.dt) >= s->n_strobe - 1e-9;
}

static int record(sb_sim *s, sb_err *e)
{
	const sb_scene *sc = &s->sc;
	const double t = s->step * sc->dt;
	if (s->intruder >= 0 && sc->traj_rate > 0 && s->step >= s->next_traj_step) {
		if (record_traj(s, t, e))
			return e->code;
		s->next_traj_step = due_step(s->n_traj, 1.0 / sc->traj_rate, sc->dt);
	}
	if (strobe_due(s, s->step)) {
		if (sc->snapshots && record_snap(s, t, e))
			return e->code;
		if (obs_sample(&s->obs, &s->st, t, drive_freq(&s->drive, t), &s->jr, &s->n_flux, &s->n_field, e))
			return e->code;
		s->n_strobe++;
		if (sc->ramp == RAMP_NONE)
			s->next_snap_step = due_step(s->n_strobe, 1.0 / sc->frequency, sc->dt);
	}
	return 0;
}

static void progress(sb_sim *s, double t0, long step0, double *last)
{
	double w = now();
	if (w - *last < 1.0 && s->step < s->nsteps)
		return;
	*last = w;
	double rate = (s->step - step0) / fmax(w - t0, 1e-9);
	double eta = rate > 0 ? (s->nsteps - s->step) / rate : 0;
	fprintf(stderr, "\rshake: t = %.2f / %.2f s  %.0f steps/s  ETA %02d:%02d:%02d ", s->step * s->sc.dt,
		s->sc.duration, rate, (int)(eta / 3600), (int)fmod(eta / 60, 60), (int)fmod(eta, 60));
	fflush(stderr);
}

int sim_run(sb_sim *s, sb_err *e)
{
	const sb_scene *sc = &s->sc;
	const double dt = sc->dt;
	const int resumed = s->step > 0 || s->n_traj > 0 || s->n_strobe > 0;
	if (!s->jr.f && journal_open(&s->jr, s->journal_path, s->st.nm, -1, e))
		return e->code;
	if (!resumed) {
		s->n_ckpt = 0;
		s->next_ckpt_step = sc->checkpoint_every > 0 ? due_step(1, sc->checkpoint_every, dt) : -1;
		if (record(s, e))
			return e->code;
	}
	s->ov_track = 1;
	s->law.max_overlap = fmin(s->obs.ov_max * (1 + 1e-9), sc->max_overlap);
	double w0 = now(), wlast = w0, seg = w0; /* seg: loop time not yet in loop_seconds */
	long step0 = s->step;
	while (s->step < s->nsteps) {
		/* a stop waits until the state is corrected (not yet predicted) */
		if (s->stop && *s->stop && !s->predicted) {
			s->status = SB_EINTR;
			s->status_time = s->step * dt;
			s->status_step = s->step;
			snprintf(s->status_msg, sizeof s->status_msg, "interrupted at t = %.6f s, step %ld",
				 s->status_time, s->step);
			break;
		}
		const long n1 = s->step + 1;
		const double t1 = n1 * dt;
		const int ring = s->obs.ring_on && n1 % s->obs.ring_every == 0;
		/* fuse unless this step's corrected state is recorded, checkpointed or final */
		const int look = n1 >= s->nsteps || n1 == s->next_ckpt_step || (s->stop && *s->stop) || ring ||
				 (s->intruder >= 0 && sc->traj_rate > 0 && n1 >= s->next_traj_step) ||
				 strobe_due(s, n1);
		if (step_once(s, -sc->gravity - sim_box_a(s, t1), 0, t1, n1, "shaking", !look,
			      ring ? s->obs.fabs_sum : NULL, e))
			break;
		s->step = n1;
		if (ring)
			obs_ring(&s->obs, &s->st, s->intruder, 1.0 / dt);
		TIC(PH_RECORD);
		if (record(s, e))
			break;
		TOC(PH_RECORD);
		if (s->step == s->next_ckpt_step) {
			double w = now(); /* the checkpoint carries the CPU time so far */
			s->loop_seconds += w - seg;
			seg = w;
			if (ckpt_write(s, e))
				break;
			s->n_ckpt++;
			s->next_ckpt_step = due_step(s->n_ckpt + 1, sc->checkpoint_every, dt);
		}
		if (s->progress && (s->step & 1023) == 0)
			progress(s, w0, step0, &wlast);
	}
	s->ov_track = 0;
	s->law.max_overlap = sc->max_overlap;
	s->loop_seconds += now() - seg;
	if (s->progress && s->nsteps > 0) {
		progress(s, w0, step0, &wlast);
		fputc('\n', stderr);
	}
	if (e->code && !s->status) {
		s->status = e->code;
		snprintf(s->status_msg, sizeof s->status_msg, "%s", e->msg);
		s->status_time = s->step * dt;
		s->status_step = s->step;
	}
	return s->status;
}

int sim_write_output(sb_sim *s, sb_err *e)
{
	long off;
	if (s->jr.f && journal_sync(&s->jr, &off, e))
		return e->code;
	return h5out_write(s, s->sc.output, e);
}

void sim_cleanup_files(sb_sim *s)
{
	journal_close(&s->jr);
	unlink(s->journal_path);
	unlink(s->ckpt_path);
}
