/* campaign.c - reading a campaign file: sections, keys, axis syntax, validation. */
#include "campaign.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "num.h"
#include "axes.h"
#include "ratio.h"
#include "inifile.h"
#include "layout.h"
#include "words.h"
#include "rule/adapt.h"
#include "safe.h"
#include "stopdef.h"

/* "; did you mean KEY?" for a typo of one of the n words (the engine's rule for its
 * keys, params_nearest: at most a third of the letters, and 3, apart), else "" */
static const char *did_you_mean(const char *key, const char *const *words, size_t n, char *buf, size_t len)
{
	int best = 4, lim = (int)strlen(key) / 3;
	const char *name = NULL;
	for (size_t i = 0; i < n; i++) {
		int d = words_distance(key, words[i]);
		if (d < best && d <= (lim > 1 ? lim : 1))
			best = d, name = words[i];
	}
	if (!name)
		return "";
	snprintf(buf, len, "; did you mean %s?", name);
	return buf;
}

int campaign_key_reserved(const char *key)
{
	const sb_param *p = params_find(key);
	return p && (p->flags & PF_DRIVER);
}

int campaign_key_derived(const char *key)
{
	return drive_axis_kind(key) > AXIS_FREQUENCY || ratio_find(key);
}

static void trim(char *s)
{
	size_t lead = strspn(s, " \t");
	memmove(s, s + lead, strlen(s + lead) + 1);
	size_t l = strlen(s);
	while (l && strchr(" \t\r\n", s[l - 1]))
		s[--l] = 0;
}

/* Values are appended as they come, duplicates included; axis_dedup removes them once
 * the axis is complete. */
static int axis_add(cp_axis *a, const char *v, sb_err *e)
{
	if ((a->n & (a->n - 1)) == 0) {
		char **nv = realloc(a->values, sizeof *nv * (size_t)(a->n ? 2 * a->n : 1));
		if (!nv)
			return sb_errf(e, SB_ENOMEM, "out of memory");
		a->values = nv;
	}
	a->values[a->n] = strdup(v);
	if (!a->values[a->n])
		return sb_errf(e, SB_ENOMEM, "out of memory");
	a->n++;
	return 0;
}

struct ranked {
	const char *v;
	long at;
};

static int by_text_then_place(const void *pa, const void *pb)
{
	const struct ranked *a = pa, *b = pb;
	int c = strcmp(a->v, b->v);
	return c ? c : (a->at > b->at) - (a->at < b->at);
}

/* "2.6, 2.60" is one grid point, not two identical runs. Sorting makes this
 * O(n log n) (a range can give 10^5 values); the first occurrence of each value stays,
 * in file order, which is the order `study expand` and the database show. */
static int axis_dedup(cp_axis *a, sb_err *e)
{
	if (a->n < 2)
		return 0;
	struct ranked *r = malloc(sizeof *r * (size_t)a->n);
	if (!r)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	for (long i = 0; i < a->n; i++)
		r[i] = (struct ranked){a->values[i], i};
	qsort(r, (size_t)a->n, sizeof *r, by_text_then_place);
	/* marked first, freed after: r[i - 1].v must live for the next comparison */
	for (long i = 1; i < a->n; i++)
		if (!strcmp(r[i].v, r[i - 1].v))
			a->values[r[i].at] = NULL;
	long w = 0;
	for (long i = 0; i < a->n; i++)
		if (!a->values[r[i].at])
			free((char *)r[i].v);
	for (long i = 0; i < a->n; i++)
		if (a->values[i])
			a->values[w++] = a->values[i];
	free(r);
	a->n = w;
	return 0;
}

/* Check one value with the engine's own parser and keep its canonical text, so that
 * "2.60" and "2.6" are the same value and the run id does not depend on spelling.
 * `scratch` is a scene at the defaults: only the value's own key is set and read. */
static int parse_num(const char *t, double *x);

/* The highest Gamma or v a campaign may ask for: the engine's frequency range (Hz) in
 * the same number, well past any bed's onset */
#define CP_DERIVED_MAX 1000

static int value_add(cp_axis *a, sb_scene *scratch, const char *v, const char *where, sb_err *e)
{
	const sb_ratio *ra = ratio_find(a->key);
	if (ra) {
		/* a ratio (ratio.h): a positive number, printed as a range's values are */
		double x;
		char buf[40];
		if (!parse_num(v, &x) || !(x > 0 && x <= ra->max))
			return sb_errf(e, SB_EUSAGE, "%s: %s: expected a number in (0, %g] (%s over %s), got '%s'", where, a->key,
				       ra->max, ra->sets, ra->base, v);
		snprintf(buf, sizeof buf, "%.12g", x);
		return axis_add(a, buf, e);
	}
	if (campaign_key_derived(a->key)) {
		/* Gamma or v: a positive number, printed as a range's values are */
		double x;
		char buf[40];
		const char *unit = drive_axis_unit(drive_axis_kind(a->key));
		if (!parse_num(v, &x) || !(x > 0 && x <= CP_DERIVED_MAX))
			return sb_errf(e, SB_EUSAGE, "%s: %s: expected a number in (0, %d]%s%s%s, got '%s'", where, a->key,
				       CP_DERIVED_MAX, *unit ? " (" : "", unit, *unit ? ")" : "", v);
		snprintf(buf, sizeof buf, "%.12g", x);
		return axis_add(a, buf, e);
	}
	if (params_set(scratch, a->key, v, where, e))
		return e->code;
	const sb_param *p = params_find(a->key);
	if (p->type == PT_STR && *v && !safe_path_value(v))
		return sb_errf(e, SB_EUSAGE, "%s: %s: '%s' " SAFE_PATH_RULE, where, a->key, v);
	char buf[SB_STR_MAX + 8];
	params_format(scratch, p, buf, sizeof buf);
	return axis_add(a, buf, e);
}

/* Room for k more values in the axis (duplicates count: they cost as much to make);
 * `count` is k as text, exact for integer ranges. */
static int axis_room(const cp_axis *a, double k, const char *count, const char *item, const char *where,
		     sb_err *e)
{
	if (k <= (double)(CP_MAX_VALUES - a->n))
		return 0;
	if (a->n)
		return sb_errf(e, SB_EUSAGE, "%s: %s: '%s' takes the axis past %d values (%ld before it)", where,
			       a->key, item, CP_MAX_VALUES, a->n);
	return sb_errf(e, SB_EUSAGE, "%s: %s: range '%s' has %s values, more than %d in one axis", where, a->key,
		       item, count, CP_MAX_VALUES);
}

/* t without the blanks around it (a range's "2.5 : 3.2"): *n bytes from the return */
static const char *unblank(const char *t, size_t *n)
{
	t += strspn(t, " \t");
	*n = strlen(t);
	while (*n && (t[*n - 1] == ' ' || t[*n - 1] == '\t'))
		--*n;
	return t;
}

