/* results.c - the result columns of a run (see results.h). Heights are in the box
 * frame, whose origin is the box floor's rest position: at t = 0 (box at rest, phase 0)
 * it coincides with the lab frame, and a rise measured in it never counts the box's
 * own motion. The definitions are the engine's (docs/model.md, "Observables"). */
#include "results.h"

#include <string.h>

#include "record.h"
#include "rowseal.h"
#include "runfile.h"

/* A summary attribute of the run file's root is a column of its name. */
#define SUMMARY_COLUMN(row, attr, how, unit, def) {#attr, RT_REAL, "@" #attr, unit, def, 0},

static const rcol TABLE[] = {
	{"status", RT_TEXT, "@status", "",
	 "how the run ended: ok, or the failure (nan, overlap, left_box, settle_failed, io, ...)", 0},
	{"exit_code", RT_INT, "@exit_code", "", "the engine's exit code (0 ok; bin/shake --help lists them)", 0},
	{"message", RT_TEXT, "@status_message", "", "the engine's message when the run failed, else empty", 0},
	{"status_time", RT_REAL, "@status_time", "s", "simulated time at which the run ended or failed", 0},
	{"stopped_by", RT_TEXT, "@stopped_by", "",
	 "the stop rule that ended the run (none: it ran its duration, or failed; risen, flux)", 0},
	{"steps", RT_INT, "@steps", "", "time steps of shaking done", 0},
	{"settle_time", RT_REAL, "@settle_time", "s",
	 "simulated settling time (of the shared packing for a run started from the cache)", RF_CACHE},
	{"settle_steps", RT_INT, "@settle_steps", "", "settling steps (of the shared packing, likewise)",
	 RF_CACHE | RF_NOVIEW},
	{"surface_height_box", RT_REAL, "@surface_height", "cm",
	 "free surface of the settled bed (median of the column tops), box frame", 0},
	{"intruder_radius", RT_REAL, "@intruder_radius", "cm", "the intruder's radius; NULL without intruder", 0},
	{"intruder_settled_y_box", RT_REAL, "@intruder_settled_y", "cm",
	 "the intruder centre's height after settling, box frame", 0},
	{"intruder_settled_depth", RT_REAL, "@intruder_settled_depth", "cm",
	 "free surface minus the intruder centre's height after settling", 0},
	/* the per-run summaries of the recorded quantities (core/scene/record.h) */
	REC_SUMMARIES(SUMMARY_COLUMN)
	{"intruder_rise_box", RT_REAL, "intruder_final_y_box - intruder_settled_y_box", "cm",
	 "final minus settled height of the intruder centre, box frame", RF_DERIVED},
	{"risen", RT_INT, "@risen", "",
	 "1 when the intruder rose (docs/model.md, \"Waiting time\"), else 0 (right-censored); NULL without "
	 "intruder", RF_FLAG},
	{"waiting_time", RT_REAL, "@waiting_time", "s",
	 "when risen = 1 the first time it did (the waiting time), else the time observed "
	 "(the censoring time, also for a run that failed before its intruder rose)", 0},
	/* several intruders (docs/model.md, "Several intruders"); NULL for one */
	{"intruders", RT_INT, "@intruders", "", "the number of intruders when there are several, each tracked; NULL for one", 0},
	{"intruders_risen", RT_INT, "@intruders_risen", "", "how many of several intruders rose (each as risen says)", 0},
	{"rise_first", RT_REAL, "@rise_first", "s", "the first waiting time of several intruders; NULL when none rose", 0},
	{"rise_median", RT_REAL, "@rise_median", "s",
	 "the median waiting time of several intruders, the unrisen later than any; NULL unless more than half rose", 0},
	{"rise_last", RT_REAL, "@rise_last", "s", "the last waiting time of the intruders that rose; NULL when none rose",
	 0},
	{"overlap_max", RT_REAL, "@overlap_max", "",
	 "largest overlap of two disks while shaking, as a fraction of the smaller radius, to 1 % "
	 "(the max_overlap stop is at 1 by default)", 0},
	{"overlap_max_time", RT_REAL, "@overlap_max_time", "s", "when the largest overlap happened", 0},
	{"overlap_max_disk_a", RT_INT, "@overlap_max_disk_a", "", "id of one disk of the largest overlap", 0},
	{"overlap_max_disk_b", RT_INT, "@overlap_max_disk_b", "", "id of the other disk", 0},
	{"overlap_max_x", RT_REAL, "@overlap_max_x", "cm", "x of the midpoint of their centres", 0},
	{"overlap_max_y_box", RT_REAL, "@overlap_max_y_box", "cm", "y of that midpoint, box frame", 0},
	{"n_mobile", RT_INT, "@n_mobile", "", "mobile disks (grains and intruder)", RF_NOVIEW},
	{"n_walls", RT_INT, "@n_walls", "", "wall disks", RF_NOVIEW},
	{"neighbour_builds", RT_INT, "@neighbour_builds", "", "neighbour-list builds while shaking", RF_NOVIEW},
	{"traj_rows", RT_INT, RUNFILE_INTRUDER_POS "#rows", "", "rows of the intruder trajectory", RF_NOVIEW},
	{"wall_seconds", RT_REAL, "/provenance@loop_seconds", "s", "wall-clock time of the shaking loop (not CPU time: on a loaded machine it is longer)", 0},
	{"host", RT_TEXT, "/provenance@host", "", "machine that ran it", RF_NOVIEW},
	{"git_hash", RT_TEXT, "/provenance@git_hash", "", "engine version", 0},
	{"git_dirty", RT_INT, "/provenance@git_dirty", "", "1 when built from a modified tree", RF_FLAG},
	{"start_time", RT_TEXT, "/provenance@start_time", "", "when the engine started (UTC)", RF_NOVIEW},
	{"end_time", RT_TEXT, "/provenance@end_time", "", "when the engine wrote the file (UTC)", RF_NOVIEW},
	/* not an attribute: the user block before HDF5's bytes (h5sum.c reads it) */
	{"file_seal", RT_TEXT, RESULTS_SEAL, "",
	 "the file's seal (core/io/h5id.h) when the run was recorded: a reader refuses a file that differs from it; "
	 "NULL for an older, unsealed file", RF_NOVIEW},
	/* not the file's: the seal of the run's rows, written after them (rowseal.h) */
	{ROWSEAL_COLUMN, RT_TEXT, RESULTS_ROWSEAL, "",
	 "the seal of the run's rows (run, param, result) when it was recorded: a reader refuses rows that differ "
	 "from it (docs/database.md, \"A damaged database\")", RF_NOVIEW},
};

const rcol *results_table(size_t *n)
{
	*n = sizeof TABLE / sizeof *TABLE;
	return TABLE;
}

int results_find(const char *name)
{
	for (size_t i = 0; i < sizeof TABLE / sizeof *TABLE; i++)
		if (!strcmp(TABLE[i].name, name))
			return (int)i;
	return -1;
}

void results_markdown(FILE *f)
{
	static const char *types[] = {"TEXT", "INTEGER", "REAL"};
	fprintf(f, "| column | type | in the run file | unit | definition |\n|---|---|---|---|---|\n");
	for (size_t i = 0; i < sizeof TABLE / sizeof *TABLE; i++) {
		const rcol *c = &TABLE[i];
		if (c->flags & RF_DERIVED)
			fprintf(f, "| `%s` | %s | view: `%s` | %s | %s |\n", c->name, types[c->type], c->where,
				c->unit, c->def);
		else
			fprintf(f, "| `%s` | %s | `%s` | %s | %s%s |\n", c->name, types[c->type], c->where, c->unit,
				c->def, c->flags & RF_NOVIEW ? " (table `result` only)" : "");
	}
}
