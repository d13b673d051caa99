/* rolls.c - the roll reach of a profile and the intervals that compare runs (rolls.h). */
#include "rolls.h"
#include "quantile.h"

#include <math.h>
#include <stdlib.h>

void rolls_smooth(const double *v, size_t L, size_t K, double *out)
{
	const size_t h = K > 1 ? K / 2 : 0;
	for (size_t l = 0; l < L; l++) {
		const size_t a = l >= h ? l - h : 0, b = l + h < L ? l + h : L - 1;
		double s = 0;
		for (size_t k = a; k <= b; k++)
			s += v[k];
		out[l] = s / (double)(b - a + 1);
	}
}

int rolls_depth(const double *h, const double *phi, size_t L, double surface, double q, size_t K, rolls_reach *r)
{
	r->phi_max = 0;
	r->sign = 0;
	r->lmax = 0;
	r->bottom = r->reach = NAN;
	r->to_floor = 0;
	if (!L)
		return -1;
	for (size_t l = 0; l < L; l++)
		if (!isfinite(phi[l]) || !isfinite(h[l]))
			return -1;
	double *sm = malloc(sizeof *sm * L);
	if (!sm)
		return -1;
	rolls_smooth(phi, L, K, sm);
	for (size_t l = 0; l < L; l++)
		if (fabs(sm[l]) > r->phi_max) {
			r->phi_max = fabs(sm[l]);
			r->lmax = l;
		}
	if (!(r->phi_max > 0)) {
		free(sm);
		return -1;
	}
	r->sign = sm[r->lmax] > 0 ? 1 : -1;
	const double lev = q * r->phi_max;
	size_t l = r->lmax;
	while (l > 0 && r->sign * sm[l - 1] >= lev)
		l--;
	if (l == 0) {
		r->bottom = h[0];
		r->to_floor = 1;
	} else {
		/* s Phi is below lev at l - 1 and at least lev at l */
		const double a = r->sign * sm[l - 1], b = r->sign * sm[l];
		const double u = b > a ? (lev - a) / (b - a) : 1;
		r->bottom = h[l - 1] + u * (h[l] - h[l - 1]);
	}
	r->reach = surface - r->bottom;
	free(sm);
	return 0;
}

void rolls_mean_ci(const double *v, size_t n, double level, rolls_mean *m)
{
	m->n = n;
	m->mean = m->sd = m->lo = m->hi = NAN;
	if (!n)
		return;
	double s = 0;
	for (size_t i = 0; i < n; i++)
		s += v[i];
	m->mean = s / (double)n;
	if (n < 2)
		return;
	double ss = 0;
	for (size_t i = 0; i < n; i++)
		ss += (v[i] - m->mean) * (v[i] - m->mean);
	m->sd = sqrt(ss / (double)(n - 1));
	const double w = quant_student(level, (double)(n - 1)) * m->sd / sqrt((double)n);
	m->lo = m->mean - w;
	m->hi = m->mean + w;
}

void rolls_welch(const double *a, size_t na, const double *b, size_t nb, double level, rolls_diff *r)
{
	rolls_mean ma, mb;
	rolls_mean_ci(a, na, level, &ma);
	rolls_mean_ci(b, nb, level, &mb);
	r->d = ma.mean - mb.mean;
	r->lo = r->hi = r->se = r->df = NAN;
	if (na < 2 || nb < 2)
		return;
	const double va = ma.sd * ma.sd / (double)na, vb = mb.sd * mb.sd / (double)nb;
	r->se = sqrt(va + vb);
	if (!(r->se > 0)) { /* no spread on either side: the difference is what it is */
		r->lo = r->hi = r->d;
		r->df = (double)(na + nb - 2);
		return;
	}
	r->df = (va + vb) * (va + vb) / (va * va / (double)(na - 1) + vb * vb / (double)(nb - 1));
	const double w = quant_student(level, r->df) * r->se;
	r->lo = r->d - w;
	r->hi = r->d + w;
}
