/* tool.c - the frame every analysis tool's main shares (tool.h). */
#include "tool.h"

#include "h5read.h"
#include "provenance.h"
#include "axis.h"
#include "label.h"
#include "num.h"

#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int tool_args(an_opts *o, int argc, char **argv, const char *help, const char *allowed, FILE *out, FILE *err)
{
	sb_err e = {0};
	const int pr = cli_parse(o, argc, argv, allowed, &e);
	if (pr < 0)
		fputs(help, out);
	else if (pr)
		fprintf(err, "%s: %s\n", o->tool, e.msg);
	return pr;
}

int tool_main(int argc, char **argv, const tool_spec *spec, void *s)
{
	/* GSL's default handler aborts the process on a domain error (a height of 1e308
	 * overflows a fit): every GSL call's status is checked where it is made instead */
	gsl_set_error_handler_off();
	an_opts o = {.tool = spec->name, .version = spec->version};
	if (argc == 2 && !strcmp(argv[1], "--version")) { /* as every program of the build */
		printf("%s %s (%s)\n", spec->name, spec->version, prov_version());
		return 0;
	}
	sb_err ee = {0};
	if (h5r_walk_env(&ee)) { /* it would refuse every run file */
		fprintf(stderr, "%s: %s\n", spec->name, ee.msg);
		return 1;
	}
	xopt x[TOOL_MAXX];
	memcpy(x, spec->x, sizeof x);
	const int pr = spec->nx ? xopt_args(&o, argc, argv, spec->help, spec->allowed, x, spec->nx, stdout, stderr)
				: tool_args(&o, argc, argv, spec->help, spec->allowed, stdout, stderr);
	if (pr < 0) /* the help's last line: tool_close's codes, said where they are made */
		fputs("Exit codes: 0 ok, 1 usage or no usable runs, 2 I/O.\n", stdout);
	if (pr)
		return pr < 0 ? 0 : 1;
	an_tool t;
	memset(&t, 0, sizeof t);
	t.o = &o;
	t.allowed = spec->allowed;
	t.x = x;
	t.nx = spec->nx;
	if (!(spec->init && spec->init(&t, s, x)) && !tool_open(&t, &o))
		spec->run(&t, s);
	if (spec->fini)
		spec->fini(&t, s);
	return tool_close(&t, stderr);
}

int tool_open(an_tool *t, const an_opts *o)
{
	t->o = o;
	if (adb_open(&t->d, o->db, !o->no_store, &t->e))
		return t->e.code;
	if (pool_read(o, &t->d, &t->runs, &t->nr, t->axes, &t->na, &t->e))
		return t->e.code;
	/* said for every run, also one this tool then leaves aside as not its kind: an
	 * edited parameter may be what made it so */
	for (int i = 0; i < t->nr; i++)
		if (t->runs[i].rows[0])
			fprintf(stderr, "%s: warning: run %s: %s (counted unusable where %s uses it)\n", o->tool,
				t->runs[i].id, t->runs[i].rows, o->tool);
	return 0;
}

int tool_old(an_tool *t, const an_run *r)
{
	return acct_version_skip(r, t->o->all_versions, &t->nold);
}

int tool_where_known(an_tool *t)
{
	const an_opts *o = t->o;
	for (int w = 0; w < o->nwhere; w++) {
		int known = 0;
		for (int i = 0; i < t->nr && !known; i++)
			known = an_str(&t->runs[i], o->where_key[w]) != NULL;
		if (t->nr && !known)
			return sb_errf(&t->e, SB_EUSAGE, "--where: '%s' is not a parameter of campaign '%s'", o->where_key[w],
				       o->campaign);
	}
	return 0;
}

int tool_where_ok(const an_opts *o, const an_run *r)
{
	for (int w = 0; w < o->nwhere; w++) {
		const char *v = an_str(r, o->where_key[w]);
		if (!v)
			return 0;
		double a, b;
		const int numeric = !num_real(v, &a) && !num_real(o->where_val[w], &b);
		if (numeric ? !(fabs(a - b) <= 1e-9 * fmax(1, fabs(b))) : strcmp(v, o->where_val[w]) != 0)
			return 0;
	}
	return 1;
}

int tool_keep(an_tool *t, int i)
{
	an_run s = t->runs[t->k];
	t->runs[t->k] = t->runs[i];
	t->runs[i] = s;
	return t->k++;
}

