/* sample.c - one sample of each recorded quantity (sample.h). */
#include "sample.h"

#include <stdlib.h>

/* Journal a fixed-length row of record id (its tag, its length: record.h) and count it. */
static int put(sb_sim *s, int id, const double *row, int len, sb_err *e)
{
	if (journal_record(&s->jr, REC_TAG(id), row, len, e))
		return e->code;
	s->rec_n[id]++;
	return 0;
}
#define PUT(s, id, row, e) put(s, id, row, (int)(sizeof row / sizeof *row), e)

int sample_traj(sb_sim *s, double t, sb_err *e)
{
	const sb_state *st = &s->st;
	int i = s->intruder;
	double idt = 1.0 / s->sc.dt;
	const double row[REC_NCOLS(REC_COLS_TRAJ)] = {t,
				    st->q[C_X][0][i],
				    st->q[C_Y][0][i] + sim_box_y(s, t),
				    st->q[C_X][1][i] * idt,
				    st->q[C_Y][1][i] * idt + sim_box_v(s, t),
				    st->q[C_TH][1][i] * idt};
	return PUT(s, REC_TRAJ, row, e);
}

int sample_snap(sb_sim *s, double t, sb_err *e)
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
	int rc = journal_snap(&s->jr, REC_TAG(REC_SNAP), t, st->q[C_X][0], ylab, st->q[C_TH][0], vx, vy, e);
	free(lab);
	if (rc)
		return e->code;
	s->rec_n[REC_SNAP]++;
	return 0;
}

/* One row of the energy series (box frame; the state is the corrected one of a
 * step nobody fused). */
int sample_energy(sb_sim *s, double t, sb_err *e)
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
	const double row[REC_NCOLS(REC_COLS_ENERGY)] = {t, kt, kr, el, m > 0 ? my / m : 0, ov, (double)nc};
	return PUT(s, REC_ENERGY, row, e);
}

/* One frame of the contact dump: every contact of the corrected state, its disks by
 * id (box frame). */
int sample_contacts(sb_sim *s, double t, sb_err *e)
{
	const sb_state *st = &s->st;
	const long cap = (long)s->nl.nflat + s->nl.nseam; /* every pair of the list may touch */
	double *rec = malloc(sizeof(double) * (size_t)(2 + REC_NCOLS(REC_COLS_CONTACT) * (cap > 0 ? cap : 1)));
	if (!rec)
		return sb_errf(e, SB_ENOMEM, "out of memory for the contact dump");
	const long n = forces_contacts(&s->law, st, &s->nl, 1.0 / s->sc.dt, rec + 2, cap);
	rec[0] = t;
	rec[1] = (double)n;
	for (long k = 0; k < n; k++) { /* list indices -> the disks' ids */
		double *c = rec + 2 + REC_NCOLS(REC_COLS_CONTACT) * k;
		c[0] = st->id[(int)c[0]];
		c[1] = st->id[(int)c[1]];
	}
	int rc = journal_record(&s->jr, REC_TAG(REC_CONTACT), rec, (int)(2 + REC_NCOLS(REC_COLS_CONTACT) * n), e);
	free(rec);
	if (rc)
		return rc;
	s->max_contacts = n > s->max_contacts ? n : s->max_contacts;
	s->rec_n[REC_CONTACT]++;
	return 0;
}

int sample_flux(sb_sim *s, double t, sb_err *e)
{
	return obs_flux(&s->obs, &s->st, t, drive_freq(&s->drive, t), &s->jr, &s->rec_n[REC_FLUX], e);
}

int sample_field(sb_sim *s, double t, sb_err *e)
{
	return obs_field(&s->obs, &s->st, t, &s->jr, &s->rec_n[REC_FIELD], e);
}

int sample_ring(sb_sim *s, double t, sb_err *e)
{
	if (obs_ring(&s->obs, &s->st, s->intruder, t, 1.0 / s->sc.dt, &s->jr, e))
		return e->code;
	s->rec_n[REC_RING]++;
	return 0;
}

/* The bed's kinetic energy (translation and rotation of the mobile disks, box frame:
 * the box's own motion is not the bed's); h5out averages a period's samples. */
int sample_kinetic(sb_sim *s, double t, sb_err *e)
{
	const double row[REC_NCOLS(REC_COLS_KINETIC)] = {t, sim_kinetic(s)};
	return PUT(s, REC_KINETIC, row, e);
}

/* The bed's centre-of-mass height: the mass-weighted mean y of the mobile disks in the
 * box frame (above the floor's rest position: the box's own motion is not the bed's,
 * as for com_height_box of the energy series); h5out averages a period's samples. */
int sample_height(sb_sim *s, double t, sb_err *e)
{
	const sb_state *st = &s->st;
	double my = 0, m = 0;
	for (int i = 0; i < st->nm; i++) {
		my += st->m[i] * st->q[C_Y][0][i];
		m += st->m[i];
	}
	const double row[REC_NCOLS(REC_COLS_HEIGHT)] = {t, m > 0 ? my / m : 0};
	return PUT(s, REC_HEIGHT, row, e);
}
