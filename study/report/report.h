/* report.h - read-only views of the study database: status, list, export. */
#ifndef ST_REPORT_H
#define ST_REPORT_H

#include <stdio.h>

#include "err.h"

/* Counts per state, cache hits, failures with their reasons and an ETA; all
 * campaigns when name is NULL. */
int report_status(const char *db_path, const char *name, int jobs, FILE *out, sb_err *e);
/* Before each look of report_watch, for each campaign: what its Slurm tasks did since
 * the last look, into the database, and how many of its runs they hold (*active). The
 * caller's (study_main.c gives slurm_refresh): the report reads, it does not collect. */
typedef int (*report_refresh)(const char *runs_dir, const char *db_path, const char *name, long *active, FILE *msg,
			      sb_err *e);
/* Live progress (watch.h) of one campaign (all when name is NULL), a look every
 * interval seconds, until every run is finished, no driver runs it any more, or
 * SIGINT/SIGTERM; runs_dir is where the runs' journals are; refresh may be NULL. */
int report_watch(const char *db_path, const char *runs_dir, const char *name, double interval,
		 report_refresh refresh, FILE *out, sb_err *e);
/* One line per campaign. */
int report_list(const char *db_path, FILE *out, sb_err *e);
/* CSV of the `runs` view (parameters + results), one row per run, then each run's file
 * (absolute; "" while it has none) under runs_dir (NULL: "runs"); units: a second row
 * with each column's unit. */
int report_export(const char *db_path, const char *runs_dir, const char *name, int units, FILE *out, sb_err *e);
/* study view: under dir, a tree of symbolic links to the campaign's run files named by
 * the parameters that vary between its current runs (KEY=VALUE/.../seed=S.h5), as
 * signac's view makes; dir is made, or one this command made before is remade. A
 * line on out says what was linked and what was left out (runs without a file). */
int report_view(const char *db_path, const char *runs_dir, const char *name, const char *dir, FILE *out, sb_err *e);

#endif
