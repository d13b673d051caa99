/* whale_main.c - bin/whale: the whale effect (docs/model.md, "The paper's claims", 4):
 * after its rise the intruder dives into the bed and comes back again and again. Per
 * run its dives after the rise (whalerun.h: period between dive starts, depth, rate,
 * rms, the spectrum's dominant period); per group (radius_ratio and the swept axes)
 * the means over runs with bootstrap intervals; per set of groups that differ only in
 * radius_ratio, Spearman's trend of the period, depth and rate against 𝓡 with a
 * permutation p (whalestat.h). Only this file prints and exits. */
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
#include "measure/whalerun.h"
#include "measure/whalestat.h"

#define VERSION "1"

#define USED(r) ((r)->use == AN_USED || (r)->use == AN_PARTLY)

static const char HELP[] =
	"usage: whale CAMPAIGN [--db FILE] [--runs DIR] [--out DIR] [--skip S] [--dive D] [--top Q]\n"
	"             [--by KEYS] [--boot N] [--seed S] [--level L] [--all-versions] [--no-plot] [--no-store]\n\n"
	"The whale effect (the paper's Fig. 4, claim 4): once at the top, the intruder dives\n"
	"into the bed and comes back, again and again. For every run with an intruder\n"
	"(radius_ratio > 0) and a trajectory (traj_rate > 0): its box-frame height y(t) (the\n"
	"lab-frame trajectory less the box motion) from the engine's waiting time (the rise)\n"
	"plus S seconds to the end of the trajectory, averaged over one drive period (the bed's\n"
	"flight within a period is no dive):\n"
	"  top level  the Q-quantile of y in that window (default 0.9): where the intruder is\n"
	"             when it is at the top\n"
	"  dive       y falls below top - D and ends when y is back above top - D/2 (the\n"
	"             hysteresis keeps noise at one level from counting twice); D is in\n"
	"             intruder radii (default 1); a dive under way when the window opens\n"
	"             is not counted (its start is unknown)\n"
	"  period     mean time between successive dive starts: (last - first) / (n - 1),\n"
	"             with n >= 2 dives, else none\n"
	"  depth      top - the lowest y within a dive, mean over the dives that ended\n"
	"  rate       dives per minute of window (a run that stays at the top: 0)\n"
	"  rms        standard deviation of y in the window\n"
	"  spectral period  1 / the strongest frequency of y's periodogram (GSL FFT, Hann\n"
	"             window) between 2 cycles per window and half the drive frequency (the\n"
	"             drive and its harmonics lie above): a cross-check without threshold,\n"
	"             averaged over the runs that have a dive period\n"
	"Runs whose intruder never rose are listed and left out of the oscillation statistics,\n"
	"as are runs without a trajectory and runs whose window holds fewer than 10 drive\n"
	"periods; every number says how many runs it rests on. Per group (radius_ratio and\n"
	"every swept axis): runs, risen, analysed, with >= 2 dives; the mean period, spectral\n"
	"period, depth, rate and rms over the runs that have one, with bootstrap percentile\n"
	"intervals over runs. Across 𝓡 (groups alike in every other key): Spearman's rank\n"
	"correlation of each run's period, depth and rate with its 𝓡, permutation p-value\n"
	"(--boot permutations).\n\n"
	"  --db FILE     campaign database (default RUNS/study.db)\n"
	"  --runs DIR    where outputs are, as RUNS/CAMPAIGN/RUN-ID.h5 (default: the\n"
	"                database's directory, or runs)\n"
	"  --out DIR     CSV, gnuplot scripts and figures (default RUNS/CAMPAIGN/analysis)\n"
	"  --skip S      seconds after the rise before the window opens (default 20)\n"
	"  --dive D      dive threshold below the top level, in intruder radii (default 1)\n"
	"  --top Q       the top level's quantile of y (0 < Q <= 1, default 0.9)\n"
	"  --by KEYS     group by these parameters (comma separated; must include\n"
	"                radius_ratio; default radius_ratio and every swept axis)\n"
	"  --boot N      bootstrap replicates and permutations (default 1000)\n"
	"  --seed S      bootstrap seed (default 1)\n"
	"  --level L     confidence level (default 0.95)\n"
	"  --all-versions  also the runs of earlier versions of the campaign file\n"
	"  --no-plot     no figure;  --no-store  nothing written to the database\n\n"
	"Writes whale_runs.csv (every considered run: status, window, top level, dives,\n"
	"period, depth, rate, rms, spectral period, representative), whale_summary.csv,\n"
	"whale_trend.csv, whale_traces.csv, whale_accounting.csv and whale.png/.pdf (period\n"
	"and depth against 𝓡 with their intervals; y(t) of one run per group, the run with\n"
	"the median period). Stores per group in the table `analysis` (tool 'whale'): runs\n"
	"(used), risen, not_risen, no_trajectory, too_short, analysed, with_period, period,\n"
	"spec_period, depth, rate, rms (lo, hi; n = the runs each rests on), spec_edge,\n"
	"top, dive_cm, skip_s, and the accounting rows; per set of groups across 𝓡 (grp\n"
	"'trend ...') trend_period_rho, trend_period_p, trend_depth_rho, ..., n the runs.\n"
	"Options take their value as --opt VALUE or --opt=VALUE.\n";

