/* powerfit.c - a power law fitted on log-log with weights from intervals (powerfit.h). */
#include "powerfit.h"

#include <gsl/gsl_fit.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "boot.h"
#include "quantile.h"

double powerfit_sigma(double lo, double hi, double level)
{
	if (!(lo > 0) || !(hi > lo) || !isfinite(hi))
		return NAN;
	return (log(hi) - log(lo)) / (2 * quant_normal(level));
}

/* The usable points into lx, ly, w (w NULL: unweighted); their number. */
static size_t points(const double *x, const double *y, const double *lo, const double *hi, size_t n, double level,
		     double *lx, double *ly, double *w, int *weighted)
{
	size_t m = 0;
	*weighted = lo && hi;
	for (size_t i = 0; i < n; i++) {
		if (!(x[i] > 0) || !(y[i] > 0) || !isfinite(x[i]) || !isfinite(y[i]))
			continue;
		const double s = *weighted ? powerfit_sigma(lo[i], hi[i], level) : NAN;
		*weighted &= isfinite(s);
		lx[m] = log(x[i]);
		ly[m] = log(y[i]);
		w[m++] = 1 / (s * s);
	}
	return m;
}

/* ln y = ln c + p ln x on m points; p, c, se, chi2 into r. 0, or -1 when degenerate. */
static int fit_log(const double *lx, const double *ly, const double *w, size_t m, int weighted, powerfit_res *r)
{
	double c0, c1, c00, c01, c11, ss;
	int rc = weighted ? gsl_fit_wlinear(lx, 1, w, 1, ly, 1, m, &c0, &c1, &c00, &c01, &c11, &ss)
			  : gsl_fit_linear(lx, 1, ly, 1, m, &c0, &c1, &c00, &c01, &c11, &ss);
	if (rc || !isfinite(c1))
		return -1;
	r->p = c1;
	r->c = exp(c0);
	r->chi2 = ss;
	/* gsl_fit_wlinear's covariance takes the weights as 1/sigma^2 (the intervals'),
	 * gsl_fit_linear's scales by the residuals over m - 2 degrees of freedom */
	r->se = weighted ? sqrt(c11) : m > 2 ? sqrt(c11) : NAN;
	return 0;
}

int powerfit_fit(const double *x, const double *y, const double *lo, const double *hi, size_t n, double level,
		 powerfit_res *r)
{
	memset(r, 0, sizeof *r);
	r->p = r->c = r->se = r->cov_lo = r->cov_hi = r->chi2 = r->boot_lo = r->boot_hi = NAN;
	double *buf = malloc(sizeof *buf * 3 * (n ? n : 1));
	if (!buf)
		return -1;
	double *lx = buf, *ly = buf + n, *w = buf + 2 * n;
	r->n = points(x, y, lo, hi, n, level, lx, ly, w, &r->weighted);
	int rc = -1;
	if (r->n >= 2) {
		for (size_t i = 1; i < r->n && rc; i++)
			rc = lx[i] != lx[0] ? 0 : -1; /* two different x at least */
		if (!rc)
			rc = fit_log(lx, ly, w, r->n, r->weighted, r);
	}
	if (!rc && isfinite(r->se)) {
		const double z = quant_normal(level);
		r->cov_lo = r->p - z * r->se;
		r->cov_hi = r->p + z * r->se;
	}
	free(buf);
	return rc;
}

int powerfit_boot(const double *x, const double *lo, const double *hi, const double *rep, size_t n, size_t B,
		  double level, powerfit_res *r)
{
	r->boot_lo = r->boot_hi = NAN;
	r->boot_ok = 0;
	if (B < 2 || n < 2)
		return 0;
	double *buf = malloc(sizeof *buf * (4 * n + B));
	if (!buf)
		return -1;
	double *y = buf, *lx = buf + n, *ly = buf + 2 * n, *w = buf + 3 * n, *ps = buf + 4 * n;
	const size_t shift = B / n;
	for (size_t b = 0; b < B; b++) {
		ps[b] = NAN;
		int weighted;
		for (size_t i = 0; i < n; i++)
			y[i] = rep[i * B + (b + i * shift) % B];
		/* the points of the main fit, every one (a replicate that lost one is out) */
		const size_t m = points(x, y, r->weighted ? lo : NULL, r->weighted ? hi : NULL, n, level, lx, ly, w, &weighted);
		powerfit_res q;
		if (m == r->n && !fit_log(lx, ly, w, m, weighted, &q))
			ps[b] = q.p;
	}
	r->boot_ok = boot_percentile(ps, B, level, &r->boot_lo, &r->boot_hi);
	free(buf);
	return 0;
}

void powerfit_interval(const powerfit_res *r, double *lo, double *hi)
{
	const int boot = isfinite(r->boot_lo) && isfinite(r->boot_hi);
	*lo = boot ? r->boot_lo : r->cov_lo;
	*hi = boot ? r->boot_hi : r->cov_hi;
}

int powerfit_excludes(const powerfit_res *r, double p0)
{
	double lo, hi;
	powerfit_interval(r, &lo, &hi);
	if (!isfinite(lo) || !isfinite(hi))
		return -1;
	return p0 < lo || p0 > hi;
}
