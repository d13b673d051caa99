/* results.h - the result columns of a run, in one table: name, SQL type, where the
 * value lives in the run's HDF5 file, unit and definition. The HDF5 reader (h5sum),
 * the `result` table's schema, the ingest, the `runs` view and docs/database.md's table of
 * columns (`study columns`) are all generated from it, so no two copies can drift.
 * Every value is the engine's: the database never recomputes a result, it copies it. */
#ifndef LIB_RESULTS_H
#define LIB_RESULTS_H

#include <stddef.h>
#include <stdio.h>

typedef enum { RT_TEXT, RT_INT, RT_REAL } rt_type;

enum {
	RF_CACHE = 1,   /* a run started from the packing cache takes it from the cache's row */
	RF_DERIVED = 2, /* not stored: an SQL expression over other columns, in the runs view */
	RF_NOVIEW = 4,  /* stored, but left out of the runs view (the run table has it) */
	RF_FLAG = 8,    /* 0 or 1 (or NULL): a value read back from the database is checked */
};

typedef struct rcol {
	const char *name;  /* column of `result` and of the `runs` view */
	rt_type type;
	const char *where; /* "@attr" (root attribute), "/group@attr", "/dataset#rows";
			    * for RF_DERIVED the SQL expression */
	const char *unit;  /* "" when dimensionless */
	const char *def;   /* one sentence; NULL in the file means what */
	int flags;
} rcol;

/* The where of the file_seal column: the seal in the file's user block. */
#define RESULTS_SEAL "(user block)"
/* The where of the row_seal column: not the file's, the database's own (rowseal.h). */
#define RESULTS_ROWSEAL "(its rows)"

const rcol *results_table(size_t *n);
/* Index of a column by name, -1 if none. */
int results_find(const char *name);

/* Prints the table as the Markdown table of docs/database.md ("Result columns"). */
void results_markdown(FILE *f);

#endif
