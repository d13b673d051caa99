/* clock.h - the monotonic clock of the run's diagnostics: wall time of the loop, and
 * the per-phase profile (TIC/TOC around a phase of a step, when sim->profile is on). */
#ifndef SB_CLOCK_H
#define SB_CLOCK_H

#include <time.h>

static inline double sb_now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* TIC(sim, ph); ...; TOC(sim, ph); adds the wall time between them to sim->tphase[ph]
 * when sim->profile is on. The run is named, not assumed; TIC declares tic_PH in the
 * enclosing block (a phase is timed once per block) and TOC is one statement, safe
 * under an if without braces. */
#define TIC(sim, ph) const double tic_##ph = (sim)->profile ? sb_now() : 0
#define TOC(sim, ph)                                                      \
	do {                                                              \
		if ((sim)->profile)                                       \
			(sim)->tphase[ph] += sb_now() - tic_##ph;         \
	} while (0)

#endif
