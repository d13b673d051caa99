/* acct.c - per-group accounting of the runs behind a statistic. */
#include "acct.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "h5id.h"
#include "h5read.h"
#include "cli.h"
#include "num.h"
#include "params.h"
#include "runfile.h"
#include "runvals.h"

static const char *const USE[AN_NUSE] = {"used", "failed_used", "unusable", "unreadable", "pending", "running"};

const char *acct_use_name(int use)
{
	return use >= 0 && use < AN_NUSE ? USE[use] : "?";
}

void acct_set(an_run *r, int use, double used_s, double planned_s, const char *fmt, ...)
{
	r->use = use;
	r->used_s = used_s;
	r->planned_s = planned_s;
	r->why[0] = 0;
	if (fmt) {
		va_list ap;
		va_start(ap, fmt);
		vsnprintf(r->why, sizeof r->why, fmt, ap);
		va_end(ap);
	}
}

/* The database's parameters of run r are the file's (/parameters): a value edited in
 * the database (frequency 15 made 25) would move the run to another group of every
 * tool. The keys compared are the numbers that make the run what it is (its
 * preparation, dynamics and length: core/scene/params.h), the ones a run's id is made of, as
 * numbers (the database may hold 15 as 15.0); not where and what it writes
 * (checkpoint_every: the driver sets it for every run), nor the choices the driver
 * resolves for a run (settle = auto is no for a run from the packing cache). A key the
 * file does not record (an older engine's) is not compared. */
static int same_params(hid_t f, const an_run *r, sb_err *e)
{
	for (int i = 0; i < r->nparam; i++) {
		const sb_param *p = params_find(r->key[i]);
		double fv, dv;
		if (!p || !r->val[i] || !(p->flags & (PF_PREP | PF_DYN | PF_LEN)) || (p->flags & (PF_DRIVER | PF_NOID)) ||
		    (p->type != PT_INT && p->type != PT_REAL) || h5r_attr_num(f, RUNFILE_PARAMS, p->name, &fv))
			continue;
		if (num_real(r->val[i], &dv) || !(fabs(fv - dv) <= 1e-12 * fmax(fabs(fv), fabs(dv))))
			return sb_errf(e, SB_EIO, "%s: %s = %.17g in the file, '%.60s' in the database: the database does "
				       "not describe this run", r->path, p->name, fv, r->val[i]);
	}
	return 0;
}

/* The database's status of run r (result.status, docs/database.md) is the file's
 * @status, which it was copied from: a status edited in the database ('ok' made
 * 'nonsense', or a failure made ok) would be reported as the run's without a word. A
 * file without @status (it is checked where it is read) or a run without a status in
 * the database is not compared. */
static int same_status(hid_t f, const an_run *r, sb_err *e)
{
	char fs[sizeof r->status];
	if (!r->status[0] || h5r_attr_str(f, "/", "status", fs, sizeof fs) || !strcmp(fs, r->status))
		return 0;
	return sb_errf(e, SB_EIO, "%s: status = '%s' in the file, '%s' in the database: the database does not "
		       "describe this run", r->path, fs, r->status);
}

int acct_classify(an_run *r)
{
	const int failed = !strcmp(r->state, "failed");
	if (!failed && strcmp(r->state, "done")) {
		/* not finished: pending, running (or a state this tool does not know) */
		acct_set(r, strcmp(r->state, "running") ? AN_PENDING : AN_RUNNING, NAN, NAN,
			 strcmp(r->state, "pending") && strcmp(r->state, "running") ? "state '%s'" : NULL, r->state);
		return 1;
	}
	if (r->bad[0]) {
		/* its parameters say nothing sure about what it ran: no value of it is used */
		acct_set(r, AN_UNUSABLE, NAN, NAN, "%s", r->bad);
		return 1;
	}
	if (access(r->path, F_OK)) {
		/* a run that failed on bad input or I/O has no file: its status says why */
		if (failed)
			acct_set(r, AN_UNUSABLE, NAN, NAN, "failed without an output file (%s%s%s)",
				 r->status[0] ? r->status : "no status", r->message[0] ? ": " : "", r->message);
		else
			acct_set(r, AN_UNREADABLE, NAN, NAN, "%s: no such file", r->path);
		return 1;
	}
	/* the file must be the one the driver recorded (its seal, checked before HDF5 reads
	 * a byte of it) and the run the database says it is: another run's file copied or
	 * linked into place, or a file changed after the engine wrote it, make it unreadable
	 * (core/io/h5id.h); so do parameters of the database that are not the file's, and
	 * values the engine cannot have written (runvals.h); its data's checksums are
	 * HDF5's to verify as the tool reads them */
	hid_t f;
	sb_err e = {0};
	int note = H5ID_OK;
	char seal[17];
	if (h5r_open_sealed(r->path, r->seal, &f, seal, &e) || h5id_check(f, r->path, r->id, &note, &e) ||
	    runvals_check(f, r->path, &e) || same_params(f, r, &e) || same_status(f, r, &e)) {
		h5r_close(f); /* -1 when it did not open: nothing */
		/* a value that is no number is there to read, and unusable */
		acct_set(r, e.code == SB_ENAN ? AN_UNUSABLE : AN_UNREADABLE, NAN, NAN, "%s", e.msg);
		return 1;
	}
	h5r_close(f);
	if (r->rows[0]) {
		/* a value the database holds for it is not the one recorded */
		acct_set(r, AN_UNUSABLE, NAN, NAN, "%s", r->rows);
		return 1;
	}
	static int noted;
	if (note != H5ID_OK && !noted++)
		fprintf(stderr, "note: %s: format %s, written before run files %s: such files are read %s "
			"(docs/inputs.md, \"Run files\")\n", r->path, note == H5ID_UNSEALED ? H5ID_FORMAT_OLD : H5ID_FORMAT_OLD3,
			note == H5ID_UNSEALED ? "named their run and carried checksums" : "were sealed whole",
			note == H5ID_UNSEALED ? "unchecked" : "with their attributes' digest checked, their data's seal not");
	return 0;
}

