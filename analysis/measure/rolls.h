/* rolls.h - how deep the convection rolls reach in one run's flux profile Phi(D)
 * (claim 2: "the intruder drags the rolls deeper"), and the intervals that compare two
 * sets of runs (docs/model.md, "Roll reach"; docs/analysis.md, "rolls").
 *
 * Roll reach. The profile is smoothed by a centred running mean over K lines (fewer
 * at the ends); its largest |Phi| is phi_max, on line m, of sign s. The roll region is
 * the lines around m where s Phi >= q |phi_max| (q = --fraction, default 0.5); going
 * down from m, the first line below q |phi_max| ends it, and the roll bottom D_b is
 * where s Phi crosses q |phi_max| between that line and the one above (linear
 * interpolation); when every line down to the lowest is in the region, D_b is the
 * lowest line's height (to_floor = 1). The reach is h_s - D_b: how far below the
 * settled surface h_s the rolls go. A profile with Phi = 0 on every line has none.
 *
 * Comparing. Runs with and without intruder start from different packings (the study
 * driver derives the engine seed from the replicate and the preparation keys, which
 * include radius_ratio), so the two sets are independent samples: the difference of
 * their means gets Welch's interval (Student t with Welch-Satterthwaite degrees of
 * freedom); a mean alone gets Student's. */
#ifndef AN_ROLLS_H
#define AN_ROLLS_H

#include <stddef.h>

typedef struct rolls_reach {
	double phi_max; /* largest |Phi| of the smoothed profile (particles per period) */
	int sign;       /* sign of Phi there: +1 rising in the centre, -1 at the walls */
	size_t lmax;    /* its line */
	double bottom;  /* D_b (cm above the floor); NaN without rolls */
	double reach;   /* h_s - D_b (cm below the settled surface); NaN without rolls */
	int to_floor;   /* the region reaches the lowest line */
} rolls_reach;

/* Centred running mean of v[0..L) over K lines (K <= 1: a copy) into out[L]. */
void rolls_smooth(const double *v, size_t L, size_t K, double *out);

/* The reach of profile phi[L] at line heights h[L] (ascending), surface h_s; q in
 * (0, 1]; K the smoothing window. Returns 0, or -1 when there are no rolls (no line
 * has Phi != 0, or a value is not finite): then bottom = reach = NaN. */
int rolls_depth(const double *h, const double *phi, size_t L, double surface, double q, size_t K, rolls_reach *r);

/* A mean with its Student-t interval at level: n >= 2 for an interval (else NaN). */
typedef struct rolls_mean {
	size_t n;
	double mean, sd, lo, hi;
} rolls_mean;

void rolls_mean_ci(const double *v, size_t n, double level, rolls_mean *m);

/* mean(a) - mean(b) with Welch's interval at level (both n >= 2, else NaN): se, the
 * degrees of freedom; lo = hi = d when both samples have no spread. */
typedef struct rolls_diff {
	double d, lo, hi, se, df;
} rolls_diff;

void rolls_welch(const double *a, size_t na, const double *b, size_t nb, double level, rolls_diff *r);

#endif
