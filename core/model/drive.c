/* drive.c - box motion and frequency ramps. For a constant frequency the phase is
 * omega t, computed exactly as it always was, so ramps cost constant runs nothing. */
#include "drive.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "units.h"

/* Linear leg: f(t) = f0 + k t, cycles = f0 t + k t^2 / 2. */
static double leg_cycles(double f0, double k, double t) { return f0 * t + 0.5 * k * t * t; }

static double ramp_freq(const sb_drive *d, double t)
{
	if (d->ramp == RAMP_NONE)
		return d->f;
	if (d->ramp == RAMP_LINEAR) {
		double u = t < d->T ? t : d->T;
		return d->f0 + (d->f1 - d->f0) * u / d->T;
	}
	double h = 0.5 * d->T, k = (d->f1 - d->f0) / h;
	if (t <= h)
		return d->f0 + k * t;
	double u = t - h < h ? t - h : h;
	return d->f1 - k * u;
}

static double ramp_cycles(const sb_drive *d, double t)
{
	if (d->ramp == RAMP_NONE)
		return d->f * t;
	if (d->ramp == RAMP_LINEAR) {
		double k = (d->f1 - d->f0) / d->T;
		if (t <= d->T)
			return leg_cycles(d->f0, k, t);
		return leg_cycles(d->f0, k, d->T) + d->f1 * (t - d->T); /* holds f1 afterwards */
	}
	double h = 0.5 * d->T, k = (d->f1 - d->f0) / h;
	if (t <= h)
		return leg_cycles(d->f0, k, t);
	double c = leg_cycles(d->f0, k, h);
	if (t <= d->T)
		return c + leg_cycles(d->f1, -k, t - h);
	return c + leg_cycles(d->f1, -k, h) + d->f0 * (t - d->T);
}

/* A ramp may first hold f0 for d->hold seconds (so that the start of shaking does not
 * fall on the ramp's first frequencies); the ramp functions see time from its start. */
double drive_freq(const sb_drive *d, double t)
{
	if (d->ramp != RAMP_NONE && t < d->hold)
		return d->f0;
	return ramp_freq(d, t - (d->ramp != RAMP_NONE ? d->hold : 0));
}

double drive_cycles(const sb_drive *d, double t)
{
	if (d->ramp == RAMP_NONE)
		return d->f * t;
	if (t < d->hold)
		return d->f0 * t;
	return d->f0 * d->hold + ramp_cycles(d, t - d->hold);
}

/* df/dt, for the box acceleration of a ramp */
static double drive_dfdt(const sb_drive *d, double t)
{
	if (t < d->hold)
		return 0;
	t -= d->hold;
	if (d->ramp == RAMP_LINEAR)
		return t <= d->T ? (d->f1 - d->f0) / d->T : 0;
	double h = 0.5 * d->T, k = (d->f1 - d->f0) / h;
	return t <= h ? k : t <= d->T ? -k : 0;
}

static double phase(const sb_drive *d, double t)
{
	return d->ramp == RAMP_NONE ? SB_TWO_PI * d->f * t : SB_TWO_PI * drive_cycles(d, t);
}

double drive_y(const sb_drive *d, double t) { return d->A * sin(phase(d, t)); }

double drive_v(const sb_drive *d, double t)
{
	return d->A * (SB_TWO_PI * drive_freq(d, t)) * cos(phase(d, t));
}

double drive_a(const sb_drive *d, double t)
{
	const double w = SB_TWO_PI * drive_freq(d, t), ph = phase(d, t);
	if (d->ramp == RAMP_NONE)
		return -d->A * w * w * sin(ph);
	return d->A * (SB_TWO_PI * drive_dfdt(d, t) * cos(ph) - w * w * sin(ph));
}

double drive_gamma(double A, double f, double g)
{
	/* the factors in this order: SQL's view (lib/schema.c) computes the same bits */
	return A * (SB_TWO_PI * f) * (SB_TWO_PI * f) / g;
}

double drive_velocity(double A, double f)
{
	return A * SB_TWO_PI * f;
}

double drive_axis(int kind, double A, double f, double g)
{
	switch (kind) {
	case AXIS_GAMMA:
		return drive_gamma(A, f, g);
	case AXIS_VELOCITY:
		return drive_velocity(A, f);
	default:
		return f;
	}
}

double drive_axis_freq(int kind, double x, double A, double g)
{
	if (kind != AXIS_GAMMA && kind != AXIS_VELOCITY)
		return x;
	if (!(x > 0) || !(A > 0))
		return NAN;
	/* in this order: a campaign's derived frequencies (printed to 12 digits) read as
	 * they always have, so that a resumed campaign names the same runs */
	return kind == AXIS_GAMMA ? sqrt(x * g / A) / SB_TWO_PI : x / (SB_TWO_PI * A);
}

/* the frequency's unit is the parameter table's too (tests/unit/drive.c checks) */
static const sb_axis_row AXES[AXIS_N] = {
	[AXIS_FREQUENCY] = {"frequency", "Hz", "frequency", "f", "f", 1},
	[AXIS_GAMMA] = {"gamma", "", "peak acceleration", "Γ", "Gamma", 2},
	[AXIS_VELOCITY] = {"velocity", "cm/s", "peak velocity", "v", "v", 1},
};

const sb_axis_row *drive_axis_row(int kind) { return kind >= 0 && kind < AXIS_N ? &AXES[kind] : NULL; }

double drive_axis_freq_from(int kind, double x, double x0, double f0)
{
	const sb_axis_row *r = drive_axis_row(kind);
	if (!r || kind == AXIS_FREQUENCY)
		return x;
	if (r->power == 2) /* Gamma = A (2 pi f)^2 / g */
		return x > 0 && x0 > 0 ? f0 * sqrt(x / x0) : NAN;
	return x0 > 0 ? f0 * x / x0 : NAN; /* v = A 2 pi f */
}

const char *drive_axis_name(int kind)
{
	return kind >= 0 && kind < AXIS_N ? AXES[kind].name : "?";
}

const char *drive_axis_unit(int kind)
{
	return kind >= 0 && kind < AXIS_N ? AXES[kind].unit : "";
}

int drive_axis_kind(const char *name)
{
	for (int k = 0; k < AXIS_N; k++)
		if (name && !strcmp(AXES[k].name, name))
			return k;
	return -1;
}

const char *drive_axis_text(int kind, const char *number, char *buf, size_t len)
{
	const sb_axis_row *r = drive_axis_row(kind);
	if (!r)
		snprintf(buf, len, "%s", number);
	else if (*r->unit)
		snprintf(buf, len, "%s %s", number, r->unit);
	else
		snprintf(buf, len, "%s %s", r->ascii, number);
	return buf;
}

const char *drive_axis_heading(int kind)
{
	const sb_axis_row *r = drive_axis_row(kind);
	return !r ? "" : *r->unit ? r->unit : r->ascii;
}
