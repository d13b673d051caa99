/* record.h - the recorded quantities, in one table as the parameter table is for the
 * inputs: per quantity its switch or rate key, its clock, its journal record and
 * columns and its place in the run file; and the per-run summaries that become result
 * columns. The table drives the recording schedule and the fusion decision (run.c),
 * the counters and their checkpoint fields (sim.h, checkpoint.c), the reading of the
 * journal and the observables' writer (h5out.c); each row's sampling function is
 * bound to it by the run's room (core/run/sample.c), which this table does not know;
 * lib/results.c makes a result column of every summary. Layout: docs/output.md. */
#ifndef SB_RECORD_H
#define SB_RECORD_H

#include <stdio.h>

#include "params.h"

/* The rows: the order the run file's groups are written in; a step records the rate
 * and per-period rows in this order, then the stroboscopic ones (run.c). A row's
 * journal tag is its index + 1 (REC_TAG; 0 is never one): a journal is read back only
 * by the build that wrote it (a checkpoint of another table, another REC_N, is not
 * resumed: checkpoint.c). A new row goes at the end. */
enum rec_id { REC_TRAJ, REC_SNAP, REC_FLUX, REC_FIELD, REC_ENERGY, REC_CONTACT, REC_RING, REC_KINETIC, REC_HEIGHT,
	      REC_SEGREG, REC_INTRUDERS, REC_SLIDING, REC_N };
#define REC_TAG(id) ((id) + 1)

/* When a quantity is sampled (the clock a new row picks; run.c keeps them all):
 *   RC_RATE    at its key's rate (Hz), on an integer step grid (no drift);
 *   RC_STROBE  at phase 0 of every drive period (the stroboscopic samples);
 *   RC_PHASE   its key's number of times per drive period, at phases k/N, k = 1..N
 *              (the last at the period's end; an integer step grid at a constant
 *              frequency, the phase itself on a ramp); h5out averages each period's
 *              samples into one row at the period's end, with the drive frequency there;
 *   RC_RING    on the ring's own schedule (observe.h: a rate or every n steps; the
 *              force kernel sums |F| on its steps, so it is sampled before the rest). */
enum rec_clock { RC_RATE, RC_STROBE, RC_RING, RC_PHASE };

/* Row flags. */
enum {
	RECF_INTRUDER = 1, /* recorded only when the scene has an intruder */
	RECF_OBS = 2,      /* a group of /observables, written by h5out's observables loop */
	RECF_INTRUDERS = 4, /* recorded only when the scene has several intruders */
};

/* Where the quantities live in the run file: spelled here once, for the engine's
 * writer and for the readers (lib/runfile.h). */
#define REC_H5_INTRUDER "/particles/intruder"
#define REC_H5_BED "/particles/bed"
#define REC_H5_INTRUDERS "/particles/intruders"
#define REC_H5_OBS "/observables"
#define REC_H5_ENERGY REC_H5_OBS "/energy"
#define REC_H5_CONTACTS REC_H5_OBS "/contacts"
#define REC_H5_FLUX REC_H5_OBS "/flux"
#define REC_H5_FIELD REC_H5_OBS "/field"
#define REC_H5_RING REC_H5_OBS "/ring"

/* The columns of the fixed-length records, time first (the contact frame's: of each
 * contact), X(name, unit): the table's columns (record.c), the samplers' row lengths
 * (REC_NCOLS) and, for a row without a writer of its own, the run file's elements. */
#define REC_COLS_TRAJ(X)                                                                                       \
	X("time", "s") X("x", "cm") X("y", "cm") X("vx", "cm s-1") X("vy", "cm s-1") X("omega", "rad s-1")
#define REC_COLS_ENERGY(X)                                                                                     \
	X("time", "s") X("kinetic_translational", "erg") X("kinetic_rotational", "erg") X("elastic", "erg")      \
	X("com_height_box", "cm") X("max_overlap", "1") X("contacts", "1")
#define REC_COLS_CONTACT(X)                                                                                    \
	X("id_a", "1") X("id_b", "1") X("normal_force", "dyn") X("tangential_force", "dyn") X("normal_x", "1")   \
	X("normal_y", "1") X("x", "cm") X("y_box", "cm")
#define REC_COLS_RING(X)                                                                                       \
	X("time", "s") X("mean_force", "dyn") X("net_force", "dyn") X("temperature", "cm+2 s-2") X("grains", "1") \
	X("centre_x", "cm") X("centre_y", "cm")
#define REC_COLS_KINETIC(X) X("time", "s") X("kinetic_energy", "erg")
#define REC_COLS_HEIGHT(X) X("time", "s") X("com_height_box", "cm")
#define REC_COLS_SEGREG(X) X("time", "s") X("segregation_index", "1")
/* several intruders' positions: time, then of each intruder (lab frame, as the trajectory) */
#define REC_COLS_INTRUDERS(X) X("x", "cm") X("y", "cm")
#define REC_COLS_SLIDING(X) X("time", "s") X("sliding_fraction", "1")

#define REC_COL_COUNT_(name, unit) +1
/* A column list's length, a constant expression: REC_NCOLS(REC_COLS_TRAJ) = 6. */
#define REC_NCOLS(list) (0 list(REC_COL_COUNT_))