int tool_none(an_tool *t, const char *kind, const char *narrowed)
{
	const an_opts *o = t->o;
	int known = 0;
	if (o->ncamp > 1) /* each is in its database (pool_read) */
		return sb_errf(&t->e, SB_EUSAGE, "campaigns %s: no finished %s%s%s", o->campaign, kind, narrowed,
			       t->nold ? " of the current grids (--all-versions)" : "");
	if (!adb_campaign_exists(&t->d, o->campaign, &known, &t->e) && !known)
		return sb_errf(&t->e, SB_EUSAGE, "campaign '%s' is not in %s", o->campaign, o->db);
	return sb_errf(&t->e, SB_EUSAGE, "campaign '%s': no finished %s in %s%s%s", o->campaign, kind, o->db, narrowed,
		       t->nold ? " of the current grid (--all-versions)" : "");
}

int tool_keys(an_tool *t, char keys[][48], int nk)
{
	t->nk = nk;
	for (int k = 0; k < nk; k++)
		memcpy(t->keys[k], keys[k], sizeof t->keys[k]);
	if (!(t->gval = calloc((size_t)(t->ng * nk > 0 ? t->ng * nk : 1), sizeof *t->gval)))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	return 0;
}

int tool_value(an_tool *t, int j, int k, const char *v)
{
	char **p = &t->gval[j * t->nk + k];
	free(*p);
	if (!(*p = strdup(v ? v : "")))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	return 0;
}

int tool_key_known(an_tool *t, const an_run *r, const char *key)
{
	char why[256];
	if (!an_known(r, key, why, sizeof why))
		return 0;
	return sb_errf(&t->e, SB_EUSAGE, "campaign '%s': run %s: %s: its group is unknown (no default stands in: it "
		       "would pool the run with others); repair or delete the run in %s", t->o->campaign, r->id, why,
		       t->o->db);
}

int tool_group(an_tool *t, const char *const *always, const char *const *drop)
{
	char keys[AN_MAXKEYS][48];
	int nk;
	cli_keys(t->o, t->axes, t->na, always, drop, keys, &nk);
	if (t->o->nby < 0 && t->o->ncamp > 1)
		t->nadded = pool_keys(t->runs, t->k, drop, keys, &nk);
	for (int i = 0; i < t->k; i++)
		for (int k = 0; k < nk; k++)
			if (tool_key_known(t, &t->runs[i], keys[k]))
				return t->e.code;
	t->ng = an_group_runs(t->runs, t->k, keys, nk, &t->labels);
	if (t->ng < 0) {
		t->ng = 0;
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	}
	if (tool_keys(t, keys, nk))
		return t->e.code;
	/* a group's values are its runs' (they are equal: that is what makes the group) */
	for (int i = t->k - 1; i >= 0; i--)
		for (int k = 0; k < nk; k++)
			if (tool_value(t, t->runs[i].group, k, an_str(&t->runs[i], keys[k])))
				return t->e.code;
	return 0;
}

void tool_legend(const an_tool *t, int j, int vary, char *buf, size_t n)
{
	label_group(buf, n, t->keys, t->nk, (const char *const *)t->gval, t->ng, j, vary);
}

void tool_curve_legend(const an_tool *t, const int *curve, size_t stride, int ncurve, const char *along, int c,
		       int vary, char *buf, size_t n)
{
	char keys[AN_MAXKEYS][48];
	const char *vals[AN_MAXKEYS * 16];
	int nk = 0, first[16] = {0};
	buf[0] = 0;
	if (ncurve > 16)
		return;
	for (int k = 0; k < t->nk; k++)
		if (strcmp(t->keys[k], along))
			memcpy(keys[nk++], t->keys[k], 48);
	for (int cc = 0; cc < ncurve; cc++)
		for (int j = 0; j < t->ng; j++)
			if (*(const int *)((const char *)curve + (size_t)j * stride) == cc) {
				first[cc] = j;
				break;
			}
	for (int cc = 0; cc < ncurve; cc++)
		for (int k = 0, m = 0; k < t->nk; k++)
			if (strcmp(t->keys[k], along))
				vals[cc * nk + m++] = t->gval[first[cc] * t->nk + k];
	label_group(buf, n, keys, nk, vals, ncurve, c, vary);
}

/* 1 when every considered run has key and the same value of it, copied to v */
static int shared(const an_tool *t, const char *key, char *v, size_t n)
{
	const char *first = t->k ? an_str(&t->runs[0], key) : NULL;
	for (int i = 1; first && i < t->k; i++) {
		const char *x = an_str(&t->runs[i], key);
		if (!x || strcmp(x, first))
			return 0;
	}
	if (first)
		snprintf(v, n, "%s", first);
	return first != NULL;
}