int acct_version_skip(const an_run *r, int all, long *nold)
{
	if (r->current)
		return 0;
	++*nold;
	return !all;
}

int acct_tally(const an_run *r, int n, int ng, an_acct **out)
{
	an_acct *a = calloc((size_t)(ng > 0 ? ng : 1), sizeof *a);
	*out = a;
	if (!a)
		return -1;
	for (int i = 0; i < n; i++) {
		if (r[i].group < 0 || r[i].group >= ng)
			continue;
		an_acct *g = &a[r[i].group];
		const int use = r[i].use >= 0 && r[i].use < AN_NUSE ? r[i].use : AN_UNUSABLE;
		g->n[use]++;
		if (use == AN_PARTLY) {
			g->used_s += isfinite(r[i].used_s) ? r[i].used_s : 0;
			g->planned_s += isfinite(r[i].planned_s) ? r[i].planned_s : 0;
		}
		if (strcmp(r[i].state, "failed"))
			continue;
		g->failed++;
		const char *st = r[i].status[0] ? r[i].status : "unknown";
		int k = 0;
		while (k < g->nreason && strcmp(g->reason[k].status, st))
			k++;
		if (k == g->nreason) {
			if (k == AN_MAXREASON) {
				k = AN_MAXREASON - 1;
				snprintf(g->reason[k].status, sizeof g->reason[k].status, "other");
			} else {
				snprintf(g->reason[k].status, sizeof g->reason[k].status, "%s", st);
				g->nreason++;
			}
		}
		g->reason[k].n++;
		g->reason[k].used += use == AN_USED || use == AN_PARTLY;
	}
	return 0;
}

long acct_used(const an_acct *a)
{
	return a->n[AN_USED] + a->n[AN_PARTLY];
}

void acct_reasons(const an_acct *a, char *buf, size_t len)
{
	size_t l = 0;
	buf[0] = 0;
	for (int k = 0; k < a->nreason && l < len; k++)
		l += (size_t)snprintf(buf + l, len - l, "%s%s=%ld", k ? ";" : "", a->reason[k].status, a->reason[k].n);
}

