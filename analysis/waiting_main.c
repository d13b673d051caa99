/* waiting_main.c - bin/waiting: waiting times of the intruder's rise per group of runs
 * (Kaplan-Meier with right-censoring, median with its Brookmeyer-Crowley interval,
 * fraction risen, histogram). Only this file prints and exits. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acct.h"
#include "adb.h"
#include "cli.h"
#include "h5read.h"
#include "km.h"
#include "logrank.h"
#include "tool.h"

#define VERSION "2"

/* a run whose observation is in the statistic: finished, or failed and observed up to it */
#define USED(r) ((r)->use == AN_USED || (r)->use == AN_PARTLY)

static const char *HELP =
	"usage: waiting CAMPAIGN [--db FILE] [--runs DIR] [--out DIR] [--by KEYS] [--level L]\n"
	"               [--bins N] [--all-versions] [--no-plot] [--no-store]\n\n"
	"Waiting time of the intruder's rise (docs/model.md: first time its centre is one intruder\n"
	"diameter above its settled height; a run that ends first is right-censored at the\n"
	"time it observed), read from the root attributes `risen` and `waiting_time` of each\n"
	"run with an intruder (radius_ratio > 0). A run that failed is observed up to its\n"
	"failure: risen before it, an event at its waiting time; else censored at the time of\n"
	"the failure (this assumes that the failure is independent of the rise; the output\n"
	"says how many runs it concerns).\n"
	"Per group of runs: Kaplan-Meier survival S(t), the median (first t with S <= 0.5)\n"
	"with its Brookmeyer-Crowley interval (Greenwood errors, plain band), the fraction\n"
	"risen by the end, and a histogram of the observed waiting times.\n\n"
	"No run is dropped silently: per group the table, waiting_summary.csv and the stored\n"
	"rows count the runs used, the failed ones by status (used up to the failure, or\n"
	"unusable: without an output file, or failed before the shaking began), the unreadable\n"
	"files and the runs still pending or running (the campaign is not finished: the output\n"
	"says so); waiting_accounting.csv has one row per run with what became of it and why.\n\n"
	"  --db FILE     campaign database (default RUNS/study.db)\n"
	"  --runs DIR    where outputs are, as RUNS/CAMPAIGN/RUN-ID.h5 (default: the\n"
	"                database's directory, or runs)\n"
	"  --out DIR     CSV, gnuplot scripts and PNG (default RUNS/CAMPAIGN/analysis)\n"
	"  --by KEYS     group by these parameters (comma separated; default radius_ratio\n"
	"                and every swept axis of the campaign)\n"
	"  --level L     confidence level (default 0.95)\n"
	"  --bins N      histogram bins over [0, longest observation] (default 10)\n"
	"  --all-versions  also the runs of earlier versions of the campaign file\n"
	"                (run.current = 0, kept by study run --keep-old); by default the\n"
	"                current grid's\n"
	"  --no-plot     no figures;  --no-store  nothing written to the database\n\n"
	"Writes waiting_runs.csv, waiting_km.csv, waiting_summary.csv, waiting_hist.csv,\n"
	"waiting_accounting.csv, waiting_km_band.csv, waiting_km.png/.pdf (with the\n"
	"confidence band), waiting_hist.png/.pdf; stores per group in the\n"
	"table `analysis` (tool 'waiting'): runs (used), risen, fraction_risen, median (lo,\n"
	"hi), t_max, s_end (lo, hi), and the accounting (runs_failed, runs_failed_used, ...,\n"
	"as onset --help lists).\n"
	"Options take their value as --opt VALUE or --opt=VALUE. Figures are written as PNG\n"
	"and PDF (vector) with their gnuplot scripts. A stored row has its group's value of\n"
	"each grouping key in that key's column (radius_ratio, depth, ...; analysis/README.md).\n"
	"Exit codes: 0 ok, 1 usage or no usable runs, 2 I/O.\n";

typedef struct grp {
	int n, cap;
	double *t;
	int *ev;
	long *run;
} grp;

