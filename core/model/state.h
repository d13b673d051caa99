/* state.h - the particle state, struct-of-arrays. Mobile disks occupy [0, nm), wall
 * disks [nm, n): loops that integrate stop at nm and never look at walls. */
#ifndef SB_STATE_H
#define SB_STATE_H

#include "err.h"

enum sb_kind { KIND_GRAIN = 0, KIND_INTRUDER = 1, KIND_WALL = 2 };
enum { C_X = 0, C_Y = 1, C_TH = 2, SB_NCOORD = 3, SB_MAXORDER = 6 };

typedef struct sb_state {
	int n, nm, cap;
	/* Scaled Nordsieck vectors in the box frame: q[c][k][i] = dt^k/k! d^k c_i/dt^k.
	 * q[c][1] / dt is the velocity; the same arrays serve gear5 (k<6), gear4 (k<5)
	 * and verlet (k<3). Walls keep only q[c][0]; their derivatives stay zero. */
	double *q[SB_NCOORD][SB_MAXORDER];
	double *f[SB_NCOORD];    /* force x, y and torque from contacts */
	double *r, *m, *inv_m, *inv_i;
	void *slab;              /* one block holds all the double arrays (state.c) */
	int *id;
	unsigned char *kind;
} sb_state;

int state_alloc(sb_state *s, int cap, sb_err *e);
void state_free(sb_state *s);

/* Append a disk; mobile ones must all come before walls (checked). */
int state_push(sb_state *s, double x, double y, double r, int kind, double m, double inv_m,
	       double inv_i, sb_err *e);

/* Index of the first intruder, or -1. */
int state_find_intruder(const sb_state *s);

#endif
