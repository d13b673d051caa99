/* axes.h - the drive's dimensionless numbers, Gamma = A (2 pi f)^2 / g and the peak
 * velocity v = A 2 pi f, and the frequency or amplitude that gives one of them: the
 * axes a campaign may sweep or search in instead of the frequency (docs/campaigns.md,
 * "Axes in Gamma and v"); and where the model is known to fail in them
 * (docs/model.md, "Where the model fails"). */
#ifndef ST_AXES_H
#define ST_AXES_H

enum ax_kind { AX_FREQUENCY, AX_GAMMA, AX_VELOCITY, AX_NKINDS };

/* The drive's peak acceleration in units of g. */
double axes_gamma(double amplitude, double frequency, double gravity);
/* The drive's peak velocity, cm/s. */
double axes_velocity(double amplitude, double frequency);
/* The value on axis kind of a drive (amplitude cm, frequency Hz, gravity cm/s^2). */
double axes_value(int kind, double amplitude, double frequency, double gravity);

/* The frequency (Hz) at which a drive of the given amplitude reaches x on axis kind,
 * and the amplitude (cm) at which one of the given frequency does. Both are printed
 * with 12 significant digits and read back, as every value of a campaign is: the same
 * x gives the same run, wherever it is computed. NaN for x <= 0. */
double axes_frequency(int kind, double x, double amplitude, double gravity);
double axes_amplitude(int kind, double x, double frequency, double gravity);

/* The drive with both Gamma and v given: omega = Gamma g / v, A = v / omega (the
 * frequency printed with 12 digits first, then the amplitude from it). */
void axes_drive(double gamma, double velocity, double gravity, double *amplitude, double *frequency);

/* "frequency", "gamma", "velocity"; its unit ("Hz", "", "cm/s"); -1 for another name. */
const char *axes_name(int kind);
const char *axes_unit(int kind);
int axes_kind(const char *name);

/* Where the model is known to fail at a drive: NULL, or what happens there (a clause),
 * with the Gamma from which it does in *limit. The limits are data, in one table of
 * axes.c, with their measurement in docs/model.md, "Where the model fails". */
const char *axes_model_fails(double gamma, double *limit);

#endif
