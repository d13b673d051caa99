/* study_identity.c - what identifies a run (docs/driver.md "Run identity",
 * docs/campaigns.md "Replicates and seeds"): run ids, engine seeds and packing-cache
 * keys. The same parameters give the same id in any file, order or spelling; every key
 * but the driver's own changes the id; the engine seed derives from the campaign seed,
 * the replicate and the preparation keys only; runs that differ only in their dynamics
 * share one packing. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campaign/campaign.h"
#include "campaign/grid.h"
#include "params.h"
#include "study_files.h"
#include "testlib.h"

/* The keys the driver owns (docs/driver.md) and those that change only how the state
 * is saved (checkpoint_every, compression): not in a run's id. */
static const char *const DRIVER_KEYS[] = {"output", "checkpoint", "restart", "write_particles", "write_lammps",
					  "progress", "run_id", "checkpoint_every", "compression", NULL};

static int driver_key(const char *k)
{
	for (int i = 0; DRIVER_KEYS[i]; i++)
		if (!strcmp(DRIVER_KEYS[i], k))
			return 1;
	return 0;
}

/* A value of p other than its default that the parser takes, into s (a scene at the
 * defaults); 0 when no candidate is taken. */
static int set_other(sb_scene *s, const sb_param *p)
{
	char def[SB_STR_MAX + 8], got[SB_STR_MAX + 8], cand[16][64];
	int n = 0;
	params_format(s, p, def, sizeof def);
	if (p->type == PT_BOOL) {
		snprintf(cand[n++], sizeof cand[0], "yes");
		snprintf(cand[n++], sizeof cand[0], "no");
	} else if (p->type == PT_ENUM) {
		char ch[256], *save = NULL;
		snprintf(ch, sizeof ch, "%s", p->choices);
		for (char *c = strtok_r(ch, "|", &save); c && n < 16; c = strtok_r(NULL, "|", &save))
			snprintf(cand[n++], sizeof cand[0], "%s", c);
	} else if (p->type == PT_STR) {
		snprintf(cand[n++], sizeof cand[0], "other.txt");
	} else {
		const double d = atof(p->def);
		const double v[] = {2 * d, d + 1, 0.5 * d, p->min, p->max, 0.5 * (p->min + p->max)};
		for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
			snprintf(cand[n++], sizeof cand[0], p->type == PT_INT ? "%.0f" : "%.17g", v[i]);
	}
	for (int i = 0; i < n; i++) {
		sb_scene t = *s;
		sb_err e = {0};
		if (params_set(&t, p->name, cand[i], "test", &e))
			continue;
		params_format(&t, p, got, sizeof got);
		if (strcmp(got, def)) {
			*s = t;
			return 1;
		}
	}
	return 0;
}

/* Every key of the table, changed alone from the defaults: the run id changes unless
 * the driver owns the key; the engine seed and the cache key change exactly for the
 * preparation keys. */
static void test_every_key(void)
{
	size_t n;
	const sb_param *T = params_table(&n);
	sb_scene d;
	params_defaults(&d);
	static campaign c = {.seed = 11, .seeds = CP_SEEDS_DERIVED};
	const unsigned long long id0 = grid_run_hash(&d), ck0 = params_hash_nondefault(&d, PF_PREP);
	const long seed0 = grid_seed(&c, &d, 1);
	char id_bad[2048] = "", seed_bad[2048] = "", cache_bad[2048] = "", untested[512] = "";
	size_t li = 0, ls = 0, lc = 0, lu = 0;
	for (size_t i = 0; i < n; i++) {
		const sb_param *p = &T[i];
		sb_scene s = d;
		if (!set_other(&s, p)) {
			lu += (size_t)snprintf(untested + lu, lu < sizeof untested ? sizeof untested - lu : 0, " %s", p->name);
			continue;
		}
		const int own = driver_key(p->name), prep = (p->flags & PF_PREP) != 0;
		if ((grid_run_hash(&s) != id0) == own && li < sizeof id_bad)
			li += (size_t)snprintf(id_bad + li, sizeof id_bad - li, " %s", p->name);
		/* the seed key is the replicate label: it reaches the engine seed as the
		 * replicate, not as a preparation key */
		if (strcmp(p->name, "seed") && (grid_seed(&c, &s, 1) != seed0) != prep && ls < sizeof seed_bad)
			ls += (size_t)snprintf(seed_bad + ls, sizeof seed_bad - ls, " %s", p->name);
		if ((params_hash_nondefault(&s, PF_PREP) != ck0) != prep && lc < sizeof cache_bad)
			lc += (size_t)snprintf(cache_bad + lc, sizeof cache_bad - lc, " %s", p->name);
	}
	CHECK("study.id.every_key_but_the_drivers", !id_bad[0],
	      "the id of these keys does not follow the rule (in it unless driver-owned):%s", id_bad);
	CHECK("study.seed.preparation_keys_only", !seed_bad[0],
	      "the engine seed of these keys does not follow the rule (preparation keys only):%s", seed_bad);
	CHECK("study.cache.preparation_keys_only", !cache_bad[0],
	      "the cache key of these keys does not follow the rule (preparation keys only):%s", cache_bad);
	CHECK("study.id.every_key_tested", !untested[0], "no other value found for:%s", untested);
	int refused = 1;
	for (int i = 0; DRIVER_KEYS[i]; i++)
		/* PF_NOID keys: not in the id, but a campaign may set them */
		if (strcmp(DRIVER_KEYS[i], "checkpoint_every") && strcmp(DRIVER_KEYS[i], "compression"))
			refused &= campaign_key_reserved(DRIVER_KEYS[i]);
	CHECK("study.id.driver_keys_reserved", refused && !campaign_key_reserved("frequency"),
	      "campaign_key_reserved does not name exactly the driver's keys");
}

