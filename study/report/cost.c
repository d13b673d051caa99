/* cost.c - a campaign's cost before the start (cost.h). */
#include "report/cost.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "params.h"

long cost_chain_max(double from, double to, double tolerance)
{
	if (!(to > from) || !(tolerance > 0) || to - from <= tolerance)
		return 2;
	return (long)ceil(log2((to - from) / tolerance) - 1e-9) + 2;
}

long cost_chain_min(double from, double to, double tolerance)
{
	return cost_chain_max(from, to, tolerance) - 2;
}

/* The shortest a run of s may be: its stop rule cannot end it sooner. */
static double shortest(const sb_scene *s)
{
	const double d = s->stop == STOP_FLUX ? s->stop_skip : s->stop == STOP_RISEN ? s->stop_after : s->duration;
	return fmin(d, s->duration);
}

/* n runs of scene s (at least n_lo), settling k packings, into sum */
static void add_runs(cost_sum *sum, const sb_scene *s, long n, long n_lo, long k)
{
	const int i = s->integrator >= 0 && s->integrator < COST_NINTEG ? s->integrator : 0;
	const double steps = ceil(s->duration / s->dt - 1e-9), lo = shortest(s);
	const int settles = !s->particles[0] && s->settle != TRI_NO;
	sum->runs += n;
	sum->sim += (double)n * s->duration;
	sum->grain_steps[i] += (double)n * steps * (double)s->n_grains;
	sum->runs_lo += n_lo;
	sum->sim_lo += (double)n_lo * lo;
	sum->grain_steps_lo[i] += (double)n_lo * ceil(lo / s->dt - 1e-9) * (double)s->n_grains;
	if (settles) {
		sum->packings += k;
		sum->settle_grains[i] += (double)k * (double)s->n_grains;
	}
	sum->stop_rule |= s->stop != STOP_NONE;
}

static void merge(cost_sum *t, const cost_sum *g)
{
	t->runs += g->runs;
	t->bound |= g->bound;
	t->stop_rule |= g->stop_rule;
	t->packings += g->packings;
	t->sim += g->sim;
	t->runs_lo += g->runs_lo;
	t->sim_lo += g->sim_lo;
	for (int i = 0; i < COST_NINTEG; i++) {
		t->settle_grains[i] += g->settle_grains[i];
		t->grain_steps[i] += g->grain_steps[i];
		t->grain_steps_lo[i] += g->grain_steps_lo[i];
	}
}

/* Whether run k's packing (its cache key) was met among runs [0, k) of the same point set. */
static int key_seen(const grid *g, long k)
{
	for (long j = 0; j < k; j++)
		if (!strcmp(g->runs[j].cache_key, g->runs[k].cache_key))
			return 1;
	return 0;
}

void cost_count(const campaign *c, const grid *g, int use_cache, cost_sum *groups, cost_sum *total)
{
	memset(total, 0, sizeof *total);
	if (groups)
		memset(groups, 0, sizeof *groups * (size_t)g->points);
	for (long p = 0; p < g->points && (c->onset.line || c->autorep.on); p++) {
		/* the runs depend on the results: every group at its maximum, each replicate
		 * settling its own packing (its seed) */
		cost_sum one = {.bound = 1};
		sb_scene s;
		grid_point_scene(c, p, &s);
		long reps, per, reps_lo, per_lo;
		if (c->onset.line) {
			reps = c->onset.autorep ? c->onset.max_replicates : c->onset.replicates;
			reps_lo = c->onset.autorep ? c->onset.batch : c->onset.replicates;
			per = cost_chain_max(c->onset.from, c->onset.to, c->onset.tolerance);
			per_lo = cost_chain_min(c->onset.from, c->onset.to, c->onset.tolerance);
		} else {
			reps = c->autorep.max_replicates;
			reps_lo = c->autorep.batch;
			per = per_lo = 1;
		}
		add_runs(&one, &s, reps * per, fmin(reps_lo, reps) * per_lo, use_cache ? reps : reps * per);
		if (groups)
			groups[p] = one;
		merge(total, &one);
	}
	if (c->onset.line || c->autorep.on)
		return;
	for (long k = 0; k < g->n; k++) {
		const grid_run *r = &g->runs[k];
		sb_scene s;
		grid_scene(g, r, &s);
		cost_sum one = {0};
		add_runs(&one, &s, 1, 1, !use_cache || !key_seen(g, k));
		if (groups && r->point >= 0 && r->point < g->points)
			merge(&groups[r->point], &one);
		merge(total, &one);
	}
}

