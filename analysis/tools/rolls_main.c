/* rolls_main.c - bin/rolls: claim 2 ("the intruder drags the convection rolls deeper")
 * as numbers with intervals: per run the flux profile Phi(D) and how deep its rolls
 * reach (rolls.h), per group the mean reach, and per frequency the difference with
 * and without intruder - of the reach and of Phi on every line - with Welch intervals
 * across seeds. A tool of its own rather than an option of figures (which draws the
 * pooled profiles of the paper's Fig. 3) or onset (Phi through one plane against f):
 * its unit is the run's profile and its question a comparison of two sets of seeds.
 * Only this file prints and exits. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flux.h"
#include "common/acct.h"
#include "common/adb.h"
#include "common/cli.h"
#include "common/fluxrun.h"
#include "common/label.h"
#include "common/tool.h"
#include "common/xopt.h"
#include "measure/rolls.h"

#define VERSION "1"
#define MAXCMP 6

/* a run whose records are in the statistic: finished, or failed and used up to it */
#define USED(r) ((r)->use == AN_USED || (r)->use == AN_PARTLY)

static const char HELP[] =
	"usage: rolls CAMPAIGN [--db FILE] [--runs DIR] [--out DIR] [--by KEYS] [--skip FRAC]\n"
	"             [--fraction Q] [--smooth K] [--level L] [--all-versions] [--no-plot]\n"
	"             [--no-store]\n\n"
	"How deep the convection rolls reach, with and without intruder (claim 2: \"the\n"
	"intruder drags the rolls deeper\"). For every run at a fixed frequency (ramp = none)\n"
	"with flux = yes: its profile Phi(D), the time mean of Phi on each height line over\n"
	"the periods after the first FRAC of them (default 0.2), smoothed by a centred running\n"
	"mean over K lines (--smooth, default 5; 1: none). Its largest |Phi| is phi_max; the\n"
	"roll region is the lines around it where Phi, with phi_max's sign, is at least Q\n"
	"phi_max (--fraction, default 0.5); the roll bottom D_b is where the region ends\n"
	"below (interpolated between lines; the lowest line when it reaches the floor), and\n"
	"the reach is h_s - D_b, how far below the run's settled surface h_s the rolls go.\n"
	"Per group (default: frequency, radius_ratio and every other swept axis): the mean\n"
	"reach and roll bottom with Student-t intervals across seeds. Per group with an\n"
	"intruder and the group without one (radius_ratio = 0) that agrees in every other\n"
	"key: the difference with - without of the mean reach, of the roll bottom and of\n"
	"Phi(D) line by line (lines paired by their index: the same fraction of each run's\n"
	"surface height), with Welch intervals: the study driver derives each run's seed\n"
	"from its replicate and its preparation keys, radius_ratio among them, so the runs\n"
	"with and without intruder start from different packings and are independent\n"
	"samples, not pairs. A reach difference > 0 means the rolls reach deeper with the\n"
	"intruder.\n\n"
	"No run is dropped silently: per group the table, rolls_summary.csv and the stored\n"
	"rows count the runs used, the failed ones by status (used up to the failure: their\n"
	"periods after the transient of the run as planned; or unusable), the unreadable\n"
	"files, the runs still pending or running, and the runs without rolls (Phi = 0 on\n"
	"every line: unusable, with why); rolls_accounting.csv has one row per run.\n\n"
	"  --db FILE, --runs DIR, --out DIR   as for every tool (waiting --help)\n"
	"  --by KEYS        group by these parameters (comma separated)\n"
	"  --fraction Q     the roll region: where Phi >= Q phi_max (0 < Q <= 1; default 0.5)\n"
	"  --smooth K       running mean over K lines before the reach is read (default 5)\n"
	"  --level L        confidence level (default 0.95)\n"
	"  --all-versions   also the runs of earlier versions of the campaign file\n"
	"  --no-plot        no figures;  --no-store  nothing written to the database\n\n"
	"Writes rolls_runs.csv (per run: phi_max, roll bottom, reach), rolls_summary.csv (per\n"
	"group), rolls_diff.csv (per comparison), rolls_profile.csv (per comparison and line:\n"
	"Phi without, with and the difference, each with its interval), rolls_accounting.csv,\n"
	"rolls.png/.pdf (per frequency: Phi(D) with and without intruder with their bands and\n"
	"roll bottoms; the difference with its band); stores per group in `analysis` (tool\n"
	"'rolls'): runs, reach (lo, hi), roll_bottom (lo, hi), phi_max, to_floor and the\n"
	"accounting keys (onset --help); per comparison (grp 'GROUP vs no intruder'):\n"
	"reach_diff (lo, hi), roll_bottom_diff (lo, hi), lines_differ (lines whose interval\n"
	"of the difference excludes 0), runs_with, runs_without.\n"
	"Options take their value as --opt VALUE or --opt=VALUE. Figures are written as PNG\n"
	"and PDF (vector) with their gnuplot scripts.\n";

