/* params.c - the parameter table: defaults parse, range and type errors name the
 * key and the range, format/set round-trips every value exactly, the hashes see
 * exactly the keys they should, and INI loading reports PATH:LINE: with the key. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "paircoef.h"
#include "params.h"
#include "validate.h"
#include "testlib.h"

static char tmpdir[] = "/tmp/sb_params_XXXXXX";

/* Write text to a file in tmpdir, load it into a default scene, return the error. */
static int load(const char *name, const char *text, sb_scene *sc, sb_err *e, char *path, size_t plen)
{
	snprintf(path, plen, "%s/%s", tmpdir, name);
	FILE *f = fopen(path, "w");
	if (!f)
		return -1;
	fputs(text, f);
	fclose(f);
	params_defaults(sc);
	memset(e, 0, sizeof *e);
	return params_load_file(sc, path, e);
}

static int starts_with(const char *s, const char *p) { return strncmp(s, p, strlen(p)) == 0; }

/* params_hash_nondefault: the identity of a scene is that of its non-default
 * values, so defaults contribute nothing and a value put back restores the hash. */
static void test_hash_nondefault(void)
{
	sb_scene a, b;
	params_defaults(&a);
	sb_err e = {0};
	unsigned long long h0 = params_hash_nondefault(&a, PF_PREP | PF_DYN | PF_LEN);
	CHECK("params.hash_nondefault.defaults_are_empty", h0 == 1469598103934665603ULL,
	      "hash of the defaults %llx is not the empty FNV-1a hash", h0);
	b = a;
	params_set(&b, "frequency", "2.8", "x", &e);
	unsigned long long h1 = params_hash_nondefault(&b, PF_PREP | PF_DYN | PF_LEN);
	CHECK("params.hash_nondefault.changes", h1 != h0, "frequency 2.8 did not change the hash");
	params_set(&b, "frequency", "3.2", "x", &e);
	CHECK("params.hash_nondefault.restored", params_hash_nondefault(&b, PF_PREP | PF_DYN | PF_LEN) == h0,
	      "putting the default back did not restore the hash");
	params_set(&b, "output", "elsewhere.h5", "x", &e);
	CHECK("params.hash_nondefault.ignores_out", params_hash_nondefault(&b, PF_PREP | PF_DYN | PF_LEN) == h0,
	      "an output key changed the run hash");
}

/* The presets: their names are the preset row's choices, in order; the paper preset's
 * values are the table's defaults; applying one sets its values, and a key after it
 * overrides it. */
static void test_presets(void)
{
	const sb_param *row = params_find("preset");
	char names[256] = "";
	size_t l = 0;
	for (int k = 0; PRESETS[k].name; k++)
		l += (size_t)snprintf(names + l, sizeof names - l, "%s%s", k ? "|" : "", PRESETS[k].name);
	CHECK("params.preset.names_are_choices", row && !strcmp(names, row->choices), "'%s' vs '%s'", names,
	      row ? row->choices : "?");
	sb_scene d;
	params_defaults(&d);
	int same = 1;
	for (const char *const *kv = PRESETS[0].set; *kv; kv += 2) {
		sb_scene t = d;
		sb_err e = {0};
		char a[64], b[64];
		params_set(&t, kv[0], kv[1], "test", &e);
		params_format(&t, params_find(kv[0]), a, sizeof a);
		params_format(&d, params_find(kv[0]), b, sizeof b);
		same &= !e.code && !strcmp(a, b);
	}
	CHECK("params.preset.paper_is_the_defaults", same, "the paper preset differs from the table's defaults");
	sb_scene f = d;
	sb_err e = {0};
	params_set(&f, "preset", "fast", "test", &e);
	CHECK("params.preset.fast_sets_its_values", !e.code && f.integrator == INTEG_VERLET && f.dt == 2e-4,
	      "integrator %d dt %g (%s)", f.integrator, f.dt, e.msg);
	params_set(&f, "dt", "1e-4", "test", &e);
	CHECK("params.preset.later_key_overrides", f.dt == 1e-4 && f.integrator == INTEG_VERLET, "dt %g", f.dt);
}

/* docs/model.md: the preset is applied first, keys given explicitly win wherever they
 * appear - in a scene file, on the command line, across the two; a later preset
 * replaces an earlier preset's values, never an explicit key's. */
