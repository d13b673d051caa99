/* nlist.h - neighbour search linear in N: a growable cell grid sized for the ordinary
 * disks and a Verlet list with a skin. Disks much larger than the rest (the intruder)
 * stay out of the cells and search the cells their own reach covers, so one big disk
 * never makes everybody's cells big. Wall-wall pairs are never formed. */
#ifndef SB_NLIST_H
#define SB_NLIST_H

#include "err.h"
#include "state.h"

/* The force kernel's variant is chosen at compile time: AVX-512 where the build
 * targets it (make picks -march=x86-64-v4 on such machines), scalar elsewhere. Both
 * give the same forces to the bit. */
#if defined(__AVX512F__) && defined(__AVX512VL__)
#define SB_KERNEL_AVX512 1
#else
#define SB_KERNEL_AVX512 0
#endif

/* The pair list stores SB_PSCALE i for disk i: 8 in the AVX-512 build, the offset in
 * doubles of the disk's 64-byte kernel record, so that the kernel addresses records
 * (base + 8 * 8i bytes) and accumulators (base + 4 * 8i bytes) with x86's scaled
 * index and no shifts: 32 of ~190 instructions per eight pairs. Readers of pi, pj
 * divide by it. (It limits n to 2^28 disks; nlist_init checks.) */
#if SB_KERNEL_AVX512
enum { SB_PSCALE = 8 };
#else
enum { SB_PSCALE = 1 };
#endif

#if SB_KERNEL_AVX512
enum { SB_KCHUNK = 256 };

/* one chunk of the list's contacts: disks 8i, 8j, the force on i and the torques
 * -R_i F_S, R_j F_S (8 spare slots: the kernel stores whole vectors) */
typedef struct sb_kbuf {
	_Alignas(64) double fx[SB_KCHUNK + 8], fy[SB_KCHUNK + 8], ti[SB_KCHUNK + 8], tj[SB_KCHUNK + 8];
	int i[SB_KCHUNK + 8], j[SB_KCHUNK + 8];
	long walls_packed;          /* the build whose wall records rec holds */
} sb_kbuf;
#endif

typedef struct sb_nlist {
	double skin;
	/* cell grid over the bounding box of all disks at the last build */
	int ncx, ncy, ccap;
	double x0, y0, cell, inv_cell;
	int *cell_start, *cell_idx; /* counting sort: disks of cell c are cell_idx[cell_start[c]..] */
	int *cell_of;
	int *cell_x, *cell_y;        /* the cell's column and row */
	int *cell_pos;               /* scratch of the counting sort */
	double *xs, *ys, *rs;       /* x, y, R of the disks in cell order (cell_idx) */
	/* The flat list the force kernel walks: the npairs pairs (i, j > i) of ordinary
	 * mobile i, in rows of ascending i (walls are j: they come after the mobile
	 * disks), then the nbig pairs of the large disks, any order */
	int *pi, *pj;               /* SB_PSCALE times the disk indices */
	int npairs, nbig;
	int nflat, fcap;            /* npairs + nbig; padded with pairs (0, 0) to a multiple of 8 */
#if SB_KERNEL_AVX512
	/* scratch of the AVX-512 force kernel (forces.c): per disk a 64-byte record (x, y,
	 * vx, vy, R w, 1/m, R, R) and a force accumulator (Fx, Fy, torque, 0); one chunk's
	 * contacts */
	double *rec, *facc;
	sb_kbuf *kbuf;
#else
	/* m_eff of each pair in the list (the AVX-512 kernel forms it from its records),
	 * and scratch of the scalar force kernel: the pairs in contact this step, their
	 * distance and its inverse */
	double *pmeff;
	int *contact;
	double *cd, *cinv;
#endif
	/* which disks are large; fixed at setup */
	unsigned char *large;
	int *large_list, nlarge;
	double r_small;             /* largest radius among ordinary disks */
	/* positions at the last build: the rebuild rule and a checkpoint use them */
	double *xref, *yref;
	int cap;
	long builds;
	/* the force kernel prefetches the far ends of its pairs: set by nlist_init when the
	 * per-disk data a step sweeps outgrow half the last-level cache (5x10^4 disks on a
	 * 32 MiB L3), where those loads come from memory; below, the prefetches only cost
	 * (measured: -6 % at 10^5 disks, +2 % at 10^4, +4.5 % at 10^3) */
	int prefetch;
} sb_nlist;

/* Classify disks (large = radius above 1.5x the mean) and allocate. */
int nlist_init(sb_nlist *nl, const sb_state *st, double skin, sb_err *e);
void nlist_free(sb_nlist *nl);

/* Build from the given reference positions (normally the current ones, copied into
 * xref/yref first by nlist_build). */
int nlist_build_from_ref(sb_nlist *nl, const sb_state *st, sb_err *e);
int nlist_build(sb_nlist *nl, const sb_state *st, sb_err *e);

/* Brute-force O(N^2) list of pairs within r_i + r_j + skin, for tests: returns the
 * number of pairs, fills (pi, pj) with pi < pj when they are non-NULL. */
long nlist_brute(const sb_state *st, double skin, int *pi, int *pj, long cap);

#endif