/* the per-group means: quantity, stored key, words */
enum { QP, QS, QD, QR, QM, NQ };
static const char *const KEY[NQ] = {"period", "spec_period", "depth", "rate", "rms"};

typedef struct wgroup {
	long n[WHALE_NSTATUS]; /* used runs by status */
	long used, with_period, spec_edge;
	double ratio;          /* the group's radius_ratio */
	whale_ci q[NQ];
	double top, dive;      /* mean top level and D (cm) of the analysed runs */
	int rep;               /* the representative run (index into t->runs), or -1 */
	int curve;             /* the set of groups alike but in radius_ratio */
} wgroup;

typedef struct whale_state {
	whale_cfg cfg;
	whale_obs *ob;  /* [k] */
	wgroup *g;      /* [ng] */
	int ncurve;
	whale_trend (*trend)[3]; /* [ncurve]: period, depth, rate against R */
	int kr;         /* the index of radius_ratio among the grouping keys */
} whale_state;

static void state_free(const an_tool *t, void *vs)
{
	(void)t;
	whale_state *s = vs;
	free(s->ob);
	free(s->g);
	free(s->trend);
}

/* One run: what of it is used (acct.h) and, when used, its observables. */
static void classify(an_run *r, whale_obs *ob, const whale_cfg *c)
{
	memset(ob, 0, sizeof *ob);
	ob->status = -1;
	if (acct_classify(r))
		return;
	sb_err e = {0};
	if (whale_read(r->path, c, ob, &e)) {
		ob->status = -1;
		/* a rise or trajectory that is no number is there, and unusable */
		acct_set(r, e.code == SB_ENAN ? AN_UNUSABLE : AN_UNREADABLE, NAN, NAN, "%s", e.msg);
		if (r->use == AN_UNREADABLE)
			fprintf(stderr, "whale: warning: %s (counted as unreadable)\n", r->why);
	} else if (strcmp(r->state, "failed"))
		acct_set(r, AN_USED, NAN, NAN, NULL);
	else if (!(ob->wait > 0)) {
		ob->status = -1;
		acct_set(r, AN_UNUSABLE, NAN, NAN, "failed before the shaking began (%s)", r->status);
	} else /* its trajectory up to the failure is the window's end */
		acct_set(r, AN_PARTLY, isfinite(ob->t_end) ? ob->t_end : ob->wait, an_num(r, "duration", NAN),
			 "failed at t = %g s (%s): its trajectory up to then is used",
			 isfinite(ob->t_end) ? ob->t_end : ob->wait, r->status);
}

/* Every run with an intruder is considered, whatever its state. */
static int consider(an_tool *t, whale_state *s)
{
	if (!(s->ob = calloc((size_t)(t->nr ? t->nr : 1), sizeof *s->ob)))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	for (int i = 0; i < t->nr; i++) {
		an_run *r = &t->runs[i];
		/* a ratio that is not known to be 0 is considered: grouping says what it lacks */
		if (an_num(r, "radius_ratio", NAN) == 0 || tool_old(t, r))
			continue;
		whale_obs ob;
		classify(r, &ob, &s->cfg);
		s->ob[tool_keep(t, i)] = ob;
	}
	return t->k ? 0 : tool_none(t, "run with an intruder", "");
}

/* The representative run of group j: of its runs with a period the one with the
 * median period (the lower middle of an even count, ties by replicate); without
 * any, the analysed run with the most dives (ties: the lowest replicate); -1 when
 * none is analysed. */
static int representative(const an_tool *t, const whale_state *s, int j)
{
	int idx[4096], m = 0, best = -1;
	for (int i = 0; i < t->k && m < 4096; i++) {
		const an_run *r = &t->runs[i];
		if (r->group != j || !USED(r) || s->ob[i].status != WHALE_OK)
			continue;
		if (isfinite(s->ob[i].run.period))
			idx[m++] = i;
		else if (best < 0 || s->ob[i].run.dives > s->ob[best].run.dives ||
			 (s->ob[i].run.dives == s->ob[best].run.dives && r->replicate < t->runs[best].replicate))
			best = i;
	}
	if (!m)
		return best;
	for (int a = 1; a < m; a++) /* insertion sort by (period, replicate) */
		for (int b = a; b > 0; b--) {
			const double pa = s->ob[idx[b - 1]].run.period, pb = s->ob[idx[b]].run.period;
			if (pa < pb || (pa == pb && t->runs[idx[b - 1]].replicate <= t->runs[idx[b]].replicate))
				break;
			const int x = idx[b];
			idx[b] = idx[b - 1];
			idx[b - 1] = x;
		}
	return idx[(m - 1) / 2];
}

