/* study_main.c - bin/study: campaigns of bin/shake runs. Only this file prints and exits. */
#include <errno.h>
#include <gsl/gsl_errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fsutil.h"
#include "h5read.h"
#include "layout.h"
#include "provenance.h"
#include "results.h"
#include "adaptive/search.h"
#include "adaptive/sharpen.h"
#include "campaign/campaign.h"
#include "campaign/grid.h"
#include "cli/opts.h"
#include "job/worker.h"
#include "local/driver.h"
#include "report/cost.h"
#include "report/dtext.h"
#include "report/report.h"
#include "slurm/submit.h"

/* NAME or a campaign file (then its [campaign] name). */
static int campaign_name(const char *arg, char *name, size_t len, sb_err *e)
{
	if (strchr(arg, '/') || (strlen(arg) > 9 && !strcmp(arg + strlen(arg) - 9, ".campaign"))) {
		campaign *c = malloc(sizeof *c);
		if (!c)
			return sb_errf(e, SB_ENOMEM, "out of memory");
		if (!campaign_load(c, arg, e))
			snprintf(name, len, "%s", c->name);
		campaign_free(c);
		free(c);
		return e->code;
	}
	snprintf(name, len, "%s", arg);
	return 0;
}

/* Before study run: what the campaign's Slurm tasks did, into the database; runs
 * they still hold would run twice. 0, or the exit code (4) after saying why. */
static int slurm_first(const char *arg, const char *runs, const char *db)
{
	char name[128], dbp[PATH_MAX + 32];
	sb_err e = {0};
	long active = 0;
	if (campaign_name(arg, name, sizeof name, &e))
		return 0; /* study run says what is wrong with the file */
	driver_db_path(runs, db, dbp, sizeof dbp);
	if (slurm_refresh(runs, dbp, name, &active, stderr, &e))
		fprintf(stderr, "study: %s\n", e.msg);
	if (active > 0) {
		fprintf(stderr, "study: %s: %ld runs are queued or running in Slurm (study status %s); wait for them "
			"or scancel their job before study run\n", name, active, name);
		return DRV_BUSY;
	}
	return 0;
}

/* An [onset] campaign's first round, or the first batch of every point of a grid with
 * replicates = auto: what it asks for before any result (a database in memory, with
 * nothing recorded). */
static int onset_first_round(const campaign *c, grid *g, sb_err *e)
{
	st_db mem;
	search s;
	if (db_open(&mem, ":memory:", 1, e))
		return e->code;
	if (c->autorep.on) {
		sharpen sh;
		sharpen_init(&sh, c, ".");
		sharpen_derive(&sh, g, &mem, e);
		sharpen_free(&sh);
	} else {
		search_init(&s, c, ".");
		search_derive(&s, g, &mem, e);
		search_free(&s);
	}
	db_close(&mem);
	return e->code;
}

static int own_path(char *self, size_t len);

/* The campaign's cost on stderr (report/cost.h): the rates of the integrators it uses,
 * measured once per engine build and CPU into the runs directory (measure = 0: read
 * from there only, and said to be unknown when they are not there), the shaking's
 * learnt from the campaign's finished runs where the database (db: --db, NULL: the
 * runs directory's) has some (calib_learn). */
static int print_cost(const campaign *c, const grid *g, const char *runs, const char *db, int use_cache, int measure,
		      sb_err *e)
{
	char self[PATH_MAX], shake[PATH_MAX + 8];
	if (own_path(self, sizeof self))
		return sb_errf(e, SB_EIO, "cannot find my own executable");
	snprintf(shake, sizeof shake, "%s", self);
	char *sl = strrchr(shake, '/');
	snprintf(sl ? sl + 1 : shake, sizeof shake - (size_t)(sl ? sl + 1 - shake : 0), "shake");
	cost_sum *groups = calloc((size_t)g->points + 1, sizeof *groups), total;
	if (!groups)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	cost_count(c, g, use_cache, groups, &total);
	calib rates[COST_NINTEG] = {0};
	char dbp[PATH_MAX + 32];
	driver_db_path(runs, db, dbp, sizeof dbp);
	st_db d;
	const int have_db = access(dbp, R_OK) == 0 && !db_open(&d, dbp, 0, e);
	for (int i = 0; i < COST_NINTEG && !e->code; i++)
		if (total.grain_steps[i] > 0 || total.settle_grains[i] > 0) {
			(void)(measure ? calib_get(runs, shake, i, &rates[i], e) : calib_cached(runs, shake, i, &rates[i], e));
			if (have_db && !e->code)
				calib_learn(&d, c->name, i, &rates[i], e);
		}
	if (have_db)
		db_close(&d);
	if (!e->code)
		cost_print(stderr, c, groups, g->points, &total, rates);
	free(groups);
	return e->code;
}

