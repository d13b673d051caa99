/* hysteresis_main.c - bin/hysteresis: transition frequencies of up and down frequency
 * ramps and their difference, bootstrap over seeds. Only this file prints and exits. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flux.h"
#include "common/acct.h"
#include "common/adb.h"
#include "common/cli.h"
#include "common/fluxrun.h"
#include "common/tool.h"
#include "measure/hyst.h"

#define VERSION "3"

static const char HELP[] =
	"usage: hysteresis CAMPAIGN [--db FILE] [--runs DIR] [--out DIR] [--by KEYS] [--band LO:HI]\n"
	"                  [--smooth K] [--threshold PHI] [--boot N] [--seed S] [--level L]\n"
	"                  [--all-versions] [--no-plot] [--no-store]\n\n"
	"Hysteresis of the convection onset. Uses the runs with a frequency ramp\n"
	"(ramp = updown: ramp_from -> ramp_to -> ramp_from, split at the turning period; or\n"
	"ramp = linear, up when ramp_to > ramp_from, down otherwise) and an /observables/flux group.\n"
	"Per period: Phi through the plane (mean over the height lines in the band LO..HI of\n"
	"the surface height, default 0.4:0.6) against the period's frequency (/observables/flux/frequency),\n"
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
	"hysteresis.png/.pdf (points and the fitted sigmoids of both branches); stores per group\n"
	"in `analysis` (tool 'hysteresis'): runs (used), seeds, up_sigmoid_f, down_sigmoid_f,\n"
	"diff_sigmoid, up_threshold_f, down_threshold_f, diff_threshold (value, lo, hi) and\n"
	"the accounting (runs_failed, runs_failed_used, ..., as onset --help lists).\n"
	"Options take their value as --opt VALUE or --opt=VALUE. Figures are written as PNG\n"
	"and PDF (vector) with their gnuplot scripts. A stored row has its group's value of\n"
	"each grouping key in that key's column (radius_ratio, depth, ...; docs/analysis.md).\n";

/* What hysteresis computes besides the frame: the flux of every considered run, the
 * points of each group's branches and their estimates. */
typedef struct hyst_state {
	flux_opts fo;
	flux_data *F;     /* [k] the considered runs' flux (freed when unusable) */
	size_t pmax;      /* the most periods of a run */
	double *raw, *sm; /* [pmax] one run's plane Phi per period, smoothed within its legs */
	hyst_data *G;     /* [ng] */
	hyst_res *R;      /* [ng] */
} hyst_state;

static void state_free(const an_tool *t, void *vs)
{
	hyst_state *s = vs;
	for (int j = 0; s->G && j < t->ng; j++)
		hyst_free(&s->G[j]);
	free(s->G);
	free(s->R);
	for (int i = 0; s->F && i < t->k; i++)
		flux_free(&s->F[i]);
	free(s->F);
	free(s->raw);
	free(s->sm);
}

/* The legs of run r's ramp in D (hyst_legs); 0 when it has fewer than two periods. */
static int legs(const an_run *r, const flux_data *D, hyst_leg leg[2])
{
	if (D->P < 2)
		return 0;
	return hyst_legs(D, !strcmp(an_str(r, "ramp"), "updown"), an_num(r, "ramp_from", NAN), an_num(r, "ramp_to", NAN),
			 an_num(r, "ramp_hold", 0), leg);
}

/* Reads run r's flux into D and says what of it the statistic uses (acct.h). */
static void classify(an_run *r, flux_data *D, size_t *pmax)
{
	if (fluxrun_load(r, D)) {
		if (r->use == AN_UNREADABLE)
			fprintf(stderr, "hysteresis: warning: %s (counted as unreadable)\n", r->why);
		return;
	}
	hyst_leg leg[2];
	const int nl = legs(r, D, leg), failed = !strcmp(r->state, "failed");
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
	*pmax = D->P > *pmax ? D->P : *pmax;
}

