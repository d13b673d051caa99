/* ring_main.c - bin/ring: claim 3 (docs/model.md, "Ring force", "The paper's claims"):
 * do the grains 4.5-8 cm around the intruder feel larger forces than the same grains
 * without it? Per group of runs with the ring, the before-the-rise averages of the
 * mean sum |F|, the mean |net force| and the granular temperature; per group with an
 * intruder, their ratios to the group without it (same other keys) with bootstrap
 * intervals (ring.h). Only this file prints and exits. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "h5read.h"
#include "runfile.h"
#include "common/acct.h"
#include "common/adb.h"
#include "common/cli.h"
#include "common/label.h"
#include "common/tool.h"
#include "measure/ring.h"

#define VERSION "1"

#define USED(r) ((r)->use == AN_USED || (r)->use == AN_PARTLY)

/* the quantities: /ring attributes (before the rise), keys of the stored rows, words */
enum { NQ = 3 };
static const char *const ATTR[NQ] = {"mean_force_before", "net_force_before", "temperature_before"};
static const char *const KEY[NQ] = {"force", "net_force", "temperature"};
static const char *const WORDS[NQ] = {"⟨Σ|F|⟩ ratio (contact forces)", "⟨|ΣF + m g|⟩ ratio (net force)",
				      "granular temperature ratio"};

static const char HELP[] =
	"usage: ring CAMPAIGN [--db FILE] [--runs DIR] [--out DIR] [--by KEYS] [--boot N] [--seed S]\n"
	"            [--level L] [--all-versions] [--no-plot] [--no-store]\n\n"
	"Claim 3 of the paper: the grains in a ring around the intruder (4.5-8 cm from its centre)\n"
	"feel about 15 % higher forces than the same grains without the intruder. The campaign\n"
	"holds runs with the ring (ring = yes) with an intruder (radius_ratio > 0) and without\n"
	"(radius_ratio = 0), the ring around the same place (ring_centre = settled: where the\n"
	"intruder settled; without one, ring_x and ring_y). Each run's numbers are its averages\n"
	"before the rise (docs/model.md, \"Ring force\"; the /ring attributes *_before: the\n"
	"samples from ring_from until the intruder rose, ring_until or the end):\n"
	"  force        mean over the ring's grains of the sum of their contact forces'\n"
	"               magnitudes, sum |F| (dominated by the weight of the grains above)\n"
	"  net_force    mean magnitude of each grain's net force |sum F + m g| (lab frame:\n"
	"               m times its acceleration; the paper speaks of accelerations)\n"
	"  temperature  the granular temperature in the ring\n"
	"A run whose intruder did not rise is used over its whole run and counted as censored.\n"
	"Per group (radius_ratio and every swept axis, e.g. frequency): the mean of each over\n"
	"its runs; per group with an intruder, the ratio of its mean to that of the group\n"
	"without intruder with the same other keys, with a bootstrap percentile interval\n"
	"(the runs of each group resampled apart: the two are different systems).\n\n"
	"No run is dropped silently: per group the table, ring_summary.csv and the stored rows\n"
	"count the runs used, censored, failed by status (used up to the failure, or\n"
	"unusable), unreadable, pending or running; ring_accounting.csv says why for each run.\n\n"
	"  --db FILE     campaign database (default RUNS/study.db)\n"
	"  --runs DIR    where outputs are, as RUNS/CAMPAIGN/RUN-ID.h5 (default: the\n"
	"                database's directory, or runs)\n"
	"  --out DIR     CSV, gnuplot scripts and figures (default RUNS/CAMPAIGN/analysis)\n"
	"  --by KEYS     group by these parameters (comma separated; must include\n"
	"                radius_ratio; default radius_ratio and every swept axis)\n"
	"  --boot N      bootstrap replicates (default 1000)\n"
	"  --seed S      bootstrap seed (default 1)\n"
	"  --level L     confidence level (default 0.95)\n"
	"  --all-versions  also the runs of earlier versions of the campaign file\n"
	"  --no-plot     no figure;  --no-store  nothing written to the database\n\n"
	"Writes ring_runs.csv, ring_summary.csv, ring_ratios.csv, ring_accounting.csv and\n"
	"ring.png/.pdf (the ratios against the frequency with their intervals, the paper's\n"
	"+15 % marked); stores per group in the table `analysis` (tool 'ring'): runs (used),\n"
	"runs_censored, force, net_force, temperature (means, lo, hi), centre_y, and for a\n"
	"group with an intruder ratio_force, ratio_net_force, ratio_temperature (lo, hi; n =\n"
	"its runs used), with the accounting rows (runs_failed, ...; onset --help lists them).\n"
	"Options take their value as --opt VALUE or --opt=VALUE.\n";

