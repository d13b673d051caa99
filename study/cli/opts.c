/* opts.c - bin/study's commands and options, one table each (opts.h). */
#include "cli/opts.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "words.h"
#include "local/driver.h" /* DRIVER_RETRIES: the default of --retries */

/* ---- the commands ---- */

typedef struct command {
	const char *name;
	unsigned bit;
	const char *operands; /* as the usage line names them */
	int min_pos, max_pos;
	const char *summary;  /* study --help: one line; NULL: internal, not listed */
	const char *text;     /* study CMD --help: what it does (before the options) */
	const char *tail;     /* ... and after them (exit codes, files); NULL: none */
} command;

static const command CMDS[] = {
	{"run", OPTS_RUN, "CAMPAIGN", 1, 1, "run what is not complete (resumable, extendable)",
	 "Expands the campaign, checks every value, records the runs in the database and runs\n"
	 "each one that has no complete output yet (RUNS/NAME/RUN-ID.h5) with GNU parallel,\n"
	 "ingesting each as it finishes. Kill it at any moment and run it again: finished runs\n"
	 "are kept, half-way runs continue from their checkpoint. Add axis values and run again:\n"
	 "only the new grid points run. A campaign with an [onset] section searches the onset\n"
	 "frequency per group instead, round by round: each round runs the midpoint of every\n"
	 "replicate's bracket, chosen from the results so far (docs/campaigns.md, \"Adaptive\n"
	 "onset search\"); killed and run again, it asks for the same points. A grid with\n"
	 "[campaign] replicates = auto runs batches of replicates per grid point until the\n"
	 "interval of its result is at most target wide (docs/campaigns.md, \"Replicates until\n"
	 "the answer is sharp\"). Across ssh hosts: docs/cluster.md.\n",
	 "Exit codes: 0 all runs done, 1 bad campaign or usage, 2 I/O (a run's I/O fault stops\n"
	 "the launching; the runs stay pending), 3 some runs failed (recorded; see study status),\n"
	 "4 another driver is running this campaign (or its Slurm tasks are queued or running:\n"
	 "study submit), 7 interrupted (run again to resume).\n"},
	{"status", OPTS_STATUS, "[NAME | CAMPAIGN-FILE]", 0, 1, "counts per state, failures with reasons, ETA",
	 "Counts per state (pending, running, done, failed), packing-cache hits, every\n"
	 "unsuccessful attempt with its exit code and message, and an ETA from the pace of the\n"
	 "last runs to finish (with one finished run: its time spread over N jobs); for a search\n"
	 "or replicates = auto over the whole campaign, at most (its chains and replicates at\n"
	 "their longest), not the current round. Without\n"
	 "NAME: all. For an [onset] campaign: per group the onset, its interval, the replicates\n"
	 "and runs so far, and every replicate's bracket. For a grid with replicates = auto: per\n"
	 "point the replicates and runs so far, the result's estimate and the interval reached.\n\n"
	 "--watch: a look every S seconds (--interval): counts, every run in flight with its\n"
	 "swept values and the simulated time t/T it reached (from its journal; t ? for runs on\n"
	 "other hosts), and an ETA from the simulated seconds per second measured over the runs\n"
	 "in flight (else the last runs to finish). Ends when nothing is pending or running,\n"
	 "when no driver runs the campaign, or on Ctrl-C.\n\n"
	 "A campaign submitted to Slurm (study submit): what its tasks did is read into the\n"
	 "database first, and one line per job array follows: its tasks queued, running and\n"
	 "ended, its runs done, failed, stopped and not started.\n",
	 NULL},
	{"list", OPTS_LIST, "", 0, 0, "the campaigns in the database",
	 "One line per campaign: runs, done, failed, pending, last update, swept axes.\n", NULL},
	{"export", OPTS_EXPORT, "NAME|CAMPAIGN-FILE", 1, 1, "CSV of every run: parameters and results",
	 "Writes the `runs` view of the campaign as CSV (RFC 4180): one row per run with\n"
	 "every parameter, its state and its results; reals with 17 significant digits\n"
	 "(the columns: docs/database.md), then `file`: the run's file, an absolute path\n"
	 "(empty while the run has none). --units: a second row with each column's unit.\n",
	 NULL},
	{"view", OPTS_VIEW, "NAME|CAMPAIGN-FILE DIR", 2, 2, "links to the run files named by their parameters",
	 "Makes DIR a tree of symbolic links to the campaign's run files, named by the\n"
	 "parameters that vary between its current runs, seed last: DIR/frequency=2.8/\n"
	 "radius_ratio=4/seed=3.h5 (as signac's view does). Runs without a file yet are left\n"
	 "out and counted. DIR is made, or remade when this command made it before for the\n"
	 "same campaign; anything else standing there is refused and not touched. The tree is\n"
	 "made beside DIR and put in its place whole; the links are absolute paths.\n",
	 "Exit codes: 0 made, 1 usage or DIR not this command's, 2 I/O.\n"},
	{"expand", OPTS_EXPAND, "CAMPAIGN", 1, 1, "check a campaign and print its grid (id, seed, values)",
	 "Checks the campaign file against the engine's parameter table and prints one line\n"
	 "per run: id, cache key, replicate, engine seed and the swept values (TSV); for an\n"
	 "[onset] campaign the runs of its first round, with their frequency (the next rounds\n"
	 "depend on the results); with replicates = auto the first batch of every point.\n"
	 "Nothing is run or recorded. After the table, on stderr, what the whole campaign will\n"
	 "cost (as study run --dry-run says it; docs/campaigns.md, \"Cost before the start\").\n",
	 NULL},
	{"columns", OPTS_COLUMNS, "", 0, 0, "the result columns: type, place in the run file, unit, definition",
	 "Prints the result columns of the database (table `result`, view `runs`) as a\n"
	 "Markdown table: name, SQL type, where the value is in the run's HDF5 file, unit and\n"
	 "definition. docs/database.md holds this table verbatim.\n",
	 NULL},
	{"options", OPTS_OPTIONS, "", 0, 0, "every option of every command, as a Markdown table",
	 "Prints this program's options as a Markdown table: option, value and range, the\n"
	 "commands that take it, default, meaning. docs/campaigns.md holds this table verbatim.\n",
	 NULL},
	{"submit", OPTS_SUBMIT, "CAMPAIGN", 1, 1, "submit the runs not done as a Slurm job array (--slurm)",
	 "Prepares the runs of the campaign that are not done as study run would (checks, argument\n"
	 "files, shared packings) and submits them to Slurm as one job array (sbatch): array task\n"
	 "I runs the runs on line I + 1 of RUNS/NAME/slurm/tasks-N.txt with `study exec`, through\n"
	 "RUNS/NAME/slurm/array.sh. The database stays on this machine: study status, study run\n"
	 "and the next study submit read back what the tasks did (outputs, logs); every run's job\n"
	 "id and array index, per attempt, are in the table slurm_task. Run it again after tasks\n"
	 "were cancelled, killed or hit their time limit: only the runs that are not done, and not\n"
	 "still queued or running, are submitted, and a stopped run resumes from its checkpoint.\n"
	 "scancel sends SIGTERM: the engine writes a checkpoint and stops, and the task starts no\n"
	 "further run. The manual: docs/cluster.md.\n",
	 "Logs: RUNS/NAME/slurm/logs/JOB_INDEX.out (each task's), RUNS/NAME/logs/RUN.log (the\n"
	 "engine's). The runs directory and the study and shake binaries must be on a file\n"
	 "system the nodes see at the same path. An [onset] search or replicates = auto goes\n"
	 "round by round: each round is an array, and a planning job that runs when it has\n"
	 "ended submits the next (docs/cluster.md, \"Searches on Slurm\").\n"
	 "Exit codes: 0 submitted (or nothing to submit), 1 bad campaign or usage, 2 sbatch,\n"
	 "squeue or I/O failed, 4 another driver holds the campaign, 7 a planning job whose\n"
	 "round finished no run (the search stops there).\n"},
	{"exec", OPTS_EXEC, "DIR run|cache NAME", 3, 3, NULL,
	 "Internal: what GNU parallel (or a Slurm task) runs for one job (docs/cluster.md).\n", NULL},
};
enum { NCMDS = sizeof CMDS / sizeof *CMDS };