/* Every ramp run with flux = yes is considered, whatever its state. */
static int consider(an_tool *t, hyst_state *s)
{
	if (!(s->F = calloc((size_t)(t->nr ? t->nr : 1), sizeof *s->F)))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	s->pmax = 1;
	for (int i = 0; i < t->nr; i++) {
		an_run *r = &t->runs[i];
		const char *ramp = an_str(r, "ramp"), *fl = an_str(r, "flux");
		if (!ramp || !strcmp(ramp, "none") || (fl && strcmp(fl, "yes")) || tool_old(t, r))
			continue;
		classify(r, &s->F[t->k], &s->pmax);
		tool_keep(t, i);
	}
	return t->k ? 0 : tool_none(t, "ramp run (ramp = linear|updown) with flux = yes", "");
}

/* Grouping reorders nothing: it only labels. */
static int groups(an_tool *t, hyst_state *s)
{
	static const char *const always[] = {"radius_ratio", "depth", NULL};
	static const char *const drop[] = {"frequency", "ramp", "ramp_from", "ramp_to", "ramp_hold", NULL};
	if (tool_group(t, always, drop))
		return t->e.code;
	const size_t ng = (size_t)(t->ng > 0 ? t->ng : 1);
	s->G = calloc(ng, sizeof *s->G);
	s->R = calloc(ng, sizeof *s->R);
	s->raw = malloc(sizeof *s->raw * s->pmax);
	s->sm = malloc(sizeof *s->sm * s->pmax);
	if (!s->G || !s->R || !s->raw || !s->sm)
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	if (tool_tally(t, stdout, "its %d ramp runs with flux = yes", t->k))
		return t->e.code;
	for (int j = 0; j < t->ng; j++)
		hyst_init(&s->G[j], t->o->threshold);
	return 0;
}

/* Considered run i's periods into its group's branches and hysteresis_periods.csv. */
static int run_periods(an_tool *t, hyst_state *s, int i, FILE *f)
{
	const an_run *r = &t->runs[i];
	hyst_data *g = &s->G[r->group];
	const flux_data *D = &s->F[i];
	size_t l0, l1;
	flux_band(D, &s->fo, &l0, &l1);
	hyst_leg leg[2];
	const int nl = legs(r, D, leg);
	if (hyst_add_run(g, r->unit))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	for (size_t p = 0; p < D->P; p++)
		s->raw[p] = flux_plane(D, p, l0, l1);
	for (int q = 0; q < nl; q++) {
		hyst_smooth(s->raw, leg[q].a, leg[q].b, t->o->smooth, s->sm);
		for (size_t p = leg[q].a; p < leg[q].b; p++) {
			if (hyst_add(g, leg[q].branch, D->f[p], s->sm[p], r->unit))
				return sb_errf(&t->e, SB_ENOMEM, "out of memory");
			acct_row_begin(f, r, t->labels);
			fprintf(f, ",%s,%zu,%.17g,%.17g,%.17g,%s\n",
				leg[q].branch == HYST_DOWN ? "down" : "up", p, D->f[p], s->raw[p], s->sm[p],
				acct_use_name(r->use));
		}
	}
	return 0;
}

/* hysteresis_periods.csv, and the points of every group's branches */
static int periods(an_tool *t, hyst_state *s)
{
	FILE *f = tool_out_open(t, "hysteresis_periods.csv");
	if (!f)
		return t->e.code;
	fprintf(f, ACCT_ROW_HEAD ",branch,period,frequency,phi,phi_smooth,use\n");
	for (int i = 0; i < t->k; i++)
		if ((t->runs[i].use == AN_USED || t->runs[i].use == AN_PARTLY) && run_periods(t, s, i, f))
			break;
	return tool_out_close(t, f);
}

