/* paircoef.c - the contact coefficients per pair of kinds (paircoef.h). */
#include "paircoef.h"


static const char *const NAMES[SB_NPAIRC] = {"grain_intruder", "intruder_intruder", "grain_wall", "intruder_wall"};

const char *paircoef_name(int cls)
{
	return cls >= 0 && cls < SB_NPAIRC ? NAMES[cls] : "grain_grain";
}

/* a class's value of a coefficient: its own, or (-1, `same`) the grain-grain one */
static double own(const double *v, int cls, double gg)
{
	return cls >= 0 && v[cls] != -1 ? v[cls] : gg;
}

sb_paircoef paircoef_of(const sb_scene *sc, int cls)
{
	const double Y0 = sc->normal == NORMAL_HERTZ ? sc->hertz_stiffness : sc->stiffness, Y = own(sc->pc_stiffness, cls, Y0);
	/* the shear spring's default, 2/7 of the normal stiffness (LAMMPS's), follows the
	 * class's own */
	const double kt = sc->shear_stiffness > 0 ? sc->shear_stiffness : 2.0 / 7.0 * Y;
	return (sb_paircoef){Y, own(sc->pc_gamma_n, cls, sc->gamma_n), own(sc->pc_gamma_s, cls, sc->gamma_s),
			     own(sc->pc_mu, cls, sc->mu), kt};
}

int paircoef_uniform(const sb_scene *sc)
{
	const sb_paircoef g = paircoef_of(sc, -1);
	for (int c = 0; c < SB_NPAIRC; c++) {
		const sb_paircoef p = paircoef_of(sc, c);
		if (p.Y != g.Y || p.gn != g.gn || p.gs != g.gs || p.mu != g.mu || p.kt != g.kt)
			return 0;
	}
	return 1;
}