/* A quantity of an analysed run (NaN when it has none). */
static double quantity(const whale_obs *ob, int q)
{
	switch (q) {
	case QP: return ob->run.period;
	case QS: /* beside the dive period of the same runs: a cross-check, not a second sample */
		return ob->spec.edge || isnan(ob->run.period) ? NAN : ob->spec.period;
	case QD: return ob->run.depth;
	case QR: return ob->run.rate;
	default: return ob->run.rms;
	}
}

/* Groups, their counts, means with intervals, representatives and curves. */
static int groups(an_tool *t, whale_state *s)
{
	static const char *const always[] = {"radius_ratio", NULL};
	if (tool_group(t, always, NULL))
		return t->e.code;
	s->kr = -1;
	for (int k = 0; k < t->nk; k++)
		s->kr = strcmp(t->keys[k], "radius_ratio") ? s->kr : k;
	if (s->kr < 0)
		return sb_errf(&t->e, SB_EUSAGE, "--by must include radius_ratio (the trend is against it)");
	if (!(s->g = calloc((size_t)(t->ng ? t->ng : 1), sizeof *s->g)))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	if (tool_tally(t, stdout, "its %d runs with an intruder", t->k))
		return t->e.code;
	double *v = malloc(sizeof *v * (size_t)(t->k ? t->k : 1));
	if (!v)
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	const an_opts *o = t->o;
	for (int j = 0; j < t->ng && !t->e.code; j++) {
		wgroup *g = &s->g[j];
		g->ratio = strtod(t->gval[j * t->nk + s->kr], NULL);
		long na = 0;
		for (int i = 0; i < t->k; i++) {
			const an_run *r = &t->runs[i];
			if (r->group != j || !USED(r))
				continue;
			g->used++;
			g->n[s->ob[i].status]++;
			if (s->ob[i].status != WHALE_OK)
				continue;
			na++;
			g->top += s->ob[i].run.top;
			g->dive += s->ob[i].dive;
			g->with_period += isfinite(s->ob[i].run.period);
			g->spec_edge += s->ob[i].spec.edge;
		}
		g->top = na ? g->top / (double)na : NAN;
		g->dive = na ? g->dive / (double)na : NAN;
		for (int q = 0; q < NQ; q++) {
			size_t m = 0;
			for (int i = 0; i < t->k; i++)
				if (t->runs[i].group == j && USED(&t->runs[i]) && s->ob[i].status == WHALE_OK &&
				    isfinite(quantity(&s->ob[i], q)))
					v[m++] = quantity(&s->ob[i], q);
			if (whale_mean_ci(v, m, (size_t)o->boot, o->seed, o->level, &g->q[q]))
				sb_errf(&t->e, SB_ENOMEM, "out of memory");
		}
		g->rep = representative(t, s, j);
		/* the curve: the first earlier group alike in every key but radius_ratio */
		g->curve = -1;
		for (int h = 0; h < j && g->curve < 0; h++) {
			int same = 1;
			for (int k = 0; k < t->nk && same; k++)
				same = k == s->kr || !strcmp(t->gval[h * t->nk + k], t->gval[j * t->nk + k]);
			if (same)
				g->curve = s->g[h].curve;
		}
		if (g->curve < 0)
			g->curve = s->ncurve++;
	}
	free(v);
	return t->e.code;
}

/* Spearman's trend of each run's period, depth and rate against its R, per curve. */
static int trends(an_tool *t, whale_state *s)
{
	static const int TQ[3] = {QP, QD, QR};
	if (!(s->trend = calloc((size_t)(s->ncurve ? s->ncurve : 1), sizeof *s->trend)))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	double *x = malloc(sizeof *x * (size_t)(t->k ? t->k : 1)), *y = malloc(sizeof *y * (size_t)(t->k ? t->k : 1));
	if (!x || !y) {
		free(x);
		free(y);
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	}
	for (int c = 0; c < s->ncurve; c++)
		for (int a = 0; a < 3; a++) {
			size_t m = 0;
			for (int i = 0; i < t->k; i++) {
				const an_run *r = &t->runs[i];
				if (r->group < 0 || s->g[r->group].curve != c || !USED(r) || s->ob[i].status != WHALE_OK ||
				    !isfinite(quantity(&s->ob[i], TQ[a])))
					continue;
				x[m] = s->g[r->group].ratio;
				y[m++] = quantity(&s->ob[i], TQ[a]);
			}
			if (whale_spearman(x, y, m, (size_t)t->o->boot, t->o->seed, &s->trend[c][a]))
				sb_errf(&t->e, SB_ENOMEM, "out of memory");
		}
	free(x);
	free(y);
	return t->e.code;
}

