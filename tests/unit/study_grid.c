/* study_grid.c - grid expansion (study/campaign/campaign.c, study/campaign/grid.c) against the contract of
 * docs/campaigns.md, "Campaign files": the runs are the cartesian product of the axes (first axis
 * fastest, values in file order, replicates the last axis), sorted by id; values are
 * canonical and duplicates are dropped, within an axis and between grid points;
 * START:STOP:STEP and FIRST..LAST ranges give the values of the written-out list; the
 * grid's size is bounded by max_runs before anything is expanded. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campaign/campaign.h"
#include "campaign/grid.h"
#include "params.h"
#include "study_files.h"
#include "testlib.h"

#define WHERE "t.campaign:3"

/* The axis's values joined by commas (truncated to len). */
static const char *joined(const cp_axis *a, char *buf, size_t len)
{
	size_t l = 0;
	buf[0] = 0;
	for (long i = 0; i < a->n && l < len; i++)
		l += (size_t)snprintf(buf + l, len - l, "%s%s", i ? "," : "", a->values[i]);
	return buf;
}

static void axis_free(cp_axis *a)
{
	for (long i = 0; i < a->n; i++)
		free(a->values[i]);
	free(a->values);
	memset(a, 0, sizeof *a);
}

/* The canonical text (params_format) of each of the comma-separated values, joined
 * by commas: what an axis stores (real values as %.17g). */
static const char *canonical(const char *key, const char *values, char *buf, size_t len)
{
	char copy[4096], *save = NULL;
	size_t l = 0;
	sb_scene s;
	params_defaults(&s);
	snprintf(copy, sizeof copy, "%s", values);
	buf[0] = 0;
	for (char *v = strtok_r(copy, ",", &save); v && l < len; v = strtok_r(NULL, ",", &save)) {
		sb_err e = {0};
		char one[SB_STR_MAX + 8];
		params_set(&s, key, v, "test", &e);
		params_format(&s, params_find(key), one, sizeof one);
		l += (size_t)snprintf(buf + l, len - l, "%s%s", l ? "," : "", one);
	}
	return buf;
}

/* CHECKs that key = text gives exactly the values want (comma separated, canonical
 * text of each). */
static void axis_is(const char *id, const char *key, const char *text, const char *want)
{
	cp_axis a;
	sb_err e = {0};
	char got[4096], w[4096];
	int rc = campaign_axis_parse(&a, key, text, WHERE, &e);
	canonical(key, want, w, sizeof w);
	CHECK(id, !rc && !strcmp(joined(&a, got, sizeof got), w), "%s = %s: got '%s' (%s), want '%s'", key, text,
	      rc ? "" : got, rc ? e.msg : "ok", w);
	axis_free(&a);
}

/* CHECKs that key = text gives the same values as key = list (a written-out list). */
static void axis_same(const char *id, const char *key, const char *text, const char *list)
{
	cp_axis a, b;
	sb_err e1 = {0}, e2 = {0};
	char ga[4096], gb[4096];
	int r1 = campaign_axis_parse(&a, key, text, WHERE, &e1), r2 = campaign_axis_parse(&b, key, list, WHERE, &e2);
	CHECK(id, !r1 && !r2 && a.n == b.n && !strcmp(joined(&a, ga, sizeof ga), joined(&b, gb, sizeof gb)),
	      "%s = %s gives '%s' (%s), the list '%s' (%s)", key, text, r1 ? "" : ga, e1.msg, r2 ? "" : gb, e2.msg);
	axis_free(&a);
	axis_free(&b);
}

/* CHECKs that key = text is refused as a usage error whose message holds every one of
 * the (NULL-terminated) words. */
static void axis_refused(const char *id, const char *key, const char *text, const char *const *words)
{
	cp_axis a;
	sb_err e = {0};
	int rc = campaign_axis_parse(&a, key, text, WHERE, &e);
	int named = rc == SB_EUSAGE && !strncmp(e.msg, WHERE ": ", strlen(WHERE) + 2);
	for (const char *const *w = words; named && *w; w++)
		named = strstr(e.msg, *w) != NULL;
	CHECK(id, named, "%s = %s: rc %d, message '%s'", key, text, rc, e.msg);
	axis_free(&a); /* a refused axis keeps the values made before the error (the caller frees) */
}

/* The runs are the product of the axes: its size, every point once, the values of
 * each point decoded as a mixed radix (first axis fastest), replicates last, the runs
 * sorted by id and found by it. */
