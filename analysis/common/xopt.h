/* xopt.h - a tool's own options beyond the common set that cli.c parses (onset
 * --sensitivity, waiting --fraction, rolls --fraction): taken out of argv before
 * cli_parse sees it, in the same forms (--opt VALUE, --opt=VALUE, an unambiguous
 * prefix of the whole name), so that cli.c's shared list stays the one every tool
 * agrees on. A misspelt own option is named as the nearest one, as cli does for its. */
#ifndef AN_XOPT_H
#define AN_XOPT_H

#include <stdio.h>

#include "err.h"
#include "cli.h"

typedef struct xopt {
	const char *name; /* without the dashes */
	int has_arg;      /* 1: takes a value */
	const char *val;  /* the value given (NULL: none) */
	int set;          /* 1 when given */
} xopt;

/* Takes the options x[0..nx) out of argv (*argc shrinks; argv[0] and everything else
 * stay in order). allowed is the tool's list of cli options (cli_parse's), so that a
 * prefix of both one of these and one of them is refused as ambiguous. Returns 0, or
 * SB_EUSAGE with the message in e. */
int xopt_take(int *argc, char **argv, xopt *x, int nx, const char *allowed, sb_err *e);

/* tool_args with the tool's own options: xopt_take, then cli_parse; an unknown option
 * nearer to one of x than to any of cli's is reported as a misspelling of it. -1 when
 * the help was printed to out, 1 after a usage error printed to err, 0 to go on. */
int xopt_args(an_opts *o, int argc, char **argv, const char *help, const char *allowed, xopt *x, int nx, FILE *out,
	      FILE *err);

/* The own options in canonical form appended to buf (cli_options' words): " name=value"
 * each, a number as %.15g, "default" when not given; a flag "yes" or "no". */
void xopt_options(const xopt *x, int nx, char *buf, size_t n);

/* The value of an own option as a number in [lo, hi] (dflt when not given); SB_EUSAGE
 * in e when it is not one. */
int xopt_num(const xopt *x, double lo, double hi, double dflt, double *v, sb_err *e);

#endif
