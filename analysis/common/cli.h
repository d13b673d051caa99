/* cli.h - what every analysis tool shares: options, default paths, default grouping
 * keys, the output directory, CSV and gnuplot helpers. */
#ifndef AN_CLI_H
#define AN_CLI_H

#include <stdio.h>

#include "csv.h" /* the tools' CSV text fields: csv_text */
#include "err.h"
#include "adb.h"
#include "fsutil.h"

#define AN_MAXKEYS 32
#define AN_MAXCAMP 8

/* One campaign of the command line: NAME or FILE.campaign (in the database of --runs/--db) or DIR/NAME
 * (its own runs directory DIR, with DIR/study.db): the layout of lib/layout.h. */
typedef struct an_camp {
	const char *name;
	char db[1024], runs[1024];
	char file_name[256]; /* a campaign file's [campaign] name (name points here) */
} an_camp;

typedef struct an_opts {
	const char *tool, *version;
	const char *campaign; /* the one campaign, or pooled's name of several */
	char db[1024], runs[1024], out[1024]; /* the (first) campaign's database and runs */
	an_camp camp[AN_MAXCAMP]; /* every campaign given, pooled by the tools (pool.h) */
	int ncamp;
	char pooled[AN_MAXCAMP * 66]; /* "A+B": the name of several campaigns pooled */
	long boot;            /* bootstrap replicates */
	unsigned long seed;   /* bootstrap seed */
	double level;         /* confidence level */
	char by[AN_MAXKEYS][48];
	int nby;              /* -1: default keys */
	double band_lo, band_hi, skip;
	double threshold;     /* NaN: midpoint of the means */
	int band_set, skip_set, threshold_set, level_set; /* given on the command line (not the defaults) */
	long bins, smooth;
	double freqs[16];
	int nfreq;
	double ratio;         /* figures: intruder radius ratio (NaN: largest) */
	char where_key[8][48], where_val[8][64]; /* figures: --where KEY=VALUE selections */
	int nwhere;
	int no_plot, no_store;
	int all_versions;     /* also the runs of earlier versions of the campaign file */
} an_opts;

/* Parses argv (getopt_long: --opt value, --opt=value, unambiguous prefixes; argv is
 * permuted), one or more campaigns (an_camp) among the options; allowed lists the tool's own options (" boot seed ... ", with spaces)
 * besides the common ones. Returns 0 (go on), -1 (help asked) or 1 (usage error in e:
 * an unknown option names the nearest one of the tool). */
int cli_parse(an_opts *o, int argc, char **argv, const char *allowed, sb_err *e);
/* The options that define a tool's numbers, in canonical form into buf: every option
 * the tool takes (allowed, as for cli_parse) but the ones that only say where things
 * go or whether they are drawn or stored (help, db, runs, out, no-plot, no-store), as
 * "name=value" in cli's order, separated by spaces, with the value in effect (a default
 * too, so that giving the default is the same definition as leaving it out; an unset
 * one by the word for what the tool does then: "threshold=halfway", "by=axes"). */
void cli_options(const an_opts *o, const char *allowed, char *buf, size_t n);
/* The edit distance of two words (a swap of neighbours is one edit), and the option
 * of the tool (allowed as for cli_parse) nearest to name; NULL when none is near. */
int cli_distance(const char *a, const char *b);
const char *cli_nearest(const char *name, const char *allowed);

/* Grouping keys: o->by when given, else always[] then the swept axes[0..na) (of every
 * campaign) not in drop[] (NULL-terminated lists). */
void cli_keys(const an_opts *o, char axes[][48], int na, const char *const *always, const char *const *drop,
	      char keys[][48], int *nk);

/* mkdir -p of o->out, refused when something other than a directory stands there (a
 * link too: docs/output.md). */
int cli_outdir(const an_opts *o, sb_err *e);
/* out/name for writing (out->f; its path out->path), only over nothing or a regular
 * file, through a temporary in the same directory (fs_open_tmp). cli_close_out
 * renames it into place after a checked flush, fsync and close (fs_commit), or, when
 * e holds an error already, removes it: either way no temporary is left, and a table
 * not written whole leaves the earlier one at its name. 0 or the error (SB_EIO naming
 * the file and the system's word). */
int cli_open_out(const an_opts *o, const char *name, sb_file *out, sb_err *e);
int cli_close_out(sb_file *out, sb_err *e);
/* A gnuplot single-quoted string. */
void gp_str(FILE *f, const char *s);
/* Runs gnuplot on the script (no shell); 0 when it exits 0 and wrote png and the PDF
 * beside it (same name, .pdf), both not empty. They are drawn into temporary names and
 * renamed into place (fsutil.h), only over nothing or a regular file. */
int gp_run(const char *script, const char *png, sb_err *e);
/* Opens a gnuplot script out/name.gp (cli_open_out into script) that draws its body
 * twice, into out/name.png (pngcairo, w x h pixels) and out/name.pdf (pdfcairo,
 * vector): it writes the loop's head, the caller the body (settings and plots, UTF-8
 * text), gp_close the loop's end (then cli_close_out and gp_run). Refused (NULL) when
 * something other than a regular file stands at a figure's path. */
FILE *gp_open(const an_opts *o, const char *name, int w, int h, sb_file *script, char *png, size_t len, sb_err *e);
void gp_close(FILE *f);
/* The x axis's label for a key of the parameter table, its unit the table's
 * (label_axis: "frequency f (Hz)"). */
void gp_xlabel(FILE *f, const char *key);
/* The axis on top of a plot against the frequency f: Gamma (drive_gamma, core/model/drive.h)
 * of the amplitude A and gravity g, with ticks at round values of Gamma over
 * [f_lo, f_hi]. */
void gp_gamma_axis(FILE *f, double A, double g, double f_lo, double f_hi);

#endif
