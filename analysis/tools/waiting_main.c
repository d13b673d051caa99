/* waiting_main.c - bin/waiting: waiting times of the intruder's rise per group of runs
 * (Kaplan-Meier with right-censoring, median with its Brookmeyer-Crowley interval,
 * fraction risen, histogram). Only this file prints and exits. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "h5read.h"
#include "km.h"
#include "logrank.h"
#include "quantile.h"
#include "common/acct.h"
#include "common/adb.h"
#include "common/cli.h"
#include "common/tool.h"
#include "common/xopt.h"
#include "measure/bootdiff.h"
#include "measure/kmboot.h"
#include "measure/lowerrow.h"
#include "measure/traj.h"

#define VERSION "2"

/* a run whose observation is in the statistic: finished, or failed and observed up to it */
#define USED(r) ((r)->use == AN_USED || (r)->use == AN_PARTLY)

static const char HELP[] =
	"usage: waiting CAMPAIGN [--db FILE] [--runs DIR] [--out DIR] [--by KEYS] [--level L]\n"
	"               [--bins N] [--fraction Q] [--diff KEY] [--boot N] [--seed S]\n"
	"               [--all-versions] [--no-plot] [--no-store]\n\n"
	"Waiting time of the intruder's rise (the engine's definition: docs/model.md, \"Waiting\n"
	"time\"; a run that ends first is right-censored at the time it observed), read from\n"
	"the root attributes `risen` and `waiting_time` of each run with an intruder\n"
	"(radius_ratio > 0). A run that failed is observed up to its\n"
	"failure: risen before it, an event at its waiting time; else censored at the time of\n"
	"the failure (this assumes that the failure is independent of the rise; the output\n"
	"says how many runs it concerns).\n"
	"Per group of runs: Kaplan-Meier survival S(t), the median (first t with S <= 0.5)\n"
	"with its Brookmeyer-Crowley interval (Greenwood errors, plain band), the fraction\n"
	"risen by the end, and a histogram of the observed waiting times. When `depth` is a\n"
	"grouping key, each group against the same start one row lower (depth - 1, docs/model.md):\n"
	"both fractions risen, their difference and the two-sided Fisher exact test.\n\n"
	"A second definition, beside the engine's (which a small intruder's slow creep of one\n"
	"diameter trips): the first time the intruder's centre has covered the fraction Q\n"
	"(--fraction, default 0.5) of the way from its settled height to the settled surface,\n"
	"in the box frame, read off the recorded trajectory (/particles/intruder/position, lab\n"
	"frame, less the box motion A sin(phi(t))) and interpolated between its samples. A run\n"
	"whose trajectory ends first is censored at its last sample: at the end of the run,\n"
	"its failure, or its stop (stop = risen ends a run stop_after seconds after the\n"
	"engine's rise, which may come before the fraction; the output counts them). A run\n"
	"without a trajectory (traj_rate = 0) has no second waiting time: counted, not used.\n"
	"Both definitions side by side: per group the runs, risen, censored and the median with\n"
	"its interval, and the log-rank test across the groups for each.\n\n"
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
	"  --fraction Q  the second definition's fraction of the way to the surface (0 < Q <= 1,\n"
	"                default 0.5)\n"
	"  --diff KEY    the difference of the medians of groups alike in every grouping key\n"
	"                but KEY: each group's median minus the one of the smallest KEY, with\n"
	"                its percentile interval from the two groups' bootstraps (each over its\n"
	"                runs, resampled apart) and whether 0 is inside. A median the curve never\n"
	"                reaches is censored, not a number: the difference is then a bound\n"
	"                (>X, <X, or none), and a resample's censored median bounds its\n"
	"                replicate (the interval is conservative, unbounded on a side where\n"
	"                too many are); waiting_diff.csv, stored key diff_median (lo, hi)\n"
	"  --boot N      bootstrap replicates for --diff (default 1000); --seed S its seed\n"
	"                (default 1)\n"
	"  --all-versions  also the runs of earlier versions of the campaign file\n"
	"                (run.current = 0, kept by study run --keep-old); by default the\n"
	"                current grid's\n"
	"  --no-plot     no figures;  --no-store  nothing written to the database\n\n"
	"Writes waiting_runs.csv, waiting_km.csv, waiting_summary.csv, waiting_hist.csv,\n"
	"waiting_accounting.csv, waiting_km_band.csv, waiting_km.png/.pdf (with the\n"
	"confidence band), waiting_hist.png/.pdf; stores per group in the\n"
	"table `analysis` (tool 'waiting'): runs (used), risen, fraction_risen (Clopper-Pearson\n"
	"lo, hi), median (lo, hi), t_max, s_end (lo, hi), and the accounting (runs_failed,\n"
	"runs_failed_used, ..., as onset --help lists); a group with a start one row lower:\n"
	"lower_fraction_diff (that start's fraction_risen less the group's), lower_fisher_p\n"
	"(n: the runs of both) and lower_risen (n: its runs). The second definition:\n"
	"waiting_way_runs.csv (both times of every used run), waiting_way_km.csv,\n"
	"waiting_way_summary.csv, waiting_way.png/.pdf\n"
	"(both definitions' Kaplan-Meier curves); keys way_fraction, way_runs, way_risen,\n"
	"way_censored, way_median (lo, hi), way_no_trajectory, way_stop_censored, and as group\n"
	"'all groups' way_logrank_chi2, way_logrank_df, way_logrank_p. With --diff:\n"
	"waiting_diff.csv and diff_median (lo, hi; n: the replicates; grp naming both groups).\n"
	"Options take their value as --opt VALUE or --opt=VALUE. Figures are written as PNG\n"
	"and PDF (vector) with their gnuplot scripts. A stored row has its group's value of\n"
	"each grouping key in that key's column (radius_ratio, depth, ...; docs/analysis.md).\n";

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
	/* the second definition (traj.h): the fraction q of the way to the surface */
	double q;
	grp *g2;            /* [ng] the used runs with a trajectory: times and events */
	km_curve *km2;      /* [ng] */
	double *way_t;      /* [k] its time (NaN: no trajectory) */
	int *way_ev;        /* [k] 1 reached, 0 censored */
	long *no_traj;      /* [ng] used runs without a trajectory */
	long *stop_cens;    /* [ng] runs stopped by stop = risen before reaching the fraction */
	/* --diff KEY: each group's bootstrap of its median over its runs (kmboot.h) */
	const char *diff;   /* NULL: not given */
	double *blo, *bhi;  /* [ng * B] group j's replicate k within [blo, bhi] */
	size_t *bcens;      /* [ng] its replicates with a censored median */
} wait_state;

