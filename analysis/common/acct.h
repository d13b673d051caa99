/* acct.h - what became of every run a statistic could have used: used, failed but
 * used up to its failure, unusable (and why), unreadable, still pending or running;
 * counted per group, printed beside the statistic, written to CSV and stored, so that
 * no run leaves a statistic without a trace. Which runs a tool could use at all (its
 * kind of run) and whether a file's records are usable is the tool's to decide. */
#ifndef AN_ACCT_H
#define AN_ACCT_H

#include <stdio.h>

#include "err.h"
#include "adb.h"

enum an_use {
	AN_USED,       /* finished (done) and in the statistic */
	AN_PARTLY,     /* failed; its records up to the failure are in the statistic */
	AN_UNUSABLE,   /* finished or failed, but nothing of it is usable (why says why) */
	AN_UNREADABLE, /* its output file is missing or cannot be read */
	AN_PENDING,    /* not started (or interrupted and queued again) */
	AN_RUNNING,
	AN_NUSE
};

#define AN_MAXREASON 8

typedef struct an_reason {
	char status[32]; /* the engine's status (overlap, nan, ...) or the attempt's */
	long n, used;    /* failed runs with that status, and how many of them are used */
} an_reason;

typedef struct an_acct {
	long n[AN_NUSE];
	long failed;               /* runs in state failed, whatever their use */
	double used_s, planned_s;  /* AN_PARTLY runs: seconds used, of the seconds planned */
	int nreason;               /* the last slot collects what does not fit as "other" */
	an_reason reason[AN_MAXREASON];
} an_acct;

/* Name of a use in CSV files ("used", "failed_used", "unusable", ...). */
const char *acct_use_name(int use);

/* Sets r->use, used_s, planned_s and r->why (printf format; NULL for none). */
void acct_set(an_run *r, int use, double used_s, double planned_s, const char *fmt, ...)
	__attribute__((format(printf, 5, 6)));

/* The classification every tool shares, before reading anything: a pending or running
 * run (returns 1); a run whose parameters are unusable (r->bad: unusable, returns 1);
 * a run whose output file does not exist: unusable when it failed (bad input or I/O:
 * the engine wrote nothing), unreadable when it is done (returns 1); else 0: the tool
 * reads the file and decides. */
int acct_classify(an_run *r);

/* An earlier version's run (current = 0) is counted in *nold and left out unless all
 * is set; returns 1 when r is left out. */
int acct_version_skip(const an_run *r, int all, long *nold);

/* Counts per group (r[i].group in [0, ng); others are in none); *out calloc'd, freed
 * by the caller. */
int acct_tally(const an_run *r, int n, int ng, an_acct **out);
/* Runs in the statistic: used + failed but used. */
long acct_used(const an_acct *a);

/* "overlap=2;nan=1" (the failed runs by status) into buf. */
void acct_reasons(const an_acct *a, char *buf, size_t len);

/* The lines every tool prints: how many runs of which versions were considered, one
 * row per group, and the warnings (unfinished campaign, unreadable files). tool names
 * the accounting CSV. */
void acct_print(FILE *f, const char *tool, char **labels, const an_acct *a, int ng, long nold, int all_versions);
/* The summary CSV's accounting columns: header (with a leading comma) and values. */
void acct_csv_head(FILE *f);
void acct_csv_row(FILE *f, const an_acct *a);
/* TOOL_accounting.csv: one row per run considered (group, run, state, status, use,
 * seconds used of planned, why); runs of group < 0 are in none and left out. */
void acct_runs_csv(FILE *f, const an_run *r, int n, char **labels);
/* The columns every per-run table of the tools begins with (TOOL_runs.csv,
 * TOOL_accounting.csv, hysteresis_periods.csv, ...): the run's group, by index and
 * label, and its id and replicate; one place, so that the tables join on them. */
#define ACCT_ROW_HEAD "group_index,group,run,replicate"
/* Run r's first columns, "G,LABEL,ID,REPLICATE" (G -1 and an empty label for a run in
 * no group); the caller goes on with ",NEXT". */
void acct_row_begin(FILE *f, const an_run *r, char *const *labels);
/* Stores runs_failed, runs_failed_used, failed_used_s, failed_planned_s, runs_unusable,
 * runs_unreadable, runs_pending, runs_running and failed_STATUS per status, each with
 * the group's values of the grouping keys (vals, as adb_store takes them). */
int acct_store(adb *d, const char *campaign, const char *tool, const char *version, const char *grp,
	       const char *const *vals, const an_acct *a, sb_err *e);

#endif
