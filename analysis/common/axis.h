/* axis.h - the x of a figure against the drive: the frequency f, Gamma = A (2 pi f)^2 / g
 * (drive_gamma) or the peak velocity v = A 2 pi f (drive_velocity), core/drive.h's
 * definitions; a run's value on it, the frequency at a value for gnuplot (to draw a
 * curve fitted in f), and its label (label.h). */
#ifndef AN_AXIS_H
#define AN_AXIS_H

#include <stdio.h>

#include "adb.h"

enum an_axis { AXIS_FREQUENCY, AXIS_GAMMA, AXIS_VELOCITY, AXIS_N };

/* "frequency", "gamma", "velocity" (the campaign files' words), -1 for another */
int axis_parse(const char *name);
const char *axis_name(int kind);

/* The value on the axis of a drive of amplitude A (cm) at frequency f (Hz) under
 * gravity g (cm/s^2). */
double axis_of(int kind, double A, double f, double g);

/* A run's gravity (cm/s^2): its param row, else the engine's default (a database
 * written before gravity was recorded); its value on the axis (NaN when its amplitude
 * or frequency is missing). */
double axis_gravity(const an_run *r);
double axis_run(int kind, const an_run *r);

/* gnuplot's expression of the frequency at axis value x (the variable x), for a
 * drive of A and g: x, sqrt(x/k) or x/k. */
void axis_gp_freq(FILE *f, int kind, double A, double g);

/* The axis label: "frequency f (Hz)", "peak acceleration Γ", "peak velocity v (cm/s)". */
void axis_label(char *buf, size_t n, int kind);

#endif