static void state_free(const an_tool *t, void *vs)
{
	wait_state *s = vs;
	for (int j = 0; s->g && j < t->ng; j++) {
		free(s->g[j].t);
		free(s->g[j].ev);
		free(s->g[j].run);
		if (s->km)
			km_free(&s->km[j]);
	}
	for (int j = 0; s->g2 && j < t->ng; j++) {
		free(s->g2[j].t);
		free(s->g2[j].ev);
		free(s->g2[j].run);
		if (s->km2)
			km_free(&s->km2[j]);
	}
	free(s->g);
	free(s->km);
	free(s->wt);
	free(s->risen);
	free(s->g2);
	free(s->km2);
	free(s->way_t);
	free(s->way_ev);
	free(s->no_traj);
	free(s->stop_cens);
	free(s->blo);
	free(s->bhi);
	free(s->bcens);
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
		if (traj_rise(h, r->path, rs, w, &he))
			/* a value that is no time is there, and unusable; a missing one unreadable */
			acct_set(r, he.code == SB_ENAN ? AN_UNUSABLE : AN_UNREADABLE, NAN, NAN, "%s", he.msg);
		h5r_attr_num(h, "/", "status_time", &st);
		h5r_close(h);
	}
	if (r->use == AN_UNREADABLE)
		fprintf(stderr, "waiting: warning: %s (counted as unreadable)\n", r->why);
	else if (r->use == AN_UNUSABLE)
		*rs = *w = NAN;
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
		/* a ratio that is not known to be 0 is considered: grouping says what it lacks */
		if (an_num(r, "radius_ratio", NAN) == 0 || tool_old(t, r))
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
	s->z = quant_normal(t->o->level);
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
	FILE *f = tool_out_open(t, "waiting_runs.csv");
	if (!f)
		return t->e.code;
	fprintf(f, ACCT_ROW_HEAD ",seed,waiting_time,risen,state,use\n");
	for (int j = 0; j < t->ng; j++)
		for (int i = 0; i < s->g[j].n; i++) {
			const an_run *r = &t->runs[s->g[j].run[i]];
			acct_row_begin(f, r, t->labels);
			fprintf(f, ",%ld,%.17g,%d,%s,%s\n", r->seed, s->g[j].t[i], s->g[j].ev[i],
				r->state, acct_use_name(r->use));
		}
	return tool_out_close(t, f);
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
	FILE *f = tool_out_open(t, "waiting_km.csv"), *b;
	if (!f)
		return t->e.code;
	if (!(b = tool_out_open(t, "waiting_km_band.csv")))
		return tool_out_close(t, f);
	fprintf(b, "group_index,t,lo,hi\n");
	for (int j = 0; j < t->ng; j++) {
		fprintf(b, "%d,0,1,1\n", j);
		band_csv(b, t, s, j);
	}
	tool_out_close(t, b);
	fprintf(f, "group_index,group,t,n_risk,events,censored,S,se,lo,hi\n");
	for (int j = 0; j < t->ng; j++) {
		const km_curve *km = &s->km[j];
		fprintf(f, "%d,", j);
		csv_text(f, t->labels[j]);
		fprintf(f, ",0,%ld,0,0,1,0,1,1\n", km->n);
		for (size_t i = 0; i < km->m; i++) {
			const double S = km->s[i], se = km->se[i];
			fprintf(f, "%d,", j);
			csv_text(f, t->labels[j]);
			fprintf(f, ",%.17g,%ld,%ld,%ld,%.17g,%.17g,%.17g,%.17g\n", km->t[i], km->n_risk[i], km->d[i], km->c[i],
				S, se, fmax(0, S - s->z * se), fmin(1, S + s->z * se));
		}
	}
	return tool_out_close(t, f);
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
	const long bins = t->o->bins;
	FILE *f = tool_out_open(t, "waiting_hist.csv");
	if (!f)
		return t->e.code;
	fprintf(f, "group_index,group,lo,hi,count\n");
	for (int j = 0; j < t->ng; j++)
		for (long b = 0; b < bins; b++) {
			const long c = hist_count(s, j, b, bins);
			fprintf(f, "%d,", j);
			csv_text(f, t->labels[j]);
			fprintf(f, ",%.17g,%.17g,%ld\n", b * s->bw, (b + 1) * s->bw, c);
		}
	return tool_out_close(t, f);
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
	csv_text(sum, L);
	fprintf(sum, ",%ld,%ld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", km->n, km->events, frac, med, lo, hi,
		tm, s_end, s_lo, s_hi);
	tool_summary_acct(t, sum, j);
	const long n = km->n;
	tool_store(t, j, L, "runs", (double)n, NAN, NAN, n);
	tool_store(t, j, L, "risen", (double)km->events, NAN, NAN, n);
	/* Clopper-Pearson: exact for a binomial count, what claim 5 compares between depths */
	double f_lo, f_hi;
	quant_clopper_pearson(km->events, n, t->o->level, &f_lo, &f_hi);
	tool_store(t, j, L, "fraction_risen", frac, f_lo, f_hi, n);
	tool_store(t, j, L, "median", med, lo, hi, n);
	tool_store(t, j, L, "t_max", tm, NAN, NAN, n);
	tool_store(t, j, L, "s_end", s_end, s_lo, s_hi, n);
	tool_store_acct(t, L, j);
}

