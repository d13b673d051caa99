/* two_disks.h - the head-on collision tests' scene (collision.c, pairclass.c): two disks
 * touching, or a disk on a wall disk, placed into a sim's state and derived. */
#ifndef SB_TWO_DISKS_H
#define SB_TWO_DISKS_H

#include "place.h"
#include "sim.h"

/* Disk i (kind ki, radius ri) and j (kj, rj): two mobile disks at the origin and touching
 * on its right (the caller sets their velocities along x), or kj = KIND_WALL: i resting
 * on the wall disk j at the origin, with two far wall disks so that the box (the hull in
 * x of the walls, above their lowest centre) contains i. Returns sim_derive's code. */
static inline int two_disks(const sb_scene *sc, sb_sim *s, double ri, double rj, int ki, int kj, sb_err *e)
{
	const double rs = ri + rj;
	if (kj != KIND_WALL) {
		place_push(sc, &s->st, 0, 0, ri, ki, e);
		place_push(sc, &s->st, rs, 0, rj, kj, e);
	} else {
		place_push(sc, &s->st, 0, rs, ri, ki, e);
		place_push(sc, &s->st, 0, 0, rj, KIND_WALL, e);
		place_push(sc, &s->st, -60, 0, rj, KIND_WALL, e);
		place_push(sc, &s->st, 60, 0, rj, KIND_WALL, e);
	}
	return sim_derive(s, e);
}

#endif