void tool_setting(const an_tool *t, char *buf, size_t n)
{
	static const char *const keys[] = {"n_grains", "width", "amplitude", NULL};
	size_t l = 0;
	buf[0] = 0;
	for (const char *const *k = keys; *k && l + 1 < n; k++) {
		char v[128], w[160];
		int grouped = 0;
		for (int q = 0; q < t->nk; q++)
			grouped |= !strcmp(t->keys[q], *k);
		if (grouped || !shared(t, *k, v, sizeof v))
			continue;
		label_param(w, sizeof w, *k, v);
		l += (size_t)snprintf(buf + l, n - l, "%s%s", l ? ", " : "", w);
	}
	if (l + 1 < n && t->ng) {
		char c[512];
		tool_legend(t, 0, 0, c, sizeof c);
		if (*c)
			snprintf(buf + l, n - l, "%s%s", l ? ", " : "", c);
	}
}

int tool_gamma(const an_tool *t, double *A, double *g)
{
	char a[128], gr[128];
	if (!shared(t, "amplitude", a, sizeof a))
		return 0;
	*A = strtod(a, NULL);
	/* a database without the key ran with the engine's default */
	*g = shared(t, "gravity", gr, sizeof gr) ? strtod(gr, NULL) : 981;
	return *A > 0 && *g > 0;
}

static int key_index(const an_tool *t, const char *key)
{
	for (int k = 0; k < t->nk; k++)
		if (!strcmp(t->keys[k], key))
			return k;
	return -1;
}

int tool_curves(an_tool *t, const char *along, int *curve)
{
	const int ka = key_index(t, along);
	if (ka < 0) {
		char ks[AN_MAXKEYS * 50] = "";
		for (int k = 0, l = 0; k < t->nk; k++)
			l += snprintf(ks + l, sizeof ks - (size_t)l, "%s%s", k ? ", " : "", t->keys[k]);
		sb_errf(&t->e, SB_EUSAGE, "'%s' is not a grouping key (they are: %s; --by sets them)", along,
			*ks ? ks : "none");
		return -1;
	}
	int nc = 0;
	for (int j = 0; j < t->ng; j++) {
		curve[j] = -1;
		for (int h = 0; h < j && curve[j] < 0; h++) {
			int alike = 1;
			for (int k = 0; k < t->nk && alike; k++)
				alike = k == ka || !strcmp(t->gval[j * t->nk + k], t->gval[h * t->nk + k]);
			if (alike)
				curve[j] = curve[h];
		}
		if (curve[j] < 0)
			curve[j] = nc++;
	}
	return nc;
}

int *tool_curves_csv(an_tool *t, const char *along, const char *name, int *nc, FILE **f)
{
	int *curve = malloc(sizeof *curve * (size_t)(t->ng > 0 ? t->ng : 1));
	*f = NULL;
	if (!curve) {
		sb_errf(&t->e, SB_ENOMEM, "out of memory");
		return NULL;
	}
	if ((*nc = tool_curves(t, along, curve)) < 0 || !(*f = tool_out_open(t, name))) {
		free(curve);
		return NULL;
	}
	return curve;
}

double tool_num(const an_tool *t, int j, const char *key)
{
	const int k = key_index(t, key);
	double v;
	if (k < 0 || j < 0 || j >= t->ng || num_real(t->gval[j * t->nk + k], &v))
		return NAN;
	return v;
}

void tool_label_but(const an_tool *t, int j, const char *key, char *buf, size_t n)
{
	size_t l = 0;
	buf[0] = 0;
	for (int k = 0; k < t->nk && l < n; k++) {
		const char *v = t->gval[j * t->nk + k];
		double x;
		if (!strcmp(t->keys[k], key))
			continue;
		if (!num_real(v, &x)) /* as an_group_runs labels a number */
			l += (size_t)snprintf(buf + l, n - l, "%s%s=%g", l ? " " : "", t->keys[k], x);
		else
			l += (size_t)snprintf(buf + l, n - l, "%s%s=%s", l ? " " : "", t->keys[k], v);
	}
	if (!l)
		snprintf(buf, n, "all");
}

int tool_group_drive(const an_tool *t, int j, double *A, double *g)
{
	int first = 1;
	for (int i = 0; i < t->k; i++) {
		const an_run *r = &t->runs[i];
		if (r->group != j)
			continue;
		const double a = an_num(r, "amplitude", NAN), gr = axis_gravity(r);
		if (first)
			*A = a, *g = gr, first = 0;
		else if (a != *A || gr != *g)
			return 0;
	}
	return !first && *A > 0 && *g > 0;
}