/* The log-rank test of equal waiting-time distributions across the groups: printed
 * with the runs it rests on, and stored as group "all groups" (no key columns). */
static void logrank_out(an_tool *t, const grp *g, const char *prefix, const char *what)
{
	long n = 0;
	for (int j = 0; j < t->ng; j++)
		n += g[j].n;
	double *tt = malloc(sizeof *tt * (size_t)(n ? n : 1));
	int *ev = malloc(sizeof *ev * (size_t)(n ? n : 1)), *gg = malloc(sizeof *gg * (size_t)(n ? n : 1));
	logrank r = {0, NAN, NAN, 0};
	if (tt && ev && gg) {
		long k = 0;
		for (int j = 0; j < t->ng; j++)
			for (int i = 0; i < g[j].n; i++, k++) {
				tt[k] = g[j].t[i];
				ev[k] = g[j].ev[i];
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
		printf("# %slog-rank test across the %d groups (%ld runs): no test, no intruder rose\n", what, r.k, n);
		return;
	}
	printf("# %slog-rank test of equal waiting-time distributions across the %d groups (%ld runs, censored ones "
	       "included): chi2 = %.4g, df = %d, p = %.3g\n", what, r.k, n, r.chi2, r.df, r.p);
	char key[64];
	snprintf(key, sizeof key, "%slogrank_chi2", prefix);
	tool_store(t, -1, "all groups", key, r.chi2, NAN, NAN, n);
	snprintf(key, sizeof key, "%slogrank_df", prefix);
	tool_store(t, -1, "all groups", key, (double)r.df, NAN, NAN, n);
	snprintf(key, sizeof key, "%slogrank_p", prefix);
	tool_store(t, -1, "all groups", key, r.p, NAN, NAN, n);
}

/* Each group j that has a start one row lower i (lowerrow.h): the fractions risen of
 * both, the difference frac(i) - frac(j) and the two-sided Fisher exact test, printed
 * and stored as group j's (its key columns, its depth) lower_fraction_diff and
 * lower_fisher_p (n the runs of both) and lower_risen (the lower start's risen, n its
 * runs), so that no reader has to pair the depths again. Nothing when no group has one. */
static void lower_out(an_tool *t, const wait_state *s)
{
	int np = 0;
	for (int j = 0; j < t->ng && !t->e.code; j++) {
		const int i = lowerrow_partner(t, j);
		if (i < 0)
			continue;
		const km_curve *a = &s->km[j], *b = &s->km[i];
		const double fa = a->n ? (double)a->events / (double)a->n : NAN;
		const double fb = b->n ? (double)b->events / (double)b->n : NAN;
		const double p = lowerrow_fisher_p(b->events, b->n, a->events, a->n), d = fb - fa;
		const long n = a->n + b->n;
		if (!np++)
			printf("\n# one row lower (depth - 1, docs/model.md): fraction risen starting one row lower minus at"
			       " the group's depth d, two-sided Fisher exact test\n%-36s %14s %14s %8s %9s %5s\n",
			       "group (depth d)", "risen/runs d", "risen/runs d-1", "diff", "fisher_p", "runs");
		char ra[48], rb[48];
		snprintf(ra, sizeof ra, "%ld/%ld", a->events, a->n);
		snprintf(rb, sizeof rb, "%ld/%ld", b->events, b->n);
		printf("%-36s %14s %14s %+8.3f %9.3g %5ld\n", t->labels[j], ra, rb, d, p, n);
		tool_store(t, j, t->labels[j], "lower_fraction_diff", d, NAN, NAN, n);
		tool_store(t, j, t->labels[j], "lower_fisher_p", p, NAN, NAN, n);
		tool_store(t, j, t->labels[j], "lower_risen", (double)b->events, NAN, NAN, b->n);
	}
}

/* Per group: waiting_summary.csv, the table, the comparison one row lower and the
 * analysis table (storing begun here, ended by the caller). */
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
	if (tool_out_close(t, sum))
		return t->e.code;
	logrank_out(t, s->g, "", "");
	lower_out(t, s);
	return t->e.code;
}