static int push(grp *g, double t, int ev, long run)
{
	if (g->n == g->cap) {
		g->cap = g->cap ? 2 * g->cap : 16;
		double *a = realloc(g->t, sizeof *a * (size_t)g->cap);
		if (a)
			g->t = a;
		int *b = realloc(g->ev, sizeof *b * (size_t)g->cap);
		if (b)
			g->ev = b;
		long *c = realloc(g->run, sizeof *c * (size_t)g->cap);
		if (c)
			g->run = c;
		if (!a || !b || !c)
			return -1;
	}
	g->t[g->n] = t;
	g->ev[g->n] = ev;
	g->run[g->n++] = run;
	return 0;
}

static double zq(double level)
{
	/* normal quantile by bisection on erfc; level in [0.5, 0.999] */
	double lo = 0, hi = 10, p = 1 - level;
	for (int i = 0; i < 100; i++) {
		double m = 0.5 * (lo + hi);
		if (erfc(m / sqrt(2)) > p)
			lo = m;
		else
			hi = m;
	}
	return 0.5 * (lo + hi);
}

/* What waiting computes besides the frame: the observation of every considered run,
 * the used ones' times and events per group, their survival curves. */
typedef struct wait_state {
	double *wt;         /* [k] the time considered run i was observed to or rose at */
	int *risen;         /* [k] 1 when it rose (an event), 0 when censored */
	grp *g;             /* [ng] the used runs' times and events */
	km_curve *km;       /* [ng] */
	double z;           /* normal quantile of the level */
	double tmax;        /* the longest observation of all groups */
	double bw;          /* histogram bin width */
	long f_ev, f_cens;  /* failed runs used: risen before the failure, censored at it */
} wait_state;

static void state_free(const an_tool *t, wait_state *s)
{
	for (int j = 0; s->g && j < t->ng; j++) {
		free(s->g[j].t);
		free(s->g[j].ev);
		free(s->g[j].run);
		if (s->km)
			km_free(&s->km[j]);
	}
	free(s->g);
	free(s->km);
	free(s->wt);
	free(s->risen);
}

/* Reads run r's rise (*rs: risen, *w: waiting time) and says what of it the statistic
 * uses (acct.h): a failed run was observed up to its failure. */
static void classify(an_run *r, double *rs, double *w, wait_state *s)
{
	double st = NAN;
	if (acct_classify(r))
		return;
	hid_t h;
	sb_err he = {0};
	if (h5r_open(r->path, &h, &he))
		acct_set(r, AN_UNREADABLE, NAN, NAN, "%s", he.msg);
	else {
		if (h5r_attr_num(h, "/", "risen", rs) || h5r_attr_num(h, "/", "waiting_time", w) || !(*w >= 0) ||
		    !isfinite(*w))
			acct_set(r, AN_UNREADABLE, NAN, NAN, "%s: no valid root attributes risen, waiting_time", r->path);
		h5r_attr_num(h, "/", "status_time", &st);
		h5r_close(h);
	}
	if (r->use == AN_UNREADABLE)
		fprintf(stderr, "waiting: warning: %s (counted as unreadable)\n", r->why);
	else if (strcmp(r->state, "failed"))
		acct_set(r, AN_USED, NAN, NAN, NULL);
	else if (!(*w > 0))
		acct_set(r, AN_UNUSABLE, NAN, NAN, "failed before the shaking began (%s)", r->status);
	else {
		/* observed up to the failure: a rise before it is an event, else the run is
		 * censored when it failed */
		if (!isfinite(st))
			st = isfinite(r->status_time) ? r->status_time : *w;
		acct_set(r, AN_PARTLY, *rs != 0 ? st : *w, an_num(r, "duration", NAN),
			 *rs != 0 ? "failed at t = %g s (%s) after the rise at %g s: an event"
				  : "failed at t = %g s (%s) before any rise: censored at %g s",
			 st, r->status, *w);
		if (*rs != 0)
			s->f_ev++;
		else
			s->f_cens++;
	}
}

/* Every run with an intruder is considered, whatever its state. */
static int consider(an_tool *t, wait_state *s)
{
	s->wt = calloc((size_t)(t->nr ? t->nr : 1), sizeof *s->wt);
	s->risen = calloc((size_t)(t->nr ? t->nr : 1), sizeof *s->risen);
	if (!s->wt || !s->risen)
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	for (int i = 0; i < t->nr; i++) {
		an_run *r = &t->runs[i];
		if (!(an_num(r, "radius_ratio", 0) > 0) || tool_old(t, r))
			continue;
		double rs = NAN, w = NAN;
		classify(r, &rs, &w, s);
		const int k = tool_keep(t, i);
		s->wt[k] = w;
		s->risen[k] = rs != 0 && !isnan(rs);
	}
	return t->k ? 0 : tool_none(t, "run with an intruder", "");
}

