/* clock.h - the monotonic clock of the run's diagnostics: wall time of the loop, and
 * the per-phase profile (TIC/TOC around a phase of a step, when s->profile is on). */
#ifndef SB_CLOCK_H
#define SB_CLOCK_H

#include <time.h>

static inline double sb_now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

#define TIC(ph) double t0_##ph = s->profile ? sb_now() : 0
#define TOC(ph) if (s->profile) s->tphase[ph] += sb_now() - t0_##ph

#endif
