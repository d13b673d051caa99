/* drive.h - the box motion y_box = A sin(phi(t)): constant frequency, or a slow
 * linear frequency ramp with a continuous phase phi = 2 pi int f dt (docs/model.md, "Walls and box motion"). */
#ifndef SB_DRIVE_H
#define SB_DRIVE_H

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

#endif
