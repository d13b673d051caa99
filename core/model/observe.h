/* observe.h - the paper's observables, each off unless the scene asks for it and then
 * recorded into the run's journal/HDF5 (definitions: docs/model.md, "Observables"):
 *   flux      crossings of nlines height lines between stroboscopic samples, j_top in
 *             the central half, j_bot in the outer half, per period (Fig. 3, ramps);
 *   field     per-disk displacement between samples averaged on a grid of cells one
 *             mean diameter wide over blocks of field_periods periods (Fig. 1);
 *   ring      grains 4.5-8 cm from the intruder (or a fixed point, box frame), sampled
 *             at ring_rate: mean sum |F| of the contact forces, mean |net force|,
 *             granular temperature, count and centre as a series (one journal record
 *             per sample), averaged over the run and over the window before the rise;
 *   waiting   the waiting time (docs/model.md, "Waiting time"; always on when there
 *             is an intruder; one compare per step).
 * An observable that is off allocates nothing and is never called. */
#ifndef SB_OBSERVE_H
#define SB_OBSERVE_H

#include "err.h"
#include "params.h"
#include "state.h"

/* The ring's sums over its samples: of the per-sample mean over the ring's grains of
 * sum |F| (MEAN), of the sum over the ring (SUM), of the granular temperature (T), of
 * the grain count (N), of the mean |net force| (NET); _LO: the grains below the centre. */
enum { OBS_RA_MEAN, OBS_RA_MEAN_LO, OBS_RA_SUM, OBS_RA_SUM_LO, OBS_RA_T, OBS_RA_T_LO, OBS_RA_N, OBS_RA_N_LO,
       OBS_RA_NET, OBS_RA_NET_LO, OBS_RING_ACC };
/* ... and over the samples of the window before the rise (whole ring only) */
enum { OBS_RB_MEAN, OBS_RB_NET, OBS_RB_T, OBS_RB_N, OBS_RB_SUM, OBS_RING_BEFORE };
/* A sample's series row (the ring's journal record, record.h): time, mean sum |F|,
 * mean |net force|, temperature, grains, centre x, centre y (box frame). */
enum { OBS_RR_TIME, OBS_RR_MEAN, OBS_RR_NET, OBS_RR_T, OBS_RR_N, OBS_RR_CX, OBS_RR_CY, OBS_RING_COLS };

