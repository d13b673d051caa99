/* whale.c - the intruder's dives after its rise: top level, dives with hysteresis,
 * period, depth, rate (whale.h). */
#include "whale.h"

#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int whale_smooth(const double *t, const double *y, size_t n, double w, double *out)
{
	if (!(w > 0)) {
		if (n)
			memcpy(out, y, sizeof *out * n);
		return 0;
	}
	/* two pointers over a window [t_i - w/2, t_i + w/2]: O(n) for any spacing; the sum
	 * is kept as a prefix sum, so that a long series does not accumulate the rounding
	 * of adding and subtracting millions of times */
	double *cs = malloc(sizeof *cs * (n + 1));
	if (!cs)
		return -1;
	cs[0] = 0;
	for (size_t i = 0; i < n; i++)
		cs[i + 1] = cs[i] + y[i];
	size_t a = 0, b = 0; /* the window is [a, b) */
	for (size_t i = 0; i < n; i++) {
		while (t[a] < t[i] - 0.5 * w)
			a++;
		if (b < i + 1)
			b = i + 1;
		while (b < n && t[b] <= t[i] + 0.5 * w)
			b++;
		out[i] = (cs[b] - cs[a]) / (double)(b - a);
	}
	free(cs);
	return 0;
}

double whale_quantile(const double *v, size_t n, double q)
{
	if (!n)
		return NAN;
	double *s = malloc(sizeof *s * n);
	if (!s)
		return NAN;
	memcpy(s, v, sizeof *s * n);
	gsl_sort(s, 1, n);
	const double x = gsl_stats_quantile_from_sorted_data(s, 1, n, q);
	free(s);
	return x;
}

void whale_run_init(whale_run *r, double t0)
{
	*r = (whale_run){t0, NAN, 0, NAN, NAN, NAN, 0, 0, NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN};
}

int whale_dives(const double *t, const double *y, size_t n, double t0, const whale_opts *o, whale_run *out,
		double **starts)
{
	whale_run_init(out, t0);
	if (starts)
		*starts = NULL;
	size_t i0 = 0;
	while (i0 < n && t[i0] < t0)
		i0++;
	const size_t m = n - i0;
	out->samples = m;
	if (m < 3)
		return 1;
	const double *tw = t + i0;
	out->t0 = tw[0]; /* the trajectory may begin after t0 */
	double *ys = malloc(sizeof *ys * m), *st = malloc(sizeof *st * m);
	if (!ys || !st || whale_smooth(tw, y + i0, m, o->drive_f > 0 ? 1 / o->drive_f : 0, ys)) {
		free(ys);
		free(st);
		return -1;
	}
	out->t1 = tw[m - 1];
	out->top = whale_quantile(ys, m, o->top_q);
	out->lo = out->top - o->dive;
	out->hi = out->top - 0.5 * o->dive;
	out->mean = gsl_stats_mean(ys, 1, m);
	out->rms = sqrt(gsl_stats_variance_with_fixed_mean(ys, 1, m, out->mean));
	/* up: at the top (a dive may start); in: in a dive; the window opens "in" until y
	 * first reaches hi, so that a dive under way at t0 (start unknown) is not one */
	int in = 1;
	double ymin = INFINITY, dsum = 0, dmax = -INFINITY;
	for (size_t i = 0; i < m; i++) {
		if (in) {
			ymin = fmin(ymin, ys[i]);
			if (ys[i] >= out->hi) {
				if (out->dives > 0) { /* the end of a dive that started within the window */
					const double d = out->top - ymin;
					dsum += d;
					dmax = fmax(dmax, d);
					out->done++;
				}
				in = 0;
			}
		} else if (ys[i] < out->lo) {
			st[out->dives++] = tw[i];
			ymin = ys[i];
			in = 1;
		}
	}
	const double span = out->t1 - out->t0;
	out->rate = span > 0 ? 60.0 * (double)out->dives / span : NAN;
	if (out->dives) {
		out->first = st[0];
		out->last = st[out->dives - 1];
	}
	if (out->dives >= 2)
		out->period = (out->last - out->first) / (double)(out->dives - 1);
	if (out->done) {
		out->depth = dsum / (double)out->done;
		out->depth_max = dmax;
	}
	free(ys);
	if (starts)
		*starts = st;
	else
		free(st);
	return 0;
}
