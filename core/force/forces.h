/* forces.h - the contact forces (docs/model.md, "Contact law": a spring-dashpot normal
 * force, hooke or hertz, and a tangential force capped by Coulomb friction, the
 * paper's viscous one or a shear spring with history) over the Verlet list: the law in
 * plain C (the reference of the vector kernel, kernel.h), the seam pairs, the spring
 * law's pass over the whole list, and the scans of the contacts. */
#ifndef SB_FORCES_H
#define SB_FORCES_H

#include "nlist.h"
#include "shear.h"
#include "state.h"

typedef struct sb_law {
	double Y, gn, gs, mu;    /* stiffness, normal and shear damping, Coulomb */
	double max_overlap;      /* fraction of the smaller radius that stops the run */
	int clip;                /* clip_attractive */
	/* restitution given (docs/model.md, "Restitution"): the normal damping of a pair
	 * is gz sqrt(m_eff), gz = 2 zeta sqrt(Y), the same restitution for every pair;
	 * else gn m_eff */
	int resti;
	double gz;
	/* normal = hertz: Y is hertz_stiffness and F_N, the shear damping too, carry the
	 * factor sqrt(xi R_eff), R_eff = R_i R_j / (R_i + R_j) (docs/model.md, "Normal law") */
	int hertz;
	/* tangential = spring: the shear spring k_t with history (docs/model.md,
	 * "Tangential law"); gs is its damping. The vector kernel's spring instances give
	 * forces_scalar's bits. */
	int spring;
	double kt;
	/* materials per pair of kinds (docs/model.md, "Materials per pair of kinds";
	 * paircoef.h): table = 1 when some class's coefficients differ from the fields
	 * above; kc[kind_i][kind_j] then holds each pair's, which the vector kernel's table
	 * instances take per listed pair (forces_scalar's bits). table = 0: kc is not read. */
	int table;
	struct sb_kc {
		double Y, gn, gs, mu, kt; /* gn: gamma_N, or gz with resti */
	} kc[3][3];
} sb_law;
typedef struct sb_kc sb_kc;

/* The pair class of two disk kinds (state.h's KIND_*, either order; paircoef.h's
 * classes): -1 for grain-grain, which the scene's own keys set, and for two walls. */
int forces_pairclass(int ki, int kj);

/* A pair's coefficients: kc[ki][kj] with a table, else the law's own. */
static inline sb_kc forces_kc(const sb_law *l, int ki, int kj)
{
	if (l->table)
		return l->kc[ki][kj];
	return (sb_kc){l->Y, l->resti ? l->gz : l->gn, l->gs, l->mu, l->kt};
}

/* The law's gz for restitution e at stiffness Y: 2 zeta sqrt(Y) (dtguard.h's zeta). */
double forces_gz(double Y, double e);

/* Where the seam loop finds disk i's x, y and scaled velocities (at [i * ps] from
 * x, y, vx, vy) and adds its force and torque (at [i * fs] from fx, fy, t): the
 * state's arrays (ps = fs = 1) or the vector kernel's records and accumulators. */
typedef struct sb_seam_io {
	const double *x, *y, *vx, *vy;
	double *fx, *fy, *t;
	int ps, fs;
} sb_seam_io;

/* The contact law over the seam pairs of periodic sides (nlist.h; none with walls):
 * disk i's image at x_i + period against disk j, the vector kernel's arithmetic to the bit
 * (scaled velocities, 1/dt in the damping), each pair with its class's coefficients
 * (forces_kc: a table of materials'), forces added after those of the flat
 * list in the list's order. hs: tangential = spring, the seam pairs' shear displacements
 * (a build's entries nflat on, shear.h), advanced as forces_scalar does; else NULL. fabs_sum (NULL: off) gets each contact's |F| added to both of its disks. Returns 1 if some overlap
 * exceeded max_overlap, else 0. */
int forces_seam(const sb_law *law, const sb_state *st, const sb_nlist *nl, const sb_seam_io *io, double inv_dt,
		double *hs, double *fabs_sum);

