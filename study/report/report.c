/* report.c - status, list, export and view: readers of the database, never writers (view writes a tree of links where the user says). */
#define _XOPEN_SOURCE 700 /* nftw */
#include "report.h"

#include <errno.h>
#include <ftw.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>
#include <unistd.h>

#include "csv.h"
#include "fsutil.h"
#include "drive.h"
#include "layout.h"
#include "params.h"
#include "results.h"
#include "rowseal.h"
#include "schema.h"
#include "campaign/axes.h"
#include "ledger/db.h"
#include "rule/adapt.h"
#include "cost.h"
#include "dtext.h"
#include "watch.h"

static int open_ro(st_db *d, const char *path, sb_err *e)
{
	if (access(path, R_OK) != 0)
		return sb_errf(e, SB_EUSAGE, "%s: no study database (run a campaign first)", path);
	if (db_open(d, path, 0, e))
		return e->code;
	if (schema_complete(d, 1, e))
		db_close(d);
	return e->code;
}

static int campaign_known(st_db *d, const char *name, sb_err *e)
{
	sqlite3_stmt *q;
	if (sql_exec(d, e, &q, "SELECT 1 FROM campaign WHERE name = ?", "t", name))
		return e->code;
	int found = sqlite3_step(q) == SQLITE_ROW;
	if (sql_done(d, q, e))
		return e->code;
	if (!found)
		return sb_errf(e, SB_EUSAGE, "campaign '%s' is not in %s (study list shows the campaigns)", name, d->path);
	return schema_runs_lost(d, name, e);
}

static const char *col(sqlite3_stmt *q, int i)
{
	const unsigned char *t = sqlite3_column_text(q, i);
	return t ? (const char *)t : "";
}

/* Runs finished per second by what actually ran: the last (at most 20) runs to finish,
 * over the time from the first of them starting to the last finishing (runs that ran
 * side by side count together, whatever --jobs or hosts did it); 0 when none has. */
static double throughput(st_db *d, const char *name)
{
	sqlite3_stmt *q;
	sb_err e = {0};
	double rate = 0;
	if (sql_exec(d, &e, &q,
		    "SELECT COUNT(*), (MAX(f) - MIN(s)) * 86400 FROM (SELECT julianday(a.finished) AS f,"
		    " julianday(r.started) AS s FROM attempt a JOIN run r ON r.campaign = a.campaign AND r.id = a.run"
		    " WHERE a.campaign = ? AND a.finished IS NOT NULL AND r.started IS NOT NULL"
		    /* only attempts that finished their run: an interrupted, killed or lost
		     * one ended early and would make the pace look faster than it is */
		    " AND COALESCE(a.status, '') NOT IN ('interrupted', 'killed', 'lost', 'io', 'crashed')"
		    " ORDER BY a.finished DESC LIMIT 20)",
		    "t", name))
		return 0;
	if (sqlite3_step(q) == SQLITE_ROW) {
		long n = sqlite3_column_int64(q, 0);
		double span = sqlite3_column_double(q, 1);
		if (n >= 1 && span > 0)
			rate = (double)n / span;
	}
	sql_done(d, q, &e);
	return rate;
}

/* "2.6875"; "-" for a NULL (an end that bounds nothing, an estimate that does not exist) */
static const char *num_or(sqlite3_stmt *q, int i, const char *none, char *buf, size_t len)
{
	if (sqlite3_column_type(q, i) == SQLITE_NULL)
		return none;
	snprintf(buf, len, "%.6g", sqlite3_column_double(q, i));
	return buf;
}

/* An [onset] campaign: the search as the driver's last pass left it (search.c): per
 * group the replicates and their states, the runs, the onset and its interval, and
 * every replicate's bracket. Nothing when the campaign has no [onset] or the
 * database predates it. */
/* A grid with replicates = auto, as the driver's last pass left it (sharpen.c): per
 * point the replicates so far, the runs used, waiting and failed, the result's
 * estimate and the interval it reached. Nothing for other campaigns. */