/* A key set to its default is the key not set (a key added to the engine later, with
 * a default that keeps the old behaviour, changes no id); a number's spelling and the
 * order in which keys are set do not matter. */
static void test_hash_spelling(void)
{
	sb_scene d, a, b;
	sb_err e = {0};
	params_defaults(&d);
	a = d;
	params_set(&a, "traj_rate", params_find("traj_rate")->def, "test", &e);
	params_set(&a, "frequency", params_find("frequency")->def, "test", &e);
	CHECK("study.id.default_is_absent", grid_run_hash(&a) == grid_run_hash(&d) && !e.code,
	      "setting keys to their defaults changed the id (%s)", e.msg);
	a = d;
	b = d;
	params_set(&a, "frequency", "2.8", "test", &e);
	params_set(&a, "amplitude", "1.5", "test", &e);
	params_set(&a, "n_grains", "200", "test", &e);
	params_set(&b, "n_grains", "200", "test", &e);
	params_set(&b, "amplitude", "1.50", "test", &e);
	params_set(&b, "frequency", "28e-1", "test", &e);
	CHECK("study.id.order_and_spelling", grid_run_hash(&a) == grid_run_hash(&b) && !e.code,
	      "the same values set in another order and spelling gave another id (%s)", e.msg);
}

#define HEAD "[campaign]\nname = a\nseed = 11\nreplicates = 2\n"
#define SCENE "[scene]\nn_grains = 200\nwidth = 20\namplitude = 1.5\nduration = 2\n"
#define AXES "[grid]\nfrequency = 2.8, 3\nradius_ratio = 0, 2\n"
static const char *const A = HEAD SCENE AXES;

/* The runs of two grids are the same: ids, replicates, engine seeds, cache keys. */
static int same_runs(const grid *a, const grid *b, char *why, size_t len)
{
	if (a->n != b->n)
		return snprintf(why, len, "%ld runs against %ld", a->n, b->n), 0;
	for (long i = 0; i < a->n; i++) {
		const grid_run *x = &a->runs[i], *y = &b->runs[i];
		if (strcmp(x->id, y->id) || strcmp(x->cache_key, y->cache_key) || x->seed != y->seed ||
		    x->replicate != y->replicate)
			return snprintf(why, len, "run %ld: %s/%s/%ld/%ld against %s/%s/%ld/%ld", i, x->id, x->cache_key,
					x->seed, x->replicate, y->id, y->cache_key, y->seed, y->replicate),
			       0;
	}
	return 1;
}

/* CHECKs that campaign text gives the runs of campaign A. */
static void same_as_a(const char *id, const grid *ga, const char *text)
{
	campaign c;
	grid g;
	sb_err e;
	char why[256] = "";
	int rc = sf_expand(text, &c, &g, &e);
	CHECK(id, !rc && same_runs(ga, &g, why, sizeof why), "%s", rc ? e.msg : why);
	if (!rc)
		sf_free(&c, &g);
}

/* The run of g at point p (NULL when none is). */
static const grid_run *at_point(const grid *g, long p)
{
	for (long i = 0; i < g->n; i++)
		if (g->runs[i].point == p)
			return &g->runs[i];
	return NULL;
}

