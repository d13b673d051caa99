/* onset_main.c - bin/onset: convective flux through a plane versus frequency, and the
 * onset frequency per group of runs (sigmoid midpoint and threshold crossing, bootstrap
 * over seeds). Only this file prints and exits. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flux.h"
#include "common/acct.h"
#include "common/adb.h"
#include "common/axis.h"
#include "common/cli.h"
#include "common/fluxrun.h"
#include "common/searchdef.h"
#include "common/label.h"
#include "common/tool.h"
#include "common/xopt.h"
#include "measure/bootdiff.h"
#include "measure/onsetfit.h"
#include "measure/resolve.h"
#include "measure/powerfit.h"
#include "measure/sigmoid.h"

#define VERSION "3" /* 3: the search's definition by default, the interval floor (resolve.c) */

/* a run whose records are in the statistic: finished, or failed and used up to it */
#define USED(r) ((r)->use == AN_USED || (r)->use == AN_PARTLY)

static const char HELP[] =
	"usage: onset CAMPAIGN... [--db FILE] [--runs DIR] [--out DIR] [--by KEYS] [--band LO:HI]\n"
	"             [--skip FRAC] [--threshold PHI] [--boot N] [--seed S] [--level L]\n"
	"             [--sensitivity] [--diff KEY] [--fit KEY] [--axis frequency|gamma|velocity]\n"
	"             [--all-versions] [--no-plot] [--no-store]\n\n"
	"Onset of convection. For every run at a fixed frequency (ramp = none) with flux =\n"
	"yes: Phi through the plane = the mean of Phi over the height lines that\n"
	"lie in the band LO..HI of the settled surface height (default 0.4:0.6, the middle\n"
	"of the bed), averaged over the periods after the first FRAC of them (default 0.2).\n"
	"On a campaign with an [onset] search over the flux, the search's threshold, band\n"
	"and skip are the defaults (one onset per campaign); an option that changes one is\n"
	"said to differ from the search's definition, and the search's own onset per group\n"
	"is printed beside this tool's with both intervals and whether they overlap.\n"
	"Per group (default: radius_ratio, depth and every other swept axis but frequency;\n"
	"radius_ratio = 0 is the system without intruder), with all runs and seeds pooled:\n"
	"  sigmoid    midpoint f0 of  Phi = b + a / (1 + exp(-(f - f0) / w))  fitted by\n"
	"             nonlinear least squares (GSL trust region), its width w and step a;\n"
	"  threshold  first frequency at which the mean Phi per frequency (oriented to rise)\n"
	"             reaches PHI (default: the search's threshold, else halfway between its\n"
	"             smallest and largest value), interpolated linearly: THE onset, the\n"
	"             one the figure marks;\n"
	"both with percentile bootstrap intervals over seeds (replicates resampled with\n"
	"replacement, all frequencies of a drawn seed together; over runs when a group has\n"
	"one seed), and the spread (standard deviation) of the per-seed threshold estimates.\n"
	"The threshold interval holds at least the two sampled frequencies around the\n"
	"crossing (no interval claims more precision than the spacing of the runs).\n\n"
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
	"  --level L        confidence level (default: the [onset] search's, else 0.95)\n"
	"  --sensitivity    also how the onset depends on the measuring band and on the sampled\n"
	"                   frequency range: both estimates again for the bands 0.2:0.4, 0.4:0.6\n"
	"                   and 0.6:0.8 of the surface height and for the sampled range without\n"
	"                   its lowest and without its highest frequency (the same bootstrap),\n"
	"                   and the spread (largest - smallest) over these and the main estimate,\n"
	"                   printed beside the main estimate's interval; onset_sensitivity.csv,\n"
	"                   stored keys sens_spread_threshold_f, sens_spread_sigmoid_f0 and per\n"
	"                   variant sens_threshold_f_V and sens_sigmoid_f0_V (lo, hi), V one of\n"
	"                   band_0.2_0.4, band_0.4_0.6, band_0.6_0.8, no_lowest_f, no_highest_f\n"
	"  --diff KEY       the difference of the onsets (both estimates) of groups alike in every\n"
	"                   grouping key but KEY, every pair (the larger KEY minus the smaller;\n"
	"                   --ref VALUE: each group against the one at KEY = VALUE):\n"
	"                   its percentile interval from the two groups' bootstraps (each over\n"
	"                   its seeds, resampled apart) and whether 0 is inside; onset_diff.csv,\n"
	"                   stored keys diff_threshold_f and diff_sigmoid_f0 (lo, hi)\n"
	"  --fit KEY        a power law f_on = c KEY^p per set of groups alike but in KEY (> 0):\n"
	"                   weighted least squares on log-log, weights from the onsets' intervals;\n"
	"                   p's interval a percentile bootstrap over the groups' own replicates\n"
	"                   (the covariance's beside it); for KEY = amplitude the exponents of\n"
	"                   Gamma = const (p = -1/2) and v = const (p = -1), each said excluded\n"
	"                   or not; onset_fit.csv, stored keys fit_p_E and fit_c_E (E threshold_f,\n"
	"                   sigmoid_f0)\n"
	"  --where KEY=VALUE  only the runs whose KEY is VALUE (repeatable; as bin/figures)\n"
	"  --axis A         the figure's x: frequency (default), gamma (Gamma = A(2 pi f)^2/g) or\n"
	"                   velocity (v = 2 pi f A), each run at its own amplitude\n"
	"  CAMPAIGN...      a campaign's name, its campaign file (FILE.campaign: its [campaign]\n"
	"                   name), or DIR/NAME in the runs directory DIR; several are pooled:\n"
	"                   groups by parameters whatever campaign (docs/analysis.md)\n"
	"  --all-versions   also the runs of earlier versions of the campaign file (run.current\n"
	"                   = 0, kept by study run --keep-old); by default the current grid's\n"
	"  --no-plot        no figures;  --no-store  nothing written to the database\n\n"
	"Writes onset_runs.csv (Phi per run), onset_seeds.csv (per-seed estimates),\n"
	"onset_summary.csv, onset_accounting.csv, onset.png/.pdf; stores per group in `analysis`\n"
	"(tool 'onset'): runs (used), seeds, sigmoid_f0 (lo, hi), sigmoid_width, sigmoid_step,\n"
	"threshold_f (lo, hi), threshold_seed_sd, search_f (lo, hi: the search's onset, on a\n"
	"campaign with one), and the accounting: runs_failed,\n"
	"runs_failed_used, failed_used_s, failed_planned_s, runs_unusable, runs_unreadable,\n"
	"runs_pending, runs_running, failed_STATUS per status; per run used (analysis_run, the\n"
	"runs view's onset_phi and onset_phi_class): Phi and its class, on past the group's\n"
	"threshold, off before it. The rows record the options that made them: a rerun with\n"
	"the same options replaces its rows, one with others adds rows (docs/database.md).\n"
	"Options take their value as --opt VALUE or --opt=VALUE. Figures are written as PNG\n"
	"and PDF (vector) with their gnuplot scripts. A stored row has its group's value of\n"
	"each grouping key in that key's column (radius_ratio, depth, ...; docs/analysis.md).\n";