static void test_product(void)
{
	campaign c;
	grid g;
	sb_err e;
	int rc = sf_expand("[campaign]\nname = g\nseed = 5\nreplicates = 2\n[grid]\nfrequency = 3, 4, 5\n"
			   "radius_ratio = 0, 2\n", &c, &g, &e);
	CHECK("study.grid.product.expands", !rc, "%s", e.msg);
	if (rc)
		return;
	long points = 0;
	campaign_points(&c, &points, &e);
	CHECK("study.grid.product.size", points == 12 && g.n == 12, "%ld points, %ld runs; want 3 x 2 x 2 = 12", points,
	      g.n);
	CHECK("study.grid.product.replicates_last_axis",
	      c.naxes == 3 && !strcmp(c.axes[0].key, "frequency") && !strcmp(c.axes[1].key, "radius_ratio") &&
		      !strcmp(c.axes[2].key, "seed") && c.axes[2].n == 2,
	      "axes: %d, the last '%s'", c.naxes, c.naxes ? c.axes[c.naxes - 1].key : "");
	int seen[12] = {0}, points_ok = 1, decoded = 1, sorted = 1, found = 1, hex = 1;
	char why[2 * SB_STR_MAX + 200] = "";
	for (long i = 0; i < g.n; i++) {
		const grid_run *r = &g.runs[i];
		if (r->point < 0 || r->point >= 12 || seen[r->point]++)
			points_ok = 0;
		if (i && strcmp(g.runs[i - 1].id, r->id) >= 0)
			sorted = 0;
		if (grid_find(&g, r->id) != r)
			found = 0;
		hex &= strlen(r->id) == 16 && strspn(r->id, "0123456789abcdef") == 16;
		sb_scene s;
		grid_scene(&g, r, &s);
		long stride = 1;
		for (int a = 0; a < c.naxes; a++) {
			const cp_axis *ax = &c.axes[a];
			const char *want = ax->values[(r->point / stride) % ax->n];
			char got[SB_STR_MAX + 8];
			if (!strcmp(ax->key, "seed")) /* the scene holds the engine seed; the label is the replicate */
				snprintf(got, sizeof got, "%ld", r->replicate);
			else
				params_format(&s, params_find(ax->key), got, sizeof got);
			if (strcmp(got, want) && decoded) {
				decoded = 0;
				snprintf(why, sizeof why, "point %ld: %s = %s, want %s", r->point, ax->key, got, want);
			}
			stride *= ax->n;
		}
	}
	CHECK("study.grid.product.every_point_once", points_ok, "the points are not 0..11 once each");
	CHECK("study.grid.order.first_axis_fastest", decoded, "%s", why);
	CHECK("study.grid.order.sorted_by_id", sorted, "runs not in ascending id order");
	CHECK("study.grid.find", found && !grid_find(&g, "no such id"), "grid_find does not find the runs' ids");
	CHECK("study.grid.id.hex16", hex, "an id is not 16 lower-case hex digits");
	sf_free(&c, &g);
}

