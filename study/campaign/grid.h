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
	int has_frequency;    /* a run of an [onset] search: its frequency is the search's */
	double frequency;
} grid_run;

typedef struct grid {
	const campaign *c;
	long n, cap;
	long points;          /* grid points (of an [onset] campaign: its groups) */
	grid_run *runs;       /* sorted by id */
} grid;

/* Expand and check every grid point (cross-key rules of params_validate included).
 * An [onset] campaign's points are its groups: each is checked at both ends of the
 * search's range and against what its observable needs, and no run is made (the
 * search adds them, grid_add). */
int grid_expand(grid *g, const campaign *c, sb_err *e);
void grid_free(grid *g);

/* A run of an [onset] search: the group's point at a frequency, replicate label
 * `replicate`; appended (grid_sort orders the runs again). Its id into id. */
int grid_add(grid *g, long point, long replicate, double frequency, char id[17], sb_err *e);
/* The id of that run, without adding it. Of both, with frequency NaN: replicate
 * `replicate` of grid point `point` of a grid with replicates = auto, the run a fixed
 * grid's seed = replicate makes. */
void grid_onset_id(const campaign *c, long point, long replicate, double frequency, char id[17]);
/* The frequency of an [onset] search's point x (in its axis: Hz, Gamma or cm/s) for
 * a group's scene s: x itself, or the frequency at which the group's amplitude
 * reaches x (axes.h). */
double grid_onset_frequency(const campaign *c, const sb_scene *s, double x);
/* The scene of grid point `point` (of an [onset] campaign: its group), without a run's
 * frequency or seed. */
void grid_point_scene(const campaign *c, long point, sb_scene *s);
/* Orders the runs by id (for grid_find) and drops duplicates. */
void grid_sort(grid *g);
/* "radius_ratio=2 depth=1": the point's values of the campaign's axes (reals with 12
 * significant digits); "all" without axes. */
void grid_point_label(const campaign *c, long point, char *buf, size_t len);

/* The text of axis `axis`'s value at grid point `point`, as the campaign wrote it
 * (canonical): for gamma and velocity, which are no scene keys. */
void grid_axis_text(const campaign *c, long point, int axis, char *buf, size_t len);

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