/* What onset computes besides the frame: Phi through the plane of every considered
 * run, one group's points at a time, and the estimates of every group. */
typedef struct onset_state {
	flux_opts fo;    /* the onset's definition: band and skip ... */
	double thr;      /* ... and threshold (NaN: halfway up the step) */
	sdef sd;         /* the campaign's [onset] search, when it has one */
	int differs;     /* a command-line option differs from the search's definition */
	int pooled;      /* several campaigns: their common definition, no search beside */
	char def[320];   /* the definition in words, for the table and the figure */
	double *phi;     /* [k] Phi of considered run i (NaN: nothing usable) */
	double *xs, *ys; /* one group's points: frequency, Phi */
	long *us;        /* ... and their seed (the unit: replicate, pool.h) */
	onset_res *R;    /* [ng] */
	int sens;        /* --sensitivity given */
	const char *diff, *fit; /* --diff KEY, --fit KEY (NULL: not given) */
	double ref;             /* --ref VALUE of --diff's key (NaN: every pair) */
	int axis;        /* --axis (axis.h) */
	double level;    /* the intervals' level: --level, else the search's, else 0.95 */
} onset_state;

static int state_alloc(an_tool *t, onset_state *s)
{
	size_t n = (size_t)(t->nr ? t->nr : 1);
	s->phi = calloc(n, sizeof *s->phi);
	s->xs = calloc(n, sizeof *s->xs);
	s->ys = calloc(n, sizeof *s->ys);
	s->us = calloc(n, sizeof *s->us);
	if (!s->phi || !s->xs || !s->ys || !s->us)
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	return 0;
}

static void state_free(const an_tool *t, void *vs)
{
	onset_state *s = vs;
	for (int j = 0; s->R && j < t->ng; j++)
		onset_res_free(&s->R[j]);
	free(s->R);
	free(s->phi);
	free(s->xs);
	free(s->ys);
	free(s->us);
}

/* Phi through the plane of run r, and what of it the statistic uses (acct.h); NaN
 * when nothing. */
static double classify(an_run *r, const flux_opts *fo)
{
	flux_data fd;
	double v = NAN;
	if (fluxrun_load(r, &fd)) {
		if (r->use == AN_UNREADABLE)
			fprintf(stderr, "onset: warning: %s (counted as unreadable)\n", r->why);
		return v;
	}
	v = flux_summary(&fd, fo);
	const double dur = an_num(r, "duration", NAN), T = fd.P ? fd.t[fd.P - 1] : 0;
	if (isfinite(v) && !strcmp(r->state, "failed"))
		acct_set(r, AN_PARTLY, T, dur, "failed at t = %g s (%s): the %zu periods before it used, after the"
			 " first %zu", r->status_time, r->status, fd.P, flux_first(&fd, fo));
	else if (isfinite(v))
		acct_set(r, AN_USED, NAN, NAN, NULL);
	else if (!strcmp(r->state, "failed"))
		acct_set(r, AN_UNUSABLE, NAN, NAN, "failed at t = %g s (%s) within the transient: %zu periods"
			 " recorded, the first %zu of the planned %zu are the transient", r->status_time,
			 r->status, fd.P, flux_first(&fd, fo), fd.planned);
	else
		acct_set(r, AN_UNUSABLE, NAN, NAN, "no flux period recorded");
	flux_free(&fd);
	return v;
}

/* The onset's one definition (docs/analysis.md, "One onset per campaign"): on a
 * campaign with an [onset] search over the flux, the search's threshold, band and
 * skip, each unless the command line gives it (then the output says that the
 * definition differs from the search's); else the options' (the defaults: band
 * 0.4:0.6, skip 0.2, the threshold halfway up the step). */
/* Several campaigns: their one definition when every one of them is in the first
 * database and has a flux search with the same threshold, band and skip; else none
 * (s->sd.found = 0), and the output says why. The searches' own estimates are per
 * campaign (bin/onset NAME): none beside pooled groups. */
static int pooled_definition(an_tool *t, onset_state *s)
{
	const an_opts *o = t->o;
	const char *why = NULL;
	memset(&s->sd, 0, sizeof s->sd);
	for (int c = 0; c < o->ncamp && !why; c++) {
		sdef x;
		if (strcmp(o->camp[c].db, o->camp[0].db)) {
			why = "a campaign of another database";
			break;
		}
		if (sdef_load(&t->d, o->camp[c].name, &x, &t->e))
			return t->e.code;
		if (!x.found || !x.flux)
			why = "a campaign without a search over the flux";
		else if (c && (x.threshold != s->sd.threshold || x.band_lo != s->sd.band_lo ||
			       x.band_hi != s->sd.band_hi || x.skip != s->sd.skip))
			why = "their searches' definitions differ";
		else
			s->sd = x;
	}
	if (why) {
		memset(&s->sd, 0, sizeof s->sd);
		printf("# several campaigns, %s: no [onset] definition applies\n", why);
	}
	s->pooled = 1;
	return 0;
}

static int definition(an_tool *t, onset_state *s)
{
	const an_opts *o = t->o;
	if (o->ncamp > 1 ? pooled_definition(t, s) : sdef_load(&t->d, o->campaign, &s->sd, &t->e))
		return t->e.code;
	const sdef *d = &s->sd;
	s->thr = o->threshold;
	s->fo = (flux_opts){o->band_lo, o->band_hi, o->skip};
	const int from_search = d->found && d->flux;
	if (from_search) {
		if (!o->threshold_set)
			s->thr = d->threshold;
		if (!o->band_set)
			s->fo.band_lo = d->band_lo, s->fo.band_hi = d->band_hi;
		if (!o->skip_set)
			s->fo.skip = d->skip;
		s->differs = s->thr != d->threshold || s->fo.band_lo != d->band_lo || s->fo.band_hi != d->band_hi ||
			     s->fo.skip != d->skip;
	}
	/* the intervals at the search's level, so that "agree" compares like with like */
	s->level = o->level;
	if (d->found && !o->level_set && d->level > 0 && d->level < 1 && d->level != o->level) {
		s->level = d->level;
		tool_define(t, "level=%.15g", s->level);
		printf("# intervals at %g %%: the [onset] search's level (--level sets another)\n", 100 * s->level);
	}
	char th[64];
	if (isnan(s->thr))
		snprintf(th, sizeof th, "halfway up the step of");
	else
		snprintf(th, sizeof th, "≥ %g in", s->thr);
	snprintf(s->def, sizeof s->def, "first f with mean Φ %s band %g–%g, skip %g", th, s->fo.band_lo, s->fo.band_hi,
		 s->fo.skip);
	/* the stored rows' definition: the options say "halfway" when the search's threshold is taken */
	tool_define(t, "onset=%s", s->def);
	printf("# onset: %s (%s)\n", s->def,
	       !from_search ? (s->pooled ? "this tool's" : "this tool's; the campaign has no [onset] search over the flux")
	       : s->differs ? "set on the command line: differs from the search's"
	       : s->pooled  ? "the [onset] searches' definition, the same in every campaign"
			    : "the [onset] search's definition");
	if (from_search && s->differs && !s->pooled)
		printf("# the search's: first f with |mean Φ| ≥ %g in band %g–%g, skip %g; its onset below is by that one\n",
		       d->threshold, d->band_lo, d->band_hi, d->skip);
	return 0;
}