/* One considered run's profile and reach. */
typedef struct prun {
	size_t L;
	double *phi, *h; /* [L] (NULL: not used) */
	double surface;
	rolls_reach rr;
} prun;

/* A comparison: group w (with intruder) against group n (without). */
typedef struct cmp {
	int w, n;
	size_t L;
	double *D;                       /* [L] mean line height over both groups' runs */
	rolls_mean *pn, *pw;             /* [L] Phi without, with */
	rolls_diff *pd;                  /* [L] with - without */
	rolls_diff reach, bottom;
	rolls_mean rn, rw, bn, bw;       /* each side's reach and bottom */
	int lines_differ;
	int ok;                          /* both sides have runs with the same lines */
} cmp;

typedef struct rolls_state {
	flux_opts fo;
	double q;
	size_t K;
	prun *pr;        /* [k] */
	rolls_mean *reach, *bottom; /* [ng] */
	double *phimax;  /* [ng] mean phi_max */
	double *bed;     /* [ng] mean settled surface h_s of the used runs: the bed's height */
	long *floor;     /* [ng] runs whose rolls reach the lowest line */
	cmp c[MAXCMP];
	int nc;
	int nocmp;       /* intruder groups without a partner */
} rolls_state;

static void state_free(const an_tool *t, void *vs)
{
	rolls_state *s = vs;
	for (int i = 0; s->pr && i < t->k; i++) {
		free(s->pr[i].phi);
		free(s->pr[i].h);
	}
	for (int c = 0; c < s->nc; c++) {
		free(s->c[c].D);
		free(s->c[c].pn);
		free(s->c[c].pw);
		free(s->c[c].pd);
	}
	free(s->pr);
	free(s->reach);
	free(s->bottom);
	free(s->phimax);
	free(s->floor);
	free(s->bed);
}

/* Run r's profile and reach, and what of it the statistic uses (acct.h). */
static void classify(an_run *r, const rolls_state *s, prun *p)
{
	flux_data fd;
	memset(p, 0, sizeof *p);
	if (fluxrun_load(r, &fd)) {
		if (r->use == AN_UNREADABLE)
			fprintf(stderr, "rolls: warning: %s (counted as unreadable)\n", r->why);
		return;
	}
	const int failed = !strcmp(r->state, "failed");
	const size_t p0 = flux_first(&fd, &s->fo);
	if (p0 >= fd.P || !fd.L) {
		if (failed)
			acct_set(r, AN_UNUSABLE, NAN, NAN, "failed at t = %g s (%s) within the transient: %zu periods recorded,"
				 " the first %zu of the planned %zu are the transient", r->status_time, r->status, fd.P, p0,
				 fd.planned);
		else
			acct_set(r, AN_UNUSABLE, NAN, NAN, "no flux period after the transient (%zu recorded)", fd.P);
		flux_free(&fd);
		return;
	}
	p->L = fd.L;
	p->surface = fd.surface;
	p->phi = malloc(sizeof *p->phi * fd.L);
	p->h = malloc(sizeof *p->h * fd.L);
	if (!p->phi || !p->h) {
		acct_set(r, AN_UNUSABLE, NAN, NAN, "out of memory");
		flux_free(&fd);
		return;
	}
	flux_profile(&fd, &s->fo, p->phi);
	memcpy(p->h, fd.h, sizeof *p->h * fd.L);
	if (rolls_depth(p->h, p->phi, p->L, p->surface, s->q, s->K, &p->rr))
		acct_set(r, AN_UNUSABLE, NAN, NAN, "Phi(D) = 0 on every line after the transient: no rolls to measure");
	else if (failed)
		acct_set(r, AN_PARTLY, fd.t[fd.P - 1], an_num(r, "duration", NAN),
			 "failed at t = %g s (%s): the %zu periods before it used, after the first %zu", r->status_time,
			 r->status, fd.P, p0);
	else
		acct_set(r, AN_USED, NAN, NAN, NULL);
	flux_free(&fd);
}

