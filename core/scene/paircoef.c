/* paircoef.c - the contact coefficients per pair of kinds (paircoef.h). */
#include "paircoef.h"

#include <stddef.h>


static const char *const NAMES[SB_NPAIRC] = {"grain_intruder", "intruder_intruder", "grain_wall", "intruder_wall"};

const char *paircoef_name(int cls)
{
	return cls >= 0 && cls < SB_NPAIRC ? NAMES[cls] : "grain_grain";
}

/* each class's fields (the params table's rows of the same names): mu, gamma_n, gamma_s,
 * stiffness */
#define CLASS_FIELDS(c) {offsetof(sb_scene, mu_##c), offsetof(sb_scene, gamma_n_##c), \
			 offsetof(sb_scene, gamma_s_##c), offsetof(sb_scene, stiffness_##c)}
static const size_t FIELDS[SB_NPAIRC][4] = {CLASS_FIELDS(grain_intruder), CLASS_FIELDS(intruder_intruder),
					   CLASS_FIELDS(grain_wall), CLASS_FIELDS(intruder_wall)};

/* a class's value of coefficient k: its own, or (-1, `same`) the grain-grain one */
static double own(const sb_scene *sc, int k, int cls, double gg)
{
	const double v = cls >= 0 ? *(const double *)((const char *)sc + FIELDS[cls][k]) : -1;
	return v != -1 ? v : gg;
}

double paircoef_given(const sb_scene *sc, int cls, int coef)
{
	return *(const double *)((const char *)sc + FIELDS[cls][coef]);
}

sb_paircoef paircoef_of(const sb_scene *sc, int cls)
{
	const double Y0 = sc->normal == NORMAL_HERTZ ? sc->hertz_stiffness : sc->stiffness, Y = own(sc, PCK_STIFFNESS, cls, Y0);
	/* the shear spring's default, 2/7 of the normal stiffness (LAMMPS's), follows the
	 * class's own */
	const double kt = sc->shear_stiffness > 0 ? sc->shear_stiffness : 2.0 / 7.0 * Y;
	return (sb_paircoef){Y, own(sc, PCK_GAMMA_N, cls, sc->gamma_n), own(sc, PCK_GAMMA_S, cls, sc->gamma_s), own(sc, PCK_MU, cls, sc->mu),
			     kt};
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