/* Every fixed-frequency run with flux = yes is considered, whatever its state. */
static int consider(an_tool *t, onset_state *s)
{
	if (tool_where_known(t))
		return t->e.code;
	for (int i = 0; i < t->nr; i++) {
		const char *ramp = an_str(&t->runs[i], "ramp"), *fl = an_str(&t->runs[i], "flux");
		if ((ramp && strcmp(ramp, "none")) || (fl && strcmp(fl, "yes")) || !tool_where_ok(t->o, &t->runs[i]) ||
		    tool_old(t, &t->runs[i]))
			continue;
		const double v = classify(&t->runs[i], &s->fo);
		s->phi[tool_keep(t, i)] = v;
	}
	char narrowed[600] = "";
	for (int w = 0; w < t->o->nwhere; w++)
		snprintf(narrowed + strlen(narrowed), sizeof narrowed - strlen(narrowed), "%s%s = %s",
			 w ? ", " : " with ", t->o->where_key[w], t->o->where_val[w]);
	return t->k ? 0 : tool_none(t, "fixed-frequency run with flux = yes", narrowed);
}

static int groups(an_tool *t, onset_state *s)
{
	static const char *const always[] = {"radius_ratio", "depth", NULL};
	static const char *const drop[] = {"frequency", "ramp", "ramp_from", "ramp_to", NULL};
	if (tool_group(t, always, drop))
		return t->e.code;
	if (!(s->R = calloc((size_t)(t->ng > 0 ? t->ng : 1), sizeof *s->R)))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	return tool_tally(t, stdout, "its %d fixed-frequency runs with flux = yes", t->k);
}

/* onset_runs.csv: Phi of every run used, by group */
static int runs_csv(an_tool *t, const onset_state *s)
{
	FILE *f = tool_out_open(t, "onset_runs.csv");
	if (!f)
		return t->e.code;
	fprintf(f, ACCT_ROW_HEAD ",seed,radius_ratio,depth,frequency,phi,use,used_s,axis_x\n");
	for (int j = 0; j < t->ng; j++)
		for (int i = 0; i < t->k; i++) {
			const an_run *r = &t->runs[i];
			if (r->group != j || !USED(r))
				continue;
			acct_row_begin(f, r, t->labels);
			const double fr = an_num(r, "frequency", NAN);
			fprintf(f, ",%ld,%.17g,%.17g,%.17g,%.17g,%s,%.17g,%.17g\n", r->seed,
				an_num(r, "radius_ratio", NAN), an_num(r, "depth", NAN), fr, s->phi[i],
				acct_use_name(r->use), r->used_s, axis_run(s->axis, r));
		}
	return tool_out_close(t, f);
}

/* Group j's points (frequency, Phi, seed) into xs, ys, us; their number. *ratio is
 * the group's radius ratio. */
static size_t group_points(const an_tool *t, onset_state *s, int j, double *ratio)
{
	size_t np = 0;
	*ratio = 0;
	for (int i = 0; i < t->k; i++) {
		const an_run *r = &t->runs[i];
		if (r->group != j)
			continue;
		*ratio = an_num(r, "radius_ratio", 0);
		if (!USED(r))
			continue;
		s->xs[np] = an_num(r, "frequency", NAN);
		s->ys[np] = s->phi[i];
		s->us[np++] = r->unit;
	}
	return np;
}

/* An estimate with its interval for a table: "5.428 [5.000, 5.500]"; "-" for none and
 * "[-, -]" for no interval, each said why by a line below the table (never a nan) */
static void cell(char *b, size_t n, double v, double lo, double hi)
{
	if (isnan(v))
		snprintf(b, n, isnan(lo) || isnan(hi) ? "-" : "- [%.3f, %.3f]", lo, hi);
	else if (isnan(lo) || isnan(hi))
		snprintf(b, n, "%.3f [-, -]", v);
	else
		snprintf(b, n, "%.3f [%.3f, %.3f]", v, lo, hi);
}

/* Group j's estimates: its per-seed rows, its table row, its summary row, its stored
 * rows; why a cell is "-" in the line below the row (why: the sigmoid's, sig_why). */
static void group_out(an_tool *t, const onset_res *r, int j, size_t np, double ratio, FILE *f, FILE *s,
		      const char *why)
{
	const char *L = t->labels[j];
	const an_acct *a = &t->A[j];
	for (size_t u = 0; u < r->units; u++) {
		fprintf(f, "%d,", j);
		csv_text(f, L);
		fprintf(f, ",%ld,%.17g,%.17g\n", r->unit_id[u], r->seed_fit[u], r->seed_thr[u]);
	}
	const sig_fit *F = &r->fit;
	const double f0 = F->ok ? F->x0 : NAN, w = F->ok ? F->w : NAN, step = F->ok ? F->a : NAN;
	char c1[64], c2[64], cw[32], cs[32];
	cell(c1, sizeof c1, f0, r->fit_lo, r->fit_hi);
	cell(c2, sizeof c2, r->thr, r->thr_lo, r->thr_hi);
	snprintf(cw, sizeof cw, isnan(w) ? "-" : "%.3f", w);
	snprintf(cs, sizeof cs, isnan(r->seed_sd) ? "-" : "%.3f", r->seed_sd);
	printf("%-30s %4s %4zu %5zu %22s %7s %22s %7s %6ld %7ld\n", L, ratio > 0 ? "yes" : "no", np, r->units, c1, cw,
	       c2, cs, a->failed, a->n[AN_PENDING] + a->n[AN_RUNNING]);
	/* every "-" above said why */
	if (!np)
		printf("#   %s: -: no run used\n", L);
	else {
		if (!F->ok)
			printf("#   %s: sigmoid f0 and width -: %s\n", L, why);
		if (isnan(r->thr))
			printf("#   %s: threshold f -: the mean Φ per frequency never crosses the level\n", L);
		if ((F->ok && (isnan(r->fit_lo) || isnan(r->fit_hi))) ||
		    (!isnan(r->thr) && (isnan(r->thr_lo) || isnan(r->thr_hi))))
			printf("#   %s: [-, -]: no interval: %s\n", L,
			       r->units < 2 ? "one seed, and too few points to resample" :
			       t->o->boot < 2 ? "no bootstrap (--boot below 2)" :
					       "too few bootstrap replicates gave an estimate");
		if (isnan(r->seed_sd))
			printf("#   %s: seed_sd -: fewer than 2 seeds with a threshold crossing of their own\n", L);
	}
	csv_text(s, L);
	fprintf(s, ",%d,%zu,%zu,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%zu", ratio > 0, np, r->units,
		F->ok, f0, r->fit_lo, r->fit_hi, w, step, r->thr, r->thr_lo, r->thr_hi, r->seed_sd, r->boot_ok);
	tool_summary_acct(t, s, j);
	const long n = (long)np;
	tool_store(t, j, L, "runs", (double)np, NAN, NAN, n);
	tool_store(t, j, L, "seeds", (double)r->units, NAN, NAN, n);
	tool_store(t, j, L, "sigmoid_f0", f0, r->fit_lo, r->fit_hi, n);
	tool_store(t, j, L, "sigmoid_width", w, NAN, NAN, n);
	tool_store(t, j, L, "sigmoid_step", step, NAN, NAN, n);
	tool_store(t, j, L, "threshold_f", r->thr, r->thr_lo, r->thr_hi, n);
	tool_store(t, j, L, "threshold_seed_sd", r->seed_sd, NAN, NAN, n);
	tool_store_acct(t, L, j);
}