/* Every fixed-frequency run with flux = yes is considered, whatever its state. */
static int consider(an_tool *t, rolls_state *s)
{
	if (!(s->pr = calloc((size_t)(t->nr ? t->nr : 1), sizeof *s->pr)))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	for (int i = 0; i < t->nr; i++) {
		const char *ramp = an_str(&t->runs[i], "ramp"), *fl = an_str(&t->runs[i], "flux");
		if ((ramp && strcmp(ramp, "none")) || (fl && strcmp(fl, "yes")) || tool_old(t, &t->runs[i]))
			continue;
		prun p;
		classify(&t->runs[i], s, &p);
		s->pr[tool_keep(t, i)] = p;
	}
	return t->k ? 0 : tool_none(t, "fixed-frequency run with flux = yes", "");
}

static double group_ratio(const an_tool *t, int j)
{
	for (int i = 0; i < t->k; i++)
		if (t->runs[i].group == j)
			return an_num(&t->runs[i], "radius_ratio", 0);
	return NAN;
}

/* The group without intruder that agrees with group j in every key but radius_ratio;
 * -1 when none. */
static int partner(const an_tool *t, int j)
{
	for (int p = 0; p < t->ng; p++) {
		if (p == j || !(group_ratio(t, p) == 0))
			continue;
		int same = 1;
		for (int k = 0; k < t->nk && same; k++)
			if (strcmp(t->keys[k], "radius_ratio"))
				same = !strcmp(t->gval[j * t->nk + k], t->gval[p * t->nk + k]);
		if (same)
			return p;
	}
	return -1;
}

/* The reach, bottom, phi_max and surface of group j's used runs into v[0..n) (which = 0 .. 3). */
static size_t group_values(const an_tool *t, const rolls_state *s, int j, int which, double *v)
{
	size_t n = 0;
	for (int i = 0; i < t->k; i++)
		if (t->runs[i].group == j && USED(&t->runs[i]))
			v[n++] = which == 0 ? s->pr[i].rr.reach : which == 1 ? s->pr[i].rr.bottom :
				 which == 2 ? s->pr[i].rr.phi_max : s->pr[i].surface;
	return n;
}

static int groups(an_tool *t, rolls_state *s)
{
	static const char *const always[] = {"frequency", "radius_ratio", NULL};
	static const char *const drop[] = {"ramp", "ramp_from", "ramp_to", NULL};
	if (tool_group(t, always, drop))
		return t->e.code;
	const size_t ng = (size_t)(t->ng > 0 ? t->ng : 1);
	s->reach = calloc(ng, sizeof *s->reach);
	s->bottom = calloc(ng, sizeof *s->bottom);
	s->phimax = calloc(ng, sizeof *s->phimax);
	s->floor = calloc(ng, sizeof *s->floor);
	s->bed = calloc(ng, sizeof *s->bed);
	double *v = malloc(sizeof *v * (size_t)(t->k ? t->k : 1));
	if (!s->reach || !s->bottom || !s->phimax || !s->floor || !s->bed || !v) {
		free(v);
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	}
	for (int j = 0; j < t->ng; j++) {
		size_t n = group_values(t, s, j, 0, v);
		rolls_mean_ci(v, n, t->o->level, &s->reach[j]);
		n = group_values(t, s, j, 1, v);
		rolls_mean_ci(v, n, t->o->level, &s->bottom[j]);
		n = group_values(t, s, j, 2, v);
		rolls_mean m;
		rolls_mean_ci(v, n, t->o->level, &m);
		s->phimax[j] = m.mean;
		n = group_values(t, s, j, 3, v);
		rolls_mean_ci(v, n, t->o->level, &m);
		s->bed[j] = m.mean;
		for (int i = 0; i < t->k; i++)
			s->floor[j] += t->runs[i].group == j && USED(&t->runs[i]) && s->pr[i].rr.to_floor;
	}
	free(v);
	return tool_tally(t, stdout, "its %d fixed-frequency runs with flux = yes", t->k);
}

/* Comparison c of group w against n: reach and bottom differences, the profiles line
 * by line. Lines must be as many in every run (they are the engine's flux_lines). */
