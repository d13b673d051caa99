/* run.c - the shaking loop: steps, fused where nobody reads the corrected state, the
 * recording schedule of the recorded quantities (record.h's table: rates on an integer
 * step grid, the stroboscopic samples, the ring), checkpoints, progress, and the
 * overlap record's threshold. */
#include "run.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "checkpoint.h"
#include "clock.h"
#include "sample.h"
#include "step.h"

/* First step at or after time k * interval: integer schedule, no drift. */
static long due_step(long k, double interval, double dt)
{
	return (long)ceil(k * interval / dt - 1e-6);
}

/* What the run records and how often, from the table (record.h), fixed for the run:
 * worked out once, not in every step's decision. */
typedef struct sched {
	int on[REC_N];          /* the row is recorded */
	double interval[REC_N]; /* a rate row's sampling interval (s); a phase row's samples
				 * per period */
	int strobe;             /* stroboscopic samples are taken */
} sched;

/* Stroboscopic samples (phase 0 of each period) feed the rows on the strobe clock
 * (snapshots, flux, field); without any of them, or without a drive, there are none,
 * and no phase row is sampled either. */
static void sched_init(sched *c, const sb_sim *s)
{
	/* every row a sampler, of its length (sample.h; the rows themselves: sim_init) */
	assert(!sample_table_check());
	const sb_record *R = rec_table();
	const int drive = s->sc.ramp != RAMP_NONE || s->sc.frequency > 0;
	c->strobe = 0;
	for (int k = 0; k < REC_N; k++) {
		c->on[k] = sample_on(s, k) && (R[k].clock != RC_PHASE || drive);
		c->interval[k] = c->on[k] ? R[k].clock == RC_RATE ? 1.0 / rec_rate(&s->sc, k) : rec_rate(&s->sc, k) : 0;
		c->strobe |= R[k].clock == RC_STROBE && c->on[k];
	}
	c->strobe = c->strobe && drive;
}

/* A phase row at a constant frequency: the step of its next sample, at phase
 * (rec_n + 1) / N of the periods (an integer schedule, no drift); on a ramp the phase
 * itself decides (due), and there is no step to give. */
static long phase_next(const sb_sim *s, const sched *c, int k)
{
	if (s->sc.ramp != RAMP_NONE)
		return 0;
	return due_step(s->rec_n[k] + 1, 1.0 / (s->sc.frequency * c->interval[k]), s->sc.dt);
}

/* Is stroboscopic sample number n_strobe due at step n? Constant frequency: an integer
 * schedule (no drift); a ramp: the phase has passed 2 pi n_strobe. */
static int strobe_due(const sb_sim *s, const sched *c, long n)
{
	if (!c->strobe)
		return 0;
	if (s->sc.ramp == RAMP_NONE)
		return n >= s->next_strobe_step;
	return drive_cycles(&s->drive, n * s->sc.dt) >= s->n_strobe - 1e-9;
}

/* Is snapshot number rec_n[REC_SNAP] due at step n? The snapshots ride the strobe's
 * clock at N = snapshots_per_period times its rate, at phases k/N: the same integer
 * schedule (or, on a ramp, the phase), and with N = 1 the strobe's own steps exactly
 * (1.0 / (f * 1) is 1.0 / f), so that a run without the key holds the snapshots it
 * always did. Worked out from the count, not kept: nothing new in a checkpoint. */
static int snap_due(const sb_sim *s, const sched *c, long n)
{
	if (!c->strobe || !c->on[REC_SNAP])
		return 0;
	const double N = (double)s->sc.snapshots_per_period, k = (double)s->rec_n[REC_SNAP];
	if (s->sc.ramp == RAMP_NONE)
		return n >= due_step(s->rec_n[REC_SNAP], 1.0 / (s->sc.frequency * N), s->sc.dt);
	return drive_cycles(&s->drive, n * s->sc.dt) >= k / N - 1e-9;
}

/* Is a sample of row k due at step n? */
static int due(const sb_sim *s, const sched *c, int k, long n)
{
	if (!c->on[k])
		return 0;
	switch (rec_table()[k].clock) {
	case RC_RATE: return n >= s->rec_next[k];
	case RC_STROBE: return k == REC_SNAP ? snap_due(s, c, n) : strobe_due(s, c, n);
	case RC_RING: return obs_ring_due(&s->obs, n);
	case RC_PHASE:
		if (s->sc.ramp == RAMP_NONE)
			return n >= s->rec_next[k];
		return drive_cycles(&s->drive, n * s->sc.dt) >= (s->rec_n[k] + 1.0) / c->interval[k] - 1e-9;
	}
	return 0;
}

/* The samples due at this step, in the table's order: the rate and phase rows, then
 * one stroboscopic sample for every row on its clock. The ring is sampled before,
 * with the step (run_shaking). */
static int record(sb_sim *s, const sched *c, sb_err *e)
{
	const sb_scene *sc = &s->sc;
	const sb_record *R = rec_table();
	const double t = s->step * sc->dt;
	for (int k = 0; k < REC_N; k++) {
		if ((R[k].clock != RC_RATE && R[k].clock != RC_PHASE) || !due(s, c, k, s->step))
			continue;
		if (sample_take(s, k, t, e))
			return e->code;
		s->rec_next[k] = R[k].clock == RC_RATE ? due_step(s->rec_n[k], c->interval[k], sc->dt) : phase_next(s, c, k);
	}
	/* the snapshot first, as the first row on the strobe's clock (with N = 1, at the
	 * strobe's step: the order it always had) */
	if (snap_due(s, c, s->step) && sample_take(s, REC_SNAP, t, e))
		return e->code;
	if (strobe_due(s, c, s->step)) {
		for (int k = 0; k < REC_N; k++)
			if (R[k].clock == RC_STROBE && k != REC_SNAP && c->on[k] && sample_take(s, k, t, e))
				return e->code;
		obs_strobe_keep(&s->obs, &s->st);
		s->n_strobe++;
		if (sc->ramp == RAMP_NONE)
			s->next_strobe_step = due_step(s->n_strobe, 1.0 / sc->frequency, sc->dt);
	}
	return 0;
}

