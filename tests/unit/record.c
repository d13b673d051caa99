/* record.c - the table of recorded quantities (core/scene/record.h) against the parameter
 * table and the journal: every row's key is a rate in Hz, a count per period or a
 * switch, an output key of the parameter table; its tag leads back to it; every row
 * has its sampler (core/run/sample.c); a fixed record's columns are as many as its length
 * with time first, its group is where the readers look; rec_on follows the key both
 * ways; the summaries belong to rows that can write them. */
#include <stddef.h>
#include <string.h>

#include "record.h"
#include "sample.h"
#include "testlib.h"

int main(void)
{
	{
		const char *why = rec_table_check();
		CHECK("record.table_invariants", !why, "%s", why); /* asserted at sim_init in the test build */
	}
	const sb_record *R = rec_table();
	char id[128];
	{ /* the check can fail: a copy of the table with one invariant broken at a time */
		static sb_record B[REC_N];
		static const rec_col notime[] = {{"kinetic_energy", "erg"}, {"time", "s"}};
#define BROKEN(name, change)                                                                                     \
	do {                                                                                                     \
		memcpy(B, R, sizeof B);                                                                          \
		change;                                                                                          \
		const char *why_ = rec_rows_check(B, REC_N);                                                     \
		CHECK("record.check." name, why_ != NULL, "a table with " name " passes");                      \
	} while (0)
		BROKEN("an_unknown_key", B[REC_ENERGY].key = "energy_rat");
		BROKEN("a_key_of_another_type", B[REC_KINETIC].key = "energy_rate");
		BROKEN("columns_not_its_length", B[REC_ENERGY].len = 6);
		BROKEN("a_first_column_not_time", (B[REC_KINETIC].cols = notime, B[REC_KINETIC].ncols = 2));
		BROKEN("a_variable_row_per_period", (B[REC_FLUX].clock = RC_PHASE, B[REC_FLUX].key = "bed_kinetic_samples"));
		BROKEN("a_shared_group", B[REC_KINETIC].h5 = B[REC_ENERGY].h5);
		BROKEN("a_summary_of_no_observable", B[REC_KINETIC].flags = 0);
#undef BROKEN
		memcpy(B, R, sizeof B);
		CHECK("record.check.the_copy_passes", rec_rows_check(B, REC_N) == NULL, "%s", rec_rows_check(B, REC_N));
	}
	{ /* the samplers' check, likewise */
		const char *why = sample_table_check();
		CHECK("record.samplers", !why, "%s", why);
		static sb_sampler S[REC_N];
#define BROKEN(name, change)                                                                                     \
	do {                                                                                                     \
		memcpy(S, sample_table(), sizeof S);                                                             \
		change;                                                                                          \
		CHECK("record.samplers.check." name, sample_rows_check(S, REC_N) != NULL, "samplers with " name " pass"); \
	} while (0)
		BROKEN("a_variable_row_without_length", S[REC_FLUX].vlen = NULL);
		BROKEN("a_fixed_row_with_a_length", S[REC_ENERGY].vlen = S[REC_FLUX].vlen);
		BROKEN("no_sampler", S[REC_RING].take = NULL);
#undef BROKEN
		CHECK("record.samplers.check.too_few", sample_rows_check(sample_table(), REC_N - 1) != NULL, "passes");
	}
	const sb_sampler *SAM = sample_table();
	for (int k = 0; k < REC_N; k++) {
		const sb_record *r = &R[k];
		const sb_param *p = params_find(r->key);
		snprintf(id, sizeof id, "record.%s.key", r->name);
		CHECK(id,
		      p && (r->clock == RC_RATE    ? p->type == PT_REAL && !strcmp(p->unit, "Hz")
			    : r->clock == RC_PHASE ? p->type == PT_INT && p->min == 0
						   : p->type == PT_BOOL),
		      "key '%s' of a row of clock %d", r->key, (int)r->clock);
		snprintf(id, sizeof id, "record.%s.key_is_output", r->name);
		CHECK(id, p && (p->flags & PF_OUT), "key '%s' is no output key", r->key);
		snprintf(id, sizeof id, "record.%s.tag", r->name);
		CHECK(id, REC_TAG(k) > 0 && rec_by_tag(REC_TAG(k)) == k, "tag %d leads to row %d", REC_TAG(k),
		      rec_by_tag(REC_TAG(k)));
		snprintf(id, sizeof id, "record.%s.columns", r->name);
		CHECK(id,
		      r->len > 0 ? r->ncols == r->len && !strcmp(r->cols[0].name, "time") && !strcmp(r->cols[0].unit, "s")
				 : SAM[k].vlen != NULL,
		      "len %d, %d columns", r->len, r->ncols);
		snprintf(id, sizeof id, "record.%s.group", r->name);
		CHECK(id,
		      r->h5[0] == '/' && !(r->flags & RECF_OBS) == !!strncmp(r->h5, REC_H5_OBS "/", strlen(REC_H5_OBS) + 1),
		      "group %s", r->h5);
		snprintf(id, sizeof id, "record.%s.sampler", r->name);
		CHECK(id, SAM[k].take != NULL, "no sampling function");
		for (int j = 0; j < k; j++) {
			snprintf(id, sizeof id, "record.%s.unique_vs_%s", r->name, R[j].name);
			CHECK(id, strcmp(r->h5, R[j].h5) && strcmp(r->name, R[j].name), "shares a name or group");
		}
	}
	CHECK("record.tag.unknown", rec_by_tag(0) == -1 && rec_by_tag(REC_TAG(REC_N)) == -1 && rec_by_tag(-3) == -1,
	      "a tag no row has");

	/* rec_on reads the key: a rate of 0 is off, any other on; a switch likewise; the
	 * trajectory needs an intruder, the intruders' positions two */
	static sb_sim s;
	params_defaults(&s.sc);
	s.intruder = -1;
	s.sc.traj_rate = 100;
	CHECK("record.on.off_by_default",
	      !sample_on(&s, REC_ENERGY) && !sample_on(&s, REC_FLUX) && !sample_on(&s, REC_KINETIC) && !sample_on(&s, REC_HEIGHT),
	      "on");
	CHECK("record.on.trajectory_needs_an_intruder", !sample_on(&s, REC_TRAJ), "on without an intruder");
	s.intruder = 0;
	s.n_intruders = 1;
	s.sc.energy_rate = 50;
	s.sc.flux = 1;
	CHECK("record.on.by_key", sample_on(&s, REC_TRAJ) && sample_on(&s, REC_ENERGY) && sample_on(&s, REC_FLUX),
	      "traj %d energy %d flux %d", sample_on(&s, REC_TRAJ), sample_on(&s, REC_ENERGY), sample_on(&s, REC_FLUX));
	s.sc.bed_kinetic_samples = 8;
	CHECK("record.on.samples_per_period", sample_on(&s, REC_KINETIC) && rec_rate(&s.sc, REC_KINETIC) == 8, "%d %g",
	      sample_on(&s, REC_KINETIC), rec_rate(&s.sc, REC_KINETIC));
	s.sc.bed_height_samples = 3;
	CHECK("record.on.bed_height",
	      sample_on(&s, REC_HEIGHT) && rec_rate(&s.sc, REC_HEIGHT) == 3 && R[REC_HEIGHT].clock == RC_PHASE, "%d %g", sample_on(&s, REC_HEIGHT), rec_rate(&s.sc, REC_HEIGHT));
	/* several intruders' positions: at the trajectory's rate, with two intruders or more */
	CHECK("record.on.intruders_need_two", !sample_on(&s, REC_INTRUDERS), "on with one intruder");
	s.n_intruders = 2;
	CHECK("record.on.intruders", sample_on(&s, REC_INTRUDERS) && sample_len(&s, REC_INTRUDERS, NULL) == 5, "%d %ld",
	      sample_on(&s, REC_INTRUDERS), sample_len(&s, REC_INTRUDERS, NULL));
	CHECK("record.rate.is_the_key", rec_rate(&s.sc, REC_ENERGY) == 50 && rec_rate(&s.sc, REC_TRAJ) == 100, "%g %g",
	      rec_rate(&s.sc, REC_ENERGY), rec_rate(&s.sc, REC_TRAJ));

	/* a variable record's length: a contact frame of 3 contacts */
	const double frame[2] = {0.5, 3};
	CHECK("record.len.contact_frame", sample_len(&s, REC_CONTACT, frame) == 2 + 3 * REC_NCOLS(REC_COLS_CONTACT), "%ld",
	      sample_len(&s, REC_CONTACT, frame));

	/* a fixed row's length is its column list's (the samplers' row arrays) */
	CHECK("record.len.fixed", sample_len(&s, REC_TRAJ, NULL) == 6 && sample_len(&s, REC_ENERGY, NULL) == 7 &&
					  sample_len(&s, REC_KINETIC, NULL) == REC_NCOLS(REC_COLS_KINETIC),
	      "traj %ld energy %ld", sample_len(&s, REC_TRAJ, NULL), sample_len(&s, REC_ENERGY, NULL));

	/* every summary belongs to a row and has a name of its own */
	for (int k = 0; k < RSUM_N; k++) {
		snprintf(id, sizeof id, "record.summary.%s", rec_summary_attr(k));
		int dup = 0;
		for (int j = 0; j < k; j++)
			dup |= !strcmp(rec_summary_attr(j), rec_summary_attr(k));
		CHECK(id, rec_summary_row(k) >= 0 && rec_summary_row(k) < REC_N && !dup, "row %d, dup %d",
		      rec_summary_row(k), dup);
	}
	return tl_done();
}
