/* convect_main.c - bin/convect: how strongly the bed convects, from the displacement
 * field, whatever the rolls' position (convect.h). With periodic sides the rolls are
 * not pinned to the box centre and the flux Phi, which splits crossings into centre and
 * outer half, can average to zero while the bed convects; the rms of the vertical mean
 * displacement in a band of the bed does not depend on where the rolls sit. Per run
 * the mean strength over the blocks after the transient; per group (every swept axis,
 * e.g. sides and frequency) the mean over runs with Student-t and bootstrap intervals;
 * a figure of S against f, one curve per value of the other keys. Only this file
 * prints and exits. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/acct.h"
#include "common/adb.h"
#include "common/cli.h"
#include "common/label.h"
#include "common/tool.h"
#include "common/xopt.h"
#include "measure/convect.h"
#include "measure/rolls.h"
#include "measure/whalestat.h"

#define VERSION "1"

#define USED(r) ((r)->use == AN_USED || (r)->use == AN_PARTLY)

static const char HELP[] =
	"usage: convect CAMPAIGN [--db FILE] [--runs DIR] [--out DIR] [--band LO:HI] [--skip FRAC]\n"
	"               [--by KEYS] [--boot N] [--seed S] [--level L] [--all-versions] [--no-plot]\n"
	"               [--no-store]\n\n"
	"How strongly the bed convects, measured from the displacement field (field = yes)\n"
	"so that it does not depend on where the rolls sit. With periodic sides (sides =\n"
	"periodic) nothing pins the rolls to the box centre, so the flux Phi = j_top - j_bot,\n"
	"which splits crossings into centre and outer half by x, can average to zero while the\n"
	"bed convects. The field (/observables/field) holds per block of field_periods periods\n"
	"and per cell (one mean grain diameter wide, from x = 0 and the floor) the mean\n"
	"displacement per period ux, uy (cm) and its samples n.\n"
	"  roll strength S  per block: sqrt(sum n uy^2 / sum n) over the cells whose centre\n"
	"             height lies in LO*h_s .. HI*h_s (h_s the run's settled surface height;\n"
	"             --band, default 0.3:0.7): the count-weighted rms of the vertical mean\n"
	"             displacement per period. Mass conservation makes the row mean of uy\n"
	"             about 0, so this is the rolls' strength wherever they are.\n"
	"  S_u        the same with ux^2 + uy^2\n"
	"  per run    the mean of S (and S_u) over the blocks after the first floor(FRAC *\n"
	"             blocks) (--skip, default 0.2; a failed run's transient is that of the\n"
	"             run as planned, its blocks before the failure are used); blocks whose\n"
	"             band holds no sample are left out and counted\n"
	"  per group  (default: frequency and every swept axis, e.g. sides; --by KEYS): the\n"
	"             runs used, the mean S with its Student-t interval over runs and a\n"
	"             bootstrap percentile interval over runs (--boot, --seed, --level), the\n"
	"             same for S_u\n"
	"Note: uy of a cell is a mean of n samples, so S carries their noise: a bed without\n"
	"rolls has a small S > 0 that falls as field_periods grows; compare runs with the same\n"
	"field_periods.\n"
	"Every fixed-frequency run (ramp = none) is considered; runs without a field (field =\n"
	"no), failed, pending, running or with an unreadable file are counted per group and\n"
	"listed with why (convect_accounting.csv); every number says how many runs it rests on.\n"
	"S carries each cell's sampling noise (a floor that grows with the bed's agitation).\n"
	"Persistent flow P = sqrt(C), C = per run the mean over neighbouring blocks b, b+1 of\n"
	"sum w uy_b uy_b+1 / sum w over the band's cells with samples in both, w = min(n_b,\n"
	"n_b+1): the noise of two blocks is independent and averages out, a roll that outlives a\n"
	"block stays (C = A^2/2 for a steady uy = A sin); per group the mean of C with its\n"
	"Student-t interval, P and its bounds their square roots (of max(0, .)).\n\n"
	"  --db FILE     campaign database (default RUNS/study.db)\n"
	"  --runs DIR    where outputs are, as RUNS/CAMPAIGN/RUN-ID.h5 (default: the\n"
	"                database's directory, or runs)\n"
	"  --out DIR     CSV, gnuplot scripts and figures (default RUNS/CAMPAIGN/analysis)\n"
	"  --band LO:HI  the band, fractions of the settled surface height (default 0.3:0.7)\n"
	"  --skip FRAC   fraction of each run's blocks dropped as transient (default 0.2)\n"
	"  --by KEYS     group by these parameters (comma separated)\n"
	"  --boot N      bootstrap replicates (default 1000)\n"
	"  --seed S      bootstrap seed (default 1)\n"
	"  --level L     confidence level (default 0.95)\n"
	"  --all-versions  also the runs of earlier versions of the campaign file\n"
	"  --no-plot     no figure;  --no-store  nothing written to the database\n\n"
	"Writes convect_runs.csv (per considered run: id, replicate, the grouping keys, use,\n"
	"blocks recorded and used, S, S_u, C, block pairs), convect_summary.csv (per group),\n"
	"convect_points.csv (the figure's), convect_accounting.csv and convect.png/.pdf (S and P against the\n"
	"frequency, one curve per value of the other keys, bars the Student-t interval).\n"
	"Stores per group in the table `analysis` (tool 'convect'): runs (used), strength and\n"
	"strength_u (Student-t lo, hi; n = runs), strength_boot and strength_u_boot (the\n"
	"bootstrap interval), persistence_c (C; n = runs with a pair of blocks), persistent\n"
	"(P), blocks (blocks used, summed over runs), band_lo, band_hi, and\n"
	"the accounting rows (onset --help).\n"
	"Options take their value as --opt VALUE or --opt=VALUE.\n";

typedef struct cgroup {
	double f;              /* the group's frequency (its key's value, else its runs' mean) */
	rolls_mean t, tu, tc;  /* S, S_u, C: mean with Student-t interval */
	whale_ci b, bu;        /* ... with bootstrap interval */
	long blocks;           /* blocks used over its runs */
	long nofield;          /* runs without a field */
	int curve;             /* the set of groups alike in every key but frequency */
} cgroup;

