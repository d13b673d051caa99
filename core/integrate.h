/* integrate.h - Gear predictor-corrector (6- and 5-value Nordsieck form) and velocity
 * Verlet, on the scaled derivative arrays of sb_state. */
#ifndef SB_INTEGRATE_H
#define SB_INTEGRATE_H

#include "state.h"

typedef struct sb_integ {
	int kind;         /* enum sb_integrator */
	int nval;         /* Nordsieck values kept: 6, 5 or 3 */
	double c[SB_MAXORDER];
	double dt, half_dt2;
} sb_integ;

void integ_init(sb_integ *in, int kind, double dt);

/* Taylor-predict positions and derivatives of the mobile disks by one step
 * (for verlet: the half kick and the drift). */
void integ_predict(const sb_integ *in, sb_state *st);

/* Correct with the accelerations from st->f plus a uniform extra acceleration gy in y
 * (gravity and, in the box frame, minus the box acceleration). */
void integ_correct(const sb_integ *in, sb_state *st, double gy);

/* integ_correct followed by integ_predict, bit-identical to the two calls but with
 * one pass over the arrays; for steps after which nobody reads the corrected state. */
void integ_correct_predict(const sb_integ *in, sb_state *st, double gy);

/* Start from positions and velocities: set the acceleration term from st->f and
 * clear the higher derivatives. */
void integ_start(const sb_integ *in, sb_state *st, double gy);

#endif
