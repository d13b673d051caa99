/* record.c - the table of recorded quantities (record.h). */
#include "record.h"

#include <string.h>


#define REC_COL_(name, unit) {name, unit},
static const rec_col TRAJ[] = {REC_COLS_TRAJ(REC_COL_)};
static const rec_col ENERGY[] = {REC_COLS_ENERGY(REC_COL_)};
static const rec_col CONTACT[] = {REC_COLS_CONTACT(REC_COL_)}; /* per contact, after the frame's time and count */
static const rec_col RING[] = {REC_COLS_RING(REC_COL_)};
static const rec_col KINETIC[] = {REC_COLS_KINETIC(REC_COL_)};
static const rec_col HEIGHT[] = {REC_COLS_HEIGHT(REC_COL_)};
static const rec_col SEGREG[] = {REC_COLS_SEGREG(REC_COL_)};
static const rec_col INTRUDERS[] = {REC_COLS_INTRUDERS(REC_COL_)}; /* per intruder, after the time */
static const rec_col SLIDING[] = {REC_COLS_SLIDING(REC_COL_)};

/* a fixed-length row: its length and columns from one list */
#define FIXED(a) .len = (int)(sizeof a / sizeof *a), .cols = a, .ncols = (int)(sizeof a / sizeof *a)

static const sb_record TABLE[REC_N] = {
	[REC_TRAJ] = {"trajectory", "traj_rate", RC_RATE, FIXED(TRAJ), .h5 = REC_H5_INTRUDER, .flags = RECF_INTRUDER},
	[REC_SNAP] = {"snapshot", "snapshots", RC_STROBE, .h5 = REC_H5_BED},
	[REC_FLUX] = {"flux", "flux", RC_STROBE, .h5 = REC_H5_FLUX, .flags = RECF_OBS},
	[REC_FIELD] = {"field", "field", RC_STROBE, .h5 = REC_H5_FIELD, .flags = RECF_OBS},
	[REC_ENERGY] = {"energy", "energy_rate", RC_RATE, FIXED(ENERGY), .h5 = REC_H5_ENERGY, .flags = RECF_OBS,
			.def = "box frame: kinetic = sum m v^2 / 2 and I w^2 / 2 of the mobile disks; elastic = sum Y "
			       "xi^2 / 2 over the contacts (hertz: 2/5 Y sqrt(R_eff) xi^5/2; tangential = spring: plus "
			       "k_t xi_t^2 / 2); com_height_box = mass-weighted mean y of the mobile disks; "
			       "max_overlap = largest xi / min(R_i, R_j) at the sample (docs/model.md, \"Observables\")"},
	[REC_CONTACT] = {"contact", "contact_rate", RC_RATE, .cols = CONTACT, .ncols = REC_NCOLS(REC_COLS_CONTACT),
			 .h5 = REC_H5_CONTACTS, .flags = RECF_OBS},
	[REC_RING] = {"ring", "ring", RC_RING, FIXED(RING), .h5 = REC_H5_RING, .flags = RECF_OBS},
	[REC_KINETIC] = {"bed kinetic energy", "bed_kinetic_samples", RC_PHASE, FIXED(KINETIC),
			 .h5 = REC_H5_OBS "/bed_kinetic", .flags = RECF_OBS,
			 .def = "per drive period (time and step: its end): kinetic_energy = the mean of the mobile "
				"disks' sum m v^2 / 2 + I w^2 / 2 (box frame) at phases k/N, k = 1..N (N = "
				"samples_per_period); frequency = the drive's at the period's end"},
	[REC_HEIGHT] = {"bed height", "bed_height_samples", RC_PHASE, FIXED(HEIGHT), .h5 = REC_H5_OBS "/bed_height",
			.flags = RECF_OBS,
			.def = "per drive period (time and step: its end): com_height_box = the mean of the mobile "
			       "disks' centre-of-mass height sum m y / sum m (box frame: above the box floor's rest "
			       "position) at phases k/N, k = 1..N (N = samples_per_period); frequency = the drive's at "
			       "the period's end"},
	[REC_SEGREG] = {"segregation", "segregation_samples", RC_PHASE, FIXED(SEGREG),
			.h5 = REC_H5_OBS "/segregation", .flags = RECF_OBS,
			.def = "per drive period (time and step: its end): segregation_index = the mean of the grains' "
			       "segregation index S at phases k/N, k = 1..N (N = samples_per_period): S = D / D_max "
			       "(D >= 0) or D / |D_min| (D < 0), D the mean height of the large grains minus that of the "
			       "small (large: radius above the midpoint of the grains' smallest and largest), D_max and "
			       "D_min the same for these heights with the large grains all on top and all at the bottom "
			       "(docs/model.md, \"Segregation index\"); frequency = the drive's at the period's end"},
	[REC_INTRUDERS] = {"intruders", "traj_rate", RC_RATE, .cols = INTRUDERS, .ncols = REC_NCOLS(REC_COLS_INTRUDERS),
			   .h5 = REC_H5_INTRUDERS, .flags = RECF_INTRUDERS},
	[REC_SLIDING] = {"sliding contacts", "sliding_samples", RC_PHASE, FIXED(SLIDING), .h5 = REC_H5_OBS "/sliding",
			 .flags = RECF_OBS,
			 .def = "per drive period (time and step: its end): sliding_fraction = the mean, over phases "
				"k/N, k = 1..N (N = samples_per_period), of the fraction of contacts whose shear force "
				"the Coulomb limit mu |F_N| caps in the contact law evaluated at the sample (0 without "
				"contacts; docs/model.md, \"Sliding contacts\"); frequency = the drive's at the period's end"},
};