typedef struct convect_state {
	convect_cfg cfg;
	convect_run *cr; /* [k] */
	int *nofield;    /* [k] 1: the run had no field */
	cgroup *g;       /* [ng] */
	int ncurve;
	int kf;          /* index of frequency among the grouping keys, -1 */
	int clipped;     /* Student-t lower bounds of S or S_u below 0, clipped at 0 */
} convect_state;

static void state_free(const an_tool *t, void *vs)
{
	(void)t;
	convect_state *s = vs;
	free(s->cr);
	free(s->nofield);
	free(s->g);
}

/* One run: what of it is used (acct.h) and, when used, its strength. */
static void classify(an_run *r, const convect_cfg *c, convect_run *cr, int *nofield)
{
	memset(cr, 0, sizeof *cr);
	cr->S = cr->Su = cr->C = NAN;
	*nofield = 0;
	if (acct_classify(r))
		return;
	const char *fp = an_str(r, "field");
	if (fp && strcmp(fp, "yes")) {
		*nofield = 1;
		acct_set(r, AN_UNUSABLE, NAN, NAN, "field = %s: no displacement field recorded", fp);
		return;
	}
	convect_field f;
	sb_err e = {0};
	const int rc = convect_read(r->path, &f, &e);
	if (rc == SB_EUSAGE) {
		*nofield = 1;
		acct_set(r, AN_UNUSABLE, NAN, NAN, "%s", e.msg);
		return;
	}
	if (rc == SB_ENAN) {
		acct_set(r, AN_UNUSABLE, NAN, NAN, "%s", e.msg);
		return;
	}
	if (rc) {
		acct_set(r, AN_UNREADABLE, NAN, NAN, "%s", e.msg);
		fprintf(stderr, "convect: warning: %s (counted as unreadable)\n", r->why);
		return;
	}
	const int failed = !strcmp(r->state, "failed");
	size_t planned = 0;
	const double per = an_num(r, "duration", NAN) * an_num(r, "frequency", NAN);
	if (failed && f.K > 0 && per >= 0 && per < 1e12)
		planned = (size_t)floor(per / (double)f.K + 1e-9);
	if (convect_summary(&f, c, planned, cr)) {
		if (failed)
			acct_set(r, AN_UNUSABLE, NAN, NAN, "failed at t = %g s (%s) within the transient: %zu field blocks"
				 " recorded, the first %zu of the planned %zu are the transient", r->status_time, r->status,
				 f.B, cr->first, planned);
		else if (cr->first < f.B)
			acct_set(r, AN_UNUSABLE, NAN, NAN, "no sample in the band %g..%g of the surface height in the %zu"
				 " blocks after the transient", c->band_lo, c->band_hi, f.B - cr->first);
		else
			acct_set(r, AN_UNUSABLE, NAN, NAN, "no field block after the transient (%zu recorded, %ld periods"
				 " each)", f.B, f.K);
	} else if (failed)
		acct_set(r, AN_PARTLY, f.t[f.B - 1], an_num(r, "duration", NAN),
			 "failed at t = %g s (%s): its %zu field blocks before it used, after the first %zu",
			 r->status_time, r->status, f.B, cr->first);
	else
		acct_set(r, AN_USED, NAN, NAN, NULL);
	convect_free(&f);
}