/* ---- the second definition: the fraction q of the way to the surface (traj.h) ---- */

/* Each used run's time from its trajectory, the groups' curves. */
static int way(an_tool *t, wait_state *s)
{
	const size_t ng = (size_t)(t->ng > 0 ? t->ng : 1), k = (size_t)(t->k ? t->k : 1);
	s->g2 = calloc(ng, sizeof *s->g2);
	s->km2 = calloc(ng, sizeof *s->km2);
	s->no_traj = calloc(ng, sizeof *s->no_traj);
	s->stop_cens = calloc(ng, sizeof *s->stop_cens);
	s->way_t = calloc(k, sizeof *s->way_t);
	s->way_ev = calloc(k, sizeof *s->way_ev);
	if (!s->g2 || !s->km2 || !s->no_traj || !s->stop_cens || !s->way_t || !s->way_ev)
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	for (int i = 0; i < t->k; i++) {
		const an_run *r = &t->runs[i];
		s->way_t[i] = NAN;
		if (!USED(r))
			continue;
		traj tr;
		sb_err e = {0};
		const int rc = traj_read(r->path, &tr, &e);
		double w = NAN;
		const int ev = rc == 0 ? traj_fraction(&tr, s->q, &w) : -1;
		if (rc > 1)
			fprintf(stderr, "waiting: warning: %s (no second waiting time: counted as without a trajectory)\n", e.msg);
		else if (rc == 0 && ev < 0)
			/* a trajectory without the levels the way is measured between: said as such,
			 * not taken for a run without a trajectory */
			fprintf(stderr, "waiting: warning: %s: no settled intruder height or surface height "
				"(intruder_settled_y %g, surface_height %g): no second waiting time, counted with the runs "
				"without one\n", r->path, tr.y0, tr.surface);
		if (ev < 0)
			s->no_traj[r->group]++;
		else {
			s->way_t[i] = w;
			s->way_ev[i] = ev;
			s->stop_cens[r->group] += !ev && !strcmp(tr.stopped_by, "risen");
			if (push(&s->g2[r->group], w, ev, i)) {
				traj_free(&tr);
				return sb_errf(&t->e, SB_ENOMEM, "out of memory");
			}
		}
		traj_free(&tr);
	}
	for (int j = 0; j < t->ng; j++)
		if (km_fit(s->g2[j].t, s->g2[j].ev, (size_t)s->g2[j].n, &s->km2[j]))
			return sb_errf(&t->e, SB_EIO, "group %s: bad second waiting times", t->labels[j]);
	return 0;
}

/* waiting_way_runs.csv (both definitions of every used run) and waiting_way_km.csv */
static int way_csv(an_tool *t, const wait_state *s)
{
	FILE *f = tool_out_open(t, "waiting_way_runs.csv"), *k = NULL;
	if (f)
		k = tool_out_open(t, "waiting_way_km.csv");
	if (!k)
		return tool_out_close(t, f);
	fprintf(f, ACCT_ROW_HEAD ",seed,waiting_time,risen,way_time,way_risen,trajectory,use\n");
	for (int j = 0; j < t->ng; j++)
		for (int i = 0; i < t->k; i++) {
			const an_run *r = &t->runs[i];
			if (r->group != j || !USED(r))
				continue;
			acct_row_begin(f, r, t->labels);
			fprintf(f, ",%ld,%.17g,%d,%.17g,%d,%s,%s\n", r->seed, s->wt[i], s->risen[i],
				s->way_t[i], isnan(s->way_t[i]) ? 0 : s->way_ev[i], isnan(s->way_t[i]) ? "no" : "yes",
				acct_use_name(r->use));
		}
	tool_out_close(t, f);
	fprintf(k, "group_index,group,t,n_risk,events,censored,S,se,lo,hi\n");
	for (int j = 0; j < t->ng; j++) {
		const km_curve *km = &s->km2[j];
		fprintf(k, "%d,", j);
		csv_text(k, t->labels[j]);
		fprintf(k, ",0,%ld,0,0,1,0,1,1\n", km->n);
		for (size_t i = 0; i < km->m; i++) {
			fprintf(k, "%d,", j);
			csv_text(k, t->labels[j]);
			fprintf(k, ",%.17g,%ld,%ld,%ld,%.17g,%.17g,%.17g,%.17g\n", km->t[i], km->n_risk[i], km->d[i], km->c[i],
				km->s[i], km->se[i], fmax(0, km->s[i] - s->z * km->se[i]), fmin(1, km->s[i] + s->z * km->se[i]));
		}
	}
	return tool_out_close(t, k);
}