static int autorep_status(st_db *d, const char *name, FILE *out, sb_err *e)
{
	sqlite3_stmt *q;
	sb_err qe = {0};
	if (sql_exec(d, &qe, &q,
		    "SELECT grp, result, replicates, used, waiting, failed, estimate, ci_lo, ci_hi, width, target, level,"
		    " batch, max_replicates, state, updated FROM auto_point WHERE campaign = ? ORDER BY point",
		    "t", name))
		return 0; /* an older database: no auto_point */
	int first = 1;
	while (sqlite3_step(q) == SQLITE_ROW) {
		char b[4][32];
		if (first)
			fprintf(out, "  replicates auto (last pass %s): %s, %s at a time up to %s, until the %g%% interval "
				"is at most %s wide\n    %-28s %10s %5s %7s %6s %12s %24s %10s  %s\n", col(q, 15), col(q, 1),
				col(q, 12), col(q, 13), 100 * sqlite3_column_double(q, 11), num_or(q, 10, "?", b[0], sizeof b[0]),
				"point", "replicates",
				"used", "waiting", "failed", "estimate", "interval", "width", "state");
		first = 0;
		char iv[80];
		snprintf(iv, sizeof iv, "[%s, %s]", num_or(q, 7, "-inf", b[1], sizeof b[1]),
			 num_or(q, 8, "+inf", b[2], sizeof b[2]));
		fprintf(out, "    %-28s %10s %5s %7s %6s %12s %24s %10s  %s\n", col(q, 0), col(q, 2), col(q, 3), col(q, 4),
			col(q, 5), num_or(q, 6, "none", b[0], sizeof b[0]), iv, num_or(q, 9, "inf", b[3], sizeof b[3]),
			col(q, 14));
	}
	return sql_done(d, q, e);
}

static int onset_status(st_db *d, const char *name, FILE *out, sb_err *e)
{
	sqlite3_stmt *q;
	sb_err qe = {0};
	if (sql_exec(d, &qe, &q,
		    "SELECT observable, freq_from, freq_to, tolerance, threshold, band_lo, band_hi, skip, replicates,"
		    " max_replicates, batch, target, level, state, updated, axis FROM onset_search WHERE campaign = ?",
		    "t", name))
		return 0; /* an older database: no onset tables */
	if (sqlite3_step(q) != SQLITE_ROW)
		return sql_done(d, q, e);
	char b[8][32];
	double level = sqlite3_column_double(q, 12);
	fprintf(out, "  onset search (%s; last pass %s): ", col(q, 13), col(q, 14));
	if (!strcmp(col(q, 0), "flux"))
		fprintf(out, "mean flux through %s-%s of the surface after %s of the periods, on at |flux| >= %s "
			"particles/period", num_or(q, 5, "?", b[0], 32), num_or(q, 6, "?", b[1], 32),
			num_or(q, 7, "?", b[2], 32), num_or(q, 4, "?", b[3], 32));
	else
		fprintf(out, "the intruder's rise (risen)");
	/* the range is in the search's axis: Hz, Gamma (no unit) or cm/s; NULL in an older database */
	int kind = drive_axis_kind(col(q, 15));
	if (kind < 0)
		kind = AXIS_FREQUENCY;
	char range[80], t1[112], t2[80];
	snprintf(range, sizeof range, "%s to %s", num_or(q, 1, "?", b[0], 32), num_or(q, 2, "?", b[1], 32));
	fprintf(out, ", %s, tolerance %s;\n", drive_axis_text(kind, range, t1, sizeof t1),
		drive_axis_text(kind, num_or(q, 3, "?", b[2], 32), t2, sizeof t2));
	if (!strcmp(col(q, 8), "auto"))
		fprintf(out, "    replicates auto: %s at a time, at most %s, until the %g%% interval is at most %s wide\n",
			col(q, 10), col(q, 9), 100 * level, drive_axis_text(kind, num_or(q, 11, "?", b[0], 32), t1, sizeof t1));
	else if (atol(col(q, 8)) < adapt_min_replicates(level))
		fprintf(out, "    replicates %s; an interval at %g%% needs %ld\n", col(q, 8), 100 * level,
			adapt_min_replicates(level));
	else
		fprintf(out, "    replicates %s; %g%% interval over them\n", col(q, 8), 100 * level);
	sql_done(d, q, e);
	if (sql_exec(d, e, &q,
		    "SELECT grp, replicates, searching, found, below, above, blocked, nonmonotone, runs, estimate, ci_lo,"
		    " ci_hi, width, state, reason FROM onset_group WHERE campaign = ? ORDER BY point",
		    "t", name))
		return e->code;
	char on[32], in[32];
	snprintf(on, sizeof on, "onset (%s)", drive_axis_heading(kind));
	snprintf(in, sizeof in, "interval (%s)", drive_axis_heading(kind));
	fprintf(out, "    %-28s %10s %9s %6s %6s %6s %7s %5s %12s %22s %9s  %s\n", "group", "replicates", "searching",
		"found", "below", "above", "blocked", "runs", on, in, "width", "state");
	while (sqlite3_step(q) == SQLITE_ROW) {
		char iv[80];
		snprintf(iv, sizeof iv, "[%s, %s]", num_or(q, 10, "-inf", b[0], 32), num_or(q, 11, "+inf", b[1], 32));
		fprintf(out, "    %-28s %10s %9s %6s %6s %6s %7s %5s %12s %22s %9s  %s%s\n", col(q, 0), col(q, 1), col(q, 2),
			col(q, 3), col(q, 4), col(q, 5), col(q, 6), col(q, 8), num_or(q, 9, "none", b[2], 32), iv,
			num_or(q, 12, "inf", b[3], 32), col(q, 13),
			sqlite3_column_int64(q, 7) ? " (a replicate's runs flip: see its brackets)" : "");
		if (*col(q, 14)) /* why a blocked group cannot finish */
			fprintf(out, "      %s blocked: %s\n", col(q, 0), col(q, 14));
	}
	sql_done(d, q, e);
	/* every replicate's bracket: "3 [2.68, 2.69]"; "5 [2.6, ~3.2] running 2.75" when
	 * an end was not run (~: the range's end, assumed); "< 2.5", "> 3.2" out of range */
	if (sql_exec(d, e, &q,
		    "SELECT grp, replicate, state, lo, hi, lo_run, hi_run, next, nonmonotone FROM onset_replicate"
		    " WHERE campaign = ? ORDER BY (SELECT point FROM onset_group g WHERE g.campaign = onset_replicate.campaign"
		    " AND g.grp = onset_replicate.grp), replicate",
		    "t", name))
		return e->code;
	char grp[512] = "";
	size_t width = 0;
	while (sqlite3_step(q) == SQLITE_ROW) {
		if (strcmp(grp, col(q, 0))) {
			snprintf(grp, sizeof grp, "%s", col(q, 0));
			fprintf(out, "%s    brackets of %s:", width ? "\n" : "", grp);
			width = 1;
		}
		char item[160];
		const char *st = col(q, 2);
		if (!strcmp(st, "below"))
			snprintf(item, sizeof item, "%s < %s", col(q, 1), num_or(q, 4, "?", b[0], 32));
		else if (!strcmp(st, "above"))
			snprintf(item, sizeof item, "%s > %s", col(q, 1), num_or(q, 3, "?", b[0], 32));
		else
			snprintf(item, sizeof item, "%s [%s%s, %s%s]%s%s%s%s", col(q, 1), sqlite3_column_int64(q, 5) ? "" : "~",
				 num_or(q, 3, "?", b[0], 32), sqlite3_column_int64(q, 6) ? "" : "~",
				 num_or(q, 4, "?", b[1], 32),
				 !strcmp(st, "searching") ? " needs " : !strcmp(st, "blocked") ? " failed at " : "",
				 !strcmp(st, "searching") || !strcmp(st, "blocked") ? num_or(q, 7, "?", b[2], 32) : "",
				 sqlite3_column_int64(q, 8) ? " flips" : "", "");
		if (width > 1 && width + strlen(item) + 2 > 100) {
			fprintf(out, "\n     ");
			width = 5;
		}
		fprintf(out, "%s %s", width > 5 ? ";" : "", item);
		width += strlen(item) + 2;
	}
	if (width)
		fprintf(out, "\n");
	return sql_done(d, q, e);
}

