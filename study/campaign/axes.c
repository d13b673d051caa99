/* axes.c - Gamma, v and the drive that gives them (see axes.h); the table of where the
 * model is known to fail. */
#include "axes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "drive.h"
#include "units.h"

/* 12 significant digits, as a campaign's ranges and the search's midpoints are
 * printed (adapt_mid): a derived value reads as written, and so hashes the same */
static double printed(double x)
{
	char buf[40];
	snprintf(buf, sizeof buf, "%.12g", x);
	return strtod(buf, NULL);
}

double axes_frequency(int kind, double x, double amplitude, double gravity)
{
	const double f = drive_axis_freq(kind, x, amplitude, gravity);
	return kind == AXIS_FREQUENCY || isnan(f) ? f : printed(f);
}

double axes_amplitude(int kind, double x, double frequency, double gravity)
{
	const sb_axis_row *r = drive_axis_row(kind);
	if (!(x > 0) || !(frequency > 0) || !r || kind == AXIS_FREQUENCY)
		return NAN;
	/* every axis is A (2 pi f)^power, over g when squared (drive.h) */
	double w = SB_TWO_PI * frequency;
	return printed(r->power == 2 ? x * gravity / (w * w) : x / w);
}

void axes_drive(const double x[AXIS_N], double gravity, double *amplitude, double *frequency)
{
	*frequency = printed(x[AXIS_GAMMA] * gravity / x[AXIS_VELOCITY] / SB_TWO_PI);
	*amplitude = axes_amplitude(AXIS_VELOCITY, x[AXIS_VELOCITY], *frequency, gravity);
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
