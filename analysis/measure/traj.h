/* traj.h - the intruder's recorded trajectory in the box frame, and the second
 * waiting-time definition read off it (docs/model.md, "Waiting time").
 *
 * /particles/intruder/position is in the lab frame; the box floor is at
 * y_box(t) = A sin(phi(t)) (core/model/drive.c, ramps included), taken off every sample, so
 * that heights are above the box floor like the settled height y_0
 * (`intruder_settled_y`) and the settled surface h_s (`surface_height`).
 *
 * Fraction rise: the first time the centre has covered the fraction q of the way from
 * y_0 to h_s, y_box(t) >= y_0 + q (h_s - y_0), linearly interpolated between the two
 * samples around the crossing. The engine's rule (docs/model.md, "Waiting time") is
 * tripped by a slow creep of a small intruder (its diameter is short); half the way to
 * the surface is not. A trajectory that never gets there is censored at its last
 * sample: the end of the run, its failure, or its stop (`stop = risen` ends a run
 * stop_after seconds after the engine's rise, which may come before the fraction). */
#ifndef AN_TRAJ_H
#define AN_TRAJ_H

#include <stddef.h>

#include "err.h"
#include "h5read.h"

typedef struct traj {
	size_t n;
	double *t;       /* [n] s */
	double *y;       /* [n] lab frame, cm */
	double *ybox;    /* [n] above the box floor, cm */
	double y0;       /* intruder_settled_y (box frame), NaN when missing */
	double surface;  /* surface_height, NaN when missing */
	double radius;   /* intruder_radius (cm), NaN when missing */
	double x0;       /* x of the first sample (the drive moves the box in y only), NaN without samples */
	char stopped_by[16]; /* the stop rule that ended the run ("none", "risen", ...; "" unknown) */
} traj;

/* Reads path's trajectory and its box frame from the file's own /parameters (ramp,
 * amplitude, frequency, ramp_from, ramp_to, ramp_hold, duration). Returns 0, 1 when
 * the file has no trajectory (traj_rate = 0, or no sample: tr->n = 0), or an error
 * code with e set: SB_ENAN when a time or position is not a finite number, else an
 * unreadable file. */
int traj_read(const char *path, traj *tr, sb_err *e);
void traj_free(traj *tr);

/* The engine's rise of a run, the root attributes risen and waiting_time of the open
 * file f: 0 with both set; SB_EIO when either is missing or is not one number;
 * SB_ENAN when waiting_time is no finite time >= 0 or risen is not 0 or 1 (a NaN
 * would count as risen, or sort as a time). e names path and the value. */
int traj_rise(hid_t f, const char *path, double *risen, double *wait, sb_err *e);

/* The first time y[i] reaches level (y[0] >= level: t[0]), interpolated linearly
 * between the samples around the crossing; NaN when it never does. */
double traj_crossing(const double *t, const double *y, size_t n, double level);

/* The fraction rise of tr (q in (0, 1]): 1 with *time the crossing, or 0 with *time
 * the last sample's time (censored); -1 when y0, surface or the samples are missing. */
int traj_fraction(const traj *tr, double q, double *time);

#endif
