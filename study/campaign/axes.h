/* axes.h - the drive a campaign asks for on an axis other than the frequency: the
 * frequency or amplitude that gives a Gamma or a peak velocity, as a campaign writes
 * its values (the axes themselves, their names and units: core/model/drive.h; docs/campaigns.md,
 * "Axes in Gamma and v"); and where the model is known to fail in them
 * (docs/model.md, "Where the model fails"). */
#ifndef ST_AXES_H
#define ST_AXES_H

#include "drive.h"

/* The frequency (Hz) at which a drive of the given amplitude reaches x on axis kind,
 * and the amplitude (cm) at which one of the given frequency does. Both are printed
 * with 12 significant digits and read back, as every value of a campaign is: the same
 * x gives the same run, wherever it is computed. NaN for x <= 0. */
double axes_frequency(int kind, double x, double amplitude, double gravity);
double axes_amplitude(int kind, double x, double frequency, double gravity);

/* The drive with both Gamma and v given, x[AXIS_GAMMA] and x[AXIS_VELOCITY]:
 * omega = Gamma g / v, A = v / omega (the frequency printed with 12 digits first, then
 * the amplitude from it). */
void axes_drive(const double x[AXIS_N], double gravity, double *amplitude, double *frequency);

/* Where the model is known to fail at a drive: NULL, or what happens there (a clause),
 * with the Gamma from which it does in *limit. The limits are data, in one table of
 * axes.c, with their measurement in docs/model.md, "Where the model fails". */
const char *axes_model_fails(double gamma, double *limit);

#endif