/* Values keep their first occurrence in file order; spellings of one value are one. */
static void test_axis_values(void)
{
	axis_is("study.grid.axis.file_order", "frequency", "5, 3, 4", "5,3,4");
	axis_is("study.grid.axis.canonical", "frequency", "2.60, 3.0, 4e0", "2.6,3,4");
	axis_is("study.grid.axis.duplicates_dropped", "frequency", "2.6, 2.60, 2.8, 26e-1, 2.6", "2.6,2.8");
	axis_is("study.grid.axis.first_occurrence_kept", "frequency", "2.8, 2.6, 2.80", "2.8,2.6");
	axis_is("study.grid.axis.int_duplicates", "depth", "3, 1, 3, 2, 1", "3,1,2");
	axis_is("study.grid.axis.enum_duplicates", "integrator", "verlet, gear5, verlet", "verlet,gear5");
	/* an empty item is a value left out: refused, naming it (it was dropped silently) */
	static const char *const trailing[] = {"depth", "item 2 of '15,' is empty", NULL};
	axis_refused("study.grid.axis.empty_item_trailing", "depth", "15,", trailing);
	static const char *const inner[] = {"depth", "item 2 of ' 1 ,, 2' is empty", NULL};
	axis_refused("study.grid.axis.empty_item_inner", "depth", " 1 ,, 2", inner);
	/* many duplicates: the first occurrences, in order */
	cp_axis a;
	sb_err e = {0};
	int rc = campaign_axis_parse(&a, "depth", "1..50000, 1..50000", WHERE, &e), order = !rc && a.n == 50000;
	for (long i = 0; order && i < a.n; i++)
		order = atol(a.values[i]) == i + 1;
	CHECK("study.grid.axis.many_duplicates", order, "rc %d (%s), %ld values", rc, e.msg, rc ? 0 : a.n);
	axis_free(&a);
	static const char *const none[] = {"depth", "no values", NULL};
	axis_refused("study.grid.axis.empty_refused", "depth", "  ", none);
	static const char *const commas[] = {"depth", "item 1 of ' , ' is empty", NULL};
	axis_refused("study.grid.axis.only_commas_refused", "depth", " , ", commas);
	/* a range past 12 significant digits: its values would read as others */
	static const char *const digits[] = {"frequency", "range '1.0000000000001:1.0000000000003:1e-13'", "value 1",
					     "outside the range", "write the values as a list", NULL};
	axis_refused("study.grid.range.refused.past_12_digits", "frequency", "1.0000000000001:1.0000000000003:1e-13",
		     digits);
	static const char *const collapse[] = {"frequency", "value 2", "the one before it", NULL};
	axis_refused("study.grid.range.refused.values_collapse", "frequency", "1:1.0000000000003:1e-13", collapse);

	/* in a campaign: a duplicated axis value is no second run */
	campaign c;
	grid g;
	rc = sf_expand("[campaign]\nname = d\nseed = 1\n[grid]\nfrequency = 3, 3.0, 4\n", &c, &g, &e);
	CHECK("study.grid.axis.duplicates_no_runs", !rc && c.axes[0].n == 2 && g.n == 2, "rc %d (%s), %ld runs", rc,
	      e.msg, rc ? 0 : g.n);
	if (!rc)
		sf_free(&c, &g);
}

/* Ranges give exactly the values of the written-out list (hence the same run ids). */
static void test_ranges(void)
{
	axis_same("study.grid.range.float", "frequency", "2.5:3.2:0.05",
		  "2.5, 2.55, 2.6, 2.65, 2.7, 2.75, 2.8, 2.85, 2.9, 2.95, 3, 3.05, 3.1, 3.15, 3.2");
	axis_is("study.grid.range.float_count", "frequency", "2.5:3.2:0.05",
		"2.5,2.55,2.6,2.65,2.7,2.75,2.8,2.85,2.9,2.95,3,3.05,3.1,3.15,3.2");
	axis_is("study.grid.range.float_stop_off_grid", "frequency", "1:2:0.3", "1,1.3,1.6,1.9");
	axis_is("study.grid.range.float_one_value", "frequency", "2:2:0.5", "2");
	axis_same("study.grid.range.mixed_with_list", "radius_ratio", "2:4:0.25, 5, 6",
		  "2, 2.25, 2.5, 2.75, 3, 3.25, 3.5, 3.75, 4, 5, 6");
	axis_is("study.grid.range.overlap_deduplicated", "frequency", "1:2:0.5, 1.5:2.5:0.5", "1,1.5,2,2.5");
	axis_is("study.grid.range.colon_on_int_key", "depth", "0:4:2", "0,2,4");
	axis_is("study.grid.range.int", "depth", "0..3", "0,1,2,3");
	axis_is("study.grid.range.int_one_value", "depth", "2..2", "2");
	axis_is("study.grid.range.int_overlap", "depth", "0..2, 1..4", "0,1,2,3,4");
	axis_same("study.grid.range.int_as_list", "n_grains", "98..102", "98, 99, 100, 101, 102");

	static const char *const bad_f[] = {"frequency", "bad range", NULL};
	static const char *const bad_d[] = {"depth", "bad range", NULL};
	static const char *const freq[] = {"frequency", NULL};
	axis_refused("study.grid.range.refused.stop_below_start", "frequency", "3:2:0.1", bad_f);
	axis_refused("study.grid.range.refused.step_zero", "frequency", "1:2:0", bad_f);
	axis_refused("study.grid.range.refused.step_negative", "frequency", "1:2:-0.1", bad_f);
	axis_refused("study.grid.range.refused.two_parts", "frequency", "1:2", bad_f);
	axis_refused("study.grid.range.refused.four_parts", "frequency", "1:2:3:4", bad_f);
	axis_refused("study.grid.range.refused.not_a_number", "frequency", "a:2:0.1", bad_f);
	axis_refused("study.grid.range.refused.int_descending", "depth", "3..1", bad_d);
	axis_refused("study.grid.range.refused.int_not_a_number", "depth", "1..x", bad_d);
	/* FIRST..LAST is for integer keys: on a real key it is no number */
	axis_refused("study.grid.range.refused.dots_on_real_key", "frequency", "1..3", freq);
	/* every value of a range is checked against the key's range */
	axis_refused("study.grid.range.refused.value_out_of_range", "frequency", "999:1001:1", freq);
}

