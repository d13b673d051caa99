/* checkpoint.h - the full state of a shaking run, enough to continue it bit-identically
 * (checkpoint.c). */
#ifndef SB_CHECKPOINT_H
#define SB_CHECKPOINT_H

#include "sim.h"

int ckpt_write(sb_sim *s, sb_err *e);
/* Returns 1 if a checkpoint was loaded, 0 if none exists (or one of another engine
 * version that restart = auto starts over from), an error code otherwise. */
int ckpt_load(sb_sim *s, sb_err *e);

#endif