int tool_tally(an_tool *t, FILE *out, const char *fmt, ...)
{
	if (acct_tally(t->runs, t->k, t->ng, &t->A))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	long used = 0;
	for (int j = 0; j < t->ng; j++)
		used += acct_used(&t->A[j]);
	if (used)
		return 0;
	char what[256];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(what, sizeof what, fmt, ap);
	va_end(ap);
	acct_print(out, t->o->tool, t->labels, t->A, t->ng, t->nold, t->o->all_versions);
	return sb_errf(&t->e, SB_EUSAGE, "campaign '%s': none of %s is usable yet", t->o->campaign, what);
}

int tool_accounting_csv(an_tool *t)
{
	char name[128];
	snprintf(name, sizeof name, "%s_accounting.csv", t->o->tool);
	FILE *f = tool_out_open(t, name);
	if (!f)
		return t->e.code;
	acct_runs_csv(f, t->runs, t->k, t->labels);
	return tool_out_close(t, f);
}

FILE *tool_summary_csv(an_tool *t, const char *name, const char *head)
{
	FILE *s = tool_out_open(t, name);
	if (!s)
		return NULL;
	fputs(head, s);
	acct_csv_head(s);
	fputc('\n', s);
	return s;
}

void tool_summary_acct(const an_tool *t, FILE *s, int j)
{
	acct_csv_row(s, &t->A[j]);
	fputc('\n', s);
}

void tool_define(an_tool *t, const char *fmt, ...)
{
	size_t l = strlen(t->defn);
	if (l + 2 >= sizeof t->defn)
		return;
	if (l)
		t->defn[l++] = ' ';
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(t->defn + l, sizeof t->defn - l, fmt, ap);
	va_end(ap);
}

int tool_store_begin(an_tool *t)
{
	if (t->o->no_store)
		return 0;
	char opts[2048];
	cli_options(t->o, t->allowed ? t->allowed : "", opts, sizeof opts);
	xopt_options(t->x, t->nx, opts, sizeof opts);
	if (*t->defn)
		snprintf(opts + strlen(opts), sizeof opts - strlen(opts), "%s%s", *opts ? " " : "", t->defn);
	return adb_store_begin(&t->d, t->o->campaign, t->o->tool, t->o->version, opts, t->keys, t->nk, &t->e);
}

/* group j's key values, as adb_store binds them */
static const char *const *group_vals(const an_tool *t, int j)
{
	return j >= 0 && j < t->ng && t->gval ? (const char *const *)&t->gval[j * t->nk] : NULL;
}

void tool_store(an_tool *t, int j, const char *grp, const char *key, double value, double lo, double hi, long n)
{
	if (!t->o->no_store)
		adb_store(&t->d, t->o->campaign, t->o->tool, t->o->version, grp, group_vals(t, j), key, value, lo, hi, n,
			  &t->e);
}

void tool_store_run(an_tool *t, const an_run *r, const char *key, double value, const char *cls)
{
	if (!t->o->no_store && !t->e.code)
		adb_store_run(&t->d, t->o->campaign, t->o->tool, r->id, key, value, cls, &t->e);
}

void tool_store_acct(an_tool *t, const char *grp, int j)
{
	if (!t->o->no_store)
		acct_store(&t->d, t->o->campaign, t->o->tool, t->o->version, grp, group_vals(t, j), &t->A[j], &t->e);
}

int tool_store_end(an_tool *t)
{
	if (!t->o->no_store)
		adb_store_end(&t->d, !t->e.code, &t->e);
	return t->e.code;
}

/* the slot of the open output f, or a free one for f NULL; NULL when none */
static sb_file *out_slot(an_tool *t, const FILE *f)
{
	for (size_t i = 0; i < sizeof t->out / sizeof t->out[0]; i++)
		if (t->out[i].f == f)
			return &t->out[i];
	return NULL;
}

FILE *tool_out_open(an_tool *t, const char *name)
{
	sb_file *o = out_slot(t, NULL);
	if (!o) { /* a tool writes at most a few tables at once */
		sb_errf(&t->e, SB_EIO, "%s/%s: too many output files open at once", t->o->out, name);
		return NULL;
	}
	return cli_open_out(t->o, name, o, &t->e) ? NULL : o->f;
}

