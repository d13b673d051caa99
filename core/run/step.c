/* step.c - one time step, as a recipe: predict -> check -> watch the rise ->
 * neighbours -> forces -> correct (the recording is the run loop's, run.c;
 * core/README.md, "The step recipe"). Two recipes: the reference step,
 * whose corrected state anybody may read, and the fused one, whose corrector also
 * predicts the next step and takes the forces straight from the
 * kernel (kernel.h). */
#include "step.h"

#include <math.h>
#include <stdio.h>

#include "clock.h"
#include "fpmode.h"
#include "periodic.h"

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
	/* where: the first disk that fails the same tests (positions and angle: the
	 * velocities are not screened, a non-finite one shows in the next positions) */
	if (r.bad_num || r.out)
		for (int i = 0; i < st->nm; i++) {
			double v = x[i] + y[i] + th[i];
			if (!isfinite(v) || x[i] < xlo || x[i] > xhi || y[i] < ylo) {
				r.where = i;
				break;
			}
		}
	return r;
}

/* A failed step ends the run: its status (sim_fail) and the error returned. */
static int fail(sb_sim *s, sb_err *e, int code, double t, long step, const char *fmt, const char *what)
{
	sim_fail(s, code, t, step, fmt, what, t, step);
	return sb_errf(e, code, "%s", s->status_msg);
}

/* Settling's viscous drag, -gamma m v on each mobile disk (v = q[c][1] / dt). */
static void add_drag(sb_state *st, double gamma, double inv_dt)
{
	const double k = gamma * inv_dt;
	for (int i = 0; i < st->nm; i++) {
		st->f[C_X][i] -= k * st->m[i] * st->q[C_X][1][i];
		st->f[C_Y][i] -= k * st->m[i] * st->q[C_Y][1][i];
	}
}

/* The largest overlap of the shaking is recorded without a cost per step: the force
 * kernel's overlap flag, which stops a run past max_overlap, is armed 1 % above the
 * record so far instead, and only a step that beats that scans the pairs (a scan costs
 * about a force evaluation). With the threshold at the record itself, every step of a
 * record-setting collision scanned: +4 % on a 1-s run of the paper scene; with 1 %
 * steps a run scans at most ~300 times (from 0.01 to 0.6 of the radius), and the
 * record is the exact overlap of a step, at most 1 % below the largest one. The forces
 * do not depend on the threshold. */
void step_arm_overlap(sb_sim *s)
{
	s->law.max_overlap = fmin(s->obs.ov_max * 1.01, s->sc.max_overlap);
}

static void new_overlap_record(sb_sim *s, double f, int a, int b, double t)
{
	const sb_state *st = &s->st;
	if (f > s->obs.ov_max) {
		s->obs.ov_max = f;
		s->obs.ov_t = t;
		s->obs.ov_i = st->id[a];
		s->obs.ov_j = st->id[b];
		s->obs.ov_x = periodic_mid(st->q[C_X][0][a], st->q[C_X][0][b], s->nl.period);
		s->obs.ov_y = 0.5 * (st->q[C_Y][0][a] + st->q[C_Y][0][b]);
	}
	step_arm_overlap(s);
}

/* The state after the predictor, screened: rebuild the list, or stop the run on a
 * non-finite number or a disk outside the box. The fused corrector of the last step
 * may have screened it already (scr.done). */
static int check(sb_sim *s, double t, long step, int *rebuild, sb_err *e)
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
		snprintf(what, sizeof what, "%s: non-finite position or angle of disk %d", s->stage, st->id[i]);
		return fail(s, e, SB_ENAN, t, step, "%s at t = %.6f s, step %ld (time step too large?)", what);
	}
	snprintf(what, sizeof what, "%s: disk %d left the box at (%.3f, %.3f) cm", s->stage, st->id[i],
		 st->q[C_X][0][i], st->q[C_Y][0][i]);
	return fail(s, e, SB_ELEFT, t, step, "%s at t = %.6f s, step %ld", what);
}

/* The waiting time (docs/model.md, "Waiting time"): the first time the intruder's
 * centre is one diameter above its settled height, on the positions the forces are
 * evaluated at; every intruder's when there are several ("Several intruders"). */
static void watch_rise(sb_sim *s, double t, long step)
{
	if (s->intruder >= 0 && !s->obs.risen && step > 0 && s->obs.rise_height > 0 &&
	    kernel_y(s->kern, &s->st, s->intruder) - s->intruder_y0 > s->obs.rise_height) {
		s->obs.risen = 1;
		s->obs.wait_time = t;
	}
	sb_obs *o = &s->obs; /* the other intruders, each by the same rule (nint > 1 only) */
	for (int k = 1; k < o->nint && step > 0; k++)
		if (!o->irisen[k] && kernel_y(s->kern, &s->st, o->iidx[k]) - o->iy0[k] > o->irise_h[k]) {
			o->irisen[k] = 1;
			o->iwait[k] = t;
		}
}

