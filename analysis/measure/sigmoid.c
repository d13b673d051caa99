/* sigmoid.c - logistic fit (GSL nonlinear least squares) and threshold crossing. */
#include "sigmoid.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

double sig_eval(const sig_fit *s, double x)
{
	return s->b + s->a / (1 + exp(-(x - s->x0) / s->w));
}

/* The fit runs on the distinct x with the mean y and the count there as a weight:
 * sum_i (f(x_i) - y_i)^2 = sum_x [n_x (f(x) - mean_x)^2] + the spread within each x,
 * which does not depend on the parameters, so the minimiser, the Jacobian's normal
 * matrix and hence the solver's steps are the raw points' (up to rounding) at the cost
 * of the distinct x: the seeds of a ramp share their frequencies, and a bootstrap
 * resample of 16 seeds costs what one seed does. */
struct pts {
	const double *x, *y, *sw; /* sw: square root of the count at x */
	size_t n;
};

static double logistic(double u)
{
	return u >= 0 ? 1 / (1 + exp(-u)) : exp(u) / (1 + exp(u));
}

static int f_res(const gsl_vector *p, void *ctx, gsl_vector *r)
{
	const struct pts *d = ctx;
	double b = gsl_vector_get(p, 0), a = gsl_vector_get(p, 1), x0 = gsl_vector_get(p, 2);
	double w = exp(gsl_vector_get(p, 3));
	for (size_t i = 0; i < d->n; i++)
		gsl_vector_set(r, i, d->sw[i] * (b + a * logistic((d->x[i] - x0) / w) - d->y[i]));
	return GSL_SUCCESS;
}

static int f_jac(const gsl_vector *p, void *ctx, gsl_matrix *J)
{
	const struct pts *d = ctx;
	double a = gsl_vector_get(p, 1), x0 = gsl_vector_get(p, 2), w = exp(gsl_vector_get(p, 3));
	for (size_t i = 0; i < d->n; i++) {
		double u = (d->x[i] - x0) / w, s = logistic(u), ds = s * (1 - s), q = d->sw[i];
		gsl_matrix_set(J, i, 0, q);
		gsl_matrix_set(J, i, 1, q * s);
		gsl_matrix_set(J, i, 2, -q * a * ds / w);
		gsl_matrix_set(J, i, 3, -q * a * ds * u);
	}
	return GSL_SUCCESS;
}

static int cmp_xy(const void *a, const void *b)
{
	const double *p = a, *q = b;
	return (p[0] > q[0]) - (p[0] < q[0]);
}

/* The distinct finite x (ascending) with the mean y there; with cnt, also the count
 * and with ss the sum of squared deviations from the mean within each x. */
static size_t means_counts(const double *x, const double *y, size_t n, double *ux, double *uy, double *cnt,
			   double *ss)
{
	double *xy = malloc(sizeof *xy * 2 * (n ? n : 1));
	if (!xy)
		return 0;
	size_t k = 0;
	for (size_t i = 0; i < n; i++)
		if (isfinite(x[i]) && isfinite(y[i])) {
			xy[2 * k] = x[i];
			xy[2 * k + 1] = y[i];
			k++;
		}
	qsort(xy, k, 2 * sizeof *xy, cmp_xy);
	size_t m = 0;
	for (size_t i = 0; i < k;) {
		size_t j = i;
		double s = 0;
		while (j < k && xy[2 * j] == xy[2 * i])
			s += xy[2 * j++ + 1];
		const double mean = s / (double)(j - i);
		if (cnt)
			cnt[m] = (double)(j - i);
		if (ss) {
			double q = 0;
			for (size_t t = i; t < j; t++)
				q += (xy[2 * t + 1] - mean) * (xy[2 * t + 1] - mean);
			*ss += q;
		}
		ux[m] = xy[2 * i];
		uy[m++] = mean;
		i = j;
	}
	free(xy);
	return m;
}

size_t sig_means(const double *x, const double *y, size_t n, double *ux, double *uy)
{
	return means_counts(x, y, n, ux, uy, NULL, NULL);
}

/* The level thr stands for on the means uy[0..m), m >= 2 (NaN: their midpoint), and
 * *sgn = 1 when they rise from the lowest to the highest x, else -1 (sig_level). */
static double level_of(const double *uy, size_t m, double thr, double *sgn)
{
	*sgn = uy[m - 1] >= uy[0] ? 1 : -1;
	if (isnan(thr)) {
		double lo = uy[0], hi = uy[0];
		for (size_t i = 1; i < m; i++) {
			lo = fmin(lo, uy[i]);
			hi = fmax(hi, uy[i]);
		}
		thr = 0.5 * (lo + hi);
	}
	return thr;
}

static double crossing(const double *ux, const double *uy, size_t m, double thr)
{
	if (m < 2)
		return NAN;
	double sgn;
	thr = level_of(uy, m, thr, &sgn);
	if (sgn * uy[0] >= sgn * thr)
		return NAN; /* already above at the lowest x: no crossing inside the data */
	for (size_t i = 1; i < m; i++)
		if (sgn * uy[i] >= sgn * thr) {
			double d = uy[i] - uy[i - 1];
			double u = d != 0 ? (thr - uy[i - 1]) / d : 1;
			return ux[i - 1] + u * (ux[i] - ux[i - 1]);
		}
	return NAN;
}

double sig_level(const double *x, const double *y, size_t n, double thr, int *rising)
{
	double *ux = malloc(sizeof *ux * (n ? n : 1)), *uy = malloc(sizeof *uy * (n ? n : 1));
	double r = NAN, sgn = 1;
	const size_t m = ux && uy ? sig_means(x, y, n, ux, uy) : 0;
	if (m >= 2)
		r = level_of(uy, m, thr, &sgn);
	*rising = sgn > 0;
	free(ux);
	free(uy);
	return r;
}