/* Why runs failed, by status (physics failures are never retried: the engine is
 * deterministic), and what was run again automatically (killed, I/O, lost). */
static int failure_summary(st_db *d, const char *name, FILE *out, sb_err *e)
{
	sqlite3_stmt *q;
	if (sql_exec(d, e, &q,
		    "SELECT COALESCE(s.status, (SELECT a.status FROM attempt a WHERE a.campaign = r.campaign AND a.run = r.id"
		    " ORDER BY a.n DESC LIMIT 1)) AS why, COUNT(*) FROM run r LEFT JOIN result s ON s.campaign = r.campaign"
		    " AND s.run = r.id WHERE r.campaign = ? AND r.state = 'failed' GROUP BY why ORDER BY why",
		    "t", name))
		return e->code;
	int first = 1;
	while (sqlite3_step(q) == SQLITE_ROW) {
		fprintf(out, "%s %s %s", first ? "  failed runs by reason (not run again; --retry-failed does):" : ",",
			col(q, 0), col(q, 1));
		first = 0;
	}
	if (!first)
		fputc('\n', out);
	sql_done(d, q, e);
	if (sql_exec(d, e, &q,
		    "SELECT a.status, COUNT(*), SUM(r.state = 'done') FROM attempt a JOIN run r ON r.campaign = a.campaign"
		    " AND r.id = a.run WHERE a.campaign = ? AND a.status IN ('killed', 'io', 'lost') GROUP BY a.status"
		    " ORDER BY a.status",
		    "t", name))
		return e->code;
	first = 1;
	while (sqlite3_step(q) == SQLITE_ROW) {
		fprintf(out, "%s %s %s (%s of their runs now done)",
			first ? "  transient attempts (run again automatically up to --retries):" : ",", col(q, 0), col(q, 1),
			col(q, 2));
		first = 0;
	}
	if (!first)
		fputc('\n', out);
	return sql_done(d, q, e);
}

