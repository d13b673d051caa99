/* rowseal.h - the seal of a run's rows in the study database: a hash over what the
 * rows say the run is and gave (its run row's identity, its param rows, its result
 * row), written when the run is recorded and checked by every reader of the rows
 * (study export, the analysis tools). SQLite keeps no checksum of a page's content, so
 * a value edited with sqlite3 or a byte changed inside a record reads as a value like
 * any other; the seal tells them apart from what was recorded (docs/database.md, "A
 * damaged database"). It guards against accidents, not against someone who recomputes
 * it. */
#ifndef LIB_ROWSEAL_H
#define LIB_ROWSEAL_H

#include <stddef.h>

#include "err.h"
#include "sql.h"

/* The column of table result that holds it (one of the result columns, results.c). */
#define ROWSEAL_COLUMN "row_seal"

/* The seal the rows of run (of campaign) have now, as 16 hex digits: FNV-1a/64 over
 * the campaign, the run's id, replicate, seed and cache key, each param row (key and
 * typed value, in key order) and each column of its result row but the seal itself
 * (name and typed value, in the table's order). "" when the run has no result row. */
int rowseal_of(sql_db *d, const char *campaign, const char *run, char seal[17], sb_err *e);

/* Writes it into the run's result row (after the row is written, inside the writer's
 * transaction). */
int rowseal_put(sql_db *d, const char *campaign, const char *run, sb_err *e);

/* The first run of campaign (in id order, after the id after when it is not NULL) whose
 * rows are not as recorded: a result row whose seal differs from its rows' (or is
 * NULL), or, with done_needs_result, a run recorded done without a result row.
 * Returns 1 and names it in run and what in why, 0 when every
 * run's rows are as recorded or the result table is not this version's
 * (schema_result_current: a database of another version, whose rows' seal is not this
 * one's; nothing to check until study run brings it up to date); e for a
 * failing query. */
int rowseal_bad(sql_db *d, const char *campaign, const char *after, int done_needs_result, char *run, size_t rlen,
		char *why, size_t wlen, sb_err *e);

/* The same, as a reader's error naming the run and what to do; a database that PRAGMA
 * quick_check finds corrupt is named so instead. */
int rowseal_check(sql_db *d, const char *campaign, sb_err *e);

#endif
