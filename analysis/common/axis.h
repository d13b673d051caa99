/* axis.h - the x of a figure against the drive: the frequency f, Gamma or the peak
 * velocity v (core/model/drive.h's axes, enum sb_axis, with their names and definitions);
 * a run's value on it, the frequency at a value for gnuplot (to draw a curve fitted in
 * f), and its label (label.h). */
#ifndef AN_AXIS_H
#define AN_AXIS_H

#include <stdio.h>

#include "adb.h"

#include "drive.h"

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