/* The onset of the points xs, ys, us [0..np) into r, its threshold interval no
 * narrower than the sampled frequencies around the crossing resolve (resolve.h). */
static int estimate_one(an_tool *t, onset_state *s, size_t np, onset_res *r)
{
	const an_opts *o = t->o;
	if (onset_estimate(s->xs, s->ys, s->us, np, s->thr, (size_t)(o->boot > 1 ? o->boot : 0), o->seed, s->level, r))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	resolve_grid(r->thr, &r->thr_lo, &r->thr_hi, s->xs, np);
	return 0;
}

/* Group j's runs used, stored with their Phi and their class by the group's threshold
 * (sig_level): "on" past it, "off" before it; none when the group has no level. */
static void runs_store(an_tool *t, const onset_state *s, int j, size_t np)
{
	int rising;
	const double lvl = sig_level(s->xs, s->ys, np, s->thr, &rising);
	for (int i = 0; i < t->k; i++) {
		const an_run *r = &t->runs[i];
		if (r->group != j || !USED(r))
			continue;
		const int on = rising ? s->phi[i] >= lvl : s->phi[i] <= lvl;
		tool_store_run(t, r, "phi", s->phi[i], isnan(lvl) || isnan(s->phi[i]) ? NULL : on ? "on" : "off");
	}
}

/* Per group: the estimates into onset_seeds.csv, onset_summary.csv, the table and
 * the analysis table (storing begun here, ended by the caller). */
static int estimate(an_tool *t, onset_state *s)
{
	FILE *f = tool_out_open(t, "onset_seeds.csv"), *sum = NULL;
	if (f)
		sum = tool_summary_csv(t, "onset_summary.csv",
				       "group,intruder,runs,seeds,sigmoid_ok,sigmoid_f0,sigmoid_f0_lo,sigmoid_f0_hi,"
				       "sigmoid_width,sigmoid_step,threshold_f,threshold_f_lo,threshold_f_hi,"
				       "threshold_seed_sd,boot_ok");
	if (sum) {
		fprintf(f, "group_index,group,seed_unit,sigmoid_f0,threshold_f\n");
		printf("%-30s %4s %4s %5s %22s %7s %22s %7s %6s %7s\n", "group", "intr", "used", "seeds",
		       "sigmoid f0 [CI] (Hz)", "width", "threshold f [CI] (Hz)", "seed_sd", "failed", "unfinished");
		tool_store_begin(t);
	}
	for (int j = 0; sum && j < t->ng && !t->e.code; j++) {
		double ratio;
		const size_t np = group_points(t, s, j, &ratio);
		onset_res *r = &s->R[j];
		char why[128] = "";
		if (!np) /* every run of the group failed, is unreadable or not finished */
			r->thr = r->fit_lo = r->fit_hi = r->thr_lo = r->thr_hi = r->seed_sd = NAN;
		else if (estimate_one(t, s, np, r))
			break;
		else
			sig_why(s->xs, s->ys, np, &r->fit, "frequencies", why, sizeof why);
		group_out(t, r, j, np, ratio, f, sum, why);
		runs_store(t, s, j, np);
	}
	tool_out_close(t, f);
	return tool_out_close(t, sum);
}

/* The [onset] search's own estimate of each group beside this tool's threshold
 * onset, both intervals, and whether they agree (overlap); stored as search_f. */
static int beside(an_tool *t, onset_state *s)
{
	if (!s->sd.found || s->pooled)
		return 0;
	const char **ids = malloc(sizeof *ids * (size_t)(t->k ? t->k : 1));
	if (!ids)
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	printf("\n# the [onset] search's onset (the median over replicates of their bisection brackets, its %g %% interval"
	       " at least one bracket wide) beside this tool's threshold onset%s\n", 100 * s->sd.level,
	       s->differs ? " by another definition (above)" : "");
	printf("%-30s %24s %-9s %24s %s\n", "group", "search f [CI] (Hz)", "state", "threshold f [CI] (Hz)", "agree");
	for (int j = 0; j < t->ng && !t->e.code; j++) {
		int n = 0;
		for (int i = 0; i < t->k; i++)
			if (t->runs[i].group == j)
				ids[n++] = t->runs[i].id;
		sdef_est g;
		if (sdef_group(&t->d, t->o->campaign, &s->sd, ids, n, &g, &t->e))
			break;
		const onset_res *r = &s->R[j];
		/* the search's answer is a bracket: no interval narrower than one */
		resolve_widen(&g.lo, &g.hi, g.bracket_lo, g.bracket_hi);
		char c1[64], c2[64], why[160];
		const char *agree = why;
		cell(c1, sizeof c1, g.est, g.lo, g.hi);
		cell(c2, sizeof c2, r->thr, r->thr_lo, r->thr_hi);
		/* The two estimates rest on the same runs of the same replicates: the search's
		 * median bracket and the median of the replicates' own crossings (each inside its
		 * replicate's bracket) can differ by at most one bracket. Intervals that merely
		 * overlap would pass estimates a whole interval apart. */
		const double gap = fabs(r->thr - g.est), width = g.bracket_hi - g.bracket_lo;
		if (!g.found)
			agree = "n/a: none of its runs is the search's";
		else if (g.pooled)
			agree = "n/a: the group pools several search groups (--by)";
		else if (!isfinite(gap) || !(width > 0))
			agree = "n/a: an estimate is missing";
		else if (s->differs)
			snprintf(why, sizeof why, "n/a: another definition (their difference %.3f Hz)", r->thr - g.est);
		else if (gap <= width * (1 + 1e-9))
			snprintf(why, sizeof why, "yes: %.3f Hz apart, within one bracket (%.3f Hz)", gap, width);
		else
			snprintf(why, sizeof why, "no: %.3f Hz apart, more than one bracket (%.3f Hz)", gap, width);
		printf("%-30s %24s %-9s %24s %s\n", t->labels[j], g.found && !g.pooled ? c1 : "-", g.state, c2, agree);
		if (g.found && !g.pooled)
			tool_store(t, j, t->labels[j], "search_f", g.est, g.lo, g.hi, g.replicates);
	}
	free(ids);
	return t->e.code;
}

