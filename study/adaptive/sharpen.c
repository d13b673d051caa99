/* sharpen.c - replicates = auto on a grid over the database and the run files: each
 * point's runs, their results, the batches, the auto_point table. */
#include "sharpen.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flux.h"
#include "h5sum.h"
#include "layout.h"
#include "rule/adapt.h"

void sharpen_init(sharpen *s, const campaign *c, const char *dir)
{
	memset(s, 0, sizeof *s);
	s->c = c;
	snprintf(s->dir, sizeof s->dir, "%s", dir);
}

void sharpen_free(sharpen *s)
{
	if (s->member)
		for (long k = 0; k <= AD_MAX_REPLICATES; k++)
			free(s->member[k]);
	free(s->member);
	free(s->pts);
	memset(s, 0, sizeof *s);
}

static sh_plan plan_of(const cp_auto *a)
{
	sh_plan p = {a->result, a->batch, a->max_replicates, a->target, a->level};
	return p;
}

/* The mean flux through bin/onset's default band (0.4 to 0.6 of the surface height)
 * after its default transient (the first 0.2 of the periods), as lib/flux.c
 * computes a run's Phi; NaN when the file has none. *damaged when the file is missing
 * or no complete run file: the sweep moves it aside and the run runs again. */
static double run_flux(const sharpen *s, const char *id, int *damaged)
{
	flux_opts o = FLUX_OPTS_DEFAULT;
	return flux_of_run(s->dir, id, &o, damaged);
}

/* A run's observation from its state and results. A failed run is used when it
 * recorded what the result needs: its intruder's rise or the time it was watched
 * (censored there: the engine's waiting_time of a failed run), not its flux (its
 * periods end where the physics broke down). */
static void observe(const sharpen *s, sqlite3_stmt *q, const char *id, sh_obs *o, long *failed)
{
	memset(o, 0, sizeof *o);
	o->kind = SH_WAIT;
	o->value = NAN;
	sqlite3_reset(q);
	sqlite3_bind_text(q, 2, id, -1, SQLITE_TRANSIENT);
	if (sqlite3_step(q) != SQLITE_ROW)
		return;
	const char *st = (const char *)sqlite3_column_text(q, 0);
	int fail = st && !strcmp(st, "failed");
	if (!st || (strcmp(st, "done") && !fail))
		return;
	*failed += fail;
	o->kind = SH_NONE;
	int has = sqlite3_column_type(q, 1) != SQLITE_NULL && sqlite3_column_type(q, 2) != SQLITE_NULL;
	o->risen = (int)sqlite3_column_int64(q, 1);
	o->time = sqlite3_column_double(q, 2);
	if (s->c->autorep.result != CP_RES_MEAN_FLUX) {
		/* a failed run that rose did rise; one that did not is censored for the wait,
		 * but says nothing of whether it would have risen */
		if (has && (s->c->autorep.result == CP_RES_MEDIAN_WAIT || !fail || o->risen))
			o->kind = SH_USED;
		return;
	}
	if (fail)
		return;
	int damaged;
	o->value = run_flux(s, id, &damaged);
	if (damaged)
		o->kind = SH_WAIT;
	else if (isfinite(o->value))
		o->kind = SH_USED;
}

int sharpen_derive(sharpen *s, grid *g, st_db *db, sb_err *e)
{
	const campaign *c = s->c;
	free(s->pts);
	s->pts = calloc((size_t)(g->points ? g->points : 1), sizeof *s->pts);
	if (!s->pts)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	s->npoints = g->points;
	sqlite3_stmt *q;
	if (sql_exec(db, e, &q,
		    "SELECT r.state, s.risen, s.waiting_time FROM run r LEFT JOIN result s ON s.campaign = r.campaign"
		    " AND s.run = r.id WHERE r.campaign = ?1 AND r.id = ?2",
		    "t", c->name))
		return e->code;
	sh_plan plan = plan_of(&c->autorep);
	sh_obs *obs = calloc((size_t)plan.max, sizeof *obs);
	if (!obs) {
		sqlite3_finalize(q);
		return sb_errf(e, SB_ENOMEM, "out of memory");
	}
	for (long p = 0; p < s->npoints && !e->code; p++) {
		shp_point *pt = &s->pts[p];
		grid_point_label(c, p, pt->label, sizeof pt->label);
		long n = sharp_first(&plan), want;
		for (;;) {
			for (long i = pt->nrep; i < n && !e->code; i++) {
				char id[17];
				if (!grid_add(g, p, i + 1, NAN, id, e))
					observe(s, q, id, &obs[i], &pt->failed);
			}
			pt->nrep = n;
			pt->state = sharp_point(&plan, obs, n, &pt->ev, &want);
			if (pt->state != SH_MORE || e->code)
				break;
			n = want; /* the interval is wider than the target: the next batch */
		}
	}
	free(obs);
	sqlite3_finalize(q);
	grid_sort(g);
	return e->code;
}

int sharpen_done(const sharpen *s)
{
	for (long i = 0; i < s->npoints; i++)
		if (s->pts[i].state == SH_RUNNING)
			return 0;
	return 1;
}

static int by_id(const void *a, const void *b)
{
	return strcmp((const char *)a, (const char *)b);
}

/* The ids of a label's runs are made once per label, not once per recorded run: a
 * check of every run against every point would cost runs x points hashes. */
int sharpen_member(sharpen *s, long points, long replicate, const char *id)
{
	if (replicate < 1 || replicate > AD_MAX_REPLICATES || points < 1)
		return 0;
	if (!s->member && !(s->member = calloc(AD_MAX_REPLICATES + 1, sizeof *s->member)))
		return 1; /* out of memory: keep the run rather than call it stale */
	char (*ids)[17] = s->member[replicate];
	if (!ids) {
		if (!(ids = malloc(sizeof *ids * (size_t)points)))
			return 1;
		for (long p = 0; p < points; p++)
			grid_onset_id(s->c, p, replicate, NAN, ids[p]);
		qsort(ids, (size_t)points, sizeof *ids, by_id);
		s->member[replicate] = ids;
	}
	return bsearch(id, ids, (size_t)points, sizeof *ids, by_id) != NULL;
}

int sharpen_store(const sharpen *s, st_db *db, sb_err *e)
{
	const campaign *c = s->c;
	const cp_auto *a = &c->autorep;
	char now[32];
	db_now(now, sizeof now);
	if (db_begin(db, e))
		return e->code;
	sql_exec(db, e, NULL, "DELETE FROM auto_point WHERE campaign = ?", "t", c->name);
	for (long p = 0; p < s->npoints && !e->code; p++) {
		const shp_point *pt = &s->pts[p];
		const sh_eval *v = &pt->ev;
		/* an end that bounds nothing, an estimate that does not exist: NULL */
		sql_exec(db, e, NULL,
			"INSERT INTO auto_point(campaign, point, grp, result, replicates, used, waiting, failed,"
			" estimate, ci_lo, ci_hi, width, target, level, batch, max_replicates, state, updated)"
			" VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
			"tlttllllDDDDddlltt", c->name, p, pt->label, sharp_result_name(a->result), pt->nrep, v->used,
			v->waiting, pt->failed, isfinite(v->est), v->est, isfinite(v->lo), v->lo, isfinite(v->hi), v->hi,
			isfinite(v->width), v->width, a->target, a->level, a->batch, a->max_replicates,
			sharp_state_name(pt->state), now);
	}
	if (e->code) {
		db_rollback(db);
		return e->code;
	}
	return db_commit(db, e);
}
