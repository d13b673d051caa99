/* prepare.h - preparing a run (prepare.c). */
#ifndef SB_PREPARE_H
#define SB_PREPARE_H

#include "sim.h"

/* Place or read the disks, settle, write particle files if asked, enter the box
 * frame and start the integrator and the observables at t = 0. */
int prepare_run(sb_sim *s, sb_err *e);

#endif
