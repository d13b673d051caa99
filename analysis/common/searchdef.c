/* searchdef.c - an [onset] campaign's own onset definition and estimates, read from
 * the driver's tables (searchdef.h). */
#include "searchdef.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "drive.h"

static double col(sqlite3_stmt *st, int i)
{
	return sqlite3_column_type(st, i) == SQLITE_NULL ? NAN : sqlite3_column_double(st, i);
}

static void text(sqlite3_stmt *st, int i, char *buf, size_t n)
{
	const unsigned char *t = sqlite3_column_text(st, i);
	snprintf(buf, n, "%s", t ? (const char *)t : "");
}

int sdef_load(adb *d, const char *campaign, sdef *s, sb_err *e)
{
	memset(s, 0, sizeof *s);
	char cols[1024];
	sql_columns(&d->db, "onset_search", cols, sizeof cols);
	if (!strstr(cols, "threshold,"))
		return 0;
	sqlite3_stmt *st;
	if (sql_exec(&d->db, e, &st,
		     "SELECT observable, axis, threshold, band_lo, band_hi, skip, tolerance, level FROM onset_search"
		     " WHERE campaign = ?", "t", campaign))
		return e->code;
	if (sqlite3_step(st) == SQLITE_ROW) {
		char obs[16];
		text(st, 0, obs, sizeof obs);
		text(st, 1, s->axis, sizeof s->axis);
		if (!*s->axis) /* a database from before the axis: the frequency's */
			snprintf(s->axis, sizeof s->axis, "frequency");
		s->found = 1;
		s->flux = !strcmp(obs, "flux");
		s->threshold = col(st, 2);
		s->band_lo = col(st, 3);
		s->band_hi = col(st, 4);
		s->skip = col(st, 5);
		s->tolerance = col(st, 6);
		s->level = col(st, 7);
	}
	sqlite3_finalize(st);
	return 0;
}

/* The frequency at axis value x of a group one of whose runs is at (x0, f0): the
 * axis's own scaling (core/model/drive.h). */
static double to_hz(const char *axis, double x, double x0, double f0)
{
	return drive_axis_freq_from(drive_axis_kind(axis), x, x0, f0);
}

int sdef_group(adb *d, const char *campaign, const sdef *s, const char *const *ids, int n, sdef_est *g, sb_err *e)
{
	memset(g, 0, sizeof *g);
	g->est = g->lo = g->hi = g->bracket_lo = g->bracket_hi = NAN;
	if (!s->found)
		return 0;
	sqlite3_stmt *st;
	if (sql_exec(&d->db, e, &st, "SELECT grp FROM onset_run WHERE campaign = ? AND run = ?", "t", campaign))
		return e->code;
	for (int i = 0; i < n; i++) {
		sqlite3_reset(st);
		sqlite3_bind_text(st, 2, ids[i], -1, SQLITE_TRANSIENT);
		if (sqlite3_step(st) != SQLITE_ROW)
			continue;
		char grp[512];
		text(st, 0, grp, sizeof grp);
		if (!g->found)
			snprintf(g->grp, sizeof g->grp, "%s", grp);
		else if (strcmp(grp, g->grp))
			g->pooled = 1;
		g->found = 1;
	}
	sqlite3_finalize(st);
	if (!g->found || g->pooled)
		return 0;
	if (sql_exec(&d->db, e, &st,
		     "SELECT g.state, g.replicates, g.estimate, g.ci_lo, g.ci_hi, r.axis_value, r.frequency"
		     " FROM onset_group g LEFT JOIN onset_run r ON r.campaign = g.campaign AND r.grp = g.grp"
		     " AND r.axis_value > 0 WHERE g.campaign = ? AND g.grp = ? LIMIT 1", "tt", campaign, g->grp))
		return e->code;
	if (sqlite3_step(st) == SQLITE_ROW) {
		text(st, 0, g->state, sizeof g->state);
		g->replicates = sqlite3_column_int64(st, 1);
		double x = col(st, 2), lo = col(st, 3), hi = col(st, 4), x0 = col(st, 5), f0 = col(st, 6);
		g->est = to_hz(s->axis, x, x0, f0);
		g->bracket_lo = to_hz(s->axis, x - 0.5 * s->tolerance, x0, f0);
		g->bracket_hi = to_hz(s->axis, x + 0.5 * s->tolerance, x0, f0);
		g->lo = to_hz(s->axis, lo, x0, f0);
		g->hi = to_hz(s->axis, hi, x0, f0);
	}
	sqlite3_finalize(st);
	return 0;
}
