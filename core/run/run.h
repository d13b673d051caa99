/* run.h - the shaking loop (run.c). */
#ifndef SB_RUN_H
#define SB_RUN_H

#include "sim.h"

/* Shake until duration (or a stop); returns SB_OK or the code that stopped the run
 * (also in s->status). */
int run_shaking(sb_sim *s, sb_err *e);

#endif