double cost_cpu(const cost_sum *s, const calib *rates)
{
	double cpu = 0;
	for (int i = 0; i < COST_NINTEG; i++)
		if (s->grain_steps[i] > 0 || s->settle_grains[i] > 0)
			cpu += s->grain_steps[i] * rates[i].step + s->settle_grains[i] * rates[i].settle;
	return cpu;
}

/* ... and at least: the shortest runs, no settling */
static double cost_cpu_lo(const cost_sum *s, const calib *rates)
{
	double cpu = 0;
	for (int i = 0; i < COST_NINTEG; i++)
		if (s->grain_steps_lo[i] > 0)
			cpu += s->grain_steps_lo[i] * rates[i].step;
	return cpu;
}

/* "3.2 s", "4.1 min", "2.3 h" */
static void human(double s, char *buf, size_t len)
{
	if (s < 120)
		snprintf(buf, len, "%.3g s", s);
	else if (s < 7200)
		snprintf(buf, len, "%.3g min", s / 60);
	else
		snprintf(buf, len, "%.3g h", s / 3600);
}

static void line(FILE *out, const char *head, const cost_sum *s, const calib *rates)
{
	char cpu[32], sim[32];
	int known = 1;
	for (int i = 0; i < COST_NINTEG; i++)
		if ((s->grain_steps[i] > 0 || s->settle_grains[i] > 0) && !(rates[i].step > 0))
			known = 0;
	if (known)
		human(cost_cpu(s, rates), cpu, sizeof cpu);
	else
		snprintf(cpu, sizeof cpu, "not known yet");
	human(s->sim, sim, sizeof sim);
	const char *most = s->bound ? "at most " : "";
	const char *up = s->bound || s->stop_rule ? "at most " : "";
	fprintf(out, "%s%s%ld runs, %s%s of simulated shaking%s, %s%ld packings to settle, CPU %s%s\n", head, most,
		s->runs, up, sim, s->stop_rule ? " (a stop rule may end runs earlier)" : "", most, s->packings,
		known ? up : "", cpu);
	if (!s->bound && !s->stop_rule)
		return;
	/* the other end: what the campaign costs at the least, so that a reader sees the
	 * range the real run falls in (docs/campaigns.md, "Cost before the start") */
	human(s->sim_lo, sim, sizeof sim);
	if (known)
		human(cost_cpu_lo(s, rates), cpu, sizeof cpu);
	fprintf(out, "%*s(at least %ld runs, %s of simulated shaking%s%s, if no run fails)\n", (int)strlen(head), "",
		s->runs_lo, sim, known ? ", CPU " : "", known ? cpu : "");
}

void cost_print(FILE *out, const campaign *c, const cost_sum *groups, long ngroups, const cost_sum *total,
		const calib *rates)
{
	fprintf(out, "study: %s: cost before the start", c->name);
	if (c->onset.line)
		fprintf(out, " (an [onset] search: every replicate's chain at its most runs, %ld, and %s%ld replicates)",
			cost_chain_max(c->onset.from, c->onset.to, c->onset.tolerance),
			c->onset.autorep ? "at most " : "", c->onset.autorep ? c->onset.max_replicates : c->onset.replicates);
	else if (c->autorep.on)
		fprintf(out, " (replicates = auto: every point at its max_replicates, %ld)", c->autorep.max_replicates);
	fputs(":\n", out);
	line(out, "  total: ", total, rates);
	for (long p = 0; groups && (c->onset.line || c->autorep.on) && ngroups > 1 && p < ngroups && p < 20; p++) {
		char label[512], head[600];
		grid_point_label(c, p, label, sizeof label);
		snprintf(head, sizeof head, "  %s: ", label);
		line(out, head, &groups[p], rates);
	}
	if (groups && (c->onset.line || c->autorep.on) && ngroups > 20)
		fprintf(out, "  (and %ld more groups)\n", ngroups - 20);
	for (int i = 0; i < COST_NINTEG; i++)
		if ((total->grain_steps[i] > 0 || total->settle_grains[i] > 0) && rates[i].step > 0)
			fprintf(out, "  rate: %.3g CPU s per grain-step, %.3g CPU s per grain settled; %s\n", rates[i].step,
				rates[i].settle, rates[i].source);
		else if (total->grain_steps[i] > 0 || total->settle_grains[i] > 0)
			fprintf(out, "  rate: %s\n", rates[i].source);
}