int tool_out_close(an_tool *t, FILE *f)
{
	sb_file *o = f ? out_slot(t, f) : NULL;
	if (!o)
		return t->e.code;
	if (t->e.code) { /* an error on the way: the table is not complete */
		fs_abort(o);
		return t->e.code;
	}
	if (fs_finish(o, &t->e))
		return t->e.code;
	sb_file *d = realloc(t->done, (size_t)(t->ndone + 1) * sizeof *d);
	if (!d) {
		unlink(o->tmp);
		return sb_errf(&t->e, SB_EIO, "%s: out of memory", o->path);
	}
	t->done = d;
	t->done[t->ndone++] = *o;
	return 0;
}

FILE *tool_gp_open(an_tool *t, const char *name, int w, int h, char *script, char *png, size_t len)
{
	sb_file *o = out_slot(t, NULL);
	if (!o) {
		sb_errf(&t->e, SB_EIO, "%s/%s.gp: too many output files open at once", t->o->out, name);
		return NULL;
	}
	FILE *f = gp_open(t->o, name, w, h, o, png, len, &t->e);
	if (f)
		snprintf(script, len, "%s", o->path);
	return f;
}

int tool_plot(an_tool *t, FILE *f, const char *script, const char *png)
{
	gp_close(f);
	if (tool_out_close(t, f))
		return t->e.code;
	char **p = realloc(t->plots, (size_t)(2 * t->nplots + 2) * sizeof *p);
	if (!p)
		return sb_errf(&t->e, SB_EIO, "%s: out of memory", png);
	t->plots = p;
	p[2 * t->nplots] = strdup(script);
	p[2 * t->nplots + 1] = strdup(png);
	t->nplots++;
	if (!p[2 * t->nplots - 2] || !p[2 * t->nplots - 1])
		return sb_errf(&t->e, SB_EIO, "%s: out of memory", png);
	return 0;
}

/* Every finished output in place, then the figures drawn from them; or, after an
 * error, every finished output removed (the earlier tables stay as they were). */
static void place_outputs(an_tool *t)
{
	int i = 0;
	for (; !t->e.code && i < t->ndone; i++)
		if (fs_rename_durable(t->done[i].tmp, t->done[i].path, &t->e))
			unlink(t->done[i].tmp);
	for (; i < t->ndone; i++)
		unlink(t->done[i].tmp);
	for (int k = 0; !t->e.code && k < t->nplots; k++)
		gp_run(t->plots[2 * k], t->plots[2 * k + 1], &t->e);
	for (int k = 0; k < 2 * t->nplots; k++)
		free(t->plots[k]);
	free(t->plots);
	free(t->done);
	t->plots = NULL;
	t->done = NULL;
	t->nplots = t->ndone = 0;
}

long tool_partly(const an_tool *t)
{
	long partly = 0;
	for (int j = 0; j < t->ng; j++)
		partly += t->A[j].n[AN_PARTLY];
	return partly;
}

void tool_report(const an_tool *t, FILE *out, const char *partly)
{
	acct_print(out, t->o->tool, t->labels, t->A, t->ng, t->nold, t->o->all_versions);
	pool_print(out, t->o, t->runs, t->k, t->labels, t->ng, t->keys, t->nk, t->nadded);
	long n = tool_partly(t);
	if (partly && n)
		fprintf(out, "# %ld failed run%s enter%s with %s\n", n, n == 1 ? "" : "s", n == 1 ? "s" : "", partly);
}

int tool_close(an_tool *t, FILE *err)
{
	/* an error between tool_store_begin and tool_store_end leaves nothing half stored */
	if (t->d.ins)
		adb_store_end(&t->d, 0, &t->e);
	for (size_t i = 0; i < sizeof t->out / sizeof t->out[0]; i++)
		if (t->out[i].f) { /* left open by a step that failed: not complete */
			if (!t->e.code) /* every step closes what it wrote; this one is a slip */
				sb_errf(&t->e, SB_EIO, "%s: not closed: not written", t->out[i].path);
			fs_abort(&t->out[i]);
		}
	place_outputs(t);
	free(t->A);
	for (int i = 0; t->gval && i < t->ng * t->nk; i++)
		free(t->gval[i]);
	free(t->gval);
	t->gval = NULL;
	an_labels_free(t->labels, t->ng);
	adb_runs_free(t->runs, t->nr);
	adb_close(&t->d);
	t->A = NULL;
	t->labels = NULL;
	t->runs = NULL;
	if (!t->e.code)
		return 0;
	fprintf(err, "%s: %s\n", t->o->tool, t->e.msg);
	return t->e.code == SB_EUSAGE ? 1 : 2;
}
