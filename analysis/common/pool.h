/* pool.h - several campaigns analysed as one: their runs read into one list (each run
 * knowing its campaign, its bootstrap unit unique over them), the union of their swept
 * axes, the parameters whose values differ between them (the default groups keep
 * such runs apart), and which campaigns each group drew from. A group is the runs
 * alike in the grouping keys, whatever campaign they came from (docs/analysis.md,
 * "Several campaigns"). */
#ifndef AN_POOL_H
#define AN_POOL_H

#include <stdio.h>

#include "err.h"
#include "adb.h"
#include "cli.h"

/* A pooled run's bootstrap unit: its replicate, offset by its campaign so that
 * replicate 0 of two campaigns are two seeds (onset_seeds.csv prints it). */
#define POOL_UNIT_STRIDE 1000000000L

/* Every run of every campaign of o (o->camp), in command-line order, into *runs (*nr
 * of them; adb_runs_free), run.camp and run.unit set; the first campaign's from d
 * (open), the others' from their databases, opened read-only and closed. With several
 * campaigns each must be in its database (a usage error names the one that is not).
 * axes[0..*na): the union of their swept axes (adb_axes). */
int pool_read(const an_opts *o, adb *d, an_run **runs, int *nr, char axes[][48], int *na, sb_err *e);

/* The parameters of the engine's table (not the output switches, the driver's paths
 * nor the keys outside a run's id; not seed nor drop[])
 * whose value differs between two of runs[0..n) of different campaigns and that
 * keys[0..*nk) lacks: appended to keys (at most AN_MAXKEYS); returns how many. */
int pool_keys(const an_run *runs, int n, const char *const *drop, char keys[][48], int *nk);

/* The campaigns group j drew from, "A, B", into buf (runs[i].group, camp; o's names). */
void pool_sources(const an_opts *o, const an_run *runs, int n, int j, char *buf, size_t len);

/* The lines a tool prints when it pooled several campaigns: each campaign with its
 * database, the keys added because they differ between them (keys[nk - nadded..nk)),
 * and per group (labels[0..ng)) the campaigns it drew from. Nothing for one campaign. */
void pool_print(FILE *f, const an_opts *o, const an_run *runs, int n, char **labels, int ng, const char keys[][48], int nk,
		int nadded);

#endif