/* ---- --diff and --fit: the onsets of several groups against each other ---- */

/* The two estimates every group has: name, value, interval and replicates (r->boot). */
enum { NEST = 2 };
static const char *const EST[NEST] = {"threshold_f", "sigmoid_f0"};

static double est(const onset_res *r, int e, double *lo, double *hi, const double **rep)
{
	*rep = r->boot && r->B ? r->boot + (e == 0 ? r->B : 0) : NULL;
	*lo = e == 0 ? r->thr_lo : r->fit_lo;
	*hi = e == 0 ? r->thr_hi : r->fit_hi;
	return e == 0 ? r->thr : r->fit.ok ? r->fit.x0 : NAN;
}

/* --diff KEY: per curve along KEY, each group against the one of the smallest KEY. */
static int diff_out(an_tool *t, onset_state *s)
{
	int nc;
	FILE *f;
	int *curve = tool_curves_csv(t, s->diff, "onset_diff.csv", &nc, &f);
	if (!curve)
		return t->e.code;
	fprintf(f, "group_a,group_b,%s_a,%s_b,estimate,difference,lo,hi,replicates,zero\n", s->diff, s->diff);
	if (isnan(s->ref))
		printf("\n# differences along %s: every pair of groups alike in the other keys, the onset at the larger %s "
		       "minus at the smaller; %g %% percentile interval from the two groups' bootstraps over their seeds, "
		       "resampled apart\n", s->diff, s->diff, 100 * s->level);
	else
		printf("\n# differences along %s: the onset at each %s minus at %s = %g (--ref; other keys equal); %g %% "
		       "percentile interval from the two groups' bootstraps over their seeds, resampled apart\n", s->diff,
		       s->diff, s->diff, s->ref, 100 * s->level);
	printf("%-30s %10s %10s %-12s %30s %8s\n", "groups alike but in", s->diff, "against", "estimate",
	       "difference (Hz) [CI]", "0");
	int pairs = 0;
	int refs = 0;
	for (int c = 0; c < nc && !t->e.code; c++)
		for (int a = 0; a < t->ng && !t->e.code; a++) {
			/* a: the reference of the pair (--ref: the group at that value; else the
			 * smaller KEY of every pair) */
			if (curve[a] != c || !acct_used(&t->A[a]))
				continue;
			if (!isnan(s->ref) && !(fabs(tool_num(t, a, s->diff) - s->ref) <= 1e-9 * fmax(1, fabs(s->ref))))
				continue;
			refs++;
			for (int b = 0; b < t->ng; b++) {
				if (curve[b] != c || b == a || !acct_used(&t->A[b]) ||
				    (isnan(s->ref) && !(tool_num(t, b, s->diff) > tool_num(t, a, s->diff))))
					continue;
				char lab[512], grp[1100];
				tool_label_but(t, a, s->diff, lab, sizeof lab);
				snprintf(grp, sizeof grp, "%s - %s", t->labels[b], t->labels[a]);
				pairs++;
				for (int e = 0; e < NEST; e++) {
					double la, ha, lb, hb;
					const double *ra, *rb;
					const double va = est(&s->R[a], e, &la, &ha, &ra), vb = est(&s->R[b], e, &lb, &hb, &rb);
					bootdiff_res d;
					if (bootdiff_run(va, vb, ra, rb, ra && rb && s->R[a].B == s->R[b].B ? s->R[a].B : 0, s->level,
							 &d)) {
						sb_errf(&t->e, SB_ENOMEM, "out of memory");
						break;
					}
					char ci[64];
					cell(ci, sizeof ci, d.d, d.lo, d.hi);
					const char *z = d.zero == 1 ? "inside" : d.zero == 0 ? "excluded" : "-";
					printf("%-30s %10g %10g %-12s %30s %8s\n", e ? "" : lab, tool_num(t, b, s->diff),
					       tool_num(t, a, s->diff), EST[e], ci, z);
					csv_text(f, t->labels[a]);
					fputc(',', f);
					csv_text(f, t->labels[b]);
					fprintf(f, ",%.17g,%.17g,%s,%.17g,%.17g,%.17g,%zu,%d\n", tool_num(t, a, s->diff),
						tool_num(t, b, s->diff), EST[e], d.d, d.lo, d.hi, d.ok, d.zero);
					char key[64];
					snprintf(key, sizeof key, "diff_%s", EST[e]);
					tool_store(t, b, grp, key, d.d, d.lo, d.hi, (long)d.ok);
				}
			}
		}
	if (!isnan(s->ref) && !refs)
		printf("# no group with usable runs at %s = %g (--ref)\n", s->diff, s->ref);
	else if (!pairs)
		printf("# no two groups with usable runs differ only in %s\n", s->diff);
	free(curve);
	return tool_out_close(t, f);
}

/* One curve's fit of estimate e: its points, the fit, the table row, CSV and stored rows. */
static int fit_curve(an_tool *t, onset_state *s, const int *curve, int c, int e, FILE *f)
{
	const size_t n = (size_t)t->ng;
	double *x = malloc(sizeof *x * 4 * n), *rep = NULL;
	size_t m = 0, B = 0;
	int first = -1, allrep = 1;
	if (!x)
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	double *y = x + n, *lo = x + 2 * n, *hi = x + 3 * n;
	const double **reps = malloc(sizeof *reps * n);
	for (int j = 0; reps && j < t->ng; j++) {
		double l, h;
		const double *r;
		const double v = est(&s->R[j], e, &l, &h, &r);
		if (curve[j] != c || !(tool_num(t, j, s->fit) > 0) || !(v > 0))
			continue;
		first = first < 0 ? j : first;
		x[m] = tool_num(t, j, s->fit), y[m] = v, lo[m] = l, hi[m] = h, reps[m++] = r;
		allrep &= r != NULL && (B == 0 || s->R[j].B == B);
		B = s->R[j].B;
	}
	powerfit_res P;
	int rc = reps ? 0 : -1;
	if (!rc && m && powerfit_fit(x, y, lo, hi, m, s->level, &P))
		m = 0; /* fewer than two points: said below */
	if (!rc && m && allrep && B > 1 && (rep = malloc(sizeof *rep * m * B))) {
		for (size_t i = 0; i < m; i++)
			memcpy(rep + i * B, reps[i], sizeof *rep * B);
		rc = powerfit_boot(x, lo, hi, rep, m, B, s->level, &P);
	}
	if (!rc && first >= 0) {
		char lab[512], grp[600], ci[64], cc[64], ref[128] = "";
		tool_label_but(t, first, s->fit, lab, sizeof lab);
		if (!m) {
			printf("%-30s %-12s fewer than two points with %s > 0 and an onset\n", lab, EST[e], s->fit);
		} else {
			double il, ih;
			powerfit_interval(&P, &il, &ih);
			snprintf(ci, sizeof ci, "%.3f [%.3f, %.3f]", P.p, il, ih);
			snprintf(cc, sizeof cc, "[%.3f, %.3f]", P.cov_lo, P.cov_hi);
			if (!strcmp(s->fit, "amplitude")) {
				const int eg = powerfit_excludes(&P, -0.5), ev = powerfit_excludes(&P, -1);
				snprintf(ref, sizeof ref, "Γ const (p = -1/2) %s, v const (p = -1) %s",
					 eg == 1 ? "excluded" : eg == 0 ? "inside" : "-", ev == 1 ? "excluded" : ev == 0 ? "inside" : "-");
			}
			printf("%-30s %-12s %6zu %26s %18s %10.4g %s%s  %s\n", lab, EST[e], m, ci, cc, P.c,
			       P.weighted ? "" : "unweighted ", isfinite(P.boot_lo) ? "bootstrap" : "covariance", ref);
			csv_text(f, lab);
			fprintf(f, ",%s,%zu,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%zu\n", EST[e], m, P.weighted, P.p,
				P.boot_lo, P.boot_hi, P.se, P.cov_lo, P.cov_hi, P.c, P.chi2, P.boot_ok);
			char key[64];
			snprintf(grp, sizeof grp, "%s: fit along %s", lab, s->fit);
			snprintf(key, sizeof key, "fit_p_%s", EST[e]);
			tool_store(t, first, grp, key, P.p, il, ih, (long)m);
			snprintf(key, sizeof key, "fit_c_%s", EST[e]);
			tool_store(t, first, grp, key, P.c, NAN, NAN, (long)m);
		}
	}
	free(rep);
	free(reps);
	free(x);
	return rc ? sb_errf(&t->e, SB_ENOMEM, "out of memory") : 0;
}

