/* schema.h - every CREATE TABLE and CREATE VIEW of the study database, in one place:
 * the driver's tables, the `result` table and the `runs` view generated from the
 * result columns (results.h) and the engine's parameters, the Slurm arrays' tables,
 * the analysis tools' table. Each call creates what is missing and is safe to repeat. */
#ifndef LIB_SCHEMA_H
#define LIB_SCHEMA_H

#include "err.h"
#include "sql.h"

/* campaign, run, param, attempt, cache, onset_*, auto_point, result; the views
 * progress, failures, caches, runs. Inside the caller's transaction. */
int schema_study(sql_db *d, sb_err *e);
/* slurm_job, slurm_task */
int schema_slurm(sql_db *d, sb_err *e);
/* analysis (its fixed columns; adb.c adds the grouping keys') */
int schema_analysis(sql_db *d, sb_err *e);

#endif
