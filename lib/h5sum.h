/* h5sum.h - a run's results read from its HDF5 output: every column of the results
 * table (results.h), each with a flag saying whether the file holds it. */
#ifndef LIB_H5SUM_H
#define LIB_H5SUM_H

#include "err.h"
#include "results.h"

#define H5SUM_MAX 64
#define H5SUM_TEXT 1024

typedef struct h5val {
	int has;            /* 0: absent from the file (NULL in the database) */
	long long i;        /* RT_INT */
	double d;           /* RT_REAL */
	char s[H5SUM_TEXT]; /* RT_TEXT */
} h5val;

typedef struct h5sum {
	h5val v[H5SUM_MAX]; /* indexed like results_table() */
	char particles[H5SUM_TEXT]; /* the run's particles parameter: the packing it started from */
	int unsealed;       /* enum h5id_note: an older file, its identity or data unchecked */
} h5sum;

/* Read every stored column; an error when the file cannot be opened, is not run
 * want_id (NULL: any run; core/io/h5id.h: format, run id, attribute digest), a value
 * cannot be read, a dataset's data fails its checksum (h5r_verify) or the run's status
 * is missing (not a complete run file). */
int h5sum_read(const char *path, const char *want_id, h5sum *s, sb_err *e);
/* ... and the file's seal (column file_seal) must be want_seal unless that is NULL or
 * "" (what the database recorded: a file replaced, or edited and sealed again, differs);
 * the values checked against their ranges too (lib/runvals.h). */
int h5sum_read_sealed(const char *path, const char *want_id, const char *want_seal, h5sum *s, sb_err *e);

/* A column by name: "" / 0 when absent. */
const char *h5sum_text(const h5sum *s, const char *name);
double h5sum_real(const h5sum *s, const char *name);
long h5sum_int(const h5sum *s, const char *name);

#endif
