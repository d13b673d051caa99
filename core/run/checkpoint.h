/* checkpoint.h - the full state of a shaking run, enough to continue it bit-identically
 * (checkpoint.c). */
#ifndef SB_CHECKPOINT_H
#define SB_CHECKPOINT_H

#include "sim.h"

int ckpt_write(sb_sim *s, sb_err *e);
/* Returns 1 if a checkpoint was loaded, 0 if none exists (or one that restart = auto
 * starts over from, said in s->warning: another engine version's, or one whose journal
 * is missing or short; the sim may then hold part of it and is set up afresh), an
 * error code otherwise. */
int ckpt_load(sb_sim *s, sb_err *e);

#endif
