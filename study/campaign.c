/* campaign.c - reading a campaign file: sections, keys, axis syntax, validation. */
#include "campaign.h"

#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "safe.h"

int campaign_key_reserved(const char *key)
{
	static const char *const own[] = {"output", "checkpoint", "restart", "write_particles",
					  "write_lammps", "progress", NULL};
	for (int i = 0; own[i]; i++)
		if (!strcmp(key, own[i]))
			return 1;
	return 0;
}

static void trim(char *s)
{
	size_t lead = strspn(s, " \t");
	memmove(s, s + lead, strlen(s + lead) + 1);
	size_t l = strlen(s);
	while (l && strchr(" \t\r\n", s[l - 1]))
		s[--l] = 0;
}

static int axis_add(cp_axis *a, const char *v, const char *where, sb_err *e)
{
	for (long i = 0; i < a->n; i++)
		if (!strcmp(a->values[i], v))
			return 0; /* "2.6, 2.60" is one grid point, not two identical runs */
	if (a->n >= CP_MAX_VALUES)
		return sb_errf(e, SB_EUSAGE, "%s: %s: more than %d values", where, a->key, CP_MAX_VALUES);
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

/* Check one value with the engine's own parser and keep its canonical text, so that
 * "2.60" and "2.6" are the same value and the run id does not depend on spelling. */
static int value_add(cp_axis *a, const char *v, const char *where, sb_err *e)
{
	sb_scene s;
	params_defaults(&s);
	if (params_set(&s, a->key, v, where, e))
		return e->code;
	const sb_param *p = params_find(a->key);
	if (p->type == PT_STR && *v && !safe_path_value(v))
		return sb_errf(e, SB_EUSAGE, "%s: %s: '%s' is not a plain file name ([A-Za-z0-9_./+-], no '..')",
			       where, a->key, v);
	char buf[SB_STR_MAX + 8];
	params_format(&s, p, buf, sizeof buf);
	return axis_add(a, buf, where, e);
}

static int parse_num(const char *t, double *x)
{
	char *end;
	errno = 0;
	*x = strtod(t, &end);
	while (*end == ' ' || *end == '\t')
		end++;
	return end != t && !*end && !errno && isfinite(*x);
}

static int parse_long(const char *t, long *x)
{
	char *end;
	errno = 0;
	long long v = strtoll(t, &end, 10);
	while (*end == ' ' || *end == '\t')
		end++;
	*x = (long)v;
	return end != t && !*end && !errno;
}

/* START:STOP:STEP, endpoint included. Value k is START + k STEP printed with 12
 * significant digits and parsed again: 2.5 + 14 * 0.05 = 3.2000000000000002 becomes
 * "3.2", so a range gives the same values (and run ids) as the written-out list. */
static int float_range(cp_axis *a, char *item, const char *where, sb_err *e)
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
	double span = (hi - lo) / step;
	if (span > CP_MAX_VALUES)
		return sb_errf(e, SB_EUSAGE, "%s: %s: range '%s' has more than %d values", where, a->key, item, CP_MAX_VALUES);
	/* the tolerance keeps the endpoint when (STOP - START) / STEP lands a hair below
	 * an integer (0.7 / 0.05 = 13.999999999999998) */
	long n = (long)floor(span + 1e-9);
	for (long k = 0; k <= n; k++) {
		char buf[64];
		snprintf(buf, sizeof buf, "%.12g", lo + (double)k * step);
		if (value_add(a, buf, where, e))
			return e->code;
	}
	return 0;
}

