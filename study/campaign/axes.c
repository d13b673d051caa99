/* axes.c - Gamma, v and the drive that gives them (see axes.h); the table of where the
 * model is known to fail. */
#include "axes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drive.h"
#include "units.h"

/* 2 pi f: the drive's angular frequency, as the engine's drive has it */
#define AX_TWO_PI SB_TWO_PI

/* 12 significant digits, as a campaign's ranges and the search's midpoints are
 * printed (adapt_mid): a derived value reads as written, and so hashes the same */
static double printed(double x)
{
	char buf[40];
	snprintf(buf, sizeof buf, "%.12g", x);
	return strtod(buf, NULL);
}

double axes_gamma(double amplitude, double frequency, double gravity)
{
	return drive_gamma(amplitude, frequency, gravity); /* Gamma's one definition */
}

double axes_velocity(double amplitude, double frequency)
{
	return drive_velocity(amplitude, frequency); /* v's one definition */
}

double axes_value(int kind, double amplitude, double frequency, double gravity)
{
	switch (kind) {
	case AX_GAMMA:
		return axes_gamma(amplitude, frequency, gravity);
	case AX_VELOCITY:
		return axes_velocity(amplitude, frequency);
	default:
		return frequency;
	}
}

double axes_frequency(int kind, double x, double amplitude, double gravity)
{
	if (!(x > 0) || !(amplitude > 0))
		return kind == AX_FREQUENCY ? x : NAN;
	switch (kind) {
	case AX_GAMMA:
		return printed(sqrt(x * gravity / amplitude) / AX_TWO_PI);
	case AX_VELOCITY:
		return printed(x / (AX_TWO_PI * amplitude));
	default:
		return x;
	}
}

double axes_amplitude(int kind, double x, double frequency, double gravity)
{
	if (!(x > 0) || !(frequency > 0))
		return NAN;
	double w = AX_TWO_PI * frequency;
	switch (kind) {
	case AX_GAMMA:
		return printed(x * gravity / (w * w));
	case AX_VELOCITY:
		return printed(x / w);
	default:
		return NAN;
	}
}

void axes_drive(double gamma, double velocity, double gravity, double *amplitude, double *frequency)
{
	*frequency = printed(gamma * gravity / velocity / AX_TWO_PI);
	*amplitude = axes_amplitude(AX_VELOCITY, velocity, *frequency, gravity);
}

static const char *const NAMES[AX_NKINDS] = {"frequency", "gamma", "velocity"};
static const char *const UNITS[AX_NKINDS] = {"Hz", "", "cm/s"};

const char *axes_name(int kind)
{
	return kind >= 0 && kind < AX_NKINDS ? NAMES[kind] : "?";
}

const char *axes_unit(int kind)
{
	return kind >= 0 && kind < AX_NKINDS ? UNITS[kind] : "";
}

int axes_kind(const char *name)
{
	for (int k = 0; k < AX_NKINDS; k++)
		if (!strcmp(NAMES[k], name))
			return k;
	return -1;
}

/* Where the model is known to fail, one row per limit; docs/model.md, "Where the model
 * fails", has the runs that measured each. */
static const struct {
	double gamma_min; /* from this Gamma up */
	const char *what;
} FAILS[] = {
	{1.6, "runs have ended with grains thrown over the side walls (left_box, exit 5)"},
};

const char *axes_model_fails(double gamma, double *limit)
{
	for (size_t i = 0; i < sizeof FAILS / sizeof *FAILS; i++)
		if (gamma >= FAILS[i].gamma_min) {
			*limit = FAILS[i].gamma_min;
			return FAILS[i].what;
		}
	return NULL;
}
