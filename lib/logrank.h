/* logrank.h - the log-rank test of equal survival in k groups with right-censoring
 * (Mantel 1966; Peto & Peto 1972): at every distinct event time, the events of each
 * group against those expected from the pooled risk set; the statistic
 * (O - E)' V^-1 (O - E) over k - 1 groups, chi-square with k - 1 degrees of freedom
 * under the null. */
#ifndef LIB_LOGRANK_H
#define LIB_LOGRANK_H

#include <stddef.h>

typedef struct logrank {
	int k;           /* groups with at least one observation */
	double chi2, p;  /* statistic and its p-value (NaN when k < 2 or no events) */
	int df;
} logrank;

/* time[i] >= 0, event[i] 1 (observed) or 0 (censored), group[i] in [0, ngroups).
 * Returns 0, or -1 on a bad argument or out of memory. */
int logrank_test(const double *time, const int *event, const int *group, size_t n, int ngroups, logrank *out);

#endif
