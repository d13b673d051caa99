/* adapt.c - brackets, chains, the interval over replicates and the replicates a
 * group needs (see adapt.h; the reasoning is in docs/driver.md). */
#include "adapt.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

double adapt_mid(double lo, double hi)
{
	char buf[40];
	snprintf(buf, sizeof buf, "%.12g", 0.5 * lo + 0.5 * hi);
	return strtod(buf, NULL);
}

/* Within a bracket of width tol the search stops; the slack absorbs the rounding of
 * the midpoints (12 digits), so a range that halves onto the tolerance stops there. */
static int narrow(const ad_range *r, double lo, double hi)
{
	return hi - lo <= r->tol * (1 + 1e-9);
}

void adapt_bracket(const ad_range *r, ad_rep *p)
{
	int has_off = 0, on_from = 0;
	double lo = r->from, hi = r->to;
	for (int i = 0; i < p->nobs; i++)
		if (!p->obs[i].on && (!has_off || p->obs[i].f > lo)) {
			lo = p->obs[i].f;
			has_off = 1;
		}
	/* the last switch: the lowest on above the highest off. Below the highest off an
	 * on means the response flips with frequency; the transition reported is the one
	 * above which every run was on */
	int has_hi = 0;
	p->nonmonotone = 0;
	for (int i = 0; i < p->nobs; i++) {
		const ad_obs *o = &p->obs[i];
		if (!o->on)
			continue;
		if (o->f == r->from)
			on_from = 1;
		if (has_off && o->f < lo)
			p->nonmonotone = 1;
		else if (o->f > lo && (!has_hi || o->f < hi)) {
			hi = o->f;
			has_hi = 1;
		}
	}
	p->lo = lo;
	p->hi = hi;
	p->lo_seen = has_off;
	p->hi_seen = has_hi;
	p->next = NAN;
	if (!has_off && on_from) {
		p->state = AD_BELOW;
		p->lo = -INFINITY;
		p->hi = r->from;
		p->hi_seen = 1;
	} else if (has_off && lo >= r->to) {
		p->state = AD_ABOVE;
		p->lo = r->to;
		p->hi = INFINITY;
	} else if (!narrow(r, lo, hi)) {
		double m = adapt_mid(lo, hi);
		/* a bracket so narrow that the printed midpoint is one of its ends is an
		 * answer too (the campaign's tolerance keeps this from happening) */
		p->state = m > lo && m < hi ? AD_SEARCHING : AD_FOUND;
		p->next = m;
	} else if (!has_off) {
		/* the bracket closed on the lower end without running it: run it, so that an
		 * onset below the range is reported as such instead of as `from` */
		p->state = AD_SEARCHING;
		p->next = r->from;
	} else if (!has_hi) {
		p->state = AD_SEARCHING;
		p->next = r->to;
	} else {
		p->state = AD_FOUND;
	}
	if (p->state == AD_FOUND)
		p->next = NAN;
}

void adapt_walk(const ad_range *r, ad_look look, void *ctx, ad_rep *p)
{
	p->nobs = 0;
	for (;;) {
		adapt_bracket(r, p);
		if (p->state != AD_SEARCHING)
			return;
		if (p->nobs >= AD_MAX_STEPS) { /* cannot happen within the campaign's limits */
			p->state = AD_FOUND;
			p->next = NAN;
			return;
		}
		int k = look(ctx, p->next);
		if (k == AD_WAIT)
			return;
		if (k == AD_FAILED) {
			p->state = AD_BLOCKED;
			return;
		}
		p->obs[p->nobs].f = p->next;
		p->obs[p->nobs++].on = k == AD_ON;
	}
}

int adapt_failure_class(const char *status)
{
	/* the statuses of core/base/err.c; one row per failure that answers the question */
	static const struct {
		const char *status;
		int cls;
	} MEANS[] = {
		{"left_box", AD_ON}, /* grains thrown over the walls: far above the onset */
	};
	for (size_t i = 0; status && i < sizeof MEANS / sizeof *MEANS; i++)
		if (!strcmp(status, MEANS[i].status))
			return MEANS[i].cls;
	return AD_FAILED;
}

static double identity(void *ctx, double x)
{
	(void)ctx;
	return x;
}

