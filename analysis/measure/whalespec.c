/* whalespec.c - the dominant period of the height from its periodogram (whalespec.h). */
#include "whalespec.h"

#include <gsl/gsl_fft_real.h>
#include <math.h>
#include <stdlib.h>

size_t whale_fft_size(size_t n)
{
	for (size_t m = n ? n : 1;; m++) {
		size_t r = m;
		while (r % 2 == 0)
			r /= 2;
		while (r % 3 == 0)
			r /= 3;
		while (r % 5 == 0)
			r /= 5;
		if (r == 1)
			return m;
	}
}

/* y at time x by linear interpolation on t (increasing); *j is a cursor that only
 * moves forward, x increasing between calls */
static double interp(const double *t, const double *y, size_t n, double x, size_t *j)
{
	while (*j + 2 < n && t[*j + 1] < x)
		(*j)++;
	const double a = t[*j], b = t[*j + 1];
	if (!(b > a))
		return y[*j];
	const double u = fmin(1, fmax(0, (x - a) / (b - a)));
	return y[*j] + u * (y[*j + 1] - y[*j]);
}

int whale_spectrum(const double *t, const double *y, size_t n, double drive_f, whale_spec *out)
{
	*out = (whale_spec){NAN, NAN, NAN, 0, 0};
	if (n < 4 || !(t[n - 1] > t[0]))
		return 0;
	const size_t N = whale_fft_size(n);
	const double T = t[n - 1] - t[0], dt = T / (double)(N - 1);
	double *d = malloc(sizeof *d * N), *P = malloc(sizeof *P * (N / 2 + 1));
	gsl_fft_real_wavetable *wt = gsl_fft_real_wavetable_alloc(N);
	gsl_fft_real_workspace *ws = gsl_fft_real_workspace_alloc(N);
	int rc = d && P && wt && ws ? 0 : -1;
	if (!rc) {
		size_t j = 0;
		double mean = 0;
		for (size_t i = 0; i < N; i++)
			mean += d[i] = interp(t, y, n, t[0] + dt * (double)i, &j);
		mean /= (double)N;
		for (size_t i = 0; i < N; i++)
			d[i] = (d[i] - mean) * (0.5 - 0.5 * cos(2 * M_PI * (double)i / (double)(N - 1)));
		gsl_fft_real_transform(d, 1, N, wt, ws);
		/* halfcomplex: d[0] the mean, d[2k-1], d[2k] = Re, Im of bin k, and for an
		 * even N d[N-1] = bin N/2 */
		for (size_t k = 1; k <= N / 2; k++)
			P[k] = 2 * k == N ? d[N - 1] * d[N - 1] : d[2 * k - 1] * d[2 * k - 1] + d[2 * k] * d[2 * k];
		const double df = 1 / (N * dt), nyq = 0.5 / dt;
		const double fhi = drive_f > 0 ? fmin(0.5 * drive_f, nyq) : 0.5 * nyq;
		const size_t k0 = 2, k1 = (size_t)floor(fhi / df + 1e-9);
		if (k0 >= 1 && k1 <= N / 2 && k1 >= k0 + 2) {
			size_t kp = k0;
			double tot = 0;
			for (size_t k = k0; k <= k1; k++) {
				tot += P[k];
				if (P[k] > P[kp])
					kp = k;
			}
			double fk = (double)kp;
			if (kp > k0 && kp < k1) { /* the vertex of the parabola through the three bins */
				const double a = P[kp - 1], b = P[kp], c = P[kp + 1], den = a - 2 * b + c;
				if (den < 0)
					fk += 0.5 * (a - c) / den;
			}
			double near = 0;
			for (size_t k = kp >= k0 + 2 ? kp - 2 : k0; k <= k1 && k <= kp + 2; k++)
				near += P[k];
			out->bins = k1 - k0 + 1;
			out->edge = kp == k0;
			if (tot > 0) {
				out->freq = fk * df;
				out->period = 1 / out->freq;
				out->share = near / tot;
			}
		}
	}
	free(d);
	free(P);
	if (wt)
		gsl_fft_real_wavetable_free(wt);
	if (ws)
		gsl_fft_real_workspace_free(ws);
	return rc;
}
