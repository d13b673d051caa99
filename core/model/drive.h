/* drive.h - the box motion y_box = A sin(phi(t)): constant frequency, or a slow
 * linear frequency ramp with a continuous phase phi = 2 pi int f dt (docs/model.md, "Walls and box motion"). */
#ifndef SB_DRIVE_H
#define SB_DRIVE_H

#include <stddef.h>

enum sb_ramp { RAMP_NONE, RAMP_LINEAR, RAMP_UPDOWN };

typedef struct sb_drive {
	int ramp;
	double A;        /* amplitude, cm */
	double f;        /* constant frequency (RAMP_NONE), Hz */
	double f0, f1;   /* ramp: from f0 to f1 (RAMP_LINEAR), f0 -> f1 -> f0 (RAMP_UPDOWN) */
	double T;        /* ramp duration, s */
	double hold;     /* ramp: seconds at f0 before the ramp starts */
} sb_drive;

/* Number of periods completed at time t (the phase in units of 2 pi). */
double drive_cycles(const sb_drive *d, double t);
double drive_freq(const sb_drive *d, double t);
double drive_y(const sb_drive *d, double t);
double drive_v(const sb_drive *d, double t);
double drive_a(const sb_drive *d, double t);

/* The dimensionless peak acceleration of a box moving at amplitude A (cm) and
 * frequency f (Hz) under gravity g (cm/s^2): Gamma = A (2 pi f)^2 / g (docs/model.md,
 * "Units and the paper's values"). The one definition: the database's `runs.gamma`
 * (lib/schema.c) is checked against it by a test, the figures' Gamma axis uses it. */
double drive_gamma(double A, double f, double g);

/* The box's peak velocity (cm/s) at amplitude A (cm) and frequency f (Hz): v = A 2 pi f,
 * the other dimensional measure of a drive the literature reports onsets in. The one
 * definition: the campaign axis velocity and the analysis tools' velocity axis use it. */
double drive_velocity(double A, double f);

/* The axes a drive is measured on: its frequency f, Gamma (drive_gamma) or its peak
 * velocity v (drive_velocity). One row per axis holds all there is to say about it:
 * its name (the campaign files' word and the tools' --axis), its unit (as the parameter
 * table writes units), its words and symbol in a figure's text (docs/model.md's
 * symbols), and how it scales with the frequency at a fixed amplitude (as f^power).
 * The campaign's search axes (docs/campaigns.md, "Axes in Gamma and v"), the figures'
 * axes and the onset search's readers use it; tests/integration/one_place_core.sh fails
 * when another file of core/, lib/, study/ or analysis/ spells an axis out again. */
enum sb_axis { AXIS_FREQUENCY, AXIS_GAMMA, AXIS_VELOCITY, AXIS_N };

typedef struct sb_axis_row {
	const char *name;   /* "frequency", "gamma", "velocity" */
	const char *unit;   /* "Hz", "", "cm/s" */
	const char *words;  /* "frequency", "peak acceleration", "peak velocity" */
	const char *symbol; /* "f", "Γ", "v" (UTF-8) */
	const char *ascii;  /* "f", "Gamma", "v": the symbol in a terminal's text */
	int power;          /* the axis grows as f^power at a fixed amplitude: 1, 2, 1 */
} sb_axis_row;

/* The row of axis kind; NULL for another kind. */
const sb_axis_row *drive_axis_row(int kind);
/* The value on axis kind of a drive of amplitude A (cm) at frequency f (Hz) under
 * gravity g (cm/s^2); f itself for AXIS_FREQUENCY (or another kind). */
double drive_axis(int kind, double A, double f, double g);
/* The inverse: the frequency (Hz) at which a drive of amplitude A reaches x on axis
 * kind; NaN unless x > 0 and A > 0 (x itself on the frequency axis). */
double drive_axis_freq(int kind, double x, double A, double g);
/* The frequency (Hz) at which a drive reaches x on axis kind, when a drive of the same
 * amplitude (and gravity) is at x0 on that axis at frequency f0: f0 (x / x0)^(1/power),
 * from the row's power alone; NaN unless x0 > 0 (and x > 0 on a squared axis); x
 * itself on the frequency axis (or another kind). */
double drive_axis_freq_from(int kind, double x, double x0, double f0);
/* Its name and unit ("?" and "" for another kind); the kind of a name, -1 for another. */
const char *drive_axis_name(int kind);
const char *drive_axis_unit(int kind);
int drive_axis_kind(const char *name);
/* A number (or range, "2 to 3") on axis kind as a line of text says it: followed by
 * the axis's unit ("2.5 Hz", "70.7 cm/s"), or, on an axis without a unit, after its
 * ASCII symbol ("Gamma 1.7"). Returns buf. */
const char *drive_axis_text(int kind, const char *number, char *buf, size_t len);
/* What heads a column of numbers on axis kind: its unit, or its ASCII symbol on an
 * axis without one ("Hz", "Gamma"). */
const char *drive_axis_heading(int kind);

#endif
