/* lowerrow.h - "starting the intruder one row lower" (the paper's claim that, close to
 * the onset, it can prevent the rise) between the groups of an analysis tool: which
 * group is the same start one row lower, and the two-sided Fisher exact test of the
 * fractions risen of the two. The meaning of "one row lower" in terms of the scene key
 * `depth` is defined in lowerrow.c and nowhere else. */
#ifndef AN_LOWERROW_H
#define AN_LOWERROW_H

#include "common/tool.h"

/* The group that is group j's start one row lower: alike in every grouping key but
 * `depth` (numbers compared as numbers, "1" = "1.0"; other text as text), its depth one
 * row lower than j's (lowerrow.c). keys[nk] are the grouping keys, gval[ng * nk] the
 * groups' values as text (group g's value of key k at gval[g * nk + k]; NULL or "":
 * none). Returns the group's index, or -1 when there is none, when `depth` is not a
 * grouping key or group j has no numeric depth. */
int lowerrow_partner_of(const char (*keys)[48], int nk, const char *const *gval, int ng, int j);

/* The same over a tool's groups (t->keys, t->nk, t->gval, t->ng). */
int lowerrow_partner(const an_tool *t, int j);

/* Two-sided Fisher exact test of k1 of n1 against k2 of n2 (the 2x2 table k1, n1 - k1;
 * k2, n2 - k2): given the margins, the probability of every table no more likely than
 * the observed one (relative tolerance 1e-7, as R's fisher.test). NaN when n1 or n2 is
 * 0 or a count is out of range. */
double lowerrow_fisher_p(long k1, long n1, long k2, long n2);

#endif
