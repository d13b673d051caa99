/* pclass.h - the pair classes a run records (docs/model.md, "Restitution"): for a
 * mean grain pair, a grain and the intruder, a grain on a wall disk and the lightest
 * pair, the effective mass, the normal damping rate, the restitution and the contact
 * time the contact law gives them - the numbers a referee asks for and the scene's keys
 * do not show (with gamma_n the restitution varies with the pair's masses; with
 * restitution, the damping does). */
#ifndef SB_PCLASS_H
#define SB_PCLASS_H

#include "forces.h"
#include "params.h"
#include "state.h"

enum { SB_NPCLASS = 4 };
/* normal = hertz: the impact speed (cm/s) of the recorded restitution and contact
 * time, which depend on it (the speed hertz_stiffness's default is set at) */
#define PCLASS_HERTZ_V 20.0

typedef struct sb_pclass {
	const char *name;     /* grain_grain, grain_intruder, grain_wall, lightest_pair */
	int present;          /* 0: the bed has no such pair (no intruder, no wall) */
	double m_eff;         /* g: the law's m_eff (a wall of infinite mass: the grain's) */
	double gamma_n;       /* 1/s: the normal damping rate, force gamma_N m_eff xidot */
	double Y, mu, gamma_s; /* the class's stiffness, friction and shear damping (paircoef.h) */
	double e, tc;         /* the normal restitution and the contact time (s) of an
			       * unclipped head-on contact (e = 0, tc = inf: overdamped);
			       * hertz: at PCLASS_HERTZ_V */
} sb_pclass;

/* From a prepared state: the grains' mean mass, the intruder's, a wall disk's (or
 * infinite, wall_mass = infinite), the lightest mobile disk's. */
void pclass_of_state(const sb_law *law, const sb_scene *sc, const sb_state *st, sb_pclass out[SB_NPCLASS]);
/* From the scene's keys alone (bin/shake --contacts): the masses of the mean grain
 * radius, the intruder's radius, the wall radius and r_min (or the intruder, when it
 * is lighter), each with its kind's density (place.h). */
void pclass_of_scene(const sb_law *law, const sb_scene *sc, sb_pclass out[SB_NPCLASS]);

#endif