/* Every fixed-frequency run is considered, whatever its state or field. */
static int consider(an_tool *t, convect_state *s)
{
	const size_t n = (size_t)(t->nr ? t->nr : 1);
	if (!(s->cr = calloc(n, sizeof *s->cr)) || !(s->nofield = calloc(n, sizeof *s->nofield)))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	for (int i = 0; i < t->nr; i++) {
		an_run *r = &t->runs[i];
		const char *ramp = an_str(r, "ramp");
		if ((ramp && strcmp(ramp, "none")) || tool_old(t, r))
			continue;
		convect_run cr;
		int nf;
		classify(r, &s->cfg, &cr, &nf);
		const int k = tool_keep(t, i);
		s->cr[k] = cr;
		s->nofield[k] = nf;
	}
	return t->k ? 0 : tool_none(t, "fixed-frequency run", "");
}

/* Groups, their means and intervals, and the curves of the figure. */
static int groups(an_tool *t, convect_state *s)
{
	static const char *const always[] = {"frequency", NULL};
	static const char *const drop[] = {"ramp", "ramp_from", "ramp_to", "field", NULL};
	if (tool_group(t, always, drop))
		return t->e.code;
	s->kf = -1;
	for (int k = 0; k < t->nk; k++)
		s->kf = strcmp(t->keys[k], "frequency") ? s->kf : k;
	if (!(s->g = calloc((size_t)(t->ng ? t->ng : 1), sizeof *s->g)))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	if (tool_tally(t, stdout, "its %d fixed-frequency runs", t->k))
		return t->e.code;
	const size_t nk = (size_t)(t->k ? t->k : 1);
	double *v = malloc(sizeof *v * nk), *vu = malloc(sizeof *vu * nk), *vc = malloc(sizeof *vc * nk);
	if (!v || !vu || !vc) {
		free(v);
		free(vu);
		free(vc);
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	}
	const an_opts *o = t->o;
	for (int j = 0; j < t->ng && !t->e.code; j++) {
		cgroup *g = &s->g[j];
		size_t m = 0;
		double fs = 0;
		long nf = 0;
		for (int i = 0; i < t->k; i++) {
			const an_run *r = &t->runs[i];
			if (r->group != j)
				continue;
			g->nofield += s->nofield[i];
			fs += an_num(r, "frequency", NAN);
			nf++;
			if (!USED(r))
				continue;
			v[m] = s->cr[i].S;
			vc[m] = s->cr[i].C;
			vu[m++] = s->cr[i].Su;
			g->blocks += (long)s->cr[i].used;
		}
		g->f = s->kf >= 0 ? strtod(t->gval[j * t->nk + s->kf], NULL) : nf ? fs / (double)nf : NAN;
		rolls_mean_ci(v, m, o->level, &g->t);
		rolls_mean_ci(vu, m, o->level, &g->tu);
		/* S and S_u are >= 0: a Student-t lower bound below 0 is clipped at 0, and the
		 * output says how many were (docs/analysis.md, "convect") */
		s->clipped += g->t.lo < 0;
		s->clipped += g->tu.lo < 0;
		g->t.lo = g->t.lo < 0 ? 0 : g->t.lo;
		g->tu.lo = g->tu.lo < 0 ? 0 : g->tu.lo;
		{ /* C: the runs with a pair of blocks */
			size_t mc = 0;
			for (size_t q = 0; q < m; q++)
				if (isfinite(vc[q]))
					vc[mc++] = vc[q];
			rolls_mean_ci(vc, mc, o->level, &g->tc);
		}
		if (whale_mean_ci(v, m, (size_t)o->boot, o->seed, o->level, &g->b) ||
		    whale_mean_ci(vu, m, (size_t)o->boot, o->seed, o->level, &g->bu))
			sb_errf(&t->e, SB_ENOMEM, "out of memory");
		/* the curve: the first earlier group alike in every key but frequency */
		g->curve = -1;
		for (int h = 0; h < j && g->curve < 0; h++) {
			int same = 1;
			for (int k = 0; k < t->nk && same; k++)
				same = k == s->kf || !strcmp(t->gval[h * t->nk + k], t->gval[j * t->nk + k]);
			if (same)
				g->curve = s->g[h].curve;
		}
		if (g->curve < 0)
			g->curve = s->ncurve++;
	}
	free(v);
	free(vu);
	free(vc);
	return t->e.code;
}

