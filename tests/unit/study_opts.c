/* study_opts.c - bin/study's option table (study/cli/opts.c) against what it drives:
 * every command's --help lists exactly the options the table gives it, in the usage
 * line and the option list; each option parses for those commands and is refused,
 * naming the commands that take it, for the others; values, ranges and defaults have
 * known answers both ways; an unknown, misspelt, valueless or extra word is a usage
 * error that names it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/opts.h"
#include "local/driver.h"
#include "testlib.h"

/* opts_parse of the words (NULL-terminated) after "study"; the message into e */
static int parse(study_args *a, sb_err *e, const char *const *words)
{
	char *argv[32];
	int argc = 0;
	argv[argc++] = "study";
	for (; *words && argc < 31; words++)
		argv[argc++] = (char *)*words;
	argv[argc] = NULL;
	memset(e, 0, sizeof *e);
	return opts_parse(a, argc, argv, e);
}
#define PARSE(a, e, ...) parse(a, e, (const char *const[]){__VA_ARGS__, NULL})

static char *help_of(const char *cmd)
{
	char *buf = NULL;
	size_t n = 0;
	FILE *f = open_memstream(&buf, &n);
	if (!f)
		return NULL;
	const int rc = opts_help(f, cmd);
	fclose(f);
	if (rc) {
		free(buf);
		return NULL;
	}
	return buf;
}

/* 1 when the help lists --name in its option list (a line "  --name" or "  -c, --name") */
static int lists(const char *help, const char *name, char shrt)
{
	char pat[80];
	if (shrt)
		snprintf(pat, sizeof pat, "\n  -%c, --%s", shrt, name);
	else
		snprintf(pat, sizeof pat, "\n  --%s", name);
	const char *p = strstr(help, pat);
	return p && (p[strlen(pat)] == ' ' || p[strlen(pat)] == '\n');
}

/* 1 when the usage line (up to the first blank line) has [--name */
static int in_usage(const char *help, const char *name)
{
	char pat[80];
	snprintf(pat, sizeof pat, "[--%s", name);
	const char *end = strstr(help, "\n\n"), *p = strstr(help, pat);
	return p && end && p < end && (p[strlen(pat)] == ']' || p[strlen(pat)] == ' ');
}

static void test_help_agrees(void)
{
	unsigned bit, cmds;
	char id[160], shrt;
	int has_value, nmin, nmax;
	for (int c = 0; opts_command(c, &bit, &nmin, &nmax); c++) {
		const char *cmd = opts_command(c, &bit, &nmin, &nmax);
		char *help = help_of(cmd);
		char head[64];
		snprintf(head, sizeof head, "usage: study %s", cmd);
		snprintf(id, sizeof id, "study.opts.help.%s.usage", cmd);
		CHECK(id, help && !strncmp(help, head, strlen(head)), "help of %s does not start with '%s'", cmd, head);
		if (!help)
			continue;
		int nlisted = 0, nmiss = 0, nextra = 0;
		for (int i = 0; i < opts_count(); i++) {
			const char *name = opts_name(i, &shrt, &cmds, &has_value);
			const int takes = !!(cmds & bit), listed = lists(help, name, shrt);
			const int used = strcmp(name, "help") ? in_usage(help, name) : takes;
			nlisted += listed;
			if (takes && (!listed || !used)) {
				nmiss++;
				printf("# %s --help: --%s missing (%s)\n", cmd, name, listed ? "usage line" : "option list");
			}
			if (!takes && (listed || used)) {
				nextra++;
				printf("# %s --help: --%s listed but not taken\n", cmd, name);
			}
		}
		snprintf(id, sizeof id, "study.opts.help.%s.same_as_table", cmd);
		CHECK(id, !nmiss && !nextra && nlisted >= 1, "%d missing, %d not taken but listed", nmiss, nextra);
		free(help);
	}
	CHECK("study.opts.help.unknown_command", !help_of("frobnicate"), "help of no command printed");
}

