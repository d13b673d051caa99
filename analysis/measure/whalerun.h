/* whalerun.h - one run's whale observables from its output file: the rise the engine
 * recorded (root attributes risen, waiting_time), the intruder's radius, the drive
 * frequency, and the box-frame trajectory (traj.h), analysed from waiting_time + skip
 * to the trajectory's end (the run's end, its failure or its stop) by whale.h and
 * whalespec.h. What became of the run is one of whale_status. */
#ifndef AN_WHALERUN_H
#define AN_WHALERUN_H

#include "err.h"
#include "whale.h"
#include "whalespec.h"

enum whale_status {
	WHALE_OK,        /* analysed: dives, period, depth, spectrum */
	WHALE_NOT_RISEN, /* the intruder never rose (risen = 0): nothing to oscillate */
	WHALE_NO_TRAJ,   /* rose, but the file has no trajectory (traj_rate = 0) */
	WHALE_SHORT,     /* rose, but the window after the skip holds fewer than
			  * WHALE_MIN_PERIODS drive periods (or 10 samples): no top level */
	WHALE_NSTATUS
};

/* A top level needs the intruder to have been watched at the top for a while: ten
 * drive periods (3.1 s at 3.2 Hz) is the least the running mean over one period
 * leaves a handful of independent values in. */
#define WHALE_MIN_PERIODS 10

typedef struct whale_obs {
	int status;        /* whale_status */
	int risen;         /* the engine's: 1 risen, 0 not (censored) */
	double wait;       /* waiting_time (s): the rise, or the time observed */
	double radius;     /* the intruder's radius (cm; intruder_radius, else radius_ratio
			    * times the mean grain radius from /parameters) */
	double drive_f;    /* /parameters/frequency (Hz; 0 when at rest) */
	double dive;       /* the D used (cm) */
	double t_end;      /* the trajectory's last sample (s); NaN without one */
	whale_run run;     /* the dives (WHALE_OK) */
	whale_spec spec;   /* the spectrum (WHALE_OK) */
} whale_obs;

typedef struct whale_cfg {
	double skip;       /* seconds after the rise before the window opens */
	double dive;       /* D in cm; NaN: dive_radii intruder radii */
	double dive_radii; /* D in intruder radii when dive is NaN (1) */
	double top_q;      /* the top level's quantile (0.9) */
} whale_cfg;

/* Reads path and fills ob. Returns 0 (ob->status says what became of the run), or an
 * error code with e set when the file cannot be read or lacks risen / waiting_time. */
int whale_read(const char *path, const whale_cfg *c, whale_obs *ob, sb_err *e);

/* The period-averaged height of path's trajectory from t_from on, one value per
 * step seconds (the first sample at or after each multiple of step after t_from): the figure's
 * trace. *t, *y malloc'd (free by the caller), *n of them. Returns 0 or an error code
 * with e set. */
int whale_trace(const char *path, double t_from, double step, double **t, double **y, size_t *n, sb_err *e);

/* "analysed", "not_risen", "no_trajectory", "too_short" */
const char *whale_status_name(int s);

#endif
