/* sharp.c - a grid point's result, its interval, and when it needs more replicates
 * (see sharp.h; the reasoning is in docs/driver.md). */
#include "sharp.h"

#include <math.h>
#include <stdlib.h>

#include "km.h"
#include "quantile.h"
#include "adapt.h"

long sharp_min_replicates(int result, double level)
{
	/* a rise fraction or a mean has an interval from two runs; the median's
	 * order statistics need 2^(1-n) <= 1 - level */
	return result == SH_MEDIAN_WAIT ? adapt_min_replicates(level) : 2;
}

long sharp_first(const sh_plan *p)
{
	long n = sharp_min_replicates(p->result, p->level);
	if (n < p->batch)
		n = p->batch;
	return n < p->max ? n : p->max;
}

/* The median wait: each run's wait lies in its [lo, hi] (a censored run's above its
 * observed time), exactly the brackets adapt_interval takes the order statistics of. */
static void median_wait(const sh_plan *p, const sh_obs *obs, long n, sh_eval *ev)
{
	ad_rep *reps = calloc((size_t)(n ? n : 1), sizeof *reps);
	double *t = malloc(sizeof *t * (size_t)(n ? n : 1));
	int *rose = malloc(sizeof *rose * (size_t)(n ? n : 1));
	if (!reps || !t || !rose) {
		free(reps), free(t), free(rose);
		return;
	}
	long m = 0;
	for (long i = 0; i < n; i++) {
		if (obs[i].kind != SH_USED)
			continue;
		ad_rep *r = &reps[m];
		r->lo = obs[i].time;
		r->lo_seen = 1;
		r->hi = obs[i].risen ? obs[i].time : INFINITY;
		r->hi_seen = obs[i].risen;
		r->state = obs[i].risen ? AD_FOUND : AD_ABOVE;
		t[m] = obs[i].time;
		rose[m++] = obs[i].risen;
	}
	if (m) {
		ad_interval iv;
		adapt_interval(reps, m, p->level, &iv);
		ev->lo = iv.lo;
		ev->hi = iv.hi;
		ev->width = iv.width;
		km_curve k;
		if (!km_fit(t, rose, (size_t)m, &k)) {
			double lo, hi;
			ev->est = km_median(&k, 1.96, &lo, &hi);
			km_free(&k);
		}
	}
	free(reps);
	free(t);
	free(rose);
}

static void rise_fraction(const sh_plan *p, const sh_obs *obs, long n, sh_eval *ev)
{
	long k = 0, m = 0;
	for (long i = 0; i < n; i++)
		if (obs[i].kind == SH_USED) {
			m++;
			k += obs[i].risen != 0;
		}
	if (!m)
		return;
	/* Clopper-Pearson: exact, never narrower than its level, defined at 0 and m */
	ev->est = (double)k / (double)m;
	quant_clopper_pearson(k, m, p->level, &ev->lo, &ev->hi);
	ev->width = ev->hi - ev->lo;
}

static void mean_flux(const sh_plan *p, const sh_obs *obs, long n, sh_eval *ev)
{
	long m = 0;
	double sum = 0, sq = 0;
	for (long i = 0; i < n; i++)
		if (obs[i].kind == SH_USED && isfinite(obs[i].value)) {
			m++;
			sum += obs[i].value;
		}
	if (!m)
		return;
	ev->est = sum / (double)m;
	if (m < 2)
		return; /* unbounded: one run says nothing of the scatter */
	for (long i = 0; i < n; i++)
		if (obs[i].kind == SH_USED && isfinite(obs[i].value))
			sq += (obs[i].value - ev->est) * (obs[i].value - ev->est);
	double h = quant_student(p->level, (double)(m - 1)) * sqrt(sq / (double)(m - 1) / (double)m);
	ev->lo = ev->est - h;
	ev->hi = ev->est + h;
	ev->width = 2 * h;
}

void sharp_interval(const sh_plan *p, const sh_obs *obs, long n, sh_eval *ev)
{
	ev->n = n;
	ev->used = ev->waiting = 0;
	for (long i = 0; i < n; i++) {
		ev->used += obs[i].kind == SH_USED;
		ev->waiting += obs[i].kind == SH_WAIT;
	}
	ev->est = NAN;
	ev->lo = -INFINITY;
	ev->hi = INFINITY;
	ev->width = INFINITY;
	if (p->result == SH_MEDIAN_WAIT)
		median_wait(p, obs, n, ev);
	else if (p->result == SH_RISE_FRACTION)
		rise_fraction(p, obs, n, ev);
	else
		mean_flux(p, obs, n, ev);
}

int sharp_point(const sh_plan *p, const sh_obs *obs, long n, sh_eval *ev, long *want)
{
	sharp_interval(p, obs, n, ev);
	*want = n;
	/* a batch starts only when the earlier runs are in: which replicates exist is a
	 * function of the results, never of timing */
	if (ev->waiting)
		return SH_RUNNING;
	if (ev->width <= p->target * (1 + 1e-9))
		return SH_DONE;
	if (n >= p->max)
		return SH_MAX;
	*want = n + p->batch < p->max ? n + p->batch : p->max;
	return SH_MORE;
}

const char *sharp_state_name(int state)
{
	static const char *const names[] = {"running", "done", "max_replicates", "more"};
	return state >= 0 && state <= SH_MORE ? names[state] : "?";
}

const char *sharp_result_name(int result)
{
	static const char *const names[] = {"median_wait", "rise_fraction", "mean_flux"};
	return result >= 0 && result <= SH_MEAN_FLUX ? names[result] : "?";
}
