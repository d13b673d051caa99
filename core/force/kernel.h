/* kernel.h - the force evaluation of a step: the vector kernel (kvec.c, one source
 * compiled per instruction set; docs/kernel.md),
 * the instance this CPU runs chosen at start-up, and its fused corrector. Its
 * interface is what a step needs: forces (into the state, or kept for the fused
 * corrector), the fused corrector, the sync of the state, the height of a disk
 * wherever it lives. The seam pairs of periodic sides (nlist.h) go through the scalar
 * law (forces_seam) after the flat list. The shear-spring law (tangential = spring) has
 * vector instances of its own (with a table of materials too), its history per listed pair in
 * the kernel's sb_shear. Every path gives the scalar law's numbers to
 * the bit (tests/unit/kernel.c, tests/integration/regression.sh).
 *
 * Every disk's contact data sit in a 64-byte record (kvec.h) that the kernel reads two
 * per pair; the kernel adds each contact's force into per-disk accumulators; on a fused
 * step the corrector reads those accumulators, corrects, predicts the next step and
 * writes the next records in one pass, keeping x, y and their velocities in the
 * records only (the state's arrays of them are stale until kernel_sync). */
#ifndef SB_KERNEL_H
#define SB_KERNEL_H

#include "err.h"
#include "forces.h"
#include "integrate.h"
#include "nlist.h"
#include "state.h"

/* The environment variable that forces a path (for tests and measurements): a name
 * from kernel_paths, or "auto" (the default: the widest this CPU runs). */
#define SB_KERNEL_ENV "SHAKEBOX_KERNEL"
enum { SB_KPATHS_MAX = 4 };

/* A path this build holds: its name, what the CPU needs for it, whether this one has it. */
typedef struct sb_kpath {
	const char *name, *needs;
	int runnable;
	int test; /* a path for tests and measurements, never chosen by itself */
} sb_kpath;

/* The paths of this build, widest first; returns how many (at most SB_KPATHS_MAX). */
int kernel_paths(sb_kpath *out);

typedef struct sb_kernel sb_kernel;

/* The path named by SHAKEBOX_KERNEL, else the widest this CPU runs; an unknown name or
 * one the CPU cannot run is an error (SB_EUSAGE) naming the variable and the choices. */
int kernel_init(sb_kernel **k, const sb_state *st, sb_err *e);
/* The same with the path given (NULL or "auto": the widest). */
int kernel_init_path(sb_kernel **k, const sb_state *st, const char *name, sb_err *e);
/* The name of the path that runs ("avx512", "avx2", "sse2", "neon", "generic"). */
const char *kernel_path(const sb_kernel *k);
/* Its candidate scan, for the neighbour list (nlist.h). */
sb_scan_fn kernel_scan(const sb_kernel *k);
void kernel_free(sb_kernel *k);

/* The neighbour list stores i << kernel_pair_shift() for disk i: 3, the offset in
 * doubles of the disk's record, so that the kernel addresses records and accumulators
 * with x86's scaled index and no shifts. */
int kernel_pair_shift(void);

/* Contact forces at the current state (velocities q1 / dt). keep = 0: into st->f;
 * keep = 1: kept for kernel_correct_predict (st->f not written). fabs_sum (NULL: off)
 * gets each contact's |F| added to both disks (the ring observable). Data that follow
 * the list (its walls' records, the per-pair m_eff) are renewed after each build.
 * Returns 1 when an overlap exceeded law->max_overlap, 0 when none did, -1 on error. */
int kernel_forces(sb_kernel *k, const sb_law *law, sb_state *st, const sb_nlist *nl, double inv_dt,
		  int keep, double *fabs_sum, sb_err *e);

/* The corrector of a step whose forces were kept, fused with the next step's predictor
 * (integ_correct_predict, bit-identical) and the screening of the predicted state
 * (scr: done = 1 when screened here). */
void kernel_correct_predict(sb_kernel *k, const sb_integ *in, sb_state *st, double gy, const sb_nlist *nl,
			    sb_screen *scr);

/* Bring st's x, y, vx, vy up to date (they may live in the records after a fused
 * corrector): before anything else reads them. */
void kernel_sync(sb_kernel *k, sb_state *st);

/* The data the fused corrector leaves for the next force evaluation (asserted after it
 * in the test build): NULL, or the first invariant broken - each mobile disk's record
 * holds its 1/m and R in the lanes kvec.h gives them, and its accumulator is zero. */
const char *kernel_check(const sb_kernel *k, const sb_state *st);

/* The state's positions were changed outside the kernel (wrapped into the period at
 * a list build, periodic.h), after a kernel_sync: the next force evaluation packs its
 * records from st instead of trusting the fused corrector's. */
void kernel_state_changed(sb_kernel *k);

/* tangential = spring: the contacts' shear displacements (shear.h), which each
 * kernel_forces advances by one step; for the scans, the checkpoint and the tests. */
sb_shear *kernel_shear(sb_kernel *k);

/* y of disk i, wherever it lives now (no sync needed). */
double kernel_y(const sb_kernel *k, const sb_state *st, int i);

#endif