/* One column of a journal record (for a variable record: of each of its items). */
typedef struct rec_col {
	const char *name, *unit;
} rec_col;

typedef struct sb_record {
	const char *name;     /* what it is, in messages */
	const char *key;      /* its switch (yes/no), rate (Hz) or samples-per-period key
	                       * (params.h; 0 = off) */
	enum rec_clock clock;
	int len;              /* doubles per record; 0: the scene's (vlen) */
	const rec_col *cols;  /* the record's columns (len > 0) or each item's (len = 0) */
	int ncols;
	const char *h5;       /* its group in the run file */
	unsigned flags;
	/* a fixed-length observable without a writer of its own (h5out.c): its group's
	 * definition attribute */
	const char *def;
} sb_record;

/* The table, REC_N rows indexed by enum rec_id. */
const sb_record *rec_table(void);
/* The table's own invariants (asserted at sim_init in the test build): NULL, or the
 * first one a row breaks - every row's key in the parameter table, of its clock's
 * type; a fixed-length row's columns as many as its doubles, time first; a
 * per-period row of fixed length; run-file groups distinct; every summary's row the trajectory (h5out's intruder
 * summary) or a fixed-length observable with a value column. */
const char *rec_table_check(void);
/* The same for n rows laid out as the table (its test breaks a copy of it). */
const char *rec_rows_check(const sb_record *rows, int n);
/* The row of a journal tag (REC_TAG), -1 if none. */
int rec_by_tag(int tag);
/* The table as TSV for tools (shake --records): name, key, clock (rate, strobe, ring,
 * phase), journal tag, run-file group, columns as name[unit] joined by commas. */
void rec_print_table(FILE *f);
/* Does the scene ask for it (its key on; an intruder, or several, where the row needs
 * them: n_intruders, the run's number)? */
int rec_on(const sb_scene *sc, int n_intruders, int id);
/* A rate row's rate (Hz), a phase row's samples per period: its key's value. */
double rec_rate(const sb_scene *sc, int id);

/* The per-run summaries: attributes of the run file's root, one value per run, written
 * from a recorded quantity when the run ends; lib/results.c makes each a result
 * column (REAL, same name). X(row, attribute, reduction, unit, definition). The
 * trajectory's (RR_OWN) are h5out's intruder summary; any other row's is, over the
 * rows the run file holds (h5out's writer of fixed-length observables), the mean
 * (RR_MEAN) or the last row's value (RR_LAST) of its first value column. */
enum rec_reduce { RR_OWN, RR_MEAN, RR_LAST };
#define REC_SUMMARIES(X)                                                                                       \
	X(REC_TRAJ, intruder_final_y_box, RR_OWN, "cm",                                                        \
	  "the intruder centre's height at the last trajectory row, box frame; NULL without a trajectory")     \
	X(REC_TRAJ, intruder_max_y_box, RR_OWN, "cm", "highest intruder centre over the trajectory rows, box frame") \
	X(REC_TRAJ, intruder_min_y_box, RR_OWN, "cm", "lowest intruder centre over the trajectory rows, box frame") \
	X(REC_TRAJ, intruder_mean_y_box, RR_OWN, "cm",                                                         \
	  "mean intruder centre height over the trajectory rows, box frame")                                   \
	X(REC_KINETIC, bed_kinetic_mean, RR_MEAN, "erg",                                                       \
	  "the mobile disks' kinetic energy (translation and rotation, box frame) averaged over the drive "     \
	  "periods of the run, bed_kinetic_samples samples each; NULL when not recorded or no period ended")    \
	X(REC_HEIGHT, bed_height_mean, RR_MEAN, "cm",                                                          \
	  "the mobile disks' centre-of-mass height (box frame) averaged over the drive periods of the run, "   \
	  "bed_height_samples samples each; NULL when not recorded or no period ended")                        \
	X(REC_SEGREG, segregation_index_mean, RR_MEAN, "",                                                     \
	  "the grains' segregation index (docs/model.md, \"Segregation index\": +1 large all above small, -1 " \
	  "all below, 0 equal mean heights) averaged over the drive periods of the run, segregation_samples "  \
	  "samples each; NULL when not recorded or no period ended")                                          \
	X(REC_SEGREG, segregation_index_final, RR_LAST, "",                                                    \
	  "the grains' segregation index of the run's last drive period; NULL when not recorded or no period " \
	  "ended")                                                                                            \
	X(REC_SLIDING, sliding_mean, RR_MEAN, "1",                                                                      \
	  "the fraction of contacts at the Coulomb limit (sliding) averaged over the drive periods of the run, " \
	  "sliding_samples samples each; NULL when not recorded or no period ended")

#define REC_SUM_ENUM_(row, attr, how, unit, def) RSUM_##attr,
enum rec_summary { REC_SUMMARIES(REC_SUM_ENUM_) RSUM_N };
#undef REC_SUM_ENUM_

/* A summary's attribute name, its row and its reduction (enum rec_reduce). */
const char *rec_summary_attr(int k);
int rec_summary_row(int k);
int rec_summary_how(int k);

#endif