/* Groups the considered runs; each used one's time and event joins its group. */
static int groups(an_tool *t, wait_state *s)
{
	static const char *const always[] = {"radius_ratio", NULL};
	if (tool_group(t, always, NULL))
		return t->e.code;
	s->g = calloc((size_t)(t->ng > 0 ? t->ng : 1), sizeof *s->g);
	s->km = calloc((size_t)(t->ng > 0 ? t->ng : 1), sizeof *s->km);
	if (!s->g || !s->km)
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	if (tool_tally(t, stdout, "its %d runs with an intruder", t->k))
		return t->e.code;
	for (int i = 0; i < t->k; i++)
		if (USED(&t->runs[i]) && push(&s->g[t->runs[i].group], s->wt[i], s->risen[i], i))
			return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	return 0;
}

/* Each group's Kaplan-Meier curve, and the longest observation. */
static int fit(an_tool *t, wait_state *s)
{
	s->z = zq(t->o->level);
	s->tmax = 0;
	for (int j = 0; j < t->ng; j++) {
		if (km_fit(s->g[j].t, s->g[j].ev, (size_t)s->g[j].n, &s->km[j]))
			return sb_errf(&t->e, SB_EIO, "group %s: bad waiting times", t->labels[j]);
		for (int i = 0; i < s->g[j].n; i++)
			s->tmax = fmax(s->tmax, s->g[j].t[i]);
	}
	s->bw = s->tmax > 0 ? s->tmax / (double)t->o->bins : 1;
	return 0;
}

/* waiting_runs.csv: each used run's time and event */
static int runs_csv(an_tool *t, const wait_state *s)
{
	char path[1400];
	FILE *f = cli_fopen(t->o, "waiting_runs.csv", path, sizeof path, &t->e);
	if (!f)
		return t->e.code;
	fprintf(f, "group_index,group,run,replicate,seed,waiting_time,risen,state,use\n");
	for (int j = 0; j < t->ng; j++)
		for (int i = 0; i < s->g[j].n; i++) {
			const an_run *r = &t->runs[s->g[j].run[i]];
			fprintf(f, "%d,", j);
			csv_str(f, t->labels[j]);
			fprintf(f, ",%s,%ld,%ld,%.17g,%d,%s,%s\n", r->id, r->replicate, r->seed, s->g[j].t[i], s->g[j].ev[i],
				r->state, acct_use_name(r->use));
		}
	fclose(f);
	return 0;
}

/* waiting_km_band.csv: group j's confidence band as the outline of steps (the band
 * is constant between event times, as S is), for gnuplot's filledcurves: at each
 * time the band before it, then after it */
static void band_csv(FILE *b, const an_tool *t, const wait_state *s, int j)
{
	const km_curve *km = &s->km[j];
	double lo = 1, hi = 1;
	for (size_t i = 0; i < km->m; i++) {
		fprintf(b, "%d,%.17g,%.17g,%.17g\n", j, km->t[i], lo, hi);
		lo = fmax(0, km->s[i] - s->z * km->se[i]);
		hi = fmin(1, km->s[i] + s->z * km->se[i]);
		fprintf(b, "%d,%.17g,%.17g,%.17g\n", j, km->t[i], lo, hi);
	}
	(void)t;
}

