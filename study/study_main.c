/* study_main.c - bin/study: campaigns of bin/shake runs. Only this file prints and exits. */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "results.h"
#include "words.h"
#include "adaptive/search.h"
#include "adaptive/sharpen.h"
#include "campaign/campaign.h"
#include "campaign/grid.h"
#include "job/worker.h"
#include "local/driver.h"
#include "report/dtext.h"
#include "report/report.h"
#include "slurm/submit.h"

static const char *USAGE =
	"usage: study COMMAND [options] ...\n\n"
	"Runs a campaign (a grid of bin/shake runs) with GNU parallel and records it in SQLite.\n\n"
	"  study run CAMPAIGN       run what is not complete (resumable, extendable)\n"
	"  study status [NAME]      counts per state, failures with reasons, ETA\n"
	"  study list               the campaigns in the database\n"
	"  study export NAME        CSV of every run: parameters and results\n"
	"  study expand CAMPAIGN    check a campaign and print its grid (id, seed, values)\n"
	"  study columns            the result columns: type, place in the run file, unit, definition\n"
	"  study submit CAMPAIGN --slurm  submit the runs not done as a Slurm job array\n\n"
	"Common options: --runs DIR (outputs; default runs), --db FILE (default DIR/study.db).\n"
	"`study COMMAND --help` describes each command; study/README.md the schema.\n";

static const char *HELP_RUN =
	"usage: study run CAMPAIGN [--jobs N] [--sshloginfile FILE] [--retries N] [--retry-failed]\n"
	"                 [--no-cache] [--progress | --no-progress] [--runs DIR] [--db FILE]\n\n"
	"Expands the campaign, checks every value, records the runs in the database and runs\n"
	"each one that has no complete output yet (RUNS/NAME/RUN-ID.h5) with GNU parallel,\n"
	"ingesting each as it finishes. Kill it at any moment and run it again: finished runs\n"
	"are kept, half-way runs continue from their checkpoint. Add axis values and run again:\n"
	"only the new grid points run. A campaign with an [onset] section searches the onset\n"
	"frequency per group instead, round by round: each round runs the midpoint of every\n"
	"replicate's bracket, chosen from the results so far (study/README.md, \"Adaptive onset\n"
	"search\"); killed and run again, it asks for the same points. A grid with\n"
	"[campaign] replicates = auto runs batches of replicates per grid point until the\n"
	"interval of its result is at most target wide (study/README.md, \"Replicates until\n"
	"the answer is sharp\").\n\n"
	"  --jobs N            parallel jobs (per host with --sshloginfile; default: cores)\n"
	"  --sshloginfile FILE GNU parallel sshlogins; binaries and inputs are copied to\n"
	"                      ~/.shakebox/NAME on each host, outputs copied back; the\n"
	"                      engine beside bin/study travels (one binary for every CPU);\n"
	"                      hosts that are down are left out, a job lost with its host\n"
	"                      is redone on another\n"
	"  --retries N         a run killed by a signal, failed on I/O or lost with its host\n"
	"                      is run again up to N times (default 2; every attempt is\n"
	"                      recorded); physics failures and bad input never are\n"
	"  --retry-failed      run failed runs again (their attempts stay recorded)\n"
	"  --keep-old          the file changed and recorded runs are no longer in its grid:\n"
	"                      keep them as an earlier version (current = 0; analysis tools\n"
	"                      leave them out unless given --all-versions)\n"
	"  --forget-old        ... or delete their rows and move their files to NAME/forgotten/\n"
	"                      (without either, study run refuses and says what changed)\n"
	"  --no-cache          every run settles its own packing\n"
	"  --progress          a progress line: runs in flight with their swept values and\n"
	"                      t/T, counts, ETA (default: when stderr is a terminal)\n\n"
	"Exit codes: 0 all runs done, 1 bad campaign or usage, 2 I/O (a run's I/O fault stops\n"
	"the launching; the runs stay pending), 3 some runs failed (recorded; see study status),\n"
	"4 another driver is running this campaign (or its Slurm tasks are queued or running:\n"
	"study submit), 7 interrupted (run again to resume).\n";