const sb_record *rec_table(void) { return TABLE; }

const char *rec_table_check(void) { return rec_rows_check(TABLE, REC_N); }

const char *rec_rows_check(const sb_record *rows, int n)
{
	for (int k = 0; k < n; k++) {
		const sb_record *r = &rows[k];
		const sb_param *p = r->key ? params_find(r->key) : NULL;
		if (!r->name || !p)
			return "a row without a name or with a key the parameter table lacks";
		const enum sb_ptype want = r->clock == RC_RATE ? PT_REAL : r->clock == RC_PHASE ? PT_INT : PT_BOOL;
		if (p->type != want)
			return "a row's key is not of its clock's type (rate: real, per period: int, else yes/no)";
		if (r->len > 0 && (r->ncols != r->len || !r->cols || strcmp(r->cols[0].name, "time")))
			return "a fixed-length row's columns differ from its length or do not start with time";
		if (r->clock == RC_PHASE && r->len <= 1)
			return "a per-period row without a fixed length and a value column (h5out averages its periods)";
		if (!r->h5)
			return "a row without a run-file group";
		for (int j = 0; j < k; j++)
			if (!strcmp(rows[j].h5, r->h5))
				return "two rows share a run-file group";
	}
	for (int k = 0; k < RSUM_N; k++) {
		const int row = rec_summary_row(k);
		if (row < 0 || row >= n || (row != REC_TRAJ && (!(rows[row].flags & RECF_OBS) || rows[row].len < 2)))
			return "a summary of a row that is neither the trajectory nor a fixed-length observable";
	}
	return NULL;
}

int rec_by_tag(int tag) { return tag >= REC_TAG(0) && tag < REC_TAG(REC_N) ? tag - REC_TAG(0) : -1; }

void rec_print_table(FILE *f)
{
	static const char *const clock[] = {[RC_RATE] = "rate", [RC_STROBE] = "strobe", [RC_RING] = "ring",
					    [RC_PHASE] = "phase"};
	fprintf(f, "name\tkey\tclock\ttag\tgroup\tcolumns\n");
	for (int k = 0; k < REC_N; k++) {
		const sb_record *r = &TABLE[k];
		fprintf(f, "%s\t%s\t%s\t%d\t%s\t", r->name, r->key, clock[r->clock], REC_TAG(k), r->h5);
		for (int c = 0; c < r->ncols; c++)
			fprintf(f, "%s%s[%s]", c ? "," : "", r->cols[c].name, r->cols[c].unit);
		fputc('\n', f);
	}
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

int rec_on(const sb_scene *sc, int n_intruders, int id)
{
	const sb_record *r = &TABLE[id];
	if (((r->flags & RECF_INTRUDER) && n_intruders < 1) || ((r->flags & RECF_INTRUDERS) && n_intruders < 2))
		return 0;
	return key_value(sc, r->key) > 0;
}

double rec_rate(const sb_scene *sc, int id) { return key_value(sc, TABLE[id].key); }

#define SUM_ATTR_(row, attr, how, unit, def) #attr,
#define SUM_ROW_(row, attr, how, unit, def) row,
#define SUM_HOW_(row, attr, how, unit, def) how,
static const char *const SUM_ATTR[RSUM_N] = {REC_SUMMARIES(SUM_ATTR_)};
static const int SUM_ROW[RSUM_N] = {REC_SUMMARIES(SUM_ROW_)};
static const int SUM_HOW[RSUM_N] = {REC_SUMMARIES(SUM_HOW_)};
/* h5out's intruder summary writes the trajectory's, its generic writer every other */
#define SUM_OWN_(row, attr, how, unit, def)                                                                  \
	_Static_assert(((row) == REC_TRAJ) == ((how) == RR_OWN), #attr ": RR_OWN is the trajectory's, only");
REC_SUMMARIES(SUM_OWN_)

const char *rec_summary_attr(int k) { return SUM_ATTR[k]; }
int rec_summary_row(int k) { return SUM_ROW[k]; }
int rec_summary_how(int k) { return SUM_HOW[k]; }