/* Numbers as every input reads them (core/text/num.h: decimal, no hex, no inf or nan). */
static int parse_num(const char *t, double *x)
{
	size_t n;
	t = unblank(t, &n);
	return !num_real_n(t, n, x);
}

static int parse_long(const char *t, long *x)
{
	size_t n;
	long long v;
	t = unblank(t, &n);
	if (num_int_n(t, n, &v) || v < LONG_MIN || v > LONG_MAX)
		return 0;
	*x = (long)v;
	return 1;
}

/* START:STOP:STEP, endpoint included. Value k is START + k STEP printed with 12
 * significant digits and parsed again: 2.5 + 14 * 0.05 = 3.2000000000000002 becomes
 * "3.2", so a range gives the same values (and run ids) as the written-out list. */
static int float_range(cp_axis *a, sb_scene *scratch, char *item, const char *where, sb_err *e)
{
	char *c1 = strchr(item, ':'), *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
	double lo, hi, step;
	if (!c1 || !c2 || strchr(c2 + 1, ':'))
		return sb_errf(e, SB_EUSAGE, "%s: %s: bad range '%s' (expected START:STOP:STEP)", where, a->key, item);
	*c1 = *c2 = 0;
	if (!parse_num(item, &lo) || !parse_num(c1 + 1, &hi) || !parse_num(c2 + 1, &step)) {
		*c1 = *c2 = ':';
		return sb_errf(e, SB_EUSAGE, "%s: %s: bad range '%s' (START:STOP:STEP must be numbers)", where, a->key, item);
	}
	*c1 = *c2 = ':';
	if (!(step > 0) || hi < lo)
		return sb_errf(e, SB_EUSAGE, "%s: %s: bad range '%s' (needs STEP > 0 and STOP >= START)", where, a->key, item);
	/* STOP - START overflows to inf for ends near +-DBL_MAX, and a subnormal STEP
	 * overflows the quotient: both give an inf count, which axis_room refuses like any
	 * other count past the limit; the tolerance keeps the endpoint when
	 * (STOP - START) / STEP lands a hair below an integer (0.7 / 0.05 = 13.999999999999998) */
	double count = floor((hi - lo) / step + 1e-9) + 1;
	char ct[32];
	if (!isfinite(count))
		snprintf(ct, sizeof ct, "too many");
	else
		snprintf(ct, sizeof ct, count < 1e15 ? "%.0f" : "%.3g", count);
	if (axis_room(a, count, ct, item, where, e))
		return e->code;
	double prev = NAN;
	for (long k = 0; k < (long)count; k++) {
		char buf[64];
		snprintf(buf, sizeof buf, "%.12g", lo + (double)k * step);
		/* beyond 12 digits a value would read as another: one outside the range
		 * (1.0000000000001 is "1"), or the one before it again */
		double v = strtod(buf, NULL);
		if (v < lo || v > hi || v == prev)
			return sb_errf(e, SB_EUSAGE, "%s: %s: range '%s': value %ld, %.17g, reads as %s, %s, with the 12 "
				       "significant digits a range's values keep (so that they are the written-out list's); "
				       "write the values as a list", where, a->key, item, k + 1, lo + (double)k * step, buf,
				       v == prev ? "the one before it" : "outside the range");
		prev = v;
		if (value_add(a, scratch, buf, where, e))
			return e->code;
	}
	return 0;
}

static int int_range(cp_axis *a, sb_scene *scratch, char *item, char *dots, const char *where, sb_err *e)
{
	long lo, hi;
	*dots = 0;
	int okn = parse_long(item, &lo) && parse_long(dots + 2, &hi);
	*dots = '.';
	if (!okn || hi < lo)
		return sb_errf(e, SB_EUSAGE, "%s: %s: bad range '%s' (expected FIRST..LAST, integers, FIRST <= LAST)",
			       where, a->key, item);
	/* hi - lo overflows a long for -1..2^63-1; the unsigned difference does not */
	unsigned long span = (unsigned long)hi - (unsigned long)lo;
	double count = (double)span + 1;
	char ct[32];
	if (span == ULONG_MAX)
		snprintf(ct, sizeof ct, "%lu + 1", span);
	else
		snprintf(ct, sizeof ct, "%lu", span + 1);
	if (axis_room(a, count, ct, item, where, e))
		return e->code;
	/* counting, not k <= hi: k++ past LONG_MAX would overflow */
	long k = lo;
	for (long i = 0; i < (long)count; i++, k += k < hi) {
		char buf[32];
		snprintf(buf, sizeof buf, "%ld", k);
		if (value_add(a, scratch, buf, where, e))
			return e->code;
	}
	return 0;
}

int campaign_axis_parse(cp_axis *a, const char *key, const char *text, const char *where, sb_err *e)
{
	memset(a, 0, sizeof *a);
	snprintf(a->key, sizeof a->key, "%s", key);
	char *copy = strdup(text);
	if (!copy)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	/* an empty item ("15," or "2,,3") is a value left out, not nothing: refused rather
	 * than dropped (strtok_r below skips them) */
	int nitem = 1;
	for (const char *s = text, *c; ; s = c + 1, nitem++) {
		c = strchr(s, ',');
		const char *end = c ? c : s + strlen(s);
		while (s < end && (*s == ' ' || *s == '\t'))
			s++;
		if (s == end && (c || nitem > 1)) {
			free(copy);
			return sb_errf(e, SB_EUSAGE, "%s: %s: item %d of '%s' is empty (a comma with no value %s it)", where, key,
				       nitem, text, c ? "before" : "after");
		}
		if (!c)
			break;
	}
	sb_scene scratch;
	params_defaults(&scratch);
	char *save = NULL;
	int any = 0, rc = 0;
	for (char *item = strtok_r(copy, ",", &save); item && !rc; item = strtok_r(NULL, ",", &save)) {
		trim(item);
		if (!*item)
			continue;
		any = 1;
		const sb_param *p = params_find(key);
		char *dots = strstr(item, "..");
		if (((p && (p->type == PT_INT || p->type == PT_REAL)) || campaign_key_derived(key)) && strchr(item, ':'))
			rc = float_range(a, &scratch, item, where, e);
		else if (p && p->type == PT_INT && dots)
			rc = int_range(a, &scratch, item, dots, where, e);
		else if (!axis_room(a, 1, "1", item, where, e))
			rc = value_add(a, &scratch, item, where, e);
		else
			rc = e->code;
	}
	free(copy);
	if (!rc && !any)
		rc = sb_errf(e, SB_EUSAGE, "%s: %s: no values", where, key);
	a->given = a->n;
	if (!rc)
		rc = axis_dedup(a, e);
	return rc;
}