static int compare(an_tool *t, rolls_state *s, cmp *c)
{
	const double lev = t->o->level;
	c->L = 0;
	for (int i = 0; i < t->k; i++) {
		const an_run *r = &t->runs[i];
		if (!USED(r) || (r->group != c->w && r->group != c->n))
			continue;
		if (c->L && s->pr[i].L != c->L)
			return 0; /* different line counts: no line-by-line comparison */
		c->L = s->pr[i].L;
	}
	double *a = malloc(sizeof *a * (size_t)(t->k ? t->k : 1)), *b = malloc(sizeof *b * (size_t)(t->k ? t->k : 1));
	c->D = calloc(c->L ? c->L : 1, sizeof *c->D);
	c->pn = calloc(c->L ? c->L : 1, sizeof *c->pn);
	c->pw = calloc(c->L ? c->L : 1, sizeof *c->pw);
	c->pd = calloc(c->L ? c->L : 1, sizeof *c->pd);
	if (!a || !b || !c->D || !c->pn || !c->pw || !c->pd) {
		free(a);
		free(b);
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	}
	size_t na = group_values(t, s, c->w, 0, a), nb = group_values(t, s, c->n, 0, b);
	rolls_welch(a, na, b, nb, lev, &c->reach);
	rolls_mean_ci(a, na, lev, &c->rw);
	rolls_mean_ci(b, nb, lev, &c->rn);
	na = group_values(t, s, c->w, 1, a);
	nb = group_values(t, s, c->n, 1, b);
	rolls_welch(a, na, b, nb, lev, &c->bottom);
	rolls_mean_ci(a, na, lev, &c->bw);
	rolls_mean_ci(b, nb, lev, &c->bn);
	for (size_t l = 0; l < c->L; l++) {
		size_t ka = 0, kb = 0;
		double hs = 0;
		for (int i = 0; i < t->k; i++) {
			const an_run *r = &t->runs[i];
			if (!USED(r) || (r->group != c->w && r->group != c->n))
				continue;
			hs += s->pr[i].h[l];
			if (r->group == c->w)
				a[ka++] = s->pr[i].phi[l];
			else
				b[kb++] = s->pr[i].phi[l];
		}
		c->D[l] = hs / (double)(ka + kb);
		rolls_mean_ci(a, ka, lev, &c->pw[l]);
		rolls_mean_ci(b, kb, lev, &c->pn[l]);
		rolls_welch(a, ka, b, kb, lev, &c->pd[l]);
		c->lines_differ += c->pd[l].lo > 0 || c->pd[l].hi < 0;
	}
	free(a);
	free(b);
	c->ok = c->L > 0;
	return 0;
}

static int comparisons(an_tool *t, rolls_state *s)
{
	for (int j = 0; j < t->ng; j++) {
		if (!(group_ratio(t, j) > 0) || !acct_used(&t->A[j]))
			continue;
		const int p = partner(t, j);
		if (p < 0 || !acct_used(&t->A[p]) || s->nc == MAXCMP) {
			s->nocmp++;
			continue;
		}
		cmp *c = &s->c[s->nc++];
		memset(c, 0, sizeof *c);
		c->w = j;
		c->n = p;
		if (compare(t, s, c))
			return t->e.code;
	}
	return 0;
}

/* rolls_runs.csv: every used run's reach */
static int runs_csv(an_tool *t, const rolls_state *s)
{
	FILE *f = tool_out_open(t, "rolls_runs.csv");
	if (!f)
		return t->e.code;
	fprintf(f, ACCT_ROW_HEAD ",seed,frequency,radius_ratio,surface,phi_max,sign,max_line,roll_bottom,"
		   "reach,to_floor,use,used_s\n");
	for (int j = 0; j < t->ng; j++)
		for (int i = 0; i < t->k; i++) {
			const an_run *r = &t->runs[i];
			const rolls_reach *q = &s->pr[i].rr;
			if (r->group != j || !USED(r))
				continue;
			acct_row_begin(f, r, t->labels);
			fprintf(f, ",%ld,%.17g,%.17g,%.17g,%.17g,%d,%zu,%.17g,%.17g,%d,%s,%.17g\n",
				r->seed, an_num(r, "frequency", NAN), an_num(r, "radius_ratio", 0), s->pr[i].surface, q->phi_max,
				q->sign, q->lmax, q->bottom, q->reach, q->to_floor, acct_use_name(r->use), r->used_s);
		}
	return tool_out_close(t, f);
}

static void ci(char *b, size_t n, double v, double lo, double hi)
{
	snprintf(b, n, "%.3f [%.3f, %.3f]", v, lo, hi);
}