/* ---- the options ---- */

typedef enum { OT_FLAG, OT_STR, OT_INT, OT_REAL } otype;

typedef struct option {
	const char *name; /* without the dashes */
	char shrt;        /* one-letter form (0: none) */
	otype type;
	const char *meta; /* the value's name in help (NULL: a flag) */
	unsigned cmds;    /* OPTS_* bits of the commands that take it */
	size_t off;       /* the field of study_args it sets */
	double lo, hi;    /* numbers: the valid range */
	double dflt;      /* the field's value when not given; a flag's value when given */
	const char *dtext; /* the default as help says it (NULL: none to say) */
	const char *help;
} option;

/* The offset of a field of study_args that must have type T: a row whose field has
 * another type does not compile (the typed rows of Redis's config.c). */
#define FIELD(f, T) _Generic(((study_args *)0)->f, T: offsetof(study_args, f))
#define FLAG(nm, sh, f, set, cm, help) {nm, sh, OT_FLAG, NULL, cm, FIELD(f, int), 0, 0, set, NULL, help}
#define STR(nm, sh, meta, f, cm, dtext, help) {nm, sh, OT_STR, meta, cm, FIELD(f, const char *), 0, 0, 0, dtext, help}
#define INT(nm, sh, meta, f, cm, lo, hi, dflt, dtext, help) \
	{nm, sh, OT_INT, meta, cm, FIELD(f, long), lo, hi, dflt, dtext, help}
