/* run.c - the shaking loop: steps, fused where nobody reads the corrected state, the
 * recording schedule (trajectory, snapshots, stroboscopic samples, the ring) on an
 * integer step grid, checkpoints, progress, and the overlap record's threshold. */
#include "run.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "checkpoint.h"
#include "clock.h"
#include "step.h"

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
	/* lab frame: shift y by y_box(t) and vy by v_box(t) */
	const double yb = sim_box_y(s, t), vb = sim_box_v(s, t), idt = 1.0 / s->sc.dt;
	const size_t nm = (size_t)st->nm;
	double *lab = malloc(sizeof(double) * 3 * (nm ? nm : 1));
	if (!lab)
		return sb_errf(e, SB_ENOMEM, "out of memory for a snapshot");
	double *ylab = lab, *vx = lab + nm, *vy = lab + 2 * nm;
	for (size_t i = 0; i < nm; i++) {
		ylab[i] = st->q[C_Y][0][i] + yb;
		vx[i] = st->q[C_X][1][i] * idt;
		vy[i] = st->q[C_Y][1][i] * idt + vb;
	}
	int rc = journal_snap(&s->jr, t, st->q[C_X][0], ylab, st->q[C_TH][0], vx, vy, e);
	free(lab);
	if (rc)
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

/* One row of the energy series (box frame; the state is the corrected one of a
 * step nobody fused). */
static int record_energy(sb_sim *s, double t, sb_err *e)
{
	const sb_state *st = &s->st;
	const double idt = 1.0 / s->sc.dt;
	double kt = 0, kr = 0, my = 0, m = 0, el, ov;
	long nc;
	for (int i = 0; i < st->nm; i++) {
		const double vx = st->q[C_X][1][i] * idt, vy = st->q[C_Y][1][i] * idt, w = st->q[C_TH][1][i] * idt;
		kt += 0.5 * st->m[i] * (vx * vx + vy * vy);
		kr += 0.5 * w * w / st->inv_i[i];
		my += st->m[i] * st->q[C_Y][0][i];
		m += st->m[i];
	}
	forces_contact_energy(&s->law, st, &s->nl, &el, &ov, &nc);
	const double row[JR_ENERGY_COLS] = {t, kt, kr, el, m > 0 ? my / m : 0, ov, (double)nc};
	if (journal_record(&s->jr, JR_ENERGY, row, JR_ENERGY_COLS, e))
		return e->code;
	s->n_energy++;
	return 0;
}

/* One frame of the contact dump: every contact of the corrected state, its disks by
 * id (box frame). */
static int record_contacts(sb_sim *s, double t, sb_err *e)
{
	const sb_state *st = &s->st;
	const long cap = (long)s->nl.nflat + s->nl.nseam; /* every pair of the list may touch */
	double *rec = malloc(sizeof(double) * (size_t)(2 + JR_CONTACT_COLS * (cap > 0 ? cap : 1)));
	if (!rec)
		return sb_errf(e, SB_ENOMEM, "out of memory for the contact dump");
	const long n = forces_contacts(&s->law, st, &s->nl, 1.0 / s->sc.dt, rec + 2, cap);
	rec[0] = t;
	rec[1] = (double)n;
	for (long k = 0; k < n; k++) { /* list indices -> the disks' ids */
		double *c = rec + 2 + JR_CONTACT_COLS * k;
		c[0] = st->id[(int)c[0]];
		c[1] = st->id[(int)c[1]];
	}
	int rc = journal_record(&s->jr, JR_CONTACT, rec, (int)(2 + JR_CONTACT_COLS * n), e);
	free(rec);
	if (rc)
		return rc;
	s->max_contacts = n > s->max_contacts ? n : s->max_contacts;
	s->n_contact++;
	return 0;
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
	if (sc->energy_rate > 0 && s->step >= s->next_energy_step) {
		if (record_energy(s, t, e))
			return e->code;
		s->next_energy_step = due_step(s->n_energy, 1.0 / sc->energy_rate, sc->dt);
	}
	if (sc->contact_rate > 0 && s->step >= s->next_contact_step) {
		if (record_contacts(s, t, e))
			return e->code;
		s->next_contact_step = due_step(s->n_contact, 1.0 / sc->contact_rate, sc->dt);
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
	double w = sb_now();
	if (w - *last < 1.0 && s->step < s->nsteps)
		return;
	*last = w;
	double rate = (s->step - step0) / fmax(w - t0, 1e-9);
	double eta = rate > 0 ? (s->nsteps - s->step) / rate : 0;
	fprintf(stderr, "\rshake: t = %.2f / %.2f s  %.0f steps/s  ETA %02d:%02d:%02d ", s->step * s->sc.dt,
		s->sc.duration, rate, (int)(eta / 3600), (int)fmod(eta / 60, 60), (int)fmod(eta, 60));
	fflush(stderr);
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

int sim_run(sb_sim *s, sb_err *e)
{
	const sb_scene *sc = &s->sc;
	const double dt = sc->dt;
	const int resumed = s->step > 0 || s->n_traj > 0 || s->n_strobe > 0;
	if (!s->jr.f && !s->jr.discard && journal_open(&s->jr, s->journal_path, s->st.nm, -1, e))
		return e->code;
	if (!resumed) {
		s->n_ckpt = 0;
		s->next_ckpt_step = sc->checkpoint_every > 0 ? due_step(1, sc->checkpoint_every, dt) : -1;
		if (record(s, e))
			return e->code;
	}
	stop_rules(s); /* a resumed run whose rule fired ends where it would have */
	s->ov_track = 1;
	step_arm_overlap(s);
	double w0 = sb_now(), wlast = w0, seg = w0; /* seg: loop time not yet in loop_seconds */
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
		const int ring = obs_ring_due(&s->obs, n1);
		/* fuse unless this step's corrected state is recorded, checkpointed or final */
		const int look = n1 >= s->nsteps || n1 == s->next_ckpt_step || (s->stop && *s->stop) || ring ||
				 (s->intruder >= 0 && sc->traj_rate > 0 && n1 >= s->next_traj_step) ||
				 (sc->energy_rate > 0 && n1 >= s->next_energy_step) ||
				 (sc->contact_rate > 0 && n1 >= s->next_contact_step) ||
				 strobe_due(s, n1);
		if (step_once(s, -sc->gravity - sim_box_a(s, t1), 0, t1, n1, "shaking", !look,
			      ring ? s->obs.fabs_sum : NULL, e))
			break;
		s->step = n1;
		if (ring && obs_ring(&s->obs, &s->st, s->intruder, t1, 1.0 / dt, &s->jr, e))
			break;
		TIC(PH_RECORD);
		if (record(s, e))
			break;
		TOC(PH_RECORD);
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

