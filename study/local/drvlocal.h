/* drvlocal.h - private to local/ (driver.c, parallel.c, reserve.c, ingest.c): what
 * only `study run` keeps of a campaign (drv.h's d->loc), and the modules only it
 * calls. The Slurm commands share drv.h, never this. */
#ifndef ST_DRVLOCAL_H
#define ST_DRVLOCAL_H

#include "adaptive/search.h"
#include "adaptive/sharpen.h"
#include "drv.h"

struct drv_local {
	int adaptive;         /* an [onset] campaign: the grid is its chains' runs, pass by pass */
	search srch;
	int autorep;          /* a grid with replicates = auto: its points' replicates, pass by pass */
	sharpen shp;
	long rounds;
	int jobs;
	int reserve;          /* the database's reserve is held (reserve.c) */
};

/* parallel.c: GNU parallel over the jobs, the workers' lines handed to ingest.c (the
 * driver's SIGINT/SIGTERM reach parallel through stop.h) */
int run_parallel(drv *d, const char *kind, char **names, long n, char **basefiles, long nbase, sb_err *e);

/* reserve.c: room on the campaign's disk held from the start (reserve_make), given
 * back for the last records after a full disk stopped the launching (reserve_release:
 * 1 when there was some to give; 0 for a drv without d->loc) */
void reserve_make(drv *d);
int reserve_release(drv *d);

#endif
