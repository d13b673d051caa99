/* drive.c - the box motion (core/model/drive.h): the phase of every drive, frequency ramps
 * up, down and up-and-down included, is continuous with rate f(t), and the velocity
 * and acceleration are the derivatives of the displacement. */
#include <math.h>
#include <stdio.h>

#include <string.h>

#include "drive.h"
#include "params.h"
#include "testlib.h"

static void test_ramp(void)
{
	/* the phase of every drive is continuous with derivative f(t), also at the turn */
	sb_drive d[4] = {{RAMP_NONE, 2, 3.0, 0, 0, 10, 0},
			 {RAMP_LINEAR, 2, 0, 2.5, 3.2, 10, 0},
			 {RAMP_UPDOWN, 2, 0, 2.5, 3.2, 10, 0},
			 {RAMP_UPDOWN, 2, 0, 2.5, 3.2, 10, 1.5}};
	const char *names[4] = {"none", "linear", "updown", "updown_hold"};
	for (int k = 0; k < 4; k++) {
		double worst_c = 0, worst_f = 0, worst_y = 0;
		const double h = 1e-6;
		for (double t = 0.01; t < 12; t += 0.0173) {
			/* derivative of cycles is f (central difference, O(h^2) ~ 1e-12) */
			double dc = (drive_cycles(&d[k], t + h) - drive_cycles(&d[k], t - h)) / (2 * h);
			worst_f = fmax(worst_f, fabs(dc - drive_freq(&d[k], t)));
			/* velocity is the derivative of the position */
			double dy = (drive_y(&d[k], t + h) - drive_y(&d[k], t - h)) / (2 * h);
			worst_y = fmax(worst_y, fabs(dy - drive_v(&d[k], t)) / (2 * 2 * 3.14159 * 3.2));
		}
		/* continuity at the turning point and at the end of the ramp */
		double ts[3] = {5 + d[k].hold, 10 + d[k].hold, d[k].hold > 0 ? d[k].hold : 5};
		for (int q = 0; q < 3; q++)
			worst_c = fmax(worst_c, fabs(drive_cycles(&d[k], ts[q] + 1e-9) - drive_cycles(&d[k], ts[q] - 1e-9)));
		char id[64];
		snprintf(id, sizeof id, "drive.%s.phase_rate_is_frequency", names[k]);
		CHECK(id, worst_f < 1e-6, "max |dcycles/dt - f| = %g", worst_f);
		snprintf(id, sizeof id, "drive.%s.velocity_is_derivative", names[k]);
		CHECK(id, worst_y < 1e-6, "max relative |dy/dt - v| = %g", worst_y);
		snprintf(id, sizeof id, "drive.%s.phase_continuous", names[k]);
		CHECK(id, worst_c < 1e-7, "jump %g", worst_c);
	}
	/* updown returns to the start frequency and covers the mean frequency's cycles */
	CHECK_REL("drive.updown.ends_at_start", drive_freq(&d[2], 10), 2.5, 1e-15);
	CHECK_REL("drive.updown.turns_at_top", drive_freq(&d[2], 5), 3.2, 1e-15);
	CHECK_REL("drive.updown.cycles", drive_cycles(&d[2], 10), 0.5 * (2.5 + 3.2) * 10, 1e-14);
	CHECK_REL("drive.linear.cycles", drive_cycles(&d[1], 10), 0.5 * (2.5 + 3.2) * 10, 1e-14);
	/* the acceleration is the derivative of the velocity */
	double worst_a = 0;
	for (double t = 0.01; t < 10; t += 0.031) {
		double h = 1e-6;
		double da = (drive_v(&d[2], t + h) - drive_v(&d[2], t - h)) / (2 * h);
		worst_a = fmax(worst_a, fabs(da - drive_a(&d[2], t)) / (2 * pow(2 * 3.14159 * 3.2, 2)));
	}
	CHECK("drive.updown.acceleration_is_derivative", worst_a < 1e-5, "max relative %g", worst_a);
	/* a hold keeps f0, then the same ramp shifted in time */
	CHECK_REL("drive.hold.holds", drive_freq(&d[3], 1.0), 2.5, 1e-15);
	CHECK_REL("drive.hold.turns_later", drive_freq(&d[3], 6.5), 3.2, 1e-15);
	CHECK_REL("drive.hold.cycles", drive_cycles(&d[3], 11.5), 2.5 * 1.5 + 0.5 * (2.5 + 3.2) * 10, 1e-14);
}