#define REAL(nm, sh, meta, f, cm, lo, hi, dflt, dtext, help) \
	{nm, sh, OT_REAL, meta, cm, FIELD(f, double), lo, hi, dflt, dtext, help}

#define ALL (OPTS_RUN | OPTS_STATUS | OPTS_LIST | OPTS_EXPORT | OPTS_EXPAND | OPTS_COLUMNS | OPTS_OPTIONS | OPTS_SUBMIT | OPTS_EXEC | OPTS_VIEW)
#define DB_USERS (OPTS_RUN | OPTS_STATUS | OPTS_LIST | OPTS_EXPORT | OPTS_SUBMIT | OPTS_VIEW)

static const option OPTS[] = {
	STR("runs", 0, "DIR", runs, DB_USERS | OPTS_EXPAND, "runs",
	    "the runs directory: outputs, logs, packings, the database, the engine's measured cost (expand only "
	    "reads that)"),
	STR("db", 0, "FILE", db, DB_USERS, "DIR/study.db", "the database"),
	INT("jobs", 'j', "N", jobs, OPTS_RUN | OPTS_STATUS, 1, 4096, 0, "cores",
	    "parallel jobs (per host with --sshloginfile); status: the jobs its ETA assumes while the pace of "
	    "finished runs is not known"),
	STR("sshloginfile", 0, "FILE", ssh, OPTS_RUN, NULL,
	    "GNU parallel sshlogins; binaries and inputs are copied to ~/.shakebox/NAME on each host, outputs "
	    "copied back; the engine beside bin/study travels (one binary for every CPU); hosts that are down are "
	    "left out, a job lost with its host is redone on another"),
	INT("retries", 0, "N", retries, OPTS_RUN, 0, 100, DRIVER_RETRIES, NULL,
	    "a run killed by a signal, failed on I/O or lost with its host is run again up to N times (every "
	    "attempt is recorded); physics failures and bad input never are"),
	FLAG("retry-failed", 0, retry_failed, 1, OPTS_RUN | OPTS_SUBMIT,
	     "run (or submit) failed runs again; their attempts stay recorded"),
	FLAG("keep-old", 0, keep_old, 1, OPTS_RUN | OPTS_SUBMIT,
	     "the file changed and recorded runs are no longer in its grid: keep them as an earlier version "
	     "(current = 0; analysis tools leave them out unless given --all-versions)"),
	FLAG("forget-old", 0, forget_old, 1, OPTS_RUN | OPTS_SUBMIT,
	     "the file changed and recorded runs are no longer in its grid: delete their rows and move their files "
	     "to NAME/forgotten/ (without --keep-old or --forget-old a changed file is refused, saying what changed)"),
	FLAG("dry-run", 0, dry_run, 1, OPTS_RUN | OPTS_SUBMIT,
	     "run: run nothing, record nothing: print the campaign's runs, simulated seconds and CPU time at this "
	     "machine's measured rate (upper bounds for a search or replicates = auto; of a grid only what remains) "
	     "and stop; submit: prepare as a submit does, then print the array script, the task lines and the "
	     "sbatch command, and submit nothing"),
	FLAG("no-cache", 0, no_cache, 1, OPTS_RUN | OPTS_SUBMIT, "every run settles its own packing"),
	FLAG("progress", 0, progress, 1, OPTS_RUN,
	     "a progress line: runs in flight with their swept values and t/T, counts, ETA (default: when stderr "
	     "is a terminal)"),
	FLAG("no-progress", 0, progress, 0, OPTS_RUN, "no progress line"),
	FLAG("watch", 0, watch, 1, OPTS_STATUS, "live: counts, runs in flight with t/T, ETA, every --interval seconds"),
	REAL("interval", 0, "S", interval, OPTS_STATUS, 0.1, 3600, 2, NULL, "seconds between two looks of --watch"),
	FLAG("slurm", 0, slurm, 1, OPTS_SUBMIT, "submit to Slurm (sbatch, squeue); the only scheduler so far"),
	INT("throttle", 0, "K", throttle, OPTS_SUBMIT, 1, 1000000, 0, "no limit",
	    "at most K tasks of the array run at once (--array=...%K)"),
	INT("runs-per-task", 0, "N", per_task, OPTS_SUBMIT, 1, 1000000, 1, NULL,
	    "N runs one after the other in each task: fewer, longer tasks for short runs"),
	STR("sbatch-args", 0, "ARGS", sbatch_args, OPTS_SUBMIT, NULL,
	    "more sbatch options, split at whitespace, no quoting, e.g. \"--partition=short --time=02:00:00 "
	    "--mem=1G\"; --array and --output are study's own; a word that is no option and no option's value is "
	    "refused (sbatch would run it as its script)"),
	INT("after", 0, "JOB", after, OPTS_SUBMIT, 1, 1e15, 0, "none",
	    "set by the planning job of an [onset] search or replicates = auto (plan.sh): the Slurm job of the "
	    "round it follows; when that round finished no run (cancelled) the search stops, and the next study "
	    "submit goes on"),
	STR("output", 'o', "FILE", outfile, OPTS_EXPORT, "standard output", "the CSV into FILE"),
	FLAG("units", 0, units, 1, OPTS_EXPORT, "a second row with each column's unit (\"\" where it has none)"),
	FLAG("help", 'h', help, 1, ALL, "this help"),
};
enum { NOPTS = sizeof OPTS / sizeof *OPTS };