double sig_threshold(const double *x, const double *y, size_t n, double thr)
{
	double *ux = malloc(sizeof *ux * (n ? n : 1)), *uy = malloc(sizeof *uy * (n ? n : 1));
	double r = NAN;
	if (ux && uy)
		r = crossing(ux, uy, sig_means(x, y, n, ux, uy), thr);
	free(ux);
	free(uy);
	return r;
}

/* One start of the trust-region solver; returns chisq or +inf. */
static double solve(struct pts *d, const double p0[4], double out[4])
{
	gsl_multifit_nlinear_parameters fp = gsl_multifit_nlinear_default_parameters();
	gsl_multifit_nlinear_workspace *w = gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &fp, d->n, 4);
	if (!w)
		return INFINITY;
	gsl_multifit_nlinear_fdf fdf = {.f = f_res, .df = f_jac, .fvv = NULL, .n = d->n, .p = 4, .params = d};
	gsl_vector_const_view v = gsl_vector_const_view_array(p0, 4);
	double chisq = INFINITY;
	int info;
	if (gsl_multifit_nlinear_init(&v.vector, &fdf, w) == GSL_SUCCESS) {
		int st = gsl_multifit_nlinear_driver(200, 1e-10, 1e-10, 0, NULL, NULL, &info, w);
		gsl_vector *r = gsl_multifit_nlinear_residual(w);
		gsl_vector *p = gsl_multifit_nlinear_position(w);
		if ((st == GSL_SUCCESS || st == GSL_EMAXITER) && r && p) {
			double s = 0;
			for (size_t i = 0; i < d->n; i++)
				s += gsl_vector_get(r, i) * gsl_vector_get(r, i);
			for (int k = 0; k < 4; k++)
				out[k] = gsl_vector_get(p, (size_t)k);
			chisq = isfinite(s) ? s : INFINITY;
		}
	}
	gsl_multifit_nlinear_free(w);
	return chisq;
}

int sig_fit_data(const double *x, const double *y, size_t n, sig_fit *s)
{
	memset(s, 0, sizeof *s);
	s->b = s->a = s->x0 = s->w = s->chisq = NAN;
	gsl_set_error_handler_off();
	double *ux = malloc(sizeof *ux * (n ? n : 1)), *uy = malloc(sizeof *uy * (n ? n : 1));
	double *sw = malloc(sizeof *sw * (n ? n : 1)), within = 0;
	size_t m = ux && uy && sw ? means_counts(x, y, n, ux, uy, sw, &within) : 0;
	size_t nf = 0; /* the finite points */
	for (size_t i = 0; i < m; i++) {
		nf += (size_t)sw[i];
		sw[i] = sqrt(sw[i]);
	}
	if (m < 3 || nf < 5) { /* four parameters need more than four points and three x */
		free(ux);
		free(uy);
		free(sw);
		return 0;
	}
	double xlo = ux[0], xhi = ux[m - 1], range = xhi - xlo;
	double x0 = crossing(ux, uy, m, NAN);
	if (!isfinite(x0))
		x0 = 0.5 * (xlo + xhi);
	struct pts d = {ux, uy, sw, m};
	double *ones = NULL;
	if (m < 4) { /* fewer residuals than parameters: the solver wants the raw points */
		ones = malloc(sizeof *ones * n);
		if (!ones) {
			free(ux);
			free(uy);
			free(sw);
			return 0;
		}
		for (size_t i = 0; i < n; i++)
			ones[i] = 1;
		d = (struct pts){x, y, ones, n};
		within = 0;
	}
	double best = INFINITY, bp[4] = {0};
	static const double widths[] = {0.02, 0.1, 0.3};
	for (int k = 0; k < 3; k++) {
		double p0[4] = {uy[0], uy[m - 1] - uy[0], x0, log(widths[k] * range)}, p[4];
		double c = solve(&d, p0, p);
		if (c < best) {
			best = c;
			memcpy(bp, p, sizeof bp);
		}
	}
	free(ux);
	free(uy);
	free(sw);
	free(ones);
	if (!isfinite(best))
		return 0;
	best += within; /* the raw points' sum of squares */
	s->b = bp[0];
	s->a = bp[1];
	s->x0 = bp[2];
	s->w = exp(bp[3]);
	s->chisq = best;
	s->ok = isfinite(s->b) && isfinite(s->a) && isfinite(s->w) && s->x0 >= xlo && s->x0 <= xhi;
	return s->ok;
}

void sig_why(const double *x, const double *y, size_t n, const sig_fit *s, const char *xs, char *buf, size_t len)
{
	if (s->ok) {
		snprintf(buf, len, "%s", "");
		return;
	}
	double *ux = malloc(sizeof *ux * (n ? n : 1)), *uy = malloc(sizeof *uy * (n ? n : 1));
	double *cnt = malloc(sizeof *cnt * (n ? n : 1)), within = 0;
	const size_t m = ux && uy && cnt ? means_counts(x, y, n, ux, uy, cnt, &within) : 0;
	size_t nf = 0;
	for (size_t i = 0; i < m; i++)
		nf += (size_t)cnt[i];
	free(ux);
	free(uy);
	free(cnt);
	/* sig_fit_data's conditions, in its order */
	if (m < 3)
		snprintf(buf, len, "not fitted: %zu distinct %s, a sigmoid needs at least 3", m, xs);
	else if (nf < 5)
		snprintf(buf, len, "not fitted: %zu points, a sigmoid needs at least 5", nf);
	else
		snprintf(buf, len, "not fitted: no convergence to a midpoint inside the %s sampled", xs);
}