static void test_each_option_where_it_belongs(void)
{
	unsigned bit, cmds;
	char shrt, word[80];
	int has_value, nmin, nmax, bad = 0, refused_ok = 0, refused = 0;
	study_args a;
	sb_err e;
	for (int i = 0; i < opts_count(); i++) {
		const char *name = opts_name(i, &shrt, &cmds, &has_value);
		if (!strcmp(name, "help"))
			continue;
		snprintf(word, sizeof word, "--%s", name);
		for (int c = 0; opts_command(c, &bit, &nmin, &nmax); c++) {
			/* study CMD --opt [1] and the fewest operands the command takes; 1 is in
			 * the range of every number */
			char *argv[10];
			int argc = 0;
			argv[argc++] = "study";
			argv[argc++] = (char *)opts_command(c, &bit, &nmin, &nmax);
			argv[argc++] = word;
			if (has_value)
				argv[argc++] = "1";
			for (int k = 0; k < nmin; k++)
				argv[argc++] = "a";
			argv[argc] = NULL;
			memset(&e, 0, sizeof e);
			const int rc = opts_parse(&a, argc, argv, &e);
			if (cmds & bit) {
				if (rc) {
					bad++;
					printf("# study %s %s refused: %s\n", argv[1], word, e.msg);
				}
				continue;
			}
			refused++;
			char want[200];
			snprintf(want, sizeof want, "%s: %s is an option of study ", argv[1], word);
			if (rc == SB_EUSAGE && !strncmp(e.msg, want, strlen(want)))
				refused_ok++;
			else
				printf("# study %s %s: '%s'\n", argv[1], word, e.msg);
		}
	}
	CHECK("study.opts.parse.taken_where_listed", !bad, "%d options refused by a command that takes them", bad);
	CHECK("study.opts.parse.refused_elsewhere", refused > 0 && refused_ok == refused,
	      "%d of %d refused naming the commands that take it", refused_ok, refused);
}

static void test_values(void)
{
	study_args a;
	sb_err e;
	int rc = PARSE(&a, &e, "run", "c.campaign");
	CHECK("study.opts.defaults", !rc && a.npos == 1 && !strcmp(a.pos[0], "c.campaign") && a.jobs == 0 &&
					     a.retries == DRIVER_RETRIES && a.progress == -1 && a.interval == 2 &&
					     a.per_task == 1 && a.throttle == 0 && !a.runs && !a.db && !a.no_cache,
	      "rc %d: jobs %ld retries %ld progress %d interval %g per_task %ld", rc, a.jobs, a.retries, a.progress,
	      a.interval, a.per_task);
	rc = PARSE(&a, &e, "run", "--runs=R", "c.campaign", "-j", "3", "--jobs=4096", "--no-progress", "--retries", "0",
		   "--db", "x.db", "--no-cache", "--keep-old");
	CHECK("study.opts.values", !rc && !strcmp(a.runs, "R") && !strcmp(a.db, "x.db") && a.jobs == 4096 &&
					   a.progress == 0 && a.retries == 0 && a.no_cache && a.keep_old && !a.forget_old,
	      "rc %d (%s)", rc, e.msg);
	rc = PARSE(&a, &e, "submit", "s.campaign", "--slurm", "--sbatch-args", "--time=10 --mem=1G", "--throttle",
		   "1000000", "--runs-per-task=2");
	CHECK("study.opts.value_like_an_option", !rc && a.slurm && !strcmp(a.sbatch_args, "--time=10 --mem=1G") &&
							 a.throttle == 1000000 && a.per_task == 2,
	      "rc %d (%s)", rc, e.msg);
	rc = PARSE(&a, &e, "status", "--watch", "--interval", "0.1", "--", "-odd-name");
	CHECK("study.opts.double_dash", !rc && a.watch && a.interval == 0.1 && a.npos == 1 && !strcmp(a.pos[0], "-odd-name"),
	      "rc %d (%s)", rc, e.msg);
	rc = PARSE(&a, &e, "export", "x", "-o", "x.csv");
	CHECK("study.opts.short_value", !rc && !strcmp(a.outfile, "x.csv"), "rc %d (%s)", rc, e.msg);
	CHECK("study.opts.help", PARSE(&a, &e, "run", "--help") == -1 && PARSE(&a, &e, "list", "-h") == -1 &&
					 !strcmp(a.cmd, "list"),
	      "--help not seen");
	CHECK("study.opts.help_before_operands", PARSE(&a, &e, "run", "-h") == -1, "run -h wants a campaign");
}