/* whale_runs.csv: every considered run */
static int runs_csv(an_tool *t, const whale_state *s)
{
	FILE *f = tool_out_open(t, "whale_runs.csv");
	if (!f)
		return t->e.code;
	fprintf(f, ACCT_ROW_HEAD ",seed,state,use,radius_ratio,risen,waiting_time,status,window_from,"
		   "window_to,samples,dive_cm,top,dive_level,end_level,dives,dives_ended,period,depth,depth_max,"
		   "rate_per_min,mean_y,rms,spec_period,spec_share,spec_edge,representative\n");
	for (int i = 0; i < t->k; i++) {
		const an_run *r = &t->runs[i];
		const whale_obs *o = &s->ob[i];
		const int used = USED(r) && o->status >= 0;
		const whale_run *w = &o->run;
		acct_row_begin(f, r, t->labels);
		fprintf(f, ",%ld,%s,%s,%.17g,", r->seed, r->state, acct_use_name(r->use),
			an_num(r, "radius_ratio", NAN));
		if (!used) {
			fprintf(f, ",,not_used,,,,,,,,,,,,,,,,,,,0\n");
			continue;
		}
		fprintf(f, "%d,%.17g,%s,", o->risen, o->wait, whale_status_name(o->status));
		if (o->status != WHALE_OK) {
			fprintf(f, ",,,%.17g,,,,,,,,,,,,,,,0\n", o->dive);
			continue;
		}
		fprintf(f, "%.17g,%.17g,%zu,%.17g,%.17g,%.17g,%.17g,%ld,%ld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d\n",
			w->t0, w->t1, w->samples, o->dive, w->top, w->lo, w->hi, w->dives, w->done, w->period, w->depth,
			w->depth_max, w->rate, w->mean, w->rms, o->spec.period, o->spec.share, o->spec.edge,
			r->group >= 0 && s->g[r->group].rep == i);
	}
	return tool_out_close(t, f);
}

/* "41.2 [38.0, 44.9] (7)" or "-" when there is no mean */
static void ci_text(char *b, size_t n, const whale_ci *c, const char *fmt)
{
	char v[32], l[32], h[32];
	if (isnan(c->mean)) {
		snprintf(b, n, "- (0)");
		return;
	}
	snprintf(v, sizeof v, fmt, c->mean);
	if (isnan(c->lo))
		snprintf(b, n, "%s [-, -] (%zu)", v, c->n);
	else {
		snprintf(l, sizeof l, fmt, c->lo);
		snprintf(h, sizeof h, fmt, c->hi);
		snprintf(b, n, "%s [%s, %s] (%zu)", v, l, h, c->n);
	}
}

