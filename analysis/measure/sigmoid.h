/* sigmoid.h - a transition located in noisy data y(x): least-squares fit of the
 * logistic  y = b + a / (1 + exp(-(x - x0) / w))  (gsl_multifit_nlinear, trust
 * region with Levenberg-Marquardt steps, several starts, w = exp(parameter) > 0), and
 * a model-free threshold-crossing estimate on the means per distinct x. */
#ifndef AN_SIGMOID_H
#define AN_SIGMOID_H

#include <stddef.h>

typedef struct sig_fit {
	double b, a, x0, w;  /* baseline, step, midpoint, width */
	double chisq;
	int ok;              /* converged, finite, x0 inside [min x, max x] */
} sig_fit;

double sig_eval(const sig_fit *s, double x);
/* Fit n points; returns s->ok. */
int sig_fit_data(const double *x, const double *y, size_t n, sig_fit *s);
/* Why a fit of these n points has no midpoint (s from sig_fit_data), in words naming
 * x as `xs` ("frequencies"): "not fitted: 2 distinct frequencies, a sigmoid needs at least 3",
 * "not fitted: 4 points, a sigmoid needs at least 5", "not fitted: no convergence to
 * a midpoint inside the frequencies sampled"; "" when s->ok. */
void sig_why(const double *x, const double *y, size_t n, const sig_fit *s, const char *xs, char *buf, size_t len);
/* Means per distinct x (sorted ascending) into ux[], uy[] (n entries each at most);
 * returns their number. */
size_t sig_means(const double *x, const double *y, size_t n, double *ux, double *uy);
/* Threshold crossing: on the means per distinct x, oriented so that the mean rises
 * from the lowest to the highest x, the first x at which it reaches thr (linear
 * interpolation between neighbours); thr = NaN takes the midpoint (min + max) / 2 of
 * the means. NaN when it never crosses or fewer than 2 distinct x. */
double sig_threshold(const double *x, const double *y, size_t n, double thr);
/* The level sig_threshold compares the means with: thr, or their midpoint when thr is
 * NaN; *rising = 1 when the means rise from the lowest to the highest x (a point is
 * past the threshold when it is >= the level then, <= it otherwise). NaN when there
 * are fewer than 2 distinct x. */
double sig_level(const double *x, const double *y, size_t n, double thr, int *rising);

#endif
