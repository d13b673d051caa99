/* search.c - the [onset] search over the database and the run files: a run's class
 * (its rise, or its mean flux through the band against the threshold), the chains of
 * every replicate, the batches of replicates, the onset_* tables. */
#include "search.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "campaign/axes.h"
#include "flux.h"
#include "h5sum.h"
#include "layout.h"

void search_init(search *s, const campaign *c, const char *dir)
{
	memset(s, 0, sizeof *s);
	s->c = c;
	snprintf(s->dir, sizeof s->dir, "%s", dir);
}

static void groups_free(search *s)
{
	for (long i = 0; i < s->ngroups; i++)
		free(s->groups[i].reps);
	free(s->groups);
	s->groups = NULL;
	s->ngroups = 0;
	s->nsteps = 0;
}

void search_free(search *s)
{
	groups_free(s);
	free(s->steps);
	free(s->vals);
	memset(s, 0, sizeof *s);
}

const char *search_class_name(int cls)
{
	static const char *const names[] = {"off", "on", "pending", "failed"};
	return cls >= 0 && cls <= AD_FAILED ? names[cls] : "?";
}

/* ---- a run's class ---- */

static int by_id(const void *a, const void *b)
{
	return strcmp(((const srch_val *)a)->id, ((const srch_val *)b)->id);
}

static const srch_val *val_find(const search *s, const char *id)
{
	srch_val key;
	memcpy(key.id, id, 17);
	return s->nvals ? bsearch(&key, s->vals, (size_t)s->nvals, sizeof *s->vals, by_id) : NULL;
}

static void val_put(search *s, const char *id, int cls, double value)
{
	if (s->nvals == s->capvals) {
		long cap = s->capvals ? 2 * s->capvals : 64;
		srch_val *v = realloc(s->vals, sizeof *v * (size_t)cap);
		if (!v)
			return; /* only a cache: the file is read again next time */
		s->vals = v;
		s->capvals = cap;
	}
	long at = 0;
	while (at < s->nvals && strcmp(s->vals[at].id, id) < 0)
		at++;
	memmove(s->vals + at + 1, s->vals + at, sizeof *s->vals * (size_t)(s->nvals - at));
	memcpy(s->vals[at].id, id, 17);
	s->vals[at].cls = cls;
	s->vals[at].value = value;
	s->nvals++;
}

/* The mean flux through the band over the periods after the transient, as bin/onset
 * computes a run's Phi (lib/flux.c, one definition); NaN when the file has no
 * period after the transient or no flux records. *damaged when the file is missing or
 * is no complete run file: the sweep moves it aside and the run runs again, so its
 * chain waits for it (a blocked chain could add a batch of replicates that the results
 * do not ask for). */
static double run_flux(const search *s, const char *id, int *damaged)
{
	flux_opts o = {s->c->onset.band_lo, s->c->onset.band_hi, s->c->onset.skip};
	return flux_of_run(s->dir, id, &o, damaged);
}

/* A run's class from its state and results. A run that the engine stopped on physics
 * while shaking is classified by what its failure means (adapt_failure_class: grains
 * thrown out of the box are "on"); any other failure stops its chain, and *why says which (its
 * status and message). An intruder that rose before a failure did rise; a failed run's
 * flux is not used: its periods end where the physics broke down. Only a finished
 * run's flux is kept between passes: a failed run may be run again (--retry-failed),
 * and a done run that is run again (its file was damaged) ends the same, to the bit. */
