/* dtguard.h - stability limits of the integrators and the dt_guard check (dtguard.c). */
#ifndef SB_DTGUARD_H
#define SB_DTGUARD_H

#include <stddef.h>

#include "err.h"
#include "params.h"

/* The stability guard (measured by `make stress`): the largest dt each
 * integrator survives is k t_c (for stiff contacts) but never more than an absolute
 * bound, with t_c = pi / sqrt(Y/m_eff - (gamma_N/2)^2) of the lightest pair (m_eff =
 * m_min / 2). Returns the limit; *tc gets t_c. */
double dtguard_limit(int kind, double Y, double gamma_n, double m_min, double *tc);

/* Apply the scene's dt_guard for the lightest mobile mass m_min: an error (SB_EUSAGE)
 * beyond the limit when dt_guard = refuse; a warning text in warn (empty if none)
 * beyond half the limit, or beyond it with dt_guard = warn. */
int dtguard_check(const sb_scene *sc, double m_min, char *warn, size_t len, sb_err *e);

#endif
