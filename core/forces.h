/* forces.h - Cundall-Strack contact forces of MODEL.md, eqs. (1)-(6), over the Verlet list. */
#ifndef SB_FORCES_H
#define SB_FORCES_H

#include "nlist.h"
#include "state.h"

typedef struct sb_law {
	double Y, gn, gs, mu;    /* stiffness, normal and shear damping, Coulomb */
	double max_overlap;      /* fraction of the smaller radius that stops the run */
	int clip;                /* clip_attractive */
} sb_law;

/* Contact forces and torques into st->f, evaluated at q[.][0] with velocities
 * q[.][1] * inv_dt. Returns 1 if some overlap exceeded max_overlap, else 0. */
int forces_compute(const sb_law *law, sb_state *st, const sb_nlist *nl, double inv_dt);

/* The same for a step whose corrector is integ_correct_predict_acc: in the AVX-512
 * build the forces stay in nl's per-disk accumulators (st->f is not written), which
 * that corrector reads; packed = 1 says the previous such corrector already wrote
 * the records this kernel reads and cleared the accumulators (so the state must not
 * have changed since). In the scalar build this is forces_compute. */
int forces_compute_acc(const sb_law *law, sb_state *st, const sb_nlist *nl, double inv_dt, int packed);

/* After integ_correct_predict_acc (AVX-512 build) the mobile disks' x, y, vx, vy
 * are only in the kernel's records: copy them into st. */
void forces_records_to_state(const sb_nlist *nl, sb_state *st);

/* The same, adding to fabs_sum[i] and fabs_sum[j] the magnitude of each contact force
 * (the ring observable; a separately compiled kernel, so this costs nothing when off). */
int forces_compute_track(const sb_law *law, sb_state *st, const sb_nlist *nl, double inv_dt,
			 double *fabs_sum);

/* The force on disk i from disk j for given relative geometry; the unit of every
 * collision test. Outputs the force on i (fx, fy) and torques on i and j. */
void forces_pair(const sb_law *law, double dx, double dy, double ri, double rj,
		 double dvx, double dvy, double wi, double wj, double meff,
		 double *fx, double *fy, double *ti, double *tj);

/* Largest overlap / smaller radius over all current contacts, and where (slow; for
 * the blow-up message). */
double forces_max_overlap(const sb_state *st, const sb_nlist *nl, int *wi, int *wj);

#endif