/* "12.345 [1.234, >6]" into b: a median and its interval, limits not reached as >t_max */
static void med_ci(char *b, size_t n, double med, double lo, double hi, double tm)
{
	char m[32], l[32], h[32];
	snprintf(m, sizeof m, isnan(med) ? ">%.3g" : "%.3f", isnan(med) ? tm : med);
	snprintf(l, sizeof l, isnan(lo) ? ">%.3g" : "%.3f", isnan(lo) ? tm : lo);
	snprintf(h, sizeof h, isnan(hi) ? ">%.3g" : "%.3f", isnan(hi) ? tm : hi);
	snprintf(b, n, "%s [%s, %s]", m, l, h);
}

static double tmax_of(const grp *g)
{
	double tm = 0;
	for (int i = 0; i < g->n; i++)
		tm = fmax(tm, g->t[i]);
	return tm;
}

/* Both definitions side by side: the table, waiting_way_summary.csv, the stored rows,
 * the second log-rank test. */
static int way_summary(an_tool *t, const wait_state *s)
{
	FILE *sum = tool_summary_csv(t, "waiting_way_summary.csv",
				     "group,fraction,runs,risen,censored,median,median_lo,median_hi,way_runs,way_risen,"
				     "way_censored,way_median,way_median_lo,way_median_hi,way_no_trajectory,way_stop_censored");
	if (!sum)
		return t->e.code;
	printf("\n# both definitions: one diameter above the settled height (the engine's) | %g of the way from the"
	       " settled height to the surface (box frame, from the trajectory)\n", s->q);
	printf("%-36s %5s %5s %5s %26s | %5s %5s %5s %26s %7s %9s\n", "group", "used", "risen", "cens", "median_s [CI]",
	       "used", "risen", "cens", "median_s [CI]", "no_traj", "stop_cens");
	long stop = 0, none = 0;
	for (int j = 0; j < t->ng && !t->e.code; j++) {
		const km_curve *a = &s->km[j], *b = &s->km2[j];
		double l1, h1, l2, h2;
		const double m1 = km_median(a, s->z, &l1, &h1), m2 = km_median(b, s->z, &l2, &h2);
		char c1[112], c2[112];
		med_ci(c1, sizeof c1, m1, l1, h1, tmax_of(&s->g[j]));
		med_ci(c2, sizeof c2, m2, l2, h2, tmax_of(&s->g2[j]));
		printf("%-36s %5ld %5ld %5ld %26s | %5ld %5ld %5ld %26s %7ld %9ld\n", t->labels[j], a->n, a->events,
		       a->n - a->events, c1, b->n, b->events, b->n - b->events, c2, s->no_traj[j], s->stop_cens[j]);
		csv_text(sum, t->labels[j]);
		fprintf(sum, ",%.17g,%ld,%ld,%ld,%.17g,%.17g,%.17g,%ld,%ld,%ld,%.17g,%.17g,%.17g,%ld,%ld", s->q, a->n,
			a->events, a->n - a->events, m1, l1, h1, b->n, b->events, b->n - b->events, m2, l2, h2, s->no_traj[j],
			s->stop_cens[j]);
		tool_summary_acct(t, sum, j);
		const char *L = t->labels[j];
		const long n = b->n;
		tool_store(t, j, L, "way_fraction", s->q, NAN, NAN, n);
		tool_store(t, j, L, "way_runs", (double)n, NAN, NAN, n);
		tool_store(t, j, L, "way_risen", (double)b->events, NAN, NAN, n);
		tool_store(t, j, L, "way_censored", (double)(n - b->events), NAN, NAN, n);
		tool_store(t, j, L, "way_median", m2, l2, h2, n);
		tool_store(t, j, L, "way_no_trajectory", (double)s->no_traj[j], NAN, NAN, a->n);
		tool_store(t, j, L, "way_stop_censored", (double)s->stop_cens[j], NAN, NAN, n);
		stop += s->stop_cens[j];
		none += s->no_traj[j];
	}
	if (tool_out_close(t, sum))
		return t->e.code;
	logrank_out(t, s->g2, "way_", "second definition: ");
	if (none)
		printf("# %ld used run%s without a trajectory (traj_rate = 0, or none recorded): no second waiting time, left"
		       " out of the second definition only\n", none, none == 1 ? "" : "s");
	if (stop)
		printf("# %ld run%s stopped by stop = risen (stop_after seconds after the engine's rise) before covering %g of"
		       " the way: censored at their end, which the second definition's median takes as a lower limit\n",
		       stop, stop == 1 ? "" : "s", s->q);
	return t->e.code;
}