static int status_one(st_db *d, const char *name, int jobs, FILE *out, sb_err *e)
{
	sqlite3_stmt *q;
	if (sql_exec(d, e, &q,
		    "SELECT COUNT(*), SUM(state = 'done'), SUM(state = 'failed'), SUM(state = 'pending'),"
		    " SUM(state = 'running'), SUM(from_cache AND state = 'done'),"
		    " (SELECT AVG(wall_seconds) FROM result s WHERE s.campaign = ?1 AND s.status = 'ok'),"
		    " (SELECT description FROM campaign WHERE name = ?1)"
		    " FROM run WHERE campaign = ?1",
		    "t", name))
		return e->code;
	if (sqlite3_step(q) == SQLITE_ROW) {
		long n = sqlite3_column_int64(q, 0), done = sqlite3_column_int64(q, 1),
		     failed = sqlite3_column_int64(q, 2), pending = sqlite3_column_int64(q, 3),
		     running = sqlite3_column_int64(q, 4), hits = sqlite3_column_int64(q, 5);
		double mean = sqlite3_column_double(q, 6);
		fprintf(out, "campaign %s: %s\n", name, col(q, 7));
		fprintf(out, "  runs %ld: done %ld, failed %ld, pending %ld, running %ld\n", n, done, failed, pending,
			running);
		fprintf(out, "  packing cache: %ld finished runs started from a shared packing\n", hits);
		/* a search or replicates = auto: the whole campaign's work, at most */
		watch_search ws = {0};
		const long left = pending + running > 0 && !watch_search_left(d, name, &ws, e) && ws.on
					  ? pending + running + ws.more_max
					  : -1;
		if (e->code) {
			sql_done(d, q, e);
			return e->code;
		}
		const long todo = left >= 0 ? left : pending + running;
		const char *most = left >= 0 ? "at most " : "about ";
		char whole[96] = "";
		if (left >= 0)
			snprintf(whole, sizeof whole, " for the whole campaign (at most %ld runs to go)", left);
		if (pending + running > 0) {
			char eta[32];
			double rate = throughput(d, name);
			if (rate > 0) {
				/* what actually ran: the pace of the last runs to finish, whatever
				 * the number of jobs or hosts that produced it */
				dtext_duration((double)todo / rate, eta, sizeof eta);
				fprintf(out, "  ETA: %s%s%s at the pace of the last runs (%.1f runs/h)\n", most, eta, whole,
					3600 * rate);
			} else if (sqlite3_column_type(q, 6) != SQLITE_NULL) {
				/* a single finished run: its time spread over what runs now */
				int w = running > 0 ? (int)running : jobs;
				dtext_duration(mean * (double)todo / (w > 0 ? w : 1), eta, sizeof eta);
				fprintf(out, "  ETA: %s%s%s with %d run%s at a time (mean run %.1f s)\n", most, eta, whole, w,
					w > 1 ? "s" : "", mean);
			} else {
				fprintf(out, "  ETA: unknown until a run has finished%s\n", whole);
			}
		}
	}
	if (sql_done(d, q, e) || onset_status(d, name, out, e))
		return e->code;
	if (autorep_status(d, name, out, e))
		return e->code;
	if (sql_exec(d, e, &q,
		    "SELECT f.run, f.attempt, f.exit_code, f.status, f.message, f.state FROM failures f"
		    " WHERE f.campaign = ? ORDER BY f.state, f.run, f.attempt",
		    "t", name))
		return e->code;
	int first = 1;
	while (sqlite3_step(q) == SQLITE_ROW) {
		if (first)
			fprintf(out, "  unsuccessful attempts (run, attempt, exit code, status: message):\n");
		first = 0;
		const char *st = col(q, 5);
		fprintf(out, "    %s #%s exit %s %s: %s%s\n", col(q, 0), col(q, 1), col(q, 2), col(q, 3), col(q, 4),
			!strcmp(st, "failed") ? "" : !strcmp(st, "done") ? "  [run again: done]" : "  [resumable]");
	}
	sql_done(d, q, e);
	return failure_summary(d, name, out, e);
}