/* The cycles of d over [0, b] as the integral of its frequency, without drive_cycles:
 * Simpson's rule on each piece between the breakpoints of the definition (end of the
 * hold, end of the ramp), where f is linear or constant and Simpson's rule is exact. */
static double cycles_by_quadrature(const sb_drive *d, double b)
{
	double edge[4] = {0, d->hold, d->hold + d->T, INFINITY}, sum = 0;
	for (int p = 0; p < 3 && edge[p] < b; p++) {
		double lo = edge[p], hi = fmin(edge[p + 1], b), h = (hi - lo) / 20;
		double s = drive_freq(d, lo + 1e-12) + drive_freq(d, hi - 1e-12);
		for (int i = 1; i < 20; i++)
			s += (i % 2 ? 4 : 2) * drive_freq(d, lo + i * h);
		sum += s * h / 3;
	}
	return sum;
}

/* A linear ramp DOWN (ramp_from > ramp_to): f falls linearly from f0 to f1 over T (after
 * the hold) and stays at f1; the phase is 2 pi int f dt, continuous everywhere, and the
 * box velocity and acceleration are the derivatives of its position and velocity (the
 * acceleration carries 2 pi A (df/dt) cos(phi), negative on the way down). */
static void test_ramp_down(void)
{
	const double f0 = 3.2, f1 = 2.5, T = 10, A = 2;
	const double holds[2] = {0, 1.5};
	const char *names[2] = {"linear_down", "linear_down_hold"};
	for (int k = 0; k < 2; k++) {
		const double hold = holds[k];
		sb_drive d = {RAMP_LINEAR, A, 0, f0, f1, T, hold};
		double worst_lin = 0, worst_rate = 0, worst_int = 0, worst_y = 0, worst_a = 0, worst_end = 0;
		int decreasing = 1;
		const double h = 1e-6, vscale = A * 2 * M_PI * f0, ascale = A * pow(2 * M_PI * f0, 2);
		for (double t = 0.01; t < hold + T + 2; t += 0.0173) {
			double f = drive_freq(&d, t);
			/* the line through (hold, f0) and (hold + T, f1), f0 before, f1 after */
			double want = t < hold ? f0 : t > hold + T ? f1 : f0 + (f1 - f0) * (t - hold) / T;
			if (t < hold + T)
				worst_lin = fmax(worst_lin, fabs(f - want));
			else
				worst_end = fmax(worst_end, fabs(f - want));
			if (t > hold + 0.02 && t < hold + T)
				decreasing &= drive_freq(&d, t) < drive_freq(&d, t - 0.01);
			double dc = (drive_cycles(&d, t + h) - drive_cycles(&d, t - h)) / (2 * h);
			worst_rate = fmax(worst_rate, fabs(dc - f));
			double dy = (drive_y(&d, t + h) - drive_y(&d, t - h)) / (2 * h);
			worst_y = fmax(worst_y, fabs(dy - drive_v(&d, t)) / vscale);
			double dv = (drive_v(&d, t + h) - drive_v(&d, t - h)) / (2 * h);
			worst_a = fmax(worst_a, fabs(dv - drive_a(&d, t)) / ascale);
		}
		/* cycles = the integral of f from 0, at points spread over hold, ramp and after */
		const double tq[5] = {hold * 0.5, hold + 0.3 * T, hold + T, hold + T + 1.7, hold + 0.999 * T};
		for (int q = 0; q < 5; q++)
			worst_int = fmax(worst_int, fabs(drive_cycles(&d, tq[q]) - cycles_by_quadrature(&d, tq[q])));
		/* no jump of phase, position or velocity where the ramp starts and ends */
		double worst_c = 0, worst_jy = 0;
		const double tj[2] = {hold, hold + T};
		for (int q = 0; q < 2; q++) {
			double a = tj[q] - 1e-9, b = tj[q] + 1e-9;
			worst_c = fmax(worst_c, fabs(drive_cycles(&d, b) - drive_cycles(&d, a)));
			worst_jy = fmax(worst_jy, fabs(drive_y(&d, b) - drive_y(&d, a)) / A);
			worst_jy = fmax(worst_jy, fabs(drive_v(&d, b) - drive_v(&d, a)) / vscale);
		}
		char id[80];
		snprintf(id, sizeof id, "drive.%s.frequency_linear", names[k]);
		CHECK(id, worst_lin < 1e-13, "max |f - (f0 + (f1 - f0) t / T)| = %g", worst_lin);
		snprintf(id, sizeof id, "drive.%s.frequency_decreases", names[k]);
		CHECK(id, decreasing, "f(t) not strictly decreasing on the ramp");
		snprintf(id, sizeof id, "drive.%s.holds_end_frequency", names[k]);
		CHECK(id, worst_end < 1e-13, "max |f - f1| after the ramp = %g", worst_end);
		snprintf(id, sizeof id, "drive.%s.phase_rate_is_frequency", names[k]);
		CHECK(id, worst_rate < 1e-6, "max |dcycles/dt - f| = %g", worst_rate);
		snprintf(id, sizeof id, "drive.%s.phase_is_integral_of_frequency", names[k]);
		CHECK(id, worst_int < 1e-9, "max |cycles - Simpson int f dt| = %g", worst_int);
		snprintf(id, sizeof id, "drive.%s.phase_continuous", names[k]);
		CHECK(id, worst_c < 1e-7, "jump %g", worst_c);
		snprintf(id, sizeof id, "drive.%s.motion_continuous", names[k]);
		CHECK(id, worst_jy < 1e-7, "relative jump of y or v %g", worst_jy);
		snprintf(id, sizeof id, "drive.%s.velocity_is_derivative", names[k]);
		CHECK(id, worst_y < 1e-6, "max relative |dy/dt - v| = %g", worst_y);
		snprintf(id, sizeof id, "drive.%s.acceleration_is_derivative", names[k]);
		CHECK(id, worst_a < 1e-5, "max relative |dv/dt - a| = %g", worst_a);
		/* the hold's f0 hold plus the ramp's trapezoid (f0 + f1) T / 2 */
		snprintf(id, sizeof id, "drive.%s.cycles", names[k]);
		CHECK_REL(id, drive_cycles(&d, hold + T), f0 * hold + 0.5 * (f0 + f1) * T, 1e-14);
	}
}

