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

#define VERSION "2"

/* a run whose observation is in the statistic: finished, or failed and observed up to it */
#define USED(r) ((r)->use == AN_USED || (r)->use == AN_PARTLY)

static const char *HELP =
	"usage: waiting CAMPAIGN [--db FILE] [--runs DIR] [--out DIR] [--by KEYS] [--level L]\n"
	"               [--bins N] [--all-versions] [--no-plot] [--no-store]\n\n"
	"Waiting time of the intruder's rise (MODEL.md: first time its centre is one intruder\n"
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
	"  --no-plot     no PNG;  --no-store  nothing written to the database\n\n"
	"Writes waiting_runs.csv, waiting_km.csv, waiting_summary.csv, waiting_hist.csv,\n"
	"waiting_accounting.csv, waiting_km.png, waiting_hist.png; stores per group in the\n"
	"table `analysis` (tool 'waiting'): runs (used), risen, fraction_risen, median (lo,\n"
	"hi), t_max, s_end (lo, hi), and the accounting (runs_failed, runs_failed_used, ...,\n"
	"as onset --help lists).\n"
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

int main(int argc, char **argv)
{
	an_opts o = {.tool = "waiting", .version = VERSION};
	int pr = cli_parse(&o, argc, argv, HELP, " by level bins ");
	if (pr)
		return pr < 0 ? 0 : 1;
	sb_err e = {0};
	adb d;
	an_run *runs = NULL;
	int nr = 0, ng = 0;
	char **labels = NULL;
	grp *g = NULL;
	km_curve *km = NULL;
	an_acct *A = NULL;
	FILE *f = NULL;
	char path[1400], script[1400], png[1400];
	if (adb_open(&d, o.db, !o.no_store, &e) || adb_runs(&d, o.campaign, o.runs, &runs, &nr, &e))
		goto out;
	/* every run with an intruder is accounted for, whatever its state */
	double *wt = calloc((size_t)(nr ? nr : 1), sizeof *wt);
	int *risen = calloc((size_t)(nr ? nr : 1), sizeof *risen), k = 0;
	long nold = 0, f_ev = 0, f_cens = 0;
	if (!wt || !risen) {
		sb_errf(&e, SB_ENOMEM, "out of memory");
		free(wt);
		free(risen);
		goto out;
	}
	for (int i = 0; i < nr; i++) {
		an_run *r = &runs[i];
		if (!(an_num(r, "radius_ratio", 0) > 0) || acct_version_skip(r, o.all_versions, &nold))
			continue;
		double rs = NAN, w = NAN, st = NAN;
		if (!acct_classify(r)) {
			hid_t h;
			sb_err he = {0};
			if (h5r_open(r->path, &h, &he))
				acct_set(r, AN_UNREADABLE, NAN, NAN, "%s", he.msg);
			else {
				if (h5r_attr_num(h, "/", "risen", &rs) || h5r_attr_num(h, "/", "waiting_time", &w) ||
				    !(w >= 0) || !isfinite(w))
					acct_set(r, AN_UNREADABLE, NAN, NAN, "%s: no valid root attributes risen, waiting_time",
						 r->path);
				h5r_attr_num(h, "/", "status_time", &st);
				h5r_close(h);
			}
			if (r->use == AN_UNREADABLE)
				fprintf(stderr, "waiting: warning: %s (counted as unreadable)\n", r->why);
			else if (strcmp(r->state, "failed"))
				acct_set(r, AN_USED, NAN, NAN, NULL);
			else if (!(w > 0))
				acct_set(r, AN_UNUSABLE, NAN, NAN, "failed before the shaking began (%s)", r->status);
			else {
				/* observed up to the failure: a rise before it is an event, else the
				 * run is censored when it failed */
				if (!isfinite(st))
					st = isfinite(r->status_time) ? r->status_time : w;
				acct_set(r, AN_PARTLY, rs != 0 ? st : w, an_num(r, "duration", NAN),
					 rs != 0 ? "failed at t = %g s (%s) after the rise at %g s: an event"
						 : "failed at t = %g s (%s) before any rise: censored at %g s",
					 st, r->status, w);
				if (rs != 0)
					f_ev++;
				else
					f_cens++;
			}
		}
		an_run t = runs[k];
		runs[k] = runs[i];
		runs[i] = t;
		wt[k] = w;
		risen[k] = rs != 0 && !isnan(rs);
		k++;
	}
	if (k == 0) {
		int known = 0;
		if (!adb_campaign_exists(&d, o.campaign, &known, &e) && !known)
			sb_errf(&e, SB_EUSAGE, "campaign '%s' is not in %s", o.campaign, o.db);
		else
			sb_errf(&e, SB_EUSAGE, "campaign '%s': no finished run with an intruder in %s%s", o.campaign, o.db,
				nold ? " of the current grid (--all-versions)" : "");
		free(wt);
		free(risen);
		goto out;
	}
	static const char *const always[] = {"radius_ratio", NULL};
	char keys[AN_MAXKEYS][48];
	int nk;
	if (cli_keys(&o, &d, always, NULL, keys, &nk, &e)) {
		free(wt);
		free(risen);
		goto out;
	}
	/* group the first k runs; remember each used one's time and event */
	ng = an_group_runs(runs, k, keys, nk, &labels);
	g = calloc((size_t)(ng > 0 ? ng : 1), sizeof *g);
	km = calloc((size_t)(ng > 0 ? ng : 1), sizeof *km);
	if (ng < 0 || !g || !km || acct_tally(runs, k, ng, &A)) {
		sb_errf(&e, SB_ENOMEM, "out of memory");
		free(wt);
		free(risen);
		goto out;
	}
	for (int i = 0; i < k; i++)
		if (USED(&runs[i]) && push(&g[runs[i].group], wt[i], risen[i], i)) {
			sb_errf(&e, SB_ENOMEM, "out of memory");
			break;
		}
	free(wt);
	free(risen);
	long used = 0;
	for (int j = 0; j < ng; j++)
		used += g[j].n;
	if (!e.code && !used) {
		acct_print(stdout, "waiting", labels, A, ng, nold, o.all_versions);
		sb_errf(&e, SB_EUSAGE, "campaign '%s': none of its %d runs with an intruder is usable yet", o.campaign, k);
		goto out;
	}
	if (e.code || cli_outdir(&o, &e))
		goto out;
	double z = zq(o.level), tmax_all = 0;
	for (int j = 0; j < ng; j++) {
		if (km_fit(g[j].t, g[j].ev, (size_t)g[j].n, &km[j])) {
			sb_errf(&e, SB_EIO, "group %s: bad waiting times", labels[j]);
			goto out;
		}
		for (int i = 0; i < g[j].n; i++)
			tmax_all = fmax(tmax_all, g[j].t[i]);
	}

	/* per-run CSV */
	if (!(f = cli_fopen(&o, "waiting_runs.csv", path, sizeof path, &e)))
		goto out;
	fprintf(f, "group_index,group,run,replicate,seed,waiting_time,risen,state,use\n");
	for (int j = 0; j < ng; j++)
		for (int i = 0; i < g[j].n; i++) {
			const an_run *r = &runs[g[j].run[i]];
			fprintf(f, "%d,", j);
			csv_str(f, labels[j]);
			fprintf(f, ",%s,%ld,%ld,%.17g,%d,%s,%s\n", r->id, r->replicate, r->seed, g[j].t[i], g[j].ev[i], r->state,
				acct_use_name(r->use));
		}
	fclose(f);
	if (!(f = cli_fopen(&o, "waiting_accounting.csv", path, sizeof path, &e)))
		goto out;
	acct_runs_csv(f, runs, k, labels);
	fclose(f);
	/* survival curves, starting at (0, 1) */
	if (!(f = cli_fopen(&o, "waiting_km.csv", path, sizeof path, &e)))
		goto out;
	fprintf(f, "group_index,group,t,n_risk,events,censored,S,se,lo,hi\n");
	for (int j = 0; j < ng; j++) {
		fprintf(f, "%d,", j);
		csv_str(f, labels[j]);
		fprintf(f, ",0,%ld,0,0,1,0,1,1\n", km[j].n);
		for (size_t i = 0; i < km[j].m; i++) {
			double s = km[j].s[i], se = km[j].se[i];
			fprintf(f, "%d,", j);
			csv_str(f, labels[j]);
			fprintf(f, ",%.17g,%ld,%ld,%ld,%.17g,%.17g,%.17g,%.17g\n", km[j].t[i], km[j].n_risk[i], km[j].d[i],
				km[j].c[i], s, se, fmax(0, s - z * se), fmin(1, s + z * se));
		}
	}
	fclose(f);
	/* histogram of observed waiting times (risen runs), common bins */
	double bw = tmax_all > 0 ? tmax_all / (double)o.bins : 1;
	if (!(f = cli_fopen(&o, "waiting_hist.csv", path, sizeof path, &e)))
		goto out;
	fprintf(f, "group_index,group,lo,hi,count\n");
	for (int j = 0; j < ng; j++)
		for (long b = 0; b < o.bins; b++) {
			long c = 0;
			for (int i = 0; i < g[j].n; i++) {
				long q = (long)floor(g[j].t[i] / bw);
				if (q >= o.bins)
					q = o.bins - 1;
				c += g[j].ev[i] && q == b;
			}
			fprintf(f, "%d,", j);
			csv_str(f, labels[j]);
			fprintf(f, ",%.17g,%.17g,%ld\n", b * bw, (b + 1) * bw, c);
		}
	fclose(f);
	f = NULL;

	/* summary: table, CSV, database */
	FILE *s = cli_fopen(&o, "waiting_summary.csv", path, sizeof path, &e);
	if (!s)
		goto out;
	fprintf(s, "group,runs,risen,fraction_risen,median,median_lo,median_hi,t_max,s_end,s_end_lo,s_end_hi");
	acct_csv_head(s);
	fputc('\n', s);
	printf("%-36s %5s %5s %6s %9s %21s %8s %6s %6s %10s\n", "group", "used", "risen", "frac", "median_s",
	       "CI (Brookmeyer-Crowley)", "t_max_s", "S_end", "failed", "unfinished");
	if (!o.no_store && adb_store_begin(&d, o.campaign, "waiting", &e)) {
		fclose(s);
		goto out;
	}
	for (int j = 0; j < ng && !e.code; j++) {
		double lo, hi, med = km_median(&km[j], z, &lo, &hi), tm = 0;
		for (int i = 0; i < g[j].n; i++)
			tm = fmax(tm, g[j].t[i]);
		double se_end = km[j].m ? km[j].se[km[j].m - 1] : 0, s_end = km[j].m ? km[j].s[km[j].m - 1] : 1;
		double frac = (double)km[j].events / (double)km[j].n;
		char ci[64], ms[32];
		snprintf(ms, sizeof ms, isnan(med) ? ">%.3g" : "%.3f", isnan(med) ? tm : med);
		if (isnan(lo))
			snprintf(ci, sizeof ci, "[>%.3g, -]", tm);
		else if (isnan(hi))
			snprintf(ci, sizeof ci, "[%.3f, >%.3g]", lo, tm);
		else
			snprintf(ci, sizeof ci, "[%.3f, %.3f]", lo, hi);
		printf("%-36s %5ld %5ld %6.3f %9s %21s %8.3f %6.3f %6ld %10ld\n", labels[j], km[j].n, km[j].events, frac, ms,
		       ci, tm, s_end, A[j].failed, A[j].n[AN_PENDING] + A[j].n[AN_RUNNING]);
		csv_str(s, labels[j]);
		fprintf(s, ",%ld,%ld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", km[j].n, km[j].events, frac, med, lo,
			hi, tm, s_end, fmax(0, s_end - z * se_end), fmin(1, s_end + z * se_end));
		acct_csv_row(s, &A[j]);
		fputc('\n', s);
		if (!o.no_store) {
			const char *L = labels[j];
			long n = km[j].n;
			adb_store(&d, o.campaign, "waiting", VERSION, L, "runs", (double)n, NAN, NAN, n, &e);
			adb_store(&d, o.campaign, "waiting", VERSION, L, "risen", (double)km[j].events, NAN, NAN, n, &e);
			adb_store(&d, o.campaign, "waiting", VERSION, L, "fraction_risen", frac, NAN, NAN, n, &e);
			adb_store(&d, o.campaign, "waiting", VERSION, L, "median", med, lo, hi, n, &e);
			adb_store(&d, o.campaign, "waiting", VERSION, L, "t_max", tm, NAN, NAN, n, &e);
			adb_store(&d, o.campaign, "waiting", VERSION, L, "s_end", s_end, fmax(0, s_end - z * se_end),
				  fmin(1, s_end + z * se_end), n, &e);
			acct_store(&d, o.campaign, "waiting", VERSION, L, &A[j], &e);
		}
	}
	fclose(s);
	if (!o.no_store && adb_store_end(&d, !e.code, &e))
		goto out;
	if (e.code)
		goto out;
	acct_print(stdout, "waiting", labels, A, ng, nold, o.all_versions);
	if (f_ev + f_cens)
		printf("# %ld failed run%s %s observed up to the failure: %ld had risen before it (events at their waiting"
		       " times), %ld are censored at the failure time; this assumes that the failure is independent of"
		       " the rise (non-informative censoring)\n", f_ev + f_cens, f_ev + f_cens == 1 ? "" : "s",
		       f_ev + f_cens == 1 ? "is" : "are", f_ev, f_cens);

	if (!o.no_plot) {
		if (!(f = gp_open(&o, "waiting_km", 900, 520, script, png, sizeof script, &e)))
			goto out;
		fprintf(f, "set title 'Intruder waiting time: Kaplan-Meier survival (+ censored)'\n"
			   "set xlabel 'time since shaking began t (s)'\nset ylabel 'S(t) = P(not yet risen)'\n"
			   "set yrange [0:1.05]\nset xrange [0:*]\nplot ");
		for (int j = 0; j < ng; j++) {
			fprintf(f, "%s'waiting_km.csv' skip 1 using 3:($1==%d?$7:1/0) with steps lw 2 lc %d title ",
				j ? ", \\\n  " : "", j, j + 1);
			gp_str(f, labels[j]);
			fprintf(f, ", 'waiting_km.csv' skip 1 using 3:($1==%d&&$6>0?$7:1/0) with points pt 2 ps 1.2 lc %d notitle",
				j, j + 1);
		}
		fprintf(f, "\n");
		fclose(f);
		f = NULL;
		if (gp_run(script, png, &e))
			goto out;
		if (!(f = gp_open(&o, "waiting_hist", 900, 520, script, png, sizeof script, &e)))
			goto out;
		fprintf(f, "set title 'Intruder waiting time: histogram of the risen runs'\n"
			   "set xlabel 'waiting time (s)'\nset ylabel 'runs'\nset yrange [0:*]\nset xrange [0:%.17g]\n"
			   "set style fill transparent solid 0.35 border\nset boxwidth %.17g absolute\nplot ",
			bw * (double)o.bins, bw / ng);
		for (int j = 0; j < ng; j++) {
			fprintf(f, "%s'waiting_hist.csv' skip 1 using ($3+%.17g):($1==%d?$5:1/0) with boxes lc %d title ",
				j ? ", \\\n  " : "", bw / ng * (j + 0.5), j, j + 1);
			gp_str(f, labels[j]);
		}
		fprintf(f, "\n");
		fclose(f);
		f = NULL;
		if (gp_run(script, png, &e))
			goto out;
		printf("# figures: %s/waiting_km.png %s/waiting_hist.png\n", o.out, o.out);
	}
	printf("# csv: %s/waiting_{runs,km,hist,summary,accounting}.csv\n", o.out);
out:
	if (f)
		fclose(f);
	for (int j = 0; g && j < ng; j++) {
		free(g[j].t);
		free(g[j].ev);
		free(g[j].run);
		if (km)
			km_free(&km[j]);
	}
	free(g);
	free(km);
	free(A);
	an_labels_free(labels, ng);
	adb_runs_free(runs, nr);
	adb_close(&d);
	if (e.code) {
		fprintf(stderr, "waiting: %s\n", e.msg);
		return e.code == SB_EUSAGE ? 1 : 2;
	}
	return 0;
}
