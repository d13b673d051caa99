/* place.h - building the initial scene: wall disks, loose placement of the grains
 * and the intruder (before settling), or a state read from a particle file. */
#ifndef SB_PLACE_H
#define SB_PLACE_H

#include "params.h"
#include "state.h"

/* Mass model (docs/model.md, "Units and the paper's values"): m = mass_factor * rho * R^2, I = m R^2 / 2,
 * rho the density of the disk's kind (place_density). */
double place_mass(const sb_scene *sc, double r, int kind);
/* The material density of a kind of disk: intruder_density for an intruder (0: density), density for
 * grains and walls; and the key it comes from, for errors. */
double place_density(const sb_scene *sc, int kind);
const char *place_density_key(const sb_scene *sc, int kind);

/* Place grains, the intruder and the walls for a scene (no particles file). */
int place_scene(const sb_scene *sc, sb_state *st, sb_err *e);

/* Push one disk of a kind with the scene's mass model (walls honour wall_mass). */
int place_push(const sb_scene *sc, sb_state *st, double x, double y, double r, int kind, sb_err *e);
/* The same with a mass of its own (a particle file's, particle_mass = file). */
int place_push_mass(const sb_scene *sc, sb_state *st, double x, double y, double r, int kind, double m, sb_err *e);

#endif
