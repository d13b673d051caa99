/* record.c - the table of recorded quantities (core/record.h) against the parameter
 * table and the journal: every row's key is a rate in Hz or a switch, its tag leads
 * back to it, a fixed record's columns are as many as its length with time first, its
 * group is where the readers look; and rec_on follows the key both ways. */
#include <string.h>

#include "record.h"
#include "sim.h"
#include "testlib.h"

int main(void)
{
	{
		const char *why = rec_table_check();
		CHECK("record.table_invariants", !why, "%s", why); /* asserted at sim_init in the test build */
	}
	const sb_record *R = rec_table();
	char id[128];
	for (int k = 0; k < REC_N; k++) {
		const sb_record *r = &R[k];
		const sb_param *p = params_find(r->key);
		snprintf(id, sizeof id, "record.%s.key", r->name);
		CHECK(id,
		      p && (r->clock == RC_RATE    ? p->type == PT_REAL && !strcmp(p->unit, "Hz")
			    : r->clock == RC_PHASE ? p->type == PT_INT && p->min == 0
						   : p->type == PT_BOOL),
		      "key '%s' of a row of clock %d", r->key, (int)r->clock);
		snprintf(id, sizeof id, "record.%s.tag", r->name);
		CHECK(id, rec_by_tag(r->tag) == k, "tag %d leads to row %d", r->tag, rec_by_tag(r->tag));
		snprintf(id, sizeof id, "record.%s.columns", r->name);
		CHECK(id,
		      r->len > 0 ? r->ncols == r->len && !strcmp(r->cols[0].name, "time") && !strcmp(r->cols[0].unit, "s")
				 : r->vlen != NULL,
		      "len %d, %d columns", r->len, r->ncols);
		snprintf(id, sizeof id, "record.%s.group", r->name);
		CHECK(id,
		      r->h5[0] == '/' && !(r->flags & RECF_OBS) == !!strncmp(r->h5, REC_H5_OBS "/", strlen(REC_H5_OBS) + 1),
		      "group %s", r->h5);
		snprintf(id, sizeof id, "record.%s.sampler", r->name);
		CHECK(id, r->sample != NULL, "no sampling function");
		for (int j = 0; j < k; j++) {
			snprintf(id, sizeof id, "record.%s.unique_vs_%s", r->name, R[j].name);
			CHECK(id, strcmp(r->h5, R[j].h5) && strcmp(r->name, R[j].name) && r->tag != R[j].tag,
			      "shares a name, group or tag");
		}
	}
	CHECK("record.tag.unknown", rec_by_tag(0) == -1 && rec_by_tag(99) == -1, "a tag no row has");

	/* rec_on reads the key: a rate of 0 is off, any other on; a switch likewise; the
	 * trajectory needs an intruder */
	static sb_sim s;
	params_defaults(&s.sc);
	s.intruder = -1;
	s.sc.traj_rate = 100;
	CHECK("record.on.off_by_default", !rec_on(&s, REC_ENERGY) && !rec_on(&s, REC_FLUX) && !rec_on(&s, REC_KINETIC),
	      "on");
	CHECK("record.on.trajectory_needs_an_intruder", !rec_on(&s, REC_TRAJ), "on without an intruder");
	s.intruder = 0;
	s.sc.energy_rate = 50;
	s.sc.flux = 1;
	CHECK("record.on.by_key", rec_on(&s, REC_TRAJ) && rec_on(&s, REC_ENERGY) && rec_on(&s, REC_FLUX),
	      "traj %d energy %d flux %d", rec_on(&s, REC_TRAJ), rec_on(&s, REC_ENERGY), rec_on(&s, REC_FLUX));
	s.sc.bed_kinetic_samples = 8;
	CHECK("record.on.samples_per_period", rec_on(&s, REC_KINETIC) && rec_rate(&s, REC_KINETIC) == 8, "%d %g",
	      rec_on(&s, REC_KINETIC), rec_rate(&s, REC_KINETIC));
	CHECK("record.rate.is_the_key", rec_rate(&s, REC_ENERGY) == 50 && rec_rate(&s, REC_TRAJ) == 100, "%g %g",
	      rec_rate(&s, REC_ENERGY), rec_rate(&s, REC_TRAJ));

	/* a variable record's length: a contact frame of 3 contacts */
	const double frame[2] = {0.5, 3};
	CHECK("record.len.contact_frame", rec_len(&s, REC_CONTACT, frame) == 2 + 3 * JR_CONTACT_COLS, "%ld",
	      rec_len(&s, REC_CONTACT, frame));

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
