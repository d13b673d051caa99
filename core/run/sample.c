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

static int sample_traj(sb_sim *s, double t, sb_err *e)
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

static int sample_snap(sb_sim *s, double t, sb_err *e)
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
static int sample_energy(sb_sim *s, double t, sb_err *e)
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
	forces_contact_energy(&s->law, st, &s->nl, kernel_shear(s->kern), &el, &ov, &nc);
	const double row[REC_NCOLS(REC_COLS_ENERGY)] = {t, kt, kr, el, m > 0 ? my / m : 0, ov, (double)nc};
	return PUT(s, REC_ENERGY, row, e);
}

/* One frame of the contact dump: every contact of the corrected state, its disks by
 * id (box frame). */
static int sample_contacts(sb_sim *s, double t, sb_err *e)
{
	const sb_state *st = &s->st;
	const long cap = (long)s->nl.nflat + s->nl.nseam; /* every pair of the list may touch */
	double *rec = malloc(sizeof(double) * (size_t)(2 + REC_NCOLS(REC_COLS_CONTACT) * (cap > 0 ? cap : 1)));
	if (!rec)
		return sb_errf(e, SB_ENOMEM, "out of memory for the contact dump");
	const long n = forces_contacts(&s->law, st, &s->nl, kernel_shear(s->kern), 1.0 / s->sc.dt, rec + 2, cap);
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

/* The flux record of a strobe (when one is due: obs_flux_due), journaled and counted. */
static int flux_put(sb_obs *o, const sb_state *st, double t, double f, sb_journal *jr, long *n, sb_err *e)
{
	if (!obs_flux_due(o))
		return 0;
	double *rec = malloc(sizeof(double) * (size_t)obs_flux_len(o));
	if (!rec)
		return sb_errf(e, SB_ENOMEM, "out of memory for the flux record");
	obs_flux(o, st, t, f, rec);
	int rc = journal_record(jr, REC_TAG(REC_FLUX), rec, obs_flux_len(o), e);
	free(rec);
	if (rc)
		return rc;
	(*n)++;
	return 0;
}

/* The field's sample of a strobe; its record when a block is complete, journaled and
 * counted. */
static int field_put(sb_obs *o, const sb_state *st, double t, sb_journal *jr, long *n, sb_err *e)
{
	if (!obs_field_add(o, st))
		return 0;
	double *rec = malloc(sizeof(double) * (size_t)obs_field_len(o));
	if (!rec)
		return sb_errf(e, SB_ENOMEM, "out of memory for the field record");
	obs_field_take(o, t, rec);
	int rc = journal_record(jr, REC_TAG(REC_FIELD), rec, obs_field_len(o), e);
	free(rec);
	if (rc)
		return rc;
	(*n)++;
	return 0;
}

int sample_obs_strobe(sb_obs *o, const sb_state *st, double t, double f, sb_journal *jr, long *nflux, long *nfield,
		      sb_err *e)
{
	if (flux_put(o, st, t, f, jr, nflux, e) || field_put(o, st, t, jr, nfield, e))
		return e->code;
	obs_strobe_keep(o, st);
	return 0;
}

static int sample_flux(sb_sim *s, double t, sb_err *e)
{
	return flux_put(&s->obs, &s->st, t, drive_freq(&s->drive, t), &s->jr, &s->rec_n[REC_FLUX], e);
}

static int sample_field(sb_sim *s, double t, sb_err *e)
{
	return field_put(&s->obs, &s->st, t, &s->jr, &s->rec_n[REC_FIELD], e);
}

_Static_assert(OBS_RING_COLS == REC_NCOLS(REC_COLS_RING), "a ring sample's row is the ring's record (record.h)");

static int sample_ring(sb_sim *s, double t, sb_err *e)
{
	double row[OBS_RING_COLS];
	obs_ring_sample(&s->obs, &s->st, s->intruder, t, 1.0 / s->sc.dt, row);
	return PUT(s, REC_RING, row, e);
}

/* The bed's kinetic energy (translation and rotation of the mobile disks, box frame:
 * the box's own motion is not the bed's); h5out averages a period's samples. */
static int sample_kinetic(sb_sim *s, double t, sb_err *e)
{
	const double row[REC_NCOLS(REC_COLS_KINETIC)] = {t, sim_kinetic(s)};
	return PUT(s, REC_KINETIC, row, e);
}

/* The bed's centre-of-mass height: the mass-weighted mean y of the mobile disks in the
 * box frame (above the floor's rest position: the box's own motion is not the bed's,
 * as for com_height_box of the energy series); h5out averages a period's samples. */
static int sample_height(sb_sim *s, double t, sb_err *e)
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

/* Several intruders' positions (lab frame, as the trajectory's), in the state's order:
 * time, then x, y of each (docs/model.md, "Several intruders"). */
static int sample_intruders(sb_sim *s, double t, sb_err *e)
{
	const sb_state *st = &s->st;
	const int n = s->obs.nint;
	double *row = malloc(sizeof(double) * (size_t)(1 + 2 * n));
	if (!row)
		return sb_errf(e, SB_ENOMEM, "out of memory for the intruders' positions");
	row[0] = t;
	for (int k = 0; k < n; k++) {
		row[1 + 2 * k] = st->q[C_X][0][s->obs.iidx[k]];
		row[2 + 2 * k] = st->q[C_Y][0][s->obs.iidx[k]] + sim_box_y(s, t);
	}
	const int rc = put(s, REC_INTRUDERS, row, 1 + 2 * n, e);
	free(row);
	return rc;
}

/* The grains' segregation index (docs/model.md, "Segregation index"; observe.h), from
 * their heights in the box frame (S is the same in any frame: differences of heights
 * over differences); large and small divided at the midpoint of the grains' radii,
 * which sim_derive has checked are of two sizes. h5out averages a period's samples. */
static int sample_segregation(sb_sim *s, double t, sb_err *e)
{
	const sb_state *st = &s->st;
	double split;
	obs_segregation_split(st->r, st->kind, st->nm, &split);
	double *work = malloc(sizeof(double) * (size_t)(st->nm ? st->nm : 1));
	if (!work)
		return sb_errf(e, SB_ENOMEM, "out of memory for the segregation index");
	const double row[REC_NCOLS(REC_COLS_SEGREG)] = {
		t, obs_segregation(st->q[C_Y][0], st->r, st->kind, st->nm, split, work)};
	free(work);
	return PUT(s, REC_SEGREG, row, e);
}

/* The fraction of contacts at the Coulomb limit (forces_sliding: the law evaluated at
 * the sample); h5out averages a period's samples. */
static int sample_sliding(sb_sim *s, double t, sb_err *e)
{
	long contacts = 0;
	const long n = forces_sliding(&s->law, &s->st, &s->nl, kernel_shear(s->kern), 1.0 / s->sc.dt, &contacts);
	const double row[REC_NCOLS(REC_COLS_SLIDING)] = {t, contacts ? (double)n / (double)contacts : 0};
	return PUT(s, REC_SLIDING, row, e);
}

/* a snapshot: time, then x, y, theta, vx, vy of every mobile disk (journal_snap) */
static long snap_len(const sb_sim *s, const double *rec) { (void)rec; return 1 + 5L * s->st.nm; }
static long flux_len(const sb_sim *s, const double *rec) { (void)rec; return obs_flux_len(&s->obs); }
static long field_len(const sb_sim *s, const double *rec) { (void)rec; return obs_field_len(&s->obs); }
static long intruders_len(const sb_sim *s, const double *rec) { (void)rec; return 1 + 2L * s->n_intruders; }
/* a contact frame: time, count, count contacts */
static long contact_len(const sb_sim *s, const double *rec)
{
	(void)s;
	return 2 + REC_NCOLS(REC_COLS_CONTACT) * (long)rec[1];
}

static const sb_sampler TABLE[REC_N] = {
	[REC_TRAJ] = {sample_traj, NULL},
	[REC_SNAP] = {sample_snap, snap_len},
	[REC_FLUX] = {sample_flux, flux_len},
	[REC_FIELD] = {sample_field, field_len},
	[REC_ENERGY] = {sample_energy, NULL},
	[REC_CONTACT] = {sample_contacts, contact_len},
	[REC_RING] = {sample_ring, NULL},
	[REC_KINETIC] = {sample_kinetic, NULL},
	[REC_HEIGHT] = {sample_height, NULL},
	[REC_SEGREG] = {sample_segregation, NULL},
	[REC_INTRUDERS] = {sample_intruders, intruders_len},
	[REC_SLIDING] = {sample_sliding, NULL},
};

const sb_sampler *sample_table(void) { return TABLE; }

const char *sample_rows_check(const sb_sampler *rows, int n)
{
	const sb_record *R = rec_table();
	for (int k = 0; k < n && k < REC_N; k++) {
		if (!rows[k].take)
			return "a row without a sampling function";
		if (!R[k].len != !!rows[k].vlen)
			return "a variable row without a length function, or a fixed-length row with one";
	}
	return n == REC_N ? NULL : "not one sampler per row of the table";
}

const char *sample_table_check(void) { return sample_rows_check(TABLE, REC_N); }

int sample_take(sb_sim *s, int id, double t, sb_err *e) { return TABLE[id].take(s, t, e); }

int sample_on(const sb_sim *s, int id) { return rec_on(&s->sc, s->n_intruders, id); }

long sample_len(const sb_sim *s, int id, const double *rec)
{
	const sb_record *r = &rec_table()[id];
	return r->len > 0 ? r->len : TABLE[id].vlen(s, rec);
}
