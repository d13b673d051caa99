/* grid.h - the cartesian product of a campaign's axes: one run per grid point, its
 * engine seed, its run id and its packing-cache key. */
#ifndef ST_GRID_H
#define ST_GRID_H

#include "campaign.h"

typedef struct grid_run {
	char id[17];          /* grid_run_hash(scene), hex */
	char cache_key[17];   /* params_hash_nondefault(scene, PF_PREP), hex */
	long replicate;       /* the campaign's seed value (replicate label) */
	long seed;            /* the engine seed */
	long point;           /* index of the grid point (mixed radix over the axes) */
} grid_run;

typedef struct grid {
	const campaign *c;
	long n;
	grid_run *runs;       /* sorted by id */
} grid;

/* Expand and check every grid point (cross-key rules of params_validate included). */
int grid_expand(grid *g, const campaign *c, sb_err *e);
void grid_free(grid *g);

/* The canonical scene of run k: defaults, scene file, [scene], axis values, engine seed. */
void grid_scene(const grid *g, const grid_run *r, sb_scene *s);

/* The engine seed for a replicate: derived from (campaign seed, replicate, the
 * preparation parameters) with seeds = derived, the replicate itself with literal. */
long grid_seed(const campaign *c, const sb_scene *s, long replicate);

/* The run id: params_hash_nondefault over every key but the driver-owned ones
 * (output, checkpoint, restart, write_*, progress) and checkpoint_every. */
unsigned long long grid_run_hash(const sb_scene *s);

const grid_run *grid_find(const grid *g, const char *id);

#endif