/* What ring reads of each considered run (index as t->runs after tool_keep). */
typedef struct rrun {
	double v[NQ];       /* the before-the-rise averages */
	double samples;     /* ring samples in the window */
	double from, to;    /* the window */
	double centre_y;    /* a fixed centre's height (NaN when it followed the intruder) */
	int risen;          /* with an intruder: 1 risen, 0 not (censored) */
} rrun;

typedef struct ring_state {
	rrun *rr;           /* [k] */
	int *ref;           /* [ng] the group without intruder that group j is compared with, or -1 */
	int *nused, *ncens; /* [ng] */
	double **val;       /* [ng] the used runs' values, [NQ * nused] */
	double *freq;       /* [ng] the groups' frequency (mean over the runs; NaN when none) */
	double *cy;         /* [ng] mean centre height of the used runs */
	ring_est (*mean)[NQ], (*ratio)[NQ]; /* [ng] */
	int *curve;         /* [ng] curve index of a group with an intruder (figure), -1 */
	int ncurve;
} ring_state;

static void state_free(const an_tool *t, void *vs)
{
	ring_state *s = vs;
	for (int j = 0; s->val && j < t->ng; j++)
		free(s->val[j]);
	free(s->val);
	free(s->rr);
	free(s->ref);
	free(s->nused);
	free(s->ncens);
	free(s->freq);
	free(s->cy);
	free(s->mean);
	free(s->ratio);
	free(s->curve);
}

static int is_intruder(const an_run *r) { return an_num(r, "radius_ratio", 0) > 0; }

/* Reads run r's /ring averages before the rise and says what of it is used. */
static void classify(an_run *r, rrun *x)
{
	for (int q = 0; q < NQ; q++)
		x->v[q] = NAN;
	x->samples = x->from = x->to = x->centre_y = NAN;
	x->risen = 0;
	if (acct_classify(r))
		return;
	hid_t h;
	sb_err he = {0};
	double rs = 0;
	if (h5r_open(r->path, &h, &he)) {
		acct_set(r, AN_UNREADABLE, NAN, NAN, "%s", he.msg);
		fprintf(stderr, "ring: warning: %s (counted as unreadable)\n", r->why);
		return;
	}
	int missing = !h5r_exists(h, RUNFILE_RING) || h5r_attr_num(h, RUNFILE_RING, "samples_before", &x->samples) ||
		      h5r_attr_num(h, RUNFILE_RING, "before_from", &x->from) || h5r_attr_num(h, RUNFILE_RING, "before_to", &x->to);
	for (int q = 0; q < NQ && !missing; q++)
		missing = h5r_attr_num(h, RUNFILE_RING, ATTR[q], &x->v[q]) || !isfinite(x->v[q]);
	h5r_attr_num(h, RUNFILE_RING, "centre_y", &x->centre_y);
	const int has_rise = h5r_attr_num(h, "/", "risen", &rs) == 0;
	h5r_close(h);
	x->risen = rs != 0;
	const int failed = !strcmp(r->state, "failed");
	if (has_rise && rs != 0 && rs != 1) /* a NaN would count as risen */
		acct_set(r, AN_UNUSABLE, NAN, NAN, "%s: risen = %g: expected 0 or 1", r->path, rs);
	else if (missing)
		acct_set(r, AN_UNUSABLE, NAN, NAN, "%s: no before-the-rise ring averages (/ring *_before)%s", r->path,
			 failed ? ": failed before the shaking" : "");
	else if (!(x->samples > 0))
		acct_set(r, AN_UNUSABLE, NAN, NAN, "no ring sample before the rise (window %g .. %g s)", x->from, x->to);
	else if (failed)
		acct_set(r, AN_PARTLY, fmax(0, x->to - x->from), an_num(r, "duration", NAN),
			 "failed at t = %g s (%s): its ring samples before then are used", x->to, r->status);
	else
		acct_set(r, AN_USED, NAN, NAN, NULL);
}

