/* adapt.h - the adaptive onset search's pure logic (no I/O): a replicate's bracket
 * from the classes of its runs, the next frequency it needs, the interval of the
 * onset over replicates, and when a group needs more replicates. The driver side
 * (search.c) feeds it the classes of the runs; tests feed it a synthetic classifier.
 * The reasoning is in docs/driver.md, "Adaptive onset search". */
#ifndef ST_ADAPT_H
#define ST_ADAPT_H

/* Bisection levels a search may take: the tolerance is at least (to - from) / 2^20
 * (campaign.c), so a chain holds at most 21 midpoints and the two ends. */
#define AD_MAX_LEVELS 20
#define AD_MAX_STEPS 32
/* The most replicates a group may have (the order statistics use 2^-n). */
#define AD_MAX_REPLICATES 1000

typedef struct ad_range {
	double from, to; /* the observable is assumed off at from and on at to */
	double tol;      /* a bracket at most this wide is an answer */
} ad_range;

/* What is known of one run: its class, or why there is none yet. */
enum ad_class {
	AD_OFF,    /* the observable did not switch on (no rise; |flux| below the threshold) */
	AD_ON,
	AD_WAIT,   /* not run yet, or running: the chain waits for it */
	AD_FAILED, /* finished without an answer (the engine failed before it): the chain stops */
};

/* The class of a run that the engine stopped on physics (its status: docs/model.md,
 * "Safety stops"), by what the failure means: a bed that throws grains out of the box
 * (left_box) is shaken far above any onset, AD_ON; a blow-up (nan, overlap) or a bed
 * that did not settle says nothing of the onset, AD_FAILED. */
int adapt_failure_class(const char *status);

/* A replicate's state. */
enum ad_state {
	AD_SEARCHING, /* it needs the run at `next` */
	AD_FOUND,     /* off at lo, on at hi, both run, hi - lo <= tol */
	AD_BELOW,     /* on at from: the onset lies below the range */
	AD_ABOVE,     /* off at to: the onset lies above the range */
	AD_BLOCKED,   /* the run at `next` failed without an answer */
};

typedef struct ad_obs {
	double f;
	int on;
} ad_obs;

typedef struct ad_rep {
	ad_obs obs[AD_MAX_STEPS]; /* the classified runs of its chain, in the order run */
	int nobs;
	double lo, hi;            /* the bracket: the last off -> on switch of the observations
				   * (an unobserved end is the range's, assumed) */
	int lo_seen, hi_seen;     /* whether lo (off) and hi (on) were run */
	int nonmonotone;          /* a run below lo was on: the response flips */
	int state;                /* enum ad_state */
	double next;              /* SEARCHING: the frequency it needs; BLOCKED: the one that failed */
} ad_rep;

/* The midpoint of [lo, hi] printed with 12 significant digits and read back (as the
 * ranges of a campaign file are), so the frequencies read as written and a chain's
 * points are the same wherever they are computed. */
double adapt_mid(double lo, double hi);

/* The bracket, state and next point of a replicate from its observations. */
void adapt_bracket(const ad_range *r, ad_rep *p);

/* The class of the run at frequency f of the replicate being walked. */
typedef int (*ad_look)(void *ctx, double f);

/* Walks a replicate's chain from nothing: asks for the run at the next point, adds its
 * class and goes on until the replicate is answered, waits for a run or is blocked. The
 * chain depends on the range and the classes alone, so every walk over the same
 * results asks for the same points in the same order. */
void adapt_walk(const ad_range *r, ad_look look, void *ctx, ad_rep *p);

/* Whether f is a point some chain of the range can ask for (from, to or a midpoint of
 * the bisection tree, at any depth up to AD_MAX_LEVELS + 4): the runs of a campaign
 * whose tolerance or replicates changed still belong to it. */
int adapt_member(const ad_range *r, double f);
/* The same for a search whose points x are mapped to run frequencies (a search in
 * Gamma or v: map(ctx, x) is a group's frequency at x, increasing with x): whether
 * frequency f is the map of such a point. map NULL: the identity. */
int adapt_member_map(const ad_range *r, double f, double (*map)(void *ctx, double x), void *ctx);

/* The interval of the median over replicates: ranks r and n + 1 - r of the ordered
 * values cover the median with probability 1 - 2 P(Bin(n, 1/2) <= r - 1) >= level
 * (distribution-free). The largest such r, 0 when n is too small for any. */
long adapt_rank(long n, double level);
/* The fewest replicates for which an interval exists at level (6 at 0.95). */
long adapt_min_replicates(double level);

typedef struct ad_interval {
	long n;            /* replicates */
	double est;        /* median of the answered replicates' bracket midpoints (-inf below,
			    * +inf above the range); NaN while none is answered */
	double lo, hi;     /* [r-th smallest lower end, r-th largest upper end]; +-inf unbounded */
	double width;
} ad_interval;

/* The onset's estimate and interval from the replicates' brackets. Each replicate's
 * switch lies in [lo, hi] (an end not run is unbounded), so the r-th smallest lower end
 * is at most the r-th smallest switch, and likewise above: the interval covers the
 * median switch at least as often as the order-statistic interval of exact values. */
void adapt_interval(const ad_rep *reps, long n, double level, ad_interval *iv);

/* How many replicates a group gets. */
typedef struct ad_plan {
	int autorep;       /* replicates = auto */
	long n;            /* fixed: the replicates */
	long max;          /* auto: at most this many */
	long batch;        /* auto: added at a time */
	double target;     /* auto: the interval width to reach */
	double level;
} ad_plan;

enum ad_gstate {
	AD_G_SEARCHING, /* some replicate needs a run */
	AD_G_DONE,      /* every replicate answered (auto: and the interval is narrow enough) */
	AD_G_MAX,       /* auto: every replicate answered at the maximum, the interval is wider */
	AD_G_MORE,      /* auto: every replicate answered, the interval is wider: add a batch */
	AD_G_BLOCKED,   /* none searching, and a replicate blocked by a run that failed without
			 * an answer: the search cannot finish (no batch is added either) */
};

/* The replicates a group starts with: fixed n, or (auto) a first batch large enough
 * for an interval to exist at level. */
long adapt_first(const ad_plan *p);
/* The group's state from its n replicates (walked): searching while one is; blocked
 * when one is blocked; else done, max_replicates or more; *want the replicates it should
 * have (more than n when a batch is due); iv its interval. */
int adapt_group(const ad_plan *p, const ad_rep *reps, long n, ad_interval *iv, long *want);

/* Names of the states, for the database and the reports. */
const char *adapt_state_name(int state);
const char *adapt_gstate_name(int gstate);

#endif