int adapt_member_map(const ad_range *r, double f, double (*map)(void *ctx, double x), void *ctx)
{
	if (!map)
		map = identity;
	if (f == map(ctx, r->from) || f == map(ctx, r->to))
		return 1;
	double lo = r->from, hi = r->to;
	/* descend the bisection tree by frequency: the map keeps the order of the points */
	for (int d = 0; d < AD_MAX_LEVELS + 4; d++) {
		double m = adapt_mid(lo, hi), fm = map(ctx, m);
		if (f == fm)
			return 1;
		if (!(m > lo && m < hi) || !(f > map(ctx, lo) && f < map(ctx, hi)))
			return 0;
		if (f < fm)
			hi = m;
		else
			lo = m;
	}
	return 0;
}

int adapt_member(const ad_range *r, double f)
{
	return adapt_member_map(r, f, NULL, NULL);
}

long adapt_rank(long n, double level)
{
	if (n < 1 || n > AD_MAX_REPLICATES)
		return 0;
	/* P(Bin(n, 1/2) = k) from k = 0 up; 2^-1000 is a normal double */
	double term = ldexp(1.0, (int)-n), cdf = 0;
	long r = 0;
	for (long k = 0; 2 * (k + 1) <= n + 1; k++) {
		cdf += term;
		if (2 * cdf > 1 - level)
			break;
		r = k + 1;
		term = term * (double)(n - k) / (double)(k + 1);
	}
	return r;
}

long adapt_min_replicates(double level)
{
	for (long n = 1; n <= AD_MAX_REPLICATES; n++)
		if (adapt_rank(n, level) > 0)
			return n;
	return AD_MAX_REPLICATES;
}

static int by_value(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

void adapt_interval(const ad_rep *reps, long n, double level, ad_interval *iv)
{
	iv->n = n;
	iv->est = iv->lo = iv->hi = iv->width = NAN;
	if (n < 1)
		return;
	double *lo = malloc(sizeof *lo * (size_t)n * 3);
	if (!lo)
		return;
	double *hi = lo + n, *mid = hi + n;
	long m = 0;
	for (long i = 0; i < n; i++) {
		const ad_rep *p = &reps[i];
		/* an end that was not run bounds nothing */
		lo[i] = p->lo_seen ? p->lo : -INFINITY;
		hi[i] = p->hi_seen ? p->hi : INFINITY;
		/* the estimate is the answered replicates' (a bracket still searching or
		 * blocked has no midpoint to speak of: its ends may be the range's) */
		if (p->state == AD_BELOW)
			mid[m++] = -INFINITY;
		else if (p->state == AD_ABOVE)
			mid[m++] = INFINITY;
		else if (p->state == AD_FOUND)
			mid[m++] = 0.5 * p->lo + 0.5 * p->hi;
	}
	qsort(lo, (size_t)n, sizeof *lo, by_value);
	qsort(hi, (size_t)n, sizeof *hi, by_value);
	qsort(mid, (size_t)m, sizeof *mid, by_value);
	if (m) {
		double a = mid[(m - 1) / 2], b = mid[m / 2];
		iv->est = a == b ? a : 0.5 * a + 0.5 * b; /* -inf and +inf: NaN, no median */
	}
	long r = adapt_rank(n, level);
	iv->lo = r ? lo[r - 1] : -INFINITY;
	iv->hi = r ? hi[n - r] : INFINITY;
	iv->width = iv->hi - iv->lo;
	free(lo);
}

long adapt_first(const ad_plan *p)
{
	if (!p->autorep)
		return p->n;
	long n = adapt_min_replicates(p->level);
	if (n < p->batch)
		n = p->batch;
	return n < p->max ? n : p->max;
}

int adapt_group(const ad_plan *p, const ad_rep *reps, long n, ad_interval *iv, long *want)
{
	adapt_interval(reps, n, p->level, iv);
	*want = n;
	for (long i = 0; i < n; i++)
		if (reps[i].state == AD_SEARCHING)
			return AD_G_SEARCHING;
	for (long i = 0; i < n; i++)
		if (reps[i].state == AD_BLOCKED)
			return AD_G_BLOCKED;
	if (!p->autorep || iv->width <= p->target * (1 + 1e-9))
		return AD_G_DONE;
	if (n >= p->max)
		return AD_G_MAX;
	*want = n + p->batch < p->max ? n + p->batch : p->max;
	return AD_G_MORE;
}

const char *adapt_state_name(int state)
{
	static const char *const names[] = {"searching", "found", "below", "above", "blocked"};
	return state >= 0 && state <= AD_BLOCKED ? names[state] : "?";
}

const char *adapt_gstate_name(int gstate)
{
	static const char *const names[] = {"searching", "done", "max_replicates", "more", "blocked"};
	return gstate >= 0 && gstate <= AD_G_BLOCKED ? names[gstate] : "?";
}
