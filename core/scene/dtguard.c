/* dtguard.c - the time step's stability limits (measured by `make stress`) and the
 * scene's dt_guard: arithmetic on the scene, so the parameter checks need no integrator. */
#include "dtguard.h"

#include <math.h>
#include <stdio.h>

#include "paircoef.h"
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

/* m xi'' = -sqrt(xi reff) (K xi + c xi'), the Hertz contact's overlap */
static double hz_acc(double xi, double v, double K, double reff, double c, double m)
{
	return xi > 0 ? -sqrt(xi * reff) * (K * xi + c * v) / m : 0;
}

void dtguard_hertz(double K, double reff, double c, double m, double v, double *e, double *tc)
{
	/* the undamped contact's duration, 2 I dmax / v (I = int_0^1 dx / sqrt(1 - x^5/2)
	 * = 1.47164), sets the step: 20000 steps of RK4 per contact */
	const double dmax = pow(5 * m * v * v / (4 * K * sqrt(reff)), 0.4), h = 2 * 1.47164 * dmax / v / 20000;
	double xi = 0, u = v, t = 0;
	for (long k = 0; k < 400000; k++) {
		const double a1 = hz_acc(xi, u, K, reff, c, m), x2 = xi + 0.5 * h * u, u2 = u + 0.5 * h * a1;
		const double a2 = hz_acc(x2, u2, K, reff, c, m), x3 = xi + 0.5 * h * u2, u3 = u + 0.5 * h * a2;
		const double a3 = hz_acc(x3, u3, K, reff, c, m), x4 = xi + h * u3, u4 = u + h * a3;
		const double a4 = hz_acc(x4, u4, K, reff, c, m);
		const double xn = xi + h / 6 * (u + 2 * u2 + 2 * u3 + u4), un = u + h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
		if (xn <= 0) { /* the contact ends in this step: where xi crosses 0, linearly */
			*tc = t + h * xi / (xi - xn);
			*e = -un / v;
			return;
		}
		xi = xn;
		u = un;
		t += h;
	}
	*tc = INFINITY; /* overdamped: it never parts */
	*e = 0;
}

/* gear5 0.15 t_c, gear4 0.2 t_c, verlet 0.4 t_c, at most the absolute bound */
static double limit_of(int kind, double tc)
{
	/* k and the absolute bound from the bisection of `make stress` (Y = 3e5 .. 3e8,
	 * a shaken 240-grain bed), rounded down. At soft contacts the Gear schemes do not
	 * gain beyond 4e-4 s. */
	static const double k[3] = {0.15, 0.2, 0.4}, cap[3] = {4e-4, 4e-4, 1.2e-3};
	const double lim = k[kind] * tc;
	return lim < cap[kind] ? lim : cap[kind];
}

double dtguard_limit(int kind, double Y, double gamma_n, double m_min, double *tc)
{
	const double meff = 0.5 * m_min, w0sq = Y / meff, b = 0.5 * gamma_n;
	const double w = w0sq > b * b ? sqrt(w0sq - b * b) : sqrt(w0sq);
	*tc = SB_PI / w;
	return limit_of(kind, *tc);
}

double dtguard_kt(const sb_scene *sc)
{
	return paircoef_of(sc, -1).kt;
}

/* The limit for one pair class's coefficients c (paircoef.h), the lightest pair m_min / 2;
 * *tc gets its contact time. */
static double class_limit(const sb_scene *sc, const sb_paircoef *c, double m_min, double *tc)
{
	double lim, eh;
	if (sc->normal == NORMAL_HERTZ) {
		/* the lightest pair of the smallest grains at DTGUARD_HERTZ_V: Hertz's contact
		 * shortens as the impact speeds up (t_c ~ v^-1/5) */
		double rlo, rhi, rmean;
		params_grain_radii(sc, &rlo, &rhi, &rmean);
		dtguard_hertz(c->Y, 0.5 * rlo, c->gn * 0.5 * m_min, 0.5 * m_min, DTGUARD_HERTZ_V, &eh, tc);
		lim = limit_of(sc->integrator, *tc);
	} else {
		const double g = sc->restitution > 0 ? 2 * dtguard_zeta(sc->restitution) * sqrt(c->Y / (0.5 * m_min)) : c->gn;
		lim = dtguard_limit(sc->integrator, c->Y, g, m_min, tc);
	}
	/* The shear spring's oscillation: a contact slides against the inertia m_t of
	 * 1/m_t = 1/m_i + 1/m_j + R_i^2/I_i + R_j^2/I_j = 3 / m_eff (disks, I = m R^2 / 2), so
	 * its frequency^2 is 3 k_t / m_eff against the normal Y / m_eff (hertz: the normal
	 * stiffness at an overlap is 1.5 K sqrt(xi R_eff), the shear's k_t sqrt(xi R_eff)).
	 * It is the faster one only for k_t above Y / 3 (hertz: K / 2); the default 2/7
	 * never is. Then the contact time shrinks by the ratio of the frequencies. */
	if (sc->tangential == TANGENTIAL_SPRING) {
		const double kn = sc->normal == NORMAL_HERTZ ? 1.5 * c->Y : c->Y, k3 = 3 * c->kt;
		if (k3 > kn) {
			*tc *= sqrt(kn / k3);
			lim = limit_of(sc->integrator, *tc);
		}
	}
	return lim;
}

int dtguard_check(const sb_scene *sc, double m_min, char *warn, size_t len, sb_err *e)
{
	char name[32]; /* the integrator's name, from the parameter table */
	params_format(sc, params_find("integrator"), name, sizeof name);
	warn[0] = 0;
	if (sc->dt_guard == 2 || !(m_min > 0))
		return 0;
	/* every pair class at the lightest mass (a bound: the stiffest class need not hold
	 * the lightest disk); the paper's one material has one class */
	double tc = 0, lim = INFINITY;
	for (int cls = -1; cls < SB_NPAIRC; cls++) {
		const sb_paircoef c = paircoef_of(sc, cls);
		double t;
		const double l = class_limit(sc, &c, m_min, &t);
		if (l < lim) {
			lim = l;
			tc = t;
		}
	}
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