/* Campaign files that say the same thing otherwise give the same runs. */
static void test_same_runs(const grid *ga)
{
	same_as_a("study.id.campaign.order_spelling_name", ga,
		  "# the runs of A, written otherwise\n[grid]\nradius_ratio = 2.0, 0\nfrequency = 3.0, 2.80\n"
		  "[scene]\nduration = 2.0\namplitude = 1.50\nwidth = 2e1\nn_grains = 200\n"
		  "[campaign]\nreplicates = 2\ndescription = the same runs\nseed = 11\nname = b\n");
	char path[256];
	sf_write("base.scene", "n_grains = 200\nwidth = 20\n", path, sizeof path);
	same_as_a("study.id.campaign.scene_file", ga,
		  "[campaign]\nname = a\nscene = base.scene\nseed = 11\nreplicates = 2\n"
		  "[scene]\namplitude = 1.5\nduration = 2\n" AXES);
	same_as_a("study.id.campaign.checkpoint_every_not_in_id", ga, HEAD SCENE "checkpoint_every = 0.5\n" AXES);
	same_as_a("study.id.campaign.default_value_absent", ga, HEAD SCENE "traj_rate = 100\ngravity = 981\n" AXES);
	/* a fixed key is a one-value axis: its runs are among A's */
	campaign c;
	grid g;
	sb_err e;
	int rc = sf_expand(HEAD SCENE "frequency = 2.8\n[grid]\nradius_ratio = 0, 2\n", &c, &g, &e), sub = !rc && g.n == 4;
	for (long i = 0; sub && i < g.n; i++)
		sub = grid_find(ga, g.runs[i].id) != NULL;
	CHECK("study.id.campaign.fixed_is_one_value_axis", sub, "%s", rc ? e.msg : "runs not among A's");
	if (!rc)
		sf_free(&c, &g);
}

/* A recorded key changes every id (not the seeds or packings); another campaign seed
 * changes every seed, id and packing. */
static void test_changed_runs(const grid *ga)
{
	campaign c;
	grid g;
	sb_err e;
	int rc = sf_expand(HEAD SCENE "traj_rate = 50\n" AXES, &c, &g, &e), ok = !rc && g.n == ga->n;
	for (long p = 0; ok && p < g.n; p++) {
		const grid_run *x = at_point(ga, p), *y = at_point(&g, p);
		ok = x && y && !grid_find(ga, y->id) && x->seed == y->seed && !strcmp(x->cache_key, y->cache_key);
	}
	CHECK("study.id.campaign.recorded_key_changes_id", ok, "%s",
	      rc ? e.msg : "traj_rate = 50 kept an id, or changed a seed or a cache key");
	if (!rc)
		sf_free(&c, &g);
	rc = sf_expand("[campaign]\nname = a\nseed = 12\nreplicates = 2\n" SCENE AXES, &c, &g, &e);
	ok = !rc && g.n == ga->n;
	for (long p = 0; ok && p < g.n; p++) {
		const grid_run *x = at_point(ga, p), *y = at_point(&g, p);
		ok = x && y && x->seed != y->seed && strcmp(x->id, y->id) && strcmp(x->cache_key, y->cache_key);
	}
	CHECK("study.seed.campaign_seed", ok, "%s", rc ? e.msg : "campaign seed 12 kept a seed, an id or a packing");
	if (!rc)
		sf_free(&c, &g);
}

/* SplitMix64's finaliser, as docs/campaigns.md "Replicates and seeds" gives it. */
static unsigned long long mix(unsigned long long z)
{
	z += 0x9e3779b97f4a7c15ULL;
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
	return z ^ (z >> 31);
}

/* Within campaign A: the seed of a run is the documented function of (campaign seed,
 * replicate, preparation keys); runs that differ only in frequency share their seed
 * and packing; runs that differ in a preparation key or replicate do not; the id and
 * the cache key are the hashes of the run's canonical scene. */
