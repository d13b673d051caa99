/* dtguard.h - stability limits of the integrators and the dt_guard check (dtguard.c). */
#ifndef SB_DTGUARD_H
#define SB_DTGUARD_H

#include <stddef.h>

#include "err.h"
#include "params.h"

/* The stability guard (measured by `make stress`): the largest dt each
 * integrator survives is k t_c (for stiff contacts) but never more than an absolute
 * bound, with t_c = pi / sqrt(Y/m_eff - (gamma_N/2)^2) of the lightest pair (m_eff =
 * m_min / 2, gamma_n its damping rate: dtguard_gamma). Returns the limit; *tc gets t_c. */
double dtguard_limit(int kind, double Y, double gamma_n, double m_min, double *tc);

/* The linear spring-dashpot contact (docs/model.md, "Restitution"): the damping ratio
 * zeta = -ln e / sqrt(pi^2 + ln^2 e) that gives it the normal restitution e (0 < e <= 1);
 * a pair's normal damping rate gamma_N under the scene (2 zeta sqrt(Y / m_eff) when
 * restitution is set, else gamma_n); and the restitution and contact time of a pair of
 * effective mass meff at gamma_N (the unclipped contact ends at xi = 0 after pi / w,
 * w = sqrt(Y / m_eff - gamma_N^2 / 4), e = exp(-gamma_N t_c / 2); e = 0 and t_c = inf
 * when overdamped). */
double dtguard_zeta(double e);
double dtguard_gamma(const sb_scene *sc, double meff);
void dtguard_pair(double Y, double gamma_n, double meff, double *e, double *tc);

/* The Hertz contact (normal = hertz): m xi'' = -sqrt(xi reff) (K xi + c xi') from
 * xi = 0 at speed v, integrated (RK4, 20000 steps a contact): its restitution and
 * contact time (e = 0, t_c = inf when it never parts). m is the mass that moves (m_eff
 * of two mobile disks, the grain's on a wall), c = gamma_N m_eff. The dt guard takes
 * the lightest pair of r_min grains at DTGUARD_HERTZ_V (cm/s), a fast impact: the
 * contact is shorter the faster the impact. */
#define DTGUARD_HERTZ_V 100.0
void dtguard_hertz(double K, double reff, double c, double m, double v, double *e, double *tc);

/* tangential = spring: the shear stiffness k_t, shear_stiffness or by default 2/7 of
 * the normal stiffness (stiffness, or hertz_stiffness with normal = hertz). */
double dtguard_kt(const sb_scene *sc);

/* Apply the scene's dt_guard for the lightest mobile mass m_min: an error (SB_EUSAGE)
 * beyond the limit when dt_guard = refuse; a warning text in warn (empty if none)
 * beyond half the limit, or beyond it with dt_guard = warn. With tangential = spring
 * the contact's tangential oscillation counts too (docs/model.md, "Tangential law"). */
int dtguard_check(const sb_scene *sc, double m_min, char *warn, size_t len, sb_err *e);

#endif