/* An interval of a reach (or a difference of reaches) wider than the bed, hi - lo >
 * the settled surface h_s, tells nothing about the rolls: the words said after it
 * (docs/analysis.md, "rolls"); "" otherwise */
static void too_wide(char *b, size_t n, const char *what, double lo, double hi, double bed)
{
	if (hi - lo > bed)
		snprintf(b, n, "  %s: interval wider than the bed (%.3g cm > h_s = %.3g cm): undecided", what, hi - lo, bed);
	else
		snprintf(b, n, "%s", "");
}

/* Per group: rolls_summary.csv, the table and the stored rows (storing begun here). */
static int summary(an_tool *t, const rolls_state *s)
{
	FILE *sum = tool_summary_csv(t, "rolls_summary.csv",
				     "group,intruder,runs,reach,reach_lo,reach_hi,reach_sd,roll_bottom,roll_bottom_lo,"
				     "roll_bottom_hi,phi_max,to_floor");
	if (!sum)
		return t->e.code;
	printf("%-32s %4s %4s %24s %24s %8s %5s %6s %10s\n", "group", "intr", "used", "reach [CI] (cm below h_s)",
	       "roll bottom D_b [CI] (cm)", "phi_max", "floor", "failed", "unfinished");
	tool_store_begin(t);
	for (int j = 0; j < t->ng && !t->e.code; j++) {
		const rolls_mean *R = &s->reach[j], *B = &s->bottom[j];
		const an_acct *a = &t->A[j];
		const double ratio = group_ratio(t, j);
		char c1[64], c2[64], w1[160], w2[160];
		ci(c1, sizeof c1, R->mean, R->lo, R->hi);
		ci(c2, sizeof c2, B->mean, B->lo, B->hi);
		too_wide(w1, sizeof w1, "reach", R->lo, R->hi, s->bed[j]);
		too_wide(w2, sizeof w2, "roll bottom", B->lo, B->hi, s->bed[j]);
		printf("%-32s %4s %4zu %24s %24s %8.3f %5ld %6ld %10ld%s%s\n", t->labels[j], ratio > 0 ? "yes" : "no", R->n,
		       c1, c2, s->phimax[j], s->floor[j], a->failed, a->n[AN_PENDING] + a->n[AN_RUNNING], w1, w2);
		csv_text(sum, t->labels[j]);
		fprintf(sum, ",%d,%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%ld", ratio > 0, R->n, R->mean, R->lo,
			R->hi, R->sd, B->mean, B->lo, B->hi, s->phimax[j], s->floor[j]);
		tool_summary_acct(t, sum, j);
		const long n = (long)R->n;
		const char *L = t->labels[j];
		tool_store(t, j, L, "runs", (double)n, NAN, NAN, n);
		tool_store(t, j, L, "reach", R->mean, R->lo, R->hi, n);
		tool_store(t, j, L, "roll_bottom", B->mean, B->lo, B->hi, n);
		tool_store(t, j, L, "phi_max", s->phimax[j], NAN, NAN, n);
		tool_store(t, j, L, "to_floor", (double)s->floor[j], NAN, NAN, n);
		tool_store_acct(t, L, j);
	}
	return tool_out_close(t, sum);
}