/* At most once a second (and at the end), the loop's progress to whoever wants it
 * (s->progress; bin/shake prints it). */
static void progress(sb_sim *s, double t0, long step0, double *last)
{
	double w = sb_now();
	if (w - *last < 1.0 && s->step < s->nsteps)
		return;
	*last = w;
	double rate = (s->step - step0) / fmax(w - t0, 1e-9);
	double eta = rate > 0 ? (s->nsteps - s->step) / rate : 0;
	s->progress(s->progress_ctx, &(sb_progress){PROG_SHAKING, .t = s->step * s->sc.dt, .t_end = s->sc.duration,
						    .steps_per_s = rate, .eta = eta});
}

/* The stop rules (docs/model.md, "Stop rules"): once the run's question is answered
 * the run ends - at a step after the one that answered it (which may have been fused,
 * its state not yet corrected), and never before anything that step would have
 * recorded - so that everything a stopped run holds is what the same run without the
 * rule holds up to then. The step it ends with is checkpointed (obs.stop_step), so a
 * restart across the stop ends at the same step. */
static void stop_rules(sb_sim *s)
{
	sb_obs *o = &s->obs;
	const sb_scene *sc = &s->sc;
	if (sc->stop == STOP_FLUX && o->have_band) { /* a period just ended */
		if (s->step * sc->dt > sc->stop_skip)
			obs_band_add(o);
		o->have_band = 0;
		if (!o->stop_step &&
		    obs_band_answered(o, 20, sc->stop_flux_se, sc->stop_flux_threshold, sc->stop_flux_k)) {
			o->stop_step = s->step + 1;
			o->stop_rule = STOP_FLUX;
		}
	}
	if (sc->stop == STOP_RISEN && o->risen && !o->stop_step) {
		const long k = llround(o->wait_time / sc->dt), after = llround(sc->stop_after / sc->dt);
		o->stop_step = k + (after > 1 ? after : 1);
		o->stop_rule = STOP_RISEN;
	}
	if (o->stop_step > 0 && o->stop_step < s->nsteps)
		s->nsteps = o->stop_step;
}

int run_shaking(sb_sim *s, sb_err *e)
{
	const sb_scene *sc = &s->sc;
	const double dt = sc->dt;
	const int resumed = s->step > 0 || s->rec_n[REC_TRAJ] > 0 || s->n_strobe > 0;
	sched c;
	sched_init(&c, s);
	if (!s->jr.f && !s->jr.discard && journal_open(&s->jr, s->journal_path, s->st.nm, -1, e))
		return e->code;
	if (!resumed) {
		s->n_ckpt = 0;
		s->next_ckpt_step = sc->checkpoint_every > 0 ? due_step(1, sc->checkpoint_every, dt) : -1;
		for (int k = 0; k < REC_N; k++) /* a phase row's first sample ends a period's first 1/N */
			if (rec_table()[k].clock == RC_PHASE && c.on[k])
				s->rec_next[k] = phase_next(s, &c, k);
		if (record(s, &c, e))
			return e->code;
	}
	stop_rules(s); /* a resumed run whose rule fired ends where it would have */
	s->ov_track = 1;
	step_arm_overlap(s);
	s->stage = "shaking";
	double w0 = sb_now(), wlast = w0, seg = w0; /* seg: loop time not yet in loop_seconds */
	long step0 = s->step;
	while (s->step < s->nsteps) {
		/* a stop waits until the state is corrected (not yet predicted) */
		if (s->stop && *s->stop && !s->predicted) {
			sim_fail(s, SB_EINTR, s->step * dt, s->step, "interrupted at t = %.6f s, step %ld", s->step * dt,
				 s->step);
			break;
		}
		const long n1 = s->step + 1;
		const double t1 = n1 * dt;
		const int ring = due(s, &c, REC_RING, n1);
		/* fuse unless this step's corrected state is recorded, checkpointed or final */
		int look = n1 >= s->nsteps || n1 == s->next_ckpt_step || (s->stop && *s->stop);
		for (int k = 0; k < REC_N && !look; k++)
			look = due(s, &c, k, n1);
		if (step_once(s, n1, -sc->gravity - sim_box_a(s, t1), 0, !look, ring ? s->obs.fabs_sum : NULL, e))
			break;
		s->step = n1;
		if (ring && sample_take(s, REC_RING, t1, e))
			break;
		TIC(s, PH_RECORD);
		if (record(s, &c, e))
			break;
		TOC(s, PH_RECORD);
		stop_rules(s);
		if (s->step == s->next_ckpt_step) {
			double w = sb_now(); /* the checkpoint carries the CPU time so far */
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
	s->loop_seconds += sb_now() - seg;
	if (s->progress && s->nsteps > 0) {
		progress(s, w0, step0, &wlast);
		s->progress(s->progress_ctx, &(sb_progress){PROG_SHAKEN, .t = s->step * dt, .t_end = sc->duration});
	}
	if (e->code && !s->status)
		sim_fail(s, e->code, s->step * dt, s->step, "%s", e->msg);
	return s->status;
}