typedef struct sb_obs {
	int flux_on, field_on, ring_on;
	double x0, x1, surface;      /* inner box faces and free surface at t = 0 */
	double period;               /* periodic sides: x0 = 0, x1 = period; 0: walls */
	double *xmid;                /* periodic flux: each disk's x midpoint between samples */
	double *xp, *yp;             /* previous stroboscopic sample (box frame) */
	int have_prev, nm;
	/* flux */
	int nlines;
	double *hline;
	double *jtop, *jbot;         /* this period's counts per line */
	/* field */
	int nx, ny, K, kdone;
	double cell, *sx, *sy, *cnt;
	/* ring (docs/model.md, "Ring force") */
	double rin, rout, ring_x, ring_y; /* the centre (box frame) unless it follows */
	int ring_follow;             /* 1: the centre is the intruder's, sample by sample */
	int ring_every;              /* > 0: a sample every this many steps, else at ring_rate */
	double ring_interval, ring_dt; /* 1 / ring_rate, the time step */
	double ring_from, ring_until, gravity;
	double *fabs_sum;            /* sum |F| per disk, filled by the force kernel */
	double acc[OBS_RING_ACC];    /* sums over every sample (OBS_RA_*) */
	double before[OBS_RING_BEFORE]; /* sums over the samples before the rise (OBS_RB_*) */
	long ring_samples, ring_before; /* samples (= series rows), and those before the rise */
	double ring_before_end;      /* time of the last sample before the rise */
	/* waiting time */
	int risen;
	double wait_time, rise_height;
	/* several intruders (docs/model.md, "Several intruders"): every intruder's index
	 * (the first the one above), settled height, rise and waiting time; nint = 0 or 1:
	 * none of these arrays (a run of one intruder keeps its checkpoint's bytes) */
	int nint;
	int *iidx, *irisen;
	double *iy0, *irise_h, *iwait;
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

/* The flux stop rule's verdict on the band's running mean (docs/model.md, "Stop
 * rules"): 1 when it is answered. With thr > 0, once the interval mean +- k SE
 * lies wholly on one side of |Phi| = thr (both ends at or above thr in magnitude
 * and of one sign, or both within -thr..thr); with thr = 0, once SE < se. Never
 * below min_n periods. */
int obs_band_answered(const sb_obs *o, double min_n, double se, double thr, double k);

/* Record sizes, for the journal and the HDF5 layout. */
int obs_flux_len(const sb_obs *o);   /* t, f, jtop[nl], jbot[nl] */
int obs_field_len(const sb_obs *o);  /* t, periods, sx[ny*nx], sy[..], cnt[..] */

/* A stroboscopic sample at time t (phase 0, box at rest position: lab = box frame),
 * drive frequency f, in three parts: the flux since the previous sample (a flux
 * record), the field (a field record when a block is complete), then the sample kept
 * for the next one. The records go where the caller wants them (the run's journal:
 * core/run/sample.c, which knows their tags); this module keeps the accumulators.
 * obs_flux_due: flux is on and there is a previous sample; then obs_flux writes the
 * record into rec[obs_flux_len] and starts the next period's counts.
 * obs_field_add: adds the displacements since the previous sample (field on, a previous
 * sample); 1 when a block is complete, then obs_field_take writes the record into
 * rec[obs_field_len] and starts the next block. */
int obs_flux_due(const sb_obs *o);
void obs_flux(sb_obs *o, const sb_state *st, double t, double f, double *rec);
int obs_field_add(sb_obs *o, const sb_state *st);
void obs_field_take(sb_obs *o, double t, double *rec);
void obs_strobe_keep(sb_obs *o, const sb_state *st);

/* Is a ring sample due at step n? */
int obs_ring_due(const sb_obs *o, long n);

/* A ring sample at time t from the disks' |F| sums in o->fabs_sum (then cleared) and
 * their contact forces in st->f (the step's, unfused): added to the averages, its
 * series row in row[OBS_RING_COLS] (the ring's record, journaled by core/run/sample.c). */
void obs_ring_sample(sb_obs *o, const sb_state *st, int intruder, double t, double inv_dt, double *row);

/* The grains' segregation index S (docs/model.md, "Segregation index"): the grains are
 * the disks of kind KIND_GRAIN among the first n, large when their radius is above
 * split, their heights y; D = mean height of the large minus that of the small, and
 * S = D / D_max for D >= 0, D / |D_min| for D < 0, where D_max (D_min) is D for the same
 * heights with the large grains all on top (all at the bottom): +1 and -1 exactly there,
 * 0 at equal mean heights, in [-1, 1] always. work holds n doubles. 0 when either size
 * is missing or the heights are all equal (D_max = D_min = 0). */
double obs_segregation(const double *y, const double *r, const unsigned char *kind, int n, double split, double *work);
/* The radius that divides a bed's large grains from its small: the midpoint of the
 * smallest and largest grain radius among the first n disks; 0 when the grains are of
 * one size (or there are none), for which no index is defined. */
int obs_segregation_split(const double *r, const unsigned char *kind, int n, double *split);

/* Intruder k's rise (0 or 1) and its waiting time (NAN while it has not risen), k <
 * max(nint, 1): the first's the scalars above, the others' the arrays. */
int obs_intruder_risen(const sb_obs *o, int k, double *wait);

/* Serialise the accumulators for a checkpoint: io(ctx, pointer, bytes) per field. */
void obs_fields(sb_obs *o, void *ctx, void (*io)(void *, void *, size_t));

#endif
