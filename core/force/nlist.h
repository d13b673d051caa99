/* nlist.h - neighbour search linear in N: a growable cell grid sized for the ordinary
 * disks and a Verlet list with a skin. Disks much larger than the rest (the intruder)
 * stay out of the cells and search the cells their own reach covers, so one big disk
 * never makes everybody's cells big. Wall-wall pairs are never formed. */
#ifndef SB_NLIST_H
#define SB_NLIST_H

#include "err.h"
#include "state.h"

typedef struct sb_nlist sb_nlist;

/* The candidate scan of one row of cells: appends to the flat list the pairs (i, j) of
 * the candidates k0..k1 (cell order, j = cell_idx[k], coordinates xs, ys, rs) with j > i
 * within reach ri of (xi, yi), in that order; returns the new count. The vector
 * kernel's instance provides one (kernel_scan); nlist_init sets the plain one. */
typedef int (*sb_scan_fn)(sb_nlist *nl, int i, double xi, double yi, double ri, int k0, int k1, int np);

struct sb_nlist {
	double skin;
	/* cell grid over the bounding box of all disks at the last build */
	int ncx, ncy, ccap;
	double x0, y0, cell, inv_cell;
	int *cell_start, *cell_idx; /* counting sort: disks of cell c are cell_idx[cell_start[c]..] */
	int *cell_of;
	int *cell_x, *cell_y;        /* the cell's column and row */
	int *cell_pos;               /* scratch of the counting sort */
	double *xs, *ys, *rs;       /* x, y, R of the disks in cell order (cell_idx); these and
				     * cell_idx have 8 spare slots, so a scan reads whole vectors */
	sb_scan_fn scan;
	/* The flat list the force kernel walks: the npairs pairs (i, j > i) of ordinary
	 * mobile i, in rows of ascending i (walls are j: they come after the mobile
	 * disks), then the nbig pairs of the large disks, any order */
	int *pi, *pj;               /* the disk indices, shifted left by pshift */
	int pshift;                 /* the force kernel's choice (kernel_pair_shift) */
	int npairs, nbig;
	int nflat, fcap;            /* npairs + nbig; padded with pairs (0, 0) to a multiple of 8 */
	/* Periodic sides (period > 0, else 0: walls, and nseam stays 0): the pairs that
	 * meet across x = 0 / period, kept apart from the flat list so that the kernel
	 * over it is the walls case's. Seam pair k is (si[k], sj[k]) with disk si's image
	 * at x + period within reach of disk sj (plain indices, no pshift; each pair of
	 * images once). */
	double period;
	int *si, *sj;
	int nseam, scap;
	/* which disks are large; fixed at setup */
	unsigned char *large;
	int *large_list, nlarge;
	double r_small;             /* largest radius among ordinary disks */
	/* positions at the last build: the rebuild rule and a checkpoint use them */
	double *xref, *yref;
	int cap;
	long builds;
};

/* Classify disks (large = radius above 1.5x the mean) and allocate; the list will
 * hold i << pshift for disk i (the force kernel's addressing, kernel.h). */
int nlist_init(sb_nlist *nl, const sb_state *st, double skin, int pshift, sb_err *e);
/* Periodic sides of period W (> 0) from the next build on: the seam pairs are listed
 * too. The positions must lie in [0, W) at a build (periodic_wrap_state). */
void nlist_set_period(sb_nlist *nl, double W);
void nlist_free(sb_nlist *nl);

/* Build from the given reference positions (normally the current ones, copied into
 * xref/yref first by nlist_build). */
int nlist_build_from_ref(sb_nlist *nl, const sb_state *st, sb_err *e);
int nlist_build(sb_nlist *nl, const sb_state *st, sb_err *e);

/* Brute-force O(N^2) list of pairs within r_i + r_j + skin, for tests: returns the
 * number of pairs, fills (pi, pj) with pi < pj when they are non-NULL. */
long nlist_brute(const sb_state *st, double skin, int *pi, int *pj, long cap);
/* The same for the pairs across the seam of period W: (i, j) with i's image at
 * x_i + W within r_i + r_j + skin of j, every ordered pair with i != j. */
long nlist_brute_seam(const sb_state *st, double skin, double W, int *pi, int *pj, long cap);

/* The list's invariants, which the force kernel's loads rely on (asserted after every
 * build in the test build): NULL, or the first one broken - every index a multiple of
 * 1 << pshift and a disk of the state (n disks, the first nm mobile); the ordinary
 * pairs (i < j, i mobile) in rows of ascending i; the padding to whole vectors of 8
 * pairs (0, 0). */
const char *nlist_check(const sb_nlist *nl, int n, int nm);

#endif
