/* grid.c - grid expansion, seed derivation, run ids. */
#include "grid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "axes.h"
#include "ratio.h"
#include "validate.h"

/* SplitMix64 finaliser: a bijective mix, so distinct inputs stay distinct. */
static unsigned long long mix64(unsigned long long z)
{
	z += 0x9e3779b97f4a7c15ULL;
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
	return z ^ (z >> 31);
}

/* The seed depends on the replicate and on the preparation parameters only (not on
 * the frequency, amplitude, duration, ...): the runs of one replicate that differ only
 * in their dynamics start from the same packing, which is what the packing cache
 * shares and what makes a frequency sweep a paired comparison. It never depends on a
 * run's position in the grid. GSL's MT19937 uses 32 bits of the seed, hence the range
 * [1, 2^32 - 1]. */
long grid_seed(const campaign *c, const sb_scene *s, long replicate)
{
	if (c->seeds == CP_SEEDS_LITERAL)
		return replicate;
	sb_scene t = *s;
	t.seed = 0;
	unsigned long long h = mix64(c->seed);
	h = mix64(h ^ (unsigned long long)replicate);
	h = mix64(h ^ params_hash_nondefault(&t, PF_PREP));
	return (long)(1 + h % 4294967295ULL);
}

/* The run id hashes every key that can change what a run's output holds: the
 * preparation, the dynamics, the length and what is recorded (traj_rate, flux,
 * ring_inner, ...), so that two grid points are never taken for one run and turning
 * an observable on computes the runs again. Left out, by resetting them to their
 * defaults: what the driver sets for every run (paths, restart, progress) and
 * checkpoint_every (when the state is saved, not what a run computes). */
static unsigned long long run_hash(const sb_scene *s, const sb_scene *def)
{
	sb_scene t = *s;
	size_t n;
	const sb_param *tab = params_table(&n);
	for (size_t i = 0; i < n; i++) {
		if (!(tab[i].flags & (PF_DRIVER | PF_NOID)))
			continue;
		char v[SB_STR_MAX + 8];
		sb_err e = {0};
		params_format(def, &tab[i], v, sizeof v);
		params_set(&t, tab[i].name, v, "default", &e);
	}
	return params_hash_nondefault(&t, ~0u);
}

unsigned long long grid_run_hash(const sb_scene *s)
{
	sb_scene def;
	params_defaults(&def);
	return run_hash(s, &def);
}

/* The value of a drive axis (gamma, velocity) at a point: its axis's value at the
 * point's digit, or [scene]'s; NaN when the campaign has none. Its line into *line. */
static double derived_at(const campaign *c, const long *digit, const char *key, int *line)
{
	for (int a = 0; a < c->naxes; a++)
		if (!strcmp(c->axes[a].key, key)) {
			*line = c->axes[a].line;
			return strtod(c->axes[a].values[digit[a]], NULL);
		}
	for (int i = 0; i < c->nfixed; i++)
		if (!strcmp(c->fixed[i].key, key)) {
			*line = c->fixed[i].line;
			return strtod(c->fixed[i].value, NULL);
		}
	return NAN;
}

/* the drive's other axes (Gamma, v: core/model/drive.h) set the point's frequency,
 * amplitude or both (campaign.c, derived_finish), within the engine's ranges of those keys */
static int scene_derive(const campaign *c, const long *digit, sb_scene *s, sb_err *e)
{
	/* x[k] and its line on each axis the campaign gives; kind the first, other the second */
	double x[AXIS_N] = {0};
	int at_line[AXIS_N] = {0}, kind = -1, other = -1;
	for (int k = AXIS_FREQUENCY + 1; k < AXIS_N; k++) {
		x[k] = derived_at(c, digit, drive_axis_name(k), &at_line[k]);
		if (at_line[k] && kind < 0)
			kind = k;
		else if (at_line[k] && other < 0)
			other = k;
	}
	if (kind < 0)
		return 0;
	int line = at_line[kind];
	double f = s->frequency, A = s->amplitude;
	if (c->derive == CP_DERIVE_FREQUENCY)
		f = axes_frequency(kind, x[kind], A, s->gravity);
	else if (c->derive == CP_DERIVE_AMPLITUDE)
		A = axes_amplitude(kind, x[kind], f, s->gravity);
	else
		axes_drive(x, s->gravity, &A, &f);
	const char *key[2] = {"frequency", "amplitude"};
	double val[2] = {f, A};
	for (int k = 0; k < 2; k++) {
		const sb_param *p = params_find(key[k]);
		char buf[40], where[SB_STR_MAX + 32];
		snprintf(buf, sizeof buf, "%.12g", val[k]);
		snprintf(where, sizeof where, "%s:%d", c->path, line);
		if (!(val[k] > p->min && val[k] <= p->max)) {
			char at[96];
			if (c->derive == CP_DERIVE_FREQUENCY)
				snprintf(at, sizeof at, "at amplitude %g cm", s->amplitude);
			else if (c->derive == CP_DERIVE_AMPLITUDE)
				snprintf(at, sizeof at, "at frequency %g Hz", s->frequency);
			else {
				char num[32], t[64];
				snprintf(num, sizeof num, "%.12g", other >= 0 ? x[other] : NAN);
				snprintf(at, sizeof at, "and %s = %s", drive_axis_name(other),
					 drive_axis_text(other, num, t, sizeof t));
			}
			return sb_errf(e, SB_EUSAGE, "%s: %s: %s = %.12g %s needs %s = %s, outside (%g, %g]", where,
				       drive_axis_name(kind), drive_axis_name(kind), x[kind], at, key[k], buf, p->min, p->max);
		}
		if (params_set(s, key[k], buf, where, e))
			return e->code;
	}
	return 0;
}