/* Two grid points with the same parameters are one run: an axis of a key that is no
 * part of a run's identity (compression: how the file is stored, not what it holds). */
static void test_point_duplicates(void)
{
	campaign c;
	grid g;
	sb_err e;
	int rc = sf_expand("[campaign]\nname = p\nseed = 1\n[grid]\ncompression = 1, 4\n", &c, &g, &e);
	long points = 0;
	if (!rc)
		campaign_points(&c, &points, &e);
	CHECK("study.grid.points.duplicates_one_run", !rc && points == 2 && g.n == 1, "rc %d (%s): %ld points, %ld runs",
	      rc, e.msg, points, rc ? 0 : g.n);
	if (!rc)
		sf_free(&c, &g);
}

/* docs/model.md: a preset is applied first, keys given explicitly win wherever they
 * appear - a dt axis before or after a preset axis, a fixed dt under a preset axis, a
 * base scene's preset under the campaign's own. */
static void preset_grid(const char *id, const char *text, long want_runs, const char *want)
{
	campaign c;
	grid g;
	sb_err e;
	int rc = sf_expand(text, &c, &g, &e);
	char got[512] = "";
	size_t l = 0;
	long n = rc ? 0 : g.n;
	/* every run's integrator and dt, in the grid's order (by id), sorted as text */
	char *rows[16];
	for (long i = 0; i < n && i < 16; i++) {
		sb_scene s;
		grid_scene(&g, &g.runs[i], &s);
		char ig[32];
		params_format(&s, params_find("integrator"), ig, sizeof ig);
		rows[i] = malloc(64);
		snprintf(rows[i], 64, "%s@%g", ig, s.dt);
	}
	for (long i = 0; i < n && i < 16; i++) /* a few rows: insertion sort */
		for (long k = i; k > 0 && strcmp(rows[k - 1], rows[k]) > 0; k--) {
			char *t = rows[k];
			rows[k] = rows[k - 1];
			rows[k - 1] = t;
		}
	for (long i = 0; i < n && i < 16; i++) {
		l += (size_t)snprintf(got + l, sizeof got - l, "%s%s", i ? " " : "", rows[i]);
		free(rows[i]);
	}
	CHECK(id, !rc && n == want_runs && !strcmp(got, want), "rc %d (%s): %ld runs '%s', want %ld '%s'", rc, e.msg, n,
	      got, want_runs, want);
	if (!rc)
		sf_free(&c, &g);
}

static void test_preset_explicit_wins(void)
{
	preset_grid("study.grid.preset.dt_axis_before_wins",
		    "[campaign]\nname = p\nseed = 1\n[grid]\ndt = 0.0001, 0.0002\npreset = fast\n", 2,
		    "verlet@0.0001 verlet@0.0002");
	preset_grid("study.grid.preset.dt_axis_after_wins",
		    "[campaign]\nname = p\nseed = 1\n[grid]\npreset = fast\ndt = 0.0001, 0.0002\n", 2,
		    "verlet@0.0001 verlet@0.0002");
	preset_grid("study.grid.preset.fixed_dt_stays",
		    "[campaign]\nname = p\nseed = 1\n[scene]\ndt = 1e-5\n[grid]\npreset = paper, fast\n", 2,
		    "gear5@1e-05 verlet@1e-05");
	preset_grid("study.grid.preset.fixed_integrator_stays",
		    "[campaign]\nname = p\nseed = 1\n[grid]\npreset = paper, fast\n[scene]\nintegrator = gear4\n", 2,
		    "gear4@0.0002 gear4@5e-05");
	/* the campaign's preset replaces its base scene's (scenes/paper.scene says preset =
	 * paper): what campaigns/reproduce/ do */
	char scene[256];
	sf_write("preset.scene", "preset = paper\nn_grains = 40\n", scene, sizeof scene);
	char text[600];
	snprintf(text, sizeof text, "[campaign]\nname = p\nseed = 1\nscene = %s\n[scene]\npreset = fast\n", scene);
	preset_grid("study.grid.preset.replaces_the_scene_files_preset", text, 1, "verlet@0.0002");
	sf_write("dt.scene", "dt = 1e-5\n", scene, sizeof scene);
	snprintf(text, sizeof text, "[campaign]\nname = p\nseed = 1\nscene = %s\n[scene]\npreset = fast\n", scene);
	preset_grid("study.grid.preset.keeps_the_scene_files_dt", text, 1, "verlet@1e-05");
}

