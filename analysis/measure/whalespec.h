/* whalespec.h - the dominant period of the whale oscillation from the power spectrum
 * of the intruder's height, a cross-check of the period counted from dives (whale.h)
 * that needs no threshold.
 *
 * The series (the period-averaged y of the window) is interpolated linearly onto N
 * evenly spaced times spanning it, N the smallest 2^a 3^b 5^c >= the samples (GSL's
 * mixed-radix FFT is fast for these factors only), its mean taken off, tapered by a
 * Hann window (a slow trend or the window's ends would leak into every bin), and
 * transformed (gsl_fft_real_transform). The periodogram's largest bin in the band
 * [2/T, f/2] is the dominant frequency, refined by a parabola through it and its two
 * neighbours (the bins are 1/T apart: a 30 s period in a 600 s window is bin 20, 5 %
 * apart). The band's lower edge asks for two cycles within the window T; its upper
 * edge, half the drive frequency f, leaves the drive and its harmonics (k f, which
 * the running mean over one period has averaged out as well) outside. A maximum on
 * the band's lowest bin is no period but a trend or a red spectrum: flagged. */
#ifndef AN_WHALESPEC_H
#define AN_WHALESPEC_H

#include <stddef.h>

typedef struct whale_spec {
	double period;  /* 1 / the dominant frequency (s); NaN when the band is empty */
	double freq;    /* the dominant frequency (Hz) */
	double share;   /* the share of the band's power within two bins of the peak */
	int edge;       /* 1 when the maximum is the band's lowest bin */
	size_t bins;    /* bins in the band */
} whale_spec;

/* y[0..n) at increasing times t[0..n); drive_f the drive frequency (Hz; 0: the band
 * ends at half the Nyquist frequency instead). Returns 0 (out->period NaN when the
 * band holds fewer than 3 bins), -1 when out of memory. */
int whale_spectrum(const double *t, const double *y, size_t n, double drive_f, whale_spec *out);

/* The smallest 2^a 3^b 5^c >= n (n >= 1). */
size_t whale_fft_size(size_t n);

#endif
