/* calib.h - this machine's cost of the engine: CPU seconds per grain-step of shaking
 * and per grain of a packing's settling, measured on the paper bed once per engine
 * build, CPU and integrator and kept in the runs directory (docs/campaigns.md, "Cost
 * before the start"). */
#ifndef ST_CALIB_H
#define ST_CALIB_H

#include <stddef.h>

#include "err.h"
#include "sql.h"

typedef struct calib {
	double step;      /* CPU s per grain per shaking step */
	double settle;    /* CPU s per grain of one settling (and the engine's start) */
	/* where the rates came from: "verlet, calibration measured now in 4.2 s on this
	 * machine, at load ...", "... calibration measured DATE (2.5 h ago) on this machine,
	 * at load L on C cores (PATH)", "... rate from N finished runs of this campaign" */
	char source[5000];
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

/* The shaking rate learnt from the campaign's own finished runs in database d (a
 * calibration taken on a busy machine, or on a bed unlike the campaign's, is replaced
 * by what its runs really cost): over its done runs of this integrator whose every
 * attempt recorded its CPU (docs/database.md, table attempt), their CPU less their own
 * settling at k's settle rate, over their grains x steps (status_time / dt). k->step
 * and k->source replaced when there is at least one such run; k untouched otherwise
 * (a database of an earlier version included). 0, or the error. */
int calib_learn(sql_db *d, const char *campaign, int integrator, calib *k, sb_err *e);

/* How old a calibration's date ("2026-11-23T15:32:47Z") is, as "2.5 h ago". */
void calib_age(const char *date, char *out, size_t len);

/* The rates from two runs of n grains: cpu_a CPU seconds for steps_a shaking steps,
 * cpu_b for steps_b (steps_b > steps_a). Negative differences (a noisy clock) are
 * clamped to a tiny positive rate. */
void calib_fit(double cpu_a, double steps_a, double cpu_b, double steps_b, long n, calib *k);

#endif