/* Group j: its table row, its summary and plot rows, its stored rows. */
static void group_out(an_tool *t, const whale_state *s, int j, FILE *sum, FILE *pts)
{
	const wgroup *g = &s->g[j];
	const char *L = t->labels[j];
	const an_acct *a = &t->A[j];
	char c[NQ][128];
	static const char *const FMT[NQ] = {"%.1f", "%.1f", "%.2f", "%.2f", "%.2f"};
	for (int q = 0; q < NQ; q++)
		ci_text(c[q], sizeof c[q], &g->q[q], FMT[q]);
	printf("%-28s %4ld %5ld %4ld %5ld %24s %24s %24s %24s %6ld %6ld\n", L, g->used, g->used - g->n[WHALE_NOT_RISEN],
	       g->n[WHALE_OK], g->with_period, c[QP], c[QS], c[QD], c[QR], a->failed, a->n[AN_PENDING] + a->n[AN_RUNNING]);
	csv_text(sum, L);
	fprintf(sum, ",%.17g,%ld,%ld,%ld,%ld,%ld,%ld,%ld", g->ratio, g->used, g->used - g->n[WHALE_NOT_RISEN],
		g->n[WHALE_NOT_RISEN], g->n[WHALE_NO_TRAJ], g->n[WHALE_SHORT], g->n[WHALE_OK], g->with_period);
	for (int q = 0; q < NQ; q++)
		fprintf(sum, ",%.17g,%.17g,%.17g,%zu", g->q[q].mean, g->q[q].lo, g->q[q].hi, g->q[q].n);
	fprintf(sum, ",%ld,%.17g,%.17g,%.17g,%.17g", g->spec_edge, g->top, g->dive, s->cfg.skip,
		g->rep >= 0 ? s->ob[g->rep].run.period : NAN);
	fputc(',', sum);
	csv_text(sum, g->rep >= 0 ? t->runs[g->rep].id : "");
	tool_summary_acct(t, sum, j);
	fprintf(pts, "%d,%d,%.17g", j, g->curve, g->ratio);
	for (int q = 0; q < NQ; q++)
		fprintf(pts, ",%.17g,%.17g,%.17g", g->q[q].mean, g->q[q].lo, g->q[q].hi);
	fputc('\n', pts);
	const long n = g->used;
	tool_store(t, j, L, "runs", (double)n, NAN, NAN, n);
	tool_store(t, j, L, "risen", (double)(n - g->n[WHALE_NOT_RISEN]), NAN, NAN, n);
	tool_store(t, j, L, "not_risen", (double)g->n[WHALE_NOT_RISEN], NAN, NAN, n);
	tool_store(t, j, L, "no_trajectory", (double)g->n[WHALE_NO_TRAJ], NAN, NAN, n);
	tool_store(t, j, L, "too_short", (double)g->n[WHALE_SHORT], NAN, NAN, n);
	tool_store(t, j, L, "analysed", (double)g->n[WHALE_OK], NAN, NAN, n);
	tool_store(t, j, L, "with_period", (double)g->with_period, NAN, NAN, g->n[WHALE_OK]);
	for (int q = 0; q < NQ; q++)
		tool_store(t, j, L, KEY[q], g->q[q].mean, g->q[q].lo, g->q[q].hi, (long)g->q[q].n);
	tool_store(t, j, L, "spec_edge", (double)g->spec_edge, NAN, NAN, g->n[WHALE_OK]);
	tool_store(t, j, L, "top", g->top, NAN, NAN, g->n[WHALE_OK]);
	tool_store(t, j, L, "dive_cm", g->dive, NAN, NAN, g->n[WHALE_OK]);
	tool_store(t, j, L, "skip_s", s->cfg.skip, NAN, NAN, g->n[WHALE_OK]);
	tool_store_acct(t, L, j);
}

/* The legend of curve c: the keys other than radius_ratio whose values differ between
 * the curves, or (vary = 0) those they share; "" when none. */
static void curve_words(const an_tool *t, const whale_state *s, int c, int vary, char *buf, size_t n)
{
	tool_curve_legend(t, &s->g[0].curve, sizeof s->g[0], s->ncurve, "radius_ratio", c, vary, buf, n);
}

/* The trend lines: printed with their n, whale_trend.csv, stored under 'trend ...'. */
static int trend_out(an_tool *t, const whale_state *s)
{
	static const char *const TK[3] = {"period", "depth", "rate"};
	FILE *f = tool_out_open(t, "whale_trend.csv");
	if (!f)
		return t->e.code;
	fprintf(f, "curve,set,quantity,runs,radius_ratios,rho,p,permutations\n");
	for (int c = 0; c < s->ncurve; c++) {
		char w[256], grp[320];
		curve_words(t, s, c, 1, w, sizeof w);
		snprintf(grp, sizeof grp, "trend over radius_ratio%s%s", *w ? ", " : "", w);
		int nr = 0;
		for (int j = 0; j < t->ng; j++)
			nr += s->g[j].curve == c && s->g[j].n[WHALE_OK] > 0;
		for (int a = 0; a < 3; a++) {
			const whale_trend *tr = &s->trend[c][a];
			fprintf(f, "%d,", c);
			csv_text(f, w);
			fprintf(f, ",%s,%zu,%d,%.17g,%.17g,%zu\n", TK[a], tr->n, nr, tr->rho, tr->p, tr->B);
			if (isnan(tr->rho))
				printf("# trend of the %s against 𝓡%s%s: none (%zu runs%s)\n", TK[a], *w ? ", " : "", w, tr->n,
				       tr->n < 3 ? ", fewer than 3" : ", no spread in 𝓡 or in the values");
			else
				printf("# trend of the %s against 𝓡%s%s: Spearman rho = %.3f, p = %.3g (permutation, %zu "
				       "shuffles; n = %zu runs over %d values of 𝓡)\n", TK[a], *w ? ", " : "", w, tr->rho, tr->p,
				       tr->B, tr->n, nr);
			char key[64];
			snprintf(key, sizeof key, "trend_%s_rho", TK[a]);
			tool_store(t, -1, grp, key, tr->rho, NAN, NAN, (long)tr->n);
			snprintf(key, sizeof key, "trend_%s_p", TK[a]);
			tool_store(t, -1, grp, key, tr->p, NAN, NAN, (long)tr->n);
		}
	}
	return tool_out_close(t, f);
}