/* The grid's size is known before any point is made, and bounded: CP_MAX_RUNS_DEFAULT,
 * raised by max_runs; an axis has at most CP_MAX_VALUES values. */
static void test_bounds(void)
{
	campaign c;
	sb_err e;
	int rc = sf_load("[campaign]\nname = b\nseed = 1\nmax_runs = 12\n[grid]\nfrequency = 3, 4, 5\ndepth = 0..3\n", &c,
			 &e);
	CHECK("study.grid.bounds.max_runs_reached", !rc, "12 points with max_runs = 12: %s", e.msg);
	campaign_free(&c);
	rc = sf_load("[campaign]\nname = b\nseed = 1\nmax_runs = 11\n[grid]\nfrequency = 3, 4, 5\ndepth = 0..3\n", &c, &e);
	CHECK("study.grid.bounds.max_runs_exceeded", rc == SB_EUSAGE && strstr(e.msg, "max_runs"),
	      "12 points with max_runs = 11: rc %d '%s'", rc, e.msg);
	campaign_free(&c);
	/* 400 x 300 points: refused by default, counted (not expanded) when allowed */
	rc = sf_load("[campaign]\nname = b\nseed = 1\n[grid]\ndepth = 1..400\nn_grains = 1..300\n", &c, &e);
	CHECK("study.grid.bounds.default_limit", rc == SB_EUSAGE && strstr(e.msg, "max_runs") && CP_MAX_RUNS_DEFAULT < 120000,
	      "120000 points without max_runs: rc %d '%s'", rc, e.msg);
	campaign_free(&c);
	rc = sf_load("[campaign]\nname = b\nseed = 1\nmax_runs = 120000\n[grid]\ndepth = 1..400\nn_grains = 1..300\n", &c,
		     &e);
	long points = 0;
	if (!rc)
		campaign_points(&c, &points, &e);
	CHECK("study.grid.bounds.max_runs_raises", !rc && points == 120000, "rc %d '%s', %ld points", rc, e.msg, points);
	campaign_free(&c);
	static const char *const many[] = {"depth", NULL};
	axis_refused("study.grid.bounds.axis_values", "depth", "0..100000", many);
}

/* zip = KEY KEY: the zipped axes advance together (value k with value k), the leader
 * keeps its place in the order; mismatched sizes, repeated values, unknown keys and a
 * single key are refused with the line. */