/* --fit KEY: per curve along KEY and estimate, f_on = c KEY^p. */
static int fit_out(an_tool *t, onset_state *s)
{
	int nc;
	FILE *f;
	int *curve = tool_curves_csv(t, s->fit, "onset_fit.csv", &nc, &f);
	if (!curve)
		return t->e.code;
	fprintf(f, "groups,estimate,points,weighted,p,p_lo,p_hi,p_se,p_cov_lo,p_cov_hi,c,chi2,boot_ok\n");
	printf("\n# power law f_on = c %s^p: weighted least squares on log f against log %s, weights from the onsets'"
	       " %g %% intervals; p's interval: percentile bootstrap over the groups' own replicates (the covariance's"
	       " beside it)\n", s->fit, s->fit, 100 * s->level);
	printf("%-30s %-12s %6s %26s %18s %10s %s\n", "groups alike but in", "estimate", "points", "p [CI]",
	       "covariance CI", "c", "interval, reference exponents");
	for (int c = 0; c < nc && !t->e.code; c++)
		for (int e = 0; e < NEST && !t->e.code; e++)
			fit_curve(t, s, curve, c, e, f);
	free(curve);
	return tool_out_close(t, f);
}

/* ---- --sensitivity: the onset again for other bands and a trimmed frequency range ---- */

enum { NBAND = 3, NVAR = NBAND + 3 };
static const double BANDS[NBAND][2] = {{0.2, 0.4}, {0.4, 0.6}, {0.6, 0.8}};
static const char *const VNAME[NVAR] = {"main", "band_0.2_0.4", "band_0.4_0.6", "band_0.6_0.8", "no_lowest_f",
					"no_highest_f"};

/* Phi through each of the bands of every used run (NaN for the others), read again. */
static int band_phis(an_tool *t, const onset_state *s, double *pb)
{
	for (int i = 0; i < t->k; i++) {
		for (int b = 0; b < NBAND; b++)
			pb[b * t->k + i] = NAN;
		flux_data fd;
		if (!USED(&t->runs[i]) || fluxrun_load(&t->runs[i], &fd))
			continue; /* classified usable: only a file changed since could fail */
		for (int b = 0; b < NBAND; b++) {
			const flux_opts fo = {BANDS[b][0], BANDS[b][1], s->fo.skip};
			pb[b * t->k + i] = flux_summary(&fd, &fo);
		}
		flux_free(&fd);
	}
	return 0;
}

/* Group j's points of variant v (1..NBAND: a band; NBAND + 1, + 2: the main band without
 * the lowest or the highest sampled frequency of the group) into xs, ys, us. */
static size_t variant_points(const an_tool *t, onset_state *s, const double *pb, int j, int v)
{
	double flo = INFINITY, fhi = -INFINITY;
	for (int i = 0; i < t->k; i++)
		if (t->runs[i].group == j && USED(&t->runs[i])) {
			flo = fmin(flo, an_num(&t->runs[i], "frequency", NAN));
			fhi = fmax(fhi, an_num(&t->runs[i], "frequency", NAN));
		}
	size_t np = 0;
	for (int i = 0; i < t->k; i++) {
		const an_run *r = &t->runs[i];
		const double f = an_num(r, "frequency", NAN);
		if (r->group != j || !USED(r) || (v == NBAND + 1 && f == flo) || (v == NBAND + 2 && f == fhi))
			continue;
		const double y = v >= 1 && v <= NBAND ? pb[(v - 1) * t->k + i] : s->phi[i];
		if (!isfinite(y))
			continue;
		s->xs[np] = f;
		s->ys[np] = y;
		s->us[np++] = r->unit;
	}
	return np;
}

/* largest - smallest of the finite v[0..n); NaN when fewer than 2 */
static double spread(const double *v, int n)
{
	double lo = INFINITY, hi = -INFINITY;
	int m = 0;
	for (int i = 0; i < n; i++)
		if (isfinite(v[i])) {
			lo = fmin(lo, v[i]);
			hi = fmax(hi, v[i]);
			m++;
		}
	return m >= 2 ? hi - lo : NAN;
}

