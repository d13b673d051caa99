/* twocode.c - exact small-sample statistics of the two-code validation (twocode.h). */
#include "twocode.h"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>

double tc_sign_p(long k, long n)
{
	if (n < 0 || k < 0 || k > n)
		return NAN;
	if (n == 0)
		return 1;
	const double lower = gsl_cdf_binomial_P((unsigned)k, 0.5, (unsigned)n);
	const double upper = k ? gsl_cdf_binomial_Q((unsigned)k - 1, 0.5, (unsigned)n) : 1;
	return fmin(1, 2 * fmin(lower, upper));
}

static int cmp_abs(const void *a, const void *b)
{
	const double x = fabs(*(const double *)a), y = fabs(*(const double *)b);
	return x < y ? -1 : x > y;
}

int tc_flip_p(const double *d, size_t n, int rank, double *p, int *exact, sb_err *e)
{
	*p = 1;
	*exact = 1;
	double *v = malloc(sizeof *v * (n ? n : 1));
	if (!v)
		return sb_errf(e, SB_ENOMEM, "out of memory for %zu differences", n);
	size_t m = 0;
	for (size_t i = 0; i < n; i++) {
		if (!isfinite(d[i])) {
			free(v);
			return sb_errf(e, SB_EUSAGE, "difference %zu is not a finite number", i + 1);
		}
		if (d[i] != 0)
			v[m++] = d[i];
	}
	if (!m) {
		free(v);
		return 0;
	}
	/* v[] becomes the magnitudes the signs act on, s the observed sum of signed ones */
	double s = 0;
	if (rank) {
		qsort(v, m, sizeof *v, cmp_abs);
		for (size_t i = 0; i < m;) { /* mean ranks over ties of |d| */
			size_t j = i;
			while (j + 1 < m && fabs(v[j + 1]) == fabs(v[i]))
				j++;
			const double r = 0.5 * (double)(i + j) + 1;
			for (size_t k = i; k <= j; k++) {
				if (v[k] > 0)
					s += r;
				v[k] = r;
			}
			i = j + 1;
		}
		/* W+ - m(m+1)/4 is half the sum of the signed ranks, W+ - W- */
		s = 2 * s - (double)m * (double)(m + 1) / 2;
	} else {
		for (size_t i = 0; i < m; i++) {
			s += v[i];
			v[i] = fabs(v[i]);
		}
	}
	const double obs = fabs(s) * (1 - 1e-12); /* ties of the statistic count as reached */
	long hits = 0, total = 0;
	if (m <= 20) {
		const unsigned long np = 1ul << m;
		for (unsigned long pat = 0; pat < np; pat++) {
			double t = 0;
			for (size_t i = 0; i < m; i++)
				t += (pat >> i & 1) ? -v[i] : v[i];
			hits += fabs(t) >= obs;
		}
		total = (long)np;
	} else {
		gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
		if (!g) {
			free(v);
			return sb_errf(e, SB_ENOMEM, "out of memory for a random number generator");
		}
		gsl_rng_set(g, 1);
		total = 1l << 20;
		for (long k = 0; k < total; k++) {
			double t = 0;
			for (size_t i = 0; i < m; i++)
				t += gsl_rng_uniform_int(g, 2) ? -v[i] : v[i];
			hits += fabs(t) >= obs;
		}
		gsl_rng_free(g);
		*exact = 0;
	}
	free(v);
	*p = (double)hits / (double)total;
	return 0;
}

double tc_mcnemar_power(long n, double pa, double pb, double alpha)
{
	if (n < 1 || !(pa >= 0 && pa <= 1) || !(pb >= 0 && pb <= 1))
		return NAN;
	const double q1 = pa * (1 - pb), q2 = pb * (1 - pa), q0 = 1 - q1 - q2;
	double pw = 0;
	for (long b = 0; b <= n; b++)
		for (long c = 0; b + c <= n; c++) {
			if (!(tc_sign_p(b, b + c) < alpha))
				continue;
			const long r = n - b - c;
			const double lg = lgamma((double)n + 1) - lgamma((double)b + 1) - lgamma((double)c + 1) -
					  lgamma((double)r + 1);
			pw += exp(lg) * pow(q1, (double)b) * pow(q2, (double)c) * pow(q0, (double)r);
		}
	return fmin(1, pw);
}

double tc_mcnemar_detect(long n, double p0, int dir, double alpha, double power)
{
	if (n < 1 || !(p0 >= 0 && p0 <= 1) || (dir != 1 && dir != -1))
		return NAN;
	for (int k = 1; k <= 1000; k++) {
		const double delta = k * 1e-3, pb = p0 + dir * delta;
		if (pb < -1e-12 || pb > 1 + 1e-12)
			break;
		if (tc_mcnemar_power(n, p0, fmin(1, fmax(0, pb)), alpha) >= power)
			return delta;
	}
	return NAN;
}