static void test_preset_explicit_wins(void)
{
	sb_scene s;
	sb_err e;
	char path[512];
	int rc = load("pre_after.scene", "dt = 1e-5\npreset = fast\n", &s, &e, path, sizeof path);
	CHECK("params.preset.scene.explicit_before_wins", !rc && s.dt == 1e-5 && s.integrator == INTEG_VERLET,
	      "rc %d (%s): dt %g integrator %d", rc, e.msg, s.dt, s.integrator);
	rc = load("pre_before.scene", "preset = fast\ndt = 1e-5\n", &s, &e, path, sizeof path);
	CHECK("params.preset.scene.explicit_after_wins", !rc && s.dt == 1e-5 && s.integrator == INTEG_VERLET,
	      "rc %d (%s): dt %g integrator %d", rc, e.msg, s.dt, s.integrator);
	/* the preset's values say where they were set: the preset's line */
	rc = load("pre_where.scene", "\ndt = 1e-5\npreset = fast\n", &s, &e, path, sizeof path);
	char want[600];
	snprintf(want, sizeof want, "%s:3", path);
	CHECK("params.preset.scene.where", !rc && !strcmp(params_where(&s, "integrator"), want) &&
	      !strncmp(params_where(&s, "dt"), path, strlen(path)) && strstr(params_where(&s, "dt"), ":2"),
	      "integrator at %s, dt at %s", params_where(&s, "integrator"), params_where(&s, "dt"));

	params_defaults(&s);
	memset(&e, 0, sizeof e);
	rc = params_override(&s, "integrator=gear4", &e) || params_override(&s, "preset=fast", &e);
	CHECK("params.preset.cli.explicit_before_wins", !rc && s.integrator == INTEG_GEAR4 && s.dt == 2e-4,
	      "rc %d (%s): dt %g integrator %d", rc, e.msg, s.dt, s.integrator);

	/* across a scene file and the command line, both ways */
	rc = load("pre_cli.scene", "dt = 1e-5\n", &s, &e, path, sizeof path);
	rc = rc || params_override(&s, "preset=fast", &e);
	CHECK("params.preset.file_then_cli.explicit_wins", !rc && s.dt == 1e-5 && s.integrator == INTEG_VERLET,
	      "rc %d (%s): dt %g integrator %d", rc, e.msg, s.dt, s.integrator);
	rc = load("pre_cli2.scene", "preset = paper\n", &s, &e, path, sizeof path);
	rc = rc || params_override(&s, "preset=fast", &e);
	CHECK("params.preset.later_preset_replaces_preset", !rc && s.dt == 2e-4 && s.integrator == INTEG_VERLET,
	      "rc %d (%s): dt %g integrator %d", rc, e.msg, s.dt, s.integrator);
	rc = load("pre_cli3.scene", "preset = fast\n", &s, &e, path, sizeof path);
	rc = rc || params_override(&s, "dt=1e-4", &e) || params_override(&s, "preset=paper", &e);
	CHECK("params.preset.later_preset_keeps_explicit", !rc && s.dt == 1e-4 && s.integrator == INTEG_GEAR5,
	      "rc %d (%s): dt %g integrator %d", rc, e.msg, s.dt, s.integrator);
}

/* A mistyped key is answered with the nearest known one; another word is not. */
static void test_nearest(void)
{
	const char *typo[][2] = {{"frequncy", "frequency"}, {"dt_gaurd", "dt_guard"}, {"durration", "duration"},
				 {"r_mx", "r_max"}, {"max_overlpa", "max_overlap"}};
	for (size_t k = 0; k < sizeof typo / sizeof *typo; k++) {
		const char *n = params_nearest(typo[k][0]);
		char id[64];
		snprintf(id, sizeof id, "params.nearest.%s", typo[k][0]);
		CHECK(id, n && !strcmp(n, typo[k][1]), "got %s, want %s", n ? n : "(none)", typo[k][1]);
	}
	CHECK("params.nearest.no_guess_for_another_word", !params_nearest("xyz") && !params_nearest("temperature"),
	      "a suggestion for an unrelated word");
	sb_scene d;
	params_defaults(&d);
	sb_err e = {0};
	params_set(&d, "frequncy", "3", "x.scene:4", &e);
	CHECK("params.nearest.in_the_message", e.code == SB_EUSAGE && strstr(e.msg, "x.scene:4") &&
						 strstr(e.msg, "did you mean frequency?"),
	      "'%s'", e.msg);
}