void acct_print(FILE *f, const char *tool, char **labels, const an_acct *a, int ng, long nold, int all_versions)
{
	long tot[AN_NUSE] = {0}, all = 0, failed = 0;
	int w = 24;
	for (int j = 0; j < ng; j++) {
		for (int u = 0; u < AN_NUSE; u++) {
			tot[u] += a[j].n[u];
			all += a[j].n[u];
		}
		failed += a[j].failed;
		int l = (int)strlen(labels[j]);
		w = l > w ? l : w;
	}
	if (all_versions)
		fprintf(f, "\n# runs: %ld, %ld of them of earlier versions of the campaign file (--all-versions)\n", all,
			nold);
	else if (nold)
		fprintf(f, "\n# runs: %ld of the campaign's current grid; %ld of earlier versions of the campaign file left out"
			   " (--all-versions uses them)\n", all, nold);
	else
		fprintf(f, "\n# runs: %ld of the campaign's current grid\n", all);
	fprintf(f, "%-*s %5s %6s %21s %8s %10s %7s %7s  %s\n", w, "group", "used", "failed", "failed_used (s of s)",
		"unusable", "unreadable", "pending", "running", "failed by status");
	for (int j = 0; j < ng; j++) {
		char part[64], why[256];
		if (a[j].n[AN_PARTLY])
			snprintf(part, sizeof part, "%ld (%.3g of %.3g)", a[j].n[AN_PARTLY], a[j].used_s, a[j].planned_s);
		else
			snprintf(part, sizeof part, "0");
		acct_reasons(&a[j], why, sizeof why);
		fprintf(f, "%-*s %5ld %6ld %21s %8ld %10ld %7ld %7ld  %s\n", w, labels[j], acct_used(&a[j]), a[j].failed, part,
			a[j].n[AN_UNUSABLE], a[j].n[AN_UNREADABLE], a[j].n[AN_PENDING], a[j].n[AN_RUNNING],
			why[0] ? why : "-");
	}
	if (tot[AN_PENDING] + tot[AN_RUNNING])
		fprintf(f, "# NOT FINISHED: %ld run%s pending and %ld running; every number above is over the runs"
			   " finished so far and will change\n", tot[AN_PENDING], tot[AN_PENDING] == 1 ? "" : "s",
			tot[AN_RUNNING]);
	if (failed)
		fprintf(f, "# %ld run%s failed: %ld used up to the failure, %ld not usable (why: %s_accounting.csv)\n", failed,
			failed == 1 ? "" : "s", tot[AN_PARTLY], failed - tot[AN_PARTLY], tool);
	if (tot[AN_UNREADABLE])
		fprintf(f, "# %ld run file%s could not be read: counted as unreadable, not used (why: %s_accounting.csv)\n",
			tot[AN_UNREADABLE], tot[AN_UNREADABLE] == 1 ? "" : "s", tool);
}

void acct_csv_head(FILE *f)
{
	fprintf(f, ",runs_failed,runs_failed_used,failed_used_s,failed_planned_s,runs_unusable,runs_unreadable,"
		   "runs_pending,runs_running,failed_by_status");
}

void acct_csv_row(FILE *f, const an_acct *a)
{
	char why[256];
	acct_reasons(a, why, sizeof why);
	fprintf(f, ",%ld,%ld,%.17g,%.17g,%ld,%ld,%ld,%ld,", a->failed, a->n[AN_PARTLY], a->used_s, a->planned_s,
		a->n[AN_UNUSABLE], a->n[AN_UNREADABLE], a->n[AN_PENDING], a->n[AN_RUNNING]);
	csv_text(f, why);
}

void acct_row_begin(FILE *f, const an_run *r, char *const *labels)
{
	fprintf(f, "%d,", r->group);
	csv_text(f, r->group >= 0 ? labels[r->group] : "");
	fprintf(f, ",%s,%ld", r->id, r->replicate);
}

void acct_runs_csv(FILE *f, const an_run *r, int n, char **labels)
{
	fprintf(f, ACCT_ROW_HEAD ",current,state,status,use,used_s,planned_s,why\n");
	for (int i = 0; i < n; i++) {
		if (r[i].group < 0)
			continue; /* in no group of this tool (e.g. a frequency not drawn) */
		acct_row_begin(f, &r[i], labels);
		fprintf(f, ",%d,%s,", r[i].current, r[i].state);
		csv_text(f, r[i].status);
		fprintf(f, ",%s,%.17g,%.17g,", acct_use_name(r[i].use), r[i].used_s, r[i].planned_s);
		csv_text(f, r[i].why);
		fputc('\n', f);
	}
}

int acct_store(adb *d, const char *campaign, const char *tool, const char *version, const char *grp,
	       const char *const *vals, const an_acct *a, sb_err *e)
{
	const struct {
		const char *key;
		double v;
	} row[] = {
		{"runs_failed", (double)a->failed},
		{"runs_failed_used", (double)a->n[AN_PARTLY]},
		{"failed_used_s", a->used_s},
		{"failed_planned_s", a->planned_s},
		{"runs_unusable", (double)a->n[AN_UNUSABLE]},
		{"runs_unreadable", (double)a->n[AN_UNREADABLE]},
		{"runs_pending", (double)a->n[AN_PENDING]},
		{"runs_running", (double)a->n[AN_RUNNING]},
	};
	for (size_t i = 0; i < sizeof row / sizeof row[0]; i++)
		if (adb_store(d, campaign, tool, version, grp, vals, row[i].key, row[i].v, NAN, NAN,
			      i == 2 || i == 3 ? a->n[AN_PARTLY] : (long)row[i].v, e))
			return e->code;
	for (int k = 0; k < a->nreason; k++) {
		char key[64];
		snprintf(key, sizeof key, "failed_%s", a->reason[k].status);
		if (adb_store(d, campaign, tool, version, grp, vals, key, (double)a->reason[k].n, NAN, NAN, a->reason[k].n, e))
			return e->code;
	}
	return 0;
}