/* ---- parsing ---- */

static const command *find_command(const char *name)
{
	for (int i = 0; i < NCMDS; i++)
		if (!strcmp(CMDS[i].name, name))
			return &CMDS[i];
	return NULL;
}

static int is_help(const option *o)
{
	return !strcmp(o->name, "help");
}

/* The row of --name (len letters of it) or of -c. */
static const option *find_long(const char *name, size_t len)
{
	for (int i = 0; i < NOPTS; i++)
		if (strlen(OPTS[i].name) == len && !strncmp(OPTS[i].name, name, len))
			return &OPTS[i];
	return NULL;
}

static const option *find_short(char c)
{
	for (int i = 0; i < NOPTS; i++)
		if (OPTS[i].shrt && OPTS[i].shrt == c)
			return &OPTS[i];
	return NULL;
}

/* "--runs, --db, ..." : the options cmd takes, into buf */
static void option_list(unsigned bit, char *buf, size_t n)
{
	size_t l = 0;
	buf[0] = 0;
	for (int i = 0; i < NOPTS && l < n; i++)
		if (OPTS[i].cmds & bit)
			l += (size_t)snprintf(buf + l, n - l, "%s--%s", l ? ", " : "", OPTS[i].name);
}

/* The commands that take o, as "study status" or "study run and study submit". */
static void command_list(const option *o, char *buf, size_t n)
{
	size_t l = 0;
	int k = 0, total = 0;
	buf[0] = 0;
	for (int i = 0; i < NCMDS; i++)
		total += !!(o->cmds & CMDS[i].bit);
	for (int i = 0; i < NCMDS && l < n; i++)
		if (o->cmds & CMDS[i].bit) {
			k++;
			l += (size_t)snprintf(buf + l, n - l, "%sstudy %s", k == 1 ? "" : k == total ? " and " : ", ",
					      CMDS[i].name);
		}
}

/* An unknown option: named, with the nearest option of the command when one is near
 * (two edits at most, as for the engine's keys), and the ones the command takes. */