/* The scene of a grid point; the axes' value indices into digit (may be NULL). */
static int scene_point_at(const campaign *c, long point, sb_scene *s, long *digit, sb_err *e)
{
	*s = c->base;
	sb_err pe = {0};
	/* mixed radix, first axis fastest; a zipped axis takes its leader's digit (the
	 * leader comes first in the file order, so its digit is known) */
	long own[CP_MAX_KEYS];
	if (!digit)
		digit = own;
	for (int a = 0; a < c->naxes; a++) {
		long k;
		if (c->axes[a].zipped_to) {
			k = digit[c->axes[a].zipped_to - 1];
		} else {
			k = point % c->axes[a].n;
			point /= c->axes[a].n;
		}
		digit[a] = k;
		if (campaign_key_derived(c->axes[a].key))
			continue;
		char where[SB_STR_MAX + 32];
		snprintf(where, sizeof where, "%s:%d", c->path, c->axes[a].line);
		params_set(s, c->axes[a].key, c->axes[a].values[k], where, &pe);
	}
	if (c->derive && scene_derive(c, digit, s, e))
		return e->code;
	/* the ratios (ratio.h) over the point's own base values, the drive's already set */
	size_t nr;
	const sb_ratio *rt = ratio_table(&nr);
	for (size_t i = 0; i < nr; i++) {
		int line = 0;
		const double x = derived_at(c, digit, rt[i].key, &line);
		if (!line)
			continue;
		char where[SB_STR_MAX + 32];
		snprintf(where, sizeof where, "%s:%d", c->path, line);
		if (ratio_apply(&rt[i], x, s, where, e))
			return e->code;
	}
	return 0;
}

static void scene_point(const campaign *c, long point, sb_scene *s)
{
	sb_err e = {0};
	scene_point_at(c, point, s, NULL, &e);
}

void grid_scene(const grid *g, const grid_run *r, sb_scene *s)
{
	scene_point(g->c, r->point, s);
	if (r->has_frequency)
		s->frequency = r->frequency;
	s->seed = r->seed;
}

void grid_point_label(const campaign *c, long point, char *buf, size_t len)
{
	sb_scene s;
	long digit[CP_MAX_KEYS];
	sb_err e = {0};
	scene_point_at(c, point, &s, digit, &e);
	size_t l = 0;
	buf[0] = 0;
	for (int a = 0; a < c->naxes && l < len; a++) {
		const sb_param *p = params_find(c->axes[a].key);
		char v[SB_STR_MAX + 8];
		if (!p) /* gamma, velocity: as the campaign wrote them */
			snprintf(v, sizeof v, "%s", c->axes[a].values[digit[a]]);
		else if (p->type == PT_REAL)
			snprintf(v, sizeof v, "%.12g", *(const double *)((const char *)&s + p->offset));
		else
			params_format(&s, p, v, sizeof v);
		l += (size_t)snprintf(buf + l, len - l, "%s%s=%s", a ? " " : "", c->axes[a].key, v);
	}
	if (!c->naxes)
		snprintf(buf, len, "all");
}

static int by_id(const void *a, const void *b)
{
	return strcmp(((const grid_run *)a)->id, ((const grid_run *)b)->id);
}

/* A point's scene checked with the engine's cross-key rules; the message names where
 * the key at fault was set when it was set in this file, else the grid's first line. */
