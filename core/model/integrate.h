/* integrate.h - Gear predictor-corrector (6- and 5-value Nordsieck form) and velocity
 * Verlet, on the scaled derivative arrays of sb_state. */
#ifndef SB_INTEGRATE_H
#define SB_INTEGRATE_H

#include "err.h"
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

/* The screening of the predicted state that a step does before its forces, done by
 * the vector kernel's fused corrector in the same pass (kernel_correct_predict): a disk
 * moved more than half the skin since the last neighbour build (d^2 > lim), a
 * non-finite position or angle, a disk outside the box (x < xlo, x > xhi, y < ylo). */
typedef struct sb_screen {
	double lim, xlo, xhi, ylo;
	int done;                 /* 0: not screened (settling's drag path), check it yourself */
	int rebuild, bad, out;
} sb_screen;

/* Start from positions and velocities: set the acceleration term from st->f and
 * clear the higher derivatives. */
void integ_start(const sb_integ *in, sb_state *st, double gy);

#endif