static int unknown(const command *c, const char *arg, sb_err *e)
{
	char name[64], list[512];
	snprintf(name, sizeof name, "%.*s", (int)strcspn(arg, "="), arg);
	const char *best = NULL;
	int bd = 3;
	for (int i = 0; i < NOPTS; i++) {
		if (!(OPTS[i].cmds & c->bit))
			continue;
		char full[64];
		snprintf(full, sizeof full, "--%s", OPTS[i].name);
		const int d = words_distance(name, full);
		if (d < bd) {
			bd = d;
			best = OPTS[i].name;
		}
	}
	option_list(c->bit, list, sizeof list);
	if (best)
		return sb_errf(e, SB_EUSAGE, "%s: unknown option '%s'; did you mean --%s? (study %s takes %s)", c->name,
			       name, best, c->name, list);
	return sb_errf(e, SB_EUSAGE, "%s: unknown option '%s' (study %s takes %s)", c->name, name, c->name, list);
}

/* "an integer in [1, 4096]" */
static void range_text(const option *o, char *buf, size_t n)
{
	snprintf(buf, n, "%s in [%.15g, %.15g]", o->type == OT_INT ? "an integer" : "a number", o->lo, o->hi);
}

/* The value v of o (given as the word shown) into a. */
static int set_value(const command *c, const option *o, const char *shown, const char *v, study_args *a, sb_err *e)
{
	char *field = (char *)a + o->off, *end;
	if (o->type == OT_STR) {
		*(const char **)field = v;
		return 0;
	}
	char range[64];
	range_text(o, range, sizeof range);
	if (o->type == OT_INT) {
		long x = strtol(v, &end, 10);
		if (!*v || *end || x < o->lo || x > o->hi)
			return sb_errf(e, SB_EUSAGE, "%s: %s: expected %s, got '%s'", c->name, shown, range, v);
		*(long *)field = x;
		return 0;
	}
	double x = strtod(v, &end);
	if (!*v || *end || !(x >= o->lo && x <= o->hi))
		return sb_errf(e, SB_EUSAGE, "%s: %s: expected %s, got '%s'", c->name, shown, range, v);
	*(double *)field = x;
	return 0;
}

static void defaults(study_args *a)
{
	memset(a, 0, sizeof *a);
	for (int i = 0; i < NOPTS; i++) {
		const option *o = &OPTS[i];
		char *field = (char *)a + o->off;
		if (o->type == OT_INT)
			*(long *)field = (long)o->dflt;
		else if (o->type == OT_REAL)
			*(double *)field = o->dflt;
	}
	a->progress = -1; /* neither --progress nor --no-progress: decided by the terminal */
}

int opts_parse(study_args *a, int argc, char **argv, sb_err *e)
{
	defaults(a);
	if (argc < 2)
		return sb_errf(e, SB_EUSAGE, "which command? (study --help)");
	const command *c = find_command(argv[1]);
	if (!c) {
		const char *best = NULL;
		int bd = 3;
		for (int i = 0; i < NCMDS; i++) {
			const int d = words_distance(argv[1], CMDS[i].name);
			if (d < bd) {
				bd = d;
				best = CMDS[i].name;
			}
		}
		if (best)
			return sb_errf(e, SB_EUSAGE, "unknown command '%s'; did you mean %s?", argv[1], best);
		return sb_errf(e, SB_EUSAGE, "unknown command '%s'", argv[1]);
	}
	a->cmd = c->name;
	a->bit = c->bit;
	int only_operands = 0;
	for (int i = 2; i < argc; i++) {
		const char *arg = argv[i];
		if (only_operands || arg[0] != '-' || !arg[1]) {
			if (a->npos >= c->max_pos)
				return sb_errf(e, SB_EUSAGE, "%s: unexpected argument '%s' (study %s --help)", c->name, arg,
					       c->name);
			a->pos[a->npos++] = arg;
			continue;
		}
		if (!strcmp(arg, "--")) {
			only_operands = 1;
			continue;
		}
		/* --name, --name=value, -c */
		const option *o;
		const char *inl = NULL;
		char shown[64];
		if (arg[1] == '-') {
			const char *eq = strchr(arg + 2, '=');
			const size_t len = eq ? (size_t)(eq - arg - 2) : strlen(arg + 2);
			o = find_long(arg + 2, len);
			inl = eq ? eq + 1 : NULL;
		} else {
			/* -j 2 and, as getopt reads it, -j2: the rest of the word is the value
			 * (a flag takes none; flags are not bundled) */
			o = find_short(arg[1]);
			if (o && arg[2] && o->type == OT_FLAG)
				o = NULL;
			else if (o && arg[2])
				inl = arg + 2;
		}
		if (!o)
			return unknown(c, arg, e);
		snprintf(shown, sizeof shown, "%.*s", arg[1] == '-' ? (int)strcspn(arg, "=") : 2, arg);
		if (!(o->cmds & c->bit)) {
			char by[256];
			command_list(o, by, sizeof by);
			return sb_errf(e, SB_EUSAGE, "%s: %s is an option of %s, not of study %s (study %s --help)", c->name,
				       shown, by, c->name, c->name);
		}
		if (o->type == OT_FLAG) {
			if (inl)
				return sb_errf(e, SB_EUSAGE, "%s: %s takes no value (study %s --help)", c->name, shown,
					       c->name);
			if (is_help(o))
				return -1;
			*(int *)((char *)a + o->off) = (int)o->dflt;
			continue;
		}
		/* the next word is the value whatever it looks like: --sbatch-args "--time=10" */
		const char *v = inl ? inl : i + 1 < argc ? argv[++i] : NULL;
		if (!v) {
			char range[64] = "";
			if (o->type != OT_STR)
				range_text(o, range, sizeof range);
			return sb_errf(e, SB_EUSAGE, "%s: %s needs a value (%s%s%s)", c->name, shown, o->meta,
				       *range ? ": " : "", range);
		}
		if (set_value(c, o, shown, v, a, e))
			return SB_EUSAGE;
	}
	if (a->npos < c->min_pos)
		return sb_errf(e, SB_EUSAGE, "%s: expected %s (usage: study %s %s [options]; study %s --help)", c->name,
			       c->operands, c->name, c->operands, c->name);
	return 0;
}