/* waiting_way.png and .pdf: per group both definitions' survival curves */
static int plot_way(an_tool *t, const wait_state *s)
{
	char script[1400], png[1400], set[512];
	FILE *f = tool_gp_open(t, "waiting_way", 900, 560, script, png, sizeof script);
	if (!f)
		return t->e.code;
	tool_setting(t, set, sizeof set);
	fprintf(f, "set title \"Intruder waiting time, two definitions: Kaplan–Meier survival\\n%s%s×: censored\\nsolid: one "
		   "intruder diameter above the settled height; dashed: %g of the way to the surface\"\n"
		   "set xlabel 'time since shaking began t (s)'\nset ylabel 'S(t) = P(not yet risen)'\n"
		   "set yrange [0:1.05]\nset xrange [0:*]\nplot ", set, *set ? "; " : "", s->q);
	int np = 0;
	for (int j = 0; j < t->ng; j++) {
		if (!acct_used(&t->A[j]))
			continue;
		char leg[512], l2[600];
		tool_legend(t, j, 1, leg, sizeof leg);
		snprintf(l2, sizeof l2, "%s%sone diameter", leg, *leg ? ": " : "");
		fprintf(f, "%s'waiting_km.csv' skip 1 using 3:($1==%d?$7:1/0) with steps lw 2 lt %d title ", np++ ? ", \\\n  " : "",
			j, j + 1);
		gp_str(f, l2);
		if (s->km2[j].n) {
			snprintf(l2, sizeof l2, "%s%s%g of the way", leg, *leg ? ": " : "", s->q);
			fprintf(f, ", \\\n  'waiting_way_km.csv' skip 1 using 3:($1==%d?$7:1/0) with steps lw 2 dt 2 lt %d title ",
				j, j + 1);
			gp_str(f, l2);
			fprintf(f, ", \\\n  'waiting_way_km.csv' skip 1 using 3:($1==%d&&$6>0?$7:1/0) with points pt 2 ps 1.2 lt %d notitle",
				j, j + 1);
		}
	}
	fprintf(f, "\n");
	return tool_plot(t, f, script, png);
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

/* Group j's Kaplan-Meier curve drawn on top of group i's: the same times and the
 * same S at each (e.g. every run of both censored at the end of the runs) */
static int km_same(const km_curve *a, const km_curve *b)
{
	if (a->m != b->m)
		return 0;
	for (size_t i = 0; i < a->m; i++)
		if (fabs(a->t[i] - b->t[i]) > 1e-9 * fmax(1, fabs(a->t[i])) || fabs(a->s[i] - b->s[i]) > 1e-9)
			return 0;
	return 1;
}

/* waiting_km.png and .pdf: the survival curves with their confidence bands, censored
 * runs marked; a curve identical to an earlier group's is drawn KM_HAIR higher per
 * earlier copy and says so in the key (docs/analysis.md, "waiting") */
#define KM_HAIR 0.012
static int plot_km(an_tool *t, const wait_state *s)
{
	char script[1400], png[1400], set[512];
	FILE *f = tool_gp_open(t, "waiting_km", 900, 560, script, png, sizeof script);
	if (!f)
		return t->e.code;
	tool_setting(t, set, sizeof set);
	fprintf(f, "set title \"Intruder waiting time: Kaplan–Meier survival\\n%s%sband: %g %% CI (Greenwood), ×: censored\"\n"
		   "set xlabel 'time since shaking began t (s)'\nset ylabel 'S(t) = P(not yet risen)'\n"
		   "set yrange [0:1.1]\nset xrange [0:*]\nset style fill transparent solid 0.18 noborder\nplot ",
		set, *set ? "; " : "", 100 * t->o->level);
	int np = 0;
	for (int j = 0; j < t->ng; j++) {
		if (!acct_used(&t->A[j])) /* nothing to draw: gnuplot would warn */
			continue;
		char leg[512], same[512] = "", title[1200];
		tool_legend(t, j, 1, leg, sizeof leg);
		int copies = 0, first = -1;
		for (int i = 0; i < j; i++)
			if (acct_used(&t->A[i]) && s->km[i].m && km_same(&s->km[i], &s->km[j])) {
				copies++;
				first = first < 0 ? i : first;
			}
		if (first >= 0)
			tool_legend(t, first, 1, same, sizeof same);
		const double off = KM_HAIR * copies;
		if (copies)
			snprintf(title, sizeof title, "%s (same as %s, drawn %g higher)",
				 *leg ? leg : "all runs", *same ? same : "another group", off);
		else
			snprintf(title, sizeof title, "%s", *leg ? leg : "all runs");
		fprintf(f, "%s'waiting_km_band.csv' skip 1 using 2:($1==%d?$3:1/0):4 with filledcurves lt %d notitle, \\\n",
			np++ ? ", \\\n  " : "", j, j + 1);
		fprintf(f, "  'waiting_km.csv' skip 1 using 3:($1==%d?$7+%g:1/0) with steps lw 2 lt %d dt %d title ", j, off,
			j + 1, j % 5 + 1);
		gp_str(f, title);
		fprintf(f, ", \\\n  'waiting_km.csv' skip 1 using 3:($1==%d&&$6>0?$7+%g:1/0) with points pt 2 ps 1.2 lt %d "
			   "notitle", j, off, j + 1);
	}
	fprintf(f, "\n");
	return tool_plot(t, f, script, png);
}

/* waiting_hist.png and .pdf: each group's histogram as semi-transparent bars over
 * whole bins, outlined in its colour: a bar covers the bin its waiting times fall in
 * (docs/analysis.md, "waiting") */
static int plot_hist(an_tool *t, const wait_state *s)
{
	char script[1400], png[1400], set[512];
	const double bw = s->bw;
	FILE *f = tool_gp_open(t, "waiting_hist", 900, 560, script, png, sizeof script);
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
		   "set xrange [0:%.17g]\nset style fill transparent solid 0.2 border\nset boxwidth %.17g absolute\nplot ",
		*set ? "\\n" : "", set, cmax + 1, cmax > 10 ? (cmax + 9) / 10 : 1, bw * (double)t->o->bins, bw);
	int np = 0;
	for (int j = 0; j < t->ng; j++) {
		if (!acct_used(&t->A[j]))
			continue;
		char leg[512];
		tool_legend(t, j, 1, leg, sizeof leg);
		fprintf(f, "%s'waiting_hist.csv' skip 1 using (($3+$4)/2):($1==%d?$5:1/0) with boxes lw 2 lt %d title ",
			np++ ? ", \\\n  " : "", j, j + 1);
		gp_str(f, *leg ? leg : "all runs");
	}
	fprintf(f, "\n");
	return tool_plot(t, f, script, png);
}