/* whale_summary.csv, whale_points.csv (the figure's), the table, the stored rows and
 * the trends (storing begun here, ended by the caller). */
static int summary(an_tool *t, const whale_state *s)
{
	FILE *sum = tool_summary_csv(t, "whale_summary.csv",
				     "group,radius_ratio,runs,risen,not_risen,no_trajectory,too_short,analysed,with_period,"
				     "period,period_lo,period_hi,period_n,spec_period,spec_period_lo,spec_period_hi,"
				     "spec_period_n,depth,depth_lo,depth_hi,depth_n,rate,rate_lo,rate_hi,rate_n,rms,rms_lo,"
				     "rms_hi,rms_n,spec_edge,top,dive_cm,skip_s,representative_period,representative");
	if (!sum)
		return t->e.code;
	FILE *pts = tool_out_open(t, "whale_points.csv");
	if (!pts)
		return tool_out_close(t, sum);
	fprintf(pts, "group_index,curve,radius_ratio,period,period_lo,period_hi,spec_period,spec_lo,spec_hi,depth,"
		     "depth_lo,depth_hi,rate,rate_lo,rate_hi,rms,rms_lo,rms_hi\n");
	printf("# window: from the rise + %g s to the end of the trajectory; a dive: %g intruder radi%s below the top level "
	       "(the %g-quantile of y), over when back above half of that; intervals: %g %% bootstrap over runs; (n) = the "
	       "runs each number rests on\n", s->cfg.skip, s->cfg.dive_radii, s->cfg.dive_radii == 1 ? "us" : "i", s->cfg.top_q, 100 * t->o->level);
	printf("%-28s %4s %5s %4s %5s %24s %24s %24s %24s %6s %6s\n", "group", "used", "rose", "anal", ">=2dv",
	       "period s [CI] (n)", "spectral s [CI] (n)", "depth cm [CI] (n)", "dives/min [CI] (n)", "failed",
	       "unfinished");
	tool_store_begin(t);
	for (int j = 0; j < t->ng && !t->e.code; j++)
		group_out(t, s, j, sum, pts);
	tool_out_close(t, sum);
	tool_out_close(t, pts);
	return t->e.code ? t->e.code : trend_out(t, s);
}

/* The closing lines: who was left out of the oscillation statistics and why, by name
 * for the runs that never rose. */
static void report(const an_tool *t, const whale_state *s)
{
	tool_report(t, stdout, "their trajectory up to the failure");
	long tot[WHALE_NSTATUS] = {0}, an = 0, wp = 0, edge = 0;
	for (int j = 0; j < t->ng; j++) {
		for (int q = 0; q < WHALE_NSTATUS; q++)
			tot[q] += s->g[j].n[q];
		wp += s->g[j].with_period;
		edge += s->g[j].spec_edge;
	}
	an = tot[WHALE_OK];
	if (tot[WHALE_NOT_RISEN]) {
		printf("# %ld used run%s never rose (risen = 0): no oscillation, left out of every statistic above but the "
		       "counts:", tot[WHALE_NOT_RISEN], tot[WHALE_NOT_RISEN] == 1 ? "" : "s");
		int shown = 0;
		for (int i = 0; i < t->k; i++)
			if (USED(&t->runs[i]) && s->ob[i].status == WHALE_NOT_RISEN && shown++ < 20)
				printf(" %s", t->runs[i].id);
		printf("%s (whale_runs.csv lists them)\n", shown > 20 ? " ..." : "");
	}
	if (tot[WHALE_NO_TRAJ])
		printf("# %ld risen run%s without a trajectory (traj_rate = 0): left out\n", tot[WHALE_NO_TRAJ],
		       tot[WHALE_NO_TRAJ] == 1 ? "" : "s");
	if (tot[WHALE_SHORT])
		printf("# %ld risen run%s with fewer than %d drive periods after the rise + %g s: left out (too short; a "
		       "smaller --skip or longer runs)\n", tot[WHALE_SHORT], tot[WHALE_SHORT] == 1 ? "" : "s",
		       WHALE_MIN_PERIODS, s->cfg.skip);
	if (an > wp)
		printf("# %ld of the %ld analysed runs had fewer than 2 dives: no period (they are in dives/min with their "
		       "0 or 1 dive; the mean period is over the runs that dived, a run that stays at the top longer than "
		       "its window has none)\n", an - wp, an);
	if (edge)
		printf("# %ld analysed run%s had the spectrum's maximum at 2 cycles per window (a trend, no line): no "
		       "spectral period\n", edge, edge == 1 ? "" : "s");
	printf("# the spectral period is averaged over the runs with a dive period (beside it, the same runs), less "
	       "those whose spectrum peaks at the band's lower edge\n");
}