static void test_zip(void)
{
	campaign c;
	grid g;
	sb_err e;
	/* gamma_n named first but written after stiffness in [grid]: the file order leads */
	int rc = sf_expand("[campaign]\nname = z\nseed = 1\nzip = gamma_n stiffness\nreplicates = 2\n[grid]\n"
			   "stiffness = 3e6, 4e6, 5e6\nfrequency = 2.8, 3\ngamma_n = 100, 316, 1000\n", &c, &g, &e);
	CHECK("study.grid.zip.expands", !rc, "%s", e.msg);
	if (rc)
		return;
	long points = 0;
	campaign_points(&c, &points, &e);
	int tuples = 1, seen[3] = {0};
	for (long i = 0; i < g.n; i++) {
		sb_scene s;
		grid_scene(&g, &g.runs[i], &s);
		int k = s.stiffness == 3e6 ? 0 : s.stiffness == 4e6 ? 1 : 2;
		const double want[] = {100, 316, 1000};
		if (s.gamma_n != want[k])
			tuples = 0;
		seen[k]++;
	}
	CHECK("study.grid.zip.size", points == 12 && g.n == 12, "%ld points, %ld runs; want 3 tuples x 2 x 2 = 12",
	      points, g.n);
	CHECK("study.grid.zip.tuples", tuples && seen[0] == 4 && seen[1] == 4 && seen[2] == 4,
	      "a run pairs stiffness with another gamma_n than its own (%d %d %d)", seen[0], seen[1], seen[2]);
	sf_free(&c, &g);
	static const struct {
		const char *id, *text, *word;
	} bad[] = {
		{"study.grid.zip.sizes_differ", "zip = stiffness gamma_n\n[grid]\nstiffness = 3e6, 3e7\ngamma_n = 1, 2, 3\n",
		 "as many values"},
		{"study.grid.zip.repeated_value", "zip = stiffness gamma_n\n[grid]\nstiffness = 3e6, 3e7\ngamma_n = 1, 1\n",
		 "distinct"},
		{"study.grid.zip.not_an_axis", "zip = stiffness mu\n[grid]\nstiffness = 3e6, 3e7\n[scene]\nmu = 0.3\n",
		 "not a [grid] axis"},
		{"study.grid.zip.one_key", "zip = stiffness\n[grid]\nstiffness = 3e6, 3e7\n", "at least two"},
		{"study.grid.zip.twice", "zip = stiffness stiffness\n[grid]\nstiffness = 3e6, 3e7\n", "twice"},
	};
	for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
		char text[512];
		snprintf(text, sizeof text, "[campaign]\nname = z\nseed = 1\n%s", bad[i].text);
		memset(&e, 0, sizeof e);
		rc = sf_load(text, &c, &e);
		CHECK(bad[i].id, rc == SB_EUSAGE && strstr(e.msg, bad[i].word) && strstr(e.msg, ".campaign:"),
		      "rc %d '%s' (want a message with the file, line and '%s')", rc, e.msg, bad[i].word);
		campaign_free(&c);
	}
}

/* The run of grid point `point` (the first with it: replicates are one here). */
static const grid_run *run_at(const grid *g, long point)
{
	for (long i = 0; i < g->n; i++)
		if (g->runs[i].point == point)
			return &g->runs[i];
	return NULL;
}

/* A campaign the driver must refuse: head + body, and a word of the message. */
typedef struct refusal {
	const char *id, *body, *word;
} refusal;

static void refusals(const char *head, const refusal *bad, size_t n)
{
	for (size_t i = 0; i < n; i++) {
		char text[1024];
		campaign c;
		grid g;
		sb_err e;
		snprintf(text, sizeof text, "%s%s", head, bad[i].body);
		int rc = sf_expand(text, &c, &g, &e);
		CHECK(bad[i].id, rc == SB_EUSAGE && strstr(e.msg, bad[i].word), "rc %d '%s' (want '%s')", rc, e.msg, bad[i].word);
		if (!rc)
			sf_free(&c, &g);
	}
}

/* gamma and velocity axes (docs/campaigns.md, "Axes in Gamma and v"): the frequency
 * from the amplitude, the amplitude from a set frequency, both from both; the runs are
 * the frequency grid's (same ids); what cannot make a drive is refused with the line. */
