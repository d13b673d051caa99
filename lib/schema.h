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
/* slurm_job, slurm_task */
int schema_slurm(sql_db *d, sb_err *e);
/* analysis_def (a tool's invocation: options, versions), analysis_all (its numbers:
 * the fixed columns; adb.c adds the grouping keys'), analysis_run (its per-run
 * observables) and the view analysis (each tool's latest definition). An `analysis`
 * table of an earlier version becomes analysis_all, its rows kept under a definition
 * whose options are NULL. */
int schema_analysis(sql_db *d, sb_err *e);

#endif