/* ---- help ---- */

enum { WIDTH = 90, HELP_COL = 22 };

/* text, word-wrapped from column col to WIDTH (the first line starts at column at) */
static void wrap(FILE *out, const char *text, int at, int col)
{
	int x = at;
	for (const char *p = text; *p;) {
		while (*p == ' ')
			p++;
		const int w = (int)strcspn(p, " ");
		if (!w)
			break;
		if (x > col && x + 1 + w > WIDTH) {
			fprintf(out, "\n%*s", col, "");
			x = col;
		} else if (x > col) {
			fputc(' ', out);
			x++;
		} else if (x < col) {
			fprintf(out, "%*s", col - x, "");
			x = col;
		}
		fprintf(out, "%.*s", w, p);
		x += w;
		p += w;
	}
	fputc('\n', out);
}

/* "-j, --jobs N" */
static void label(const option *o, char *buf, size_t n)
{
	if (o->shrt)
		snprintf(buf, n, "-%c, --%s%s%s", o->shrt, o->name, o->meta ? " " : "", o->meta ? o->meta : "");
	else
		snprintf(buf, n, "--%s%s%s", o->name, o->meta ? " " : "", o->meta ? o->meta : "");
}

/* What help says after an option's text: its range and default. */
static void range_default(const option *o, char *buf, size_t n)
{
	char range[64] = "", dflt[64] = "";
	if (o->type == OT_INT || o->type == OT_REAL)
		snprintf(range, sizeof range, "%s in [%.15g, %.15g]", o->meta, o->lo, o->hi);
	if (o->dtext)
		snprintf(dflt, sizeof dflt, "default: %s", o->dtext);
	else if (o->type == OT_INT || o->type == OT_REAL)
		snprintf(dflt, sizeof dflt, "default: %.15g", o->dflt);
	snprintf(buf, n, "%s%s%s", range, *range && *dflt ? "; " : "", dflt);
}

void opts_usage(FILE *out)
{
	fputs("usage: study COMMAND [options] ...\n\n"
	      "Runs a campaign (a grid of bin/shake runs) with GNU parallel and records it in SQLite.\n\n",
	      out);
	for (int i = 0; i < NCMDS; i++) {
		if (!CMDS[i].summary)
			continue;
		char head[64];
		snprintf(head, sizeof head, "study %s %s", CMDS[i].name, CMDS[i].operands);
		if (strlen(head) > 24) /* a long one: its summary on the next line */
			fprintf(out, "  %s\n  %-24s %s\n", head, "", CMDS[i].summary);
		else
			fprintf(out, "  %-24s %s\n", head, CMDS[i].summary);
	}
	fputs("\n`study COMMAND --help` lists the options of each command. The manual:\n"
	      "docs/campaigns.md (campaign files, options, exit codes), docs/cluster.md (ssh hosts,\n"
	      "Slurm), docs/database.md (the database and its result columns).\n",
	      out);
}