/* convect_runs.csv: every considered run */
static int runs_csv(an_tool *t, const convect_state *s)
{
	FILE *f = tool_out_open(t, "convect_runs.csv");
	if (!f)
		return t->e.code;
	fprintf(f, ACCT_ROW_HEAD ",seed,state,use");
	for (int k = 0; k < t->nk; k++) {
		fputc(',', f);
		csv_text(f, t->keys[k]);
	}
	fprintf(f, ",field,blocks,first_block,blocks_used,blocks_empty,band_rows,strength,strength_u,persistence_c,"
		   "block_pairs\n");
	for (int i = 0; i < t->k; i++) {
		const an_run *r = &t->runs[i];
		const convect_run *c = &s->cr[i];
		acct_row_begin(f, r, t->labels);
		fprintf(f, ",%ld,%s,%s", r->seed, r->state, acct_use_name(r->use));
		for (int k = 0; k < t->nk; k++) {
			const char *v = an_str(r, t->keys[k]);
			fputc(',', f);
			csv_text(f, v ? v : "");
		}
		fprintf(f, ",%s", s->nofield[i] ? "no" : "yes");
		if (USED(r))
			fprintf(f, ",%zu,%zu,%zu,%zu,%zu,%.17g,%.17g,%.17g,%zu\n", c->blocks, c->first, c->used, c->empty,
				c->rows, c->S, c->Su, c->C, c->pairs);
		else
			fprintf(f, ",,,,,,nan,nan,nan,\n");
	}
	return tool_out_close(t, f);
}

/* "0.123 [0.100, 0.150] (5)", "0.123 [-, -] (1)" or "- (0)" */
static void ci_text(char *b, size_t n, double mean, double lo, double hi, size_t k)
{
	if (isnan(mean))
		snprintf(b, n, "- (0)");
	else if (isnan(lo))
		snprintf(b, n, "%.4f [-, -] (%zu)", mean, k);
	else
		snprintf(b, n, "%.4f [%.4f, %.4f] (%zu)", mean, lo, hi, k);
}