/* whale_traces.csv: the representative run of each group, period-averaged, one point
 * per drive period, time since its rise */
static int traces_csv(an_tool *t, const whale_state *s)
{
	FILE *f = tool_out_open(t, "whale_traces.csv");
	if (!f)
		return t->e.code;
	fprintf(f, "group_index,run,t,t_since_rise,y,top,dive_level\n");
	for (int j = 0; j < t->ng; j++) {
		const int i = s->g[j].rep;
		if (i < 0)
			continue;
		const whale_obs *o = &s->ob[i];
		double *tt, *yy;
		size_t n;
		sb_err e = {0};
		if (whale_trace(t->runs[i].path, o->wait, o->drive_f > 0 ? 1 / o->drive_f : 0, &tt, &yy, &n, &e)) {
			sb_errf(&t->e, e.code, "%s", e.msg);
			return tool_out_close(t, f); /* removed: not complete */
		}
		for (size_t m = 0; m < n; m++)
			fprintf(f, "%d,%s,%.17g,%.17g,%.17g,%.17g,%.17g\n", j, t->runs[i].id, tt[m], tt[m] - o->wait, yy[m],
				o->run.top, o->run.lo);
		free(tt);
		free(yy);
	}
	return tool_out_close(t, f);
}

/* One panel of a quantity against R: per curve the means, their intervals as bars
 * (points without an interval drawn alone) and, for the period, the spectral period
 * beside it (open). A panel without any mean says so instead of plotting nothing. */
static void panel(FILE *f, const an_tool *t, const whale_state *s, int q, const char *ylab, const char *title,
		  double xlo, double xhi)
{
	int any = 0;
	for (int j = 0; j < t->ng; j++)
		any |= isfinite(s->g[j].q[q].mean) || (q == QP && isfinite(s->g[j].q[QS].mean));
	fprintf(f, "set title '%s'\nset xlabel '𝓡 (intruder / mean grain radius)'\nset ylabel '%s'\n"
		   "set xrange [%.17g:%.17g]\n", title, ylab, xlo, xhi);
	if (!any) {
		fprintf(f, "set yrange [0:1]\nset label 'no run has one' at graph 0.5, graph 0.5 center\n"
			   "plot 2 notitle\nunset label\nset yrange [*:*]\n");
		return;
	}
	fprintf(f, "set yrange [0:*]\nplot ");
	const int col = 4 + 3 * q;
	int np = 0;
	for (int c = 0; c < s->ncurve; c++) {
		char w[256];
		curve_words(t, s, c, 1, w, sizeof w);
		fprintf(f, "%s'whale_points.csv' skip 1 using ($2==%d?$3:1/0):%d:%d:%d with yerrorbars lt %d pt 7 ps 1.2 "
			   "notitle, \\\n  'whale_points.csv' skip 1 using ($2==%d?$3:1/0):%d with linespoints lt %d pt 7 "
			   "ps 1.2 lw 1.5 title ", np++ ? ", \\\n  " : "", c, col, col + 1, col + 2, c + 1, c, col, c + 1);
		char tt[320];
		snprintf(tt, sizeof tt, "%s%s%s", q == QP ? "from dives" : "mean", *w ? ", " : "", w);
		gp_str(f, tt);
		if (q == QP) {
			fprintf(f, ", \\\n  'whale_points.csv' skip 1 using ($2==%d?$3+0.03:1/0):7:8:9 with yerrorbars lt %d "
				   "pt 6 ps 1.2 dt 2 notitle, \\\n  'whale_points.csv' skip 1 using ($2==%d?$3+0.03:1/0):7 "
				   "with points lt %d pt 6 ps 1.2 title ", c, c + 1, c, c + 1);
			snprintf(tt, sizeof tt, "spectral%s%s", *w ? ", " : "", w);
			gp_str(f, tt);
		}
	}
	fputc('\n', f);
}