int report_status(const char *db_path, const char *name, int jobs, FILE *out, sb_err *e)
{
	st_db d;
	if (open_ro(&d, db_path, e))
		return e->code;
	if (name) {
		if (!campaign_known(&d, name, e))
			status_one(&d, name, jobs, out, e);
	} else {
		sqlite3_stmt *q;
		if (!sql_exec(&d, e, &q, "SELECT name FROM campaign ORDER BY name", "")) {
			while (!e->code && sqlite3_step(q) == SQLITE_ROW) {
				char n[128];
				snprintf(n, sizeof n, "%s", col(q, 0));
				if (!schema_runs_lost(&d, n, e))
					status_one(&d, n, jobs, out, e);
			}
			sql_done(&d, q, e);
		}
	}
	db_close(&d);
	return e->code;
}

int report_list(const char *db_path, FILE *out, sb_err *e)
{
	st_db d;
	if (open_ro(&d, db_path, e))
		return e->code;
	sqlite3_stmt *q;
	if (!sql_exec(&d, e, &q,
		     "SELECT c.name, COUNT(r.id), SUM(r.state = 'done'), SUM(r.state = 'failed'),"
		     " SUM(r.state IN ('pending', 'running')), c.updated, c.axes, c.file,"
		     /* the failed runs' reasons: "overlap:2 nan:1" */
		     " (SELECT group_concat(why || ':' || n, ' ') FROM (SELECT COALESCE(s.status, (SELECT a.status FROM attempt a"
		     "  WHERE a.campaign = f.campaign AND a.run = f.id ORDER BY a.n DESC LIMIT 1), 'failed') AS why,"
		     "  COUNT(*) AS n FROM run f LEFT JOIN result s ON s.campaign = f.campaign AND s.run = f.id"
		     "  WHERE f.campaign = c.name AND f.state = 'failed' GROUP BY why ORDER BY why))"
		     " FROM campaign c LEFT JOIN run r ON r.campaign = c.name GROUP BY c.name ORDER BY c.name",
		     "")) {
		fprintf(out, "%-24s %6s %6s %6s %7s  %-20s %s\n", "campaign", "runs", "done", "failed", "pending",
			"updated", "axes (file) [failed: reasons]");
		while (sqlite3_step(q) == SQLITE_ROW)
			fprintf(out, "%-24s %6s %6s %6s %7s  %-20s %s (%s)%s%s%s\n", col(q, 0), col(q, 1), col(q, 2), col(q, 3),
				col(q, 4), col(q, 5), col(q, 6), col(q, 7), col(q, 8)[0] ? " [failed: " : "", col(q, 8),
				col(q, 8)[0] ? "]" : "");
		sql_done(&d, q, e);
	}
	db_close(&d);
	return e->code;
}

/* The unit of a column of the runs view: an engine parameter's, a result column's, a
 * derived drive axis's (gamma, v_box), or "" (identity, state, counts, text). */
static const char *column_unit(const char *name)
{
	const sb_param *p = params_find(name);
	if (p)
		return p->unit;
	size_t n;
	const int r = results_find(name);
	if (r >= 0)
		return results_table(&n)[r].unit;
	const int k = schema_view_axis(name);
	return k >= 0 ? drive_axis_unit(k) : "";
}

/* The campaign's directory, absolute (rdir ""; when it is not there); runs_dir NULL:
 * "runs". Resolved once per command, not per run. */
static void campaign_dir(const char *runs_dir, const char *name, char rdir[PATH_MAX])
{
	char dir[4200];
	layout_campaign(runs_dir ? runs_dir : "runs", name, dir, sizeof dir);
	if (!realpath(dir, rdir))
		rdir[0] = 0;
}

/* A run's file in the campaign's directory rdir, when it is there (else "") */
static void run_file(const char *rdir, const char *id, char *out, size_t len)
{
	char f[PATH_MAX + 64];
	out[0] = 0;
	if (!rdir[0] || layout_file(rdir, 0, id, LAY_OUTPUT, f, sizeof f) >= (int)sizeof f || access(f, F_OK))
		return;
	snprintf(out, len, "%s", f);
}

