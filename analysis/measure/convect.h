/* convect.h - the strength of the convection rolls from one run's displacement field
 * (/observables/field, docs/model.md "Displacement field"), a measure that does not
 * depend on where the rolls sit. With periodic sides nothing pins the rolls to the box
 * centre, so the flux Phi = j_top - j_bot, which splits the crossings into a centre and
 * an outer half by x, can average to zero while the bed convects.
 *
 * Roll strength of a block: S = sqrt(sum n uy^2 / sum n) over the cells whose centre
 * height lies in the band LO*h_s .. HI*h_s (h_s the settled surface height), n the
 * cell's samples, uy its mean vertical displacement per period; S_u the same with
 * ux^2 + uy^2. Mass conservation makes the mean of uy over a row about 0, so this rms
 * is the rolls' amplitude wherever they are (a shift in x permutes the cells).
 * Note: uy of a cell is a mean over its n samples, so S^2 carries the sampling noise
 * var/n: a bed without rolls has a small S > 0, which falls with more periods per
 * block (field_periods); compare S across runs with the same field_periods.
 *
 * Per run: the mean of S over the blocks after the first floor(skip * blocks) (of a
 * failed run, the blocks its duration was to hold: a failure does not shorten the
 * transient); blocks whose band holds no sample are left out and counted.
 *
 * Persistence, the measure without the noise floor: C = the mean over neighbouring
 * blocks b, b+1 (both after the transient) of sum w uy_b uy_b+1 / sum w over the band's
 * cells with samples in both, w = min(n_b, n_b+1). The sampling noise of two blocks is
 * independent, so it averages out of C, while a roll that outlives a block contributes
 * its mean square: C estimates the square of the part of the flow that persists from
 * one block to the next (0 without rolls, A^2/2 for a steady roll uy = A sin). */
#ifndef AN_CONVECT_H
#define AN_CONVECT_H

#include <stddef.h>

#include "err.h"

typedef struct convect_cfg {
	double band_lo, band_hi; /* the band, fractions of the settled surface height */
	double skip;             /* fraction of the blocks dropped as transient */
} convect_cfg;

#define CONVECT_CFG_DEFAULT {0.3, 0.7, 0.2}

/* One run's field: [B][ny][nx] row-major, row r spans r*cell .. (r+1)*cell above the
 * floor, column c x0 + c*cell .. x0 + (c+1)*cell. */
typedef struct convect_field {
	size_t B, ny, nx;
	double cell, x0;     /* cm */
	double surface;      /* settled free-surface height h_s (cm) */
	long K;              /* periods per block */
	double *t;           /* [B] the block's end time (s) */
	double *ux, *uy, *n; /* [B * ny * nx] */
} convect_field;

/* One block's strength. */
typedef struct convect_block {
	double S, Su;  /* NaN when the band holds no sample */
	double w;      /* samples in the band (sum of n) */
	size_t cells;  /* cells of the band with samples */
} convect_block;

/* The strength of one block's cells ux, uy, n [ny * nx] (cell size cell) over the rows
 * whose centre (r + 1/2) cell lies in [ylo, yhi] (cm). Cells with n <= 0 (or a value
 * not finite) carry no weight. */
void convect_strength(const double *ux, const double *uy, const double *n, size_t ny, size_t nx, double cell,
		      double ylo, double yhi, convect_block *out);

/* The run's summary. */
typedef struct convect_run {
	size_t blocks;  /* recorded */
	size_t first;   /* the first block after the transient */
	size_t used;    /* blocks after it with samples in the band */
	size_t empty;   /* blocks after it without */
	size_t rows;    /* rows of the grid in the band */
	double S, Su;   /* means over the used blocks; NaN when none */
	double C;       /* persistence (cm^2 per period^2); NaN without a pair of blocks */
	size_t pairs;   /* neighbouring block pairs C rests on */
} convect_run;

/* The covariance of uy between two blocks [ny * nx] over the rows whose centre lies in
 * [ylo, yhi]: sum w uy_a uy_b / sum w, w = min(n_a, n_b), over the cells with samples
 * in both; NaN when there are none. */
double convect_cov(const double *uya, const double *na, const double *uyb, const double *nb, size_t ny, size_t nx,
		   double cell, double ylo, double yhi);

/* Summary of field f; planned = the blocks the whole run was to record (0: f->B), for a
 * run stopped by a failure. Returns 0, or 1 when no block is used (S = Su = NaN). */
int convect_summary(const convect_field *f, const convect_cfg *c, size_t planned, convect_run *r);

/* Reads /observables/field and the root attribute surface_height of a run file.
 * Returns 0; SB_EUSAGE (e set, nothing to free) when the file has no field group (the
 * run had field = no); SB_EIO when the file or its field cannot be read. */
int convect_read(const char *path, convect_field *f, sb_err *e);
void convect_free(convect_field *f);

#endif