/* paircoef's class names are the key rows' suffixes: setting mu_NAME, gamma_n_NAME, ...
 * by the name paircoef_name gives reaches that class's own coefficient and no other */
static void test_paircoef_names(const sb_scene *d)
{
	static const char *const COEF[] = {"mu", "gamma_n", "gamma_s", "stiffness"};
	const int KEYS[] = {PCK_MU, PCK_GAMMA_N, PCK_GAMMA_S, PCK_STIFFNESS};
	for (int c = 0; c < SB_NPAIRC; c++)
		for (int k = 0; k < 4; k++) {
			char key[64], id[100];
			snprintf(key, sizeof key, "%s_%s", COEF[k], paircoef_name(c));
			sb_err e = {0};
			sb_scene s = *d;
			const int rc = params_set(&s, key, "0.375", "x", &e);
			int others = 1;
			for (int c2 = 0; c2 < SB_NPAIRC; c2++)
				for (int k2 = 0; k2 < 4; k2++)
					if ((c2 != c || k2 != k) && paircoef_given(&s, c2, KEYS[k2]) != -1)
						others = 0;
			snprintf(id, sizeof id, "params.paircoef.%s", key);
			CHECK(id, rc == 0 && paircoef_given(&s, c, KEYS[k]) == 0.375 && others,
			      "rc %d (%s): the class's value %g, every other class's still same: %d", rc, e.msg,
			      paircoef_given(&s, c, KEYS[k]), others);
		}
}