static int classify(search *s, sqlite3_stmt *q, const char *id, double *value, char *why, size_t len)
{
	*value = NAN;
	why[0] = 0;
	const srch_val *v = val_find(s, id);
	if (v) {
		*value = v->value;
		return v->cls;
	}
	sqlite3_reset(q);
	sqlite3_bind_text(q, 2, id, -1, SQLITE_TRANSIENT);
	if (sqlite3_step(q) != SQLITE_ROW)
		return AD_WAIT; /* not recorded yet: the next run of its chain */
	const char *st = (const char *)sqlite3_column_text(q, 0);
	int failed = st && !strcmp(st, "failed");
	if (!st || (strcmp(st, "done") && !failed))
		return AD_WAIT;
	const char *status = (const char *)sqlite3_column_text(q, 2), *msg = (const char *)sqlite3_column_text(q, 3);
	/* only a failure while shaking says something of the drive: a bed that spills
	 * while it settles (no step of shaking) fails the same at every frequency */
	int shaken = sqlite3_column_int64(q, 4) > 0;
	int fcls = failed && shaken ? adapt_failure_class(status) : AD_FAILED;
	if (failed)
		snprintf(why, len, "%s%s%s%s", status ? status : "failed", shaken ? "" : " before shaking",
			 msg && *msg ? ": " : "", msg ? msg : "");
	if (s->c->onset.observable == CP_OBS_RISE) {
		int has = sqlite3_column_type(q, 1) != SQLITE_NULL;
		long risen = (long)sqlite3_column_int64(q, 1);
		*value = has ? (double)risen : NAN;
		if (has && risen)
			return AD_ON;
		if (failed)
			return fcls;
		if (!has)
			snprintf(why, len, "done without a rise recorded");
		return has ? AD_OFF : AD_FAILED;
	}
	if (failed)
		return fcls;
	int damaged;
	*value = run_flux(s, id, &damaged);
	if (damaged)
		return AD_WAIT;
	if (isnan(*value))
		snprintf(why, len, "done without a period of flux after the transient");
	int cls = isnan(*value) ? AD_FAILED : fabs(*value) >= s->c->onset.threshold ? AD_ON : AD_OFF;
	val_put(s, id, cls, *value);
	return cls;
}

/* ---- the chains ---- */

struct walk {
	search *s;
	grid *g;
	sqlite3_stmt *q;
	long group, replicate;
	int step;
	sb_err *e;
	const sb_scene *scene; /* the group's: its amplitude gives the frequency of a point */
};

static int look(void *ctx, double x)
{
	struct walk *w = ctx;
	search *s = w->s;
	char id[17], why[300];
	double f = grid_onset_frequency(s->c, w->scene, x);
	if (w->e->code || grid_add(w->g, w->group, w->replicate, f, id, w->e))
		return AD_WAIT;
	double value;
	int cls = classify(s, w->q, id, &value, why, sizeof why);
	srch_group *gr = &s->groups[w->group];
	if (cls == AD_FAILED && !gr->reason[0]) {
		char at[64];
		if (s->c->onset.axis == AXIS_FREQUENCY)
			snprintf(at, sizeof at, "%.12g Hz", f);
		else
			snprintf(at, sizeof at, "%s %.12g (%.12g Hz)", drive_axis_name(s->c->onset.axis), x, f);
		snprintf(gr->reason, sizeof gr->reason, "replicate %ld at %s: %s", w->replicate, at, why);
	}
	if (s->nsteps == s->capsteps) {
		long cap = s->capsteps ? 2 * s->capsteps : 256;
		srch_step *n = realloc(s->steps, sizeof *n * (size_t)cap);
		if (!n) {
			sb_errf(w->e, SB_ENOMEM, "out of memory");
			return AD_WAIT;
		}
		s->steps = n;
		s->capsteps = cap;
	}
	srch_step *st = &s->steps[s->nsteps++];
	st->group = w->group;
	st->replicate = w->replicate;
	st->step = w->step++;
	st->x = x;
	st->f = f;
	memcpy(st->id, id, 17);
	st->cls = cls;
	st->value = value;
	s->groups[w->group].runs++;
	return cls;
}

static ad_plan plan_of(const cp_onset *o)
{
	ad_plan p = {o->autorep, o->replicates, o->max_replicates, o->batch, o->target, o->level};
	return p;
}

int search_derive(search *s, grid *g, st_db *db, sb_err *e)
{
	const campaign *c = s->c;
	const cp_onset *o = &c->onset;
	groups_free(s);
	s->groups = calloc((size_t)(g->points ? g->points : 1), sizeof *s->groups);
	if (!s->groups)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	s->ngroups = g->points;
	sqlite3_stmt *q;
	if (sql_exec(db, e, &q,
		    "SELECT r.state, s.risen, a.status, a.message, s.steps FROM run r"
		    " LEFT JOIN result s ON s.campaign = r.campaign AND s.run = r.id"
		    " LEFT JOIN attempt a ON a.campaign = r.campaign AND a.run = r.id"
		    "  AND a.n = (SELECT MAX(n) FROM attempt b WHERE b.campaign = r.campaign AND b.run = r.id)"
		    " WHERE r.campaign = ?1 AND r.id = ?2",
		    "t", c->name))
		return e->code;
	ad_range range = {o->from, o->to, o->tolerance};
	ad_plan plan = plan_of(o);
	for (long p = 0; p < s->ngroups && !e->code; p++) {
		srch_group *gr = &s->groups[p];
		grid_point_label(c, p, gr->label, sizeof gr->label);
		sb_scene scene;
		grid_point_scene(c, p, &scene);
		long n = adapt_first(&plan), want;
		for (;;) {
			ad_rep *nr = realloc(gr->reps, sizeof *nr * (size_t)n);
			if (!nr) {
				sb_errf(e, SB_ENOMEM, "out of memory");
				break;
			}
			gr->reps = nr;
			for (long i = gr->nrep; i < n && !e->code; i++) {
				struct walk w = {s, g, q, p, i + 1, 0, e, &scene};
				adapt_walk(&range, look, &w, &gr->reps[i]);
			}
			gr->nrep = n;
			gr->state = adapt_group(&plan, gr->reps, n, &gr->iv, &want);
			if (gr->state != AD_G_MORE || e->code)
				break;
			n = want; /* the answer is not sharp enough: the next batch of replicates */
		}
	}
	sqlite3_finalize(q);
	grid_sort(g);
	return e->code;
}