static void test_derived(void)
{
	const double tau = 6.283185307179586;
	campaign c, c2;
	grid g, g2;
	sb_err e;
	const char *head = "[campaign]\nname = d\nseed = 1\n";
	char text[1024];
	snprintf(text, sizeof text, "%s[scene]\namplitude = 1\n[grid]\ngamma = 1.5, 2.5\n", head);
	int rc = sf_expand(text, &c, &g, &e);
	double want[2] = {sqrt(1.5 * 981 / 1) / tau, sqrt(2.5 * 981 / 1) / tau}; /* 6.10521, 7.88179 Hz */
	int ok = !rc && g.n == 2 && c.derive == CP_DERIVE_FREQUENCY;
	char f1[40] = "", f2[40] = "", l0[256] = "";
	for (long p = 0; ok && p < 2; p++) {
		sb_scene s;
		const grid_run *r = run_at(&g, p);
		ok = r != NULL;
		if (ok) {
			grid_scene(&g, r, &s);
			ok = fabs(s.frequency - want[p]) < 1e-11 * want[p] && s.amplitude == 1 &&
			     fabs(s.amplitude * (tau * s.frequency) * (tau * s.frequency) / s.gravity - (p ? 2.5 : 1.5)) < 1e-10;
			snprintf(p ? f2 : f1, 40, "%.12g", s.frequency);
		}
	}
	if (!rc)
		grid_point_label(&c, 0, l0, sizeof l0);
	CHECK("study.grid.gamma.frequencies", ok && !strcmp(f1, "6.10520519167") && !strcmp(f2, "7.88178601084") && !strcmp(l0, "gamma=1.5"),
	      "%s: f %s, %s (want %.12g, %.12g), label '%s'", rc ? e.msg : "ok", f1, f2, want[0], want[1], l0);
	/* the same runs as the frequencies written out */
	snprintf(text, sizeof text, "%s[scene]\namplitude = 1\n[grid]\nfrequency = %s, %s\n", head, f1, f2);
	int rc2 = sf_expand(text, &c2, &g2, &e);
	CHECK("study.grid.gamma.same_runs", !rc && !rc2 && g.n == g2.n && g.n == 2 && !strcmp(g.runs[0].id, g2.runs[0].id) &&
	      !strcmp(g.runs[1].id, g2.runs[1].id), "ids differ (%s)", e.msg);
	if (!rc)
		sf_free(&c, &g);
	if (!rc2)
		sf_free(&c2, &g2);

	/* a set frequency: the amplitude follows, A = v / (2 pi f) */
	snprintf(text, sizeof text, "%s[scene]\nfrequency = 5\n[grid]\nvelocity = 50\n", head);
	rc = sf_expand(text, &c, &g, &e);
	sb_scene s;
	if (!rc)
		grid_scene(&g, &g.runs[0], &s);
	CHECK("study.grid.velocity.amplitude", !rc && c.derive == CP_DERIVE_AMPLITUDE && s.frequency == 5 &&
	      fabs(s.amplitude - 50 / (tau * 5)) < 1e-11, "%s: A %.17g", rc ? e.msg : "ok", rc ? 0 : s.amplitude);
	if (!rc)
		sf_free(&c, &g);
	/* both: omega = Gamma g / v, A = v / omega */
	snprintf(text, sizeof text, "%s[scene]\ngamma = 2\nvelocity = 60\n", head);
	rc = sf_expand(text, &c, &g, &e);
	if (!rc)
		grid_scene(&g, &g.runs[0], &s);
	CHECK("study.grid.gamma_velocity.both", !rc && c.derive == CP_DERIVE_BOTH &&
	      fabs(s.frequency - 2 * 981.0 / 60 / tau) < 1e-10 && fabs(s.amplitude - 60 / (2 * 981.0 / 60)) < 1e-10,
	      "%s: f %.17g A %.17g", rc ? e.msg : "ok", rc ? 0 : s.frequency, rc ? 0 : s.amplitude);
	if (!rc)
		sf_free(&c, &g);

	static const refusal bad[] = {
		{"study.grid.gamma.overdetermined", "[scene]\namplitude = 1\nfrequency = 3\n[grid]\ngamma = 1, 2\n",
		 ".campaign:8: gamma: amplitude (line 5) and frequency (line 6) are both set"},
		{"study.grid.gamma.not_positive", "[grid]\ngamma = 0, 1\n", ".campaign:5: gamma: expected a number in (0, 1000], got '0'"},
		{"study.grid.gamma.frequency_range", "[scene]\namplitude = 0.001\n[grid]\ngamma = 1, 900\n",
		 ".campaign:7: gamma: gamma = 900 at amplitude 0.001 cm needs frequency = 4729.07160651, outside (0, 1000]"},
		{"study.grid.gamma.onset", "[scene]\nradius_ratio = 2\n[grid]\ngamma = 1\n[onset]\nobservable = rise\n"
		 "from = 2\nto = 3\ntolerance = 0.1\n", ".campaign:7: gamma: an [onset] campaign searches the frequency; to "
		 "search in gamma, set axis = gamma under [onset]"},
		{"study.grid.velocity.not_positive", "[grid]\nvelocity = -1\n",
		 ".campaign:5: velocity: expected a number in (0, 1000] (cm/s), got '-1'"},
		{"study.grid.gamma_velocity.overdetermined", "[scene]\namplitude = 1\ngamma = 2\nvelocity = 60\n",
		 ".campaign:5: amplitude: gamma (line 6) and velocity (line 7) set both the amplitude and the frequency"},
		{"study.grid.gamma_velocity.frequency_range", "[scene]\ngamma = 2\nvelocity = 0.001\n",
		 ".campaign:5: gamma: gamma = 2 and velocity = 0.001 cm/s needs frequency = "},
		{"study.grid.derived.unknown_key", "[grid]\nzzqq = 1\n",
		 ".campaign:5: unknown key 'zzqq' (shake --help lists the keys; gamma, velocity and density_ratio are the campaign's)"},
	};
	refusals(head, bad, sizeof bad / sizeof *bad);
}

