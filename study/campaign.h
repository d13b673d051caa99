/* campaign.h - a campaign file: [campaign] identity, [scene] fixed overrides and
 * [grid] axes, read with libinih; every value checked against the engine's table. */
#ifndef ST_CAMPAIGN_H
#define ST_CAMPAIGN_H

#include "err.h"
#include "params.h"

#define CP_MAX_KEYS 64
/* Values one axis may generate, duplicates included: checked against each range's
 * size before any value is made, so the work of reading an axis stays bounded. */
#define CP_MAX_VALUES 100000
/* Grid points (the product of the axes' sizes) a campaign may have: the default, which
 * `max_runs = N` in [campaign] raises, and the most N may be (64 bytes a point in
 * memory, a few hundred microseconds a point to expand and check). */
#define CP_MAX_RUNS_DEFAULT 100000
#define CP_MAX_RUNS_LIMIT 10000000

enum cp_seeds { CP_SEEDS_DERIVED, CP_SEEDS_LITERAL };

typedef struct cp_axis {
	char key[64];
	int line;
	long n;
	char **values;  /* canonical text (params_format), duplicates removed, file order */
} cp_axis;

typedef struct cp_fixed {
	char key[64];
	int line;
	char value[SB_STR_MAX];
} cp_fixed;

typedef struct campaign {
	char path[SB_STR_MAX];
	char name[80];
	char description[1024];
	char scene_file[SB_STR_MAX];    /* resolved: relative to the campaign file's directory */
	unsigned long long seed;        /* campaign seed */
	int seeds;                      /* enum cp_seeds */
	long replicates;                /* 0 = not given */
	int replicates_line;
	long max_runs;                  /* 0 = not given: CP_MAX_RUNS_DEFAULT */
	int max_runs_line;
	int nfixed, naxes;
	cp_fixed fixed[CP_MAX_KEYS];
	cp_axis axes[CP_MAX_KEYS];
	sb_scene base;                  /* defaults + scene file + [scene]; seed = replicate label */
} campaign;

/* Read and check a campaign file. On error e holds "FILE:LINE: key: why". */
int campaign_load(campaign *c, const char *path, sb_err *e);
void campaign_free(campaign *c);

/* The number of grid points (the product of the axes' sizes) in *points, or an error
 * naming the axis that takes the grid past max_runs and how to raise it. */
int campaign_points(const campaign *c, long *points, sb_err *e);

/* Keys the driver owns (paths, restart, progress): not allowed in a campaign. */
int campaign_key_reserved(const char *key);

/* Expand one axis value text ("2.6, 2.8", "2.5:3.2:0.05", "1..8") into canonical
 * values, each checked with params_set, duplicates removed (first occurrence kept, file
 * order); at most CP_MAX_VALUES values before duplicates are removed. `where` is
 * "FILE:LINE". */
int campaign_axis_parse(cp_axis *a, const char *key, const char *text, const char *where, sb_err *e);

#endif