/* One group's variants: table rows, CSV rows, stored rows; the spreads. */
static int sens_group(an_tool *t, onset_state *s, const double *pb, int j, FILE *f)
{
	const char *L = t->labels[j];
	double thr[NVAR], f0[NVAR];
	for (int v = 0; v < NVAR; v++) {
		const size_t np = variant_points(t, s, pb, j, v);
		onset_res r = {0};
		if (np && estimate_one(t, s, np, &r))
			return t->e.code;
		if (!np)
			r.thr = r.thr_lo = r.thr_hi = r.fit_lo = r.fit_hi = NAN;
		thr[v] = r.thr;
		f0[v] = r.fit.ok ? r.fit.x0 : NAN;
		const double blo = v >= 1 && v <= NBAND ? BANDS[v - 1][0] : s->fo.band_lo;
		const double bhi = v >= 1 && v <= NBAND ? BANDS[v - 1][1] : s->fo.band_hi;
		double flo = INFINITY, fhi = -INFINITY;
		for (size_t p = 0; p < np; p++) {
			flo = fmin(flo, s->xs[p]);
			fhi = fmax(fhi, s->xs[p]);
		}
		char c1[64], c2[64], what[64];
		cell(c1, sizeof c1, r.thr, r.thr_lo, r.thr_hi);
		cell(c2, sizeof c2, f0[v], r.fit_lo, r.fit_hi);
		if (v)
			snprintf(what, sizeof what, "%s", VNAME[v]);
		else
			snprintf(what, sizeof what, "main (band %g:%g)", blo, bhi);
		printf("%-30s %-22s %5.2f-%-5.2f %4zu %22s %22s\n", v ? "" : L, what, np ? flo : NAN, np ? fhi : NAN, np, c1,
		       c2);
		fprintf(f, "%d,", j);
		csv_text(f, L);
		fprintf(f, ",%s,%.17g,%.17g,%.17g,%.17g,%zu,%.17g,%.17g,%.17g,%d,%.17g,%.17g,%.17g\n", VNAME[v], blo, bhi,
			np ? flo : NAN, np ? fhi : NAN, np, r.thr, r.thr_lo, r.thr_hi, r.fit.ok, f0[v], r.fit_lo, r.fit_hi);
		if (v) {
			char k1[64], k2[64];
			snprintf(k1, sizeof k1, "sens_threshold_f_%s", VNAME[v]);
			snprintf(k2, sizeof k2, "sens_sigmoid_f0_%s", VNAME[v]);
			tool_store(t, j, L, k1, r.thr, r.thr_lo, r.thr_hi, (long)np);
			tool_store(t, j, L, k2, f0[v], r.fit_lo, r.fit_hi, (long)np);
		}
		onset_res_free(&r);
	}
	const double st = spread(thr, NVAR), sf = spread(f0, NVAR);
	const onset_res *m = &s->R[j];
	const long n = (long)acct_used(&t->A[j]);
	printf("%-30s spread over the %d variants: threshold f %.3f Hz (main interval %.3f Hz wide), sigmoid f0 %.3f Hz"
	       " (main interval %.3f Hz wide)\n", "", NVAR, st, m->thr_hi - m->thr_lo, sf, m->fit_hi - m->fit_lo);
	tool_store(t, j, L, "sens_spread_threshold_f", st, NAN, NAN, n);
	tool_store(t, j, L, "sens_spread_sigmoid_f0", sf, NAN, NAN, n);
	return 0;
}

/* --sensitivity: onset_sensitivity.csv and the table (rows stored beside the main ones). */
static int sensitivity(an_tool *t, onset_state *s)
{
	double *pb = malloc(sizeof *pb * (size_t)(NBAND * (t->k ? t->k : 1)));
	FILE *f = pb ? tool_out_open(t, "onset_sensitivity.csv") : NULL;
	if (!pb)
		sb_errf(&t->e, SB_ENOMEM, "out of memory");
	if (!f) {
		free(pb);
		return t->e.code;
	}
	band_phis(t, s, pb);
	fprintf(f, "group_index,group,variant,band_lo,band_hi,f_lo,f_hi,runs,threshold_f,threshold_f_lo,threshold_f_hi,"
		   "sigmoid_ok,sigmoid_f0,sigmoid_f0_lo,sigmoid_f0_hi\n");
	printf("\n# sensitivity of the onset: the measuring band (fraction of the surface height) and the sampled frequency"
	       " range (without its lowest or highest frequency); %ld bootstrap replicates each\n", t->o->boot);
	printf("%-30s %-22s %11s %4s %22s %22s\n", "group", "variant", "f range", "runs", "threshold f [CI] (Hz)",
	       "sigmoid f0 [CI] (Hz)");
	for (int j = 0; j < t->ng && !t->e.code; j++)
		if (acct_used(&t->A[j]))
			sens_group(t, s, pb, j, f);
	free(pb);
	return tool_out_close(t, f);
}

/* The onset a figure marks for group j: the threshold crossing of the definition (the
 * one the table, the stored rows and the search share), its interval; 0 when the data
 * hold no crossing. The sigmoid's midpoint is another number, named as such. */
static int onset_mark(const onset_res *r, double *f, double *lo, double *hi)
{
	*f = r->thr, *lo = r->thr_lo, *hi = r->thr_hi;
	return isfinite(r->thr);
}

/* onset.png and onset.pdf: every group's runs and fitted sigmoid (its midpoint in the
 * legend), the onset of the definition named in the title (a dashed line) and its
 * interval (a shaded band) in the group's colour, Gamma on top */

/* The onset mark m [lo, hi] (Hz) of group j on the figure's axis: 0 when the group's
 * runs do not share one amplitude and gravity (its frequencies map onto no one x). */
static int on_axis(const an_tool *t, const onset_state *s, int j, double *m, double *lo, double *hi)
{
	double A, g;
	if (s->axis == AXIS_FREQUENCY)
		return 1;
	if (!tool_group_drive(t, j, &A, &g))
		return 0;
	*m = drive_axis(s->axis, A, *m, g);
	*lo = drive_axis(s->axis, A, *lo, g);
	*hi = drive_axis(s->axis, A, *hi, g);
	return 1;
}