/* Group j: its table row, summary row, stored rows. */
static void group_out(an_tool *t, const convect_state *s, int j, FILE *sum)
{
	const cgroup *g = &s->g[j];
	const char *L = t->labels[j];
	const an_acct *a = &t->A[j];
	char c1[80], c2[80], c3[80], c4[80];
	/* P = sqrt(C): the persisting flow's rms in cm per period, its interval from C's */
	const double P = sqrt(fmax(0, g->tc.mean)), Plo = sqrt(fmax(0, g->tc.lo)), Phi = sqrt(fmax(0, g->tc.hi));
	ci_text(c4, sizeof c4, isnan(g->tc.mean) ? NAN : P, isnan(g->tc.lo) ? NAN : Plo, Phi, g->tc.n);
	ci_text(c1, sizeof c1, g->t.mean, g->t.lo, g->t.hi, g->t.n);
	ci_text(c2, sizeof c2, g->b.mean, g->b.lo, g->b.hi, g->b.n);
	ci_text(c3, sizeof c3, g->tu.mean, g->tu.lo, g->tu.hi, g->tu.n);
	printf("%-30s %4zu %6ld %7ld %31s %31s %31s %31s %6ld %6ld\n", L, g->t.n, g->blocks, g->nofield, c1, c2, c3, c4,
	       a->failed, a->n[AN_PENDING] + a->n[AN_RUNNING]);
	csv_text(sum, L);
	fprintf(sum, ",%.17g,%zu,%ld,%ld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,"
		     "%.17g,%.17g,%.17g",
		g->f, g->t.n, g->blocks, g->nofield, g->t.mean, g->t.sd, g->t.lo, g->t.hi, g->b.lo, g->b.hi, g->tu.mean,
		g->tu.sd, g->tu.lo, g->tu.hi, g->bu.lo, g->bu.hi, s->cfg.band_lo, s->cfg.band_hi, s->cfg.skip,
		t->o->level);
	tool_summary_acct(t, sum, j);
	const long n = (long)g->t.n;
	tool_store(t, j, L, "runs", (double)n, NAN, NAN, n);
	tool_store(t, j, L, "strength", g->t.mean, g->t.lo, g->t.hi, n);
	tool_store(t, j, L, "strength_boot", g->b.mean, g->b.lo, g->b.hi, n);
	tool_store(t, j, L, "strength_u", g->tu.mean, g->tu.lo, g->tu.hi, n);
	tool_store(t, j, L, "strength_u_boot", g->bu.mean, g->bu.lo, g->bu.hi, n);
	tool_store(t, j, L, "persistence_c", g->tc.mean, g->tc.lo, g->tc.hi, (long)g->tc.n);
	tool_store(t, j, L, "persistent", isnan(g->tc.mean) ? NAN : P, isnan(g->tc.lo) ? NAN : Plo,
		   isnan(g->tc.hi) ? NAN : Phi, (long)g->tc.n);
	tool_store(t, j, L, "blocks", (double)g->blocks, NAN, NAN, n);
	tool_store(t, j, L, "no_field", (double)g->nofield, NAN, NAN, g->nofield);
	tool_store(t, j, L, "band_lo", s->cfg.band_lo, NAN, NAN, n);
	tool_store(t, j, L, "band_hi", s->cfg.band_hi, NAN, NAN, n);
	tool_store_acct(t, L, j);
}

/* P from C: the square root of max(0, C), NaN stays NaN */
static double root(double c)
{
	return isnan(c) ? NAN : sqrt(fmax(0, c));
}

/* convect_points.csv: per curve its groups by frequency, so that a curve's rows are
 * together (gnuplot joins the rows of a curve; a row it skips between them would break
 * the line) */
static void points(const an_tool *t, const convect_state *s, FILE *pts)
{
	for (int c = 0; c < s->ncurve; c++) {
		double last = -INFINITY;
		for (;;) { /* the next frequency of curve c, in increasing order */
			int j = -1;
			for (int h = 0; h < t->ng; h++)
				if (s->g[h].curve == c && s->g[h].f > last && (j < 0 || s->g[h].f < s->g[j].f))
					j = h;
			if (j < 0)
				break;
			for (int h = 0; h < t->ng; h++) { /* groups of one curve at one f (--by without frequency) */
				const cgroup *g = &s->g[h];
				if (g->curve == c && g->f == s->g[j].f)
					fprintf(pts, "%d,%d,%.17g,%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", h,
						g->curve, g->f, g->t.n, g->t.mean, g->t.lo, g->t.hi, g->tu.mean, g->tu.lo, g->tu.hi,
						root(g->tc.mean), root(g->tc.lo), root(g->tc.hi));
			}
			last = s->g[j].f;
		}
	}
}

