/* searchdef.h - an [onset] campaign's own onset, as the study driver stored it (the
 * onset_search and onset_group tables, docs/database.md): the definition its search
 * classified runs by (threshold, band, skip), which bin/onset takes as its default so
 * that one campaign has one onset, and the search's estimate of each group beside the
 * tool's. The values are the driver's, parsed from the campaign file once by its
 * parser; nothing here reads the campaign file. */
#ifndef AN_SEARCHDEF_H
#define AN_SEARCHDEF_H

#include "err.h"
#include "adb.h"

typedef struct sdef {
	int found;              /* the campaign has a search (a row in onset_search) */
	int flux;               /* its observable is the flux (threshold, band, skip mean something) */
	char axis[16];          /* frequency, gamma or velocity: the unit of from, to, tolerance */
	double threshold;       /* |mean flux| at or above it is on (particles per period) */
	double band_lo, band_hi; /* fractions of the surface height */
	double skip;            /* fraction of the periods left out as transient */
	double tolerance;       /* a replicate's bracket at most this wide (axis unit) */
	double level;           /* the level of its interval */
} sdef;

/* The campaign's search definition; s->found = 0 when it has none (or the database
 * has no onset_search table: made before searches existed). */
int sdef_load(adb *d, const char *campaign, sdef *s, sb_err *e);

/* The search's estimate of one group of runs, in Hz. */
typedef struct sdef_est {
	int found;              /* 0: none of the runs is a run of the search */
	int pooled;             /* the runs belong to more than one search group: no estimate */
	char grp[512];          /* the search's group label */
	char state[16];         /* searching, done, max, blocked */
	long replicates;
	double est, lo, hi;     /* Hz; NaN when the search has none (no replicate answered,
				 * or the onset lies outside the range) */
	double bracket_lo, bracket_hi; /* Hz: one bisection bracket (tolerance) around est,
				 * the least its interval can be (resolve.h) */
} sdef_est;

/* The estimate of the search group that the runs ids[0..n) belong to (onset_run),
 * converted from the search's axis to Hz by the group's own runs (a point's
 * frequency is a power of its axis value: Gamma ~ f^2, v ~ f). */
int sdef_group(adb *d, const char *campaign, const sdef *s, const char *const *ids, int n, sdef_est *g, sb_err *e);

#endif
