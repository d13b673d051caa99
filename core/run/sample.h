/* sample.h - the sampling of the recorded quantities: record.h's table says what each
 * is, this module binds each row to its sampling function, which takes one sample of
 * the corrected state at time t, journals it and counts it in s->rec_n. Definitions:
 * docs/model.md, "Observables"; layout: docs/output.md. */
#ifndef SB_SAMPLE_H
#define SB_SAMPLE_H

#include "sim.h"

/* A row's sampling: its function and, for a row of variable length (record.h: len 0),
 * the length of the record that starts at rec. */
typedef struct sb_sampler {
	int (*take)(sb_sim *s, double t, sb_err *e);
	long (*vlen)(const sb_sim *s, const double *rec);
} sb_sampler;

/* The samplers, REC_N rows indexed by enum rec_id. */
const sb_sampler *sample_table(void);
/* NULL, or the first invariant a row breaks: a sampling function for every row, a
 * length function for the variable rows and only those (asserted at sim_init in the
 * test build; rows: a copy its test breaks). */
const char *sample_table_check(void);
const char *sample_rows_check(const sb_sampler *rows, int n);

/* One sample of row id at time t. */
int sample_take(sb_sim *s, int id, double t, sb_err *e);
/* Does the run record row id (record.h's rec_on for its scene and intruder)? */
int sample_on(const sb_sim *s, int id);
/* The length of the record of row id that starts at rec. */
long sample_len(const sb_sim *s, int id, const double *rec);

/* One strobe of the flux and the field into journal jr (their records when due,
 * counted in *nflux, *nfield), then the sample kept for the next: what the run's
 * strobe does for these two rows, for the observables' tests. */
int sample_obs_strobe(sb_obs *o, const sb_state *st, double t, double f, sb_journal *jr, long *nflux, long *nfield,
		      sb_err *e);

#endif
