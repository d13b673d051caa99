/* prep.h - preparing a run (prep.c). */
#ifndef SB_PREP_H
#define SB_PREP_H

#include "sim.h"

/* Place or read the disks, settle, write particle files if asked, enter the box
 * frame and start the integrator and the observables at t = 0. */
int sim_prepare(sb_sim *s, sb_err *e);

#endif
