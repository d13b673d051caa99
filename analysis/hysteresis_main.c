/* hysteresis_main.c - bin/hysteresis: transition frequencies of up and down frequency
 * ramps and their difference, bootstrap over seeds. Only this file prints and exits. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acct.h"
#include "adb.h"
#include "cli.h"
#include "flux.h"
#include "hyst.h"

#define VERSION "3"

static const char *HELP =
	"usage: hysteresis CAMPAIGN [--db FILE] [--runs DIR] [--out DIR] [--by KEYS] [--band LO:HI]\n"
	"                  [--smooth K] [--threshold PHI] [--boot N] [--seed S] [--level L]\n"
	"                  [--all-versions] [--no-plot] [--no-store]\n\n"
	"Hysteresis of the convection onset. Uses the runs with a frequency ramp\n"
	"(ramp = updown: ramp_from -> ramp_to -> ramp_from, split at the turning period; or\n"
	"ramp = linear, up when ramp_to > ramp_from, down otherwise) and a /flux group.\n"
	"Per period: Phi through the plane (mean over the height lines in the band LO..HI of\n"
	"the surface height, default 0.4:0.6) against the period's frequency (/flux/frequency),\n"
	"smoothed by a centred running mean over K periods of the same branch (default 5).\n"
	"Periods shaken during ramp_hold (at ramp_from, before the ramp starts: the start of\n"
	"shaking) belong to no branch.\n"
	"Per group (default: radius_ratio, depth and every swept axis except frequency, seed\n"
	"and the ramp keys) and branch, with the seeds pooled: the transition frequency as\n"
	"the midpoint of a fitted sigmoid and as the threshold crossing (as in onset --help),\n"
	"f_up, f_down and their difference f_up - f_down, with percentile bootstrap intervals\n"
	"over seeds (a drawn seed brings both its branches, so the difference is paired).\n"
	"A failed run is used up to its failure (its file holds the periods before it: a\n"
	"branch cut short is used as far as it got). Per group the table, the summary and\n"
	"the stored rows count the runs used, failed (by status; used up to the failure or\n"
	"unusable), unreadable, pending and running, as onset --help describes;\n"
	"hysteresis_accounting.csv has one row per run.\n\n"
	"  --db FILE, --runs DIR, --out DIR   as for every tool (waiting --help)\n"
	"  --boot N, --seed S, --level L      bootstrap replicates (1000), seed (1), level (0.95)\n"
	"  --all-versions   also the runs of earlier versions of the campaign file (run.current = 0)\n"
	"  --no-plot, --no-store\n\n"
	"Writes hysteresis_periods.csv, hysteresis_summary.csv, hysteresis_accounting.csv,\n"
	"hysteresis.png (points and the fitted sigmoids of both branches); stores per group\n"
	"in `analysis` (tool 'hysteresis'): runs (used), seeds, up_sigmoid_f, down_sigmoid_f,\n"
	"diff_sigmoid, up_threshold_f, down_threshold_f, diff_threshold (value, lo, hi) and\n"
	"the accounting (runs_failed, runs_failed_used, ..., as onset --help lists).\n"
	"Exit codes: 0 ok, 1 usage or no usable runs, 2 I/O.\n";

int main(int argc, char **argv)
{
	an_opts o = {.tool = "hysteresis", .version = VERSION};
	int pr = cli_parse(&o, argc, argv, HELP, " by band smooth threshold boot seed level ");
	if (pr)
		return pr < 0 ? 0 : 1;
	flux_opts fo = {o.band_lo, o.band_hi, 0};
	sb_err e = {0};
	adb d;
	an_run *runs = NULL;
	int nr = 0, ng = 0, k = 0;
	char **labels = NULL;
	hyst_data *G = NULL;
	hyst_res *R = NULL;
	an_acct *A = NULL;
	flux_data *F = NULL;
	double *raw = NULL, *sm = NULL;
	FILE *f = NULL, *s = NULL;
	char path[1400], script[1400], png[1400];
	if (adb_open(&d, o.db, !o.no_store, &e) || adb_runs(&d, o.campaign, o.runs, &runs, &nr, &e))
		goto out;
	F = calloc((size_t)(nr ? nr : 1), sizeof *F);
	if (!F) {
		sb_errf(&e, SB_ENOMEM, "out of memory");
		goto out;
	}
	/* every ramp run with flux = yes is accounted for, whatever its state */
	size_t pmax = 1;
	long nold = 0;
	for (int i = 0; i < nr; i++) {
		an_run *r = &runs[i];
		const char *ramp = an_str(r, "ramp"), *fl = an_str(r, "flux");
		if (!ramp || !strcmp(ramp, "none") || (fl && strcmp(fl, "yes")) ||
		    acct_version_skip(r, o.all_versions, &nold))
			continue;
		flux_data *D = &F[k];
		if (!flux_load(r, D)) {
			hyst_leg leg[2];
			const int nl = D->P < 2 ? 0
						: hyst_legs(D, !strcmp(ramp, "updown"), an_num(r, "ramp_from", NAN),
							    an_num(r, "ramp_to", NAN), an_num(r, "ramp_hold", 0), leg);
			const int failed = !strcmp(r->state, "failed");
			if (!nl)
				acct_set(r, AN_UNUSABLE, NAN, NAN, "%s%s%s: %zu periods recorded, too few after the hold",
					 failed ? "failed (" : "finished", failed ? r->status : "", failed ? ")" : "", D->P);
			else if (failed)
				acct_set(r, AN_PARTLY, D->t[D->P - 1], an_num(r, "duration", NAN),
					 "failed at t = %g s (%s): the %zu periods before it used", r->status_time, r->status, D->P);
			else
				acct_set(r, AN_USED, NAN, NAN, NULL);
			if (!nl)
				flux_free(D);
			pmax = D->P > pmax ? D->P : pmax;
		} else if (r->use == AN_UNREADABLE)
			fprintf(stderr, "hysteresis: warning: %s (counted as unreadable)\n", r->why);
		an_run t = runs[k];
		runs[k] = runs[i];
		runs[i] = t;
		k++;
	}
	if (!k) {
		int known = 0;
		if (!adb_campaign_exists(&d, o.campaign, &known, &e) && !known)
			sb_errf(&e, SB_EUSAGE, "campaign '%s' is not in %s", o.campaign, o.db);
		else
			sb_errf(&e, SB_EUSAGE,
				"campaign '%s': no finished ramp run (ramp = linear|updown) with flux = yes in %s%s", o.campaign,
				o.db, nold ? " of the current grid (--all-versions)" : "");
		goto out;
	}
	static const char *const always[] = {"radius_ratio", "depth", NULL};
	static const char *const drop[] = {"frequency", "ramp", "ramp_from", "ramp_to", "ramp_hold", NULL};
	char keys[AN_MAXKEYS][48];
	int nk;
	if (cli_keys(&o, &d, always, drop, keys, &nk, &e))
		goto out;
	/* grouping reorders nothing: it only labels */
	ng = an_group_runs(runs, k, keys, nk, &labels);
	G = calloc((size_t)(ng > 0 ? ng : 1), sizeof *G);
	R = calloc((size_t)(ng > 0 ? ng : 1), sizeof *R);
	raw = malloc(sizeof *raw * pmax);
	sm = malloc(sizeof *sm * pmax);
	if (ng < 0 || !G || !R || !raw || !sm || acct_tally(runs, k, ng, &A)) {
		sb_errf(&e, SB_ENOMEM, "out of memory");
		goto out;
	}
	long used = 0;
	for (int j = 0; j < ng; j++)
		used += acct_used(&A[j]);
	if (!used) {
		acct_print(stdout, "hysteresis", labels, A, ng, nold, o.all_versions);
		sb_errf(&e, SB_EUSAGE, "campaign '%s': none of its %d ramp runs with flux = yes is usable yet", o.campaign, k);
		goto out;
	}
	for (int j = 0; j < ng; j++)
		hyst_init(&G[j], o.threshold);
	if (cli_outdir(&o, &e) || !(f = cli_fopen(&o, "hysteresis_periods.csv", path, sizeof path, &e)))
		goto out;
	fprintf(f, "group_index,group,run,replicate,branch,period,frequency,phi,phi_smooth,use\n");
	for (int i = 0; i < k; i++) {
		if (runs[i].use != AN_USED && runs[i].use != AN_PARTLY)
			continue;
		hyst_data *g = &G[runs[i].group];
		flux_data *D = &F[i];
		size_t l0, l1;
		flux_band(D, &fo, &l0, &l1);
		hyst_leg leg[2];
		int nl = hyst_legs(D, !strcmp(an_str(&runs[i], "ramp"), "updown"), an_num(&runs[i], "ramp_from", NAN),
				   an_num(&runs[i], "ramp_to", NAN), an_num(&runs[i], "ramp_hold", 0), leg);
		if (hyst_add_run(g, runs[i].replicate)) {
			sb_errf(&e, SB_ENOMEM, "out of memory");
			goto out;
		}
		for (size_t p = 0; p < D->P; p++)
			raw[p] = flux_plane(D, p, l0, l1);
		for (int q = 0; q < nl; q++) {
			hyst_smooth(raw, leg[q].a, leg[q].b, o.smooth, sm);
			for (size_t p = leg[q].a; p < leg[q].b; p++) {
				if (hyst_add(g, leg[q].branch, D->f[p], sm[p], runs[i].replicate)) {
					sb_errf(&e, SB_ENOMEM, "out of memory");
					goto out;
				}
				fprintf(f, "%d,", runs[i].group);
				csv_str(f, labels[runs[i].group]);
				fprintf(f, ",%s,%ld,%s,%zu,%.17g,%.17g,%.17g,%s\n", runs[i].id, runs[i].replicate,
					leg[q].branch == HYST_DOWN ? "down" : "up", p, D->f[p], raw[p], sm[p],
					acct_use_name(runs[i].use));
			}
		}
	}
	fclose(f);
	f = NULL;
	if (!(f = cli_fopen(&o, "hysteresis_accounting.csv", path, sizeof path, &e)))
		goto out;
	acct_runs_csv(f, runs, k, labels);
	fclose(f);
	f = NULL;
	if (!(s = cli_fopen(&o, "hysteresis_summary.csv", path, sizeof path, &e)))
		goto out;
	fprintf(s, "group,runs,seeds,up_sigmoid_f,up_lo,up_hi,down_sigmoid_f,down_lo,down_hi,diff_sigmoid,diff_lo,diff_hi,"
		   "up_threshold_f,up_thr_lo,up_thr_hi,down_threshold_f,down_thr_lo,down_thr_hi,diff_threshold,"
		   "diff_thr_lo,diff_thr_hi,boot_ok");
	acct_csv_head(s);
	fputc('\n', s);
	printf("%-26s %4s %5s %22s %22s %24s %8s %8s %8s %6s %10s\n", "group", "used", "seeds", "f_up sigmoid [CI]",
	       "f_down sigmoid [CI]", "up - down [CI] (Hz)", "f_up_thr", "f_dn_thr", "diff_thr", "failed", "unfinished");
	if (!o.no_store && adb_store_begin(&d, o.campaign, "hysteresis", &e))
		goto out;
	for (int j = 0; j < ng && !e.code; j++) {
		hyst_data *g = &G[j];
		hyst_res *r = &R[j];
		if (hyst_estimate(g, (size_t)(o.boot > 1 ? o.boot : 0), o.seed, o.level, r)) {
			sb_errf(&e, SB_ENOMEM, "out of memory");
			break;
		}
		char c[3][64];
		for (int q = 0; q < 3; q++)
			snprintf(c[q], sizeof c[q], "%.3f [%.3f, %.3f]", r->v[q], r->lo[q], r->hi[q]);
		printf("%-26s %4zu %5zu %22s %22s %24s %8.3f %8.3f %8.3f %6ld %10ld\n", labels[j], g->nruns, g->nu, c[0], c[1],
		       c[2], r->v[3], r->v[4], r->v[5], A[j].failed, A[j].n[AN_PENDING] + A[j].n[AN_RUNNING]);
		csv_str(s, labels[j]);
		fprintf(s, ",%zu,%zu", g->nruns, g->nu);
		for (int q = 0; q < 6; q++)
			fprintf(s, ",%.17g,%.17g,%.17g", r->v[q], r->lo[q], r->hi[q]);
		fprintf(s, ",%zu", r->boot_ok);
		acct_csv_row(s, &A[j]);
		fputc('\n', s);
		if (!o.no_store) {
			static const char *const names[6] = {"up_sigmoid_f", "down_sigmoid_f", "diff_sigmoid",
							     "up_threshold_f", "down_threshold_f", "diff_threshold"};
			long n = (long)g->nruns;
			adb_store(&d, o.campaign, "hysteresis", VERSION, labels[j], "runs", (double)g->nruns, NAN, NAN, n, &e);
			adb_store(&d, o.campaign, "hysteresis", VERSION, labels[j], "seeds", (double)g->nu, NAN, NAN, n, &e);
			for (int q = 0; q < 6; q++)
				adb_store(&d, o.campaign, "hysteresis", VERSION, labels[j], names[q], r->v[q], r->lo[q], r->hi[q],
					  n, &e);
			acct_store(&d, o.campaign, "hysteresis", VERSION, labels[j], &A[j], &e);
		}
	}
	fclose(s);
	s = NULL;
	if (!o.no_store && adb_store_end(&d, !e.code, &e))
		goto out;
	if (e.code)
		goto out;
	acct_print(stdout, "hysteresis", labels, A, ng, nold, o.all_versions);
	long partly = 0;
	for (int j = 0; j < ng; j++)
		partly += A[j].n[AN_PARTLY];
	if (partly)
		printf("# %ld failed run%s enter%s with the periods they recorded before the failure (a leg cut short by"
		       " it is used as far as it got)\n", partly, partly == 1 ? "" : "s", partly == 1 ? "s" : "");
	if (!o.no_plot) {
		if (!(f = gp_open(&o, "hysteresis", 1000, 560, script, png, sizeof script, &e)))
			goto out;
		fprintf(f, "set title 'Flux through the plane during frequency ramps (running mean of %ld periods; lines: fitted sigmoids)'\n"
			   "set xlabel 'frequency f (Hz)'\nset ylabel 'Phi (particles per period)'\nset samples 500\n",
			o.smooth);
		for (int j = 0; j < ng; j++)
			for (int b = 0; b < 2; b++)
				if (R[j].fit[b].ok)
					fprintf(f, "s%d_%d(x) = %.17g + %.17g / (1 + exp(-(x - %.17g) / %.17g))\n", j, b,
						R[j].fit[b].b, R[j].fit[b].a, R[j].fit[b].x0, R[j].fit[b].w);
		fprintf(f, "plot ");
		for (int j = 0; j < ng; j++)
			for (int b = 0; b < 2; b++) {
				fprintf(f, "%s'hysteresis_periods.csv' skip 1 using 7:($1==%d&&strcol(5)eq'%s'?$9:1/0) with points pt %d ps 0.6 lc %d title ",
					j || b ? ", \\\n  " : "", j, b ? "down" : "up", b ? 6 : 7, 2 * j + b + 1);
				char t[600];
				snprintf(t, sizeof t, "%s, %s", labels[j], b ? "down" : "up");
				gp_str(f, t);
				if (R[j].fit[b].ok)
					fprintf(f, ", s%d_%d(x) with lines lw 2 dt %d lc %d notitle", j, b, b ? 2 : 1, 2 * j + b + 1);
			}
		fprintf(f, "\n");
		fclose(f);
		f = NULL;
		if (gp_run(script, png, &e))
			goto out;
		printf("# figure: %s\n", png);
	}
	printf("# csv: %s/hysteresis_{periods,summary,accounting}.csv\n", o.out);
out:
	if (f)
		fclose(f);
	if (s)
		fclose(s);
	for (int j = 0; G && j < ng; j++)
		hyst_free(&G[j]);
	free(G);
	free(R);
	free(A);
	for (int i = 0; F && i < k; i++)
		flux_free(&F[i]);
	free(F);
	free(raw);
	free(sm);
	an_labels_free(labels, ng);
	adb_runs_free(runs, nr);
	adb_close(&d);
	if (e.code) {
		fprintf(stderr, "hysteresis: %s\n", e.msg);
		return e.code == SB_EUSAGE ? 1 : 2;
	}
	return 0;
}