/* Per comparison: rolls_diff.csv, rolls_profile.csv, the table and the stored rows. */
static int diffs(an_tool *t, const rolls_state *s)
{
	FILE *f = tool_out_open(t, "rolls_diff.csv"), *p = NULL;
	if (f)
		p = tool_out_open(t, "rolls_profile.csv");
	if (!p)
		return tool_out_close(t, f);
	fprintf(f, "comparison,group,partner,runs_with,runs_without,reach_with,reach_without,reach_diff,reach_diff_lo,"
		   "reach_diff_hi,reach_diff_df,roll_bottom_diff,roll_bottom_diff_lo,roll_bottom_diff_hi,lines,lines_differ\n");
	fprintf(p, "comparison,group,line,D,phi_without,phi_without_lo,phi_without_hi,phi_with,phi_with_lo,phi_with_hi,"
		   "diff,diff_lo,diff_hi,runs_with,runs_without\n");
	if (s->nc)
		printf("\n%-32s %9s %26s %26s %8s\n", "with intruder - without", "runs w/wo", "reach diff [CI] (cm)",
		       "roll bottom diff [CI] (cm)", "lines≠0");
	for (int k = 0; k < s->nc; k++) {
		const cmp *c = &s->c[k];
		const char *L = t->labels[c->w];
		char g[600], c1[64], c2[64], w1[160], w2[160];
		snprintf(g, sizeof g, "%s vs no intruder", L);
		ci(c1, sizeof c1, c->reach.d, c->reach.lo, c->reach.hi);
		ci(c2, sizeof c2, c->bottom.d, c->bottom.lo, c->bottom.hi);
		const double bed = fmax(s->bed[c->w], s->bed[c->n]);
		too_wide(w1, sizeof w1, "reach diff", c->reach.lo, c->reach.hi, bed);
		too_wide(w2, sizeof w2, "bottom diff", c->bottom.lo, c->bottom.hi, bed);
		printf("%-32s %4zu/%-4zu %26s %26s %3d of %zu%s%s\n", L, c->rw.n, c->rn.n, c1, c2, c->lines_differ, c->L, w1,
		       w2);
		fprintf(f, "%d,", k);
		csv_text(f, L);
		fputc(',', f);
		csv_text(f, t->labels[c->n]);
		fprintf(f, ",%zu,%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%zu,%d\n", c->rw.n, c->rn.n,
			c->rw.mean, c->rn.mean, c->reach.d, c->reach.lo, c->reach.hi, c->reach.df, c->bottom.d, c->bottom.lo,
			c->bottom.hi, c->L, c->lines_differ);
		for (size_t l = 0; l < c->L; l++) {
			fprintf(p, "%d,", k);
			csv_text(p, L);
			fprintf(p, ",%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%zu,%zu\n", l, c->D[l],
				c->pn[l].mean, c->pn[l].lo, c->pn[l].hi, c->pw[l].mean, c->pw[l].lo, c->pw[l].hi, c->pd[l].d,
				c->pd[l].lo, c->pd[l].hi, c->pw[l].n, c->pn[l].n);
		}
		const long n = (long)(c->rw.n + c->rn.n);
		tool_store(t, c->w, g, "reach_diff", c->reach.d, c->reach.lo, c->reach.hi, n);
		tool_store(t, c->w, g, "roll_bottom_diff", c->bottom.d, c->bottom.lo, c->bottom.hi, n);
		tool_store(t, c->w, g, "lines_differ", c->lines_differ, NAN, NAN, n);
		tool_store(t, c->w, g, "runs_with", (double)c->rw.n, NAN, NAN, (long)c->rw.n);
		tool_store(t, c->w, g, "runs_without", (double)c->rn.n, NAN, NAN, (long)c->rn.n);
	}
	tool_out_close(t, f);
	if (tool_out_close(t, p))
		return t->e.code;
	if (s->nc)
		printf("# differences with - without intruder, Welch intervals at %g %%: the runs with and without intruder"
		       " start from different packings (the driver's seed depends on radius_ratio), so they are independent"
		       " samples; reach diff > 0: the rolls reach deeper with the intruder; lines≠0: lines whose interval of"
		       " the Phi difference excludes 0\n", 100 * t->o->level);
	if (s->nocmp)
		printf("# %d group%s with an intruder without a usable group without one that agrees in every other key (or"
		       " beyond the %d compared): no difference\n", s->nocmp, s->nocmp == 1 ? "" : "s", MAXCMP);
	return t->e.code;
}

/* rolls.png and .pdf: one row per comparison; left Phi(D) of both systems with their
 * bands and roll bottoms, right the difference with its band */