/* waiting_km.csv: the survival curves, each starting at (0, 1), and their bands */
static int km_csv(an_tool *t, const wait_state *s)
{
	char path[1400];
	FILE *f = cli_fopen(t->o, "waiting_km.csv", path, sizeof path, &t->e), *b;
	if (!f)
		return t->e.code;
	if (!(b = cli_fopen(t->o, "waiting_km_band.csv", path, sizeof path, &t->e))) {
		fclose(f);
		return t->e.code;
	}
	fprintf(b, "group_index,t,lo,hi\n");
	for (int j = 0; j < t->ng; j++) {
		fprintf(b, "%d,0,1,1\n", j);
		band_csv(b, t, s, j);
	}
	fclose(b);
	fprintf(f, "group_index,group,t,n_risk,events,censored,S,se,lo,hi\n");
	for (int j = 0; j < t->ng; j++) {
		const km_curve *km = &s->km[j];
		fprintf(f, "%d,", j);
		csv_str(f, t->labels[j]);
		fprintf(f, ",0,%ld,0,0,1,0,1,1\n", km->n);
		for (size_t i = 0; i < km->m; i++) {
			const double S = km->s[i], se = km->se[i];
			fprintf(f, "%d,", j);
			csv_str(f, t->labels[j]);
			fprintf(f, ",%.17g,%ld,%ld,%ld,%.17g,%.17g,%.17g,%.17g\n", km->t[i], km->n_risk[i], km->d[i], km->c[i],
				S, se, fmax(0, S - s->z * se), fmin(1, S + s->z * se));
		}
	}
	fclose(f);
	return 0;
}

/* The risen runs of group j whose waiting time is in bin b of bins (the last bin
 * holds the longest). */
static long hist_count(const wait_state *s, int j, long b, long bins)
{
	long c = 0;
	for (int i = 0; i < s->g[j].n; i++) {
		long q = (long)floor(s->g[j].t[i] / s->bw);
		if (q >= bins)
			q = bins - 1;
		c += s->g[j].ev[i] && q == b;
	}
	return c;
}

/* waiting_hist.csv: the risen runs' waiting times, bins common to every group */
static int hist_csv(an_tool *t, const wait_state *s)
{
	char path[1400];
	const long bins = t->o->bins;
	FILE *f = cli_fopen(t->o, "waiting_hist.csv", path, sizeof path, &t->e);
	if (!f)
		return t->e.code;
	fprintf(f, "group_index,group,lo,hi,count\n");
	for (int j = 0; j < t->ng; j++)
		for (long b = 0; b < bins; b++) {
			const long c = hist_count(s, j, b, bins);
			fprintf(f, "%d,", j);
			csv_str(f, t->labels[j]);
			fprintf(f, ",%.17g,%.17g,%ld\n", b * s->bw, (b + 1) * s->bw, c);
		}
	fclose(f);
	return 0;
}

/* Group j's summary: its table row, its summary row, its stored rows. */
static void group_out(an_tool *t, const wait_state *s, int j, FILE *sum)
{
	const km_curve *km = &s->km[j];
	const char *L = t->labels[j];
	const an_acct *a = &t->A[j];
	double lo, hi, med = km_median(km, s->z, &lo, &hi), tm = 0;
	for (int i = 0; i < s->g[j].n; i++)
		tm = fmax(tm, s->g[j].t[i]);
	const double se_end = km->m ? km->se[km->m - 1] : 0, s_end = km->m ? km->s[km->m - 1] : 1;
	const double s_lo = fmax(0, s_end - s->z * se_end), s_hi = fmin(1, s_end + s->z * se_end);
	const double frac = (double)km->events / (double)km->n;
	char ci[64], ms[32];
	snprintf(ms, sizeof ms, isnan(med) ? ">%.3g" : "%.3f", isnan(med) ? tm : med);
	if (isnan(lo))
		snprintf(ci, sizeof ci, "[>%.3g, -]", tm);
	else if (isnan(hi))
		snprintf(ci, sizeof ci, "[%.3f, >%.3g]", lo, tm);
	else
		snprintf(ci, sizeof ci, "[%.3f, %.3f]", lo, hi);
	printf("%-36s %5ld %5ld %6.3f %9s %21s %8.3f %6.3f %6ld %10ld\n", L, km->n, km->events, frac, ms, ci, tm, s_end,
	       a->failed, a->n[AN_PENDING] + a->n[AN_RUNNING]);
	csv_str(sum, L);
	fprintf(sum, ",%ld,%ld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", km->n, km->events, frac, med, lo, hi,
		tm, s_end, s_lo, s_hi);
	tool_summary_acct(t, sum, j);
	const long n = km->n;
	tool_store(t, j, L, "runs", (double)n, NAN, NAN, n);
	tool_store(t, j, L, "risen", (double)km->events, NAN, NAN, n);
	tool_store(t, j, L, "fraction_risen", frac, NAN, NAN, n);
	tool_store(t, j, L, "median", med, lo, hi, n);
	tool_store(t, j, L, "t_max", tm, NAN, NAN, n);
	tool_store(t, j, L, "s_end", s_end, s_lo, s_hi, n);
	tool_store_acct(t, L, j);
}