static int cmd_expand(const char *path, const char *runs, sb_err *e)
{
	campaign *c = malloc(sizeof *c);
	grid g = {0};
	if (!c)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	if (!campaign_load(c, path, e) && !grid_expand(&g, c, e) && (!(c->onset.line || c->autorep.on) || !onset_first_round(c, &g, e))) {
		if (c->onset.line)
			fprintf(stderr, "study: %s: an [onset] search: its first round below; the next ones depend on "
				"the results\n", path);
		for (long p = 0; c->onset.line && p < g.points; p++) {
			char pv[2048];
			search_preview(c, p, pv, sizeof pv);
			fprintf(stderr, "%s", pv);
		}
		if (c->autorep.on)
			fprintf(stderr, "study: %s: replicates = auto: the first batch of every grid point below; more "
				"replicates depend on the results\n", path);
		printf("id\tcache_key\treplicate\tseed");
		for (int a = 0; a < c->naxes; a++)
			if (strcmp(c->axes[a].key, "seed"))
				printf("\t%s", c->axes[a].key);
		if (c->onset.line || c->derive == CP_DERIVE_FREQUENCY || c->derive == CP_DERIVE_BOTH)
			printf("\tfrequency");
		if (c->derive == CP_DERIVE_AMPLITUDE || c->derive == CP_DERIVE_BOTH)
			printf("\tamplitude");
		printf("\n");
		for (long i = 0; i < g.n; i++) {
			const grid_run *r = &g.runs[i];
			sb_scene s;
			grid_scene(&g, r, &s);
			printf("%s\t%s\t%ld\t%ld", r->id, r->cache_key, r->replicate, r->seed);
			for (int a = 0; a < c->naxes; a++) {
				if (!strcmp(c->axes[a].key, "seed"))
					continue;
				char v[SB_STR_MAX + 8];
				const sb_param *p = params_find(c->axes[a].key);
				if (!p) /* gamma, velocity: the campaign's own keys */
					grid_axis_text(c, r->point, a, v, sizeof v);
				else if (p->type == PT_REAL) /* the value as written; the id hashes all 17 digits */
					dtext_shortest(*(const double *)((const char *)&s + p->offset), v, sizeof v);
				else
					params_format(&s, p, v, sizeof v);
				printf("\t%s", v);
			}
			if (c->onset.line || c->derive == CP_DERIVE_FREQUENCY || c->derive == CP_DERIVE_BOTH) {
				char v[40];
				dtext_shortest(s.frequency, v, sizeof v);
				printf("\t%s", v);
			}
			if (c->derive == CP_DERIVE_AMPLITUDE || c->derive == CP_DERIVE_BOTH) {
				char v[40];
				dtext_shortest(s.amplitude, v, sizeof v);
				printf("\t%s", v);
			}
			printf("\n");
		}
		fflush(stdout);
		/* the table is the command's answer: a cost that cannot be measured is said, not fatal */
		sb_err ce = {0};
		/* expand measures nothing: the rate comes from the cache, or is said to be unknown */
		if (print_cost(c, &g, runs, NULL, 1, 0, &ce))
			fprintf(stderr, "study: cost: %s\n", ce.msg);
	}
	grid_free(&g);
	campaign_free(c);
	free(c);
	return e->code;
}

/* The path of this program, for the workers it starts; 0, or the exit code (2). */
static int own_path(char *self, size_t len)
{
	ssize_t l = readlink("/proc/self/exe", self, len - 1);
	if (l <= 0) {
		fprintf(stderr, "study: cannot find my own executable\n");
		return 2;
	}
	self[l] = 0;
	return 0;
}

/* study run --dry-run: the cost, and nothing run or recorded (no database, no
 * campaign directory). */
