/* onset_main.c - bin/onset: convective flux through a plane versus frequency, and the
 * onset frequency per group of runs (sigmoid midpoint and threshold crossing, bootstrap
 * over seeds). Only this file prints and exits. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acct.h"
#include "adb.h"
#include "cli.h"
#include "flux.h"
#include "onsetfit.h"

#define VERSION "2"

/* a run whose records are in the statistic: finished, or failed and used up to it */
#define USED(r) ((r)->use == AN_USED || (r)->use == AN_PARTLY)

static const char *HELP =
	"usage: onset CAMPAIGN [--db FILE] [--runs DIR] [--out DIR] [--by KEYS] [--band LO:HI]\n"
	"             [--skip FRAC] [--threshold PHI] [--boot N] [--seed S] [--level L]\n"
	"             [--all-versions] [--no-plot] [--no-store]\n\n"
	"Onset of convection. For every run at a fixed frequency (ramp = none) with flux =\n"
	"yes: Phi through the plane = the mean of Phi over the height lines that\n"
	"lie in the band LO..HI of the settled surface height (default 0.4:0.6, the middle\n"
	"of the bed), averaged over the periods after the first FRAC of them (default 0.2).\n"
	"Per group (default: radius_ratio, depth and every other swept axis but frequency;\n"
	"radius_ratio = 0 is the system without intruder), with all runs and seeds pooled:\n"
	"  sigmoid    midpoint f0 of  Phi = b + a / (1 + exp(-(f - f0) / w))  fitted by\n"
	"             nonlinear least squares (GSL trust region), its width w and step a;\n"
	"  threshold  first frequency at which the mean Phi per frequency (oriented to rise)\n"
	"             reaches PHI (default: halfway between its smallest and largest value),\n"
	"             interpolated linearly;\n"
	"both with percentile bootstrap intervals over seeds (replicates resampled with\n"
	"replacement, all frequencies of a drawn seed together; over runs when a group has\n"
	"one seed), and the spread (standard deviation) of the per-seed threshold estimates.\n\n"
	"No run is dropped silently: per group the table, onset_summary.csv and the stored\n"
	"rows count the runs used; the failed ones by status, of which those used up to the\n"
	"failure (a failed run's file holds its periods before it: used after the transient\n"
	"of the run as planned, floor(FRAC * duration * f) periods; one point like any run);\n"
	"the unusable ones (failed without an output file, or within the transient); the\n"
	"unreadable files (missing, truncated); the runs still pending or running (then the\n"
	"campaign is not finished and the numbers will change: the output says so).\n"
	"onset_accounting.csv has one row per run with what became of it and why.\n\n"
	"  --db FILE, --runs DIR, --out DIR   as for every tool (waiting --help)\n"
	"  --by KEYS        group by these parameters (comma separated)\n"
	"  --boot N         bootstrap replicates (default 1000); --seed S its seed (default 1)\n"
	"  --level L        confidence level (default 0.95)\n"
	"  --all-versions   also the runs of earlier versions of the campaign file (run.current\n"
	"                   = 0, kept by study run --keep-old); by default the current grid's\n"
	"  --no-plot        no PNG;  --no-store  nothing written to the database\n\n"
	"Writes onset_runs.csv (Phi per run), onset_seeds.csv (per-seed estimates),\n"
	"onset_summary.csv, onset_accounting.csv, onset.png; stores per group in `analysis`\n"
	"(tool 'onset'): runs (used), seeds, sigmoid_f0 (lo, hi), sigmoid_width, sigmoid_step,\n"
	"threshold_f (lo, hi), threshold_seed_sd, and the accounting: runs_failed,\n"
	"runs_failed_used, failed_used_s, failed_planned_s, runs_unusable, runs_unreadable,\n"
	"runs_pending, runs_running, failed_STATUS per status.\n"
	"Exit codes: 0 ok, 1 usage or no usable runs, 2 I/O.\n";