/* The log-rank test of equal waiting-time distributions across the groups: printed
 * with the runs it rests on, and stored as group "all groups" (no key columns). */
static void logrank_out(an_tool *t, const wait_state *s)
{
	long n = 0;
	for (int j = 0; j < t->ng; j++)
		n += s->g[j].n;
	double *tt = malloc(sizeof *tt * (size_t)(n ? n : 1));
	int *ev = malloc(sizeof *ev * (size_t)(n ? n : 1)), *gg = malloc(sizeof *gg * (size_t)(n ? n : 1));
	logrank r = {0, NAN, NAN, 0};
	if (tt && ev && gg) {
		long k = 0;
		for (int j = 0; j < t->ng; j++)
			for (int i = 0; i < s->g[j].n; i++, k++) {
				tt[k] = s->g[j].t[i];
				ev[k] = s->g[j].ev[i];
				gg[k] = j;
			}
		logrank_test(tt, ev, gg, (size_t)n, t->ng, &r);
	}
	free(tt);
	free(ev);
	free(gg);
	if (r.k < 2)
		return; /* one group: nothing to compare */
	if (isnan(r.p)) {
		printf("# log-rank test across the %d groups (%ld runs): no test, no intruder rose\n", r.k, n);
		return;
	}
	printf("# log-rank test of equal waiting-time distributions across the %d groups (%ld runs, censored ones "
	       "included): chi2 = %.4g, df = %d, p = %.3g\n", r.k, n, r.chi2, r.df, r.p);
	tool_store(t, -1, "all groups", "logrank_chi2", r.chi2, NAN, NAN, n);
	tool_store(t, -1, "all groups", "logrank_df", (double)r.df, NAN, NAN, n);
	tool_store(t, -1, "all groups", "logrank_p", r.p, NAN, NAN, n);
}

/* Per group: waiting_summary.csv, the table and the analysis table (storing begun
 * here, ended by the caller). */
static int summary(an_tool *t, const wait_state *s)
{
	FILE *sum = tool_summary_csv(t, "waiting_summary.csv",
				     "group,runs,risen,fraction_risen,median,median_lo,median_hi,t_max,s_end,s_end_lo,"
				     "s_end_hi");
	if (!sum)
		return t->e.code;
	printf("%-36s %5s %5s %6s %9s %21s %8s %6s %6s %10s\n", "group", "used", "risen", "frac", "median_s",
	       "CI (Brookmeyer-Crowley)", "t_max_s", "S_end", "failed", "unfinished");
	tool_store_begin(t);
	for (int j = 0; j < t->ng && !t->e.code; j++)
		group_out(t, s, j, sum);
	fclose(sum);
	logrank_out(t, s);
	return t->e.code;
}

/* The closing lines, and how the failed runs used entered. */
static void report(const an_tool *t, const wait_state *s)
{
	tool_report(t, stdout, NULL);
	const long n = s->f_ev + s->f_cens;
	if (n)
		printf("# %ld failed run%s %s observed up to the failure: %ld had risen before it (events at their waiting"
		       " times), %ld are censored at the failure time; this assumes that the failure is independent of"
		       " the rise (non-informative censoring)\n", n, n == 1 ? "" : "s", n == 1 ? "is" : "are", s->f_ev,
		       s->f_cens);
}

/* waiting_km.png and .pdf: the survival curves with their confidence bands, censored
 * runs marked */
