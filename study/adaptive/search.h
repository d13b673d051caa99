/* search.h - an [onset] campaign's search on the driver's side: every replicate's
 * chain walked again from the database and the run files on each pass (adapt.h), the
 * runs the chains ask for added to the grid as ordinary runs, and the state of the
 * search stored in the onset_* tables, which `study status` reads. */
#ifndef ST_SEARCH_H
#define ST_SEARCH_H

#include "campaign/campaign.h"
#include "campaign/grid.h"
#include "ledger/db.h"
#include "rule/adapt.h"

typedef struct srch_group {
	char label[512];     /* grid_point_label */
	long nrep;           /* replicates, labelled 1..nrep */
	ad_rep *reps;
	ad_interval iv;
	int state;           /* enum ad_gstate (never AD_G_MORE after a pass) */
	long runs;           /* runs of its chains, the waiting ones included */
	char reason[400];    /* blocked: the first failed run's replicate, point, status and message */
} srch_group;

/* One run of a chain (a row of onset_run). */
typedef struct srch_step {
	long group, replicate;
	int step;            /* 0, 1, ...: its place in the replicate's chain */
	double x;            /* the point in the search's axis (Hz, Gamma or cm/s) */
	double f;            /* its frequency for the group */
	char id[17];
	int cls;             /* enum ad_class */
	double value;        /* rise: risen; flux: the mean flux through the band (NaN: none) */
} srch_step;

/* A finished run's flux, read from its file once per driver. */
typedef struct srch_val {
	char id[17];
	int cls;
	double value;
} srch_val;

typedef struct search {
	const campaign *c;
	char dir[4400];      /* the campaign's directory (run files) */
	long ngroups;
	srch_group *groups;
	srch_step *steps;
	long nsteps, capsteps;
	srch_val *vals;      /* the done runs' flux, sorted by id */
	long nvals, capvals;
} search;

void search_init(search *s, const campaign *c, const char *dir);
void search_free(search *s);

/* One pass: walks every group's replicates over what the database (states, results)
 * and the run files (flux) say, adds a batch of replicates where replicates = auto
 * asks for one, and adds every run of every chain to g (an expanded [onset] grid, no
 * runs yet), sorted. The same results give the same runs, in the same chains. */
int search_derive(search *s, grid *g, st_db *db, sb_err *e);

/* Whether every group is answered (nothing left to run). */
int search_done(const search *s);

/* Writes the pass's state into onset_search, onset_group, onset_replicate and
 * onset_run (replacing the campaign's rows), in one transaction. */
int search_store(const search *s, st_db *db, sb_err *e);

/* Whether a recorded run (its replicate label, frequency and id) belongs to the
 * campaign: a replicate of one of its groups at a point some chain of the range can
 * ask for. A changed tolerance or number of replicates keeps the runs; a changed range
 * or scene does not. */
int search_member(const campaign *c, long points, long replicate, double frequency, const char *id);

/* The observable of a classified run, for the messages: "on", "off", ... */
const char *search_class_name(int cls);

/* What a group's search will run first, said before it starts: the first point's
 * frequency, Gamma and v and the range's, and, when the model is known to fail at the
 * first point (axes_model_fails), a warning. Lines into buf ("" when none); returns
 * whether there is a warning. */
int search_preview(const campaign *c, long group, char *buf, size_t len);

#endif
