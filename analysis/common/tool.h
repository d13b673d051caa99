/* tool.h - the frame every analysis tool's main shares: one recipe (tool_main runs a
 * tool from its tool_spec), the campaign's runs read from
 * the database, the runs the tool considers gathered at the front, their groups and
 * accounting, the rows stored in `analysis`, the closing lines and the exit code. What
 * a tool considers, how it classifies a run and what it computes stay in its main.
 * Functions return the error code kept in t->e (the first error wins); the ones that
 * print take the stream, so that only tool_main and the tools' own functions choose
 * where output goes. */
#ifndef AN_TOOL_H
#define AN_TOOL_H

#include <stdio.h>

#include "err.h"
#include "acct.h"
#include "adb.h"
#include "cli.h"
#include "pool.h"
#include "xopt.h"

typedef struct an_tool {
	const an_opts *o;
	adb d;
	an_run *runs;   /* every run of the campaign; runs[0..k) are the ones considered */
	int nr, k;
	long nold;      /* runs of earlier versions of the campaign file left out */
	int ng;         /* groups of the considered runs, labelled labels[0..ng) */
	char **labels;  /* malloc'd strings, freed by tool_close */
	char keys[AN_MAXKEYS][48]; /* the grouping keys ... */
	int nk;
	char **gval;    /* [ng * nk]: group j's value of key k as text ("": none), malloc'd */
	an_acct *A;     /* the accounting of each group (tool_tally) */
	char axes[AN_MAXKEYS][48]; /* the swept axes of the campaigns (pool_read) */
	int na;
	int nadded;     /* keys[nk - nadded..nk): differing between pooled campaigns */
	/* what defines the stored numbers (tool_store_begin): the options the tool takes
	 * (cli's, its own as given) and words it adds itself (tool_define) */
	const char *allowed;
	const xopt *x;
	int nx;
	char defn[512];
	/* the output files open now (tool_out_open), written under temporary names:
	 * tool_close removes those a failed step left open */
	sb_file out[6];
	/* the outputs finished (tool_out_close) and the figures asked for (tool_plot),
	 * put in place by tool_close only when every step succeeded: a run of the tool
	 * replaces all of its tables or none (a full disk at the ninth leaves the eight
	 * earlier ones as they were) */
	sb_file *done;
	int ndone;
	char **plots; /* [2 * nplots]: script, png; malloc'd */
	int nplots;
	sb_err e;
} an_tool;

/* One tool: what tool_main needs to run it. Everything but run may be NULL or 0. */
enum { TOOL_MAXX = 5 };
typedef struct tool_spec {
	const char *name, *version; /* the tool's name (bin/NAME, messages) and its version (rows it stores) */
	const char *help;           /* --help's text (tool_main adds the exit codes) */
	const char *allowed;        /* the cli options it takes beyond the common ones (cli_parse) */
	xopt x[TOOL_MAXX];          /* its own options (xopt.h), nx of them: their names and has_arg */
	int nx;
	/* After the command line, before the database: the options into the state s; a
	 * usage error into t->e (the database is not opened then). x: the own options as
	 * given. */
	int (*init)(an_tool *t, void *s, const xopt *x);
	/* The tool's work, with the database open and the campaign's runs read (t->runs):
	 * its steps in order, stopping at the first that fails (the error in t->e). */
	int (*run)(an_tool *t, void *s);
	/* Frees the state, whatever step failed (also when init or tool_open did). */
	void (*fini)(const an_tool *t, void *s);
} tool_spec;

/* The recipe every analysis tool's main follows, once: the command line (the help
 * printed to stdout: exit 0; a usage error to stderr: exit 1), spec->init, the database
 * opened (tool_open), spec->run, spec->fini, and the error printed as "TOOL: message"
 * with the exit code of tool_close. s is the tool's state, passed to its functions. */
int tool_main(int argc, char **argv, const tool_spec *spec, void *s);

/* The command line (cli_parse): -1 when the help was printed to out (exit 0), 1 when
 * a usage error was printed to err (exit 1), 0 to go on. */