/* Every run with the ring is considered, whatever its state. */
static int consider(an_tool *t, ring_state *s)
{
	if (!(s->rr = calloc((size_t)(t->nr ? t->nr : 1), sizeof *s->rr)))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	for (int i = 0; i < t->nr; i++) {
		an_run *r = &t->runs[i];
		const char *ring = an_str(r, "ring");
		if (!ring || strcmp(ring, "yes") || tool_old(t, r))
			continue;
		rrun x;
		classify(r, &x);
		s->rr[tool_keep(t, i)] = x;
	}
	return t->k ? 0 : tool_none(t, "run with the ring (ring = yes)", "");
}

/* The group without intruder whose other keys equal group j's, or -1. */
static int reference(const an_tool *t, int j, int kr)
{
	for (int g = 0; g < t->ng; g++) {
		if (g == j || strtod(t->gval[g * t->nk + kr], NULL) != 0)
			continue;
		int same = 1;
		for (int k = 0; k < t->nk && same; k++)
			same = k == kr || !strcmp(t->gval[g * t->nk + k], t->gval[j * t->nk + k]);
		if (same)
			return g;
	}
	return -1;
}

/* Groups, their used runs' values, the references and the figure's curves (the
 * groups with an intruder alike in every key but the frequency). */
static int groups(an_tool *t, ring_state *s)
{
	static const char *const always[] = {"radius_ratio", NULL};
	if (tool_group(t, always, NULL))
		return t->e.code;
	int kr = -1, kf = -1;
	for (int k = 0; k < t->nk; k++) {
		kr = strcmp(t->keys[k], "radius_ratio") ? kr : k;
		kf = strcmp(t->keys[k], "frequency") ? kf : k;
	}
	if (kr < 0)
		return sb_errf(&t->e, SB_EUSAGE, "--by must include radius_ratio (the runs with and without intruder)");
	const size_t ng = (size_t)(t->ng ? t->ng : 1);
	s->ref = malloc(sizeof *s->ref * ng);
	s->curve = malloc(sizeof *s->curve * ng);
	s->nused = calloc(ng, sizeof *s->nused);
	s->ncens = calloc(ng, sizeof *s->ncens);
	s->val = calloc(ng, sizeof *s->val);
	s->freq = calloc(ng, sizeof *s->freq);
	s->cy = calloc(ng, sizeof *s->cy);
	s->mean = calloc(ng, sizeof *s->mean);
	s->ratio = calloc(ng, sizeof *s->ratio);
	if (!s->ref || !s->curve || !s->nused || !s->ncens || !s->val || !s->freq || !s->cy || !s->mean || !s->ratio)
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	if (tool_tally(t, stdout, "its %d runs with the ring", t->k))
		return t->e.code;
	int *nf = calloc(ng, sizeof *nf);
	if (!nf)
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	for (int i = 0; i < t->k; i++) {
		const an_run *r = &t->runs[i];
		const int j = r->group;
		const double f = an_num(r, "frequency", NAN);
		if (isfinite(f)) {
			s->freq[j] += f;
			nf[j]++;
		}
		if (USED(r)) {
			s->nused[j]++;
			s->ncens[j] += is_intruder(r) && !s->rr[i].risen;
		}
	}
	for (int j = 0; j < t->ng; j++) {
		s->freq[j] = nf[j] ? s->freq[j] / nf[j] : NAN;
		s->ref[j] = strtod(t->gval[j * t->nk + kr], NULL) > 0 ? reference(t, j, kr) : -1;
		if (!(s->val[j] = malloc(sizeof(double) * NQ * (size_t)(s->nused[j] ? s->nused[j] : 1)))) {
			free(nf);
			return sb_errf(&t->e, SB_ENOMEM, "out of memory");
		}
		nf[j] = 0; /* now: the used runs placed so far */
	}
	for (int i = 0; i < t->k; i++) {
		const an_run *r = &t->runs[i];
		const int j = r->group;
		if (!USED(r))
			continue;
		for (int q = 0; q < NQ; q++)
			s->val[j][q * s->nused[j] + nf[j]] = s->rr[i].v[q];
		s->cy[j] += s->rr[i].centre_y;
		nf[j]++;
	}
	free(nf);
	/* the curves: groups with an intruder whose keys other than the frequency agree */
	s->ncurve = 0;
	for (int j = 0; j < t->ng; j++) {
		s->cy[j] = s->nused[j] ? s->cy[j] / s->nused[j] : NAN;
		s->curve[j] = -1;
		if (strtod(t->gval[j * t->nk + kr], NULL) <= 0)
			continue;
		for (int g = 0; g < j && s->curve[j] < 0; g++) {
			int same = s->curve[g] >= 0;
			for (int k = 0; k < t->nk && same; k++)
				same = k == kf || !strcmp(t->gval[g * t->nk + k], t->gval[j * t->nk + k]);
			if (same)
				s->curve[j] = s->curve[g];
		}
		if (s->curve[j] < 0)
			s->curve[j] = s->ncurve++;
	}
	return 0;
}