/* Gamma's known values: the paper's 2.6 and 3.2 Hz at A = 2 cm, g = 981 cm/s^2 give
 * 0.54 and 0.82 (docs/model.md), and Gamma = 1 at f = sqrt(g / A) / (2 pi); the peak of
 * drive_a at constant frequency is Gamma g. */
static void test_gamma(void)
{
	CHECK_REL("drive.gamma.paper_low", drive_gamma(2, 2.6, 981), 0.5440858369122451, 1e-14);
	CHECK_REL("drive.gamma.paper_high", drive_gamma(2, 3.2, 981), 0.8241773624232825, 1e-14);
	CHECK_REL("drive.gamma.one", drive_gamma(1, sqrt(981.0) / (2 * M_PI), 981), 1, 1e-14);
	sb_drive d = {.ramp = RAMP_NONE, .A = 2, .f = 3.2};
	CHECK_REL("drive.gamma.is_peak_acceleration", fabs(drive_a(&d, 0.75 / 3.2)) / 981, drive_gamma(2, 3.2, 981),
		  1e-12);
	/* the peak velocity: 2 pi f A (40.2 cm/s at the paper's 3.2 Hz and 2 cm), drive_v at t = 0 */
	CHECK_REL("drive.velocity.paper_high", drive_velocity(2, 3.2), 40.21238596594935, 1e-14);
	CHECK_REL("drive.velocity.is_peak_velocity", drive_v(&d, 0), drive_velocity(2, 3.2), 1e-14);
}

/* The axes' one table: each name reads back as its kind, an unknown name or kind is
 * refused, the frequency's unit is the parameter table's, and drive_axis_freq undoes
 * drive_axis (Gamma 0.824 at the paper's 3.2 Hz and 2 cm is 3.2 Hz again). */