int search_done(const search *s)
{
	for (long i = 0; i < s->ngroups; i++)
		if (s->groups[i].state == AD_G_SEARCHING)
			return 0;
	return 1;
}

struct member_map {
	const campaign *c;
	sb_scene scene;
};

static double member_map(void *ctx, double x)
{
	struct member_map *m = ctx;
	return grid_onset_frequency(m->c, &m->scene, x);
}

int search_member(const campaign *c, long points, long replicate, double frequency, const char *id)
{
	const cp_onset *o = &c->onset;
	ad_range range = {o->from, o->to, o->tolerance};
	if (replicate < 1 || replicate > AD_MAX_REPLICATES)
		return 0;
	if (o->axis == AXIS_FREQUENCY && !adapt_member(&range, frequency))
		return 0;
	for (long p = 0; p < points; p++) {
		if (o->axis != AXIS_FREQUENCY) {
			/* each group has its own frequencies: the point's amplitude maps them */
			struct member_map m = {c, {0}};
			grid_point_scene(c, p, &m.scene);
			if (!adapt_member_map(&range, frequency, member_map, &m))
				continue;
		}
		char want[17];
		grid_onset_id(c, p, replicate, frequency, want);
		if (!strcmp(want, id))
			return 1;
	}
	return 0;
}

/* ---- the onset_* tables ---- */

/* An end that bounds nothing (+-inf) or a number that does not exist is NULL. */
static int bounded(double x)
{
	return isfinite(x);
}

int search_store(const search *s, st_db *db, sb_err *e)
{
	const campaign *c = s->c;
	const cp_onset *o = &c->onset;
	char now[32], reps[32];
	db_now(now, sizeof now);
	if (o->autorep)
		snprintf(reps, sizeof reps, "auto");
	else
		snprintf(reps, sizeof reps, "%ld", o->replicates);
	if (db_begin(db, e))
		return e->code;
	static const char *const clear[] = {"DELETE FROM onset_search WHERE campaign = ?",
					    "DELETE FROM onset_group WHERE campaign = ?",
					    "DELETE FROM onset_replicate WHERE campaign = ?",
					    "DELETE FROM onset_run WHERE campaign = ?"};
	for (size_t i = 0; i < sizeof clear / sizeof *clear && !e->code; i++)
		sql_exec(db, e, NULL, clear[i], "t", c->name);
	int flux = o->observable == CP_OBS_FLUX, blocked = 0;
	for (long p = 0; p < s->ngroups; p++)
		blocked += s->groups[p].state == AD_G_BLOCKED;
	/* freq_from, freq_to, tolerance and target are in the axis's unit (the name of
	 * the first two is older than the axis) */
	sql_exec(db, e, NULL,
		"INSERT INTO onset_search(campaign, observable, axis, freq_from, freq_to, tolerance, threshold, band_lo,"
		" band_hi, skip, replicates, max_replicates, batch, target, level, state, updated)"
		" VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
		"tttdddDDDDtllDdtt", c->name, flux ? "flux" : "rise", drive_axis_name(o->axis), o->from, o->to, o->tolerance,
		flux, o->threshold, flux, o->band_lo, flux, o->band_hi, flux, o->skip, reps,
		o->autorep ? o->max_replicates : o->replicates, o->autorep ? o->batch : o->replicates, o->autorep,
		o->target, o->level, !search_done(s) ? "searching" : blocked ? "blocked" : "done", now);
	for (long p = 0; p < s->ngroups && !e->code; p++) {
		const srch_group *gr = &s->groups[p];
		long count[AD_BLOCKED + 1] = {0}, nonmono = 0;
		for (long i = 0; i < gr->nrep; i++) {
			const ad_rep *r = &gr->reps[i];
			count[r->state]++;
			nonmono += r->nonmonotone;
			sql_exec(db, e, NULL,
				"INSERT INTO onset_replicate(campaign, grp, replicate, state, lo, hi, lo_run, hi_run, next,"
				" runs, nonmonotone) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
				"ttltDDllDll", c->name, gr->label, i + 1, adapt_state_name(r->state), bounded(r->lo), r->lo,
				bounded(r->hi), r->hi, (long)r->lo_seen, (long)r->hi_seen, bounded(r->next), r->next,
				(long)r->nobs + (r->state == AD_SEARCHING || r->state == AD_BLOCKED), (long)r->nonmonotone);
		}
		const ad_interval *iv = &gr->iv;
		sql_exec(db, e, NULL,
			"INSERT INTO onset_group(campaign, grp, point, replicates, searching, found, below, above, blocked,"
			" nonmonotone, runs, estimate, ci_lo, ci_hi, width, state, reason)"
			" VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
			"ttlllllllllDDDDtt", c->name, gr->label, p, gr->nrep, count[AD_SEARCHING], count[AD_FOUND],
			count[AD_BELOW], count[AD_ABOVE], count[AD_BLOCKED], nonmono, gr->runs, bounded(iv->est), iv->est,
			bounded(iv->lo), iv->lo, bounded(iv->hi), iv->hi, bounded(iv->width), iv->width,
			adapt_gstate_name(gr->state), gr->state == AD_G_BLOCKED ? gr->reason : NULL);
	}
	for (long i = 0; i < s->nsteps && !e->code; i++) {
		const srch_step *st = &s->steps[i];
		sql_exec(db, e, NULL,
			"INSERT OR REPLACE INTO onset_run(campaign, run, grp, replicate, step, axis_value, frequency, value,"
			" class) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)",
			"tttllddDt", c->name, st->id, s->groups[st->group].label, st->replicate, (long)st->step, st->x, st->f,
			bounded(st->value), st->value, search_class_name(st->cls));
	}
	if (e->code) {
		db_rollback(db);
		return e->code;
	}
	return db_commit(db, e);
}