/* Group j's estimates: its table row, its summary row, its stored rows. */
static void group_out(an_tool *t, const hyst_data *g, const hyst_res *r, int j, FILE *s)
{
	static const char *const names[6] = {"up_sigmoid_f", "down_sigmoid_f", "diff_sigmoid",
					     "up_threshold_f", "down_threshold_f", "diff_threshold"};
	const char *L = t->labels[j];
	const an_acct *a = &t->A[j];
	char c[3][64];
	for (int q = 0; q < 3; q++)
		snprintf(c[q], sizeof c[q], "%.3f [%.3f, %.3f]", r->v[q], r->lo[q], r->hi[q]);
	printf("%-26s %4zu %5zu %22s %22s %24s %8.3f %8.3f %8.3f %6ld %10ld\n", L, g->nruns, g->nu, c[0], c[1], c[2],
	       r->v[3], r->v[4], r->v[5], a->failed, a->n[AN_PENDING] + a->n[AN_RUNNING]);
	csv_text(s, L);
	fprintf(s, ",%zu,%zu", g->nruns, g->nu);
	for (int q = 0; q < 6; q++)
		fprintf(s, ",%.17g,%.17g,%.17g", r->v[q], r->lo[q], r->hi[q]);
	fprintf(s, ",%zu", r->boot_ok);
	tool_summary_acct(t, s, j);
	const long n = (long)g->nruns;
	tool_store(t, j, L, "runs", (double)g->nruns, NAN, NAN, n);
	tool_store(t, j, L, "seeds", (double)g->nu, NAN, NAN, n);
	for (int q = 0; q < 6; q++)
		tool_store(t, j, L, names[q], r->v[q], r->lo[q], r->hi[q], n);
	tool_store_acct(t, L, j);
}

/* Per group: the estimates into hysteresis_summary.csv, the table and the analysis
 * table (storing begun here, ended by the caller). */
static int estimate(an_tool *t, hyst_state *s)
{
	const an_opts *o = t->o;
	FILE *sum = tool_summary_csv(t, "hysteresis_summary.csv",
				     "group,runs,seeds,up_sigmoid_f,up_lo,up_hi,down_sigmoid_f,down_lo,down_hi,diff_sigmoid,"
				     "diff_lo,diff_hi,up_threshold_f,up_thr_lo,up_thr_hi,down_threshold_f,down_thr_lo,"
				     "down_thr_hi,diff_threshold,diff_thr_lo,diff_thr_hi,boot_ok");
	if (!sum)
		return t->e.code;
	printf("%-26s %4s %5s %22s %22s %24s %8s %8s %8s %6s %10s\n", "group", "used", "seeds", "f_up sigmoid [CI]",
	       "f_down sigmoid [CI]", "up - down [CI] (Hz)", "f_up_thr", "f_dn_thr", "diff_thr", "failed", "unfinished");
	tool_store_begin(t);
	for (int j = 0; j < t->ng && !t->e.code; j++) {
		if (hyst_estimate(&s->G[j], (size_t)(o->boot > 1 ? o->boot : 0), o->seed, o->level, &s->R[j])) {
			sb_errf(&t->e, SB_ENOMEM, "out of memory");
			break;
		}
		group_out(t, &s->G[j], &s->R[j], j, sum);
	}
	return tool_out_close(t, sum);
}

