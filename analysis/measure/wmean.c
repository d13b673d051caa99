/* wmean.c - a weighted pooled mean across runs and its Student-t interval (pool.h). */
#include "wmean.h"

#include <math.h>

#include "quantile.h"

void wmean_ci(const double *x, size_t stride, const double *w, size_t n, double level, wmean_res *m)
{
	m->n = 0;
	m->mean = m->se = m->lo = m->hi = NAN;
	double sw = 0, swx = 0;
	for (size_t i = 0; i < n; i++)
		if (w[i] > 0) {
			swx += w[i] * x[i * stride];
			sw += w[i];
			m->n++;
		}
	if (!m->n)
		return;
	m->mean = swx / sw;
	if (m->n < 2)
		return;
	double ss = 0;
	for (size_t i = 0; i < n; i++)
		if (w[i] > 0) {
			const double d = w[i] * (x[i * stride] - m->mean);
			ss += d * d;
		}
	const double k = (double)m->n;
	m->se = sqrt(k / (k - 1) * ss) / sw;
	const double h = quant_student(level, k - 1) * m->se;
	m->lo = m->mean - h;
	m->hi = m->mean + h;
}