static const char *HELP_STATUS =
	"usage: study status [NAME | CAMPAIGN-FILE] [--jobs N] [--watch [--interval S]] [--runs DIR]\n"
	"                    [--db FILE]\n\n"
	"Counts per state (pending, running, done, failed), packing-cache hits, every\n"
	"unsuccessful attempt with its exit code and message, and an ETA from the mean\n"
	"time of the finished runs spread over N jobs (default: cores). Without NAME: all.\n"
	"For an [onset] campaign: per group the onset, its interval, the replicates and\n"
	"runs so far, and every replicate's bracket. For a grid with replicates = auto: per\n"
	"point the replicates and runs so far, the result's estimate and the interval reached.\n\n"
	"--watch: a look every S seconds (--interval, default 2): counts, every run in flight\n"
	"with its swept values and the simulated time t/T it reached (from its journal; t ?\n"
	"for runs on other hosts), and an ETA from the simulated seconds per second measured\n"
	"over the runs in flight (else the last runs to finish). Ends when nothing is\n"
	"pending or running, when no driver runs the campaign, or on Ctrl-C.\n\n"
	"A campaign submitted to Slurm (study submit): what its tasks did is read into the\n"
	"database first, and one line per job array follows: its tasks queued, running and\n"
	"ended, its runs done, failed, stopped and not started.\n";

static const char *HELP_SUBMIT =
	"usage: study submit CAMPAIGN --slurm [--throttle K] [--runs-per-task N] [--sbatch-args \"ARGS\"]\n"
	"                    [--retry-failed] [--no-cache] [--keep-old | --forget-old] [--runs DIR] [--db FILE]\n\n"
	"Prepares the runs of the campaign that are not done as study run would (checks, argument\n"
	"files, shared packings) and submits them to Slurm as one job array (sbatch): array task\n"
	"I runs the runs on line I + 1 of RUNS/NAME/slurm/tasks-N.txt with `study exec`, through\n"
	"RUNS/NAME/slurm/array.sh. The database stays on this machine: study status, study run\n"
	"and the next study submit read back what the tasks did (outputs, logs); every run's job\n"
	"id and array index, per attempt, are in the table slurm_task. Run it again after tasks\n"
	"were cancelled, killed or hit their time limit: only the runs that are not done, and not\n"
	"still queued or running, are submitted, and a stopped run resumes from its checkpoint.\n"
	"scancel sends SIGTERM: the engine writes a checkpoint and stops, and the task starts no\n"
	"further run.\n\n"
	"  --slurm             submit to Slurm (sbatch, squeue); the only scheduler so far\n"
	"  --throttle K        at most K tasks of the array run at once (--array=...%K)\n"
	"  --runs-per-task N   N runs one after the other in each task (default 1): fewer, longer\n"
	"                      tasks for short runs\n"
	"  --sbatch-args ARGS  more sbatch options, split at whitespace, no quoting, e.g.\n"
	"                      \"--partition=short --time=02:00:00 --mem=1G\"; --array and\n"
	"                      --output are study's own; a word that is no option and no\n"
	"                      option's value is refused (sbatch would run it as its script)\n"
	"  --retry-failed      submit failed runs again too (their attempts stay recorded)\n"
	"  --no-cache          every run settles its own packing\n"
	"  --keep-old, --forget-old  the campaign file changed: as for study run\n\n"
	"Logs: RUNS/NAME/slurm/logs/JOB_INDEX.out (each task's), RUNS/NAME/logs/RUN.log (the\n"
	"engine's). The runs directory and the study and shake binaries must be on a file\n"
	"system the nodes see at the same path. [onset] searches and replicates = auto choose\n"
	"their runs from the results: run them with study run.\n"
	"Exit codes: 0 submitted (or nothing to submit), 1 bad campaign or usage, 2 sbatch,\n"
	"squeue or I/O failed, 4 another driver holds the campaign.\n";

static const char *HELP_LIST =
	"usage: study list [--runs DIR] [--db FILE]\n\n"
	"One line per campaign: runs, done, failed, pending, last update, swept axes.\n";

static const char *HELP_EXPORT =
	"usage: study export NAME|CAMPAIGN-FILE [--runs DIR] [--db FILE] [-o FILE]\n\n"
	"Writes the `runs` view of the campaign as CSV (RFC 4180): one row per run with\n"
	"every parameter, its state and its results; reals with 17 significant digits.\n";

static const char *HELP_EXPAND =
	"usage: study expand CAMPAIGN\n\n"
	"Checks the campaign file against the engine's parameter table and prints one line\n"
	"per run: id, cache key, replicate, engine seed and the swept values (TSV); for an\n"
	"[onset] campaign the runs of its first round, with their frequency (the next rounds\n"
	"depend on the results); with replicates = auto the first batch of every point.\n"
	"Nothing is run or recorded.\n";

