/* record.h - the recorded quantities, in one table as the parameter table is for the
 * inputs: per quantity its switch or rate key, its clock, its journal record and
 * columns, its place in the run file and its sampling function; and the per-run
 * summaries that become result columns. The table drives the recording schedule and
 * the fusion decision (run.c), the counters and their checkpoint fields (sim.h,
 * checkpoint.c), the reading of the journal and the observables' writer (h5out.c);
 * lib/results.c makes a result column of every summary. Layout: docs/output.md. */
#ifndef SB_RECORD_H
#define SB_RECORD_H

#include "err.h"

struct sb_sim;

/* The rows: the order the run file's groups are written in; a step records the rate
 * rows in this order, then the stroboscopic ones (run.c). */
enum rec_id { REC_TRAJ, REC_SNAP, REC_FLUX, REC_FIELD, REC_ENERGY, REC_CONTACT, REC_RING, REC_KINETIC, REC_N };

/* When a quantity is sampled:
 *   RC_RATE    at its key's rate (Hz), on an integer step grid (no drift);
 *   RC_STROBE  at phase 0 of every drive period (the stroboscopic samples);
 *   RC_PHASE   its key's number of times per drive period, at phases k/N, k = 1..N
 *              (the last at the period's end; an integer step grid at a constant
 *              frequency, the phase itself on a ramp);
 *   RC_RING    on the ring's own schedule (observe.h: a rate or every n steps; the
 *              force kernel sums |F| on its steps, so it is sampled before the rest). */
enum rec_clock { RC_RATE, RC_STROBE, RC_RING, RC_PHASE };

/* Row flags. */
enum {
	RECF_INTRUDER = 1, /* recorded only when the scene has an intruder */
	RECF_OBS = 2,      /* a group of /observables, written by h5out's observables loop */
};

/* Where the quantities live in the run file: spelled here once, for the engine's
 * writer and for the readers (lib/runfile.h). */
#define REC_H5_INTRUDER "/particles/intruder"
#define REC_H5_BED "/particles/bed"
#define REC_H5_OBS "/observables"
#define REC_H5_ENERGY REC_H5_OBS "/energy"
#define REC_H5_CONTACTS REC_H5_OBS "/contacts"
#define REC_H5_FLUX REC_H5_OBS "/flux"
#define REC_H5_FIELD REC_H5_OBS "/field"
#define REC_H5_RING REC_H5_OBS "/ring"
#define REC_H5_KINETIC REC_H5_OBS "/bed_kinetic"

/* One column of a journal record (for a variable record: of each of its items). */
typedef struct rec_col {
	const char *name, *unit;
} rec_col;

typedef struct sb_record {
	const char *name;     /* what it is, in messages */
	const char *key;      /* its switch (yes/no), rate (Hz) or samples-per-period key
	                       * (params.h; 0 = off) */
	enum rec_clock clock;
	int tag;              /* its journal record (journal.h) */
	int len;              /* doubles per record; 0: the scene's (vlen) */
	const rec_col *cols;  /* the record's columns (len > 0) or each item's (len = 0) */
	int ncols;
	const char *h5;       /* its group in the run file */
	unsigned flags;
	/* the sampling function: one sample of the corrected state at time t, journaled */
	int (*sample)(struct sb_sim *s, double t, sb_err *e);
	/* len = 0: the length of the record that starts at rec */
	long (*vlen)(const struct sb_sim *s, const double *rec);
} sb_record;

/* The table, REC_N rows indexed by enum rec_id. */
const sb_record *rec_table(void);
/* The table's own invariants (asserted at sim_init in the test build): NULL, or the
 * first one a row breaks - every row's key in the parameter table, of its clock's
 * type; a fixed-length row's columns as many as its doubles; a variable row's length
 * function; a sampling function; tags and run-file groups distinct. */
const char *rec_table_check(void);
/* The row of a journal tag, -1 if none. */
int rec_by_tag(int tag);
/* Does the scene ask for it (its key on; an intruder where the row needs one)? */
int rec_on(const struct sb_sim *s, int id);
/* A rate row's rate (Hz), a phase row's samples per period: its key's value. */
double rec_rate(const struct sb_sim *s, int id);
/* The length of the record of row id that starts at rec. */
long rec_len(const struct sb_sim *s, int id, const double *rec);

/* The per-run summaries: attributes of the run file's root, one value per run, written
 * from a recorded quantity when the run ends; lib/results.c makes each a result
 * column (REAL, same name). X(row, attribute, unit, definition). */
#define REC_SUMMARIES(X)                                                                                       \
	X(REC_TRAJ, intruder_final_y_box, "cm",                                                                \
	  "the intruder centre's height at the last trajectory row, box frame; NULL without a trajectory")     \
	X(REC_TRAJ, intruder_max_y_box, "cm", "highest intruder centre over the trajectory rows, box frame")   \
	X(REC_TRAJ, intruder_min_y_box, "cm", "lowest intruder centre over the trajectory rows, box frame")    \
	X(REC_TRAJ, intruder_mean_y_box, "cm", "mean intruder centre height over the trajectory rows, box frame") \
	X(REC_KINETIC, bed_kinetic_mean, "erg",                                                                \
	  "the mobile disks' kinetic energy (translation and rotation, box frame) averaged over the drive "     \
	  "periods of the run, bed_kinetic_samples samples each; NULL when not recorded or no period ended")

#define REC_SUM_ENUM_(row, attr, unit, def) RSUM_##attr,
enum rec_summary { REC_SUMMARIES(REC_SUM_ENUM_) RSUM_N };
#undef REC_SUM_ENUM_

/* A summary's attribute name and its row. */
const char *rec_summary_attr(int k);
int rec_summary_row(int k);

#endif