/* With periodic sides the mobile disks are wrapped back into [0, W) here, at a
 * build only: the list's reference positions are the wrapped ones, so the
 * displacement since the build never sees a jump of W (docs/model.md, "Periodic side
 * boundaries"). With walls nothing moves. */
static int neighbours(sb_sim *s, sb_err *e)
{
	kernel_sync(s->kern, &s->st);
	if (s->nl.period > 0 && periodic_wrap_state(&s->st, s->nl.period))
		kernel_state_changed(s->kern);
	return nlist_build(&s->nl, &s->st, e);
}

/* Forces at the predicted state (keep: for the fused corrector; track: the ring's
 * per-disk |F| sums; drag: settling's viscous drag). An overlap past the kernel's
 * threshold beats the run's record (kept, the step goes on) or the stop (it ends). */
static int forces(sb_sim *s, int keep, double *track, double drag, double t, long step, sb_err *e)
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
		 s->stage, st->id[a], st->id[b], f, s->sc.max_overlap);
	return fail(s, e, SB_EOVERLAP, t, step, "%s at t = %.6f s, step %ld", what);
}

/* What both recipes begin with: predict (unless the last step's corrector did),
 * check, watch the rise (watch_rise: the waiting time), rebuild the neighbour list
 * when due. */
static int step_begin(sb_sim *s, double t, long step, sb_err *e)
{
	int rebuild;
	if (!s->predicted) {
		TIC(s, PH_PREDICT);
		integ_predict(&s->in, &s->st);
		TOC(s, PH_PREDICT);
	}
	s->predicted = 0;
	TIC(s, PH_CHECK);
	int rc = check(s, t, step, &rebuild, e);
	TOC(s, PH_CHECK);
	if (rc)
		return rc;
	watch_rise(s, t, step);
	if (rebuild) {
		TIC(s, PH_NEIGH);
		rc = neighbours(s, e);
		TOC(s, PH_NEIGH);
	}
	return rc;
}

/* The reference step, as in a textbook MD code: predict, check, watch the rise,
 * neighbours, forces, correct (record: run_shaking). gy is the uniform acceleration in y at the new time t
 * (step). Its corrected state is in st for whoever reads it next. */
static int step_reference(sb_sim *s, double gy, double drag, double t, long step, double *track, sb_err *e)
{
	int rc = step_begin(s, t, step, e);
	if (rc)
		return rc;
	TIC(s, PH_FORCE);
	rc = forces(s, 0, track, drag, t, step, e);
	TOC(s, PH_FORCE);
	if (rc)
		return rc;
	TIC(s, PH_CORRECT);
	integ_correct(&s->in, &s->st, gy);
	TOC(s, PH_CORRECT);
	return 0;
}

/* The fused step, for a step whose corrected state nobody reads: the same recipe, but
 * the corrector also predicts the next step (s->predicted), and without settling's
 * drag it takes the forces straight from the kernel and screens the predicted state
 * (kernel_correct_predict). Bit-identical to step_reference followed by a predictor. */
static int step_fused(sb_sim *s, double gy, double drag, double t, long step, sb_err *e)
{
	int rc = step_begin(s, t, step, e);
	if (rc)
		return rc;
	const int keep = drag == 0; /* the drag acts on st->f, which a kept force skips */
	TIC(s, PH_FORCE);
	rc = forces(s, keep, NULL, drag, t, step, e);
	TOC(s, PH_FORCE);
	if (rc)
		return rc;
	TIC(s, PH_CORRECT);
	if (keep) {
		const double half = 0.5 * s->sc.skin;
		s->screen = (sb_screen){half * half, s->xlo, s->xhi, s->ylo, 0, 0, 0, 0};
		kernel_correct_predict(s->kern, &s->in, &s->st, gy, &s->nl, &s->screen);
	} else {
		integ_correct_predict(&s->in, &s->st, gy);
	}
	s->predicted = 1;
	TOC(s, PH_CORRECT);
	return 0;
}

int step_once(sb_sim *s, long step, double gy, double drag, int fuse, double *track, sb_err *e)
{
	const double t = step * s->sc.dt; /* the new time, as the callers' schedules count it */
	const sb_fpmode fp = fpmode_enter(); /* subnormals flushed: fpmode.h says why */
	const int rc = fuse && !track ? step_fused(s, gy, drag, t, step, e)
				      : step_reference(s, gy, drag, t, step, track, e);
	fpmode_leave(fp);
	return rc;
}

int step_advance(sb_sim *s, double gy, sb_err *e)
{
	s->step++;
	return step_once(s, s->step, gy, 0, 0, NULL, e);
}

/* Forces at the current state and the integrator's acceleration term from them. */
int step_start(sb_sim *s, double gy, sb_err *e)
{
	if (neighbours(s, e))
		return e->code;
	const sb_fpmode fp = fpmode_enter(); /* as in step_once */
	const int bad = kernel_forces(s->kern, &s->law, &s->st, &s->nl, 1.0 / s->sc.dt, 0, NULL, e) < 0;
	if (!bad)
		integ_start(&s->in, &s->st, gy);
	fpmode_leave(fp);
	return bad ? e->code : 0;
}

