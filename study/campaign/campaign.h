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
enum cp_observable { CP_OBS_NONE, CP_OBS_RISE, CP_OBS_FLUX };

/* [onset]: instead of a frequency axis, the onset frequency of an observable per
 * group of the other axes, searched by bisection per replicate (docs/driver.md,
 * "Adaptive onset search"). Lines are 0 for keys the file did not give. */
typedef struct cp_onset {
	int line;                 /* the section's header; 0: no [onset] */
	int observable;           /* enum cp_observable */
	int axis;                 /* enum ax_kind: what from, to, tolerance and target are in
				   * (Hz, Gamma or cm/s); each group's frequency follows from
				   * its amplitude (axes.h) */
	double from, to;          /* off at from, on at to */
	double tolerance;         /* a replicate's bracket at most this wide is its answer */
	double threshold;         /* flux: |mean flux| at or above it is on (particles/period) */
	double band_lo, band_hi;  /* flux: the band of heights, fractions of the surface */
	double skip;              /* flux: fraction of the periods left out as transient */
	int autorep;              /* replicates = auto */
	long replicates;          /* fixed: this many; auto: 0 */
	long max_replicates;      /* auto: at most */
	long batch;               /* auto: added at a time */
	double target;            /* auto: interval width to reach */
	double level;             /* confidence level of the interval */
	int axis_line, observable_line, from_line, to_line, tolerance_line, threshold_line, band_line, skip_line,
		replicates_line, max_line, batch_line, target_line, level_line;
} cp_onset;

/* [campaign] replicates = auto on a grid: per grid point (every axis but the
 * replicate), batches of replicates until the interval of a result of its runs is at
 * most target wide (docs/driver.md, "Replicates until the answer is sharp"). Lines
 * are 0 for keys the file did not give. */
enum cp_result { CP_RES_MEDIAN_WAIT, CP_RES_RISE_FRACTION, CP_RES_MEAN_FLUX };
typedef struct cp_auto {
	int on;                   /* replicates = auto */
	int result;               /* enum cp_result */
	double target;            /* the interval width to reach (the result's unit) */
	long batch;               /* replicates added at a time (the first batch: at least
				   * the replicates an interval needs) */
	long max_replicates;      /* at most this many per point */
	double level;             /* confidence level of the interval */
	int result_line, target_line, batch_line, max_line, level_line;
} cp_auto;

typedef struct cp_axis {
	char key[64];
	int line;
	long n;
	char **values;  /* canonical text (params_format), duplicates removed, file order */
	long given;     /* values before duplicates were removed */
	int zipped_to;  /* 1 + the index of the axis whose value index this one follows
			 * ([campaign] zip); 0 = an axis of its own */
} cp_axis;

typedef struct cp_fixed {
	char key[64];
	int line;
	char value[SB_STR_MAX];
} cp_fixed;

/* What the drive axes gamma and velocity set (docs/campaigns.md, "Axes in Gamma and v"):
 * the frequency from the amplitude, the amplitude from the frequency (a campaign that
 * sets the frequency), or both (gamma and velocity together). */
enum cp_derive { CP_DERIVE_NONE, CP_DERIVE_FREQUENCY, CP_DERIVE_AMPLITUDE, CP_DERIVE_BOTH };

typedef struct campaign {
	char path[SB_STR_MAX];
	char name[80];
	int name_line;
	char description[1024];
	char scene_file[SB_STR_MAX];    /* resolved: relative to the campaign file's directory */
	unsigned long long seed;        /* campaign seed */
	int seeds;                      /* enum cp_seeds */
	long replicates;                /* 0 = not given */
	int replicates_line;
	long max_runs;                  /* 0 = not given: CP_MAX_RUNS_DEFAULT */
	int max_runs_line;
	char zip[512];                  /* [campaign] zip = KEY KEY ...: axes advanced together */
	int zip_line;
	int nfixed, naxes;
	cp_fixed fixed[CP_MAX_KEYS];
	cp_axis axes[CP_MAX_KEYS];
	sb_scene base;                  /* defaults + scene file + [scene]; seed = replicate label */
	cp_auto autorep;                /* autorep.on: replicates = auto on a grid */
	cp_onset onset;                 /* onset.line != 0: an adaptive campaign (its axes are
					 * the groups; frequency and seed are the search's) */
	int derive;                     /* enum cp_derive: gamma or velocity in [scene] or [grid] */
} campaign;

/* Read and check a campaign file. On error e holds "FILE:LINE: key: why". */
int campaign_load(campaign *c, const char *path, sb_err *e);
void campaign_free(campaign *c);

/* The number of grid points (the product of the axes' sizes) in *points, or an error
 * naming the axis that takes the grid past max_runs and how to raise it. */
int campaign_points(const campaign *c, long *points, sb_err *e);

/* Whether key is a drive axis (gamma, velocity): no scene key, but a campaign key whose
 * values set the frequency or the amplitude of each point (axes.h). */
int campaign_key_derived(const char *key);

/* Keys the driver owns (paths, restart, progress): not allowed in a campaign. */
int campaign_key_reserved(const char *key);

/* Expand one axis value text ("2.6, 2.8", "2.5:3.2:0.05", "1..8") into canonical
 * values, each checked with params_set, duplicates removed (first occurrence kept, file
 * order); at most CP_MAX_VALUES values before duplicates are removed. `where` is
 * "FILE:LINE". */
int campaign_axis_parse(cp_axis *a, const char *key, const char *text, const char *where, sb_err *e);

#endif