/* The force on disk i from disk j for given relative geometry; the unit of every
 * collision test. Outputs the force on i (fx, fy) and torques on i and j. */
void forces_pair(const sb_law *law, double dx, double dy, double ri, double rj,
		 double dvx, double dvy, double wi, double wj, double meff,
		 double *fx, double *fy, double *ti, double *tj);

/* tangential = spring: the force on disk i from disk j with the contact's shear
 * displacement *h (cm), velocities scaled as the kernel's (q1 = v dt, so that the
 * step's increment v_t dt is the scaled v_t itself; the damping gets inv_dt);
 * update: advance *h by the step and rescale it at the Coulomb cap, as a force
 * evaluation of a step does. Not in contact: all zero, *h untouched. */
void forces_pair_spring(const sb_law *law, double dx, double dy, double ri, double rj, double dvx, double dvy,
			double wi, double wj, double meff, double inv_dt, double *h, int update, double *fx, double *fy,
			double *ti, double *tj);

/* The law over the flat list and the seam pairs in that order, scalar, each pair with
 * its class's coefficients (forces_kc): the reference of the vector kernel's instances
 * (kvec.c: every instance gives its bits; the tests compare them). Positions and scaled velocities at io's x, y, vx, vy, the state's
 * spins; forces added at io's fx, fy, t. With the spring law each contact's shear
 * displacement in sh (in nl's order: shear_follow first) is advanced and every pair
 * not in contact reset to zero (sh is not read otherwise). fabs_sum and the return as
 * forces_seam's. */
int forces_scalar(const sb_law *law, const sb_state *st, const sb_nlist *nl, sb_shear *sh, const sb_seam_io *io,
		  double inv_dt, double *fabs_sum);

/* The scans below cover the seam pairs too (their normal and midpoint through the
 * minimum image, the midpoint wrapped into the period).
 *
 * The elastic energy of the contacts, sum of Y xi^2 / 2 (hertz: 2/5 Y sqrt(R_eff)
 * xi^5/2) and, with the spring law, of k_t xi_t^2 / 2 (hertz: times sqrt(xi R_eff)) from
 * sh (NULL, or not in nl's order: none), the largest overlap as a fraction of the
 * smaller radius, and the number of contacts (a scan of the list, for the energy
 * series). */
void forces_contact_energy(const sb_law *law, const sb_state *st, const sb_nlist *nl, const sb_shear *sh,
			   double *elastic, double *max_overlap, long *contacts);

/* Every current contact as (i, j, F_N, F_S, n_x, n_y, x, y): the list's indices, the
 * normal force along n = (r_i - r_j)/d and the tangential one along t (the force on i
 * is F_N n + F_S t), and the midpoint of the centres; velocities q1 * inv_dt. Writes at
 * most cap contacts into out (8 doubles each) and returns how many there are. The
 * spring law's F_S is that of the shear displacements in sh as they are (NULL, or not
 * in nl's order: zero). */
long forces_contacts(const sb_law *law, const sb_state *st, const sb_nlist *nl, const sb_shear *sh, double inv_dt,
		     double *out, long cap);

/* The contacts at the Coulomb limit (docs/model.md, "Sliding contacts"): how many of
 * the current contacts (*contacts of them) have their shear force capped at mu |F_N| by
 * the law evaluated at the state (velocities q1 * inv_dt), as a force evaluation would
 * (the spring's displacements from sh advanced by a step on a copy; NULL, or not in
 * nl's order: from zero). */
long forces_sliding(const sb_law *law, const sb_state *st, const sb_nlist *nl, const sb_shear *sh, double inv_dt,
		    long *contacts);

/* Largest overlap / smaller radius over all current contacts, and which disks (a scan
 * of the list: for the overlap record and the stop's message). */
double forces_max_overlap(const sb_state *st, const sb_nlist *nl, int *wi, int *wj);

#endif