static int cmd_dry_run(const study_args *o)
{
	sb_err e = {0};
	campaign *c = malloc(sizeof *c);
	grid g = {0};
	if (!c)
		return 2;
	if (!campaign_load(c, o->pos[0], &e) && !grid_expand(&g, c, &e)) {
		/* a grid extended or half run: the cost of what remains (a run whose file is
		 * there is complete: lib/layout.h), as Snakemake's -n lists only the jobs to do;
		 * a search's runs depend on the results, and its bound stays the whole one */
		long have = 0;
		if (!c->onset.line && !c->autorep.on) {
			char dir[PATH_MAX], f[PATH_MAX + 64];
			layout_campaign(o->runs ? o->runs : "runs", c->name, dir, sizeof dir);
			long k = 0;
			for (long i = 0; i < g.n; i++) {
				layout_file(dir, 0, g.runs[i].id, LAY_OUTPUT, f, sizeof f);
				if (access(f, F_OK))
					g.runs[k++] = g.runs[i];
				else
					have++;
			}
			if (have)
				fprintf(stderr, "study: %s: %ld of %ld runs are done already (their files are in %s): the cost "
						"below is of the %ld that remain\n",
					c->name, have, g.n, dir, k);
			g.n = k;
		}
		if (g.n || !have)
			print_cost(c, &g, o->runs, o->db, !o->no_cache, 1, &e);
		else
			fprintf(stderr, "study: %s: nothing remains to run\n", c->name);
	}
	grid_free(&g);
	campaign_free(c);
	free(c);
	if (e.code)
		fprintf(stderr, "study: %s\n", e.msg);
	return !e.code ? 0 : e.code == SB_EUSAGE ? DRV_USAGE : DRV_IO;
}

static int cmd_run(const study_args *o)
{
	char self[PATH_MAX];
	sb_err e = {0};
	int rc;
	if ((rc = own_path(self, sizeof self)))
		return rc;
	if (o->keep_old && o->forget_old) {
		fprintf(stderr, "study: run: --keep-old and --forget-old exclude each other\n");
		return 1;
	}
	if (o->ssh && access(o->ssh, R_OK)) {
		fprintf(stderr, "study: --sshloginfile: %s: %s\n", o->ssh, strerror(errno));
		return 1;
	}
	driver_opts d = {.campaign_file = o->pos[0], .runs_dir = o->runs, .db_path = o->db,
			 .sshloginfile = o->ssh, .self = self, .jobs = (int)o->jobs, .retry_failed = o->retry_failed,
			 .keep_old = o->keep_old, .forget_old = o->forget_old,
			 .use_cache = !o->no_cache, .progress = o->progress, .retries = (int)o->retries};
	if ((rc = slurm_first(o->pos[0], o->runs, o->db)))
		return rc;
	if (driver_run(&d, &e)) {
		fprintf(stderr, "study: %s\n", e.msg);
		return e.code == DRV_FAILED || e.code == DRV_INTERRUPTED || e.code == DRV_BUSY ? e.code
		       : e.code == SB_EUSAGE                                                    ? DRV_USAGE
											       : DRV_IO;
	}
	return 0;
}

static int cmd_submit(const study_args *o)
{
	char self[PATH_MAX];
	sb_err e = {0};
	int rc;
	if (!o->slurm) {
		fprintf(stderr, "study: submit: to which scheduler? --slurm (the only one so far)\n");
		return 1;
	}
	if (o->keep_old && o->forget_old) {
		fprintf(stderr, "study: submit: --keep-old and --forget-old exclude each other\n");
		return 1;
	}
	if ((rc = own_path(self, sizeof self)))
		return rc;
	slurm_opts so = {.sbatch_args = o->sbatch_args, .throttle = o->throttle, .runs_per_task = o->per_task, .after = o->after,
			 .dry_run = o->dry_run};
	driver_opts d = {.campaign_file = o->pos[0], .runs_dir = o->runs, .db_path = o->db, .self = self,
			 .retry_failed = o->retry_failed, .keep_old = o->keep_old, .forget_old = o->forget_old,
			 .use_cache = !o->no_cache};
	if (slurm_submit(&d, &so, &e)) {
		fprintf(stderr, "study: %s\n", e.msg);
		return e.code == DRV_BUSY || e.code == DRV_INTERRUPTED ? e.code : e.code == SB_EUSAGE ? DRV_USAGE : DRV_IO;
	}
	return 0;
}