/* convect_summary.csv, convect_points.csv, the table and the stored rows */
static int summary(an_tool *t, const convect_state *s)
{
	FILE *sum = tool_summary_csv(t, "convect_summary.csv",
				     "group,frequency,runs,blocks,no_field,strength,strength_sd,strength_lo,strength_hi,"
				     "strength_boot_lo,strength_boot_hi,strength_u,strength_u_sd,strength_u_lo,"
				     "strength_u_hi,strength_u_boot_lo,strength_u_boot_hi,band_lo,band_hi,skip,level");
	if (!sum)
		return t->e.code;
	FILE *pts = tool_out_open(t, "convect_points.csv");
	if (!pts)
		return tool_out_close(t, sum);
	fprintf(pts, "group_index,curve,frequency,runs,strength,strength_lo,strength_hi,strength_u,strength_u_lo,"
		     "strength_u_hi,persistent,persistent_lo,persistent_hi\n");
	printf("# roll strength S = sqrt(sum n uy^2 / sum n) over the cells in %g..%g of the settled surface height, per "
	       "block of field_periods periods (cm per period); per run the mean over the blocks after the first %g of "
	       "them; intervals at %g %%: Student t over runs, bootstrap percentile over runs (%ld replicates); (n) = the "
	       "runs each number rests on\n", s->cfg.band_lo, s->cfg.band_hi, s->cfg.skip, 100 * t->o->level, t->o->boot);
	printf("# persistent flow P = sqrt(C), C = the mean over neighbouring blocks of sum w uy_b uy_b+1 / sum w: the "
	       "sampling noise of two blocks is independent and averages out, a roll that outlives a block stays; "
	       "interval from C's Student t\n");
	printf("%-30s %4s %6s %7s %31s %31s %31s %31s %6s %6s\n", "group", "used", "blocks", "nofield", "S cm [t CI] (n)",
	       "S [bootstrap CI] (n)", "S_u cm [t CI] (n)", "P cm [t CI] (n)", "failed", "unfinished");
	tool_store_begin(t);
	for (int j = 0; j < t->ng && !t->e.code; j++)
		group_out(t, s, j, sum);
	if (s->clipped)
		printf("# %d Student-t lower bound%s of S or S_u below 0 clipped at 0 (S >= 0); the table, CSV, stored rows "
		       "and figure show 0\n", s->clipped, s->clipped == 1 ? "" : "s");
	points(t, s, pts);
	tool_out_close(t, sum);
	return tool_out_close(t, pts);
}

/* The closing lines: the accounting, then every run left out, by name, with why. */
static void report(const an_tool *t, const convect_state *s)
{
	tool_report(t, stdout, "the field blocks they recorded before the failure (after the transient of the run as "
			       "planned): one value each, like a finished run");
	long nf = 0, out = 0;
	for (int i = 0; i < t->k; i++) {
		nf += s->nofield[i];
		out += !USED(&t->runs[i]);
	}
	if (nf)
		printf("# %ld run%s without a displacement field (field = no): counted as unusable, not in S\n", nf,
		       nf == 1 ? "" : "s");
	int shown = 0;
	for (int i = 0; i < t->k && shown < 30; i++) {
		const an_run *r = &t->runs[i];
		if (USED(r))
			continue;
		printf("#   not used: %s (%s, %s): %s\n", r->id, r->group >= 0 ? t->labels[r->group] : "-",
		       acct_use_name(r->use), *r->why ? r->why : r->state);
		shown++;
	}
	if (out > shown)
		printf("#   ... and %ld more (convect_accounting.csv)\n", out - shown);
	long empty = 0;
	for (int i = 0; i < t->k; i++)
		empty += USED(&t->runs[i]) ? (long)s->cr[i].empty : 0;
	if (empty)
		printf("# %ld field block%s after the transient had no sample in the band: left out of their run's mean\n",
		       empty, empty == 1 ? "" : "s");
	printf("# S carries the sampling noise of each cell's mean (var/n): a bed without rolls has a small S > 0 that "
	       "falls as field_periods grows; compare runs with the same field_periods\n");
}

/* The legend of curve c: the grouping keys but frequency whose values differ between
 * the curves; "" when none. */
static void curve_words(const an_tool *t, const convect_state *s, int c, char *buf, size_t n)
{
	tool_curve_legend(t, &s->g[0].curve, sizeof s->g[0], s->ncurve, "frequency", c, 1, buf, n);
}

/* One panel: a quantity (columns col, col+1, col+2 of convect_points.csv) against f,
 * one curve per set of other keys, the Student-t interval as bars. */
static void panel(FILE *f, const an_tool *t, const convect_state *s, int col, const char *title, const char *ylab)
{
	fprintf(f, "set title '%s'\n", title);
	gp_xlabel(f, "frequency");
	fprintf(f, "set ylabel '%s'\nset yrange [0:*]\nplot ", ylab);
	for (int c = 0; c < s->ncurve; c++) {
		char w[256];
		curve_words(t, s, c, w, sizeof w);
		fprintf(f, "%s'convect_points.csv' skip 1 using ($2==%d?$3:1/0):%d:%d:%d with yerrorbars lt %d pt 7 ps 1.2 "
			   "notitle, \\\n  'convect_points.csv' skip 1 using ($2==%d?$3:1/0):%d with linespoints lt %d pt 7 "
			   "ps 1.2 lw 1.5 title ", c ? ", \\\n  " : "", c, col, col + 1, col + 2, c + 1, c, col, c + 1);
		gp_str(f, *w ? w : "all runs");
	}
	fputc('\n', f);
}

