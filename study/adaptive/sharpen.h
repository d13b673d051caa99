/* sharpen.h - replicates = auto on a grid, on the driver's side: every grid point's
 * replicates derived again from the database (and, for mean_flux, the run files) on
 * each pass (sharp.h), the runs they ask for added to the grid as ordinary runs, and
 * the points' state stored in the table auto_point, which `study status` reads. */
#ifndef ST_SHARPEN_H
#define ST_SHARPEN_H

#include "campaign/campaign.h"
#include "campaign/grid.h"
#include "ledger/db.h"
#include "rule/sharp.h"

typedef struct shp_point {
	char label[512];     /* grid_point_label */
	long nrep;           /* replicates, labelled 1..nrep */
	sh_eval ev;
	long failed;         /* runs that failed (used when they recorded a value) */
	int state;           /* enum sh_state (never SH_MORE after a pass) */
} shp_point;

typedef struct sharpen {
	const campaign *c;
	char dir[4400];      /* the campaign's directory (run files) */
	long npoints;
	shp_point *pts;
	char (**member)[17];  /* per replicate label: every point's run id, sorted; made
			       * when a recorded run of that label is first checked */
} sharpen;

void sharpen_init(sharpen *s, const campaign *c, const char *dir);
void sharpen_free(sharpen *s);

/* One pass: every point's replicates over what the database says, a batch added where
 * the interval is wider than the target, and every run of every point added to g (an
 * expanded replicates = auto grid, no runs yet), sorted. The same results give the
 * same runs. */
int sharpen_derive(sharpen *s, grid *g, st_db *db, sb_err *e);

/* Whether no point waits for a run. */
int sharpen_done(const sharpen *s);

/* Writes the pass's state into auto_point (replacing the campaign's rows). */
int sharpen_store(const sharpen *s, st_db *db, sb_err *e);

/* Whether a recorded run (its replicate label and id) belongs to the campaign: a
 * replicate of one of its points. A changed target or maximum keeps the runs. */
int sharpen_member(sharpen *s, long points, long replicate, const char *id);

#endif