/* ---- --diff KEY: the medians of several groups against each other ---- */

/* Each group's bootstrap of its median over its used runs (kmboot.h), all from --seed
 * so that bootdiff pairs them apart; nothing with --boot below 2. */
static int diff_boot(an_tool *t, wait_state *s)
{
	const size_t B = t->o->boot > 1 ? (size_t)t->o->boot : 0, ng = (size_t)(t->ng > 0 ? t->ng : 1);
	s->bcens = calloc(ng, sizeof *s->bcens);
	s->blo = malloc(sizeof *s->blo * ng * (B ? B : 1));
	s->bhi = malloc(sizeof *s->bhi * ng * (B ? B : 1));
	if (!s->bcens || !s->blo || !s->bhi)
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	for (int j = 0; B && j < t->ng; j++)
		if (s->g[j].n && kmboot_median(s->g[j].t, s->g[j].ev, (size_t)s->g[j].n, B, t->o->seed, s->blo + j * B,
					       s->bhi + j * B, &s->bcens[j]))
			return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	return 0;
}

/* A limit of the interval as text: unbounded as -inf or +inf, none as - */
static void limit_txt(char *b, size_t n, double v)
{
	if (isnan(v))
		snprintf(b, n, "-");
	else if (isinf(v))
		snprintf(b, n, "%sinf", v < 0 ? "-" : "+");
	else
		snprintf(b, n, "%.3f", v);
}

/* The difference b - a of two medians as text: a number when both are reached, else
 * the bound the longest observations give (>X: b's median is censored, <X: a's), or
 * "censored" when both are. */
static void diff_txt(char *buf, size_t n, double ma, double mb, double ta, double tb)
{
	if (!isnan(ma) && !isnan(mb))
		snprintf(buf, n, "%.3f", mb - ma);
	else if (!isnan(ma))
		snprintf(buf, n, ">%.3f", tb - ma);
	else if (!isnan(mb))
		snprintf(buf, n, "<%.3f", mb - ta);
	else
		snprintf(buf, n, "censored");
}

/* One pair: group b against group a, the reference of its curve: the table row,
 * waiting_diff.csv's row and the stored row. */
static int diff_pair(an_tool *t, const wait_state *s, int a, int b, const char *lab, FILE *f)
{
	const size_t B = t->o->boot > 1 ? (size_t)t->o->boot : 0;
	double l, h;
	const double ma = km_median(&s->km[a], 0, &l, &h), mb = km_median(&s->km[b], 0, &l, &h);
	const double ta = tmax_of(&s->g[a]), tb = tmax_of(&s->g[b]);
	bootdiff_res d;
	if (bootdiff_bounds(ma, mb, B ? s->blo + a * B : NULL, B ? s->bhi + a * B : NULL, B ? s->blo + b * B : NULL,
			    B ? s->bhi + b * B : NULL, B, t->o->level, &d))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	const char *cens = isnan(ma) ? isnan(mb) ? "both" : "a" : isnan(mb) ? "b" : "none";
	char dt[48], lo[32], hi[32], ci[128], grp[1100];
	diff_txt(dt, sizeof dt, ma, mb, ta, tb);
	limit_txt(lo, sizeof lo, d.lo);
	limit_txt(hi, sizeof hi, d.hi);
	snprintf(ci, sizeof ci, "%s [%s, %s]", dt, lo, hi);
	const char *z = d.zero == 1 ? "inside" : d.zero == 0 ? "excluded" : "-";
	printf("%-30s %10g %10g %30s %9s %8zu %8zu %8s\n", lab, tool_num(t, b, s->diff), tool_num(t, a, s->diff), ci,
	       strcmp(cens, "none") ? cens : "", B ? s->bcens[b] : 0, B ? s->bcens[a] : 0, z);
	csv_text(f, t->labels[a]);
	fputc(',', f);
	csv_text(f, t->labels[b]);
	fprintf(f, ",%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%s,%.17g,%.17g,%.17g,%zu,%zu,%zu,%d\n", tool_num(t, a, s->diff),
		tool_num(t, b, s->diff), ma, mb, ta, tb, cens, d.d, d.lo, d.hi, d.ok, B ? s->bcens[a] : 0,
		B ? s->bcens[b] : 0, d.zero);
	snprintf(grp, sizeof grp, "%s - %s", t->labels[b], t->labels[a]);
	tool_store(t, b, grp, "diff_median", d.d, d.lo, d.hi, (long)d.ok);
	return 0;
}

