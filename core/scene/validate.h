/* validate.h - a scene's cross-key checks (validate.c). */
#ifndef SB_VALIDATE_H
#define SB_VALIDATE_H

#include "err.h"
#include "params.h"

/* Checks that involve more than one key (r_min <= r_max, ...); the error names the
 * file and line (or command-line argument) where the key at fault was set. */
int params_validate(const sb_scene *s, sb_err *e);

#endif
