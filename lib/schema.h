/* schema.h - every CREATE TABLE and CREATE VIEW of the study database, in one place:
 * the driver's tables, the `result` table and the `runs` view generated from the
 * result columns (results.h), the engine's parameters and the tools' per-run
 * observables, the Slurm arrays' tables, the analysis tools' tables. Each call creates
 * what is missing and is safe to repeat. */
#ifndef LIB_SCHEMA_H
#define LIB_SCHEMA_H

#include "err.h"
#include "sql.h"

/* campaign, run, param, attempt, cache, onset_*, auto_point, result, the analysis
 * tools' tables (schema_analysis); the views progress, failures, caches, runs. Inside
 * the caller's transaction. */
int schema_study(sql_db *d, sb_err *e);
/* The `runs` view anew when what it shows changed: after a tool stored per-run
 * observables of a (tool, key) the view has no column for yet; left as it is while the
 * result table is an earlier version's (the driver brings both up to date). */
int schema_runs(sql_db *d, sb_err *e);
/* The driver's run tables (campaign, run, param; with all: attempt, result, cache)
 * that a study database lacks, as "run, param" in lost ("" for none, and for a new
 * database, which has none of them): a DROP TABLE, a tool gone wrong. */
int schema_lost(sql_db *d, int all, char *lost, size_t len, sb_err *e);
/* A reader's check of the same: an error naming the table and what to do; then the
 * indexes of run and campaign against their tables (a damaged index is corruption that
 * PRAGMA quick_check does not see). */
int schema_complete(sql_db *d, int all, sb_err *e);
/* A campaign recorded without a single run (the driver records a campaign and its runs
 * in one transaction) is a database that lost rows: an error naming it corrupt (a
 * quick check) or the rows lost, with what to do. Nothing when the campaign is not
 * recorded or has runs. */
int schema_runs_lost(sql_db *d, const char *campaign, sb_err *e);
/* A value of campaign's rows that no run can have, as a file's would be refused: a
 * parameter the engine's parser refuses (ramp = 3), a result flag not 0 or 1 (risen =
 * 2). Number parameters only when numbers is 1: the analysis tools count a run whose
 * number is no finite number unusable, with the reason, and go on with the others
 * (docs/inputs.md), where the driver writes every such value again. Returns 1 and
 * names the first in why (its run in run, if run is not NULL), 0 when every value is
 * possible; e for a failing query. */
int schema_bad_value(sql_db *d, const char *campaign, int numbers, char *run, size_t rlen, char *why, size_t wlen,
		     sb_err *e);
/* The same, as a reader's error naming the value and what to do. */
int schema_values(sql_db *d, const char *campaign, int numbers, sb_err *e);
/* Whether the result table's columns are this version's (results.h): a table of an
 * earlier or later version is read as it is, and its rows' seals (rowseal.h) are not
 * this version's to check. */
int schema_result_current(sql_db *d);
/* slurm_job, slurm_task */
int schema_slurm(sql_db *d, sb_err *e);
/* analysis_def (a tool's invocation: options, versions), analysis_all (its numbers:
 * the fixed columns; adb.c adds the grouping keys'), analysis_run (its per-run
 * observables) and the view analysis (each tool's latest definition). An `analysis`
 * table of an earlier version becomes analysis_all, its rows kept under a definition
 * whose options are NULL. */
int schema_analysis(sql_db *d, sb_err *e);

/* The drive axis (core/model/drive.h, enum sb_axis) a derived column of the runs view
 * (gamma, v_box) is on, or -1 for any other column. */
int schema_view_axis(const char *column);

#endif