/* The means per group and the ratios to the references. */
static int estimate(an_tool *t, ring_state *s)
{
	const an_opts *o = t->o;
	for (int j = 0; j < t->ng; j++) {
		if (ring_ratio(s->val[j], (size_t)s->nused[j], NULL, 0, NQ, (size_t)o->boot, o->seed, o->level, s->mean[j]))
			return sb_errf(&t->e, SB_ENOMEM, "out of memory");
		const int g = s->ref[j];
		if (g < 0) {
			for (int q = 0; q < NQ; q++)
				s->ratio[j][q] = (ring_est){NAN, NAN, NAN, 0};
			continue;
		}
		if (ring_ratio(s->val[j], (size_t)s->nused[j], s->val[g], (size_t)s->nused[g], NQ, (size_t)o->boot, o->seed,
			       o->level, s->ratio[j]))
			return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	}
	return 0;
}

/* ring_runs.csv: every considered run's numbers and use */
static int runs_csv(an_tool *t, const ring_state *s)
{
	FILE *f = tool_out_open(t, "ring_runs.csv");
	if (!f)
		return t->e.code;
	fprintf(f, ACCT_ROW_HEAD ",seed,state,use,risen,samples_before,before_from,before_to,"
		   "force,net_force,temperature,centre_y\n");
	for (int i = 0; i < t->k; i++) {
		const an_run *r = &t->runs[i];
		const rrun *x = &s->rr[i];
		acct_row_begin(f, r, t->labels);
		fprintf(f, ",%ld,%s,%s,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", r->seed,
			r->state, acct_use_name(r->use), is_intruder(r) ? x->risen : 0, x->samples, x->from, x->to, x->v[0],
			x->v[1], x->v[2], x->centre_y);
	}
	return tool_out_close(t, f);
}

static void ci_text(char *buf, size_t n, const ring_est *e)
{
	if (isnan(e->value))
		snprintf(buf, n, "-");
	else if (isnan(e->lo))
		snprintf(buf, n, "%.3f [-, -]", e->value);
	else
		snprintf(buf, n, "%.3f [%.3f, %.3f]", e->value, e->lo, e->hi);
}

/* Group j: its table row, its summary row and its stored rows. */
static void group_out(an_tool *t, const ring_state *s, int j, FILE *sum)
{
	const char *L = t->labels[j];
	const an_acct *a = &t->A[j];
	const long n = s->nused[j];
	char c[NQ][64];
	for (int q = 0; q < NQ; q++)
		ci_text(c[q], sizeof c[q], &s->ratio[j][q]);
	printf("%-32s %4ld %4d %11.5g %11.5g %9.4g %23s %23s %23s %6.2f %6ld %10ld\n", L, n, s->ncens[j],
	       s->mean[j][0].value, s->mean[j][1].value, s->mean[j][2].value, c[0], c[1], c[2], s->cy[j], a->failed,
	       a->n[AN_PENDING] + a->n[AN_RUNNING]);
	csv_text(sum, L);
	fputc(',', sum);
	csv_text(sum, s->ref[j] >= 0 ? t->labels[s->ref[j]] : "");
	fprintf(sum, ",%.17g,%ld,%d", s->freq[j], n, s->ncens[j]);
	for (int q = 0; q < NQ; q++)
		fprintf(sum, ",%.17g,%.17g,%.17g", s->mean[j][q].value, s->mean[j][q].lo, s->mean[j][q].hi);
	for (int q = 0; q < NQ; q++)
		fprintf(sum, ",%.17g,%.17g,%.17g", s->ratio[j][q].value, s->ratio[j][q].lo, s->ratio[j][q].hi);
	fprintf(sum, ",%.17g", s->cy[j]);
	tool_summary_acct(t, sum, j);
	tool_store(t, j, L, "runs", (double)n, NAN, NAN, n);
	tool_store(t, j, L, "runs_censored", (double)s->ncens[j], NAN, NAN, n);
	for (int q = 0; q < NQ; q++)
		tool_store(t, j, L, KEY[q], s->mean[j][q].value, s->mean[j][q].lo, s->mean[j][q].hi, n);
	tool_store(t, j, L, "centre_y", s->cy[j], NAN, NAN, n);
	if (s->ref[j] >= 0) {
		char key[64];
		for (int q = 0; q < NQ; q++) {
			snprintf(key, sizeof key, "ratio_%s", KEY[q]);
			tool_store(t, j, L, key, s->ratio[j][q].value, s->ratio[j][q].lo, s->ratio[j][q].hi, n);
		}
	}
	tool_store_acct(t, L, j);
}

