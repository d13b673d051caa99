/* ratio.c - the table of ratio keys and what one sets (ratio.h). */
#include "ratio.h"

#include <stdio.h>
#include <string.h>

static const sb_ratio RATIOS[] = {
	/* the reverse Brazil-nut effect's axis: a light or heavy intruder in the same bed */
	{"density_ratio", "intruder_density", "density", 1000, 1},
};

const sb_ratio *ratio_table(size_t *n)
{
	*n = sizeof RATIOS / sizeof *RATIOS;
	return RATIOS;
}

const sb_ratio *ratio_find(const char *key)
{
	for (size_t i = 0; i < sizeof RATIOS / sizeof *RATIOS; i++)
		if (!strcmp(RATIOS[i].key, key))
			return &RATIOS[i];
	return NULL;
}

int ratio_apply(const sb_ratio *r, double x, sb_scene *s, const char *where, sb_err *e)
{
	const sb_param *b = params_find(r->base), *t = params_find(r->sets);
	const double base = *(const double *)((const char *)s + b->offset);
	char buf[40];
	snprintf(buf, sizeof buf, "%.12g", x * base);
	double v;
	if (sscanf(buf, "%lf", &v) != 1 || !(v > t->min && v <= t->max))
		return sb_errf(e, SB_EUSAGE, "%s: %s: %s = %.12g at %s = %.12g %s gives %s = %s, outside (%g, %g]", where,
			       r->key, r->key, x, r->base, base, b->unit, r->sets, buf, t->min, t->max);
	sb_err pe = {0};
	if (params_set(s, r->sets, buf, where, &pe))
		return sb_errf(e, pe.code, "%s: %s: %s", where, r->key, pe.msg);
	return 0;
}

void ratio_view_column(const sb_ratio *r, char *buf, size_t len)
{
	if (r->zero_is_base)
		snprintf(buf, len, "COALESCE(NULLIF(b.%s, 0), b.%s) / b.%s AS %s", r->sets, r->base, r->base, r->key);
	else
		snprintf(buf, len, "b.%s / b.%s AS %s", r->sets, r->base, r->key);
}