static int plot(an_tool *t, const onset_state *s)
{
	char script[1400], png[1400], set[512];
	FILE *f = tool_gp_open(t, "onset", 1000, 600, script, png, sizeof script);
	if (!f)
		return t->e.code;
	tool_setting(t, set, sizeof set);
	fprintf(f, "set title \"Convective flux Φ through the plane at %.2f–%.2f of the bed height\\n%s%sdashed: onset = %s;"
		   " band: %g %% CI\"\n", s->fo.band_lo, s->fo.band_hi, set, *set ? "; " : "", s->def, 100 * s->level);
	if (s->axis == AXIS_FREQUENCY)
		gp_xlabel(f, "frequency");
	else {
		char xl[128];
		axis_label(xl, sizeof xl, s->axis);
		fputs("set xlabel ", f);
		gp_str(f, xl);
		fputc('\n', f);
	}
	double flo = INFINITY, fhi = -INFINITY, xlo = INFINITY, xhi = -INFINITY, A, g;
	for (int i = 0; i < t->k; i++)
		if (USED(&t->runs[i])) {
			flo = fmin(flo, an_num(&t->runs[i], "frequency", NAN));
			fhi = fmax(fhi, an_num(&t->runs[i], "frequency", NAN));
			xlo = fmin(xlo, axis_run(s->axis, &t->runs[i]));
			xhi = fmax(xhi, axis_run(s->axis, &t->runs[i]));
		}
	/* the x range padded by 6 % of the runs' span on either side: no point on the border */
	const double pad = xhi > xlo ? 0.06 * (xhi - xlo) : 0.1 * fmax(1, fabs(xlo));
	fprintf(f, "set ylabel 'Φ (particles per period)'\nset offsets 0, 0, graph 0.05, graph 0.05\nset samples 500\n");
	if (isfinite(xlo) && isfinite(xhi))
		fprintf(f, "set xrange [%.17g:%.17g]\n", xlo - pad, xhi + pad);
	if (s->axis == AXIS_FREQUENCY && tool_gamma(t, &A, &g) && flo < fhi)
		gp_gamma_axis(f, A, g, flo, fhi);
	int nlab = 0;
	for (int j = 0; j < t->ng; j++) {
		double m, lo, hi;
		if (s->R[j].fit.ok)
			fprintf(f, "s%d(x) = %.17g + %.17g / (1 + exp(-(x - %.17g) / %.17g))\n", j, s->R[j].fit.b,
				s->R[j].fit.a, s->R[j].fit.x0, s->R[j].fit.w);
		if (!onset_mark(&s->R[j], &m, &lo, &hi) || !on_axis(t, s, j, &m, &lo, &hi))
			continue;
		if (isfinite(lo) && isfinite(hi))
			fprintf(f, "set object %d rect from %.17g, graph 0 to %.17g, graph 1 behind fc lt %d "
				   "fs transparent solid 0.15 noborder\n", j + 1, lo, hi, j + 1);
		fprintf(f, "set arrow %d from %.17g, graph 0 to %.17g, graph 1 nohead lt %d dt 2 lw 1.5\n", j + 1, m, m,
			j + 1);
		/* each line labelled in its group's colour, the labels staggered down the plot so
		 * that equal or close onsets stay apart */
		char leg[512], lab[600];
		tool_legend(t, j, 1, leg, sizeof leg);
		char u[32];
		label_unit(u, sizeof u, drive_axis_name(s->axis));
		snprintf(lab, sizeof lab, "%s%sonset %s = %.3g%s%s", leg, *leg ? ": " : "",
			 drive_axis_row(s->axis) ? drive_axis_row(s->axis)->symbol : "?", m, *u ? " " : "", u);
		fprintf(f, "set label %d ", j + 1);
		gp_str(f, lab);
		fprintf(f, " at %.17g, graph %.3f left offset 0.5, 0 tc lt %d front\n", m, 0.96 - 0.06 * nlab++, j + 1);
	}
	fprintf(f, "plot ");
	int np = 0;
	for (int j = 0; j < t->ng; j++) {
		if (!acct_used(&t->A[j])) /* nothing to draw: gnuplot would warn */
			continue;
		char leg[512], mark[256];
		tool_legend(t, j, 1, leg, sizeof leg);
		fprintf(f, "%s'onset_runs.csv' skip 1 using %d:($1==%d?$9:1/0) with points pt 7 ps 0.8 lt %d title ",
			np++ ? ", \\\n  " : "", s->axis == AXIS_FREQUENCY ? 8 : 12, j, j + 1);
		gp_str(f, *leg ? leg : "runs");
		double m, lo, hi, A = NAN, g = NAN;
		const int drawn = s->axis == AXIS_FREQUENCY || tool_group_drive(t, j, &A, &g);
		if (s->R[j].fit.ok && drawn) { /* the sigmoid is one in f: drawn at the axis's f */
			snprintf(mark, sizeof mark, "sigmoid, midpoint f₀ = %.3g Hz (not the onset)", s->R[j].fit.x0);
			fprintf(f, ", s%d(", j);
			axis_gp_freq(f, s->axis, A, g);
			fprintf(f, ") with lines lw 2 lt %d title ", j + 1);
			gp_str(f, mark);
		}
		if (!onset_mark(&s->R[j], &m, &lo, &hi) || !on_axis(t, s, j, &m, &lo, &hi))
			continue;
		char u[32];
		char xs[32];
		snprintf(xs, sizeof xs, "onset %s", drive_axis_row(s->axis) ? drive_axis_row(s->axis)->symbol : "?");
		label_unit(u, sizeof u, drive_axis_name(s->axis));
		if (isfinite(lo) && isfinite(hi))
			snprintf(mark, sizeof mark, "%s = %.3g%s%s [%.3g, %.3g]", xs, m, *u ? " " : "", u, lo, hi);
		else
			snprintf(mark, sizeof mark, "%s = %.3g%s%s", xs, m, *u ? " " : "", u);
		fprintf(f, ", keyentry with lines lt %d dt 2 lw 1.5 title ", j + 1);
		gp_str(f, mark);
	}
	fprintf(f, "\n");
	if (tool_plot(t, f, script, png))
		return t->e.code;
	printf("# figure: %s (and .pdf)\n", png);
	return 0;
}

static int init(an_tool *t, void *vs, const xopt *x)
{
	(void)t;
	onset_state *s = vs;
	s->sens = x[0].set;
	s->diff = x[1].set ? x[1].val : NULL;
	s->fit = x[2].set ? x[2].val : NULL;
	s->ref = NAN;
	if (x[4].set) {
		char *end;
		s->ref = strtod(x[4].val, &end);
		if (end == x[4].val || *end || !isfinite(s->ref))
			return sb_errf(&t->e, SB_EUSAGE, "--ref: expected a number (a value of the --diff key), got '%s'",
				       x[4].val);
		if (!s->diff)
			return sb_errf(&t->e, SB_EUSAGE, "--ref: only with --diff KEY (the value of KEY the others are "
							 "taken against)");
	}
	if ((s->axis = x[3].set ? drive_axis_kind(x[3].val) : AXIS_FREQUENCY) < 0)
		return sb_errf(&t->e, SB_EUSAGE, "--axis: expected one of frequency|gamma|velocity, got '%s'", x[3].val);
	return 0;
}

static int run(an_tool *t, void *vs)
{
	onset_state *s = vs;
	if (state_alloc(t, s) || definition(t, s) || consider(t, s) || groups(t, s) || cli_outdir(t->o, &t->e) ||
	    runs_csv(t, s) || tool_accounting_csv(t) || estimate(t, s) || beside(t, s) || (s->sens && sensitivity(t, s)) ||
	    (s->diff && diff_out(t, s)) || (s->fit && fit_out(t, s)) || tool_store_end(t))
		return t->e.code;
	tool_report(t, stdout, "the periods they recorded before the failure (after the transient of the run as"
			       " planned): one point each, like a finished run");
	if (!t->o->no_plot && plot(t, s))
		return t->e.code;
	printf("# csv: %s/onset_{runs,seeds,summary,accounting%s%s%s}.csv\n", t->o->out, s->sens ? ",sensitivity" : "",
	       s->diff ? ",diff" : "", s->fit ? ",fit" : "");
	return 0;
}

static const tool_spec SPEC = {.name = "onset", .version = VERSION, .help = HELP,
			       .allowed = " by band skip threshold boot seed level where ", .x = {{"sensitivity", 0, NULL, 0}, {"diff", 1, NULL, 0}, {"fit", 1, NULL, 0}, {"axis", 1, NULL, 0}, {"ref", 1, NULL, 0}},
			       .nx = 5, .init = init, .run = run, .fini = state_free};

int main(int argc, char **argv)
{
	onset_state s = {0};
	return tool_main(argc, argv, &SPEC, &s);
}