static void test_axes(void)
{
	char id[64];
	for (int k = 0; k < AXIS_N; k++) {
		snprintf(id, sizeof id, "drive.axis.%s.name", drive_axis_name(k));
		CHECK(id, drive_axis_kind(drive_axis_name(k)) == k, "%d", drive_axis_kind(drive_axis_name(k)));
		snprintf(id, sizeof id, "drive.axis.%s.round_trip", drive_axis_name(k));
		const double x = drive_axis(k, 2, 3.2, 981);
		CHECK_REL(id, drive_axis_freq(k, x, 2, 981), 3.2, 1e-14);
		/* the row's scaling agrees with its value: from a run at 2.5 Hz to x */
		const sb_axis_row *r = drive_axis_row(k);
		snprintf(id, sizeof id, "drive.axis.%s.row", drive_axis_name(k));
		CHECK(id, r && !strcmp(r->name, drive_axis_name(k)) && !strcmp(r->unit, drive_axis_unit(k)) && r->words &&
				  *r->words && r->symbol && *r->symbol && (r->power == 1 || r->power == 2),
		      "an incomplete row");
		snprintf(id, sizeof id, "drive.axis.%s.scaling", drive_axis_name(k));
		CHECK_REL(id, drive_axis_freq_from(k, x, drive_axis(k, 2, 2.5, 981), 2.5), 3.2, 1e-14);
	}
	CHECK("drive.axis.row_of_another_kind", !drive_axis_row(AXIS_N) && !drive_axis_row(-1), "a row");
	CHECK("drive.axis.scaling_needs_positive",
	      isnan(drive_axis_freq_from(AXIS_GAMMA, -1, 2, 3)) && isnan(drive_axis_freq_from(AXIS_VELOCITY, 1, 0, 3)) &&
		      drive_axis_freq_from(AXIS_FREQUENCY, 7, 0, 3) == 7 && drive_axis_freq_from(-1, 7, 1, 3) == 7,
	      "%g", drive_axis_freq_from(AXIS_GAMMA, -1, 2, 3));
	CHECK("drive.axis.unknown_name", drive_axis_kind("Gamma") == -1 && drive_axis_kind("") == -1 &&
						 drive_axis_kind(NULL) == -1,
	      "%d", drive_axis_kind("Gamma"));
	CHECK("drive.axis.unknown_kind", !strcmp(drive_axis_name(AXIS_N), "?") && !strcmp(drive_axis_unit(-1), ""),
	      "%s", drive_axis_name(AXIS_N));
	const sb_param *f = params_find("frequency");
	CHECK("drive.axis.frequency_unit_is_the_tables", f && !strcmp(f->unit, drive_axis_unit(AXIS_FREQUENCY)),
	      "table '%s', axis '%s'", f ? f->unit : "(none)", drive_axis_unit(AXIS_FREQUENCY));
	CHECK_REL("drive.axis.gamma_value", drive_axis(AXIS_GAMMA, 2, 3.2, 981), drive_gamma(2, 3.2, 981), 0);
	CHECK_REL("drive.axis.velocity_value", drive_axis(AXIS_VELOCITY, 2, 3.2, 981), drive_velocity(2, 3.2), 0);
	CHECK("drive.axis.freq_needs_positive", isnan(drive_axis_freq(AXIS_GAMMA, -1, 2, 981)) &&
						   isnan(drive_axis_freq(AXIS_VELOCITY, 1, 0, 981)) &&
						   drive_axis_freq(AXIS_FREQUENCY, -1, 0, 981) == -1,
	      "%g", drive_axis_freq(AXIS_GAMMA, -1, 2, 981));
	/* a number as a line of text says it: unit after, or the symbol before on the unitless axis */
	char t[64];
	CHECK("drive.axis.text.frequency", !strcmp(drive_axis_text(AXIS_FREQUENCY, "2.5", t, sizeof t), "2.5 Hz"), "%s", t);
	CHECK("drive.axis.text.gamma", !strcmp(drive_axis_text(AXIS_GAMMA, "1 to 2", t, sizeof t), "Gamma 1 to 2"), "%s", t);
	CHECK("drive.axis.text.velocity", !strcmp(drive_axis_text(AXIS_VELOCITY, "70.7", t, sizeof t), "70.7 cm/s"), "%s", t);
	CHECK("drive.axis.text.another_kind", !strcmp(drive_axis_text(AXIS_N, "3", t, sizeof t), "3"), "%s", t);
	CHECK("drive.axis.text.truncates", !strcmp(drive_axis_text(AXIS_VELOCITY, "70.7", t, 6), "70.7 "), "%s", t);
	CHECK("drive.axis.heading", !strcmp(drive_axis_heading(AXIS_FREQUENCY), "Hz") &&
					    !strcmp(drive_axis_heading(AXIS_GAMMA), "Gamma") &&
					    !strcmp(drive_axis_heading(AXIS_VELOCITY), "cm/s") && !strcmp(drive_axis_heading(-1), ""),
	      "%s %s %s", drive_axis_heading(AXIS_FREQUENCY), drive_axis_heading(AXIS_GAMMA),
	      drive_axis_heading(AXIS_VELOCITY));
}

int main(void)
{
	test_axes();
	test_gamma();
	test_ramp();
	test_ramp_down();
	return tl_done();
}