int campaign_points(const campaign *c, long *points, sb_err *e)
{
	long limit = c->max_runs ? c->max_runs : CP_MAX_RUNS_DEFAULT;
	long total = 1;
	int past = -1; /* the axis that takes the product past the limit */
	int over = 0;  /* the product does not fit a long */
	for (int a = 0; a < c->naxes; a++) {
		long n = c->axes[a].n;
		if (n < 1 || c->axes[a].zipped_to)
			continue;
		if (!over && total > LONG_MAX / n)
			over = 1;
		else if (!over)
			total *= n;
		if (past < 0 && (over || total > limit))
			past = a;
	}
	*points = over ? LONG_MAX : total;
	if (past < 0)
		return 0;
	char sizes[400] = "";
	size_t l = 0;
	for (int a = 0; a < c->naxes && l < sizeof sizes; a++)
		if (!c->axes[a].zipped_to)
			l += (size_t)snprintf(sizes + l, sizeof sizes - l, "%s%s %ld", l ? " x " : "", c->axes[a].key,
					      c->axes[a].n);
	if (l >= sizeof sizes)
		memcpy(sizes + sizeof sizes - 4, "...", 4);
	const cp_axis *ax = &c->axes[past];
	/* the replicates shorthand is the seed axis: name the key the file wrote */
	int rep = c->replicates && ax->line == c->replicates_line && !strcmp(ax->key, "seed");
	char count[64], now[160], fix[160];
	if (over)
		snprintf(count, sizeof count, "more than %ld", LONG_MAX);
	else
		snprintf(count, sizeof count, "%ld", total);
	if (c->max_runs)
		snprintf(now, sizeof now, "max_runs = %ld (line %d)", limit, c->max_runs_line);
	else
		snprintf(now, sizeof now, "the limit of %ld", limit);
	if (over || total > CP_MAX_RUNS_LIMIT)
		snprintf(fix, sizeof fix, "max_runs under [campaign] raises the limit to at most %d: "
			 "split the campaign or drop values", CP_MAX_RUNS_LIMIT);
	else if (c->max_runs)
		snprintf(fix, sizeof fix, "raise max_runs to %ld under [campaign] to allow them", total);
	else
		snprintf(fix, sizeof fix, "add max_runs = %ld under [campaign] to allow them", total);
	return sb_errf(e, SB_EUSAGE, "%s:%d: %s: the grid has %s points (%s), more than %s; %s", c->path,
		       ax->line, rep ? "replicates" : ax->key, count, sizes, now, fix);
}

/* ---- the file's sections and keys (core/text/inifile.c reads its lines) ---- */

#define CP_MAX_LINES 100000

enum { SEC_NONE, SEC_CAMPAIGN, SEC_SCENE, SEC_GRID, SEC_ONSET, SEC_N };

struct rd {
	campaign *c;
	sb_err *e;
	int line, err_line, section;
	int seen_name, seen_seed;
	int sec_line[SEC_N];
	char ckey[16][16];    /* [campaign] keys seen, with their lines */
	int ckey_line[16], nckey;
};

/* A [section] line (core/text/inifile.c reads the lines): the four sections, each once. */
static int cp_section(void *user, const char *header, const char *name, int len, int line, sb_err *e)
{
	struct rd *r = user;
	int sec = -1;
	r->line = line;
	if (len == 8 && !strncmp(name, "campaign", 8))
		sec = SEC_CAMPAIGN;
	else if (len == 5 && !strncmp(name, "scene", 5))
		sec = SEC_SCENE;
	else if (len == 4 && !strncmp(name, "grid", 4))
		sec = SEC_GRID;
	else if (len == 5 && !strncmp(name, "onset", 5))
		sec = SEC_ONSET;
	if (sec < 0)
		return sb_errf(e, SB_EUSAGE, "%s:%d: unknown section '%s' (expected [campaign], [scene], [grid] or [onset])",
			       r->c->path, line, header);
	if (r->sec_line[sec])
		return sb_errf(e, SB_EUSAGE, "%s:%d: section [%.*s] repeated (first on line %d)", r->c->path, line, len,
			       name, r->sec_line[sec]);
	r->sec_line[sec] = line;
	r->section = sec;
	if (sec == SEC_ONSET)
		r->c->onset.line = line;
	return 0;
}

/* Whether the product of the axes' sizes exceeds limit (without overflowing). */
static int product_past(const campaign *c, long limit)
{
	long total = 1;
	for (int a = 0; a < c->naxes; a++) {
		if (c->axes[a].n < 1)
			continue;
		if (c->axes[a].n > limit / total)
			return 1;
		total *= c->axes[a].n;
	}
	return 0;
}

static int seen_key(const campaign *c, const char *key)
{
	for (int i = 0; i < c->nfixed; i++)
		if (!strcmp(c->fixed[i].key, key))
			return c->fixed[i].line;
	for (int i = 0; i < c->naxes; i++)
		if (!strcmp(c->axes[i].key, key))
			return c->axes[i].line;
	return 0;
}