/* hysteresis.png and .pdf: every group's points and fitted sigmoid per leg, Gamma on top */
static int plot(an_tool *t, const hyst_state *s)
{
	char script[1400], png[1400], set[512];
	FILE *f = tool_gp_open(t, "hysteresis", 1000, 600, script, png, sizeof script);
	if (!f)
		return t->e.code;
	tool_setting(t, set, sizeof set);
	fprintf(f, "set title \"Flux Φ through the plane during frequency ramps (running mean of %ld periods; lines: "
		   "fitted sigmoids)%s%s\"\n", t->o->smooth, *set ? "\\n" : "", set);
	gp_xlabel(f, "frequency");
	fprintf(f, "set ylabel 'Φ (particles per period)'\nset samples 500\n");
	double flo = INFINITY, fhi = -INFINITY, A, g;
	for (int j = 0; j < t->ng; j++)
		for (int b = 0; b < 2; b++)
			for (size_t i = 0; i < s->G[j].br[b].n; i++) {
				flo = fmin(flo, s->G[j].br[b].x[i]);
				fhi = fmax(fhi, s->G[j].br[b].x[i]);
			}
	if (tool_gamma(t, &A, &g) && flo < fhi)
		gp_gamma_axis(f, A, g, flo, fhi);
	int nmark = 0;
	for (int j = 0; j < t->ng; j++)
		for (int b = 0; b < 2; b++) {
			const sig_fit *F = &s->R[j].fit[b];
			if (!F->ok)
				continue;
			fprintf(f, "s%d_%d(x) = %.17g + %.17g / (1 + exp(-(x - %.17g) / %.17g))\n", j, b, F->b, F->a, F->x0,
				F->w);
			/* f_up and f_down: a vertical line in the leg's colour, labelled, the labels
			 * staggered so that close ones stay apart */
			char leg[512], lab[600];
			tool_legend(t, j, 1, leg, sizeof leg);
			snprintf(lab, sizeof lab, "%s%s%s = %.3g Hz", leg, *leg ? ": " : "", b ? "f_down" : "f_up", F->x0);
			fprintf(f, "set arrow %d from %.17g, graph 0 to %.17g, graph 1 nohead lt %d dt 3 lw 1.5\nset label %d ",
				nmark + 1, F->x0, F->x0, 2 * j + b + 1, nmark + 1);
			gp_str(f, lab);
			fprintf(f, " at %.17g, graph %.3f left offset 0.5, 0 tc lt %d front\n", F->x0, 0.96 - 0.06 * nmark,
				2 * j + b + 1);
			nmark++;
		}
	fprintf(f, "plot ");
	int np = 0;
	for (int j = 0; j < t->ng; j++)
		for (int b = 0; b < 2; b++) {
			if (!s->G[j].br[b].n) /* a leg without periods: gnuplot would warn */
				continue;
			fprintf(f, "%s'hysteresis_periods.csv' skip 1 using 7:($1==%d&&strcol(5)eq'%s'?$9:1/0) with points pt %d ps 0.6 lt %d title ",
				np++ ? ", \\\n  " : "", j, b ? "down" : "up", b ? 6 : 7, 2 * j + b + 1);
			char leg[512], title[700];
			tool_legend(t, j, 1, leg, sizeof leg);
			snprintf(title, sizeof title, "%s%s%s", leg, *leg ? ", " : "", b ? "down" : "up");
			gp_str(f, title);
			if (s->R[j].fit[b].ok) {
				fprintf(f, ", s%d_%d(x) with lines lw 2 dt %d lt %d title ", j, b, b ? 2 : 1, 2 * j + b + 1);
				snprintf(title, sizeof title, "%s%s%s: fitted sigmoid, %s = %.3g Hz (dotted line)", leg,
					 *leg ? ", " : "", b ? "down" : "up", b ? "f_down" : "f_up", s->R[j].fit[b].x0);
				gp_str(f, title);
			}
		}
	fprintf(f, "\n");
	if (tool_plot(t, f, script, png))
		return t->e.code;
	printf("# figure: %s (and .pdf)\n", png);
	return 0;
}

static int init(an_tool *t, void *vs, const xopt *x)
{
	(void)x;
	hyst_state *s = vs;
	s->fo = (flux_opts){t->o->band_lo, t->o->band_hi, 0};
	return 0;
}

static int run(an_tool *t, void *vs)
{
	hyst_state *s = vs;
	if (consider(t, s) || groups(t, s) || cli_outdir(t->o, &t->e) || periods(t, s) || tool_accounting_csv(t) ||
	    estimate(t, s) || tool_store_end(t))
		return t->e.code;
	tool_report(t, stdout, "the periods they recorded before the failure (a leg cut short by it is used as far as"
			       " it got)");
	if (!t->o->no_plot && plot(t, s))
		return t->e.code;
	printf("# csv: %s/hysteresis_{periods,summary,accounting}.csv\n", t->o->out);
	return 0;
}

static const tool_spec SPEC = {.name = "hysteresis", .version = VERSION, .help = HELP,
			       .allowed = " by band smooth threshold boot seed level ", .init = init, .run = run,
			       .fini = state_free};

int main(int argc, char **argv)
{
	hyst_state s = {0};
	return tool_main(argc, argv, &SPEC, &s);
}
