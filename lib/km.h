/* km.h - Kaplan-Meier survival with right-censoring (Kaplan & Meier, JASA 53, 457,
 * 1958): S(t) = prod over event times t_i <= t of (1 - d_i / n_i), Greenwood's
 * variance Var S = S^2 sum d_i / (n_i (n_i - d_i)); the median (first t with
 * S(t) <= 0.5) and its Brookmeyer-Crowley interval (Biometrics 38, 29, 1982): the
 * times where the pointwise band S -+ z se first reaches 0.5. At tied times events
 * come before censorings. */
#ifndef LIB_KM_H
#define LIB_KM_H

#include <stddef.h>

typedef struct km_curve {
	size_t m;        /* distinct observed times (events or censorings) */
	double *t;       /* [m] ascending */
	long *n_risk;    /* [m] at risk just before t */
	long *d, *c;     /* [m] events, censorings at t */
	double *s, *se;  /* [m] S(t) just after t and its Greenwood standard error */
	long n, events;
} km_curve;

/* time[i] >= 0 with event[i] = 1 (observed) or 0 (right-censored). Returns 0, or -1
 * on a bad argument or out of memory. */
int km_fit(const double *time, const int *event, size_t n, km_curve *k);
void km_free(km_curve *k);
/* S just after t (1 before the first event). */
double km_at(const km_curve *k, double t);
/* Median and its interval at normal quantile z (1.96 for 95 %); NaN when S does not
 * reach 0.5 (median) or the band does not (hi: "beyond the observation"). */
double km_median(const km_curve *k, double z, double *lo, double *hi);

#endif
