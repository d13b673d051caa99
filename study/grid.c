/* grid.c - grid expansion, seed derivation, run ids. */
#include "grid.h"

#include <stdlib.h>
#include <string.h>

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

static void scene_point(const campaign *c, long point, sb_scene *s)
{
	*s = c->base;
	sb_err e = {0};
	/* mixed radix, first axis fastest */
	for (int a = 0; a < c->naxes; a++) {
		long k = point % c->axes[a].n;
		point /= c->axes[a].n;
		char where[SB_STR_MAX + 32];
		snprintf(where, sizeof where, "%s:%d", c->path, c->axes[a].line);
		params_set(s, c->axes[a].key, c->axes[a].values[k], where, &e);
	}
}

void grid_scene(const grid *g, const grid_run *r, sb_scene *s)
{
	scene_point(g->c, r->point, s);
	s->seed = r->seed;
}

static int by_id(const void *a, const void *b)
{
	return strcmp(((const grid_run *)a)->id, ((const grid_run *)b)->id);
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
	g->runs = calloc((size_t)total, sizeof *g->runs);
	if (!g->runs)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	/* once, not per point: making the defaults is a third of a point's cost */
	sb_scene def;
	params_defaults(&def);
	for (long p = 0; p < total; p++) {
		sb_scene s;
		scene_point(c, p, &s);
		sb_err ve = {0};
		if (params_validate(&s, &ve)) {
			char pt[1024] = "";
			size_t l = 0;
			for (int a = 0; a < c->naxes && l < sizeof pt - 1; a++) {
				char v[SB_STR_MAX + 8];
				params_format(&s, params_find(c->axes[a].key), v, sizeof v);
				l += (size_t)snprintf(pt + l, sizeof pt - l, "%s%s=%s", a ? " " : "", c->axes[a].key, v);
			}
			/* the message names where the key at fault was set when it was set in
			 * this file; otherwise the grid's first line stands for it */
			int line = c->naxes ? c->axes[0].line : 0;
			if (!strncmp(ve.msg, c->path, strlen(c->path)))
				sb_errf(e, SB_EUSAGE, "%s (grid point %s)", ve.msg, pt);
			else
				sb_errf(e, SB_EUSAGE, "%s:%d: grid point %s: %s", c->path, line, pt, ve.msg);
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
	qsort(g->runs, (size_t)g->n, sizeof *g->runs, by_id);
	/* two points with the same parameters are one run (e.g. literal seeds) */
	long w = 0;
	for (long i = 0; i < g->n; i++)
		if (!w || strcmp(g->runs[w - 1].id, g->runs[i].id))
			g->runs[w++] = g->runs[i];
	g->n = w;
	return 0;
}

void grid_free(grid *g)
{
	free(g->runs);
	g->runs = NULL;
	g->n = 0;
}

const grid_run *grid_find(const grid *g, const char *id)
{
	grid_run key;
	snprintf(key.id, sizeof key.id, "%s", id);
	return bsearch(&key, g->runs, (size_t)g->n, sizeof *g->runs, by_id);
}
