/* adb.h - the analysis side of a campaign database: every run of a campaign with its
 * state, its parameters and output path, grouping by parameters, and the tables where
 * the tools store their derived numbers and per-run observables under the definition
 * (options, versions) that produced them (prepared statements only). */
#ifndef AN_ADB_H
#define AN_ADB_H

#include <sqlite3.h>
#include <stddef.h>

#include "err.h"
#include "sql.h"

typedef struct an_run {
	char id[128];
	long replicate;     /* run.replicate: the bootstrap unit ("seed") */
	long seed;          /* engine seed (run.seed) */
	int camp;           /* which campaign of the command line it is of (an_opts.camp) */
	long unit;          /* the bootstrap unit: replicate, made unique over several
			     * campaigns pooled (pool.h) */
	char path[1400];    /* RUNS/CAMPAIGN/ID.h5 */
	int nparam;
	char **key, **val;  /* param table rows, values as text */
	int group;          /* index into an_groups.label, set by an_group_runs */
	char state[12];     /* run.state: pending, running, done, failed */
	int current;        /* run.current: 1 = the campaign file's current grid (1 when the
			     * database has no such column), 0 = a run of an earlier version */
	char status[32];    /* result.status, else the last attempt's; "" when none */
	char message[400];  /* ... and its message */
	double status_time; /* result.status_time (s): when the run ended or failed; NaN if unknown */
	char seal[17];      /* result.file_seal: the seal of the file the driver recorded ("" when
			     * none: an older file or database); acct_classify holds the file to it */
	/* what became of the run in a tool's statistic, set by the tool (acct.h) */
	int use;            /* an_use */
	double used_s;      /* a failed run used up to its failure: the seconds used */
	double planned_s;   /* ... of the seconds it was to run (duration) */
	char why[400];      /* why it is not used (unreadable, unusable); "" otherwise */
	char bad[200];      /* why its parameters are unusable (a number key whose value is
			     * not a finite number, a key every run has that is missing);
			     * "" when they are fine: set by adb_runs */
	char rows[200];     /* why its rows in the database are not those recorded (their
			     * seal, lib/rowseal.h); "" when they are: set by adb_runs,
			     * acct_classify counts it unusable once its file is sound */
} an_run;

#define AN_ADB_MAXKEYS 32

typedef struct adb {
	sql_db db;          /* lib/sql.h */
	sqlite3_stmt *ins;  /* INSERT into analysis_all, prepared by adb_store_begin */
	int nk;             /* ... with the columns of these grouping keys: */
	int col[AN_ADB_MAXKEYS]; /* 1 when key k has a column (adb_key_column) */
	sqlite3_stmt *rins; /* INSERT into analysis_run, prepared likewise */
	long long def;      /* the definition being stored: analysis_def.id */
} adb;

int adb_open(adb *d, const char *path, int writable, sb_err *e);
void adb_close(adb *d);

/* Every run of campaign whatever its state or version (ordered by id): state, current,
 * status, its parameters from the param table and output path runs_dir/campaign/id.h5.
 * Databases without run.current or a result table are read too. A run whose numeric
 * parameter is not a finite number, or that lacks one of the keys every run records,
 * gets the reason in bad (acct_classify counts it unusable). Returns 0 or an error
 * code; *n may be 0. */
int adb_runs(adb *d, const char *campaign, const char *runs_dir, an_run **out, int *n, sb_err *e);
void adb_runs_free(an_run *r, int n);

/* 1 when the campaign has a row in table campaign, 0 when not. */
int adb_campaign_exists(adb *d, const char *campaign, int *yes, sb_err *e);

/* The campaign's swept axes (campaign.axes, space separated); *n = 0 when unknown. */
int adb_axes(adb *d, const char *campaign, char axes[][48], int max, int *n, sb_err *e);

/* A parameter as a number: dflt when the run has no such key, NaN when its value is no
 * finite decimal number (num.h: never a silent default), or as text (NULL). */
double an_num(const an_run *r, const char *key, double dflt);
/* 0 when the run has key and, for a number key of the engine's table, a finite number
 * as its value; else 1 with the reason in why ("radius_ratio: no row in the param
 * table", "frequency = 'nan': not a finite number"). */
int an_known(const an_run *r, const char *key, char *why, size_t n);
const char *an_str(const an_run *r, const char *key);

/* Group runs by the values of keys[0..nk): sets r[i].group, returns the number of
 * groups and their labels ("radius_ratio=2 depth=1"; "all" for nk = 0), ordered by
 * the key values (numerically when they are numbers). labels: free with an_labels_free. */
int an_group_runs(an_run *r, int n, char keys[][48], int nk, char ***labels);
void an_labels_free(char **labels, int ng);

/* Storing results (docs/database.md, "Derived numbers"): BEGIN, create the tables if
 * missing (an `analysis` table of an earlier version becomes analysis_all), add the
 * columns of the grouping keys keys[0..nk) (and of the common grid keys: radius_ratio,
 * depth, width, frequency, amplitude, n_grains) when analysis_all lacks them, and
 * record the definition: the tool's version and its options in canonical form (the
 * same options give the same text; cli_options) with the build (prov_version). The
 * rows of an earlier definition of this campaign, tool, version and options are
 * deleted (a rerun replaces its own rows); those of other definitions are kept, and
 * the view `analysis` shows the newest. adb_store inserts one row (NaN value/lo/hi
 * become NULL) with the group's values of the keys, vals[0..nk) as text (NULL or "":
 * NULL; stored typed: integer, real or text), NULL in the other keys' columns;
 * adb_store_end commits (ok != 0), with the `runs` view given a column for each
 * per-run observable stored, or rolls back. Table:
 *   analysis_all(campaign, tool, version, grp, key, value, lo, hi, n, created, def,
 *                radius_ratio, depth, ..., one column per grouping key) */
int adb_store_begin(adb *d, const char *campaign, const char *tool, const char *version, const char *options,
		    char keys[][48], int nk, sb_err *e);
int adb_store(adb *d, const char *campaign, const char *tool, const char *version, const char *grp,
	      const char *const *vals, const char *key, double value, double lo, double hi, long n, sb_err *e);
/* The observable a tool computed for run (key, e.g. "phi"; NaN: NULL) and the run's
 * class by it (e.g. "on", "off"; NULL: none), under the definition being stored:
 * analysis_run, shown in the `runs` view as columns TOOL_KEY and TOOL_KEY_class. */
int adb_store_run(adb *d, const char *campaign, const char *tool, const char *run, const char *key, double value,
		  const char *cls, sb_err *e);
/* 1 when a grouping key gets a column: not empty, not named like one of the fixed
 * eleven. */
int adb_key_column(const char *key);
int adb_store_end(adb *d, int ok, sb_err *e);

#endif
