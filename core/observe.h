/* observe.h - the paper's observables, each off unless the scene asks for it and then
 * recorded into the run's journal/HDF5 (definitions: docs/model.md, "Observables"):
 *   flux      crossings of nlines height lines between stroboscopic samples, j_top in
 *             the central half, j_bot in the outer half, per period (Fig. 3, ramps);
 *   field     per-disk displacement between samples averaged on a grid of cells one
 *             mean diameter wide over blocks of field_periods periods (Fig. 1);
 *   ring      time average of sum |F| on grains 4.5-8 cm from the intruder (or a fixed
 *             point), all and lower half, and the granular temperature there;
 *   waiting   time until the intruder first rises one diameter above its settled
 *             height (always on when there is an intruder; one compare per step).
 * An observable that is off allocates nothing and is never called. */
#ifndef SB_OBSERVE_H
#define SB_OBSERVE_H

#include "err.h"
#include "journal.h"
#include "params.h"
#include "state.h"

typedef struct sb_obs {
	int flux_on, field_on, ring_on;
	double x0, x1, surface;      /* inner box faces and free surface at t = 0 */
	double *xp, *yp;             /* previous stroboscopic sample (box frame) */
	int have_prev, nm;
	/* flux */
	int nlines;
	double *hline;
	double *jtop, *jbot;         /* this period's counts per line */
	/* field */
	int nx, ny, K, kdone;
	double cell, *sx, *sy, *cnt;
	/* ring */
	double rin, rout, ring_x, ring_y;
	int ring_every;
	double *fabs_sum;            /* sum |F| per disk, filled by the force kernel */
	double acc[8];               /* time sums: mean|F|, mean|F| lower, sum|F|, sum|F| lower,
				      * T, T lower, grains, grains lower */
	long ring_samples;
	/* waiting time */
	int risen;
	double wait_time, rise_height;
	/* the largest overlap of the shaking, a result of every run: the fraction of the
	 * smaller radius, when, which disks (ids), and where (midpoint of the centres,
	 * box frame); ov_max = 0 while no two disks have touched */
	double ov_max, ov_t, ov_x, ov_y;
	int ov_i, ov_j;
	/* the flux in a band of lines per period (the flux stop rule): the last period's,
	 * and the sums over the periods after the transient */
	int band_l0, band_l1, have_band;
	double band_last, band_n, band_sum, band_sum2;
	/* a stop rule that fired: the step the run ends with (0: none) and which */
	long stop_step;
	int stop_rule;
} sb_obs;

/* Set up from the scene and the prepared state (t = 0). intruder: index or -1. */
int obs_init(sb_obs *o, const sb_scene *sc, const sb_state *st, int intruder, double surface,
	     double x0, double x1, sb_err *e);
void obs_free(sb_obs *o);

/* The running mean of the band's flux: add the last period's (after the transient),
 * and its standard error (infinite below min_n periods). */
void obs_band_add(sb_obs *o);
double obs_band_se(const sb_obs *o, double min_n);

/* Record sizes, for the journal and the HDF5 layout. */
int obs_flux_len(const sb_obs *o);   /* t, f, jtop[nl], jbot[nl] */
int obs_field_len(const sb_obs *o);  /* t, periods, sx[ny*nx], sy[..], cnt[..] */

/* A stroboscopic sample at time t (phase 0, box at rest position: lab = box frame),
 * drive frequency f. Writes JR_FLUX / JR_FIELD records when due; returns the
 * number of records written through *nflux, *nfield. */
int obs_sample(sb_obs *o, const sb_state *st, double t, double f, sb_journal *jr, long *nflux,
	       long *nfield, sb_err *e);

/* Ring average over the disks' |F| sums in o->fabs_sum (then cleared), intruder
 * position (box frame) if any. */
void obs_ring(sb_obs *o, const sb_state *st, int intruder, double inv_dt);

/* Serialise the accumulators for a checkpoint: io(ctx, pointer, bytes) per field. */
void obs_fields(sb_obs *o, void *ctx, void (*io)(void *, void *, size_t));

#endif