static int int_range(cp_axis *a, char *item, char *dots, const char *where, sb_err *e)
{
	long lo, hi;
	*dots = 0;
	int okn = parse_long(item, &lo) && parse_long(dots + 2, &hi);
	*dots = '.';
	if (!okn || hi < lo)
		return sb_errf(e, SB_EUSAGE, "%s: %s: bad range '%s' (expected FIRST..LAST, integers, FIRST <= LAST)",
			       where, a->key, item);
	if (hi - lo >= CP_MAX_VALUES)
		return sb_errf(e, SB_EUSAGE, "%s: %s: range '%s' has more than %d values", where, a->key, item, CP_MAX_VALUES);
	for (long k = lo; k <= hi; k++) {
		char buf[32];
		snprintf(buf, sizeof buf, "%ld", k);
		if (value_add(a, buf, where, e))
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
	char *save = NULL;
	int any = 0;
	for (char *item = strtok_r(copy, ",", &save); item; item = strtok_r(NULL, ",", &save)) {
		trim(item);
		if (!*item)
			continue;
		any = 1;
		const sb_param *p = params_find(key);
		char *dots = strstr(item, "..");
		int rc;
		if (p && (p->type == PT_INT || p->type == PT_REAL) && strchr(item, ':'))
			rc = float_range(a, item, where, e);
		else if (p && p->type == PT_INT && dots)
			rc = int_range(a, item, dots, where, e);
		else
			rc = value_add(a, item, where, e);
		if (rc) {
			free(copy);
			return rc;
		}
	}
	free(copy);
	if (!any)
		return sb_errf(e, SB_EUSAGE, "%s: %s: no values", where, key);
	return 0;
}

/* ---- the INI reader (same line counting as core/params.c) ---- */

enum { SEC_NONE, SEC_CAMPAIGN, SEC_SCENE, SEC_GRID };

struct rd {
	campaign *c;
	sb_err *e;
	FILE *f;
	int line, err_line, section;
	int seen_name, seen_seed;
	int sec_line[4];
	char ckey[8][16];     /* [campaign] keys seen, with their lines */
	int ckey_line[8], nckey;
};

/* inih's Debian build has no INI_HANDLER_LINENO: the reader counts lines (the handler
 * runs right after its line is read), strips indentation (inih would take it as a
 * continuation of the previous value) and inline " # comments", and checks section
 * names itself (inih says nothing about an empty section). */
static char *cp_reader(char *str, int num, void *stream)
{
	struct rd *r = stream;
	if (r->err_line)
		return NULL;
	char *got = fgets(str, num, r->f);
	if (!got)
		return NULL;
	r->line++;
	size_t l = strlen(str);
	if (l == (size_t)num - 1 && str[l - 1] != '\n') {
		r->err_line = r->line;
		sb_errf(r->e, SB_EUSAGE, "%s:%d: line too long", r->c->path, r->line);
		return NULL;
	}
	size_t lead = strspn(str, " \t");
	if (lead)
		memmove(str, str + lead, strlen(str + lead) + 1);
	for (char *h = strchr(str, '#'); h; h = strchr(h + 1, '#'))
		if (h == str || h[-1] == ' ' || h[-1] == '\t') {
			h[0] = '\n';
			h[1] = 0;
			break;
		}
	if (str[0] == '[') {
		char *q = strchr(str, ']');
		int sec = -1;
		size_t n = q ? (size_t)(q - str - 1) : 0;
		if (q && n == 8 && !strncmp(str + 1, "campaign", 8))
			sec = SEC_CAMPAIGN;
		else if (q && n == 5 && !strncmp(str + 1, "scene", 5))
			sec = SEC_SCENE;
		else if (q && n == 4 && !strncmp(str + 1, "grid", 4))
			sec = SEC_GRID;
		if (sec < 0) {
			r->err_line = r->line;
			sb_errf(r->e, SB_EUSAGE, "%s:%d: unknown section '%.*s' (expected [campaign], [scene] or [grid])",
				r->c->path, r->line, (int)strcspn(str, "\r\n"), str);
			return NULL;
		}
		if (r->sec_line[sec]) {
			r->err_line = r->line;
			sb_errf(r->e, SB_EUSAGE, "%s:%d: section [%.*s] repeated (first on line %d)", r->c->path,
				r->line, (int)n, str + 1, r->sec_line[sec]);
			return NULL;
		}
		r->sec_line[sec] = r->line;
		r->section = sec;
	}
	return got;
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
	if (r->nckey < 8 && strlen(name) < sizeof r->ckey[0]) {
		snprintf(r->ckey[r->nckey], sizeof r->ckey[0], "%s", name);
		r->ckey_line[r->nckey++] = r->line;
	}
	if (!strcmp(name, "name")) {
		if (!safe_name(value))
			return sb_errf(e, SB_EUSAGE, "%s: name: '%s' is not a valid campaign name "
				       "(1-64 of [A-Za-z0-9_.-], not starting with '.' or '-')", where, value);
		snprintf(c->name, sizeof c->name, "%s", value);
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
	} else if (!strcmp(name, "seed")) {
		char *end;
		errno = 0;
		unsigned long long s = strtoull(value, &end, 10);
		if (!*value || *end || errno || value[0] == '-')
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
	} else if (!strcmp(name, "replicates")) {
		char *end;
		errno = 0;
		long n = strtol(value, &end, 10);
		if (!*value || *end || errno || n < 1 || n > CP_MAX_VALUES)
			return sb_errf(e, SB_EUSAGE, "%s: replicates: expected an integer in [1, %d], got '%s'", where,
				       CP_MAX_VALUES, value);
		c->replicates = n;
	} else {
		return sb_errf(e, SB_EUSAGE, "%s: unknown key '%s' in [campaign] "
			       "(name, description, scene, seed, seeds, replicates)", where, name);
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
	} else {
		int prev;
		if (!params_find(name))
			sb_errf(&tmp, SB_EUSAGE, "%s: unknown key '%s' (shake --help lists the keys)", where, name);
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

int campaign_load(campaign *c, const char *path, sb_err *e)
{
	memset(c, 0, sizeof *c);
	snprintf(c->path, sizeof c->path, "%s", path);
	params_defaults(&c->base);
	FILE *f = fopen(path, "r");
	if (!f)
		return sb_errf(e, SB_EUSAGE, "%s: cannot open campaign file: %s", path, strerror(errno));
	struct rd r = {.c = c, .e = e, .f = f};
	int rc = ini_parse_stream(cp_reader, &r, cp_handler, &r);
	int ioerr = ferror(f);
	fclose(f);
	if (rc > 0 && (!r.err_line || rc < r.err_line)) {
		e->code = 0;
		return sb_errf(e, SB_EUSAGE, "%s:%d: malformed line (expected key = value or [section])", path, rc);
	}
	if (e->code)
		return e->code;
	if (rc < 0 || ioerr)
		return sb_errf(e, SB_EIO, "%s: cannot read campaign file", path);
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
		snprintf(where, sizeof where, "%s:%d", path, c->fixed[i].line);
		if (params_set(&c->base, c->fixed[i].key, c->fixed[i].value, where, e))
			return e->code;
	}
	int sl = seen_key(c, "seed");
	if (c->replicates && sl)
		return sb_errf(e, SB_EUSAGE, "%s:%d: seed: both replicates and seed given; "
			       "replicates = N means seed = 1..N", path, sl);
	if (c->replicates) {
		char buf[64];
		snprintf(buf, sizeof buf, "1..%ld", c->replicates);
		if (c->naxes >= CP_MAX_KEYS)
			return sb_errf(e, SB_EUSAGE, "%s: too many axes", path);
		if (campaign_axis_parse(&c->axes[c->naxes], "seed", buf, path, e))
			return e->code;
		c->naxes++;
	}
	return 0;
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
