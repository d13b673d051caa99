/* resolve.h - the precision floor of an onset's interval: no interval claims more
 * precision than the data resolve (docs/analysis.md, "Intervals and the data's
 * resolution"). A threshold crossing interpolated between two sampled frequencies is
 * only known to lie between them, and a bisection's answer only to its bracket; an
 * interval narrower than that is widened to hold it. Two onsets agree when their
 * intervals overlap. */
#ifndef AN_RESOLVE_H
#define AN_RESOLVE_H

#include <stddef.h>

/* The sampled values around t among x[0..n) (any order, repeats allowed): *a the
 * largest below t, *b the smallest at or above t (a crossing interpolated in (a, b]);
 * a missing side is t itself. 0 when t and some x are finite, else 1 (a, b NaN). */
int resolve_neighbours(const double *x, size_t n, double t, double *a, double *b);

/* Widens [*lo, *hi] to hold [a, b]; an interval that holds it already is left as it
 * is, and so is one that does not exist (a NaN end: no bootstrap). Returns 1 when it
 * widened, else 0. */
int resolve_widen(double *lo, double *hi, double a, double b);

/* The rule for a threshold onset t on sampled frequencies x[0..n): its interval holds
 * at least the two sampled frequencies around it (resolve_neighbours, resolve_widen).
 * Returns 1 when it widened. */
int resolve_grid(double t, double *lo, double *hi, const double *x, size_t n);

/* Whether two onsets agree: both intervals exist (finite ends) and overlap. */
int resolve_overlap(double lo1, double hi1, double lo2, double hi2);

#endif