static int campaign_key(struct rd *r, const char *where, const char *name, const char *value)
{
	campaign *c = r->c;
	sb_err *e = r->e;
	/* like a scene key, each [campaign] key once: a second name = would silently win */
	for (int i = 0; i < r->nckey; i++)
		if (!strcmp(r->ckey[i], name))
			return sb_errf(e, SB_EUSAGE, "%s: %s: given twice (first on line %d)", where, name, r->ckey_line[i]);
	if (r->nckey < 16 && strlen(name) < sizeof r->ckey[0]) {
		snprintf(r->ckey[r->nckey], sizeof r->ckey[0], "%s", name);
		r->ckey_line[r->nckey++] = r->line;
	}
	if (!strcmp(name, "name")) {
		if (!safe_name(value))
			return sb_errf(e, SB_EUSAGE, "%s: name: '%s' is not a valid campaign name "
				       "(1-64 of [A-Za-z0-9_.-], not starting with '.' or '-')", where, value);
		/* RUNS/NAME is the campaign's directory: it must not be the database or a
		 * file beside it (docs/driver.md, "Safety") */
		if (layout_reserved(value, NULL))
			return sb_errf(e, SB_EUSAGE, "%s: name: '%s' is a name of the runs directory's own files (the "
				       "database study.db and the files beside it: -journal, -wal, -shm, .NAME.lock); "
				       "choose a name that does not begin with 'study.db'", where, value);
		snprintf(c->name, sizeof c->name, "%s", value);
		c->name_line = r->line;
		r->seen_name = 1;
	} else if (!strcmp(name, "description")) {
		snprintf(c->description, sizeof c->description, "%s", value);
	} else if (!strcmp(name, "scene")) {
		if (!*value)
			return sb_errf(e, SB_EUSAGE, "%s: scene: empty file name", where);
		/* relative to the campaign file, so a campaign runs from any directory */
		const char *slash = strrchr(c->path, '/');
		if (value[0] == '/' || !slash)
			snprintf(c->scene_file, sizeof c->scene_file, "%s", value);
		else
			snprintf(c->scene_file, sizeof c->scene_file, "%.*s/%s", (int)(slash - c->path), c->path, value);
		sb_err tmp = {0};
		if (params_load_file(&c->base, c->scene_file, &tmp))
			return sb_errf(e, SB_EUSAGE, "%s: scene: %s", where, tmp.msg);
		/* the base scene's strings reach the engine's command line like the
		 * campaign's own: the same rule, named where the scene file set them */
		size_t np;
		const sb_param *t = params_table(&np);
		for (size_t i = 0; i < np; i++) {
			const char *v = (const char *)&c->base + t[i].offset;
			if (t[i].type == PT_STR && !campaign_key_reserved(t[i].name) && *v && !safe_path_value(v))
				return sb_errf(e, SB_EUSAGE, "%s: %s: '%s' " SAFE_PATH_RULE " (scene = %s, %s)",
					       params_where(&c->base, t[i].name), t[i].name, v, value, where);
		}
	} else if (!strcmp(name, "seed")) {
		/* digits only (an unsigned 64-bit seed: past num_int's range) */
		char *end;
		errno = 0;
		unsigned long long s = strtoull(value, &end, 10);
		if (!*value || *end || errno || value[strspn(value, "0123456789")])
			return sb_errf(e, SB_EUSAGE, "%s: seed: expected a non-negative integer, got '%s'", where, value);
		c->seed = s;
		r->seen_seed = 1;
	} else if (!strcmp(name, "seeds")) {
		if (!strcmp(value, "derived"))
			c->seeds = CP_SEEDS_DERIVED;
		else if (!strcmp(value, "literal"))
			c->seeds = CP_SEEDS_LITERAL;
		else
			return sb_errf(e, SB_EUSAGE, "%s: seeds: expected one of derived|literal, got '%s'", where, value);
	} else if (!strcmp(name, "replicates") && !strcmp(value, "auto")) {
		c->autorep.on = 1;
		c->replicates_line = r->line;
	} else if (!strcmp(name, "result")) {
		static const char *const names[] = {"median_wait", "rise_fraction", "mean_flux"};
		int k = -1;
		for (int i = 0; i < 3; i++)
			if (!strcmp(value, names[i]))
				k = i;
		if (k < 0)
			return sb_errf(e, SB_EUSAGE, "%s: result: expected one of median_wait|rise_fraction|mean_flux, "
				       "got '%s'", where, value);
		c->autorep.result = k;
		c->autorep.result_line = r->line;
	} else if (!strcmp(name, "target") || !strcmp(name, "level")) {
		int tg = name[0] == 't';
		double x;
		/* a width in the result's unit (s, a fraction, particles/period); a level
		 * above 0.999 would need more replicates than a campaign runs */
		if (!parse_num(value, &x) || (tg ? !(x > 0 && x <= 1e9) : !(x >= 0.5 && x <= 0.999)))
			return sb_errf(e, SB_EUSAGE, "%s: %s: expected a number in %s, got '%s'", where, name,
				       tg ? "(0, 1e+09]" : "[0.5, 0.999]", value);
		*(tg ? &c->autorep.target : &c->autorep.level) = x;
		*(tg ? &c->autorep.target_line : &c->autorep.level_line) = r->line;
	} else if (!strcmp(name, "batch") || !strcmp(name, "max_replicates")) {
		int b = name[0] == 'b';
		long n;
		if (!parse_long(value, &n) || n < 1 || n > AD_MAX_REPLICATES)
			return sb_errf(e, SB_EUSAGE, "%s: %s: expected an integer in [1, %d], got '%s'", where, name,
				       AD_MAX_REPLICATES, value);
		*(b ? &c->autorep.batch : &c->autorep.max_replicates) = n;
		*(b ? &c->autorep.batch_line : &c->autorep.max_line) = r->line;
	} else if (!strcmp(name, "replicates")) {
		long n;
		if (!parse_long(value, &n) || n < 1 || n > CP_MAX_VALUES)
			return sb_errf(e, SB_EUSAGE, "%s: replicates: expected auto or an integer in [1, %d], got '%s'",
				       where, CP_MAX_VALUES, value);
		c->replicates = n;
		c->replicates_line = r->line;
	} else if (!strcmp(name, "zip")) {
		if (strlen(value) >= sizeof c->zip)
			return sb_errf(e, SB_EUSAGE, "%s: zip: at most %zu characters", where, sizeof c->zip - 1);
		snprintf(c->zip, sizeof c->zip, "%s", value);
		c->zip_line = r->line;
	} else if (!strcmp(name, "max_runs")) {
		long n;
		if (!parse_long(value, &n) || n < 1 || n > CP_MAX_RUNS_LIMIT)
			return sb_errf(e, SB_EUSAGE, "%s: max_runs: expected an integer in [1, %d], got '%s'", where,
				       CP_MAX_RUNS_LIMIT, value);
		c->max_runs = n;
		c->max_runs_line = r->line;
	} else {
		static const char *const keys[] = {"name", "description", "scene", "seed", "seeds", "replicates",
						   "max_runs", "zip", "result", "target", "batch", "max_replicates",
						   "level"};
		char dym[96];
		return sb_errf(e, SB_EUSAGE, "%s: unknown key '%s' in [campaign]%s "
			       "(name, description, scene, seed, seeds, replicates, max_runs, zip; with replicates = auto: "
			       "result, target, batch, max_replicates, level)", where, name,
			       did_you_mean(name, keys, sizeof keys / sizeof *keys, dym, sizeof dym));
	}
	return 0;
}

/* ---- [onset]: one table of its keys drives the parser, the range checks and the
 * messages ---- */

enum { OK_OBS, OK_AXIS, OK_FREQ, OK_REAL, OK_BAND, OK_REPS, OK_INT };