static int plot_km(an_tool *t)
{
	char script[1400], png[1400], set[512];
	FILE *f = gp_open(t->o, "waiting_km", 900, 560, script, png, sizeof script, &t->e);
	if (!f)
		return t->e.code;
	tool_setting(t, set, sizeof set);
	fprintf(f, "set title \"Intruder waiting time: Kaplan–Meier survival\\n%s%sband: %g %% CI (Greenwood), ×: censored\"\n"
		   "set xlabel 'time since shaking began t (s)'\nset ylabel 'S(t) = P(not yet risen)'\n"
		   "set yrange [0:1.05]\nset xrange [0:*]\nset style fill transparent solid 0.18 noborder\nplot ",
		set, *set ? "; " : "", 100 * t->o->level);
	int np = 0;
	for (int j = 0; j < t->ng; j++) {
		if (!acct_used(&t->A[j])) /* nothing to draw: gnuplot would warn */
			continue;
		char leg[512];
		tool_legend(t, j, 1, leg, sizeof leg);
		fprintf(f, "%s'waiting_km_band.csv' skip 1 using 2:($1==%d?$3:1/0):4 with filledcurves lt %d notitle, \\\n",
			np++ ? ", \\\n  " : "", j, j + 1);
		fprintf(f, "  'waiting_km.csv' skip 1 using 3:($1==%d?$7:1/0) with steps lw 2 lt %d title ", j, j + 1);
		gp_str(f, *leg ? leg : "all runs");
		fprintf(f, ", \\\n  'waiting_km.csv' skip 1 using 3:($1==%d&&$6>0?$7:1/0) with points pt 2 ps 1.2 lt %d notitle",
			j, j + 1);
	}
	fprintf(f, "\n");
	return tool_plot(t, f, script, png);
}

/* waiting_hist.png and .pdf: the histograms side by side in each bin */
static int plot_hist(an_tool *t, const wait_state *s)
{
	char script[1400], png[1400], set[512];
	const double bw = s->bw;
	FILE *f = gp_open(t->o, "waiting_hist", 900, 560, script, png, sizeof script, &t->e);
	if (!f)
		return t->e.code;
	tool_setting(t, set, sizeof set);
	/* counts: whole-number ticks, and a range also when no run rose (gnuplot would
	 * warn of an empty one) */
	long cmax = 0;
	for (int j = 0; j < t->ng; j++)
		for (long b = 0; b < t->o->bins; b++)
			if (hist_count(s, j, b, t->o->bins) > cmax)
				cmax = hist_count(s, j, b, t->o->bins);
	fprintf(f, "set title \"Intruder waiting time: histogram of the risen runs%s%s\"\n"
		   "set xlabel 'waiting time (s)'\nset ylabel 'runs'\nset yrange [0:%ld]\nset ytics %ld\n"
		   "set xrange [0:%.17g]\nset style fill transparent solid 0.35 border\nset boxwidth %.17g absolute\nplot ",
		*set ? "\\n" : "", set, cmax + 1, cmax > 10 ? (cmax + 9) / 10 : 1, bw * (double)t->o->bins, bw / t->ng);
	int np = 0;
	for (int j = 0; j < t->ng; j++) {
		if (!acct_used(&t->A[j]))
			continue;
		char leg[512];
		tool_legend(t, j, 1, leg, sizeof leg);
		fprintf(f, "%s'waiting_hist.csv' skip 1 using ($3+%.17g):($1==%d?$5:1/0) with boxes lt %d title ",
			np++ ? ", \\\n  " : "", bw / t->ng * (j + 0.5), j, j + 1);
		gp_str(f, *leg ? leg : "all runs");
	}
	fprintf(f, "\n");
	return tool_plot(t, f, script, png);
}

int main(int argc, char **argv)
{
	an_opts o = {.tool = "waiting", .version = VERSION};
	int pr = tool_args(&o, argc, argv, HELP, " by level bins ", stdout, stderr);
	if (pr)
		return pr < 0 ? 0 : 1;
	an_tool t;
	wait_state s = {0};
	if (tool_open(&t, &o) || consider(&t, &s) || groups(&t, &s) || cli_outdir(&o, &t.e) || fit(&t, &s))
		goto out;
	if (runs_csv(&t, &s) || tool_accounting_csv(&t) || km_csv(&t, &s) || hist_csv(&t, &s))
		goto out;
	if (summary(&t, &s) || tool_store_end(&t))
		goto out;
	report(&t, &s);
	if (!o.no_plot) {
		if (plot_km(&t) || plot_hist(&t, &s))
			goto out;
		printf("# figures: %s/waiting_{km,hist}.{png,pdf}\n", o.out);
	}
	printf("# csv: %s/waiting_{runs,km,km_band,hist,summary,accounting}.csv\n", o.out);
out:
	state_free(&t, &s);
	return tool_close(&t, stderr);
}