/* ---- before the start ---- */

/* "4 Hz (Gamma 1.93, v 75.4 cm/s)": the frequency, then the drive on each other axis */
static void drive_text(const sb_scene *s, double f, char *buf, size_t len)
{
	char num[32], t[64];
	snprintf(num, sizeof num, "%.6g", f);
	size_t l = (size_t)snprintf(buf, len, "%s (", drive_axis_text(AXIS_FREQUENCY, num, t, sizeof t));
	for (int k = AXIS_FREQUENCY + 1; k < AXIS_N && l < len; k++) {
		const sb_axis_row *r = drive_axis_row(k);
		snprintf(num, sizeof num, "%.3g", drive_axis(k, s->amplitude, f, s->gravity));
		l += (size_t)snprintf(buf + l, len - l, "%s%s %s%s%s", k > AXIS_FREQUENCY + 1 ? ", " : "", r->ascii, num,
				      *r->unit ? " " : "", r->unit);
	}
	if (l < len)
		snprintf(buf + l, len - l, ")");
}

int search_preview(const campaign *c, long group, char *buf, size_t len)
{
	const cp_onset *o = &c->onset;
	sb_scene s;
	grid_point_scene(c, group, &s);
	char label[512], at[3][96];
	grid_point_label(c, group, label, sizeof label);
	double x[3] = {adapt_mid(o->from, o->to), o->from, o->to}, f[3];
	for (int k = 0; k < 3; k++) {
		f[k] = grid_onset_frequency(c, &s, x[k]);
		drive_text(&s, f[k], at[k], sizeof at[k]);
	}
	/* every replicate's chain starts at the midpoint; the ends run only when a bracket
	 * closes on them */
	size_t l = (size_t)snprintf(buf, len, "group %s (amplitude %g cm): first point %s; range %s to %s\n", label,
				    s.amplitude, at[0], at[1], at[2]);
	double limit, gamma = drive_gamma(s.amplitude, f[0], s.gravity);
	const char *what = axes_model_fails(gamma, &limit);
	if (what && l < len) {
		char g[32], tg[64];
		snprintf(g, sizeof g, "%.3g", gamma);
		snprintf(buf + l, len - l, "warning: group %s: the first point, %.6g Hz, is at %s, at or above %g "
			 "where %s (docs/model.md, \"Where the model fails\"); such a run counts as on\n", label, f[0],
			 drive_axis_text(AXIS_GAMMA, g, tg, sizeof tg), limit, what);
	}
	return what != NULL;
}