static int plot(an_tool *t, const rolls_state *s)
{
	char script[1400], png[1400], set[512];
	FILE *f = tool_gp_open(t, "rolls", 1100, 300 * s->nc + 110, script, png, sizeof script);
	if (!f)
		return t->e.code;
	tool_setting(t, set, sizeof set);
	fprintf(f, "set multiplot layout %d,2 title \"How deep the convection rolls reach: Φ(D) with and without intruder%s%s\\n"
		   "bands: %g %% CI across seeds (Student; difference: Welch); dashed: mean roll bottom D_b, where Φ falls "
		   "below %g of its largest value\"\n"
		   "set xlabel 'D (cm above the floor)'\nset style fill transparent solid 0.2 noborder\n",
		s->nc, *set ? "\\n" : "", set, 100 * t->o->level, s->q);
	for (int k = 0; k < s->nc; k++) {
		const cmp *c = &s->c[k];
		char leg[512], wv[64], ww[96], title[700];
		tool_legend(t, c->w, 1, leg, sizeof leg);
		snprintf(wv, sizeof wv, "%.17g", group_ratio(t, c->w));
		label_param(ww, sizeof ww, "radius_ratio", wv);
		const int last = k + 1 == s->nc;
		fprintf(f, "%s", last ? "set key below height 1\n" : "unset key\n");
		snprintf(title, sizeof title, "%s: Φ(D)", *leg ? leg : ww);
		fprintf(f, "set title ");
		gp_str(f, title);
		fprintf(f, "\nset ylabel 'Φ (particles per period)'\nunset arrow\n");
		if (isfinite(c->bn.mean))
			fprintf(f, "set arrow 1 from %.17g, graph 0 to %.17g, graph 1 nohead lt 1 dt 2\n", c->bn.mean, c->bn.mean);
		if (isfinite(c->bw.mean))
			fprintf(f, "set arrow 2 from %.17g, graph 0 to %.17g, graph 1 nohead lt 2 dt 2\n", c->bw.mean, c->bw.mean);
		fprintf(f, "plot 'rolls_profile.csv' skip 1 using 4:($1==%d?$6:1/0):7 with filledcurves lt 1 notitle, \\\n"
			   "  '' skip 1 using 4:($1==%d?$5:1/0) with lines lw 2 lt 1 title 'no intruder', \\\n"
			   "  '' skip 1 using 4:($1==%d?$9:1/0):10 with filledcurves lt 2 notitle, \\\n"
			   "  '' skip 1 using 4:($1==%d?$8:1/0) with lines lw 2 lt 2 title ", k, k, k, k);
		gp_str(f, ww);
		fprintf(f, ", \\\n  0 with lines lc 'gray' notitle\n");
		snprintf(title, sizeof title, "difference with − without: reach %+.2f cm [%.2f, %.2f], %d of %zu lines ≠ 0",
			 c->reach.d, c->reach.lo, c->reach.hi, c->lines_differ, c->L);
		fprintf(f, "set title ");
		gp_str(f, title);
		fprintf(f, "\nset ylabel 'ΔΦ (particles per period)'\nunset arrow\n"
			   "plot 'rolls_profile.csv' skip 1 using 4:($1==%d?$12:1/0):13 with filledcurves lt 3 title '%g %% CI (Welch)', \\\n"
			   "  '' skip 1 using 4:($1==%d?$11:1/0) with lines lw 2 lt 3 title 'with − without intruder', \\\n"
			   "  0 with lines lc 'gray' notitle\n", k, 100 * t->o->level, k);
	}
	fprintf(f, "unset multiplot\n");
	if (tool_plot(t, f, script, png))
		return t->e.code;
	printf("# figure: %s (and .pdf, %d comparison%s)\n", png, s->nc, s->nc == 1 ? "" : "s");
	return 0;
}

static int init(an_tool *t, void *vs, const xopt *x)
{
	rolls_state *s = vs;
	s->fo = (flux_opts){t->o->band_lo, t->o->band_hi, t->o->skip};
	s->K = (size_t)t->o->smooth;
	return xopt_num(&x[0], 1e-6, 1, 0.5, &s->q, &t->e);
}

static int run(an_tool *t, void *vs)
{
	rolls_state *s = vs;
	if (consider(t, s) || groups(t, s) || comparisons(t, s) || cli_outdir(t->o, &t->e) || runs_csv(t, s) ||
	    tool_accounting_csv(t) || summary(t, s) || diffs(t, s) || tool_store_end(t))
		return t->e.code;
	tool_report(t, stdout, "the periods they recorded before the failure (after the transient of the run as"
			       " planned): one profile each, like a finished run");
	if (!t->o->no_plot && s->nc && plot(t, s))
		return t->e.code;
	if (!s->nc)
		printf("# no comparison with and without intruder: no figure\n");
	printf("# csv: %s/rolls_{runs,summary,diff,profile,accounting}.csv\n", t->o->out);
	return 0;
}

static const tool_spec SPEC = {.name = "rolls", .version = VERSION, .help = HELP, .allowed = " by skip level smooth ",
			       .x = {{"fraction", 1, NULL, 0}}, .nx = 1, .init = init, .run = run, .fini = state_free};

int main(int argc, char **argv)
{
	rolls_state s = {0};
	return tool_main(argc, argv, &SPEC, &s);
}