int tool_args(an_opts *o, int argc, char **argv, const char *help, const char *allowed, FILE *out, FILE *err);

/* Opens the (first campaign's) database (writable unless --no-store) and reads every
 * run of every campaign into t (pool_read; t zeroed but for t->o and t->e, as
 * tool_main leaves it). */
int tool_open(an_tool *t, const an_opts *o);

/* A run of an earlier version of the campaign file that the options leave out
 * (counted in t->nold). */
int tool_old(an_tool *t, const an_run *r);
/* --where KEY=VALUE (repeatable): every KEY a parameter of the campaign's runs (else
 * SB_EUSAGE naming it); a run is selected when its KEY equals VALUE for every one (as
 * numbers when both are numbers, to 1e-9 relative). */
int tool_where_known(an_tool *t);
int tool_where_ok(const an_opts *o, const an_run *r);

/* Moves runs[i] to runs[k], the end of the considered runs (i >= k), and returns k,
 * its new index. */
int tool_keep(an_tool *t, int i);

/* The usage error when no run was considered: the campaign is not in the database, or
 * it has no finished KIND (e.g. "run with an intruder"); narrowed ends that sentence
 * (e.g. " that matches --where", or ""). */
int tool_none(an_tool *t, const char *kind, const char *narrowed);

/* 0 when run r has key, and a finite number as its value when it is a number key
 * (an_known); else the error: a group whose key is missing or no number is refused,
 * naming the run, the key and the value. */
int tool_key_known(an_tool *t, const an_run *r, const char *key);

/* Groups the considered runs by the grouping keys (cli_keys: --by, else always[] and
 * the swept axes not in drop[], and with several campaigns the keys that differ
 * between them, pool_keys); a run whose value of a key is unknown is refused
 * (tool_key_known). */
int tool_group(an_tool *t, const char *const *always, const char *const *drop);

/* The grouping keys of groups a tool made itself (t->ng and t->labels set): every
 * group's values "" until tool_value sets them. */
int tool_keys(an_tool *t, char keys[][48], int nk);
int tool_value(an_tool *t, int j, int k, const char *v);

/* Figure text for group j in words and symbols (label.h): the keys whose values differ
 * between the groups (vary = 1: the legend), or those that every group shares (vary =
 * 0: for the title); "" when there are none. */
void tool_legend(const an_tool *t, int j, int vary, char *buf, size_t n);

/* The legend of curve c of ncurve, a curve being the groups alike in every grouping key
 * but `along` (the figure's x): the other keys whose values differ between the curves
 * (vary = 1) or those they share (vary = 0); "" with more than 16 curves. Group j's
 * curve is the int at (const char *)curve + j * stride (an array, or a member of an
 * array of structs). */
void tool_curve_legend(const an_tool *t, const int *curve, size_t stride, int ncurve, const char *along, int c,
		       int vary, char *buf, size_t n);

/* The curves along a grouping key: curve[j] (of t->ng) = the index of the set of
 * groups alike in every grouping key but along (numbered in group order); returns
 * their number, or -1 (a usage error in t->e, naming the keys) when along is not a
 * grouping key. */
int tool_curves(an_tool *t, const char *along, int *curve);
/* The start of a table per curve (--diff, --fit): the curves along a grouping key
 * (tool_curves) and the CSV `name` opened in the output directory. Returns curve
 * (t->ng ints, the caller frees it) with *nc curves and *f open, or NULL (t->e says why). */
int *tool_curves_csv(an_tool *t, const char *along, const char *name, int *nc, FILE **f);
/* Group j's value of a grouping key as a number (NaN: none or no number); its label
 * without that key ("radius_ratio=0 depth=1"; "all" when nothing else). */
double tool_num(const an_tool *t, int j, const char *key);
void tool_label_but(const an_tool *t, int j, const char *key, char *buf, size_t n);
/* 1 when every considered run of group j shares the amplitude A and the gravity g
 * (a database without gravity: the engine's default), so that its frequencies map
 * onto one Gamma or v axis (axis.h); else 0. */