/* ring_summary.csv, the table and the stored rows (storing begun here, ended by the
 * caller). */
static int summary(an_tool *t, const ring_state *s)
{
	FILE *sum = tool_summary_csv(t, "ring_summary.csv",
				     "group,reference,frequency,runs,runs_censored,force,force_lo,force_hi,net_force,"
				     "net_force_lo,net_force_hi,temperature,temperature_lo,temperature_hi,ratio_force,"
				     "ratio_force_lo,ratio_force_hi,ratio_net_force,ratio_net_force_lo,ratio_net_force_hi,"
				     "ratio_temperature,ratio_temperature_lo,ratio_temperature_hi,centre_y");
	if (!sum)
		return t->e.code;
	printf("%-32s %4s %4s %11s %11s %9s %23s %23s %23s %6s %6s %10s\n", "group", "used", "cens", "sum|F| dyn",
	       "|net F| dyn", "T cm2/s2", "ratio sum|F| [CI]", "ratio |net F| [CI]", "ratio T [CI]", "y_c cm", "failed",
	       "unfinished");
	tool_store_begin(t);
	for (int j = 0; j < t->ng && !t->e.code; j++)
		group_out(t, s, j, sum);
	return tool_out_close(t, sum);
}

/* The closing lines: the accounting, what censored means here, groups without a
 * reference and rings that were not around the same place. */
static void report(const an_tool *t, const ring_state *s)
{
	tool_report(t, stdout, "their ring samples before the failure");
	long cens = 0;
	for (int j = 0; j < t->ng; j++)
		cens += s->ncens[j];
	if (cens)
		printf("# %ld run%s with an intruder that did not rise (censored) enter%s with the whole run as "
		       "\"before the rise\"\n", cens, cens == 1 ? "" : "s", cens == 1 ? "s" : "");
	for (int j = 0; j < t->ng; j++) {
		if (s->curve[j] >= 0 && s->ref[j] < 0)
			printf("# %s: no group without intruder with the same other keys: no ratio\n", t->labels[j]);
		const int g = s->ref[j];
		if (g >= 0 && isfinite(s->cy[j]) && isfinite(s->cy[g]) && fabs(s->cy[j] - s->cy[g]) > 0.5)
			printf("# %s: the ring's centre is %.2f cm high with the intruder, %.2f cm without (%s): not the "
			       "same grains; set ring_y to where the intruder settles\n", t->labels[j], s->cy[j], s->cy[g],
			       t->labels[g]);
	}
}

/* ring_ratios.csv (the figure's data): curve, quantity, frequency, ratio, lo, hi */
static int ratios_csv(an_tool *t, const ring_state *s)
{
	FILE *f = tool_out_open(t, "ring_ratios.csv");
	if (!f)
		return t->e.code;
	fprintf(f, "curve,quantity,frequency,ratio,lo,hi,group\n");
	for (int j = 0; j < t->ng; j++)
		for (int q = 0; q < NQ && s->ref[j] >= 0; q++) {
			fprintf(f, "%d,%d,%.17g,%.17g,%.17g,%.17g,", s->curve[j], q, s->freq[j], s->ratio[j][q].value,
				s->ratio[j][q].lo, s->ratio[j][q].hi);
			csv_text(f, t->labels[j]);
			fputc('\n', f);
		}
	return tool_out_close(t, f);
}

/* The legend of curve c: the keys other than the frequency whose values differ
 * between the curves ("" with one curve). */
static void curve_legend(const an_tool *t, const ring_state *s, int c, char *buf, size_t n)
{
	buf[0] = 0;
	if (s->ncurve >= 2)
		tool_curve_legend(t, s->curve, sizeof *s->curve, s->ncurve, "frequency", c, 1, buf, n);
}

/* ring.png and .pdf: the three ratios against the frequency with their intervals
 * (slightly apart, so the bars do not hide each other), no change and the paper's
 * +15 % marked */
