/* pairdiff.h - two codes' profiles over the same ensemble of beds, compared bed by bed
 * (the LAMMPS validation, tests/bench/validate_lammps.sh). Bed b gives profile a_b[L]
 * from one code and b_b[L] from the other; per line l:
 *   each code's mean over the n beds with its Student-t interval (level),
 *   the paired difference d_b = a_b - b_b: its mean, interval and t = mean / (sd / sqrt n),
 *   agree = the difference's interval holds 0.
 * Over the lines together (they are correlated: a bed's profile is smooth in height),
 * two statistics, max |t| and the mean of t^2 (chi2/L), with p-values from the
 * sign-flip permutation test: under "both codes give the same distribution" each
 * bed's d_b is as likely to have either sign, so the statistic of all 2^n sign
 * patterns (exact for n <= 16, else 65536 random ones) is its null distribution, lines'
 * correlations included. */
#ifndef AN_PAIRDIFF_H
#define AN_PAIRDIFF_H

#include <stddef.h>

#include "err.h"

typedef struct pd_result {
	size_t n, L;
	double level;
	double *ma, *ha;   /* [L] code A: mean and interval half-width */
	double *mb, *hb;   /* [L] code B */
	double *md, *hd;   /* [L] paired difference A - B */
	double *t;         /* [L] the difference's t (0 when every d_b is 0) */
	int *agree;        /* [L] */
	int ndis;          /* lines where the interval misses 0 */
	double maxt;       /* max |t| over the lines with any crossing */
	double chi2;       /* mean t^2 over those lines */
	size_t lines_used; /* lines where some d_b differs from 0 */
	double p_maxt, p_chi2;
	long perms;        /* sign patterns evaluated */
	int exact;         /* all 2^n of them */
} pd_result;

/* a, b: [n x L] row-major (bed-major). n >= 2. */
int pd_compare(size_t n, size_t L, const double *a, const double *b, double level, pd_result *r, sb_err *e);
void pd_free(pd_result *r);

#endif
