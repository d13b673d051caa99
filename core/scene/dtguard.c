/* dtguard.c - the time step's stability limits (measured by `make stress`) and the
 * scene's dt_guard: arithmetic on the scene, so the parameter checks need no integrator. */
#include "dtguard.h"

#include <math.h>
#include <stdio.h>

#include "units.h"

double dtguard_zeta(double e)
{
	const double l = log(e);
	return -l / sqrt(SB_PI * SB_PI + l * l);
}

double dtguard_gamma(const sb_scene *sc, double meff)
{
	return sc->restitution > 0 ? 2 * dtguard_zeta(sc->restitution) * sqrt(sc->stiffness / meff) : sc->gamma_n;
}

void dtguard_pair(double Y, double gamma_n, double meff, double *e, double *tc)
{
	const double b = 0.5 * gamma_n, w2 = Y / meff - b * b;
	if (!(w2 > 0)) {
		*e = 0;
		*tc = INFINITY;
		return;
	}
	*tc = SB_PI / sqrt(w2);
	*e = exp(-b * *tc);
}

double dtguard_limit(int kind, double Y, double gamma_n, double m_min, double *tc)
{
	/* k and the absolute bound from the bisection of `make stress` (Y = 3e5 .. 3e8,
	 * a shaken 240-grain bed), rounded down: gear5 0.15 t_c, gear4 0.2 t_c, verlet
	 * 0.4 t_c. At soft contacts the Gear schemes do not gain beyond 4e-4 s. */
	static const double k[3] = {0.15, 0.2, 0.4}, cap[3] = {4e-4, 4e-4, 1.2e-3};
	const double meff = 0.5 * m_min, w0sq = Y / meff, b = 0.5 * gamma_n;
	const double w = w0sq > b * b ? sqrt(w0sq - b * b) : sqrt(w0sq);
	*tc = SB_PI / w;
	const double lim = k[kind] * *tc;
	return lim < cap[kind] ? lim : cap[kind];
}

int dtguard_check(const sb_scene *sc, double m_min, char *warn, size_t len, sb_err *e)
{
	char name[32]; /* the integrator's name, from the parameter table */
	params_format(sc, params_find("integrator"), name, sizeof name);
	warn[0] = 0;
	if (sc->dt_guard == 2 || !(m_min > 0))
		return 0;
	double tc, lim = dtguard_limit(sc->integrator, sc->stiffness, dtguard_gamma(sc, 0.5 * m_min), m_min, &tc);
	if (sc->dt > lim && sc->dt_guard == 0)
		return sb_errf(e, SB_EUSAGE,
			       "%s: dt: %g s is beyond the stability limit %.3g s of %s at this stiffness "
			       "(contact time %.3g s; make stress measures the limits); a smaller dt, or "
			       "dt_guard = warn to run anyway", params_where(sc, "dt"), sc->dt, lim,
			       name, tc);
	if (sc->dt > 0.5 * lim)
		snprintf(warn, len, "dt = %g s is %s the stability limit %.3g s of %s at this stiffness "
				    "(contact time %.3g s)", sc->dt, sc->dt > lim ? "beyond" : "close to", lim,
			 name, tc);
	return 0;
}