static int point_check(const campaign *c, long point, const sb_scene *s, const char *extra, sb_err *e)
{
	sb_err ve = {0};
	if (!params_validate(s, &ve))
		return 0;
	char pt[1024] = "";
	size_t l = 0;
	for (int a = 0; a < c->naxes && l < sizeof pt - 1; a++) {
		char v[SB_STR_MAX + 8];
		const sb_param *p = params_find(c->axes[a].key);
		if (p)
			params_format(s, p, v, sizeof v);
		else
			grid_axis_text(c, point, a, v, sizeof v);
		l += (size_t)snprintf(pt + l, sizeof pt - l, "%s%s=%s", a ? " " : "", c->axes[a].key, v);
	}
	if (extra && l < sizeof pt - 1)
		snprintf(pt + l, sizeof pt - l, "%s%s", l ? " " : "", extra);
	int line = c->naxes ? c->axes[0].line : 0;
	if (!strncmp(ve.msg, c->path, strlen(c->path)))
		return sb_errf(e, SB_EUSAGE, "%s (grid point %s)", ve.msg, pt);
	return sb_errf(e, SB_EUSAGE, "%s:%d: grid point %s: %s", c->path, line, pt, ve.msg);
}

/* What an [onset] search needs of every group: fixed-frequency runs, and the
 * observable it reads (an intruder's rise, or the flux records). */
static int onset_group_check(const campaign *c, long p, sb_scene *s, sb_err *e)
{
	const cp_onset *o = &c->onset;
	char label[1024];
	grid_point_label(c, p, label, sizeof label);
	if (s->ramp != 0) /* RAMP_NONE */
		return sb_errf(e, SB_EUSAGE, "%s:%d: observable: the search runs fixed frequencies, but group %s has a "
			       "frequency ramp (ramp, set at %s): set ramp = none", c->path, o->observable_line, label,
			       params_where(s, "ramp"));
	if (o->observable == CP_OBS_RISE && !(s->radius_ratio > 0))
		return sb_errf(e, SB_EUSAGE, "%s:%d: observable: rise needs an intruder, but group %s has "
			       "radius_ratio = 0", c->path, o->observable_line, label);
	if (o->observable == CP_OBS_FLUX && !s->flux)
		return sb_errf(e, SB_EUSAGE, "%s:%d: observable: flux needs the flux records: set flux = yes under "
			       "[scene] (group %s has flux = no)", c->path, o->observable_line, label);
	if (o->axis != AXIS_FREQUENCY && !(s->amplitude > 0))
		return sb_errf(e, SB_EUSAGE, "%s:%d: axis: a search in %s needs an amplitude above 0, but group %s has "
			       "amplitude = %g", c->path, o->axis_line, drive_axis_name(o->axis), label, s->amplitude);
	double ends[2] = {o->from, o->to};
	for (int k = 0; k < 2; k++) {
		char at[128];
		s->frequency = grid_onset_frequency(c, s, ends[k]);
		if (o->axis == AXIS_FREQUENCY)
			snprintf(at, sizeof at, "frequency=%.12g", ends[k]);
		else
			snprintf(at, sizeof at, "%s=%.12g frequency=%.12g", drive_axis_name(o->axis), ends[k], s->frequency);
		if (point_check(c, p, s, at, e))
			return e->code;
	}
	return 0;
}

/* What replicates = auto's result needs of every point: an intruder whose rise is
 * recorded, or the flux records. */
static int autorep_point_check(const campaign *c, long p, const sb_scene *s, sb_err *e)
{
	const cp_auto *a = &c->autorep;
	char label[1024];
	grid_point_label(c, p, label, sizeof label);
	int line = a->result_line;
	if (a->result != CP_RES_MEAN_FLUX && !(s->radius_ratio > 0))
		return sb_errf(e, SB_EUSAGE, "%s:%d: result: %s needs an intruder, but grid point %s has "
			       "radius_ratio = 0", c->path, line,
			       a->result == CP_RES_MEDIAN_WAIT ? "median_wait" : "rise_fraction", label);
	if (a->result == CP_RES_MEAN_FLUX && !s->flux)
		return sb_errf(e, SB_EUSAGE, "%s:%d: result: mean_flux needs the flux records: set flux = yes under "
			       "[scene] (grid point %s has flux = no)", c->path, line, label);
	return 0;
}