static const struct onset_keydef {
	const char *name;
	int kind;
	double min, max;       /* OK_REAL, OK_INT, OK_REPS; OK_FREQ: the frequency key's (Gamma and v
				* in the same range) */
	int min_open, max_open;
	size_t val, line;      /* offsets in cp_onset: the value (double or long) and its line */
} ONSET_KEYS[] = {
	{"observable", OK_OBS, 0, 0, 0, 0, offsetof(cp_onset, observable), offsetof(cp_onset, observable_line)},
	{"from", OK_FREQ, 0, 0, 1, 0, offsetof(cp_onset, from), offsetof(cp_onset, from_line)},
	{"to", OK_FREQ, 0, 0, 1, 0, offsetof(cp_onset, to), offsetof(cp_onset, to_line)},
	{"tolerance", OK_REAL, 0, 1000, 1, 0, offsetof(cp_onset, tolerance), offsetof(cp_onset, tolerance_line)},
	{"threshold", OK_REAL, 0, 1e6, 0, 0, offsetof(cp_onset, threshold), offsetof(cp_onset, threshold_line)},
	{"band", OK_BAND, 0, 1, 0, 0, offsetof(cp_onset, band_lo), offsetof(cp_onset, band_line)},
	{"skip", OK_REAL, 0, 1, 0, 1, offsetof(cp_onset, skip), offsetof(cp_onset, skip_line)},
	{"replicates", OK_REPS, 1, AD_MAX_REPLICATES, 0, 0, offsetof(cp_onset, replicates),
	 offsetof(cp_onset, replicates_line)},
	{"max_replicates", OK_INT, 1, AD_MAX_REPLICATES, 0, 0, offsetof(cp_onset, max_replicates),
	 offsetof(cp_onset, max_line)},
	{"batch", OK_INT, 1, AD_MAX_REPLICATES, 0, 0, offsetof(cp_onset, batch), offsetof(cp_onset, batch_line)},
	{"target", OK_REAL, 0, 1000, 1, 0, offsetof(cp_onset, target), offsetof(cp_onset, target_line)},
	/* at most 0.999: an interval of the median at 0.999 needs 11 replicates */
	{"level", OK_REAL, 0.5, 0.999, 0, 0, offsetof(cp_onset, level), offsetof(cp_onset, level_line)},
	/* what from, to, tolerance and target are in */
	{"axis", OK_AXIS, 0, 0, 0, 0, offsetof(cp_onset, axis), offsetof(cp_onset, axis_line)},
};
#define N_ONSET_KEYS (sizeof ONSET_KEYS / sizeof *ONSET_KEYS)

static const struct onset_keydef *onset_keydef(const char *name)
{
	for (size_t i = 0; i < N_ONSET_KEYS; i++)
		if (!strcmp(ONSET_KEYS[i].name, name))
			return &ONSET_KEYS[i];
	return NULL;
}

static int *onset_line(cp_onset *o, const char *name)
{
	return (int *)((char *)o + onset_keydef(name)->line);
}

/* "(0, 1000]" */
static void range_text(double lo, double hi, int lo_open, int hi_open, char *buf, size_t len)
{
	snprintf(buf, len, "%c%g, %g%c", lo_open ? '(' : '[', lo, hi, hi_open ? ')' : ']');
}

