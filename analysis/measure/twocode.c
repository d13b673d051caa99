/* twocode.c - exact small-sample statistics of the two-code validation (twocode.h). */
#include "twocode.h"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
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

/* What every power of one n and alpha shares: whether the discordant counts (b, c) are
 * significant (sig[m(m+1)/2 + b], m = b + c: the sign test's two GSL tails per cell
 * are most of the cost) and lgamma(i + 1) for i = 0..n. Computed once, the search of
 * tc_mcnemar_detect over up to 1000 differences costs sums only, with the same terms
 * in the same order as before. */
typedef struct mc_table {
	long n;
	unsigned char *sig;
	double *lgf;
} mc_table;

static int mc_init(mc_table *t, long n, double alpha)
{
	t->n = n;
	t->sig = malloc((size_t)(n + 1) * (size_t)(n + 2) / 2);
	t->lgf = malloc(sizeof *t->lgf * (size_t)(n + 1));
	if (!t->sig || !t->lgf)
		return -1;
	for (long m = 0; m <= n; m++)
		for (long b = 0; b <= m; b++)
			t->sig[m * (m + 1) / 2 + b] = tc_sign_p(b, m) < alpha;
	for (long i = 0; i <= n; i++)
		t->lgf[i] = lgamma((double)i + 1);
	return 0;
}

static void mc_free(mc_table *t)
{
	free(t->sig);
	free(t->lgf);
}

static double mc_power(const mc_table *t, double pa, double pb)
{
	const long n = t->n;
	const double q1 = pa * (1 - pb), q2 = pb * (1 - pa), q0 = 1 - q1 - q2;
	/* each term whole in logarithms: the trinomial coefficient alone passes DBL_MAX
	 * from n ~ 650 beds on (inf times an underflowed power made the sum NaN, taken as
	 * power 1); a probability 0 contributes only where its count is 0 (0^0 = 1) */
	const double l1 = log(q1), l2 = log(q2), l0 = log(fmax(0, q0));
	double pw = 0;
	for (long b = 0; b <= n; b++)
		for (long c = 0; b + c <= n; c++) {
			const long m = b + c;
			if (!t->sig[m * (m + 1) / 2 + b])
				continue;
			const long r = n - b - c;
			const double lg = t->lgf[n] - t->lgf[b] - t->lgf[c] - t->lgf[r];
			pw += exp(lg + (b ? (double)b * l1 : 0) + (c ? (double)c * l2 : 0) + (r ? (double)r * l0 : 0));
		}
	return fmin(1, pw);
}

double tc_mcnemar_power(long n, double pa, double pb, double alpha)
{
	if (n < 1 || n > TC_MCNEMAR_MAX || !(pa >= 0 && pa <= 1) || !(pb >= 0 && pb <= 1))
		return NAN;
	mc_table t;
	const double pw = mc_init(&t, n, alpha) ? NAN : mc_power(&t, pa, pb);
	mc_free(&t);
	return pw;
}

double tc_mcnemar_detect(long n, double p0, int dir, double alpha, double power)
{
	if (n < 1 || n > TC_MCNEMAR_MAX || !(p0 >= 0 && p0 <= 1) || (dir != 1 && dir != -1))
		return NAN;
	mc_table t;
	double found = NAN;
	if (!mc_init(&t, n, alpha))
		for (int k = 1; k <= 1000; k++) {
			const double delta = k * 1e-3, pb = p0 + dir * delta;
			if (pb < -1e-12 || pb > 1 + 1e-12)
				break;
			if (mc_power(&t, p0, fmin(1, fmax(0, pb))) >= power) {
				found = delta;
				break;
			}
		}
	mc_free(&t);
	return found;
}

enum tc_verdict tc_verdict_of(double pa, double pb, double pab, double alpha)
{
	if (isnan(pa) || isnan(pb) || isnan(pab) || isnan(alpha))
		return TC_NONE;
	if (pab < alpha)
		return TC_DIFFER;
	const int sa = pa < alpha, sb = pb < alpha;
	return sa && sb ? TC_BOTH : !sa && !sb ? TC_NEITHER : TC_ONE;
}

/* a p-value as the sentences print it */
static const char *pval(double p, char *buf, size_t len)
{
	snprintf(buf, len, p < 0.001 ? "%.1e" : "%.3g", p);
	return buf;
}

enum tc_verdict tc_verdict_text(double pa, double pb, double pab, double alpha, const char *a, const char *b,
				const char *effect, const char *test_own, const char *test_ab, char *buf, size_t len)
{
	char s[3][32];
	const enum tc_verdict v = tc_verdict_of(pa, pb, pab, alpha);
	pval(pa, s[0], sizeof s[0]);
	pval(pb, s[1], sizeof s[1]);
	pval(pab, s[2], sizeof s[2]);
	switch (v) {
	case TC_DIFFER:
		snprintf(buf, len, "The codes differ: %s p = %s between %s and %s on the same beds (%s p = %s in %s, %s in %s).",
			 test_ab, s[2], a, b, test_own, s[0], a, s[1], b);
		break;
	case TC_BOTH:
		snprintf(buf, len, "The codes agree (%s p = %s), and each shows %s (%s p = %s in %s, %s in %s).", test_ab,
			 s[2], effect, test_own, s[0], a, s[1], b);
		break;
	case TC_NEITHER:
		snprintf(buf, len, "The codes agree (%s p = %s), and neither can decide: neither shows %s on these beds "
			 "(%s p = %s in %s, %s in %s).", test_ab, s[2], effect, test_own, s[0], a, s[1], b);
		break;
	case TC_ONE:
		snprintf(buf, len, "The codes are not told apart bed by bed (%s p = %s), but only %s shows %s (%s p = %s in "
			 "%s, %s in %s): these beds cannot decide whether it is the model's or one code's.", test_ab, s[2],
			 pa < alpha ? a : b, effect, test_own, s[0], a, s[1], b);
		break;
	default: snprintf(buf, len, "No verdict: a p-value is missing."); break;
	}
	return v;
}