/* status, list, export: reports from the database */
static int cmd_report(const study_args *o)
{
	sb_err e = {0};
	char dbp[PATH_MAX + 32], name[128] = "";
	driver_db_path(o->runs, o->db, dbp, sizeof dbp);
	if (o->npos && campaign_name(o->pos[0], name, sizeof name, &e)) {
		fprintf(stderr, "study: %s\n", e.msg);
		return 1;
	}
	if (o->bit == OPTS_STATUS && o->watch) {
		report_watch(dbp, o->runs, o->npos ? name : NULL, o->interval, slurm_refresh, stdout, &e);
	} else if (o->bit == OPTS_STATUS) {
		int jobs = o->jobs ? (int)o->jobs : (int)sysconf(_SC_NPROCESSORS_ONLN);
		long active;
		/* what Slurm tasks did, first (nothing without arrays recorded) */
		if (slurm_refresh(o->runs, dbp, o->npos ? name : NULL, &active, stderr, &e))
			fprintf(stderr, "study: %s\n", e.msg), e.code = 0;
		report_status(dbp, o->npos ? name : NULL, jobs, stdout, &e);
		if (!e.code)
			slurm_report(dbp, o->npos ? name : NULL, stdout, &e);
	} else if (o->bit == OPTS_LIST) {
		report_list(dbp, stdout, &e);
	} else if (o->bit == OPTS_VIEW) {
		report_view(dbp, o->runs, name, o->pos[1], stdout, &e);
	} else {
		/* --out FILE: written whole or not at all, only over nothing or a regular
		 * file (a link is not followed, a FIFO does not hang the export) */
		sb_file sf = {0};
		const char *kind;
		if (o->outfile && !fs_replaceable(o->outfile, &kind))
			sb_errf(&e, SB_EIO, "%s: %s stands there, not a regular file: not written", o->outfile, kind);
		else if (o->outfile)
			fs_open_tmp(&sf, o->outfile, &e);
		if (!e.code)
			report_export(dbp, o->runs, name, o->units, o->outfile ? sf.f : stdout, &e);
		if (o->outfile && sf.f && e.code)
			fs_abort(&sf);
		else if (o->outfile && sf.f)
			fs_commit(&sf, &e);
	}
	if (e.code) {
		fprintf(stderr, "study: %s\n", e.msg);
		return e.code == SB_EUSAGE ? 1 : 2;
	}
	return 0;
}

int main(int argc, char **argv)
{
	gsl_set_error_handler_off(); /* statuses are checked: GSL's default handler aborts */
	if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
		opts_usage(argc < 2 ? stderr : stdout);
		return argc < 2 ? 1 : 0;
	}
	if (argc == 2 && !strcmp(argv[1], "--version")) {
		printf("study (%s)\n", prov_version());
		return 0;
	}
	study_args o;
	sb_err e = {0};
	if (h5r_walk_env(&e)) { /* it would refuse every unsealed run file */
		fprintf(stderr, "study: %s\n", e.msg);
		return 1;
	}
	int rc = opts_parse(&o, argc, argv, &e);
	if (rc < 0) {
		opts_help(stdout, o.cmd);
		return 0;
	}
	if (rc) {
		fprintf(stderr, "study: %s\n", e.msg);
		if (!o.cmd) /* no command: the list of them */
			opts_usage(stderr);
		return 1;
	}
	switch (o.bit) {
	case OPTS_EXEC: {
		char self[PATH_MAX];
		if ((rc = own_path(self, sizeof self)))
			return rc;
		return worker_exec(o.pos[0], o.pos[1], o.pos[2], self);
	}
	case OPTS_RUN:
		return o.dry_run ? cmd_dry_run(&o) : cmd_run(&o);
	case OPTS_SUBMIT:
		return cmd_submit(&o);
	case OPTS_EXPAND:
		if (cmd_expand(o.pos[0], o.runs, &e)) {
			fprintf(stderr, "study: %s\n", e.msg);
			return e.code == SB_EUSAGE ? 1 : 2;
		}
		return 0;
	case OPTS_COLUMNS:
		results_markdown(stdout);
		return 0;
	case OPTS_OPTIONS:
		opts_markdown(stdout);
		return 0;
	default:
		return cmd_report(&o);
	}
}