/* whale.png and .pdf: period and depth against R (top), one trace per group (below) */
static int plot(an_tool *t, const whale_state *s)
{
	char script[1400], png[1400], set[512];
	double xlo = INFINITY, xhi = -INFINITY;
	for (int j = 0; j < t->ng; j++) {
		xlo = fmin(xlo, s->g[j].ratio);
		xhi = fmax(xhi, s->g[j].ratio);
	}
	const double pad = xhi > xlo ? 0.12 * (xhi - xlo) : 0.5;
	FILE *f = tool_gp_open(t, "whale", 1100, 900, script, png, sizeof script);
	if (!f)
		return t->e.code;
	tool_setting(t, set, sizeof set);
	fprintf(f, "set multiplot title \"The whale effect: dives of the intruder after its rise\\n%s%sfrom the rise + "
		   "%g s; a dive goes %g intruder radi%s below the top level (the %g-quantile of y); bars: %g %% bootstrap over "
		   "runs\"\nset key below\nset size 0.5, 0.5\nset origin 0, 0.45\n",
		set, *set ? "; " : "", s->cfg.skip, s->cfg.dive_radii, s->cfg.dive_radii == 1 ? "us" : "i", s->cfg.top_q, 100 * t->o->level);
	panel(f, t, s, QP, "period (s)", "period: mean time between dives", xlo - pad, xhi + pad);
	fprintf(f, "set origin 0.5, 0.45\n");
	panel(f, t, s, QD, "depth (cm)", "depth: top level − lowest height in a dive", xlo - pad, xhi + pad);
	/* the traces: one run per group, the one with the median period */
	fprintf(f, "set size 1, 0.45\nset origin 0, 0\nset autoscale\nset yrange [*:*]\n"
		   "set title 'y(t) after the rise, averaged over one drive period: per 𝓡 the run with the median period "
		   "(none: the one with the most dives); dashed: its dive threshold'\n"
		   "set xlabel 'time since the rise (s)'\nset ylabel 'height above the box floor (cm)'\n"
		   "set arrow from first %.17g, graph 0 to first %.17g, graph 1 nohead lc rgb 'gray40' dt 3\n"
		   "set label 'window opens' at first %.17g, graph 0.95 offset 0.5, 0 font ',9' tc rgb 'gray40'\n",
		s->cfg.skip, s->cfg.skip, s->cfg.skip);
	int any = 0;
	for (int j = 0; j < t->ng; j++)
		any |= s->g[j].rep >= 0;
	if (!any)
		fprintf(f, "set xrange [0:1]\nset yrange [0:1]\nset label 'no analysed run' at graph 0.5, graph 0.5 center\n"
			   "plot 2 notitle\n");
	else {
		fputs("plot ", f);
		int np = 0;
		for (int j = 0; j < t->ng; j++) {
			const int i = s->g[j].rep;
			if (i < 0)
				continue;
			char leg[256], tt[512], per[64];
			tool_legend(t, j, 1, leg, sizeof leg);
			const double p = s->ob[i].run.period;
			if (isfinite(p))
				snprintf(per, sizeof per, "period %.1f s", p);
			else
				snprintf(per, sizeof per, "%ld dive%s", s->ob[i].run.dives, s->ob[i].run.dives == 1 ? "" : "s");
			snprintf(tt, sizeof tt, "%s%s%s (%s)", *leg ? leg : "", *leg ? ": " : "", t->runs[i].id, per);
			fprintf(f, "%s'whale_traces.csv' skip 1 using ($1==%d?$4:1/0):5 with lines lt %d lw 1.2 title ",
				np++ ? ", \\\n  " : "", j, j + 1);
			gp_str(f, tt);
			fprintf(f, ", \\\n  'whale_traces.csv' skip 1 using ($1==%d?$4:1/0):7 with lines lt %d dt 2 lw 1 notitle",
				j, j + 1);
		}
		fputc('\n', f);
	}
	fprintf(f, "unset multiplot\n");
	return tool_plot(t, f, script, png);
}

static int init(an_tool *t, void *vs, const xopt *x)
{
	whale_state *s = vs;
	if (xopt_num(&x[0], 0, 1e7, 20, &s->cfg.skip, &t->e) || xopt_num(&x[1], 1e-3, 100, 1, &s->cfg.dive_radii, &t->e))
		return t->e.code;
	return xopt_num(&x[2], 0.01, 1, 0.9, &s->cfg.top_q, &t->e);
}

static int run(an_tool *t, void *vs)
{
	whale_state *s = vs;
	if (consider(t, s) || groups(t, s) || trends(t, s) || cli_outdir(t->o, &t->e) || runs_csv(t, s) ||
	    tool_accounting_csv(t) || traces_csv(t, s) || summary(t, s) || tool_store_end(t))
		return t->e.code;
	report(t, s);
	if (!t->o->no_plot) {
		if (plot(t, s))
			return t->e.code;
		printf("# figure: %s/whale.{png,pdf}\n", t->o->out);
	}
	printf("# csv: %s/whale_{runs,summary,points,trend,traces,accounting}.csv\n", t->o->out);
	return 0;
}

static const tool_spec SPEC = {.name = "whale", .version = VERSION, .help = HELP, .allowed = " by boot seed level ",
			       .x = {{"skip", 1, NULL, 0}, {"dive", 1, NULL, 0}, {"top", 1, NULL, 0}}, .nx = 3,
			       .init = init, .run = run, .fini = state_free};

int main(int argc, char **argv)
{
	whale_state s = {.cfg = {20, NAN, 1, 0.9}};
	return tool_main(argc, argv, &SPEC, &s);
}
