/* stopdef.c - the [onset] search's threshold and band as the runs' stop = flux rule
 * (stopdef.h). */
#include "stopdef.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The engine's keys that say what [onset]'s do, and where [onset]'s values sit. */
static const struct twin {
	const char *key;      /* the engine's */
	const char *okey;     /* [onset]'s */
	size_t val, line;     /* offsets in cp_onset */
} TWINS[] = {
	{"stop_flux_threshold", "threshold", offsetof(cp_onset, threshold), offsetof(cp_onset, threshold_line)},
	{"stop_flux_lo", "band", offsetof(cp_onset, band_lo), offsetof(cp_onset, band_line)},
	{"stop_flux_hi", "band", offsetof(cp_onset, band_hi), offsetof(cp_onset, band_line)},
};

/* two texts of one number (params_format's and the file's): equal to rounding */
static int same(double a, double b)
{
	return fabs(a - b) <= 1e-12 * fmax(1, fmax(fabs(a), fabs(b)));
}

/* "threshold = 2 (line 24)" or "band (default 0.4:0.6, the section on line 20)" */
static void onset_where(const cp_onset *o, const struct twin *t, char *buf, size_t n)
{
	const int line = *(const int *)((const char *)o + t->line);
	const double v = *(const double *)((const char *)o + t->val);
	if (!strcmp(t->okey, "band"))
		snprintf(buf, n, "[onset] band = %g:%g (%s %d)", o->band_lo, o->band_hi, line ? "line" : "the default; section on line",
			 line ? line : o->line);
	else
		snprintf(buf, n, "[onset] %s = %g (line %d)", t->okey, v, line);
}

static int refuse(const campaign *c, int line, const struct twin *t, double value, sb_err *e)
{
	char ow[160];
	onset_where(&c->onset, t, ow, sizeof ow);
	return sb_errf(e, SB_EUSAGE, "%s:%d: %s: %g differs from %s: the runs' stop = flux rule and the search would "
		       "call a bed convecting by different definitions; remove %s (the driver sets it from [onset]) or "
		       "give both one value", c->path, line, t->key, value, ow, t->key);
}

static int stops_by_flux(const campaign *c)
{
	if (c->base.stop == STOP_FLUX)
		return 1;
	for (int a = 0; a < c->naxes; a++)
		if (!strcmp(c->axes[a].key, "stop"))
			for (long i = 0; i < c->axes[a].n; i++)
				if (!strcmp(c->axes[a].values[i], "flux"))
					return 1;
	return 0;
}

int stopdef_apply(campaign *c, sb_err *e)
{
	const cp_onset *o = &c->onset;
	if (!o->line || o->observable != CP_OBS_FLUX)
		return 0;
	sb_scene def;
	params_defaults(&def);
	for (size_t k = 0; k < sizeof TWINS / sizeof *TWINS; k++) {
		const struct twin *t = &TWINS[k];
		const double want = *(const double *)((const char *)o + t->val);
		const sb_param *p = params_find(t->key);
		int set = 0;
		for (int i = 0; i < c->nfixed; i++)
			if (!strcmp(c->fixed[i].key, t->key)) {
				if (!same(strtod(c->fixed[i].value, NULL), want))
					return refuse(c, c->fixed[i].line, t, strtod(c->fixed[i].value, NULL), e);
				set = 1;
			}
		for (int a = 0; a < c->naxes; a++)
			if (!strcmp(c->axes[a].key, t->key)) {
				for (long i = 0; i < c->axes[a].n; i++)
					if (!same(strtod(c->axes[a].values[i], NULL), want))
						return refuse(c, c->axes[a].line, t, strtod(c->axes[a].values[i], NULL), e);
				set = 1;
			}
		if (set)
			continue;
		char have[64], dflt[64];
		params_format(&c->base, p, have, sizeof have);
		params_format(&def, p, dflt, sizeof dflt);
		if (strcmp(have, dflt)) { /* the scene file's */
			if (same(strtod(have, NULL), want))
				continue;
			const int line = *(const int *)((const char *)o + t->line);
			return sb_errf(e, SB_EUSAGE, "%s:%d: %s: [onset] says %g, the scene file %s says %s = %g: the runs' "
				       "stop = flux rule and the search would call a bed convecting by different definitions; "
				       "set %s = %g under [scene] or give both one value", c->path, line ? line : o->line,
				       t->okey, want, c->scene_file, t->key, strtod(have, NULL), t->key, want);
		}
		if (!stops_by_flux(c))
			continue;
		char v[64], where[SB_STR_MAX + 32];
		snprintf(v, sizeof v, "%.17g", want);
		snprintf(where, sizeof where, "%s:%d", c->path, *(const int *)((const char *)o + t->line));
		if (params_set(&c->base, t->key, v, where, e))
			return e->code;
	}
	return 0;
}