/* density_ratio (docs/campaigns.md, "Ratios"): each point's intruder_density is the ratio
 * times its own density, the runs those of intruder_density written out (same ids), the
 * label the ratio as written; what cannot be is refused with the line. */
static void test_ratio(void)
{
	campaign c, c2;
	grid g, g2;
	sb_err e;
	const char *head = "[campaign]\nname = r\nseed = 1\n";
	char text[1024];
	snprintf(text, sizeof text, "%s[grid]\ndensity = 1, 2.5\ndensity_ratio = 0.25, 4\n", head);
	int rc = sf_expand(text, &c, &g, &e);
	int ok = !rc && g.n == 4;
	char got[256] = "", l3[256] = "";
	for (long p = 0; ok && p < 4; p++) {
		const grid_run *r = run_at(&g, p);
		ok = r != NULL;
		if (ok) {
			sb_scene s;
			grid_scene(&g, r, &s);
			size_t l = strlen(got);
			snprintf(got + l, sizeof got - l, "%s%g/%g", p ? " " : "", s.density, s.intruder_density);
		}
	}
	if (!rc)
		grid_point_label(&c, 3, l3, sizeof l3);
	/* first axis fastest: (1, 0.25) (2.5, 0.25) (1, 4) (2.5, 4) */
	CHECK("study.grid.density_ratio.sets", ok && !strcmp(got, "1/0.25 2.5/0.625 1/4 2.5/10") &&
	      !strcmp(l3, "density=2.5 density_ratio=4"), "%s: %s, label '%s'", rc ? e.msg : "ok", got, l3);
	/* the same runs as intruder_density written out, point by point */
	static const char *const pt[4][2] = {{"1", "0.25"}, {"2.5", "0.625"}, {"1", "4"}, {"2.5", "10"}};
	int same = !rc && g.n == 4, rc2 = 0;
	for (long i = 0; same && i < 4; i++) {
		snprintf(text, sizeof text, "%s[scene]\ndensity = %s\nintruder_density = %s\n", head, pt[i][0], pt[i][1]);
		rc2 = sf_expand(text, &c2, &g2, &e);
		const grid_run *a = run_at(&g, i);
		same = !rc2 && g2.n == 1 && a && !strcmp(a->id, g2.runs[0].id);
		if (!rc2)
			sf_free(&c2, &g2);
	}
	CHECK("study.grid.density_ratio.same_runs", same, "ids differ (%s)", rc2 ? e.msg : "");
	if (!rc)
		sf_free(&c, &g);

	static const refusal bad[] = {
		{"study.grid.density_ratio.not_positive", "[grid]\ndensity_ratio = 0, 1\n",
		 ".campaign:5: density_ratio: expected a number in (0, 1000] (intruder_density over density), got '0'"},
		{"study.grid.density_ratio.too_large", "[scene]\ndensity_ratio = 2000\n",
		 ".campaign:5: density_ratio: expected a number in (0, 1000]"},
		{"study.grid.density_ratio.both", "[scene]\nintruder_density = 2\n[grid]\ndensity_ratio = 1, 2\n",
		 ".campaign:7: density_ratio: density_ratio (line 7) sets intruder_density = density_ratio x density, and "
		 "intruder_density is given too (line 5)"},
		{"study.grid.density_ratio.range", "[scene]\ndensity = 5000\n[grid]\ndensity_ratio = 1, 500\n",
		 ".campaign:7: density_ratio: density_ratio = 500 at density = 5000 g/cm^3 gives intruder_density = 2500000, "
		 "outside (0, 1e+06]"},
	};
	refusals(head, bad, sizeof bad / sizeof *bad);
}

int main(void)
{
	if (sf_init()) {
		printf("FAIL study.grid.setup: cannot make a temporary directory\n");
		return 1;
	}
	test_product();
	test_axis_values();
	test_ranges();
	test_point_duplicates();
	test_preset_explicit_wins();
	test_bounds();
	test_zip();
	test_derived();
	test_ratio();
	sf_cleanup();
	return tl_done();
}