static const char *HELP_COLUMNS =
	"usage: study columns\n\n"
	"Prints the result columns of the database (table `result`, view `runs`) as a\n"
	"Markdown table: name, SQL type, where the value is in the run's HDF5 file, unit and\n"
	"definition. study/README.md holds this table verbatim.\n";

static const char *HELP_EXEC =
	"usage: study exec DIR run|cache NAME\n\n"
	"Internal: what GNU parallel runs for one job (see study/README.md).\n";

struct opts {
	const char *runs, *db, *ssh, *outfile;
	const char *pos[4];
	int npos, jobs, retry, nocache, progress, keep_old, forget_old;
	int slurm;                                   /* submit --slurm */
	const char *throttle, *per_task, *sbatch_args; /* submit: checked there */
	int retries, watch;  /* --retries N (-1: default), status --watch */
	double interval;     /* status --watch --interval S */
};

static int parse(int argc, char **argv, struct opts *o, const char *help, int maxpos)
{
	memset(o, 0, sizeof *o);
	o->progress = -1;
	o->retries = -1;
	o->interval = 2;
	static const char *const known[] = {"--help", "--runs", "--db", "--sshloginfile", "--jobs", "--retry-failed",
					    "--keep-old", "--forget-old", "--no-cache", "--progress", "--no-progress",
					    "--retries", "--watch", "--interval",
					    "--slurm", "--throttle", "--runs-per-task", "--sbatch-args", NULL};
	for (int i = 2; i < argc; i++) {
		const char *a = argv[i];
		/* --opt=value as well as --opt value */
		char name[64];
		const char *inl = NULL, *eq = a[0] == '-' && a[1] == '-' ? strchr(a, '=') : NULL;
		if (eq && eq - a < (long)sizeof name) {
			snprintf(name, sizeof name, "%.*s", (int)(eq - a), a);
			inl = eq + 1;
			a = name;
		}
		const char *next = inl ? inl : i + 1 < argc ? argv[i + 1] : NULL;
#define VAL(opt, dst) if (!strcmp(a, opt)) { if (!next) { fprintf(stderr, "study: %s needs a value\n", opt); return 1; } dst = next; i += !inl; continue; }
		if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
			fputs(help, stdout);
			return -1;
		}
		VAL("--runs", o->runs)
		VAL("--db", o->db)
		VAL("--sshloginfile", o->ssh)
		VAL("-o", o->outfile)
		VAL("--throttle", o->throttle)
		VAL("--runs-per-task", o->per_task)
		VAL("--sbatch-args", o->sbatch_args)
		if (!strcmp(a, "--jobs") || !strcmp(a, "-j")) {
			char *end;
			long j = next ? strtol(next, &end, 10) : 0;
			if (!next || *end || j < 1 || j > 4096) {
				fprintf(stderr, "study: --jobs: expected an integer in [1, 4096]\n");
				return 1;
			}
			o->jobs = (int)j;
			i += !inl;
			continue;
		}
		if (!strcmp(a, "--retries")) {
			char *end;
			long r = next ? strtol(next, &end, 10) : -1;
			if (!next || *end || r < 0 || r > 100) {
				fprintf(stderr, "study: --retries: expected an integer in [0, 100]\n");
				return 1;
			}
			o->retries = (int)r;
			i += !inl;
			continue;
		}
		if (!strcmp(a, "--interval")) {
			char *end;
			double v = next ? strtod(next, &end) : 0;
			if (!next || *end || !(v >= 0.1 && v <= 3600)) {
				fprintf(stderr, "study: --interval: expected seconds in [0.1, 3600]\n");
				return 1;
			}
			o->interval = v;
			i += !inl;
			continue;
		}
		if (inl) {
			fprintf(stderr, "study: %s: %s takes no value (study %s --help)\n", argv[1], a, argv[1]);
			return 1;
		}
		if (!strcmp(a, "--retry-failed")) { o->retry = 1; continue; }
		if (!strcmp(a, "--keep-old")) { o->keep_old = 1; continue; }
		if (!strcmp(a, "--forget-old")) { o->forget_old = 1; continue; }
		if (!strcmp(a, "--no-cache")) { o->nocache = 1; continue; }
		if (!strcmp(a, "--progress")) { o->progress = 1; continue; }
		if (!strcmp(a, "--no-progress")) { o->progress = 0; continue; }
		if (!strcmp(a, "--slurm")) { o->slurm = 1; continue; }
		if (!strcmp(a, "--watch")) { o->watch = 1; continue; }
#undef VAL
		if (a[0] == '-' && a[1]) {
			const char *best = NULL;
			int bd = 3;
			for (int k = 0; known[k]; k++) {
				int dist = words_distance(a, known[k]);
				if (dist < bd) {
					bd = dist;
					best = known[k];
				}
			}
			if (best)
				fprintf(stderr, "study: %s: unknown option '%s'; did you mean %s? (study %s --help)\n", argv[1], a,
					best, argv[1]);
			else
				fprintf(stderr, "study: %s: unknown option '%s' (study %s --help)\n", argv[1], a, argv[1]);
			return 1;
		}
		if (o->npos >= maxpos) {
			fprintf(stderr, "study: %s: unexpected argument '%s' (study %s --help)\n", argv[1], a, argv[1]);
			return 1;
		}
		o->pos[o->npos++] = a;
	}
	return 0;
}

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