int opts_help(FILE *out, const char *name)
{
	const command *c = find_command(name);
	if (!c)
		return 1;
	/* the usage line: operands, then every option but --help */
	char head[64];
	snprintf(head, sizeof head, "usage: study %s%s%s", c->name, *c->operands ? " " : "", c->operands);
	fputs(head, out);
	int x = (int)strlen(head);
	const int col = (int)strlen("usage: study ") + (int)strlen(c->name) + 1;
	for (int i = 0; i < NOPTS; i++) {
		const option *o = &OPTS[i];
		if (!(o->cmds & c->bit) || is_help(o))
			continue;
		char w[64];
		snprintf(w, sizeof w, "[--%s%s%s]", o->name, o->meta ? " " : "", o->meta ? o->meta : "");
		if (x + 1 + (int)strlen(w) > WIDTH) {
			fprintf(out, "\n%*s", col, "");
			x = col;
		} else {
			fputc(' ', out);
			x++;
		}
		fputs(w, out);
		x += (int)strlen(w);
	}
	fprintf(out, "\n\n%s\n", c->text);
	for (int i = 0; i < NOPTS; i++) {
		const option *o = &OPTS[i];
		if (!(o->cmds & c->bit))
			continue;
		char lab[64], rd[160], text[1024];
		label(o, lab, sizeof lab);
		range_default(o, rd, sizeof rd);
		snprintf(text, sizeof text, "%s%s%s%s", o->help, *rd ? " (" : "", rd, *rd ? ")" : "");
		fprintf(out, "  %s", lab);
		const int at = 2 + (int)strlen(lab);
		if (at + 1 > HELP_COL) {
			fputc('\n', out);
			wrap(out, text, 0, HELP_COL);
		} else {
			wrap(out, text, at, HELP_COL);
		}
	}
	if (c->tail)
		fprintf(out, "\n%s", c->tail);
	return 0;
}

/* Markdown's table cells: a | would end the cell. */
static void md_cell(FILE *out, const char *s)
{
	for (; *s; s++)
		fputs(*s == '|' ? "\\|" : (char[2]){*s, 0}, out);
}

void opts_markdown(FILE *out)
{
	fputs("| option | value | commands | default | meaning |\n|---|---|---|---|---|\n", out);
	for (int i = 0; i < NOPTS; i++) {
		const option *o = &OPTS[i];
		char lab[64], range[64] = "", dflt[64] = "";
		label(o, lab, sizeof lab);
		if (o->type == OT_INT || o->type == OT_REAL)
			range_text(o, range, sizeof range);
		else
			snprintf(range, sizeof range, o->type == OT_STR ? "text" : "none (a switch)");
		if (o->dtext)
			snprintf(dflt, sizeof dflt, "%s", o->dtext);
		else if (o->type == OT_INT || o->type == OT_REAL)
			snprintf(dflt, sizeof dflt, "%.15g", o->dflt);
		fprintf(out, "| `%s` | %s | ", lab, range);
		if ((o->cmds & ALL) == ALL) {
			fputs("all", out);
		} else {
			int k = 0;
			for (int j = 0; j < NCMDS; j++)
				if (o->cmds & CMDS[j].bit)
					fprintf(out, "%s%s", k++ ? ", " : "", CMDS[j].name);
		}
		fprintf(out, " | %s | ", dflt);
		md_cell(out, o->help);
		fputs(" |\n", out);
	}
}

/* ---- for tests ---- */

int opts_count(void)
{
	return NOPTS;
}

const char *opts_name(int i, char *shrt, unsigned *cmds, int *has_value)
{
	if (i < 0 || i >= NOPTS)
		return NULL;
	*shrt = OPTS[i].shrt;
	*cmds = OPTS[i].cmds;
	*has_value = OPTS[i].type != OT_FLAG;
	return OPTS[i].name;
}

const char *opts_command(int i, unsigned *bit, int *min_pos, int *max_pos)
{
	if (i < 0 || i >= NCMDS)
		return NULL;
	*bit = CMDS[i].bit;
	*min_pos = CMDS[i].min_pos;
	*max_pos = CMDS[i].max_pos;
	return CMDS[i].name;
}
