/* ratio.h - scene keys a campaign may give as a ratio to another: `density_ratio`, the
 * intruder's density over the grains' (docs/campaigns.md, "Ratios"). Like Gamma and v
 * they are the campaign's keys, not the engine's: each grid point sets the scene key
 * from the ratio and the point's own base value (study/campaign/grid.c), so a run
 * records (and is identified by) the scene key it ran, and the runs view has the ratio
 * beside it (schema.c, from this table). */
#ifndef SB_RATIO_H
#define SB_RATIO_H

#include "err.h"
#include "params.h"

typedef struct sb_ratio {
	const char *key;  /* the campaign's key */
	const char *sets; /* the scene key it sets: sets = key x base */
	const char *base; /* the scene key it is a ratio to */
	double max;       /* the largest ratio a campaign may ask for */
	int zero_is_base; /* sets = 0 means "the base value" (intruder_density = 0: density) */
} sb_ratio;

/* The row of a ratio key, or NULL. */
const sb_ratio *ratio_find(const char *key);
/* The rows; their number into *n. */
const sb_ratio *ratio_table(size_t *n);

/* The scene value a ratio x gives over scene s's base value, printed with 12 significant
 * digits and read back (as a campaign's every value is), into buf; then set in s, with
 * the engine's range check. where names the campaign file and line of the ratio; an
 * error names the ratio, the base value and the scene key's range. */
int ratio_apply(const sb_ratio *r, double x, sb_scene *s, const char *where, sb_err *e);

/* The runs view's expression of ratio r over the subquery b of the run's parameters
 * (schema.c), "... AS key", into buf. */
void ratio_view_column(const sb_ratio *r, char *buf, size_t len);

#endif
