/* paircoef.h - the contact coefficients per pair of kinds (docs/model.md, "Materials
 * per pair of kinds"): grain, intruder and wall disks may be of different materials,
 * as LAMMPS's pair_coeff I J gives each pair of atom types its own. The grain-grain
 * class is the scene's own keys (mu, gamma_n, gamma_s, stiffness or hertz_stiffness,
 * shear_stiffness); the other classes have a row of their own per coefficient
 * (mu_grain_wall, ...), whose `same` is the grain-grain value. Two wall disks never
 * meet (walls do not move). Which class a pair of disks is in: forces.h,
 * forces_pairclass. */
#ifndef SB_PAIRCOEF_H
#define SB_PAIRCOEF_H

#include "params.h"

/* The classes with keys of their own, in the params table's order (SB_NPAIRC). */
enum sb_pairclass { PC_GRAIN_INTRUDER, PC_INTRUDER_INTRUDER, PC_GRAIN_WALL, PC_INTRUDER_WALL };

/* A class's name as in its keys ("grain_wall"); "grain_grain" for -1. */
const char *paircoef_name(int cls);

/* A class's coefficients, `same` resolved: Y the normal stiffness in the normal law's
 * unit, gn and gs the damping rates, mu, kt the shear spring's stiffness (shear_stiffness,
 * or 2/7 of Y when it is 0). cls -1: the grain-grain class. */
typedef struct sb_paircoef {
	double Y, gn, gs, mu, kt;
} sb_paircoef;
sb_paircoef paircoef_of(const sb_scene *sc, int cls);

/* A class's (0 .. SB_NPAIRC - 1) coefficient coef as given; -1 for `same`. */
enum sb_paircoef_key { PCK_MU, PCK_GAMMA_N, PCK_GAMMA_S, PCK_STIFFNESS };
double paircoef_given(const sb_scene *sc, int cls, int coef);

/* 1 when every class resolves to the grain-grain coefficients (the paper's one material:
 * the vector kernel's laws run), else 0. */
int paircoef_uniform(const sb_scene *sc);

#endif