/* convect.png and .pdf: S and P against the frequency */
static int plot(an_tool *t, const convect_state *s)
{
	char script[1400], png[1400], set[512];
	FILE *f = tool_gp_open(t, "convect", 1100, 520, script, png, sizeof script);
	if (!f)
		return t->e.code;
	tool_setting(t, set, sizeof set);
	double A, g, flo = INFINITY, fhi = -INFINITY;
	for (int j = 0; j < t->ng; j++)
		if (isfinite(s->g[j].t.mean)) {
			flo = fmin(flo, s->g[j].f);
			fhi = fmax(fhi, s->g[j].f);
		}
	const double pad = fhi > flo ? 0.06 * (fhi - flo) : 0.25;
	fprintf(f, "set multiplot layout 1,2 title \"Roll strength from the displacement field (independent of where "
		   "the rolls sit)\\n%s%sband %g–%g of the surface height; bars: %g %% Student-t interval over runs%s\"\n"
		   "set key below\n",
		set, *set ? "; " : "", s->cfg.band_lo, s->cfg.band_hi, 100 * t->o->level,
		s->clipped ? ", lower bounds below 0 clipped at 0" : "");
	if (isfinite(flo))
		fprintf(f, "set xrange [%.17g:%.17g]\n", flo - pad, fhi + pad);
	if (isfinite(flo) && fhi > flo && tool_gamma(t, &A, &g))
		gp_gamma_axis(f, A, g, flo - pad, fhi + pad);
	panel(f, t, s, 5, "S: rms of the vertical mean displacement per period", "S (cm per period)");
	panel(f, t, s, 11, "P: the flow that persists from one block to the next (no noise floor)", "P (cm per period)");
	fprintf(f, "unset multiplot\n");
	return tool_plot(t, f, script, png);
}

/* --band LO:HI, this tool's own option (its default is not onset's) */
static int band_opt(const xopt *x, convect_cfg *c, sb_err *e)
{
	if (!x->set)
		return 0;
	char buf[128], *colon, *end1, *end2;
	snprintf(buf, sizeof buf, "%s", x->val);
	if (!(colon = strchr(buf, ':')))
		return sb_errf(e, SB_EUSAGE, "--band: expected LO:HI (fractions of the surface height), got '%s'", x->val);
	*colon = 0;
	const double lo = strtod(buf, &end1), hi = strtod(colon + 1, &end2);
	if (!*buf || *end1 || !colon[1] || *end2 || !(lo >= 0 && lo <= 2) || !(hi >= 0 && hi <= 2))
		return sb_errf(e, SB_EUSAGE, "--band: expected LO:HI with numbers in [0, 2], got '%s'", x->val);
	if (lo > hi)
		return sb_errf(e, SB_EUSAGE, "--band: LO must not exceed HI, got '%s'", x->val);
	c->band_lo = lo;
	c->band_hi = hi;
	return 0;
}

static int init(an_tool *t, void *vs, const xopt *x)
{
	convect_state *s = vs;
	s->cfg.skip = t->o->skip;
	return band_opt(&x[0], &s->cfg, &t->e);
}

static int run(an_tool *t, void *vs)
{
	convect_state *s = vs;
	if (consider(t, s) || groups(t, s) || cli_outdir(t->o, &t->e) || runs_csv(t, s) || tool_accounting_csv(t) ||
	    summary(t, s) || tool_store_end(t))
		return t->e.code;
	report(t, s);
	if (!t->o->no_plot) {
		if (plot(t, s))
			return t->e.code;
		printf("# figure: %s/convect.{png,pdf}\n", t->o->out);
	}
	printf("# csv: %s/convect_{runs,summary,points,accounting}.csv\n", t->o->out);
	return 0;
}

static const tool_spec SPEC = {.name = "convect", .version = VERSION, .help = HELP,
			       .allowed = " by skip boot seed level ", .x = {{"band", 1, NULL, 0}}, .nx = 1,
			       .init = init, .run = run, .fini = state_free};

int main(int argc, char **argv)
{
	convect_state s = {.cfg = CONVECT_CFG_DEFAULT};
	return tool_main(argc, argv, &SPEC, &s);
}
