/* flux.h - the convective flux of one run (/observables/flux of its run file,
 * runfile.h) reduced to what the tools use: Phi through "the plane" (the mean of Phi over the height lines in a
 * band of the bed, default its middle, 0.4-0.6 of the settled surface height) per
 * period, its mean over the periods after a transient, and the time-mean profile
 * Phi(D) over every line (Fig. 3). */
#ifndef LIB_FLUX_H
#define LIB_FLUX_H

#include <stddef.h>

#include "err.h"

typedef struct flux_opts {
	double band_lo, band_hi; /* plane band as fractions of the surface height */
	double skip;             /* fraction of the periods dropped as transient */
} flux_opts;

#define FLUX_OPTS_DEFAULT {0.4, 0.6, 0.2}

typedef struct flux_data {
	size_t P, L;              /* periods, lines */
	double *t, *f;            /* [P] end time and frequency of each period */
	double *phi;              /* [P x L] particles per period */
	double *h;                /* [L] line heights, cm above the bottom */
	double surface;           /* settled free-surface height, cm */
	size_t planned;           /* periods the whole run was to record (0: P); set by the
				   * caller for a run stopped by a failure, which holds fewer */
} flux_data;

/* SB_ENAN when a time, frequency, Phi or height is not a finite number. */
int flux_read(const char *path, flux_data *d, sb_err *e);
void flux_free(flux_data *d);
/* Lines [*l0, *l1) whose heights lie in the band (the nearest line when none does). */
void flux_band(const flux_data *d, const flux_opts *o, size_t *l0, size_t *l1);
/* Phi through the plane in period p. */
double flux_plane(const flux_data *d, size_t p, size_t l0, size_t l1);
/* First period after the transient: floor(skip * P), at most P - 1; of a run stopped
 * early (planned > P) floor(skip * planned), which is P or more when it stopped within
 * the transient: then it has no period after it. */
size_t flux_first(const flux_data *d, const flux_opts *o);
/* Mean plane Phi over the periods after the transient (NaN without such periods). */
double flux_summary(const flux_data *d, const flux_opts *o);
/* Time-mean Phi per line over the periods after the transient, into prof[L]. */
void flux_profile(const flux_data *d, const flux_opts *o, double *prof);

/* The mean plane flux (flux_summary) of run id's output in campaign directory dir
 * (lib/layout.h), NaN when its flux cannot be read; then *damaged says whether the
 * file is no complete run file either (h5sum_read refuses it), else 0. */
double flux_of_run(const char *dir, const char *id, const flux_opts *o, int *damaged);

#endif