int main(int argc, char **argv)
{
	an_opts o = {.tool = "onset", .version = VERSION};
	int pr = cli_parse(&o, argc, argv, HELP, " by band skip threshold boot seed level ");
	if (pr)
		return pr < 0 ? 0 : 1;
	flux_opts fo = {o.band_lo, o.band_hi, o.skip};
	sb_err e = {0};
	adb d;
	an_run *runs = NULL;
	int nr = 0, ng = 0, k = 0;
	char **labels = NULL;
	double *phi = NULL, *xs = NULL, *ys = NULL;
	long *us = NULL;
	onset_res *R = NULL;
	an_acct *A = NULL;
	FILE *f = NULL, *s = NULL;
	char path[1400], script[1400], png[1400];
	if (adb_open(&d, o.db, !o.no_store, &e) || adb_runs(&d, o.campaign, o.runs, &runs, &nr, &e))
		goto out;
	phi = calloc((size_t)(nr ? nr : 1), sizeof *phi);
	xs = calloc((size_t)(nr ? nr : 1), sizeof *xs);
	ys = calloc((size_t)(nr ? nr : 1), sizeof *ys);
	us = calloc((size_t)(nr ? nr : 1), sizeof *us);
	if (!phi || !xs || !ys || !us) {
		sb_errf(&e, SB_ENOMEM, "out of memory");
		goto out;
	}
	/* every fixed-frequency run with flux = yes is accounted for, whatever its state */
	long nold = 0;
	for (int i = 0; i < nr; i++) {
		const char *ramp = an_str(&runs[i], "ramp"), *fl = an_str(&runs[i], "flux");
		if ((ramp && strcmp(ramp, "none")) || (fl && strcmp(fl, "yes")) ||
		    acct_version_skip(&runs[i], o.all_versions, &nold))
			continue;
		an_run *r = &runs[i];
		flux_data fd;
		double v = NAN;
		if (!flux_load(r, &fd)) {
			v = flux_summary(&fd, &fo);
			const double dur = an_num(r, "duration", NAN), T = fd.P ? fd.t[fd.P - 1] : 0;
			if (isfinite(v) && !strcmp(r->state, "failed"))
				acct_set(r, AN_PARTLY, T, dur, "failed at t = %g s (%s): the %zu periods before it used, after the"
					 " first %zu", r->status_time, r->status, fd.P, flux_first(&fd, &fo));
			else if (isfinite(v))
				acct_set(r, AN_USED, NAN, NAN, NULL);
			else if (!strcmp(r->state, "failed"))
				acct_set(r, AN_UNUSABLE, NAN, NAN, "failed at t = %g s (%s) within the transient: %zu periods"
					 " recorded, the first %zu of the planned %zu are the transient", r->status_time,
					 r->status, fd.P, flux_first(&fd, &fo), fd.planned);
			else
				acct_set(r, AN_UNUSABLE, NAN, NAN, "no flux period recorded");
			flux_free(&fd);
		} else if (r->use == AN_UNREADABLE)
			fprintf(stderr, "onset: warning: %s (counted as unreadable)\n", r->why);
		an_run t = runs[k];
		runs[k] = runs[i];
		runs[i] = t;
		phi[k++] = v;
	}
	if (!k) {
		int known = 0;
		if (!adb_campaign_exists(&d, o.campaign, &known, &e) && !known)
			sb_errf(&e, SB_EUSAGE, "campaign '%s' is not in %s", o.campaign, o.db);
		else
			sb_errf(&e, SB_EUSAGE, "campaign '%s': no finished fixed-frequency run with flux = yes in %s%s",
				o.campaign, o.db, nold ? " of the current grid (--all-versions)" : "");
		goto out;
	}
	static const char *const always[] = {"radius_ratio", "depth", NULL};
	static const char *const drop[] = {"frequency", "ramp", "ramp_from", "ramp_to", NULL};
	char keys[AN_MAXKEYS][48];
	int nk;
	if (cli_keys(&o, &d, always, drop, keys, &nk, &e))
		goto out;
	ng = an_group_runs(runs, k, keys, nk, &labels);
	R = calloc((size_t)(ng > 0 ? ng : 1), sizeof *R);
	if (ng < 0 || !R || acct_tally(runs, k, ng, &A)) {
		sb_errf(&e, SB_ENOMEM, "out of memory");
		goto out;
	}
	long used = 0;
	for (int j = 0; j < ng; j++)
		used += acct_used(&A[j]);
	if (!used) {
		acct_print(stdout, "onset", labels, A, ng, nold, o.all_versions);
		sb_errf(&e, SB_EUSAGE, "campaign '%s': none of its %d fixed-frequency runs with flux = yes is usable yet",
			o.campaign, k);
		goto out;
	}
	if (cli_outdir(&o, &e))
		goto out;
	if (!(f = cli_fopen(&o, "onset_runs.csv", path, sizeof path, &e)))
		goto out;
	fprintf(f, "group_index,group,run,replicate,seed,radius_ratio,depth,frequency,phi,use,used_s\n");
	for (int j = 0; j < ng; j++)
		for (int i = 0; i < k; i++)
			if (runs[i].group == j && USED(&runs[i])) {
				fprintf(f, "%d,", j);
				csv_str(f, labels[j]);
				fprintf(f, ",%s,%ld,%ld,%.17g,%.17g,%.17g,%.17g,%s,%.17g\n", runs[i].id, runs[i].replicate,
					runs[i].seed, an_num(&runs[i], "radius_ratio", NAN), an_num(&runs[i], "depth", NAN),
					an_num(&runs[i], "frequency", NAN), phi[i], acct_use_name(runs[i].use), runs[i].used_s);
			}
	fclose(f);
	f = NULL;
	if (!(f = cli_fopen(&o, "onset_accounting.csv", path, sizeof path, &e)))
		goto out;
	acct_runs_csv(f, runs, k, labels);
	fclose(f);
	f = NULL;
	if (!(f = cli_fopen(&o, "onset_seeds.csv", path, sizeof path, &e)) ||
	    !(s = cli_fopen(&o, "onset_summary.csv", path, sizeof path, &e)))
		goto out;
	fprintf(f, "group_index,group,seed_unit,sigmoid_f0,threshold_f\n");
	fprintf(s, "group,intruder,runs,seeds,sigmoid_ok,sigmoid_f0,sigmoid_f0_lo,sigmoid_f0_hi,sigmoid_width,"
		   "sigmoid_step,threshold_f,threshold_f_lo,threshold_f_hi,threshold_seed_sd,boot_ok");
	acct_csv_head(s);
	fputc('\n', s);
	printf("%-30s %4s %4s %5s %22s %7s %22s %7s %6s %7s\n", "group", "intr", "used", "seeds", "sigmoid f0 [CI] (Hz)",
	       "width", "threshold f [CI] (Hz)", "seed_sd", "failed", "unfinished");
	if (!o.no_store && adb_store_begin(&d, o.campaign, "onset", &e))
		goto out;
	for (int j = 0; j < ng && !e.code; j++) {
		size_t np = 0;
		double ratio = 0;
		for (int i = 0; i < k; i++) {
			if (runs[i].group != j)
				continue;
			ratio = an_num(&runs[i], "radius_ratio", 0);
			if (!USED(&runs[i]))
				continue;
			xs[np] = an_num(&runs[i], "frequency", NAN);
			ys[np] = phi[i];
			us[np++] = runs[i].replicate;
		}
		onset_res *r = &R[j];
		if (!np) { /* every run of the group failed, is unreadable or not finished */
			r->thr = r->fit_lo = r->fit_hi = r->thr_lo = r->thr_hi = r->seed_sd = NAN;
		} else if (onset_estimate(xs, ys, us, np, o.threshold, (size_t)(o.boot > 1 ? o.boot : 0), o.seed, o.level, r)) {
			sb_errf(&e, SB_ENOMEM, "out of memory");
			break;
		}
		for (size_t u = 0; u < r->units; u++) {
			fprintf(f, "%d,", j);
			csv_str(f, labels[j]);
			fprintf(f, ",%ld,%.17g,%.17g\n", r->unit_id[u], r->seed_fit[u], r->seed_thr[u]);
		}
		const sig_fit *F = &r->fit;
		char c1[64], c2[64];
		snprintf(c1, sizeof c1, "%.3f [%.3f, %.3f]", F->ok ? F->x0 : NAN, r->fit_lo, r->fit_hi);
		snprintf(c2, sizeof c2, "%.3f [%.3f, %.3f]", r->thr, r->thr_lo, r->thr_hi);
		printf("%-30s %4s %4zu %5zu %22s %7.3f %22s %7.3f %6ld %7ld\n", labels[j], ratio > 0 ? "yes" : "no", np,
		       r->units, c1, F->ok ? F->w : NAN, c2, r->seed_sd, A[j].failed, A[j].n[AN_PENDING] + A[j].n[AN_RUNNING]);
		csv_str(s, labels[j]);
		fprintf(s, ",%d,%zu,%zu,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%zu", ratio > 0, np,
			r->units, F->ok, F->ok ? F->x0 : NAN, r->fit_lo, r->fit_hi, F->ok ? F->w : NAN, F->ok ? F->a : NAN,
			r->thr, r->thr_lo, r->thr_hi, r->seed_sd, r->boot_ok);
		acct_csv_row(s, &A[j]);
		fputc('\n', s);
		if (!o.no_store) {
			const char *L = labels[j];
			long n = (long)np;
			adb_store(&d, o.campaign, "onset", VERSION, L, "runs", (double)np, NAN, NAN, n, &e);
			adb_store(&d, o.campaign, "onset", VERSION, L, "seeds", (double)r->units, NAN, NAN, n, &e);
			adb_store(&d, o.campaign, "onset", VERSION, L, "sigmoid_f0", F->ok ? F->x0 : NAN, r->fit_lo, r->fit_hi, n,
				  &e);
			adb_store(&d, o.campaign, "onset", VERSION, L, "sigmoid_width", F->ok ? F->w : NAN, NAN, NAN, n, &e);
			adb_store(&d, o.campaign, "onset", VERSION, L, "sigmoid_step", F->ok ? F->a : NAN, NAN, NAN, n, &e);
			adb_store(&d, o.campaign, "onset", VERSION, L, "threshold_f", r->thr, r->thr_lo, r->thr_hi, n, &e);
			adb_store(&d, o.campaign, "onset", VERSION, L, "threshold_seed_sd", r->seed_sd, NAN, NAN, n, &e);
			acct_store(&d, o.campaign, "onset", VERSION, L, &A[j], &e);
		}
	}
	fclose(f);
	fclose(s);
	f = s = NULL;
	if (!o.no_store && adb_store_end(&d, !e.code, &e))
		goto out;
	if (e.code)
		goto out;
	acct_print(stdout, "onset", labels, A, ng, nold, o.all_versions);
	long partly = 0;
	for (int j = 0; j < ng; j++)
		partly += A[j].n[AN_PARTLY];
	if (partly)
		printf("# %ld failed run%s enter%s with the periods they recorded before the failure (after the transient of"
		       " the run as planned): one point each, like a finished run\n", partly,
		       partly == 1 ? "" : "s", partly == 1 ? "s" : "");
	if (!o.no_plot) {
		if (!(f = gp_open(&o, "onset", 1000, 560, script, png, sizeof script, &e)))
			goto out;
		fprintf(f, "set title 'Convective flux through the plane (%.2f-%.2f of the bed height) vs frequency'\n"
			   "set xlabel 'frequency f (Hz)'\nset ylabel 'Phi (particles per period)'\n"
			   "set offsets graph 0.03, graph 0.03, graph 0.05, graph 0.05\nset samples 500\n",
			o.band_lo, o.band_hi);
		for (int j = 0; j < ng; j++)
			if (R[j].fit.ok)
				fprintf(f, "s%d(x) = %.17g + %.17g / (1 + exp(-(x - %.17g) / %.17g))\n", j, R[j].fit.b, R[j].fit.a,
					R[j].fit.x0, R[j].fit.w);
		fprintf(f, "plot ");
		for (int j = 0; j < ng; j++) {
			fprintf(f, "%s'onset_runs.csv' skip 1 using 8:($1==%d?$9:1/0) with points pt 7 ps 0.8 lc %d title ",
				j ? ", \\\n  " : "", j, j + 1);
			gp_str(f, labels[j]);
			if (R[j].fit.ok)
				fprintf(f, ", s%d(x) with lines lw 2 lc %d notitle", j, j + 1);
		}
		fprintf(f, "\n");
		fclose(f);
		f = NULL;
		if (gp_run(script, png, &e))
			goto out;
		printf("# figure: %s\n", png);
	}
	printf("# csv: %s/onset_{runs,seeds,summary,accounting}.csv\n", o.out);
out:
	if (f)
		fclose(f);
	if (s)
		fclose(s);
	for (int j = 0; R && j < ng; j++)
		onset_res_free(&R[j]);
	free(R);
	free(A);
	free(phi);
	free(xs);
	free(ys);
	free(us);
	an_labels_free(labels, ng);
	adb_runs_free(runs, nr);
	adb_close(&d);
	if (e.code) {
		fprintf(stderr, "onset: %s\n", e.msg);
		return e.code == SB_EUSAGE ? 1 : 2;
	}
	return 0;
}
