/* pairdiff.c - paired comparison of two codes' profiles (pairdiff.h). */
#include "pairdiff.h"
#include "quantile.h"

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void pd_free(pd_result *r)
{
	free(r->ma);
	free(r->ha);
	free(r->mb);
	free(r->hb);
	free(r->md);
	free(r->hd);
	free(r->t);
	free(r->agree);
	memset(r, 0, sizeof *r);
}

/* mean and sample standard deviation of v[0], v[stride], ... (n values) */
static void meansd(const double *v, size_t n, size_t stride, double *m, double *sd)
{
	double s = 0;
	for (size_t i = 0; i < n; i++)
		s += v[i * stride];
	*m = s / (double)n;
	double q = 0;
	for (size_t i = 0; i < n; i++)
		q += (v[i * stride] - *m) * (v[i * stride] - *m);
	*sd = n > 1 ? sqrt(q / (double)(n - 1)) : NAN;
}

/* t of the mean of sign[i] * d[i * L + l] over the beds, per used line; the two
 * statistics over the lines */
static void stats(const double *d, const double *sign, size_t n, size_t L, const int *used, double *maxt,
		  double *chi2)
{
	double mx = 0, s2 = 0;
	size_t k = 0;
	for (size_t l = 0; l < L; l++) {
		if (!used[l])
			continue;
		double s = 0, q = 0;
		for (size_t i = 0; i < n; i++)
			s += sign[i] * d[i * L + l];
		const double m = s / (double)n;
		for (size_t i = 0; i < n; i++) {
			const double u = sign[i] * d[i * L + l] - m;
			q += u * u;
		}
		const double se = sqrt(q / (double)(n - 1) / (double)n);
		const double t = se > 0 ? m / se : (m != 0 ? INFINITY : 0);
		mx = fmax(mx, fabs(t));
		s2 += t * t;
		k++;
	}
	*maxt = mx;
	*chi2 = k ? s2 / (double)k : 0;
}

int pd_compare(size_t n, size_t L, const double *a, const double *b, double level, pd_result *r, sb_err *e)
{
	memset(r, 0, sizeof *r);
	if (n < 2)
		return sb_errf(e, SB_EUSAGE, "a comparison over beds needs two beds at least (got %zu)", n);
	if (!(level > 0 && level < 1))
		return sb_errf(e, SB_EUSAGE, "confidence level %g is not in (0, 1)", level);
	r->n = n;
	r->L = L;
	r->level = level;
	const size_t L1 = L ? L : 1;
	r->ma = calloc(L1, sizeof(double));
	r->ha = calloc(L1, sizeof(double));
	r->mb = calloc(L1, sizeof(double));
	r->hb = calloc(L1, sizeof(double));
	r->md = calloc(L1, sizeof(double));
	r->hd = calloc(L1, sizeof(double));
	r->t = calloc(L1, sizeof(double));
	r->agree = calloc(L1, sizeof(int));
	double *d = malloc(sizeof(double) * n * L1), *sign = malloc(sizeof(double) * n);
	int *used = calloc(L1, sizeof(int));
	if (!r->ma || !r->ha || !r->mb || !r->hb || !r->md || !r->hd || !r->t || !r->agree || !d || !sign || !used) {
		free(d), free(sign), free(used);
		pd_free(r);
		return sb_errf(e, SB_ENOMEM, "out of memory");
	}
	const double tq = quant_student(level, (double)(n - 1));
	const double sq = sqrt((double)n);
	for (size_t i = 0; i < n * L; i++)
		d[i] = a[i] - b[i];
	for (size_t l = 0; l < L; l++) {
		double sd;
		meansd(a + l, n, L, &r->ma[l], &sd);
		r->ha[l] = tq * sd / sq;
		meansd(b + l, n, L, &r->mb[l], &sd);
		r->hb[l] = tq * sd / sq;
		meansd(d + l, n, L, &r->md[l], &sd);
		r->hd[l] = tq * sd / sq;
		const double se = sd / sq;
		r->t[l] = se > 0 ? r->md[l] / se : (r->md[l] != 0 ? INFINITY : 0);
		r->agree[l] = fabs(r->md[l]) <= r->hd[l];
		r->ndis += !r->agree[l];
		for (size_t i = 0; i < n && !used[l]; i++)
			used[l] = d[i * L + l] != 0;
		r->lines_used += (size_t)used[l];
	}
	for (size_t i = 0; i < n; i++)
		sign[i] = 1;
	stats(d, sign, n, L, used, &r->maxt, &r->chi2);
	/* the sign-flip null distribution */
	long ge_max = 0, ge_chi = 0;
	r->exact = n <= 16;
	r->perms = r->exact ? 1L << n : 65536;
	gsl_rng *rng = r->exact ? NULL : gsl_rng_alloc(gsl_rng_mt19937);
	if (rng)
		gsl_rng_set(rng, 1);
	for (long p = 0; p < r->perms; p++) {
		for (size_t i = 0; i < n; i++)
			sign[i] = r->exact ? ((p >> i) & 1 ? -1 : 1) : (gsl_rng_uniform(rng) < 0.5 ? -1 : 1);
		double mx, c2;
		stats(d, sign, n, L, used, &mx, &c2);
		/* a relative tolerance so that the pattern equal to the data counts */
		ge_max += mx >= r->maxt * (1 - 1e-12);
		ge_chi += c2 >= r->chi2 * (1 - 1e-12);
	}
	if (rng)
		gsl_rng_free(rng);
	r->p_maxt = (double)ge_max / (double)r->perms;
	r->p_chi2 = (double)ge_chi / (double)r->perms;
	free(d);
	free(sign);
	free(used);
	return 0;
}