int grid_expand(grid *g, const campaign *c, sb_err *e)
{
	memset(g, 0, sizeof *g);
	g->c = c;
	/* campaign_load has checked this; a campaign assembled otherwise gets the same
	 * limit before anything is allocated */
	long total;
	if (campaign_points(c, &total, e))
		return e->code;
	g->points = total;
	if (c->autorep.on) {
		for (long p = 0; p < total; p++) {
			sb_scene s;
			if (scene_point_at(c, p, &s, NULL, e) || autorep_point_check(c, p, &s, e) ||
			    point_check(c, p, &s, NULL, e))
				return e->code;
		}
		return 0;
	}
	if (c->onset.line) {
		for (long p = 0; p < total; p++) {
			sb_scene s;
			if (scene_point_at(c, p, &s, NULL, e) || onset_group_check(c, p, &s, e))
				return e->code;
		}
		return 0;
	}
	g->runs = calloc((size_t)total, sizeof *g->runs);
	if (!g->runs)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	g->cap = total;
	/* once, not per point: making the defaults is a third of a point's cost */
	sb_scene def;
	params_defaults(&def);
	for (long p = 0; p < total; p++) {
		sb_scene s;
		if (scene_point_at(c, p, &s, NULL, e) || point_check(c, p, &s, NULL, e)) {
			grid_free(g);
			return e->code;
		}
		grid_run *r = &g->runs[g->n];
		r->point = p;
		r->replicate = s.seed;
		r->seed = grid_seed(c, &s, s.seed);
		s.seed = r->seed;
		/* hashes over non-default values only: a key added to the engine later
		 * leaves the identities of existing campaigns as they were */
		snprintf(r->id, sizeof r->id, "%016llx", run_hash(&s, &def));
		snprintf(r->cache_key, sizeof r->cache_key, "%016llx", params_hash_nondefault(&s, PF_PREP));
		g->n++;
	}
	grid_sort(g);
	return 0;
}

void grid_sort(grid *g)
{
	if (!g->n)
		return;
	qsort(g->runs, (size_t)g->n, sizeof *g->runs, by_id);
	/* two points with the same parameters are one run (e.g. literal seeds) */
	long w = 0;
	for (long i = 0; i < g->n; i++)
		if (!w || strcmp(g->runs[w - 1].id, g->runs[i].id))
			g->runs[w++] = g->runs[i];
	g->n = w;
}

/* The scene of an [onset] run: the group's point at the frequency, the engine seed of
 * the replicate (a replicate's runs share their packing: frequency is no preparation
 * key). */
static void onset_run(const campaign *c, long point, long replicate, double frequency, grid_run *r)
{
	memset(r, 0, sizeof *r);
	sb_scene s;
	scene_point(c, point, &s);
	/* NaN: a replicate of a grid point with replicates = auto, at the point's own
	 * frequency: the same run (and id) as seed = replicate on a fixed grid */
	if (!isnan(frequency)) {
		s.frequency = frequency;
		r->has_frequency = 1;
		r->frequency = frequency;
	}
	r->point = point;
	r->replicate = replicate;
	r->seed = grid_seed(c, &s, replicate);
	s.seed = r->seed;
	snprintf(r->id, sizeof r->id, "%016llx", grid_run_hash(&s));
	snprintf(r->cache_key, sizeof r->cache_key, "%016llx", params_hash_nondefault(&s, PF_PREP));
}

double grid_onset_frequency(const campaign *c, const sb_scene *s, double x)
{
	return axes_frequency(c->onset.axis, x, s->amplitude, s->gravity);
}

void grid_point_scene(const campaign *c, long point, sb_scene *s)
{
	scene_point(c, point, s);
}

void grid_axis_text(const campaign *c, long point, int axis, char *buf, size_t len)
{
	sb_scene s;
	long digit[CP_MAX_KEYS];
	sb_err e = {0};
	scene_point_at(c, point, &s, digit, &e);
	snprintf(buf, len, "%s", c->axes[axis].values[digit[axis]]);
}

void grid_onset_id(const campaign *c, long point, long replicate, double frequency, char id[17])
{
	grid_run r;
	onset_run(c, point, replicate, frequency, &r);
	memcpy(id, r.id, 17);
}

int grid_add(grid *g, long point, long replicate, double frequency, char id[17], sb_err *e)
{
	if (g->n == g->cap) {
		long cap = g->cap ? 2 * g->cap : 64;
		grid_run *nr = realloc(g->runs, sizeof *nr * (size_t)cap);
		if (!nr)
			return sb_errf(e, SB_ENOMEM, "out of memory");
		g->runs = nr;
		g->cap = cap;
	}
	grid_run *r = &g->runs[g->n];
	onset_run(g->c, point, replicate, frequency, r);
	memcpy(id, r->id, 17);
	g->n++;
	return 0;
}

void grid_free(grid *g)
{
	free(g->runs);
	g->runs = NULL;
	g->n = g->cap = 0;
}

const grid_run *grid_find(const grid *g, const char *id)
{
	grid_run key;
	snprintf(key.id, sizeof key.id, "%s", id);
	return bsearch(&key, g->runs, (size_t)g->n, sizeof *g->runs, by_id);
}