/* --diff KEY: per curve along KEY, each group's median against the one of the
 * smallest KEY (as bin/onset --diff). */
static int diff_out(an_tool *t, wait_state *s)
{
	int nc;
	FILE *f;
	/* the bootstraps first: nothing is written when they cannot be */
	int *curve = diff_boot(t, s) ? NULL : tool_curves_csv(t, s->diff, "waiting_diff.csv", &nc, &f);
	if (!curve)
		return t->e.code;
	fprintf(f, "group_a,group_b,%s_a,%s_b,median_a,median_b,t_max_a,t_max_b,censored,difference,lo,hi,replicates,"
		   "censored_replicates_a,censored_replicates_b,zero\n", s->diff, s->diff);
	char how[160];
	if (t->o->boot > 1)
		snprintf(how, sizeof how, "%ld replicates from seed %lu", t->o->boot, t->o->seed);
	else
		snprintf(how, sizeof how, "no interval (--boot below 2)");
	printf("\n# differences along %s: the median waiting time at each %s minus at the smallest (other keys equal);"
	       " %g %% percentile interval from the two groups' bootstraps over their runs, resampled apart (%s); a"
	       " censored median (S never reaches 1/2) is no number: the difference is then a bound, >X or <X, and a"
	       " resample's censored median bounds its replicate (a side it leaves open: inf)\n",
	       s->diff, s->diff, 100 * t->o->level, how);
	printf("%-30s %10s %10s %30s %9s %8s %8s %8s\n", "groups alike but in", s->diff, "against",
	       "median difference (s) [CI]", "censored", "cens_rep", "cens_ref", "0");
	int pairs = 0;
	for (int c = 0; c < nc && !t->e.code; c++) {
		int a = -1;
		for (int j = 0; j < t->ng; j++) /* the reference: the smallest KEY with used runs */
			if (curve[j] == c && s->g[j].n && (a < 0 || tool_num(t, j, s->diff) < tool_num(t, a, s->diff)))
				a = j;
		char lab[512];
		if (a >= 0)
			tool_label_but(t, a, s->diff, lab, sizeof lab);
		for (int b = 0, first = 1; a >= 0 && b < t->ng; b++) {
			if (curve[b] != c || b == a || !s->g[b].n)
				continue;
			if (diff_pair(t, s, a, b, first ? lab : "", f))
				break;
			first = 0;
			pairs++;
		}
	}
	if (!pairs)
		printf("# no two groups with used runs differ only in %s\n", s->diff);
	free(curve);
	return tool_out_close(t, f);
}

static int init(an_tool *t, void *vs, const xopt *x)
{
	wait_state *s = vs;
	s->diff = x[1].set ? x[1].val : NULL;
	return xopt_num(&x[0], 1e-6, 1, 0.5, &s->q, &t->e);
}

static int run(an_tool *t, void *vs)
{
	wait_state *s = vs;
	if (consider(t, s) || groups(t, s) || cli_outdir(t->o, &t->e) || fit(t, s) || way(t, s) || runs_csv(t, s) ||
	    tool_accounting_csv(t) || km_csv(t, s) || hist_csv(t, s) || way_csv(t, s) || summary(t, s) ||
	    way_summary(t, s) || (s->diff && diff_out(t, s)) || tool_store_end(t))
		return t->e.code;
	report(t, s);
	if (!t->o->no_plot) {
		if (plot_km(t, s) || plot_hist(t, s) || plot_way(t, s))
			return t->e.code;
		printf("# figures: %s/waiting_{km,hist,way}.{png,pdf}\n", t->o->out);
	}
	printf("# csv: %s/waiting_{runs,km,km_band,hist,summary,accounting,way_runs,way_km,way_summary%s}.csv\n",
	       t->o->out, s->diff ? ",diff" : "");
	return 0;
}

static const tool_spec SPEC = {.name = "waiting", .version = VERSION, .help = HELP, .allowed = " by level bins boot seed ",
			       .x = {{"fraction", 1, NULL, 0}, {"diff", 1, NULL, 0}}, .nx = 2, .init = init, .run = run, .fini = state_free};

int main(int argc, char **argv)
{
	wait_state s = {0};
	return tool_main(argc, argv, &SPEC, &s);
}