int main(void)
{
	char id[200], buf[SB_STR_MAX + 64];
	size_t n;
	const sb_param *T = params_table(&n);
	CHECK("params.table.nonempty", n > 30, "only %zu keys", n);

	/* every default parses, and equals what params_defaults stored */
	sb_scene d, s;
	params_defaults(&d);
	for (size_t i = 0; i < n; i++) {
		sb_err e = {0};
		s = d;
		int rc = params_set(&s, T[i].name, T[i].def, "default", &e);
		snprintf(id, sizeof id, "params.default.%s.parses", T[i].name);
		CHECK(id, rc == 0 && e.code == 0, "default '%s': %s", T[i].def, e.msg);
		snprintf(id, sizeof id, "params.default.%s.applied", T[i].name);
		CHECK(id, memcmp(&s, &d, sizeof s) == 0, "setting the default changed the defaults struct");
		snprintf(id, sizeof id, "params.table.%s.find", T[i].name);
		CHECK(id, params_find(T[i].name) == &T[i], "params_find does not return the row");
	}
	CHECK("params.default.validates", ({ sb_err e = {0}; params_validate(&d, &e) == 0; }), "defaults fail params_validate");

	/* round trip: format then set gives the identical field, for the defaults and
	 * for awkward values */
	sb_scene w = d;
	w.dt = 0.1 + 0.2 - 0.3 + 3e-5; /* not a short decimal */
	w.stiffness = 3e6 * (1 + 1e-15);
	w.mu = 1.0 / 3;
	w.seed = 9007199254740992L;
	w.clip_attractive = 1;
	w.integrator = INTEG_VERLET;
	w.wall_mass = WALLMASS_INFINITE;
	w.settle = TRI_NO;
	snprintf(w.output, sizeof w.output, "dir with space/out.h5");
	const sb_scene *srcs[2] = {&d, &w};
	for (int k = 0; k < 2; k++)
		for (size_t i = 0; i < n; i++) {
			params_format(srcs[k], &T[i], buf, sizeof buf);
			sb_scene t;
			params_defaults(&t);
			memset((char *)&t + T[i].offset, 0x5a, 1); /* make sure set writes the field */
			sb_err e = {0};
			int rc = params_set(&t, T[i].name, buf, "roundtrip", &e);
			size_t sz = T[i].type == PT_STR ? SB_STR_MAX : T[i].type == PT_REAL ? sizeof(double)
				  : T[i].type == PT_INT ? sizeof(long) : sizeof(int);
			int same = T[i].type == PT_STR
					   ? strcmp((char *)&t + T[i].offset, (const char *)srcs[k] + T[i].offset) == 0
					   : memcmp((char *)&t + T[i].offset, (const char *)srcs[k] + T[i].offset, sz) == 0;
			snprintf(id, sizeof id, "params.roundtrip.%s.%s", k ? "awkward" : "default", T[i].name);
			CHECK(id, rc == 0 && same, "formatted '%s' does not set back identically: %s", buf, e.msg);
		}

	/* range errors name the key and the range */
	struct {
		const char *key, *val, *want1, *want2;
	} bad[] = {
		{"dt", "0", "dt", "(0, 0.01]"},
		{"dt", "0.02", "dt", "(0, 0.01]"},
		{"mu", "-1", "mu", "[0, 100]"},
		{"n_grains", "-5", "n_grains", "[0, 10000000]"},
		{"n_grains", "1.5", "n_grains", "integer"},
		{"settle_ke", "0", "settle_ke", "(0, inf)"},
		{"gamma_n", "abc", "gamma_n", "number"},
		{"gamma_n", "nan", "gamma_n", "number"},
		{"gamma_n", "inf", "gamma_n", "number"},
		{"gamma_n", "", "gamma_n", "number"},
		{"integrator", "gear6", "integrator", "gear5|gear4|verlet"},
		{"clip_attractive", "maybe", "clip_attractive", "yes or no"},
		{"no_such_key", "1", "no_such_key", "unknown key"},
	};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		sb_err e = {0};
		s = d;
		int rc = params_set(&s, bad[i].key, bad[i].val, "here", &e);
		snprintf(id, sizeof id, "params.set.error.%s=%s", bad[i].key, bad[i].val);
		CHECK(id, rc == SB_EUSAGE && e.code == SB_EUSAGE && starts_with(e.msg, "here: ") &&
			      strstr(e.msg, bad[i].want1) && strstr(e.msg, bad[i].want2) &&
			      memcmp(&s, &d, sizeof s) == 0,
		      "rc %d msg '%s' (want '%s' and '%s', scene unchanged)", rc, e.msg, bad[i].want1, bad[i].want2);
	}
	/* boundaries: inclusive max and min are accepted, the exclusive min is not */
	{
		sb_err e = {0};
		s = d;
		CHECK("params.set.range.inclusive_max", params_set(&s, "dt", "0.01", "x", &e) == 0 && s.dt == 0.01, "%s", e.msg);
		CHECK("params.set.range.inclusive_min", params_set(&s, "mu", "0", "x", &e) == 0 && s.mu == 0, "%s", e.msg);
		CHECK("params.set.range.int_max", params_set(&s, "n_grains", "10000000", "x", &e) == 0 && s.n_grains == 10000000, "%s", e.msg);
		CHECK("params.set.trim", params_set(&s, "mu", "  0.25 \t", "x", &e) == 0 && s.mu == 0.25, "%s", e.msg);
	}

	/* enum and bool parsing */
	{
		const char *yes[] = {"yes", "YES", "true", "On", "1"}, *no[] = {"no", "False", "off", "0"};
		int okb = 1;
		for (size_t i = 0; i < 5; i++) {
			sb_err e = {0};
			s = d;
			okb &= params_set(&s, "clip_attractive", yes[i], "x", &e) == 0 && s.clip_attractive == 1;
		}
		for (size_t i = 0; i < 4; i++) {
			sb_err e = {0};
			s.clip_attractive = 1;
			okb &= params_set(&s, "clip_attractive", no[i], "x", &e) == 0 && s.clip_attractive == 0;
		}
		CHECK("params.set.bool", okb, "a yes/no spelling was not accepted");
		sb_err e = {0};
		s = d;
		int oke = params_set(&s, "integrator", "gear4", "x", &e) == 0 && s.integrator == INTEG_GEAR4 &&
			  params_set(&s, "integrator", "verlet", "x", &e) == 0 && s.integrator == INTEG_VERLET &&
			  params_set(&s, "integrator", "gear5", "x", &e) == 0 && s.integrator == INTEG_GEAR5 &&
			  params_set(&s, "wall_mass", "infinite", "x", &e) == 0 && s.wall_mass == WALLMASS_INFINITE &&
			  params_set(&s, "settle", "no", "x", &e) == 0 && s.settle == TRI_NO;
		CHECK("params.set.enum", oke, "%s", e.msg);
		/* a prefix of a choice is not that choice */
		e = (sb_err){0};
		CHECK("params.set.enum.no_prefix", params_set(&s, "integrator", "gear", "x", &e) == SB_EUSAGE,
		      "'gear' accepted");
		e = (sb_err){0};
		CHECK("params.set.enum.no_longer", params_set(&s, "integrator", "gear55", "x", &e) == SB_EUSAGE,
		      "'gear55' accepted");
	}

	/* hashes: a PREP key changes the PREP hash, an OUT key does not */
	{
		unsigned long long h0 = params_hash(&d, PF_PREP), r0 = params_hash(&d, PF_PREP | PF_DYN | PF_LEN);
		for (size_t i = 0; i < n; i++) {
			s = d;
			sb_err e = {0};
			/* a different valid value of this key */
			const char *v = T[i].type == PT_BOOL ? (d.clip_attractive ? "no" : "yes") : NULL;
			char tmp[64];
			switch (T[i].type) {
			case PT_INT: {
				/* the default plus one, or minus one at the top of the range */
				long x = *(long *)((char *)&d + T[i].offset);
				snprintf(tmp, sizeof tmp, "%ld", (double)(x + 1) <= T[i].max ? x + 1 : x - 1);
				v = tmp;
				break;
			}
			case PT_REAL: {
				double x = *(double *)((char *)&d + T[i].offset);
				snprintf(tmp, sizeof tmp, "%.17g", x < T[i].max ? (x + T[i].max) / 2 : (x + T[i].min) / 2);
				v = tmp;
				break;
			}
			case PT_BOOL: v = *(int *)((char *)&d + T[i].offset) ? "no" : "yes"; break;
			case PT_ENUM: {
				int k = *(int *)((char *)&d + T[i].offset);
				const char *c = T[i].choices;
				const char *bar = strchr(c, '|');
				if (k == 0)
					snprintf(tmp, sizeof tmp, "%s", bar + 1);
				else
					snprintf(tmp, sizeof tmp, "%.*s", (int)(bar - c), c);
				char *b2 = strchr(tmp, '|');
				if (b2)
					*b2 = 0;
				v = tmp;
				break;
			}
			case PT_STR: v = "other-value"; break;
			}
			int rc = params_set(&s, T[i].name, v, "x", &e);
			unsigned long long h1 = params_hash(&s, PF_PREP), r1 = params_hash(&s, PF_PREP | PF_DYN | PF_LEN);
			snprintf(id, sizeof id, "params.hash.%s", T[i].name);
			int changed_prep = h1 != h0, changed_run = r1 != r0;
			int want_prep = (T[i].flags & PF_PREP) != 0, want_run = (T[i].flags & (PF_PREP | PF_DYN | PF_LEN)) != 0;
			CHECK(id, rc == 0 && memcmp(&s, &d, sizeof s) != 0 && changed_prep == want_prep && changed_run == want_run,
			      "set to '%s' (rc %d %s): PREP hash changed %d (want %d), run hash changed %d (want %d)",
			      v, rc, e.msg, changed_prep, want_prep, changed_run, want_run);
		}
	}

	/* INI files */
	if (!mkdtemp(tmpdir)) {
		CHECK("params.ini.tmpdir", 0, "mkdtemp failed");
		return tl_done();
	}
	char path[256], want[300];
	sb_scene f;
	sb_err e;
	int rc;
	rc = load("ok.ini", "# comment\n\n[scene]\nmu = 0.3\n; another comment\ndt=2.5e-5\nintegrator = verlet  \n", &f, &e, path, sizeof path);
	CHECK("params.ini.ok", rc == 0 && f.mu == 0.3 && f.dt == 2.5e-5 && f.integrator == INTEG_VERLET, "rc %d: %s", rc, e.msg);
	/* An indented key line is a key line. inih (multi-line values on by default)
	 * takes it as a continuation of the previous key's value instead: here dt would
	 * be set to "integrator = verlet" (an error naming the wrong key), and after a
	 * string key the line is silently swallowed into that string. */
	rc = load("indent.ini", "[scene]\ndt=2.5e-5\n  integrator = verlet\n", &f, &e, path, sizeof path);
	CHECK("params.ini.indented_key", rc == 0 && f.dt == 2.5e-5 && f.integrator == INTEG_VERLET, "rc %d: %s", rc, e.msg);
	rc = load("indent2.ini", "output = a.h5\n    mu = 0.3\n", &f, &e, path, sizeof path);
	CHECK("params.ini.indented_key_after_string", rc == 0 && strcmp(f.output, "a.h5") == 0 && f.mu == 0.3,
	      "rc %d '%s': output = '%s', mu = %g", rc, e.msg, f.output, f.mu);
	rc = load("top.ini", "mu = 0.2\n", &f, &e, path, sizeof path);
	CHECK("params.ini.top_level_keys", rc == 0 && f.mu == 0.2, "rc %d: %s", rc, e.msg);

	rc = load("unknown.ini", "# c\n\n[scene]\nmu = 0.3\nfrobnicate = 2\n", &f, &e, path, sizeof path);
	snprintf(want, sizeof want, "%s:5:", path);
	CHECK("params.ini.unknown_key", rc == SB_EUSAGE && starts_with(e.msg, want) && strstr(e.msg, "frobnicate"),
	      "rc %d msg '%s' (want prefix '%s' and the key)", rc, e.msg, want);

	rc = load("range.ini", "\n\n# three\n\n  \n[scene]\ndt = 1\n", &f, &e, path, sizeof path);
	snprintf(want, sizeof want, "%s:7:", path);
	CHECK("params.ini.out_of_range", rc == SB_EUSAGE && starts_with(e.msg, want) && strstr(e.msg, "dt") &&
		      strstr(e.msg, "(0, 0.01]"),
	      "rc %d msg '%s' (want prefix '%s', dt and its range)", rc, e.msg, want);

	rc = load("malformed.ini", "[scene]\nmu = 0.3\n; c\nthis line has no equals sign\ndt = 1e-5\n", &f, &e, path, sizeof path);
	snprintf(want, sizeof want, "%s:4:", path);
	CHECK("params.ini.malformed", rc == SB_EUSAGE && starts_with(e.msg, want) && strstr(e.msg, "malformed"),
	      "rc %d msg '%s' (want prefix '%s')", rc, e.msg, want);

	/* the section header itself is the mistake: its line is named, and the valid place */
	rc = load("section.ini", "mu = 0.3\n\n[shake]\ndt = 1e-5\n", &f, &e, path, sizeof path);
	snprintf(want, sizeof want, "%s:3:", path);
	CHECK("params.ini.unknown_section", rc == SB_EUSAGE && starts_with(e.msg, want) && strstr(e.msg, "shake"),
	      "rc %d msg '%s' (want prefix '%s' and the section)", rc, e.msg, want);
	CHECK("params.ini.unknown_section.names_valid", rc == SB_EUSAGE && strstr(e.msg, "[scene]"),
	      "msg '%s' does not say where keys belong", e.msg);

	/* the first error wins: a bad value before a malformed line */
	rc = load("first.ini", "mu = 200\nnot a pair\n", &f, &e, path, sizeof path);
	snprintf(want, sizeof want, "%s:1:", path);
	CHECK("params.ini.first_error_wins", rc == SB_EUSAGE && starts_with(e.msg, want) && strstr(e.msg, "mu"),
	      "rc %d msg '%s' (want prefix '%s' and mu)", rc, e.msg, want);

	rc = load("missing.ini", "", &f, &e, path, sizeof path);
	unlink(path);
	memset(&e, 0, sizeof e);
	rc = params_load_file(&f, path, &e);
	CHECK("params.ini.missing_file", rc == SB_EUSAGE && strstr(e.msg, path), "rc %d msg '%s'", rc, e.msg);

	test_preset_explicit_wins();

	/* clean up */
	const char *names[] = {"ok.ini", "top.ini", "unknown.ini", "range.ini", "malformed.ini", "section.ini", "first.ini",
			       "indent.ini", "indent2.ini", "pre_after.scene", "pre_before.scene", "pre_where.scene",
			       "pre_cli.scene", "pre_cli2.scene", "pre_cli3.scene"};
	for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
		snprintf(path, sizeof path, "%s/%s", tmpdir, names[i]);
		unlink(path);
	}
	rmdir(tmpdir);
	test_hash_nondefault();
	test_presets();
	test_nearest();
	test_paircoef_names(&d);
	return tl_done();
}
