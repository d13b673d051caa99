/* sharp.h - replicates until the answer is sharp, the pure logic (no I/O): the
 * interval of a grid point's result from its runs (the median wait with
 * right-censoring, the rise fraction, the mean flux) and whether the point needs
 * another batch of replicates. The driver side (sharpen.c) feeds it the runs'
 * results from the database; tests feed it synthetic ones. The reasoning is in
 * docs/driver.md, "Replicates until the answer is sharp". */
#ifndef ST_SHARP_H
#define ST_SHARP_H

enum sh_result { SH_MEDIAN_WAIT, SH_RISE_FRACTION, SH_MEAN_FLUX }; /* = enum cp_result */

/* What is known of one replicate's run. */
enum sh_kind {
	SH_WAIT,   /* not run yet, or running: the point waits for it */
	SH_USED,   /* finished with a value */
	SH_NONE,   /* finished without one (failed before anything was recorded) */
};

typedef struct sh_obs {
	int kind;      /* enum sh_kind */
	int risen;     /* median_wait, rise_fraction: the intruder rose (else right-censored) */
	double time;   /* median_wait: the waiting time, or the time observed when not risen */
	double value;  /* mean_flux: the run's mean flux through the band */
} sh_obs;

typedef struct sh_plan {
	int result;    /* enum sh_result */
	long batch;    /* replicates added at a time */
	long max;      /* at most this many */
	double target; /* the interval width to reach */
	double level;
} sh_plan;

typedef struct sh_eval {
	long n;            /* replicates */
	long used;         /* with a value */
	long waiting;      /* not finished */
	double est;        /* NaN: none (no run used; the survival curve never reached 1/2) */
	double lo, hi;     /* -inf / +inf: unbounded */
	double width;
} sh_eval;

enum sh_state {
	SH_RUNNING, /* some replicate's run is not finished */
	SH_DONE,    /* the interval is at most target wide */
	SH_MAX,     /* max replicates, the interval still wider */
	SH_MORE,    /* wider, below the maximum: add a batch */
};

/* The fewest replicates for which the result has an interval at level. */
long sharp_min_replicates(int result, double level);
/* The first batch: at least batch and the replicates an interval needs, at most max. */
long sharp_first(const sh_plan *p);

/* The estimate and interval of the result over the runs used among obs[0..n).
 * median_wait: the Kaplan-Meier median (bin/waiting's) and the order-statistic
 * interval of the median with each run's wait known to lie in [t, t] (risen) or
 * [t, +inf) (censored): distribution-free, and censoring only widens it.
 * rise_fraction: risen / used, Clopper-Pearson. mean_flux: the mean, Student's t. */
void sharp_interval(const sh_plan *p, const sh_obs *obs, long n, sh_eval *ev);

/* The point's state from its n replicates; *want the replicates it should have
 * (n + batch, at most max, when a batch is due). */
int sharp_point(const sh_plan *p, const sh_obs *obs, long n, sh_eval *ev, long *want);

const char *sharp_state_name(int state);
const char *sharp_result_name(int result);

#endif