static int plot(an_tool *t, const ring_state *s)
{
	char script[1400], png[1400], set[512];
	double flo = INFINITY, fhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
	int any = 0;
	for (int j = 0; j < t->ng; j++)
		for (int q = 0; q < NQ && s->ref[j] >= 0; q++) {
			const ring_est *e = &s->ratio[j][q];
			if (!isfinite(e->value) || !isfinite(s->freq[j]))
				continue;
			any = 1;
			flo = fmin(flo, s->freq[j]);
			fhi = fmax(fhi, s->freq[j]);
			ylo = fmin(ylo, isfinite(e->lo) ? e->lo : e->value);
			yhi = fmax(yhi, isfinite(e->hi) ? e->hi : e->value);
		}
	if (!any) {
		printf("# no ratio to draw: no figure\n");
		return 0;
	}
	const double span = fhi > flo ? fhi - flo : 0.2, dx = 0.012 * span;
	ylo = fmin(ylo, 0.95);
	yhi = fmax(yhi, 1.2);
	FILE *f = tool_gp_open(t, "ring", 900, 600, script, png, sizeof script);
	if (!f)
		return t->e.code;
	tool_setting(t, set, sizeof set);
	const double rin = an_num(&t->runs[0], "ring_inner", 4.5), rout = an_num(&t->runs[0], "ring_outer", 8);
	fprintf(f,
		"set title \"Claim 3: grains %g–%g cm from the intruder, with / without it, before the rise\\n%s%s"
		"bars: %g %% bootstrap intervals over runs\"\n"
		"set ylabel 'with intruder / without'\n"
		"set xrange [%.17g:%.17g]\nset yrange [%.17g:%.17g]\nset key below\n"
		"set arrow from graph 0, first 1 to graph 1, first 1 nohead lc rgb 'gray50' lw 1\n"
		"set arrow from graph 0, first 1.15 to graph 1, first 1.15 nohead lc rgb 'black' dt 2 lw 1.5\n"
		"set label 'paper: +15 %%' at graph 0.01, first 1.15 offset 0, 0.6 font ',9'\n"
		"set label 'no change' at graph 0.01, first 1 offset 0, -0.8 font ',9' tc rgb 'gray40'\n",
		rin, rout, set, *set ? "; " : "", 100 * t->o->level, flo - 0.15 * span, fhi + 0.15 * span,
		ylo - 0.05 * (yhi - ylo), yhi + 0.08 * (yhi - ylo));
	gp_xlabel(f, "frequency");
	double A, g;
	if (tool_gamma(t, &A, &g))
		gp_gamma_axis(f, A, g, flo - 0.15 * span, fhi + 0.15 * span);
	fputs("plot ", f);
	static const int pt[NQ] = {7, 5, 9};
	int np = 0;
	for (int c = 0; c < s->ncurve; c++) {
		char leg[256], title[512];
		curve_legend(t, s, c, leg, sizeof leg);
		for (int q = 0; q < NQ; q++) {
			snprintf(title, sizeof title, "%s%s%s", WORDS[q], *leg ? ", " : "", leg);
			fprintf(f,
				"%s'ring_ratios.csv' skip 1 using ($3+%.17g):($1==%d&&$2==%d?$4:1/0):5:6 with yerrorlines "
				"lt %d pt %d ps 1.3 lw 1.5 title ",
				np++ ? ", \\\n  " : "", (q - 1) * dx, c, q, q + 1 + NQ * c, pt[q]);
			gp_str(f, title);
		}
	}
	fprintf(f, "\n");
	if (tool_plot(t, f, script, png))
		return t->e.code;
	/* the figure line only for a figure written (not after "no ratio to draw") */
	printf("# figure: %s/ring.{png,pdf}\n", t->o->out);
	return 0;
}

static int run(an_tool *t, void *vs)
{
	ring_state *s = vs;
	if (consider(t, s) || groups(t, s) || cli_outdir(t->o, &t->e) || estimate(t, s) || runs_csv(t, s) ||
	    tool_accounting_csv(t) || ratios_csv(t, s) || summary(t, s) || tool_store_end(t))
		return t->e.code;
	report(t, s);
	if (!t->o->no_plot && plot(t, s))
		return t->e.code;
	printf("# csv: %s/ring_{runs,summary,ratios,accounting}.csv\n", t->o->out);
	return 0;
}

static const tool_spec SPEC = {.name = "ring", .version = VERSION, .help = HELP, .allowed = " by boot seed level ",
			       .run = run, .fini = state_free};

int main(int argc, char **argv)
{
	ring_state s = {0};
	return tool_main(argc, argv, &SPEC, &s);
}