static void test_seeds_in_grid(const grid *ga)
{
	int formula = 1, range = 1, shared = 1, apart = 1, id_hash = 1, cache_hash = 1;
	for (long i = 0; i < ga->n; i++) {
		const grid_run *r = &ga->runs[i];
		sb_scene s;
		grid_scene(ga, r, &s);
		char h[17];
		snprintf(h, sizeof h, "%016llx", grid_run_hash(&s));
		id_hash &= !strcmp(h, r->id);
		snprintf(h, sizeof h, "%016llx", params_hash_nondefault(&s, PF_PREP));
		cache_hash &= !strcmp(h, r->cache_key);
		s.seed = 0;
		const unsigned long long want =
			1 + mix(mix(mix(11) ^ (unsigned long long)r->replicate) ^ params_hash_nondefault(&s, PF_PREP)) %
				    4294967295ULL;
		formula &= (unsigned long long)r->seed == want;
		range &= r->seed >= 1 && r->seed <= 4294967295L;
		sb_scene si;
		grid_scene(ga, r, &si);
		for (long j = 0; j < ga->n; j++) {
			const grid_run *q = &ga->runs[j];
			sb_scene sj;
			grid_scene(ga, q, &sj);
			const int same_prep = q->replicate == r->replicate && si.radius_ratio == sj.radius_ratio;
			if (same_prep)
				shared &= q->seed == r->seed && !strcmp(q->cache_key, r->cache_key);
			else
				apart &= q->seed != r->seed && strcmp(q->cache_key, r->cache_key);
		}
	}
	CHECK("study.seed.formula", formula, "an engine seed is not 1 + mix(mix(mix(seed) ^ replicate) ^ prep hash) mod 2^32-1");
	CHECK("study.seed.range", range, "an engine seed is outside [1, 2^32 - 1]");
	CHECK("study.seed.shared_across_frequency", shared, "runs differing only in frequency differ in seed or packing");
	CHECK("study.seed.distinct_preparations", apart, "runs of different replicates or radius ratios share a seed or packing");
	CHECK("study.id.is_hash_of_scene", id_hash, "a run id is not %%016llx of grid_run_hash(its scene)");
	CHECK("study.cache.is_prep_hash_of_scene", cache_hash, "a cache key is not %%016llx of the scene's PF_PREP hash");
}

/* seeds = literal: the replicate label is the engine seed. */
static void test_literal(void)
{
	campaign c;
	grid g;
	sb_err e;
	int rc = sf_expand("[campaign]\nname = l\nseed = 11\nseeds = literal\nreplicates = 3\n" SCENE AXES, &c, &g, &e);
	int ok = !rc && g.n == 12;
	for (long i = 0; ok && i < g.n; i++)
		ok = g.runs[i].seed == g.runs[i].replicate && g.runs[i].replicate >= 1 && g.runs[i].replicate <= 3;
	CHECK("study.seed.literal", ok, "%s", rc ? e.msg : "an engine seed is not its replicate label");
	if (!rc)
		sf_free(&c, &g);
	static campaign lit = {.seed = 11, .seeds = CP_SEEDS_LITERAL};
	sb_scene s;
	params_defaults(&s);
	CHECK("study.seed.literal_grid_seed", grid_seed(&lit, &s, 7) == 7, "grid_seed with seeds = literal is not the label");
}

/* A campaign cannot set what the driver owns. */
static void test_driver_keys_refused(void)
{
	static const char *const keys[] = {"output = x.h5", "checkpoint = x.ckpt", "restart = no",
					   "write_particles = p.txt", "write_lammps = l.data", "progress = no", NULL};
	char id[96], text[512];
	for (int i = 0; keys[i]; i++) {
		campaign c;
		sb_err e;
		snprintf(text, sizeof text, "[campaign]\nname = r\nseed = 1\n[scene]\n%s\n", keys[i]);
		int rc = sf_load(text, &c, &e);
		snprintf(id, sizeof id, "study.id.driver_key_refused.%.*s", (int)strcspn(keys[i], " "), keys[i]);
		CHECK(id, rc == SB_EUSAGE && strstr(e.msg, "set by the study driver") && strstr(e.msg, ":5:"),
		      "'%s' in [scene]: rc %d '%s'", keys[i], rc, e.msg);
		campaign_free(&c);
	}
	campaign c;
	sb_err e;
	int rc = sf_load("[campaign]\nname = r\nseed = 1\n[grid]\ncheckpoint_every = 1, 2\n", &c, &e);
	CHECK("study.id.checkpoint_every_not_an_axis", rc == SB_EUSAGE && strstr(e.msg, "checkpoint_every"),
	      "rc %d '%s'", rc, e.msg);
	campaign_free(&c);
}

int main(void)
{
	if (sf_init()) {
		printf("FAIL study.id.setup: cannot make a temporary directory\n");
		return 1;
	}
	test_every_key();
	test_hash_spelling();
	campaign ca;
	grid ga;
	sb_err e;
	int rc = sf_expand(A, &ca, &ga, &e);
	CHECK("study.id.campaign.expands", !rc && ga.n == 8, "%s", rc ? e.msg : "not 8 runs");
	if (!rc) {
		test_same_runs(&ga);
		test_changed_runs(&ga);
		test_seeds_in_grid(&ga);
		sf_free(&ca, &ga);
	}
	test_literal();
	test_driver_keys_refused();
	sf_cleanup();
	return tl_done();
}
