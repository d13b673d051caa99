/* journal.h - the append-only record stream of a run (trajectory rows, snapshots).
 * A checkpoint stores the journal's synced length; a restart truncates to it, so
 * what was recorded after the checkpoint is recorded again, once. The HDF5 output is
 * assembled from the journal when the run ends. */
#ifndef SB_JOURNAL_H
#define SB_JOURNAL_H

#include <stdio.h>

#include "err.h"

enum { JR_TRAJ = 1, JR_SNAP = 2, JR_FLUX = 3, JR_FIELD = 4, JR_ENERGY = 5, JR_CONTACT = 6, JR_RING = 7, JR_KINETIC = 8,
       JR_LAST = JR_KINETIC };
#define JR_CONTACT_COLS 8 /* per contact: id a, id b, F_N, F_S, n_x, n_y, x, y (box frame) */
#define JR_TRAJ_COLS 6
#define JR_RING_COLS 7 /* t, mean sum |F|, mean |net force|, temperature, grains, centre x, y (observe.h) */
#define JR_KINETIC_COLS 3 /* t, the bed's kinetic energy (box frame), drive frequency */
#define JR_ENERGY_COLS 7 /* t, kinetic (translational, rotational), elastic, com y, max overlap, contacts */

typedef struct sb_journal {
	FILE *f;
	char path[4200];
	int nm;
	int discard; /* opened with an empty path: records go nowhere (output = none) */
} sb_journal;

/* offset < 0: create anew; else reopen and truncate to offset. An empty path: a
 * journal that drops its records (a run without a run file has nothing to assemble). */
int journal_open(sb_journal *j, const char *path, int nm, long offset, sb_err *e);
/* Any record: a tag and count doubles. */
int journal_record(sb_journal *j, int tag, const double *data, int count, sb_err *e);
int journal_traj(sb_journal *j, const double row[JR_TRAJ_COLS], sb_err *e);
/* Snapshot: time, then x, y, theta, vx, vy of the nm mobile disks (lab frame). */
int journal_snap(sb_journal *j, double t, const double *x, const double *y, const double *th,
		 const double *vx, const double *vy, sb_err *e);
/* Flush and fsync; returns the durable length through *offset. */
int journal_sync(sb_journal *j, long *offset, sb_err *e);
void journal_close(sb_journal *j);

/* Reading back, record by record. */
typedef struct sb_jreader {
	FILE *f;
	int nm;
} sb_jreader;
int journal_reader_open(sb_jreader *r, const char *path, sb_err *e);
/* Next record into buf (capacity cap doubles): returns its tag and sets *count;
 * 0 at the end, < 0 on error. */
int journal_next(sb_jreader *r, double *buf, long cap, int *count, sb_err *e);
void journal_reader_close(sb_jreader *r);

#endif
