/* cli.h - what every analysis tool shares: options, default paths, default grouping
 * keys, the output directory, CSV and gnuplot helpers. */
#ifndef AN_CLI_H
#define AN_CLI_H

#include <stdio.h>

#include "adb.h"
#include "err.h"

#define AN_MAXKEYS 32

typedef struct an_opts {
	const char *tool, *version;
	const char *campaign;
	char db[1024], runs[1024], out[1024];
	long boot;            /* bootstrap replicates */
	unsigned long seed;   /* bootstrap seed */
	double level;         /* confidence level */
	char by[AN_MAXKEYS][48];
	int nby;              /* -1: default keys */
	double band_lo, band_hi, skip;
	double threshold;     /* NaN: midpoint of the means */
	long bins, smooth;
	double freqs[16];
	int nfreq;
	double ratio;         /* figures: intruder radius ratio (NaN: largest) */
	char where_key[8][48], where_val[8][64]; /* figures: --where KEY=VALUE selections */
	int nwhere;
	int no_plot, no_store;
	int all_versions;     /* also the runs of earlier versions of the campaign file */
} an_opts;

/* Parses argv; allowed lists the tool's own options (" boot seed ... ", with spaces).
 * Returns 0 (go on), -1 (help printed: exit 0) or 1 (usage error printed). */
int cli_parse(an_opts *o, int argc, char **argv, const char *help, const char *allowed);

/* Grouping keys: o->by when given, else always[] then the campaign's swept axes not in
 * drop[] (NULL-terminated lists). */
int cli_keys(const an_opts *o, adb *d, const char *const *always, const char *const *drop, char keys[][48],
	     int *nk, sb_err *e);

/* mkdir -p of o->out; fopen of out/name for writing (path returned in path). */
int cli_outdir(const an_opts *o, sb_err *e);
FILE *cli_fopen(const an_opts *o, const char *name, char *path, size_t len, sb_err *e);
/* A CSV field in double quotes (RFC 4180). */
void csv_str(FILE *f, const char *s);
/* A gnuplot single-quoted string. */
void gp_str(FILE *f, const char *s);
/* Runs gnuplot on the script (no shell); 0 when it exits 0 and png exists. */
int gp_run(const char *script, const char *png, sb_err *e);
/* Opens a gnuplot script out/name.gp, writes the pngcairo terminal and output out/name.png. */
FILE *gp_open(const an_opts *o, const char *name, int w, int h, char *script, char *png, size_t len, sb_err *e);

#endif
