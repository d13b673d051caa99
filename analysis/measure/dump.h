/* dump.h - reading LAMMPS text dumps (`dump custom ... id type x y [radius ...]`, and
 * scripts/dump_lammps.sh's), frame by frame. Each frame's atoms come sorted by id
 * whatever order the file has them in; columns are found by name in the
 * "ITEM: ATOMS" line, so their order does not matter and extra columns are skipped.
 * ITEM sections other than TIMESTEP, NUMBER OF ATOMS, BOX BOUNDS and ATOMS (TIME,
 * UNITS) are skipped. Errors name the file and the line. */
#ifndef AN_DUMP_H
#define AN_DUMP_H

#include <stdio.h>

#include "err.h"

typedef struct dump_frame {
	long step;     /* ITEM: TIMESTEP */
	long n;        /* atoms */
	long *id;      /* [n], ascending */
	int *type;     /* [n] */
	double *x, *y; /* [n] */
	double *r;     /* [n] radius; NAN when the dump has no radius column */
	int has_r;
	long cap;      /* allocated rows */
} dump_frame;

typedef struct dump_reader {
	FILE *f;
	char path[512];
	long line;     /* lines read */
	char *buf;
	size_t cap;
} dump_reader;

int dump_open(dump_reader *rd, const char *path, sb_err *e);
/* The next frame into fr (reusing its arrays): 1 read, 0 at the end of the file, -1 on
 * an error (e says where: a truncated frame, a bad number, a missing column, a
 * repeated id). */
int dump_next(dump_reader *rd, dump_frame *fr, sb_err *e);
void dump_close(dump_reader *rd);
void dump_frame_free(dump_frame *fr);

#endif
