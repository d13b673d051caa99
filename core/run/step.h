/* step.h - one time step of a run (step.c). */
#ifndef SB_STEP_H
#define SB_STEP_H

#include "sim.h"

/* One step of length dt to step number step (the new time t = step dt), as a recipe:
 * predict, check, watch the rise, neighbours, forces, correct (core/README.md, "The
 * step recipe"). gy is the uniform acceleration in y at t (gravity and, in the box
 * frame, minus the box's), drag the settling's viscous drag (0 while shaking). fuse:
 * nobody reads the corrected state, so the next step's predictor runs inside this
 * step's corrector (s->predicted). track: the ring's per-disk |F| sums, or NULL. A
 * failure (non-finite number, a disk out of the box, an overlap past max_overlap) is
 * the run's status (sim_fail; its message names s->stage) and is returned. */
int step_once(sb_sim *s, long step, double gy, double drag, int fuse, double *track, sb_err *e);

/* Arm the kernel's overlap flag for the run's overlap record (step.c). */
void step_arm_overlap(sb_sim *s);

/* Low-level stepping for tests and tools: step_start builds the neighbour list and
 * sets the integrator's acceleration from the current forces (call it after placing
 * disks and setting velocities q[c][1] = v dt); step_advance advances one reference step
 * with the uniform extra acceleration gy in y, no drive, and counts s->step. */
int step_start(sb_sim *s, double gy, sb_err *e);
int step_advance(sb_sim *s, double gy, sb_err *e);

#endif
