/* watch.h - live progress of a campaign: counts per state, the runs in flight with
 * their swept values and the simulated time t/T each has reached (from its journal,
 * jtail.h), and an ETA from the throughput actually measured - simulated seconds per
 * wall second summed over the runs in flight (from successive looks at their
 * journals), else over the runs that finished last (whatever ran them: local jobs,
 * ssh hosts, Slurm tasks) - never from a configured number of jobs. A reader of the
 * database and the journals only; `study status --watch` and the progress line of
 * `study run` both poll one. */
#ifndef ST_WATCH_H
#define ST_WATCH_H

#include <stdio.h>

#include "ledger/db.h"

typedef struct watch_run {
	char id[24];
	char label[256];   /* "frequency=2.8 radius_ratio=4 seed=3" */
	char host[64];
	double T;          /* the run's duration (simulated s) */
	double t;          /* simulated time reached; < 0 unknown (settling, or on another host) */
	double rate;       /* simulated s per wall s of this run; < 0 not measured yet */
	double t_ref, w_ref, t_last, w_last; /* samples the rate is measured between */
	long offset;       /* jtail state */
	unsigned long ino;
	int seen;          /* 1 when still in flight at the last poll */
} watch_run;

/* What an [onset] search or replicates = auto may still run after the runs pending or
 * running now (the round in flight), from the driver's last pass (the onset_* and
 * auto_point tables; docs/driver.md). */
typedef struct watch_search {
	int on;           /* the campaign is a search or replicates = auto */
	long more_max;    /* runs after this round, at most: each searching replicate's
			   * longest chain (cost_chain_max) less its runs so far, the chains of the
			   * replicates a group may still get; a point's replicates up to its maximum */
	long rounds_max;  /* rounds after this one, at most */
	long more;        /* expected: the bisections each searching replicate's bracket still
			   * needs after its run of this round, ceil(log2(width / tolerance)) - 1;
			   * -1 when the results decide (replicates = auto: whether a batch more
			   * is needed) */
	long rounds;      /* expected rounds after this one (the longest of those chains); -1 as more */
} watch_search;

/* s for campaign name; s->on = 0 (and the rest 0) for a plain grid. 0, or the error. */
int watch_search_left(st_db *db, const char *name, watch_search *s, sb_err *e);

typedef struct watch {
	char name[128];
	char dir[4200];    /* the campaign directory: where local runs' journals are */
	long total, done, failed, pending, running;
	watch_run *runs;   /* in flight, kept across polls for their rates */
	long nruns, cap;
	double rate;       /* simulated s per wall s over everything running; <= 0 unknown */
	const char *basis; /* what rate was measured from */
	double remaining;  /* simulated s still to run */
	double eta;        /* wall s; < 0 unknown (a search's: of the round in flight) */
	watch_search search; /* a search's rounds to come */
	double eta_search; /* wall s of the whole search as expected (search.more; < 0 unknown) */
	double eta_search_max; /* ... at most (search.more_max) */
	long jobs;         /* runs at a time the estimate assumes (the runs in flight now) */
	int driver;        /* a driver holds the campaign's lock */
	long slurm;        /* runs whose Slurm tasks are queued or running (-1: squeue cannot say) */
} watch;

/* name: the campaign; dir: its directory under the runs root. */
void watch_init(watch *w, const char *name, const char *dir);
void watch_free(watch *w);
/* One look at the database and the journals. */
int watch_poll(watch *w, st_db *db, sb_err *e);
/* Nothing pending or running, or nobody running it any more (no driver, no Slurm task). */
int watch_over(const watch *w);
/* The look as lines (status --watch), or as one line cut to len - 1 characters
 * (study run's progress line). */
void watch_print(const watch *w, FILE *out);
void watch_line(const watch *w, char *buf, size_t len);

#endif
