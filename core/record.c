/* record.c - the table of recorded quantities (record.h). */
#include "record.h"

#include <string.h>

#include "params.h"
#include "sample.h"

static const rec_col TRAJ[] = {{"time", "s"}, {"x", "cm"}, {"y", "cm"}, {"vx", "cm s-1"}, {"vy", "cm s-1"},
			       {"omega", "rad s-1"}};
static const rec_col ENERGY[] = {{"time", "s"},         {"kinetic_translational", "erg"}, {"kinetic_rotational", "erg"},
				 {"elastic", "erg"},    {"com_height_box", "cm"},         {"max_overlap", "1"},
				 {"contacts", "1"}};
/* per contact, after the frame's time and count */
static const rec_col CONTACT[] = {{"id_a", "1"},     {"id_b", "1"},     {"normal_force", "dyn"}, {"tangential_force", "dyn"},
				  {"normal_x", "1"}, {"normal_y", "1"}, {"x", "cm"},             {"y_box", "cm"}};
static const rec_col RING[] = {{"time", "s"},          {"mean_force", "dyn"}, {"net_force", "dyn"}, {"temperature", "cm2 s-2"},
			       {"grains", "1"},        {"centre_x", "cm"},    {"centre_y", "cm"}};

static const rec_col KINETIC[] = {{"time", "s"}, {"kinetic_energy", "erg"}, {"frequency", "Hz"}};

_Static_assert(sizeof KINETIC / sizeof *KINETIC == JR_KINETIC_COLS, "a kinetic sample's columns");
_Static_assert(sizeof TRAJ / sizeof *TRAJ == JR_TRAJ_COLS, "a trajectory row's columns");
_Static_assert(sizeof ENERGY / sizeof *ENERGY == JR_ENERGY_COLS, "an energy row's columns");
_Static_assert(sizeof CONTACT / sizeof *CONTACT == JR_CONTACT_COLS, "a contact's columns");
_Static_assert(sizeof RING / sizeof *RING == JR_RING_COLS, "a ring row's columns");

/* a snapshot: time, then x, y, theta, vx, vy of every mobile disk (journal_snap) */
static long snap_len(const sb_sim *s, const double *rec) { (void)rec; return 1 + 5L * s->st.nm; }
static long flux_len(const sb_sim *s, const double *rec) { (void)rec; return obs_flux_len(&s->obs); }
static long field_len(const sb_sim *s, const double *rec) { (void)rec; return obs_field_len(&s->obs); }
/* a contact frame: time, count, count contacts */
static long contact_len(const sb_sim *s, const double *rec) { (void)s; return 2 + JR_CONTACT_COLS * (long)rec[1]; }

#define COLS(a) a, (int)(sizeof a / sizeof *a)

static const sb_record TABLE[REC_N] = {
	[REC_TRAJ] = {"trajectory", "traj_rate", RC_RATE, JR_TRAJ, JR_TRAJ_COLS, COLS(TRAJ), REC_H5_INTRUDER,
		      RECF_INTRUDER, sample_traj, NULL},
	[REC_SNAP] = {"snapshot", "snapshots", RC_STROBE, JR_SNAP, 0, NULL, 0, REC_H5_BED, 0, sample_snap, snap_len},
	[REC_FLUX] = {"flux", "flux", RC_STROBE, JR_FLUX, 0, NULL, 0, REC_H5_FLUX, RECF_OBS, sample_flux, flux_len},
	[REC_FIELD] = {"field", "field", RC_STROBE, JR_FIELD, 0, NULL, 0, REC_H5_FIELD, RECF_OBS, sample_field,
		       field_len},
	[REC_ENERGY] = {"energy", "energy_rate", RC_RATE, JR_ENERGY, JR_ENERGY_COLS, COLS(ENERGY), REC_H5_ENERGY,
			RECF_OBS, sample_energy, NULL},
	[REC_CONTACT] = {"contact", "contact_rate", RC_RATE, JR_CONTACT, 0, COLS(CONTACT), REC_H5_CONTACTS, RECF_OBS,
			 sample_contacts, contact_len},
	[REC_RING] = {"ring", "ring", RC_RING, JR_RING, JR_RING_COLS, COLS(RING), REC_H5_RING, RECF_OBS, sample_ring,
		      NULL},
	[REC_KINETIC] = {"bed kinetic energy", "bed_kinetic_samples", RC_PHASE, JR_KINETIC, JR_KINETIC_COLS,
			 COLS(KINETIC), REC_H5_KINETIC, RECF_OBS, sample_kinetic, NULL},
};

const sb_record *rec_table(void) { return TABLE; }

const char *rec_table_check(void)
{
	for (int k = 0; k < REC_N; k++) {
		const sb_record *r = &TABLE[k];
		const sb_param *p = r->key ? params_find(r->key) : NULL;
		if (!r->name || !p)
			return "a row without a name or with a key the parameter table lacks";
		const enum sb_ptype want = r->clock == RC_RATE ? PT_REAL : r->clock == RC_PHASE ? PT_INT : PT_BOOL;
		if (p->type != want)
			return "a row's key is not of its clock's type (rate: real, per period: int, else yes/no)";
		if (r->len > 0 ? r->ncols != r->len || !r->cols : !r->vlen)
			return "a fixed-length row's columns differ from its length, or a variable row has no length function";
		if (!r->sample || !r->h5)
			return "a row without a sampling function or a run-file group";
		for (int j = 0; j < k; j++)
			if (TABLE[j].tag == r->tag || !strcmp(TABLE[j].h5, r->h5))
				return "two rows share a journal tag or a run-file group";
	}
	return NULL;
}

int rec_by_tag(int tag)
{
	for (int k = 0; k < REC_N; k++)
		if (TABLE[k].tag == tag)
			return k;
	return -1;
}

/* The key's value in the scene: a rate (REAL), a count per period (INT) or a switch
 * (BOOL); the table's unit test holds every row's key to its clock's type. */
static double key_value(const sb_scene *sc, const char *key)
{
	const sb_param *p = params_find(key);
	const char *base = (const char *)sc + p->offset;
	return p->type == PT_REAL ? *(const double *)base : p->type == PT_INT ? (double)*(const long *)base
									 : *(const int *)base;
}

int rec_on(const sb_sim *s, int id)
{
	const sb_record *r = &TABLE[id];
	if ((r->flags & RECF_INTRUDER) && s->intruder < 0)
		return 0;
	return key_value(&s->sc, r->key) > 0;
}

double rec_rate(const sb_sim *s, int id) { return key_value(&s->sc, TABLE[id].key); }

long rec_len(const sb_sim *s, int id, const double *rec)
{
	return TABLE[id].len > 0 ? TABLE[id].len : TABLE[id].vlen(s, rec);
}

#define SUM_ATTR_(row, attr, unit, def) #attr,
#define SUM_ROW_(row, attr, unit, def) row,
static const char *const SUM_ATTR[RSUM_N] = {REC_SUMMARIES(SUM_ATTR_)};
static const int SUM_ROW[RSUM_N] = {REC_SUMMARIES(SUM_ROW_)};

const char *rec_summary_attr(int k) { return SUM_ATTR[k]; }
int rec_summary_row(int k) { return SUM_ROW[k]; }
