/* journal.h - the append-only record stream of a run: records of a tag and doubles,
 * the tag and the layout a row's of the table of recorded quantities (record.h).
 * A checkpoint stores the journal's synced length; a restart truncates to it, so
 * what was recorded after the checkpoint is recorded again, once. The HDF5 output is
 * assembled from the journal when the run ends. */
#ifndef SB_JOURNAL_H
#define SB_JOURNAL_H

#include <stdio.h>

#include "err.h"

/* The engine's files beside its run file OUT while it runs: OUT.journal (the records
 * the run file is assembled from) and OUT.ckpt (the checkpoint, unless checkpoint =
 * names another); a finished run removes both. The driver names them by these too
 * (lib/layout.h, LAY_JOURNAL and LAY_CKPT). */
#define SB_JOURNAL_EXT ".journal"
#define SB_CKPT_EXT ".ckpt"

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
/* A snapshot under tag: time, then x, y, theta, vx, vy of the nm mobile disks (lab
 * frame), written from the five arrays without a copy. */
int journal_snap(sb_journal *j, int tag, double t, const double *x, const double *y, const double *th,
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
/* Next record into buf (capacity cap doubles): returns its tag (> 0; whether a row
 * has it is the caller's question: rec_by_tag) and sets *count; 0 at the end, < 0 on
 * error. */
int journal_next(sb_jreader *r, double *buf, long cap, int *count, sb_err *e);
void journal_reader_close(sb_jreader *r);

#endif