int report_export(const char *db_path, const char *runs_dir, const char *name, int units, FILE *out, sb_err *e)
{
	st_db d;
	if (open_ro(&d, db_path, e))
		return e->code;
	sqlite3_stmt *q;
	/* nothing printed from rows that are not as recorded: a value edited with sqlite3
	 * or a byte changed in a page reads as a value like any other (rowseal.h) */
	if (!campaign_known(&d, name, e) && !schema_values(&d, name, 1, e) && !rowseal_check(&d, name, e) &&
	    !sql_exec(&d, e, &q, "SELECT * FROM runs WHERE campaign = ? ORDER BY id", "t", name)) {
		int nc = sqlite3_column_count(q), idc = -1;
		char rdir[PATH_MAX];
		campaign_dir(runs_dir, name, rdir);
		for (int i = 0; i < nc; i++) {
			csv_field(out, sqlite3_column_name(q, i));
			fputc(',', out);
			if (!strcmp(sqlite3_column_name(q, i), "id"))
				idc = i;
		}
		/* then the run's file: where a reader (h5py, bin/movie) finds it */
		fputs("file\n", out);
		if (units) { /* the units row: each column's unit as the tables write it */
			for (int i = 0; i < nc; i++) {
				csv_field(out, column_unit(sqlite3_column_name(q, i)));
				fputc(',', out);
			}
			fputs("\n", out);
		}
		while (sqlite3_step(q) == SQLITE_ROW) {
			for (int i = 0; i < nc; i++) {
				if (sqlite3_column_type(q, i) == SQLITE_FLOAT) {
					char num[40];
					dtext_shortest(sqlite3_column_double(q, i), num, sizeof num);
					fputs(num, out);
				} else {
					csv_field(out, col(q, i));
				}
				fputc(',', out);
			}
			char f[PATH_MAX + 64];
			run_file(rdir, idc >= 0 ? col(q, idc) : "", f, sizeof f);
			csv_field(out, f);
			fputc('\n', out);
		}
		sql_done(&d, q, e);
	}
	db_close(&d);
	return e->code;
}

/* Ctrl-C or SIGTERM ends a watch after the look it is at: the one flag a handler
 * sets (a handler has no other way to speak). */
static volatile sig_atomic_t g_watch_stop;

static void on_watch_signal(int sig)
{
	(void)sig;
	g_watch_stop = 1;
}

int report_watch(const char *db_path, const char *runs_dir, const char *name, double interval,
		 report_refresh refresh, FILE *out, sb_err *e)
{
	st_db d;
	if (open_ro(&d, db_path, e))
		return e->code;
	long nw = 0;
	watch *w = NULL;
	sqlite3_stmt *q;
	if (name) {
		if (campaign_known(&d, name, e))
			goto out;
	}
	if (sql_exec(&d, e, &q, "SELECT name FROM campaign WHERE ?1 IS NULL OR name = ?1 ORDER BY name", "t", name))
		goto out;
	while (sqlite3_step(q) == SQLITE_ROW) {
		watch *nwp = realloc(w, (size_t)(nw + 1) * sizeof *w);
		if (!nwp)
			break;
		w = nwp;
		char dir[4200];
		layout_campaign(runs_dir ? runs_dir : "runs", col(q, 0), dir, sizeof dir);
		watch_init(&w[nw++], col(q, 0), dir);
	}
	sql_done(&d, q, e);
	struct sigaction sa, old_int, old_term;
	memset(&sa, 0, sizeof sa);
	sa.sa_handler = on_watch_signal; /* no SA_RESTART: the sleep ends at once */
	sigaction(SIGINT, &sa, &old_int);
	sigaction(SIGTERM, &sa, &old_term);
	g_watch_stop = 0;
	int tty = isatty(fileno(out));
	for (;;) {
		int over = 1;
		/* what Slurm tasks did since the last look, into the database (the runs they
		 * started show as running, with their journals beside them on the shared file
		 * system); nothing without arrays recorded */
		for (long i = 0; i < nw && refresh; i++) {
			sb_err se = {0};
			if (refresh(runs_dir, db_path, w[i].name, &w[i].slurm, stderr, &se))
				fprintf(stderr, "study: %s\n", se.msg);
		}
		for (long i = 0; i < nw && !e->code; i++) {
			watch_poll(&w[i], &d, e);
			over &= watch_over(&w[i]);
		}
		if (e->code)
			break;
		char stamp[32];
		time_t now = time(NULL);
		struct tm tm;
		localtime_r(&now, &tm);
		strftime(stamp, sizeof stamp, "%H:%M:%S", &tm);
		if (tty)
			fputs("\033[H\033[J", out); /* redraw in place */
		fprintf(out, "%s%s\n", stamp, over ? "  (final)" : "");
		for (long i = 0; i < nw; i++)
			watch_print(&w[i], out);
		if (!tty)
			fputc('\n', out);
		fflush(out);
		if (over || g_watch_stop)
			break;
		struct timespec ts = {(time_t)interval, (long)((interval - floor(interval)) * 1e9)};
		while (!g_watch_stop && nanosleep(&ts, &ts) && errno == EINTR)
			;
		if (g_watch_stop)
			break;
	}
	sigaction(SIGINT, &old_int, NULL);
	sigaction(SIGTERM, &old_term, NULL);
out:
	for (long i = 0; i < nw; i++)
		watch_free(&w[i]);
	free(w);
	db_close(&d);
	return e->code;
}

