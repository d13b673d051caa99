/* watch.c - live progress of a campaign from the database and the journals of the
 * runs in flight (see watch.h). */
#include "watch.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "layout.h"
#include "lock.h"
#include "dtext.h"
#include "jtail.h"
#include "cost.h"

/* a rate is measured over at least this much wall time (the engine's journal reaches
 * the disk in stdio buffers, so t advances in steps), and over the last this much at
 * most, so that it follows a host that slows down */
#define RATE_MIN_WALL 1.0
#define RATE_WINDOW 30.0

static double now_s(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_REALTIME, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static const char *col(sqlite3_stmt *q, int i)
{
	const unsigned char *t = sqlite3_column_text(q, i);
	return t ? (const char *)t : "";
}

void watch_init(watch *w, const char *name, const char *dir)
{
	memset(w, 0, sizeof *w);
	snprintf(w->name, sizeof w->name, "%s", name);
	snprintf(w->dir, sizeof w->dir, "%s", dir);
	w->eta = -1;
	w->driver = -1;
}

void watch_free(watch *w)
{
	free(w->runs);
	w->runs = NULL;
	w->nruns = w->cap = 0;
}

/* "frequency=2.8 radius_ratio=4 seed=3": the campaign's swept keys (its `axes`) with
 * this run's values, and its replicate */
static void run_label(st_db *db, const char *camp, const char *axes, const char *id, long replicate, char *out,
		      size_t len)
{
	size_t l = 0;
	out[0] = 0;
	char keys[2048];
	snprintf(keys, sizeof keys, "%s", axes);
	for (char *sv, *k = strtok_r(keys, " ", &sv); k && l < len; k = strtok_r(NULL, " ", &sv)) {
		if (!strcmp(k, "seed"))
			continue; /* the replicate label, below */
		sqlite3_stmt *q;
		sb_err e = {0};
		if (sql_exec(db, &e, &q, "SELECT value FROM param WHERE campaign = ? AND run = ? AND key = ?", "ttt", camp, id,
			    k))
			continue;
		if (sqlite3_step(q) == SQLITE_ROW) {
			char v[64];
			if (sqlite3_column_type(q, 0) == SQLITE_FLOAT)
				dtext_shortest(sqlite3_column_double(q, 0), v, sizeof v);
			else
				snprintf(v, sizeof v, "%s", col(q, 0));
			l += (size_t)snprintf(out + l, len - l, "%s%s=%s", l ? " " : "", k, v);
		}
		sqlite3_finalize(q);
	}
	if (l < len)
		snprintf(out + l, len - l, "%sseed=%ld", l ? " " : "", replicate);
}

static watch_run *find_run(watch *w, const char *id)
{
	for (long i = 0; i < w->nruns; i++)
		if (!strcmp(w->runs[i].id, id))
			return &w->runs[i];
	if (w->nruns == w->cap) {
		long c = w->cap ? 2 * w->cap : 16;
		watch_run *r = realloc(w->runs, (size_t)c * sizeof *r);
		if (!r)
			return NULL;
		w->runs = r;
		w->cap = c;
	}
	watch_run *r = &w->runs[w->nruns++];
	memset(r, 0, sizeof *r);
	snprintf(r->id, sizeof r->id, "%s", id);
	r->t = r->rate = -1;
	return r;
}

/* The journal's time, and the run's rate between this look and an earlier one. */
static void sample(watch *w, watch_run *r, double now, double started, long attempts)
{
	char jp[4400];
	layout_file(w->dir, 0, r->id, LAY_JOURNAL, jp, sizeof jp);
	jtail j = {r->offset, r->ino, r->t};
	int known = jtail_poll(&j, jp);
	r->offset = j.offset;
	r->ino = j.ino;
	r->t = known ? j.t : -1;
	if (!known)
		return;
	if (r->w_ref <= 0 || r->t < r->t_ref) { /* first look, or a restart went back */
		r->t_ref = r->t_last = r->t;
		r->w_ref = r->w_last = now;
		/* until a second look: its pace since it started, when this attempt is its
		 * first (a resumed run did not simulate its t since it started) */
		if (attempts == 0 && started > 0 && now - started >= RATE_MIN_WALL && r->t > 0)
			r->rate = r->t / (now - started);
		return;
	}
	if (r->t > r->t_last) {
		r->t_last = r->t;
		r->w_last = now;
	}
	if (r->w_last - r->w_ref >= RATE_MIN_WALL)
		r->rate = (r->t_last - r->t_ref) / (r->w_last - r->w_ref);
	if (now - r->w_ref > RATE_WINDOW) { /* slide: measure from the last step on */
		r->t_ref = r->t_last;
		r->w_ref = r->w_last;
	}
}

int watch_search_left(st_db *db, const char *name, watch_search *s, sb_err *e)
{
	sqlite3_stmt *q;
	memset(s, 0, sizeof *s);
	if (sql_exec(db, e, &q, "SELECT freq_from, freq_to, tolerance FROM onset_search WHERE campaign = ?", "t", name))
		return e->code;
	if (sqlite3_step(q) == SQLITE_ROW) {
		const double from = sqlite3_column_double(q, 0), to = sqlite3_column_double(q, 1),
			     tol = sqlite3_column_double(q, 2);
		const long chain = cost_chain_max(from, to, tol);
		if (sql_done(db, q, e))
			return e->code;
		s->on = 1;
		/* the replicates still searching: their brackets (NULL: the range's end) */
		if (sql_exec(db, e, &q,
			     "SELECT runs, COALESCE(lo, ?2), COALESCE(hi, ?3) FROM onset_replicate WHERE campaign = ?1"
			     " AND state = 'searching'",
			     "tdd", name, from, to))
			return e->code;
		while (sqlite3_step(q) == SQLITE_ROW) {
			const long runs = sqlite3_column_int64(q, 0);
			const double width = sqlite3_column_double(q, 2) - sqlite3_column_double(q, 1);
			/* runs counts the one of this round: the chain's at most, less what it ran */
			s->more_max += chain > runs ? chain - runs : 0;
			s->rounds_max = chain - runs > s->rounds_max ? chain - runs : s->rounds_max;
			/* a bisection halves the bracket per run; this round's run is the first */
			const long b = tol > 0 && width > tol ? (long)ceil(log2(width / tol) - 1e-9) - 1 : 0;
			s->more += b > 0 ? b : 0;
			s->rounds = b > s->rounds ? b : s->rounds;
		}
		if (sql_done(db, q, e))
			return e->code;
		/* the replicates a group not yet answered may still get, each a whole chain */
		if (sql_exec(db, e, &q,
			     "SELECT COALESCE(SUM(MAX(0, s.max_replicates - g.replicates)), 0), COALESCE(MAX(MAX(0,"
			     " s.max_replicates - g.replicates)), 0), MAX(1, COALESCE(s.batch, 1)) FROM onset_group g JOIN"
			     " onset_search s ON s.campaign = g.campaign WHERE g.campaign = ? AND g.state IN ('searching', 'more')",
			     "t", name))
			return e->code;
		if (sqlite3_step(q) == SQLITE_ROW) {
			const long extra = sqlite3_column_int64(q, 0), most = sqlite3_column_int64(q, 1),
				   batch = sqlite3_column_int64(q, 2);
			s->more_max += chain * extra;
			s->rounds_max += chain * ((most + batch - 1) / batch);
		}
		return sql_done(db, q, e);
	}
	if (sql_done(db, q, e) ||
	    sql_exec(db, e, &q,
		     "SELECT COUNT(*), COALESCE(SUM(MAX(0, max_replicates - replicates)), 0), COALESCE(MAX((MAX(0,"
		     " max_replicates - replicates) + MAX(1, batch) - 1) / MAX(1, batch)), 0) FROM auto_point"
		     " WHERE campaign = ? AND state IN ('running', 'more')",
		     "t", name))
		return e->code;
	if (sqlite3_step(q) == SQLITE_ROW && sqlite3_column_int64(q, 0) > 0) {
		/* whether a point needs another batch depends on its interval: only bounds */
		s->on = 1;
		s->more_max = sqlite3_column_int64(q, 1);
		s->rounds_max = sqlite3_column_int64(q, 2);
		s->more = s->rounds = -1;
	}
	return sql_done(db, q, e);
}

int watch_poll(watch *w, st_db *db, sb_err *e)
{
	double now = now_s();
	sqlite3_stmt *q;
	if (sql_exec(db, e, &q,
		    "SELECT COUNT(*), SUM(state = 'done'), SUM(state = 'failed'), SUM(state = 'pending'),"
		    " SUM(state = 'running'), (SELECT axes FROM campaign WHERE name = ?1),"
		    " (SELECT TOTAL(p.value) FROM run r2 JOIN param p ON p.campaign = r2.campaign AND p.run = r2.id"
		    "  AND p.key = 'duration' WHERE r2.campaign = ?1 AND r2.current AND r2.state = 'pending'),"
		    " (SELECT AVG(p.value) FROM run r3 JOIN param p ON p.campaign = r3.campaign AND p.run = r3.id"
		    "  AND p.key = 'duration' WHERE r3.campaign = ?1 AND r3.current)"
		    " FROM run WHERE campaign = ?1 AND current",
		    "t", w->name))
		return e->code;
	char axes[2048] = "";
	double pending_T = 0, mean_T = 0;
	if (sqlite3_step(q) == SQLITE_ROW) {
		w->total = sqlite3_column_int64(q, 0);
		w->done = sqlite3_column_int64(q, 1);
		w->failed = sqlite3_column_int64(q, 2);
		w->pending = sqlite3_column_int64(q, 3);
		w->running = sqlite3_column_int64(q, 4);
		snprintf(axes, sizeof axes, "%s", col(q, 5));
		pending_T = sqlite3_column_double(q, 6);
		mean_T = sqlite3_column_double(q, 7);
	}
	if (sql_done(db, q, e))
		return e->code;

	/* the speed of one run, from the last runs to finish: simulated time over the
	 * shaking loop's wall time */
	double speed = -1;
	if (!sql_exec(db, e, &q,
		     "SELECT TOTAL(st), TOTAL(ws) FROM (SELECT s.status_time AS st, s.wall_seconds AS ws FROM result s"
		     " JOIN run r ON r.campaign = s.campaign AND r.id = s.run WHERE s.campaign = ? AND s.status_time > 0"
		     " AND s.wall_seconds > 0 ORDER BY r.finished DESC LIMIT 20)",
		     "t", w->name)) {
		if (sqlite3_step(q) == SQLITE_ROW && sqlite3_column_double(q, 1) > 0)
			speed = sqlite3_column_double(q, 0) / sqlite3_column_double(q, 1);
		sql_done(db, q, e);
	}
	if (e->code)
		return e->code;

	for (long i = 0; i < w->nruns; i++)
		w->runs[i].seen = 0;
	if (sql_exec(db, e, &q,
		    "SELECT r.id, r.host, CAST(strftime('%s', r.started) AS INTEGER), r.replicate, r.attempts,"
		    " (SELECT value FROM param p WHERE p.campaign = r.campaign AND p.run = r.id AND p.key = 'duration')"
		    " FROM run r WHERE r.campaign = ? AND r.current AND r.state = 'running' ORDER BY r.started, r.id",
		    "t", w->name))
		return e->code;
	double inflight = 0, left = pending_T;
	long measured = 0;
	while (sqlite3_step(q) == SQLITE_ROW) {
		watch_run *r = find_run(w, col(q, 0));
		if (!r)
			break;
		r->seen = 1;
		snprintf(r->host, sizeof r->host, "%s", col(q, 1));
		r->T = sqlite3_column_double(q, 5);
		if (!r->label[0])
			run_label(db, w->name, axes, r->id, (long)sqlite3_column_int64(q, 3), r->label, sizeof r->label);
		double started = (double)sqlite3_column_int64(q, 2);
		sample(w, r, now, started, (long)sqlite3_column_int64(q, 4));
		double rate = r->rate > 0 ? r->rate : speed;
		if (r->rate > 0)
			measured++;
		if (rate > 0)
			inflight += rate;
		/* what is left of it: from its journal, else what its pace would have done */
		double t = r->t >= 0 ? r->t : rate > 0 && started > 0 ? rate * (now - started) : 0;
		left += r->T > t ? r->T - t : 0;
	}
	if (sql_done(db, q, e))
		return e->code;
	/* forget the runs no longer in flight */
	long k = 0;
	for (long i = 0; i < w->nruns; i++)
		if (w->runs[i].seen)
			w->runs[k++] = w->runs[i];
	w->nruns = k;

	w->remaining = left;
	w->rate = 0;
	w->basis = "";
	if (w->nruns > 0 && inflight > 0) {
		w->rate = inflight;
		w->basis = measured ? "the runs in flight" : "the last runs' pace";
	} else {
		/* nothing in flight (between passes, or hosts whose output comes back
		 * whole): simulated time finished per wall second by the last runs */
		if (!sql_exec(db, e, &q,
			     "SELECT COUNT(*), TOTAL(st), (MAX(f) - MIN(s)) * 86400 FROM (SELECT s.status_time AS st,"
			     " julianday(r.finished) AS f, julianday(r.started) AS s FROM result s JOIN run r"
			     " ON r.campaign = s.campaign AND r.id = s.run WHERE s.campaign = ? AND r.started IS NOT NULL"
			     " AND r.finished IS NOT NULL ORDER BY r.finished DESC LIMIT 20)",
			     "t", w->name)) {
			if (sqlite3_step(q) == SQLITE_ROW && sqlite3_column_int64(q, 0) >= 1 && sqlite3_column_double(q, 2) > 0) {
				w->rate = sqlite3_column_double(q, 1) / sqlite3_column_double(q, 2);
				w->basis = "the last runs to finish";
			}
			sqlite3_finalize(q);
		}
	}
	w->eta = w->rate > 0 ? w->remaining / w->rate : -1;
	/* a search: the rounds after this one too, each as long as one run at one run's
	 * pace (the last runs' to finish, else this round's share), as many at a time as
	 * run now (docs/driver.md, "A search's ETA covers the search") */
	w->eta_search = w->eta_search_max = -1;
	if (watch_search_left(db, w->name, &w->search, e))
		return e->code;
	w->jobs = w->running > 0 ? w->running : 1;
	const double one = speed > 0 ? speed : w->rate / (double)w->jobs;
	if (w->search.on && w->eta >= 0 && one > 0 && mean_T > 0) {
		const double round = mean_T / one;
		w->eta_search_max = w->eta + round * fmax((double)w->search.rounds_max,
							  ceil((double)w->search.more_max / (double)w->jobs));
		if (w->search.more >= 0)
			w->eta_search = w->eta + round * fmax((double)w->search.rounds,
							      ceil((double)w->search.more / (double)w->jobs));
	}
	w->driver = lock_campaign_held(w->dir);
	return e->code;
}

int watch_over(const watch *w)
{
	/* a campaign on Slurm has no driver: its tasks keep it going */
	return (w->pending == 0 && w->running == 0) || (w->driver == 0 && w->slurm == 0);
}

static void run_state(const watch_run *r, char *buf, size_t len)
{
	char T[32];
	dtext_shortest(r->T, T, sizeof T);
	if (r->t >= 0)
		snprintf(buf, len, "t %.3g/%s s", r->t, T);
	else
		snprintf(buf, len, "t ?/%s s", T);
}

static void head(const watch *w, char *buf, size_t len)
{
	/* (the whole search's estimate when there is one: its rounds to come, not only the
	 * round in flight) */
	char eta[32];
	dtext_duration(w->eta, eta, sizeof eta);
	long fin = w->done + w->failed;
	int n = snprintf(buf, len, "%s: %ld/%ld finished (%.0f%%): %ld done, %ld failed, %ld pending, %ld running", w->name,
			 fin, w->total, w->total ? 100.0 * (double)fin / (double)w->total : 100.0, w->done, w->failed,
			 w->pending, w->running);
	if ((w->pending || w->running) && n > 0 && (size_t)n < len) {
		char most[32], about[32];
		dtext_duration(w->eta_search_max, most, sizeof most);
		dtext_duration(w->eta_search, about, sizeof about);
		const watch_search *s = &w->search;
		if (w->rate > 0 && w->eta_search_max >= 0 && s->more >= 0)
			/* an [onset] search: the bisections its brackets still need */
			snprintf(buf + n, len - (size_t)n, "; ETA this round: %s; search: about %s (%ld more round%s expected, "
				 "%ld more run%s, %ld at a time), at most %s (%ld more runs) at %.3g simulated s per s from %s", eta,
				 about, s->rounds, s->rounds == 1 ? "" : "s", s->more, s->more == 1 ? "" : "s", w->jobs, most, s->more_max, w->rate,
				 w->basis);
		else if (w->rate > 0 && w->eta_search_max >= 0)
			/* replicates = auto: whether a batch more is needed, the results say */
			snprintf(buf + n, len - (size_t)n, "; ETA this round: %s; search: at most %s (up to %ld more round%s, "
				 "%ld more runs, if the intervals need them; %ld at a time) at %.3g simulated s per s from %s", eta,
				 most, s->rounds_max, s->rounds_max == 1 ? "" : "s", s->more_max, w->jobs, w->rate, w->basis);
		else if (w->rate > 0)
			snprintf(buf + n, len - (size_t)n, "; ETA %s at %.3g simulated s per s from %s", eta, w->rate, w->basis);
		else
			snprintf(buf + n, len - (size_t)n, "; ETA unknown until a run has advanced");
	}
}

void watch_print(const watch *w, FILE *out)
{
	char h[1024];
	head(w, h, sizeof h);
	fprintf(out, "%s\n", h);
	for (long i = 0; i < w->nruns; i++) {
		const watch_run *r = &w->runs[i];
		char st[64], rate[48] = "";
		run_state(r, st, sizeof st);
		if (r->rate > 0)
			snprintf(rate, sizeof rate, "  %.3g simulated s per s", r->rate);
		fprintf(out, "  %-40s %-18s %5.0f%%%s  %s (%s)\n", r->label, st,
			r->t >= 0 && r->T > 0 ? 100 * fmin(r->t / r->T, 1) : 0.0, rate, r->host, r->id);
	}
	if (w->driver == 0 && w->slurm > 0)
		fprintf(out, "  Slurm tasks queued or running hold %ld of its runs\n", w->slurm);
	else if (w->driver == 0 && w->slurm < 0)
		fprintf(out, "  no driver is running %s; squeue cannot say whether Slurm tasks are\n", w->name);
	else if (w->driver == 0 && (w->pending || w->running))
		fprintf(out, "  no driver is running %s (study run or study submit resumes it)\n", w->name);
}

void watch_line(const watch *w, char *buf, size_t len)
{
	char h[1024];
	head(w, h, sizeof h);
	size_t l = (size_t)snprintf(buf, len, "%s", h);
	for (long i = 0; i < w->nruns && l < len; i++) {
		char st[64];
		run_state(&w->runs[i], st, sizeof st);
		l += (size_t)snprintf(buf + l, len - l, " | %s %s", w->runs[i].label, st);
	}
}
