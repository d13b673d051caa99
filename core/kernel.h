/* kernel.h - the force evaluation of a step and its fast path: the one module that
 * knows the AVX-512 kernel's per-disk records and the scaling of the pair list's
 * indices. Its interface is what a step needs: forces (into the state, or kept for
 * the fused corrector), the fused corrector, the sync of the state, the height of a
 * disk wherever it lives. The seam pairs of periodic sides (nlist.h) go through the
 * scalar law (forces_seam) after the flat list, in both builds alike. In a build without AVX-512 the same calls run the portable
 * kernel (forces.c) and correctors (integrate.c); both builds give the same numbers to
 * the bit (tests/integration/regression.sh).
 *
 * The fast path of the AVX-512 build: every disk's contact data sit in a 64-byte
 * record (kernel_rec.h) that the kernel reads two per pair; the kernel adds each
 * contact's force into per-disk accumulators; on a fused step the corrector reads
 * those accumulators, corrects, predicts the next step and writes the next records in
 * one pass, keeping x, y and their velocities in the records only (the state's arrays
 * of them are stale until kernel_sync). */
#ifndef SB_KERNEL_H
#define SB_KERNEL_H

#include "err.h"
#include "forces.h"
#include "integrate.h"
#include "nlist.h"
#include "state.h"

/* The kernel is chosen at compile time: AVX-512 where the build targets it (make picks
 * -march=x86-64-v4 on such machines), the portable one elsewhere. */
#if defined(__AVX512F__) && defined(__AVX512VL__)
#define SB_KERNEL_AVX512 1
#else
#define SB_KERNEL_AVX512 0
#endif

typedef struct sb_kernel sb_kernel;

int kernel_init(sb_kernel **k, const sb_state *st, sb_err *e);
void kernel_free(sb_kernel *k);

/* The neighbour list stores i << kernel_pair_shift() for disk i: in the AVX-512 build
 * 3, the offset in doubles of the disk's record, so that the kernel addresses records
 * and accumulators with x86's scaled index and no shifts (32 of ~190 instructions per
 * eight pairs); 0 in the portable build. */
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

/* The state's positions were changed outside the kernel (wrapped into the period at
 * a list build, periodic.h), after a kernel_sync: the next force evaluation packs its
 * records from st instead of trusting the fused corrector's. */
void kernel_state_changed(sb_kernel *k);

/* y of disk i, wherever it lives now (no sync needed). */
double kernel_y(const sb_kernel *k, const sb_state *st, int i);

#endif