/* ---- study view ---- */

/* What marks a tree study view made (and may remake): a file at its top naming the
 * campaign. */
#define VIEW_MARK ".shakebox-view"

/* A value as one path component: its text, with every byte outside [A-Za-z0-9._+-] and
 * a leading '.' written %XX, so that a '/' or ".." in a value makes no other path. */
static void view_word(const char *s, char *out, size_t len)
{
	size_t o = 0;
	for (size_t i = 0; s[i] && o + 4 < len; i++) {
		const unsigned char c = (unsigned char)s[i];
		const int plain = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
				  ((c == '.') && i > 0) || c == '_' || c == '+' || c == '-';
		o += (size_t)snprintf(out + o, len - o, plain ? "%c" : "%%%02X", c);
	}
	out[o] = 0;
}

/* the text of a param value as the view names it */
static void view_value(sqlite3_stmt *q, int i, char *out, size_t len)
{
	char t[256];
	if (sqlite3_column_type(q, i) == SQLITE_FLOAT)
		dtext_shortest(sqlite3_column_double(q, i), t, sizeof t);
	else
		snprintf(t, sizeof t, "%s", col(q, i));
	view_word(t, out, len);
}

/* Removes a tree study view made: its links, its mark and its directories; anything
 * else in it is left (and the directories holding it). */
static int view_rm_one(const char *p, const struct stat *st, int flag, struct FTW *ftw)
{
	(void)st;
	(void)ftw;
	if (flag == FTW_DP)
		rmdir(p);
	else if (flag == FTW_SL || flag == FTW_SLN || (flag == FTW_F && !strcmp(p + strlen(p) - strlen(VIEW_MARK), VIEW_MARK)))
		unlink(p);
	return 0;
}

static int cmp_idx(const void *a, const void *b) { return *(const int *)a - *(const int *)b; }