/* A usage error whose message contains every one of the words (NULL-terminated). */
static void refused(const char *id, const char *const *words, const char *const *want)
{
	study_args a;
	sb_err e;
	const int rc = parse(&a, &e, words);
	int all = rc == SB_EUSAGE;
	for (const char *const *w = want; *w; w++)
		all &= strstr(e.msg, *w) != NULL;
	CHECK(id, all, "rc %d, message '%s'", rc, e.msg);
}
#define REFUSED(id, words, ...) refused(id, (const char *const[]){words}, (const char *const[]){__VA_ARGS__, NULL})
#define W(...) __VA_ARGS__, NULL

static void test_errors(void)
{
	REFUSED("study.opts.error.unknown", W("run", "c", "--bogus"), "run: unknown option '--bogus'", "--jobs",
		"--no-cache", "--help");
	REFUSED("study.opts.error.unknown_short", W("run", "c", "-x"), "unknown option '-x'");
	REFUSED("study.opts.error.suggestion", W("status", "--rnus", "R"), "did you mean --runs?");
	REFUSED("study.opts.error.suggestion_swap", W("run", "c", "--no-chace"), "did you mean --no-cache?");
	REFUSED("study.opts.error.other_command", W("run", "c", "--watch"), "--watch is an option of study status",
		"not of study run");
	REFUSED("study.opts.error.below_range", W("run", "c", "--jobs", "0"), "--jobs: expected an integer in [1, 4096]",
		"got '0'");
	REFUSED("study.opts.error.above_range", W("run", "c", "--jobs=4097"), "got '4097'");
	REFUSED("study.opts.error.not_a_number", W("status", "--interval", "fast"), "--interval: expected a number in "
		"[0.1, 3600]", "got 'fast'");
	REFUSED("study.opts.error.interval_low", W("status", "--interval", "0.09"), "got '0.09'");
	REFUSED("study.opts.error.nan", W("status", "--interval", "nan"), "got 'nan'");
	REFUSED("study.opts.error.trailing", W("run", "c", "-j", "3x"), "got '3x'");
	REFUSED("study.opts.error.throttle", W("submit", "c", "--slurm", "--throttle", "0"), "submit: --throttle",
		"[1, 1000000]");
	REFUSED("study.opts.error.missing_value", W("run", "c", "--jobs"), "--jobs needs a value", "[1, 4096]");
	REFUSED("study.opts.error.flag_value", W("run", "c", "--no-cache=1"), "--no-cache takes no value");
	REFUSED("study.opts.error.extra_operand", W("run", "a", "b"), "unexpected argument 'b'");
	REFUSED("study.opts.error.no_operand", W("export"), "export: expected NAME");
	REFUSED("study.opts.error.list_operand", W("list", "x"), "unexpected argument 'x'");
	REFUSED("study.opts.error.command", W("lsit"), "unknown command 'lsit'", "did you mean list?");
	REFUSED("study.opts.error.command_far", W("frobnicate"), "unknown command 'frobnicate'");
	study_args a;
	sb_err e;
	PARSE(&a, &e, "frobnicate");
	CHECK("study.opts.error.command_unset", a.cmd == NULL, "cmd '%s' after an unknown command", a.cmd);
}

static void test_markdown(void)
{
	char *buf = NULL, shrt;
	size_t n = 0;
	unsigned cmds;
	int has_value, rows = 0, named = 0;
	FILE *f = open_memstream(&buf, &n);
	opts_markdown(f);
	fclose(f);
	for (const char *p = buf; (p = strstr(p, "\n| `")); p++)
		rows++;
	for (int i = 0; i < opts_count(); i++) {
		char pat[80];
		snprintf(pat, sizeof pat, "--%s", opts_name(i, &shrt, &cmds, &has_value));
		named += strstr(buf, pat) != NULL;
	}
	CHECK("study.opts.markdown.rows", rows == opts_count() && named == opts_count(),
	      "%d rows, %d of %d options named", rows, named, opts_count());
	free(buf);
}

int main(void)
{
	test_help_agrees();
	test_each_option_where_it_belongs();
	test_values();
	test_errors();
	test_markdown();
	return tl_done();
}