static int in_range(double x, double lo, double hi, int lo_open, int hi_open)
{
	return (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
}

/* the unit of a key in the search's axis ("Hz"), "" for Gamma (which has none) and
 * for the keys in no axis */
static const char *onset_unit(const cp_onset *o, const struct onset_keydef *k)
{
	int in_axis = k->kind == OK_FREQ || !strcmp(k->name, "tolerance") || !strcmp(k->name, "target");
	return in_axis ? drive_axis_unit(o->axis) : "";
}

static int onset_key(cp_onset *o, int line, const char *where, const char *name, const char *value, sb_err *e)
{
	const struct onset_keydef *k = onset_keydef(name);
	if (!k) {
		char keys[400], dym[96];
		const char *names[N_ONSET_KEYS];
		size_t l = 0;
		for (size_t i = 0; i < N_ONSET_KEYS; i++) {
			names[i] = ONSET_KEYS[i].name;
			l += (size_t)snprintf(keys + l, sizeof keys - l, "%s%s", i ? ", " : "", ONSET_KEYS[i].name);
		}
		return sb_errf(e, SB_EUSAGE, "%s: unknown key '%s' in [onset]%s (%s)", where, name,
			       did_you_mean(name, names, N_ONSET_KEYS, dym, sizeof dym), keys);
	}
	int *at = (int *)((char *)o + k->line);
	if (*at)
		return sb_errf(e, SB_EUSAGE, "%s: %s: given twice (first on line %d)", where, name, *at);
	*at = line;
	double *dv = (double *)((char *)o + k->val);
	long *lv = (long *)((char *)o + k->val);
	double lo = k->min, hi = k->max, x;
	long n;
	char rt[96];
	switch (k->kind) {
	case OK_OBS:
		if (!strcmp(value, "rise"))
			o->observable = CP_OBS_RISE;
		else if (!strcmp(value, "flux"))
			o->observable = CP_OBS_FLUX;
		else
			return sb_errf(e, SB_EUSAGE, "%s: observable: expected one of rise|flux, got '%s'", where, value);
		return 0;
	case OK_AXIS:
		/* what the range is in: each group's frequency follows from its amplitude */
		o->axis = drive_axis_kind(value);
		if (o->axis < 0)
			return sb_errf(e, SB_EUSAGE, "%s: axis: expected one of frequency|gamma|velocity, got '%s'", where,
				       value);
		return 0;
	case OK_BAND: {
		/* LO:HI, fractions of the settled surface height */
		const char *c = strchr(value, ':');
		char a[64];
		double b0, b1;
		snprintf(a, sizeof a, "%.*s", c ? (int)(c - value) : 0, value);
		if (!c || strlen(value) > 60 || !parse_num(a, &b0) || !parse_num(c + 1, &b1) || !(b0 >= 0) ||
		    !(b1 <= 1) || !(b0 < b1))
			return sb_errf(e, SB_EUSAGE, "%s: band: expected LO:HI with 0 <= LO < HI <= 1 "
				       "(fractions of the settled surface height), got '%s'", where, value);
		dv[0] = b0;
		o->band_hi = b1;
		return 0;
	}
	case OK_REPS:
		if (!strcmp(value, "auto")) {
			o->autorep = 1;
			return 0;
		}
		if (!parse_long(value, &n) || n < (long)lo || n > (long)hi)
			return sb_errf(e, SB_EUSAGE, "%s: replicates: expected auto or an integer in [%.0f, %.0f], got '%s'",
				       where, lo, hi, value);
		*lv = n;
		return 0;
	case OK_INT:
		if (!parse_long(value, &n) || n < (long)lo || n > (long)hi)
			return sb_errf(e, SB_EUSAGE, "%s: %s: expected an integer in [%.0f, %.0f], got '%s'", where, name, lo,
				       hi, value);
		*lv = n;
		return 0;
	case OK_FREQ: {
		/* the engine's own range of the frequency key, without its 0 (no shaking) */
		const sb_param *f = params_find("frequency");
		lo = f->min;
		hi = f->max;
	}
		/* fall through */
	default:
		range_text(lo, hi, k->min_open, k->max_open, rt, sizeof rt);
		if (!parse_num(value, &x) || !in_range(x, lo, hi, k->min_open, k->max_open)) {
			const char *u = onset_unit(o, k);
			return sb_errf(e, SB_EUSAGE, "%s: %s: expected a number in %s%s%s%s%s%s, got '%s'", where, name,
				       rt, *u ? " (" : "", u, *u ? ")" : "", o->axis_line ? " with axis = " : "",
				       o->axis_line ? drive_axis_name(o->axis) : "", value);
		}
		*dv = x;
		return 0;
	}
}

/* The [onset] section as a whole, and what it excludes elsewhere in the file. */
static int onset_finish(campaign *c, int campaign_replicates_line, sb_err *e)
{
	cp_onset *o = &c->onset;
	const char *p = c->path;
	const char *need[] = {"observable", "from", "to", "tolerance"};
	for (size_t i = 0; i < sizeof need / sizeof *need; i++)
		if (!*onset_line(o, need[i]))
			return sb_errf(e, SB_EUSAGE, "%s:%d: [onset] has no %s%s", p, o->line, need[i],
				       i ? "" : " (rise or flux)");
	const char *ax = drive_axis_name(o->axis), *unit = drive_axis_unit(o->axis);
	if (!(o->to > o->from))
		return sb_errf(e, SB_EUSAGE, "%s:%d: to: expected a %s above from = %g (line %d), got %g", p,
			       o->to_line, ax, o->from, o->from_line, o->to);
	/* at most AD_MAX_LEVELS halvings of the range; a bracket as wide as the range is
	 * no search */
	double w = o->to - o->from, tmin = ldexp(w, -AD_MAX_LEVELS);
	if (o->tolerance < tmin || o->tolerance >= w)
		return sb_errf(e, SB_EUSAGE, "%s:%d: tolerance: expected a width in [%.3g, %g)%s%s (from %g to %g in at "
			       "most %d halvings), got %g", p, o->tolerance_line, tmin, w, *unit ? " " : "", unit, o->from,
			       o->to, AD_MAX_LEVELS, o->tolerance);
	if (o->observable == CP_OBS_FLUX && !o->threshold_line)
		return sb_errf(e, SB_EUSAGE, "%s:%d: [onset] has no threshold (observable = flux: a run is on when "
			       "its mean flux through the band is at least threshold particles per period)", p, o->line);
	if (o->observable == CP_OBS_RISE) {
		const char *flux_only[] = {"threshold", "band", "skip"};
		for (size_t i = 0; i < 3; i++)
			if (*onset_line(o, flux_only[i]))
				return sb_errf(e, SB_EUSAGE, "%s:%d: %s: only for observable = flux (a run's rise is the "
					       "engine's risen)", p, *onset_line(o, flux_only[i]), flux_only[i]);
	}
	if (!o->replicates_line)
		o->autorep = 1;
	if (!o->autorep) {
		const char *auto_only[] = {"max_replicates", "batch", "target"};
		for (size_t i = 0; i < 3; i++)
			if (*onset_line(o, auto_only[i]))
				return sb_errf(e, SB_EUSAGE, "%s:%d: %s: only with replicates = auto (line %d says %ld)", p,
					       *onset_line(o, auto_only[i]), auto_only[i], o->replicates_line, o->replicates);
	}
	if (!o->band_line) {
		o->band_lo = 0.4;
		o->band_hi = 0.6;
	}
	if (!o->skip_line)
		o->skip = 0.2;
	if (!o->level_line)
		o->level = 0.95;
	if (!o->batch_line)
		o->batch = 4;
	if (!o->max_line)
		o->max_replicates = 32;
	if (!o->target_line)
		o->target = o->tolerance;
	long nmin = adapt_min_replicates(o->level);
	if (o->autorep && o->max_replicates < nmin)
		return sb_errf(e, SB_EUSAGE, "%s:%d: max_replicates: at least %ld replicates are needed for an "
			       "interval of the onset at level %g, got %ld", p, o->max_line ? o->max_line : o->line, nmin,
			       o->level, o->max_replicates);
	/* the search owns the frequency and the replicates */
	if (campaign_replicates_line)
		return sb_errf(e, SB_EUSAGE, "%s:%d: replicates: an [onset] campaign sets its replicates under [onset] "
			       "(replicates = auto | N)", p, campaign_replicates_line);
	int l;
	if ((l = seen_key(c, "frequency")))
		return sb_errf(e, SB_EUSAGE, "%s:%d: frequency: chosen by the [onset] search (%s%sfrom %g to %g, line %d); "
			       "remove it", p, l, o->axis ? ax : "", o->axis ? " " : "", o->from, o->to, o->line);
	if ((l = seen_key(c, "seed")))
		return sb_errf(e, SB_EUSAGE, "%s:%d: seed: the [onset] search numbers its replicates 1, 2, ...; remove "
			       "it", p, l);
	return 0;
}

/* replicates = auto on a grid: its keys as a whole, and what it excludes. */
static int autorep_finish(campaign *c, sb_err *e)
{
	cp_auto *a = &c->autorep;
	const char *p = c->path;
	const char *names[] = {"result", "target", "batch", "max_replicates", "level"};
	const int lines[] = {a->result_line, a->target_line, a->batch_line, a->max_line, a->level_line};
	if (!a->on) {
		for (int i = 0; i < 5; i++)
			if (lines[i])
				return sb_errf(e, SB_EUSAGE, "%s:%d: %s: only with replicates = auto under [campaign]", p,
					       lines[i], names[i]);
		return 0;
	}
	if (c->onset.line)
		return sb_errf(e, SB_EUSAGE, "%s:%d: replicates: an [onset] campaign sets its replicates under [onset] "
			       "(replicates = auto | N)", p, c->replicates_line);
	if (!a->result_line)
		return sb_errf(e, SB_EUSAGE, "%s:%d: replicates: auto needs result = median_wait|rise_fraction|mean_flux "
			       "(what the interval is of)", p, c->replicates_line);
	if (!a->target_line)
		return sb_errf(e, SB_EUSAGE, "%s:%d: replicates: auto needs target = W (the interval width at which a "
			       "grid point stops getting replicates)", p, c->replicates_line);
	if (!a->batch_line)
		a->batch = 4;
	if (!a->max_line)
		a->max_replicates = 32;
	if (!a->level_line)
		a->level = 0.95;
	/* the median's interval is the order-statistic one: it needs a few runs */
	long nmin = a->result == CP_RES_MEDIAN_WAIT ? adapt_min_replicates(a->level) : 2;
	if (a->max_replicates < nmin)
		return sb_errf(e, SB_EUSAGE, "%s:%d: max_replicates: at least %ld replicates are needed for an interval "
			       "of %s at level %g, got %ld", p, a->max_line ? a->max_line : c->replicates_line, nmin,
			       a->result == CP_RES_MEDIAN_WAIT ? "the median wait" :
			       a->result == CP_RES_RISE_FRACTION ? "the rise fraction" : "the mean flux", a->level,
			       a->max_replicates);
	int l;
	if ((l = seen_key(c, "seed")))
		return sb_errf(e, SB_EUSAGE, "%s:%d: seed: replicates = auto (line %d) numbers the replicates 1, 2, ...; "
			       "remove it", p, l, c->replicates_line);
	return 0;
}

/* zip = KEY KEY ...: [grid] axes that advance together, value k of each with value k of
 * the others (a sweep of the stiffness at a fixed restitution moves gamma_n and dt with
 * it; a sweep of the width at a fixed bed height moves n_grains). The first key's axis
 * keeps its place in the grid's order; the others follow its value index. */
static int zip_finish(campaign *c, sb_err *e)
{
	char buf[sizeof c->zip];
	snprintf(buf, sizeof buf, "%s", c->zip);
	const char *p = c->path;
	int idx[CP_MAX_KEYS], nkeys = 0, lead = -1;
	for (char *save = NULL, *k = strtok_r(buf, " \t,", &save); k; k = strtok_r(NULL, " \t,", &save)) {
		int a = -1;
		for (int i = 0; i < c->naxes; i++)
			if (!strcmp(c->axes[i].key, k))
				a = i;
		if (a < 0)
			return sb_errf(e, SB_EUSAGE, "%s:%d: zip: '%s' is not a [grid] axis of this file (zip names axes "
				       "that advance together)", p, c->zip_line, k);
		for (int j = 0; j < nkeys; j++)
			if (idx[j] == a)
				return sb_errf(e, SB_EUSAGE, "%s:%d: zip: '%s' named twice", p, c->zip_line, k);
		const cp_axis *ax = &c->axes[a];
		/* removing a repeated value would shift the tuples against each other */
		if (ax->given != ax->n)
			return sb_errf(e, SB_EUSAGE, "%s:%d: %s: a zipped axis needs distinct values (%ld given, %ld "
				       "distinct): value k goes with value k of the other zipped axes", p, ax->line, k,
				       ax->given, ax->n);
		if (nkeys && ax->n != c->axes[idx[0]].n)
			return sb_errf(e, SB_EUSAGE, "%s:%d: zip: %s has %ld values, %s has %ld: zipped axes need as "
				       "many values each", p, c->zip_line, k, ax->n, c->axes[idx[0]].key, c->axes[idx[0]].n);
		if (c->onset.line && !strcmp(k, "frequency"))
			return sb_errf(e, SB_EUSAGE, "%s:%d: zip: frequency is the [onset] search's", p, c->zip_line);
		idx[nkeys++] = a;
		if (lead < 0 || a < lead)
			lead = a;
	}
	if (nkeys < 2)
		return sb_errf(e, SB_EUSAGE, "%s:%d: zip: expected at least two [grid] axes, got '%s'", p, c->zip_line,
			       c->zip);
	/* the axis first in the file leads: the grid's order computes its digit first */
	for (int j = 0; j < nkeys; j++)
		if (idx[j] != lead)
			c->axes[idx[j]].zipped_to = lead + 1;
	return 0;
}

/* The drive's other axes (Gamma, v): what they set. Of amplitude, frequency and those
 * axes two make the drive; a campaign gives at most two of them (the amplitude's default
 * counts only when the campaign sets neither it nor the frequency). */
static int derived_finish(campaign *c, sb_err *e)
{
	const char *p = c->path;
	int line[AXIS_N] = {0}, first = -1, second = -1;
	for (int k = AXIS_FREQUENCY + 1; k < AXIS_N; k++)
		if ((line[k] = seen_key(c, drive_axis_name(k)))) {
			if (first < 0)
				first = k;
			else if (second < 0)
				second = k;
		}
	int la = seen_key(c, "amplitude"), lf = seen_key(c, "frequency");
	if (first < 0)
		return 0;
	int l = line[first];
	const char *k = drive_axis_name(first);
	if (c->onset.line)
		return sb_errf(e, SB_EUSAGE, "%s:%d: %s: an [onset] campaign searches the frequency; to search in %s, set "
			       "axis = %s under [onset] (line %d)", p, l, k, k, k, c->onset.line);
	if (second >= 0) {
		if (la || lf)
			return sb_errf(e, SB_EUSAGE, "%s:%d: %s: %s (line %d) and %s (line %d) set both the "
				       "amplitude and the frequency; remove it", p, la ? la : lf, la ? "amplitude" : "frequency",
				       k, l, drive_axis_name(second), line[second]);
		c->derive = CP_DERIVE_BOTH;
	} else if (la && lf) {
		return sb_errf(e, SB_EUSAGE, "%s:%d: %s: amplitude (line %d) and frequency (line %d) are both set, so %s has "
			       "nothing to set; remove one of the three", p, l, k, la, lf, k);
	} else {
		c->derive = lf ? CP_DERIVE_AMPLITUDE : CP_DERIVE_FREQUENCY;
	}
	return 0;
}

/* A ratio key (ratio.h) and the scene key it sets, both given: one would undo the other. */
static int ratio_finish(const campaign *c, sb_err *e)
{
	size_t n;
	const sb_ratio *t = ratio_table(&n);
	for (size_t i = 0; i < n; i++) {
		int lr = seen_key(c, t[i].key), ls = seen_key(c, t[i].sets);
		if (lr && ls)
			return sb_errf(e, SB_EUSAGE, "%s:%d: %s: %s (line %d) sets %s = %s x %s, and %s is given too (line %d); "
				       "remove one of the two", c->path, lr, t[i].key, t[i].key, lr, t[i].sets, t[i].key,
				       t[i].base, t[i].sets, ls);
	}
	return 0;
}

static int cp_handler(void *user, const char *section, const char *name, const char *value)
{
	struct rd *r = user;
	campaign *c = r->c;
	(void)section; /* tracked by the reader, which also sees empty sections */
	if (r->err_line)
		return 1;
	char where[SB_STR_MAX + 32];
	snprintf(where, sizeof where, "%s:%d", c->path, r->line);
	sb_err tmp = {0};
	if (r->section == SEC_NONE) {
		sb_errf(&tmp, SB_EUSAGE, "%s: '%s' outside a section (put it under [campaign], [scene] or [grid])",
			where, name);
	} else if (r->section == SEC_CAMPAIGN) {
		campaign_key(r, where, name, value);
		if (r->e->code) {
			tmp = *r->e;
			r->e->code = 0;
		}
	} else if (r->section == SEC_ONSET) {
		onset_key(&c->onset, r->line, where, name, value, &tmp);
	} else {
		int prev;
		if (!params_find(name) && !campaign_key_derived(name)) {
			const char *near = params_nearest(name);
			/* the drive's other axes, the campaign's own keys: "gamma and velocity" */
			size_t nr;
			const sb_ratio *rt = ratio_table(&nr);
			const char *derived[AXIS_N + 8];
			char dym[96], names[96] = "";
			int nd = 0;
			for (int k = AXIS_FREQUENCY + 1; k < AXIS_N; k++)
				derived[nd++] = drive_axis_name(k);
			for (size_t k = 0; k < nr && nd < AXIS_N + 8; k++)
				derived[nd++] = rt[k].key;
			for (int k = 0; k < nd; k++) {
				size_t l = strlen(names);
				snprintf(names + l, sizeof names - l, "%s%s", !k ? "" : k == nd - 1 ? " and " : ", ", derived[k]);
			}
			if (near)
				snprintf(dym, sizeof dym, "; did you mean %s?", near);
			sb_errf(&tmp, SB_EUSAGE, "%s: unknown key '%s'%s (shake --help lists the keys; %s are the campaign's)",
				where, name, near ? dym : did_you_mean(name, derived, nd, dym, sizeof dym), names);
		}
		else if (campaign_key_reserved(name))
			sb_errf(&tmp, SB_EUSAGE, "%s: %s: set by the study driver, not by a campaign", where, name);
		else if ((prev = seen_key(c, name)))
			sb_errf(&tmp, SB_EUSAGE, "%s: %s: given twice (first on line %d)", where, name, prev);
		else if (r->section == SEC_SCENE) {
			if (c->nfixed >= CP_MAX_KEYS)
				sb_errf(&tmp, SB_EUSAGE, "%s: too many keys", where);
			else {
				cp_axis one;
				if (!campaign_axis_parse(&one, name, value, where, &tmp) && one.n != 1)
					sb_errf(&tmp, SB_EUSAGE, "%s: %s: [scene] takes one value; put lists and ranges under [grid]",
						where, name);
				if (!tmp.code) {
					cp_fixed *f = &c->fixed[c->nfixed++];
					snprintf(f->key, sizeof f->key, "%s", name);
					snprintf(f->value, sizeof f->value, "%s", one.values[0]);
					f->line = r->line;
					if (!campaign_key_derived(name)) /* gamma, velocity: per point (grid.c) */
						params_set(&c->base, name, one.values[0], where, &tmp);
				}
				for (long i = 0; i < one.n; i++)
					free(one.values[i]);
				free(one.values);
			}
		} else if (!strcmp(name, "checkpoint_every")) {
			sb_errf(&tmp, SB_EUSAGE, "%s: checkpoint_every: not a grid axis (it does not change results); "
				"set it under [scene]", where);
		} else if (c->naxes >= CP_MAX_KEYS) {
			sb_errf(&tmp, SB_EUSAGE, "%s: too many axes", where);
		} else if (!campaign_axis_parse(&c->axes[c->naxes], name, value, where, &tmp)) {
			c->axes[c->naxes].line = r->line;
			c->naxes++;
			/* max_runs may come later in the file, so the limit is checked at the
			 * end; past the most it can be, reading more axes is wasted work */
			long points;
			if (product_past(c, CP_MAX_RUNS_LIMIT))
				campaign_points(c, &points, &tmp);
		} else {
			cp_axis *a = &c->axes[c->naxes];
			for (long i = 0; i < a->n; i++)
				free(a->values[i]);
			free(a->values);
			memset(a, 0, sizeof *a);
		}
	}
	if (tmp.code) {
		r->err_line = r->line;
		sb_errf(r->e, tmp.code, "%s", tmp.msg);
		return 0;
	}
	return 1;
}

/* A key = value line, from core/text/inifile.c: cp_handler (inih's form) at that line. */
static int cp_key(void *user, const char *name, const char *value, int line, sb_err *e)
{
	struct rd *r = user;
	r->line = line;
	return cp_handler(r, NULL, name, value) ? 0 : e->code ? e->code : SB_EUSAGE;
}

int campaign_load(campaign *c, const char *path, sb_err *e)
{
	memset(c, 0, sizeof *c);
	snprintf(c->path, sizeof c->path, "%s", path);
	params_defaults(&c->base);
	struct rd r = {.c = c, .e = e};
	const inifile in = {path, "campaign file", CP_MAX_LINES, cp_section, cp_key, &r};
	if (inifile_read(&in, e))
		return e->code;
	/* the [campaign] header, or line 1 of a file that has none */
	int cl = r.sec_line[SEC_CAMPAIGN] ? r.sec_line[SEC_CAMPAIGN] : 1;
	if (!r.seen_name)
		return sb_errf(e, SB_EUSAGE, "%s:%d: [campaign] has no name", path, cl);
	if (!r.seen_seed)
		return sb_errf(e, SB_EUSAGE, "%s:%d: [campaign] has no seed", path, cl);
	/* [scene] overrides the base scene wherever the two appear in the file: a
	 * [scene] section above `scene = FILE` must not be undone by loading FILE */
	for (int i = 0; i < c->nfixed; i++) {
		char where[SB_STR_MAX + 32];
		if (campaign_key_derived(c->fixed[i].key))
			continue;
		snprintf(where, sizeof where, "%s:%d", path, c->fixed[i].line);
		if (params_set(&c->base, c->fixed[i].key, c->fixed[i].value, where, e))
			return e->code;
	}
	if (c->onset.line && onset_finish(c, c->replicates ? c->replicates_line : 0, e))
		return e->code;
	if (stopdef_apply(c, e))
		return e->code;
	if (autorep_finish(c, e))
		return e->code;
	if (c->zip_line && zip_finish(c, e))
		return e->code;
	if (derived_finish(c, e) || ratio_finish(c, e))
		return e->code;
	int sl = seen_key(c, "seed");
	if (c->replicates && sl)
		return sb_errf(e, SB_EUSAGE, "%s:%d: seed: both replicates and seed given; "
			       "replicates = N means seed = 1..N", path, sl);
	if (c->replicates) {
		char buf[64], where[SB_STR_MAX + 32];
		snprintf(buf, sizeof buf, "1..%ld", c->replicates);
		snprintf(where, sizeof where, "%s:%d", path, c->replicates_line);
		if (c->naxes >= CP_MAX_KEYS)
			return sb_errf(e, SB_EUSAGE, "%s: too many axes", where);
		if (campaign_axis_parse(&c->axes[c->naxes], "seed", buf, where, e))
			return e->code;
		c->axes[c->naxes++].line = c->replicates_line;
	}
	/* counted from the axes' sizes before anything expands the grid: a grid of 10^6
	 * points takes minutes to check, and a driver would start it without a word */
	long points;
	return campaign_points(c, &points, e);
}

void campaign_free(campaign *c)
{
	for (int i = 0; i < c->naxes; i++) {
		for (long k = 0; k < c->axes[i].n; k++)
			free(c->axes[i].values[k]);
		free(c->axes[i].values);
	}
	c->naxes = 0;
}
