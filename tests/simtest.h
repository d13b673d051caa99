/* simtest.h - a simulation on the heap for the physics tests, which place their own
 * disks (place_push) and step it (step.h). */
#ifndef SB_SIMTEST_H
#define SB_SIMTEST_H

#include <stdlib.h>

#include "sim.h"

static inline sb_sim *new_sim(const sb_scene *sc)
{
	sb_sim *s = calloc(1, sizeof *s);
	sb_err e = {0};
	sim_init(s, sc, &e);
	return s;
}

static inline void del_sim(sb_sim *s)
{
	sim_free(s);
	free(s);
}

#endif
