/* guard.h - what a scene or a particle file may ask of the preparation: limits on the
 * sizes computed from user numbers, and SIGINT/SIGTERM in the loops that run before
 * the run's stop flag is looked at (placement, reading a particle file). */
#ifndef SB_GUARD_H
#define SB_GUARD_H

#include <signal.h>

/* Sizes computed from user numbers are checked against these before they are cast to
 * int or allocated. Columns: the largest n_grains, since a lattice row wider than that
 * can never be filled. Walls: 10^6, ten times what a 10^5-grain bed needs; beyond it a
 * box's walls cost gigabytes and minutes before the first step (5 10^6 wall disks took
 * 2.6 GB and did not finish in 2 minutes). */
#define GUARD_MAX_COLUMNS 10000000 /* sites in a row of the placement lattice */
#define GUARD_MAX_WALLS 1000000    /* wall disks of a generated box */

/* A particle file spans at most this many mean grain diameters in x or y: the grids
 * sized by the grain diameter (free-surface columns, displacement field, the load
 * checks here) stay far inside int. A generated box spans at most about 2.2 10^7
 * (GUARD_MAX_COLUMNS lattice pitches of 2.2 r_max, and its walls twice the bed height),
 * so its own particle files always read back. */
#define GUARD_MAX_SPAN 1e8

/* The loops of the preparation cannot see the run's stop flag (sim.h), which main's
 * signal handler sets. They hold SIGINT and SIGTERM pending instead and poll for them;
 * releasing lets a pending one reach the handler, so that the run's flag is set as if
 * it had arrived a moment later. A signal whose action is to ignore it does not count. */
typedef struct guard_sig {
	sigset_t old;
} guard_sig;

void guard_hold(guard_sig *g);
/* 1 if SIGINT or SIGTERM arrived since guard_hold (cheap enough for every 10^4th pass
 * of a loop, not for every one). */
int guard_stopped(void);
void guard_release(const guard_sig *g);

#endif