int report_view(const char *db_path, const char *runs_dir, const char *name, const char *dir, FILE *out, sb_err *e)
{
	st_db d;
	if (open_ro(&d, db_path, e))
		return e->code;
	sqlite3_stmt *q = NULL;
	size_t np;
	const sb_param *P = params_table(&np);
	int keys[128], nk = 0, seed = 0;
	char tmp[PATH_MAX], old[PATH_MAX], path[PATH_MAX + 1024];
	long linked = 0, missing = 0, clash = 0;
	/* dir: nothing there, or a tree this command made for this campaign */
	struct stat st;
	if (!lstat(dir, &st)) {
		char mark[PATH_MAX + 32], got[160] = "";
		snprintf(mark, sizeof mark, "%s/" VIEW_MARK, dir);
		FILE *m = S_ISDIR(st.st_mode) ? fopen(mark, "r") : NULL;
		if (m) {
			if (!fgets(got, sizeof got, m))
				got[0] = 0;
			fclose(m);
			got[strcspn(got, "\n")] = 0;
		}
		if (!m || strcmp(got, name)) {
			db_close(&d);
			return sb_errf(e, SB_EUSAGE, "%s: %s stands there that study view did not make for campaign '%s': not touched",
				       dir, S_ISDIR(st.st_mode) ? "a directory" : fs_kind(st.st_mode), name);
		}
	}
	if (campaign_known(&d, name, e) || schema_values(&d, name, 1, e) || rowseal_check(&d, name, e))
		goto out;
	/* the keys whose values differ between the current runs: engine parameters the runs
	 * view shows (not the output-only ones), in the engine table's order, seed last */
	if (sql_exec(&d, e, &q,
		     "SELECT key FROM param WHERE campaign = ?1 AND run IN (SELECT id FROM run WHERE campaign = ?1 AND "
		     "current) GROUP BY key HAVING COUNT(DISTINCT value) > 1",
		     "t", name))
		goto out;
	while (sqlite3_step(q) == SQLITE_ROW) {
		const sb_param *p = params_find(col(q, 0));
		if (!p || (p->flags & PF_OUT))
			continue;
		if (!strcmp(p->name, "seed"))
			seed = 1;
		else if (nk < (int)(sizeof keys / sizeof *keys))
			keys[nk++] = (int)(p - P);
	}
	if (sql_done(&d, q, e))
		goto out;
	qsort(keys, (size_t)nk, sizeof *keys, cmp_idx);
	if (seed)
		keys[nk++] = (int)(params_find("seed") - P);
	/* the tree is made beside dir and put in its place whole */
	snprintf(tmp, sizeof tmp, "%s.tmp.%ld", dir, (long)getpid());
	snprintf(old, sizeof old, "%s.old.%ld", dir, (long)getpid());
	if (mkdir(tmp, 0777)) {
		sb_errf(e, SB_EIO, "%s: cannot make the view: %s", tmp, strerror(errno));
		goto out;
	}
	snprintf(path, sizeof path, "%s/" VIEW_MARK, tmp);
	FILE *m = fopen(path, "w");
	if (!m || fprintf(m, "%s\n", name) < 0 || fclose(m)) {
		sb_errf(e, SB_EIO, "%s: cannot write: %s", path, strerror(errno));
		goto undo;
	}
	char rdir[PATH_MAX];
	campaign_dir(runs_dir, name, rdir);
	sqlite3_stmt *r;
	if (sql_exec(&d, e, &r, "SELECT id FROM run WHERE campaign = ? AND current ORDER BY id", "t", name))
		goto undo;
	while (!e->code && sqlite3_step(r) == SQLITE_ROW) {
		const char *id = col(r, 0);
		char file[PATH_MAX + 64];
		run_file(rdir, id, file, sizeof file);
		if (!file[0]) {
			missing++;
			continue;
		}
		size_t o = (size_t)snprintf(path, sizeof path, "%s", tmp);
		if (!nk) /* nothing varies: the run's id names it */
			o += (size_t)snprintf(path + o, sizeof path - o, "/%s", id);
		for (int k = 0; k < nk && !e->code; k++) {
			sqlite3_stmt *v;
			char w[300] = "";
			if (sql_exec(&d, e, &v, "SELECT value FROM param WHERE campaign = ? AND run = ? AND key = ?", "ttt",
				     name, id, P[keys[k]].name))
				break;
			if (sqlite3_step(v) == SQLITE_ROW)
				view_value(v, 0, w, sizeof w);
			sql_done(&d, v, e);
			/* each key but the last a directory */
			if (o < sizeof path)
				o += (size_t)snprintf(path + o, sizeof path - o, "/%s=%s", P[keys[k]].name, w);
			if (k + 1 < nk && o < sizeof path && mkdir(path, 0777) && errno != EEXIST)
				sb_errf(e, SB_EIO, "%s: cannot make: %s", path, strerror(errno));
		}
		if (e->code)
			break;
		if (o + 40 >= sizeof path) {
			sb_errf(e, SB_EIO, "%s...: a path too long for the view", tmp);
			break;
		}
		size_t base = o;
		snprintf(path + o, sizeof path - o, ".h5");
		if (!access(path, F_OK)) { /* two runs alike in every varying key: the id tells them apart */
			snprintf(path + base, sizeof path - base, ".%s.h5", id);
			clash++;
		}
		if (symlink(file, path))
			sb_errf(e, SB_EIO, "%s: cannot make the link: %s", path, strerror(errno));
		else
			linked++;
	}
	sql_done(&d, r, e);
	if (e->code)
		goto undo;
	/* in place: the old tree (this command's) aside, the new one in, the old removed */
	if (!lstat(dir, &st) && rename(dir, old)) {
		sb_errf(e, SB_EIO, "%s: cannot replace: %s", dir, strerror(errno));
		goto undo;
	}
	if (rename(tmp, dir)) {
		sb_errf(e, SB_EIO, "%s: cannot put the view in place: %s", dir, strerror(errno));
		rename(old, dir);
		goto undo;
	}
	nftw(old, view_rm_one, 16, FTW_DEPTH | FTW_PHYS);
	fprintf(out, "view: %s: %ld links to the run files of '%s' by ", dir, linked, name);
	for (int k = 0; k < nk; k++)
		fprintf(out, "%s%s", k ? ", " : "", P[keys[k]].name);
	fprintf(out, "%s", nk ? "" : "run id (no key varies)");
	if (missing)
		fprintf(out, "; %ld runs without a file yet (not done) left out", missing);
	if (clash)
		fprintf(out, "; %ld alike in every varying key, told apart by their id", clash);
	fputc('\n', out);
	goto out;
undo:
	nftw(tmp, view_rm_one, 16, FTW_DEPTH | FTW_PHYS);
out:
	db_close(&d);
	return e->code;
}