/* A count option of study submit: an integer in [lo, hi], or 0 when not given. */
static int count_opt(const char *name, const char *v, long lo, long hi, long *out)
{
	char *end;
	*out = 0;
	if (!v)
		return 0;
	long x = strtol(v, &end, 10);
	if (!*v || *end || x < lo || x > hi) {
		fprintf(stderr, "study: submit: %s: expected an integer in [%ld, %ld], got '%s'\n", name, lo, hi, v);
		return 1;
	}
	*out = x;
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

static int cmd_expand(const char *path, sb_err *e)
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
	}
	grid_free(&g);
	campaign_free(c);
	free(c);
	return e->code;
}

int main(int argc, char **argv)
{
	if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
		fputs(USAGE, argc < 2 ? stderr : stdout);
		return argc < 2 ? 1 : 0;
	}
	const char *cmd = argv[1];
	struct opts o;
	sb_err e = {0};
	char dbp[PATH_MAX + 32];
	int rc;
	if (!strcmp(cmd, "exec")) {
		if (argc == 3 && !strcmp(argv[2], "--help")) {
			fputs(HELP_EXEC, stdout);
			return 0;
		}
		if (argc != 5) {
			fputs(HELP_EXEC, stderr);
			return 1;
		}
		char self[PATH_MAX];
		ssize_t l = readlink("/proc/self/exe", self, sizeof self - 1);
		if (l <= 0) {
			fprintf(stderr, "study: cannot find my own executable\n");
			return 2;
		}
		self[l] = 0;
		return worker_exec(argv[2], argv[3], argv[4], self);
	}
	if (!strcmp(cmd, "run")) {
		if ((rc = parse(argc, argv, &o, HELP_RUN, 1)))
			return rc < 0 ? 0 : 1;
		if (o.npos != 1) {
			fputs(HELP_RUN, stderr);
			return 1;
		}
		char self[PATH_MAX];
		ssize_t l = readlink("/proc/self/exe", self, sizeof self - 1);
		if (l <= 0) {
			fprintf(stderr, "study: cannot find my own executable\n");
			return 2;
		}
		self[l] = 0;
		if (o.keep_old && o.forget_old) {
			fprintf(stderr, "study: run: --keep-old and --forget-old exclude each other\n");
			return 1;
		}
		if (o.ssh && access(o.ssh, R_OK)) {
			fprintf(stderr, "study: --sshloginfile: %s: %s\n", o.ssh, strerror(errno));
			return 1;
		}
		driver_opts d = {.campaign_file = o.pos[0], .runs_dir = o.runs, .db_path = o.db,
				 .sshloginfile = o.ssh, .self = self, .jobs = o.jobs, .retry_failed = o.retry,
				 .keep_old = o.keep_old, .forget_old = o.forget_old,
				 .use_cache = !o.nocache, .progress = o.progress,
				 .retries = o.retries < 0 ? DRIVER_RETRIES : o.retries};
		if ((rc = slurm_first(o.pos[0], o.runs, o.db)))
			return rc;
		if (driver_run(&d, &e)) {
			fprintf(stderr, "study: %s\n", e.msg);
			return e.code == DRV_FAILED || e.code == DRV_INTERRUPTED || e.code == DRV_BUSY ? e.code
			       : e.code == SB_EUSAGE                             ? DRV_USAGE
										 : DRV_IO;
		}
		return 0;
	}
	if (!strcmp(cmd, "submit")) {
		if ((rc = parse(argc, argv, &o, HELP_SUBMIT, 1)))
			return rc < 0 ? 0 : 1;
		if (o.npos != 1) {
			fputs(HELP_SUBMIT, stderr);
			return 1;
		}
		if (!o.slurm) {
			fprintf(stderr, "study: submit: to which scheduler? --slurm (the only one so far)\n");
			return 1;
		}
		slurm_opts so = {.sbatch_args = o.sbatch_args};
		if (count_opt("--throttle", o.throttle, 1, 1000000, &so.throttle) ||
		    count_opt("--runs-per-task", o.per_task, 1, 1000000, &so.runs_per_task))
			return 1;
		if (!so.runs_per_task)
			so.runs_per_task = 1;
		if (o.keep_old && o.forget_old) {
			fprintf(stderr, "study: submit: --keep-old and --forget-old exclude each other\n");
			return 1;
		}
		char self[PATH_MAX];
		ssize_t l = readlink("/proc/self/exe", self, sizeof self - 1);
		if (l <= 0) {
			fprintf(stderr, "study: cannot find my own executable\n");
			return 2;
		}
		self[l] = 0;
		driver_opts d = {.campaign_file = o.pos[0], .runs_dir = o.runs, .db_path = o.db, .self = self,
				 .retry_failed = o.retry, .keep_old = o.keep_old, .forget_old = o.forget_old,
				 .use_cache = !o.nocache};
		if (slurm_submit(&d, &so, &e)) {
			fprintf(stderr, "study: %s\n", e.msg);
			return e.code == DRV_BUSY ? DRV_BUSY : e.code == SB_EUSAGE ? DRV_USAGE : DRV_IO;
		}
		return 0;
	}
	if (!strcmp(cmd, "expand")) {
		if ((rc = parse(argc, argv, &o, HELP_EXPAND, 1)))
			return rc < 0 ? 0 : 1;
		if (o.npos != 1) {
			fputs(HELP_EXPAND, stderr);
			return 1;
		}
		if (cmd_expand(o.pos[0], &e)) {
			fprintf(stderr, "study: %s\n", e.msg);
			return e.code == SB_EUSAGE ? 1 : 2;
		}
		return 0;
	}
	if (!strcmp(cmd, "columns")) {
		if ((rc = parse(argc, argv, &o, HELP_COLUMNS, 0)))
			return rc < 0 ? 0 : 1;
		results_markdown(stdout);
		return 0;
	}
	const char *help = !strcmp(cmd, "status") ? HELP_STATUS : !strcmp(cmd, "list") ? HELP_LIST
			   : !strcmp(cmd, "export")                                    ? HELP_EXPORT
										       : NULL;
	if (!help) {
		fprintf(stderr, "study: unknown command '%s'\n%s", cmd, USAGE);
		return 1;
	}
	if ((rc = parse(argc, argv, &o, help, !strcmp(cmd, "list") ? 0 : 1)))
		return rc < 0 ? 0 : 1;
	driver_db_path(o.runs, o.db, dbp, sizeof dbp);
	char name[128] = "";
	if (o.npos && campaign_name(o.pos[0], name, sizeof name, &e)) {
		fprintf(stderr, "study: %s\n", e.msg);
		return 1;
	}
	if (!strcmp(cmd, "status") && o.watch) {
		report_watch(dbp, o.runs, o.npos ? name : NULL, o.interval, slurm_refresh, stdout, &e);
	} else if (!strcmp(cmd, "status")) {
		int jobs = o.jobs ? o.jobs : (int)sysconf(_SC_NPROCESSORS_ONLN);
		long active;
		/* what Slurm tasks did, first (nothing without arrays recorded) */
		if (slurm_refresh(o.runs, dbp, o.npos ? name : NULL, &active, stderr, &e))
			fprintf(stderr, "study: %s\n", e.msg), e.code = 0;
		report_status(dbp, o.npos ? name : NULL, jobs, stdout, &e);
		if (!e.code)
			slurm_report(dbp, o.npos ? name : NULL, stdout, &e);
	} else if (!strcmp(cmd, "list")) {
		report_list(dbp, stdout, &e);
	} else {
		if (o.npos != 1) {
			fputs(HELP_EXPORT, stderr);
			return 1;
		}
		FILE *out = o.outfile ? fopen(o.outfile, "w") : stdout;
		if (!out) {
			fprintf(stderr, "study: %s: %s\n", o.outfile, strerror(errno));
			return 2;
		}
		report_export(dbp, name, out, &e);
		if (o.outfile && fclose(out) && !e.code)
			sb_errf(&e, SB_EIO, "%s: cannot write", o.outfile);
	}
	if (e.code) {
		fprintf(stderr, "study: %s\n", e.msg);
		return e.code == SB_EUSAGE ? 1 : 2;
	}
	return 0;
}