int tool_group_drive(const an_tool *t, int j, double *A, double *g);

/* The setting every considered run shares, in words for a title: the values of the
 * keys that every run has alike (of N, W, A) and the grouping keys that every group
 * shares, joined by ", "; "" when none. */
void tool_setting(const an_tool *t, char *buf, size_t n);

/* The box's amplitude A (cm) and gravity g (cm/s^2) when every considered run shares
 * them (then 1: the Gamma axis of a plot against f, drive_gamma, means one thing),
 * else 0. */
int tool_gamma(const an_tool *t, double *A, double *g);

/* Counts each group's runs (acct_tally). When none of them is usable, prints the
 * accounting to out and fails: "campaign 'C': none of WHAT is usable yet", WHAT
 * formatted from fmt. */
int tool_tally(an_tool *t, FILE *out, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* TOOL_accounting.csv in the output directory: one row per considered run. */
int tool_accounting_csv(an_tool *t);

/* A summary CSV: its own columns (head, without newline) and the accounting's; a
 * row's own values are the caller's, tool_summary_acct ends it with group j's. */
FILE *tool_summary_csv(an_tool *t, const char *name, const char *head);
void tool_summary_acct(const an_tool *t, FILE *s, int j);

/* Rows of the analysis tables (nothing under --no-store): begin records the definition
 * (the options in canonical form, cli_options and xopt_options, then tool_define's
 * words; the tool's version) and replaces the rows of an earlier run with the same
 * definition, keeping other definitions' (adb_store_begin; and gives the table a column
 * per grouping key), one row of group j (its key values in their columns; j < 0:
 * none), the observable of run r and its class (cls NULL: none), group j's accounting
 * rows (acct_store), and end commits when no error was kept, else rolls back and
 * returns the error. */
int tool_store_begin(an_tool *t);
void tool_store(an_tool *t, int j, const char *grp, const char *key, double value, double lo, double hi, long n);
void tool_store_run(an_tool *t, const an_run *r, const char *key, double value, const char *cls);
/* A word of the definition the options do not say ("threshold=search 2"), added to
 * the stored options (before tool_store_begin). */
void tool_define(an_tool *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void tool_store_acct(an_tool *t, const char *grp, int j);
int tool_store_end(an_tool *t);

/* An output file out/name (cli_open_out: through a temporary, renamed into place
 * complete), NULL with the error in t->e. tool_out_close finishes it (or, when t->e
 * holds an error, removes it) and returns t->e.code: a failed write (a full disk) is an
 * I/O error naming the file, never a truncated table at its name. Every finished output
 * is put in place by tool_close, together, when no step failed; else all are removed
 * and the earlier tables stay. One left open is removed by tool_close. */
FILE *tool_out_open(an_tool *t, const char *name);
int tool_out_close(an_tool *t, FILE *f);
/* gp_open's script, opened as tool_out_open does. */
FILE *tool_gp_open(an_tool *t, const char *name, int w, int h, char *script, char *png, size_t len);
/* Closes a gnuplot script (tool_gp_open) as tool_out_close does; tool_close runs it
 * once the tables it reads are in place. */
int tool_plot(an_tool *t, FILE *f, const char *script, const char *png);

/* The closing lines: the accounting table, the campaigns each group drew from when
 * several were pooled (pool_print) and, when failed runs were used up to
 * their failure, "# N failed runs enter with PARTLY" (no such line when partly is
 * NULL: the tool says it itself). */
void tool_report(const an_tool *t, FILE *out, const char *partly);
/* Runs used up to their failure, over every group. */
long tool_partly(const an_tool *t);

/* Rolls back unfinished storing, frees everything, prints the error to err as
 * "TOOL: message" and returns the exit code: 0 ok, 1 usage or no usable runs, 2 I/O. */
int tool_close(an_tool *t, FILE *err);

#endif
