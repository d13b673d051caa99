/* calib.h - this machine's cost of the engine: CPU seconds per grain-step of shaking
 * and per grain of a packing's settling, measured on the paper bed once per engine
 * build, CPU and integrator and kept in the runs directory (docs/campaigns.md, "Cost
 * before the start"). */
#ifndef ST_CALIB_H
#define ST_CALIB_H

#include <stddef.h>

#include "err.h"

typedef struct calib {
	double step;      /* CPU s per grain per shaking step */
	double settle;    /* CPU s per grain of one settling (and the engine's start) */
	char source[5000]; /* "measured now in 4.2 s (RUNS/.calibration/TAG.txt)", "cached from DATE (...)" */
} calib;

/* The rates of integrator (enum sb_integrator) for the engine at path shake: read from
 * RUNS/.calibration/TAG.txt when that file exists (TAG: a hash of `shake --version`,
 * which names the build and the CPU, and the integrator), else measured now with two
 * runs of the paper bed without intruder (0.5 s of shaking and 40000 steps more, the
 * preset of that integrator; the CPU difference per step, the rest per grain the settling) and
 * written there. Nothing outside RUNS/.calibration is touched. */
int calib_get(const char *runs, const char *shake, int integrator, calib *k, sb_err *e);
/* The same from the cache only: 0 with the rates when RUNS/.calibration has them, 1
 * (k->step = 0, k->source saying so) when it has not; nothing is run or written. */
int calib_cached(const char *runs, const char *shake, int integrator, calib *k, sb_err *e);

/* The rates from two runs of n grains: cpu_a CPU seconds for steps_a shaking steps,
 * cpu_b for steps_b (steps_b > steps_a). Negative differences (a noisy clock) are
 * clamped to a tiny positive rate. */
void calib_fit(double cpu_a, double steps_a, double cpu_b, double steps_b, long n, calib *k);

#endif
