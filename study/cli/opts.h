/* opts.h - bin/study's command line: one table of commands and one of options (name,
 * value, the commands that take it, range, default, help) drive the parsing, every
 * --help text, the option list of docs/campaigns.md and the errors for a bad option. */
#ifndef ST_OPTS_H
#define ST_OPTS_H

#include <stdio.h>

#include "err.h"

/* The commands, as bits: an option row says which of them take it. */
enum {
	OPTS_RUN = 1 << 0,
	OPTS_STATUS = 1 << 1,
	OPTS_LIST = 1 << 2,
	OPTS_EXPORT = 1 << 3,
	OPTS_EXPAND = 1 << 4,
	OPTS_COLUMNS = 1 << 5,
	OPTS_SUBMIT = 1 << 6,
	OPTS_EXEC = 1 << 7,
	OPTS_OPTIONS = 1 << 8,
	OPTS_VIEW = 1 << 9,
};

/* What one command line says: the command, its operands and every option's value
 * (the row's default when not given). */
typedef struct study_args {
	const char *cmd;   /* "run", "status", ... */
	unsigned bit;      /* its OPTS_* bit */
	const char *pos[3];
	int npos;
	const char *runs, *db, *ssh, *outfile, *sbatch_args; /* NULL: not given */
	long jobs;         /* 0: as many as cores */
	long retries;      /* study run: attempts after the first of a transient failure */
	long throttle;     /* submit: 0: no limit */
	long per_task;     /* submit: runs per array task */
	long after;        /* submit: the round's array a search's planning job follows (0: none) */
	double interval;   /* status --watch: seconds between looks */
	int retry_failed, no_cache, keep_old, forget_old, slurm, watch, dry_run;
	int units;         /* export: a units row */
	int progress;      /* -1: when stderr is a terminal */
	int help;          /* --help given (opts_parse returns -1 at once) */
} study_args;

/* Parses argv (argv[1] the command; --opt VALUE, --opt=VALUE, the one-letter forms,
 * "--" ends the options). Returns 0 (go on), -1 (--help asked: the command's help is
 * the caller's to print) or SB_EUSAGE with the message in e: an unknown command or
 * option (the nearest one named, and the options the command takes), an option of
 * another command, a value missing, not taken or out of range, too many or too few
 * operands. a->cmd is set as soon as the command is known (NULL otherwise). */
int opts_parse(study_args *a, int argc, char **argv, sb_err *e);

/* The overview (study --help): the commands, where the manual is. */
void opts_usage(FILE *out);
/* The help of a command (study CMD --help): usage line, what it does, its options
 * with their ranges and defaults, the rest (exit codes). 1 when cmd is no command. */
int opts_help(FILE *out, const char *cmd);
/* Every option as a Markdown table (study options; docs/campaigns.md holds it). */
void opts_markdown(FILE *out);

/* For tests: the number of option rows, and row i's long name (without dashes), its
 * one-letter form (0: none), the commands that take it (OPTS_* bits) and whether it
 * takes a value; command i's name, bit and how many operands it takes (NULL past the
 * last command). */
int opts_count(void);
const char *opts_name(int i, char *shrt, unsigned *cmds, int *has_value);
const char *opts_command(int i, unsigned *bit, int *min_pos, int *max_pos);

#endif
