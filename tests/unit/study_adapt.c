/* study_adapt.c - the adaptive onset search's pure logic (study/rule/adapt.c) against
 * docs/driver.md, "Adaptive onset search": a replicate's bracket from its runs (the
 * last off -> on switch, unobserved ends confirmed, out-of-range onsets reported, flips
 * flagged), chains walked from results alone (the same results give the same points),
 * the order-statistic interval of the median over replicates (its ranks, censored and
 * unbounded replicates), the replicates a group gets (fixed, auto batches up to the
 * target or the maximum), and a whole search over a synthetic classifier whose
 * transition is known, run round by round as the driver does; then the [onset] section
 * of a campaign file (study/campaign/campaign.c): defaults, and bad input refused with file,
 * line, key and the valid range. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rule/adapt.h"
#include "campaign/axes.h"
#include "campaign/campaign.h"
#include "adaptive/search.h"
#include "study_files.h"
#include "testlib.h"

static const ad_range R = {2.5, 3.2, 0.02};

static void obs(ad_rep *p, double f, int on)
{
	p->obs[p->nobs].f = f;
	p->obs[p->nobs++].on = on;
}

/* ---- brackets ---- */

static void test_brackets(void)
{
	CHECK("adapt.mid.printed", adapt_mid(2.5, 3.2) == 2.85 && adapt_mid(0.1, 0.2) == 0.15,
	      "mid(2.5, 3.2) = %.17g, mid(0.1, 0.2) = %.17g", adapt_mid(2.5, 3.2), adapt_mid(0.1, 0.2));

	ad_rep p = {0};
	adapt_bracket(&R, &p);
	CHECK("adapt.bracket.empty", p.state == AD_SEARCHING && p.next == 2.85 && p.lo == 2.5 && p.hi == 3.2 &&
	      !p.lo_seen && !p.hi_seen, "state %d next %g [%g, %g] seen %d %d", p.state, p.next, p.lo, p.hi,
	      p.lo_seen, p.hi_seen);

	obs(&p, 2.85, 0);
	adapt_bracket(&R, &p);
	CHECK("adapt.bracket.off_raises_lo", p.state == AD_SEARCHING && p.lo == 2.85 && p.lo_seen && !p.hi_seen &&
	      p.next == adapt_mid(2.85, 3.2), "[%g, %g] next %g", p.lo, p.hi, p.next);
	obs(&p, p.next, 1);
	adapt_bracket(&R, &p);
	CHECK("adapt.bracket.on_lowers_hi", p.hi == 3.025 && p.hi_seen && p.next == adapt_mid(2.85, 3.025),
	      "[%g, %g] next %g", p.lo, p.hi, p.next);

	/* off at 2.6875, on at 2.7: width 0.0125 <= 0.02, both run */
	ad_rep q = {0};
	obs(&q, 2.6875, 0);
	obs(&q, 2.7, 1);
	adapt_bracket(&R, &q);
	CHECK("adapt.bracket.found", q.state == AD_FOUND && q.lo == 2.6875 && q.hi == 2.7 && isnan(q.next),
	      "state %s [%g, %g]", adapt_state_name(q.state), q.lo, q.hi);

	/* every run on: the bracket closes on `from`, which is then run */
	ad_rep b = {0};
	for (int i = 0; i < 6; i++) {
		adapt_bracket(&R, &b);
		obs(&b, b.next, 1);
	}
	adapt_bracket(&R, &b);
	CHECK("adapt.bracket.confirm_from", b.state == AD_SEARCHING && b.next == R.from && b.hi - b.lo <= R.tol,
	      "state %s next %g [%g, %g]", adapt_state_name(b.state), b.next, b.lo, b.hi);
	ad_rep b2 = b;
	obs(&b, R.from, 1);
	adapt_bracket(&R, &b);
	CHECK("adapt.bracket.below", b.state == AD_BELOW && b.lo == -INFINITY && b.hi == R.from,
	      "state %s [%g, %g]", adapt_state_name(b.state), b.lo, b.hi);
	obs(&b2, R.from, 0);
	adapt_bracket(&R, &b2);
	CHECK("adapt.bracket.from_confirmed", b2.state == AD_FOUND && b2.lo == R.from && b2.lo_seen,
	      "state %s [%g, %g]", adapt_state_name(b2.state), b2.lo, b2.hi);

	ad_rep a = {0};
	for (int i = 0; i < 6; i++) {
		adapt_bracket(&R, &a);
		obs(&a, a.next, 0);
	}
	adapt_bracket(&R, &a);
	CHECK("adapt.bracket.confirm_to", a.state == AD_SEARCHING && a.next == R.to, "state %s next %g",
	      adapt_state_name(a.state), a.next);
	obs(&a, R.to, 0);
	adapt_bracket(&R, &a);
	CHECK("adapt.bracket.above", a.state == AD_ABOVE && a.lo == R.to && a.hi == INFINITY, "state %s [%g, %g]",
	      adapt_state_name(a.state), a.lo, a.hi);

	/* on at 2.7 below an off at 2.9: the response flips; the switch reported is the
	 * last one, between the highest off and the lowest on above it */
	ad_rep n = {0};
	obs(&n, 2.7, 1);
	obs(&n, 2.9, 0);
	obs(&n, 2.91, 1);
	obs(&n, 3.0, 1);
	adapt_bracket(&R, &n);
	CHECK("adapt.bracket.last_switch", n.state == AD_FOUND && n.lo == 2.9 && n.hi == 2.91 && n.nonmonotone,
	      "state %s [%g, %g] nonmonotone %d", adapt_state_name(n.state), n.lo, n.hi, n.nonmonotone);
	CHECK("adapt.bracket.monotone_not_flagged", !q.nonmonotone && !p.nonmonotone, "flagged");
}

/* ---- chains over a synthetic classifier ---- */

/* A replicate's response: on above its switch f0, except in a band of width `flap`
 * above f0 where it flips pseudo-randomly with frequency (as runs near the onset do). */
typedef struct synth {
	double f0, flap;
	int looks;
	double asked[64];
	double fail_at;   /* a run that fails (NaN: none) */
	const char *failure; /* its status (NULL: one that says nothing) */
	int known;        /* how many of the asked runs have results (the rest wait) */
} synth;

static int flips(double f)
{
	unsigned long long h = (unsigned long long)llround(f * 1e6) * 0x9e3779b97f4a7c15ULL;
	return (int)((h >> 29) & 1);
}

static int synth_class(const synth *s, double f)
{
	if (f == s->fail_at)
		return adapt_failure_class(s->failure);
	if (f < s->f0)
		return AD_OFF;
	if (f < s->f0 + s->flap)
		return flips(f) ? AD_ON : AD_OFF;
	return AD_ON;
}

static int synth_look(void *ctx, double f)
{
	synth *s = ctx;
	if (s->looks >= s->known) {
		s->asked[s->looks++] = f;
		return AD_WAIT;
	}
	s->asked[s->looks++] = f;
	return synth_class(s, f);
}

/* A group of amplitude *ctx cm searched in Gamma: the frequency of point x */
static double gamma_freq(void *ctx, double x)
{
	return axes_frequency(AXIS_GAMMA, x, *(const double *)ctx, 981);
}

/* Walks the replicate round by round (each round makes one more result known, as
 * one `study run` round does) until it is answered; returns the rounds. */
static int synth_search(const ad_range *r, synth *s, ad_rep *p)
{
	int rounds = 0;
	for (s->known = 0;; s->known++) {
		s->looks = 0;
		adapt_walk(r, synth_look, s, p);
		if (p->state != AD_SEARCHING)
			return rounds;
		rounds++;
	}
}

static void test_chains(void)
{
	synth s = {.f0 = 2.6917, .fail_at = NAN};
	ad_rep p;
	int rounds = synth_search(&R, &s, &p);
	/* 0.7 Hz halved to 0.0109 <= 0.02: six midpoints */
	CHECK("adapt.walk.finds_step", p.state == AD_FOUND && p.lo < s.f0 && s.f0 <= p.hi && p.hi - p.lo <= R.tol &&
	      rounds == 6 && p.nobs == 6, "state %s [%g, %g] rounds %d obs %d", adapt_state_name(p.state), p.lo, p.hi,
	      rounds, p.nobs);

	/* a range that halves exactly onto the tolerance stops there: 0.8 Hz in three
	 * halvings is 0.1 Hz, but the midpoints are printed to 12 digits and 3.0 - 2.9 is
	 * 0.10000000000000009 in doubles; a stop rule without the slack (hi - lo < tol, or
	 * <= tol exactly) asks for a fourth midpoint */
	{
		const ad_range R8 = {2.5, 3.3, 0.1};
		synth s8 = {.f0 = 2.95, .fail_at = NAN};
		ad_rep p8;
		int r8 = synth_search(&R8, &s8, &p8);
		CHECK("adapt.walk.halves_onto_tolerance", p8.state == AD_FOUND && r8 == 3 && p8.nobs == 3 &&
		      p8.lo < s8.f0 && s8.f0 <= p8.hi,
		      "state %s [%.17g, %.17g] after %d rounds, %d points (want 3)", adapt_state_name(p8.state), p8.lo,
		      p8.hi, r8, p8.nobs);
	}

	/* the same results give the same points, in the same order */
	synth s2 = s;
	ad_rep p2;
	synth_search(&R, &s2, &p2);
	int same = p.nobs == p2.nobs;
	for (int i = 0; same && i < p.nobs; i++)
		same = p.obs[i].f == p2.obs[i].f && p.obs[i].on == p2.obs[i].on;
	CHECK("adapt.walk.reproducible", same, "two walks differ");
	int members = 1;
	for (int i = 0; i < p.nobs; i++)
		members &= adapt_member(&R, p.obs[i].f);
	CHECK("adapt.member.chain_points", members && adapt_member(&R, R.from) && adapt_member(&R, R.to) &&
	      !adapt_member(&R, 2.7) && !adapt_member(&R, 2.4) && !adapt_member(&R, 3.3),
	      "members %d, 2.7 %d", members, adapt_member(&R, 2.7));
	/* a finer tolerance continues the same chain: its points are the coarser chain's
	 * and more */
	ad_range fine = R;
	fine.tol = 0.005;
	synth s3 = s;
	ad_rep p3;
	synth_search(&fine, &s3, &p3);
	int prefix = p3.nobs > p.nobs;
	for (int i = 0; prefix && i < p.nobs; i++)
		prefix = p3.obs[i].f == p.obs[i].f;
	CHECK("adapt.walk.finer_tolerance_extends", prefix && p3.hi - p3.lo <= fine.tol && adapt_member(&R, p3.obs[p3.nobs - 1].f),
	      "finer chain of %d points (coarse %d)", p3.nobs, p.nobs);

	/* a run still pending: the chain waits at it, and asks for nothing beyond */
	synth w = {.f0 = 2.9, .fail_at = NAN, .known = 2};
	ad_rep pw;
	w.looks = 0;
	adapt_walk(&R, synth_look, &w, &pw);
	CHECK("adapt.walk.waits", pw.state == AD_SEARCHING && pw.nobs == 2 && w.looks == 3 && pw.next == w.asked[2],
	      "state %s obs %d looks %d", adapt_state_name(pw.state), pw.nobs, w.looks);

	/* a run that failed without an answer blocks its replicate, where it failed */
	synth f = {.f0 = 2.9, .fail_at = adapt_mid(2.85, 3.2)};
	ad_rep pf;
	synth_search(&R, &f, &pf);
	CHECK("adapt.walk.blocked", pf.state == AD_BLOCKED && pf.next == f.fail_at && pf.nobs == 1 && pf.lo == 2.85,
	      "state %s next %g obs %d", adapt_state_name(pf.state), pf.next, pf.nobs);

	/* a run that threw grains out of the box (left_box) is far above the onset: on, and
	 * the bracket moves down past it; any other failure blocks, in both directions */
	CHECK("adapt.failure.left_box_is_on", adapt_failure_class("left_box") == AD_ON, "%d",
	      adapt_failure_class("left_box"));
	CHECK("adapt.failure.others_block", adapt_failure_class("overlap") == AD_FAILED &&
	      adapt_failure_class("nan") == AD_FAILED && adapt_failure_class("settle_failed") == AD_FAILED &&
	      adapt_failure_class("io") == AD_FAILED && adapt_failure_class(NULL) == AD_FAILED, "a failure is not blocked");
	synth lb = {.f0 = 2.9, .fail_at = 2.85, .failure = "left_box"};
	ad_rep plb;
	synth_search(&R, &lb, &plb);
	CHECK("adapt.walk.left_box_moves_down", plb.state == AD_FOUND && plb.obs[0].f == 2.85 && plb.obs[0].on &&
	      plb.hi <= 2.85 && plb.obs[1].f == adapt_mid(2.5, 2.85), "state %s first %g on %d [%g, %g]",
	      adapt_state_name(plb.state), plb.obs[0].f, plb.obs[0].on, plb.lo, plb.hi);
	synth ov = {.f0 = 2.9, .fail_at = 2.85, .failure = "overlap"};
	ad_rep pov;
	synth_search(&R, &ov, &pov);
	CHECK("adapt.walk.overlap_blocks", pov.state == AD_BLOCKED && pov.next == 2.85 && pov.nobs == 0,
	      "state %s next %g", adapt_state_name(pov.state), pov.next);

	/* a search in Gamma: its points are a group's frequencies through a map; every
	 * chain point's frequency is a member, a frequency between two is not */
	double amp = 3;
	int gm = 1;
	for (int i = 0; i < p.nobs; i++)
		gm &= adapt_member_map(&R, gamma_freq(&amp, p.obs[i].f), gamma_freq, &amp);
	CHECK("adapt.member.mapped", gm && adapt_member_map(&R, gamma_freq(&amp, R.from), gamma_freq, &amp) &&
	      !adapt_member_map(&R, gamma_freq(&amp, 2.7), gamma_freq, &amp) &&
	      !adapt_member_map(&R, p.obs[0].f, gamma_freq, &amp), "mapped members %d", gm);

	/* onsets outside the range are reported as such, after running the end */
	synth lo = {.f0 = 2.0, .fail_at = NAN}, hi = {.f0 = 4.0, .fail_at = NAN};
	ad_rep pl, ph;
	int rl = synth_search(&R, &lo, &pl), rh = synth_search(&R, &hi, &ph);
	CHECK("adapt.walk.below_range", pl.state == AD_BELOW && rl == 7 && pl.obs[6].f == R.from, "state %s rounds %d",
	      adapt_state_name(pl.state), rl);
	CHECK("adapt.walk.above_range", ph.state == AD_ABOVE && rh == 7 && ph.obs[6].f == R.to, "state %s rounds %d",
	      adapt_state_name(ph.state), rh);

	/* a response that flips in a band above f0: the switch found lies in the band */
	int inband = 1;
	for (int k = 0; k < 50; k++) {
		synth fl = {.f0 = 2.62 + 0.01 * k, .flap = 0.025, .fail_at = NAN};
		ad_rep pfl;
		synth_search(&R, &fl, &pfl);
		if (pfl.state != AD_FOUND || pfl.hi < fl.f0 || pfl.lo > fl.f0 + fl.flap)
			inband = 0;
	}
	CHECK("adapt.walk.flipping_band", inband, "a switch found outside the flipping band");
}

/* ---- the interval over replicates ---- */

static ad_rep found(double lo, double hi)
{
	ad_rep p = {0};
	p.lo = lo;
	p.hi = hi;
	p.lo_seen = p.hi_seen = 1;
	p.state = AD_FOUND;
	return p;
}

static void test_interval(void)
{
	static const long n[] = {1, 5, 6, 7, 8, 10, 12, 16, 20, 32, 100};
	static const long r95[] = {0, 0, 1, 1, 1, 2, 3, 4, 6, 10, 40}, r99[] = {0, 0, 0, 0, 1, 1, 2, 3, 4, 9, 37};
	int ok = 1;
	for (size_t i = 0; i < sizeof n / sizeof *n; i++)
		if (adapt_rank(n[i], 0.95) != r95[i] || adapt_rank(n[i], 0.99) != r99[i]) {
			ok = 0;
			printf("# n %ld: rank %ld at 0.95 (want %ld), %ld at 0.99 (want %ld)\n", n[i], adapt_rank(n[i], 0.95),
			       r95[i], adapt_rank(n[i], 0.99), r99[i]);
		}
	CHECK("adapt.rank.binomial", ok, "ranks differ from 1 - 2 P(Bin(n, 1/2) <= r - 1) >= level");
	CHECK("adapt.rank.min_replicates", adapt_min_replicates(0.95) == 6 && adapt_min_replicates(0.99) == 8 &&
	      adapt_min_replicates(0.5) == 2, "%ld %ld %ld", adapt_min_replicates(0.95), adapt_min_replicates(0.99),
	      adapt_min_replicates(0.5));

	/* ten brackets [k, k + 0.1], shuffled: rank 2 of the lower ends and of the upper
	 * ends from the top; the median of the midpoints */
	ad_rep reps[12];
	static const int order[] = {7, 2, 9, 0, 4, 1, 8, 3, 6, 5};
	for (int i = 0; i < 10; i++)
		reps[i] = found(order[i], order[i] + 0.1);
	ad_interval iv;
	adapt_interval(reps, 10, 0.95, &iv);
	CHECK("adapt.interval.order_statistics", iv.lo == 1 && fabs(iv.hi - 8.1) < 1e-12 && fabs(iv.est - 4.55) < 1e-12 &&
	      fabs(iv.width - 7.1) < 1e-12 && iv.n == 10, "est %g [%g, %g] width %g", iv.est, iv.lo, iv.hi, iv.width);
	adapt_interval(reps, 5, 0.95, &iv);
	CHECK("adapt.interval.too_few", iv.lo == -INFINITY && iv.hi == INFINITY && isinf(iv.width),
	      "[%g, %g] with 5 replicates", iv.lo, iv.hi);

	/* one onset below and one above the range: the median and the interval stay
	 * finite with enough replicates in between */
	reps[10] = found(0, 0);
	reps[10].state = AD_BELOW;
	reps[10].lo = -INFINITY;
	reps[10].lo_seen = 0;
	reps[11] = found(9.1, 0);
	reps[11].state = AD_ABOVE;
	reps[11].hi = INFINITY;
	reps[11].hi_seen = 0;
	adapt_interval(reps, 12, 0.95, &iv);
	CHECK("adapt.interval.censored", isfinite(iv.lo) && isfinite(iv.hi) && fabs(iv.est - 4.55) < 1e-12,
	      "est %g [%g, %g]", iv.est, iv.lo, iv.hi);
	/* a replicate whose lower end was never run bounds nothing below */
	ad_rep six[6];
	for (int i = 0; i < 6; i++)
		six[i] = found(2.68, 2.69);
	six[3].lo_seen = 0;
	six[3].state = AD_SEARCHING;
	adapt_interval(six, 6, 0.95, &iv);
	CHECK("adapt.interval.unrun_end_unbounded", iv.lo == -INFINITY && iv.hi == 2.69, "[%g, %g]", iv.lo, iv.hi);
	six[3] = found(2.68, 2.69);
	adapt_interval(six, 6, 0.95, &iv);
	CHECK("adapt.interval.agreeing", iv.lo == 2.68 && iv.hi == 2.69 && fabs(iv.est - 2.685) < 1e-12,
	      "est %g [%g, %g]", iv.est, iv.lo, iv.hi);
	/* the estimate is over the answered replicates alone: one still searching on the
	 * range's assumed ends does not pull it */
	six[3].state = AD_SEARCHING;
	six[3].lo = 2.5;
	six[3].hi = 3.2;
	six[3].lo_seen = six[3].hi_seen = 0;
	six[0].state = AD_BLOCKED;
	six[0].lo = 2.5;
	six[0].hi = 3.2;
	six[0].lo_seen = six[0].hi_seen = 0;
	adapt_interval(six, 6, 0.95, &iv);
	CHECK("adapt.interval.estimate_answered_only", fabs(iv.est - 2.685) < 1e-12 && isinf(iv.lo) && isinf(iv.hi),
	      "est %g [%g, %g]", iv.est, iv.lo, iv.hi);
	for (int i = 0; i < 6; i++)
		six[i].state = AD_BLOCKED;
	adapt_interval(six, 6, 0.95, &iv);
	CHECK("adapt.interval.no_answer_no_estimate", isnan(iv.est), "est %g", iv.est);
}

/* ---- replicates: fixed, auto ---- */

static void test_group(void)
{
	ad_plan fixed = {0, 3, 0, 0, 0, 0.95};
	ad_rep reps[40];
	for (int i = 0; i < 40; i++)
		reps[i] = found(2.68 + 0.001 * i, 2.69 + 0.001 * i);
	ad_interval iv;
	long want;
	CHECK("adapt.group.fixed_first", adapt_first(&fixed) == 3, "%ld", adapt_first(&fixed));
	int st = adapt_group(&fixed, reps, 3, &iv, &want);
	CHECK("adapt.group.fixed_done", st == AD_G_DONE && want == 3 && isinf(iv.width), "%s want %ld",
	      adapt_gstate_name(st), want);
	reps[1].state = AD_SEARCHING;
	st = adapt_group(&fixed, reps, 3, &iv, &want);
	CHECK("adapt.group.searching", st == AD_G_SEARCHING, "%s", adapt_gstate_name(st));
	/* a blocked replicate: the group cannot finish, and says so (never done) */
	reps[1].state = AD_BLOCKED;
	st = adapt_group(&fixed, reps, 3, &iv, &want);
	CHECK("adapt.group.blocked_is_blocked", st == AD_G_BLOCKED && want == 3 && !strcmp(adapt_gstate_name(st), "blocked"),
	      "%s want %ld", adapt_gstate_name(st), want);
	reps[1].state = AD_SEARCHING;
	reps[2].state = AD_BLOCKED;
	st = adapt_group(&fixed, reps, 3, &iv, &want);
	CHECK("adapt.group.searching_before_blocked", st == AD_G_SEARCHING, "%s", adapt_gstate_name(st));
	reps[1] = found(2.681, 2.691);
	reps[2] = found(2.682, 2.692);
	/* auto, an interval wider than the target: a blocked replicate adds no batch */
	ad_plan wide = {1, 0, 16, 4, 0.0001, 0.95};
	reps[3].state = AD_BLOCKED;
	st = adapt_group(&wide, reps, 6, &iv, &want);
	CHECK("adapt.group.blocked_adds_no_batch", st == AD_G_BLOCKED && want == 6, "%s want %ld", adapt_gstate_name(st), want);
	reps[3] = found(2.683, 2.693);
	st = adapt_group(&wide, reps, 6, &iv, &want);
	CHECK("adapt.group.unblocked_adds_batch", st == AD_G_MORE && want == 10, "%s want %ld", adapt_gstate_name(st), want);

	ad_plan au = {1, 0, 16, 4, 0.05, 0.95};
	CHECK("adapt.group.auto_first", adapt_first(&au) == 6, "%ld (the fewest with an interval at 0.95)",
	      adapt_first(&au));
	au.batch = 8;
	CHECK("adapt.group.auto_first_batch", adapt_first(&au) == 8, "%ld", adapt_first(&au));
	au.batch = 4;
	/* six agreeing brackets: [2.68, 2.695] is narrower than 0.05 */
	st = adapt_group(&au, reps, 6, &iv, &want);
	CHECK("adapt.group.auto_target_reached", st == AD_G_DONE && want == 6 && iv.width <= 0.05, "%s width %g",
	      adapt_gstate_name(st), iv.width);
	au.target = 0.01;
	st = adapt_group(&au, reps, 6, &iv, &want);
	CHECK("adapt.group.auto_more", st == AD_G_MORE && want == 10, "%s want %ld", adapt_gstate_name(st), want);
	st = adapt_group(&au, reps, 14, &iv, &want);
	CHECK("adapt.group.auto_capped_batch", st == AD_G_MORE && want == 16, "%s want %ld", adapt_gstate_name(st), want);
	st = adapt_group(&au, reps, 16, &iv, &want);
	CHECK("adapt.group.auto_max", st == AD_G_MAX && want == 16, "%s want %ld", adapt_gstate_name(st), want);
}

/* ---- a whole group searched round by round, as the driver does ---- */

/* Replicate i's switch: the group's median 2.69 plus a seed-to-seed scatter of
 * +-0.02, and a band of 0.01 above it where runs flip. */
static double f0_of(long i)
{
	return 2.69 + 0.04 * ((double)((i * 7919) % 101) / 100.0 - 0.5);
}

typedef struct world {
	double asked[4096];   /* every run asked for, in order (replicate-major) */
	long rep[4096];
	long nasked;
	long cur;             /* the replicate being walked */
	double done[4096];    /* the runs with results: (replicate, f) pairs */
	long done_rep[4096];
	long ndone;
} world;

static int world_look(void *ctx, double f)
{
	world *w = ctx;
	for (long i = 0; i < w->ndone; i++)
		if (w->done_rep[i] == w->cur && w->done[i] == f) {
			synth s = {.f0 = f0_of(w->cur), .flap = 0.01, .fail_at = NAN};
			return synth_class(&s, f);
		}
	if (w->nasked < 4096) {
		w->asked[w->nasked] = f;
		w->rep[w->nasked++] = w->cur;
	}
	return AD_WAIT;
}

/* One pass: walks every replicate (adding batches as asked) and returns the group's
 * state; the runs the chains wait for are in w->asked. */
static int world_pass(const ad_plan *pl, world *w, ad_rep *reps, long *n, ad_interval *iv)
{
	long want;
	*n = adapt_first(pl);
	w->nasked = 0;
	for (long done = 0;;) {
		for (long i = done; i < *n; i++) {
			w->cur = i + 1;
			adapt_walk(&R, world_look, w, &reps[i]);
		}
		done = *n;
		int st = adapt_group(pl, reps, *n, iv, &want);
		if (st != AD_G_MORE)
			return st;
		*n = want;
	}
}

/* Runs the search to its end; the sequence of runs asked for in seq (replicate,
 * frequency), rounds in *rounds. */
static int world_search(const ad_plan *pl, world *w, ad_rep *reps, long *n, ad_interval *iv, long *rounds,
			double *seq, long *seqrep, long *nseq, long stop_after)
{
	int st;
	*rounds = 0;
	*nseq = 0;
	for (;;) {
		st = world_pass(pl, w, reps, n, iv);
		if (st != AD_G_SEARCHING || *rounds == stop_after)
			return st;
		for (long i = 0; i < w->nasked; i++) { /* the round: every waiting run runs */
			w->done[w->ndone] = w->asked[i];
			w->done_rep[w->ndone++] = w->rep[i];
			seq[*nseq] = w->asked[i];
			seqrep[(*nseq)++] = w->rep[i];
		}
		(*rounds)++;
	}
}

static void test_search(void)
{
	static ad_rep reps[64];
	static world w;
	static double seq[4096], seq2[4096];
	static long seqrep[4096], seqrep2[4096];
	ad_plan pl = {1, 0, 40, 4, 0.03, 0.95};
	long n, rounds, nseq, nseq2;
	ad_interval iv;
	int st = world_search(&pl, &w, reps, &n, &iv, &rounds, seq, seqrep, &nseq, -1);
	/* the replicates' switches have their median at 2.69 (+-0.02 scatter, 0.01 flips) */
	CHECK("adapt.search.finds_onset", st == AD_G_DONE && iv.lo <= 2.69 && 2.69 <= iv.hi + 0.01 &&
	      fabs(iv.est - 2.69) < 0.02, "%s est %g [%g, %g] with %ld replicates", adapt_gstate_name(st), iv.est, iv.lo,
	      iv.hi, n);
	CHECK("adapt.search.auto_stops_at_target", iv.width <= 0.03 && n < 40 && (n - 6) % 4 == 0,
	      "width %g with %ld replicates (target 0.03)", iv.width, n);
	printf("# synthetic search: %ld replicates, %ld runs in %ld rounds, onset %.4f [%.4f, %.4f]\n", n, w.ndone,
	       rounds, iv.est, iv.lo, iv.hi);

	/* stopped after three rounds (a driver killed) and resumed from the results: the
	 * same runs in the same order, the same answer */
	static world w2;
	long r1, n2;
	ad_interval iv2;
	world_search(&pl, &w2, reps, &n2, &iv2, &r1, seq2, seqrep2, &nseq2, 3);
	long base = nseq2;
	long r2;
	st = world_search(&pl, &w2, reps, &n2, &iv2, &r2, seq2 + base, seqrep2 + base, &nseq2, -1);
	nseq2 += base;
	int same = nseq2 == nseq && n2 == n && iv2.est == iv.est && iv2.lo == iv.lo && iv2.hi == iv.hi;
	for (long i = 0; same && i < nseq; i++)
		same = seq[i] == seq2[i] && seqrep[i] == seqrep2[i];
	CHECK("adapt.search.resume_same_sequence", same && r1 + r2 == rounds, "%ld runs then %ld (want %ld)", base,
	      nseq2 - base, nseq);

	/* the target out of reach: the search stops at the maximum */
	static world w3;
	ad_plan tight = {1, 0, 12, 4, 0.001, 0.95};
	st = world_search(&tight, &w3, reps, &n, &iv, &rounds, seq, seqrep, &nseq, -1);
	CHECK("adapt.search.stops_at_max", st == AD_G_MAX && n == 12 && iv.width > 0.001, "%s with %ld replicates",
	      adapt_gstate_name(st), n);
}

/* ---- the [onset] section ---- */

static const char *HEAD = "[campaign]\nname = t\nseed = 1\n[scene]\nradius_ratio = 0\nflux = yes\n";

/* loads HEAD + body; CHECKs that it fails with a message containing want (NULL: that
 * it loads) */
static void section(const char *id, const char *body, const char *want)
{
	char text[2048];
	snprintf(text, sizeof text, "%s%s", HEAD, body);
	campaign c;
	sb_err e;
	int rc = sf_load(text, &c, &e);
	if (!want)
		CHECK(id, !rc, "refused: %s", e.msg);
	else
		CHECK(id, rc && strstr(e.msg, want), "got %s (want '%s')", rc ? e.msg : "no error", want);
	campaign_free(&c);
}

static void test_section(void)
{
	const char *ok = "[onset]\nobservable = flux\nfrom = 2.5\nto = 3.2\ntolerance = 0.02\nthreshold = 0.5\n";
	char text[2048];
	snprintf(text, sizeof text, "%s%s", HEAD, ok);
	campaign c;
	sb_err e;
	int rc = sf_load(text, &c, &e);
	const cp_onset *o = &c.onset;
	CHECK("adapt.section.defaults", !rc && o->line == 7 && o->observable == CP_OBS_FLUX && o->autorep &&
	      o->max_replicates == 32 && o->batch == 4 && o->target == 0.02 && o->level == 0.95 && o->band_lo == 0.4 &&
	      o->band_hi == 0.6 && o->skip == 0.2, "%s", rc ? e.msg : "a default differs");
	campaign_free(&c);
	/* the file's lines: [campaign] 1-3, [scene] 4-6, [onset] 7, its keys from 8 */
	section("adapt.section.bad_observable", "[onset]\nobservable = rolls\n",
		":8: observable: expected one of rise|flux, got 'rolls'");
	section("adapt.section.bad_from", "[onset]\nobservable = flux\nfrom = fast\n",
		":9: from: expected a number in (0, 1000] (Hz), got 'fast'");
	section("adapt.section.to_below_from", "[onset]\nobservable = flux\nfrom = 3\nto = 2.5\ntolerance = 0.1\nthreshold = 1\n",
		":10: to: expected a frequency above from = 3 (line 9), got 2.5");
	section("adapt.section.tolerance_too_wide", "[onset]\nobservable = flux\nfrom = 2.5\nto = 3\ntolerance = 0.5\nthreshold = 1\n",
		":11: tolerance: expected a width in [");
	section("adapt.section.tolerance_too_fine", "[onset]\nobservable = flux\nfrom = 2.5\nto = 3\ntolerance = 1e-9\nthreshold = 1\n",
		"(from 2.5 to 3 in at most 20 halvings), got 1e-09");
	section("adapt.section.missing_key", "[onset]\nobservable = flux\nfrom = 2.5\nto = 3.2\n",
		":7: [onset] has no tolerance");
	section("adapt.section.flux_needs_threshold", "[onset]\nobservable = flux\nfrom = 2.5\nto = 3.2\ntolerance = 0.02\n",
		":7: [onset] has no threshold");
	section("adapt.section.rise_no_threshold", "[onset]\nobservable = rise\nfrom = 2.5\nto = 3.2\ntolerance = 0.02\nthreshold = 1\n",
		":12: threshold: only for observable = flux");
	section("adapt.section.bad_band", "[onset]\nband = 0.6:0.4\n", ":8: band: expected LO:HI with 0 <= LO < HI <= 1");
	section("adapt.section.bad_skip", "[onset]\nskip = 1\n", ":8: skip: expected a number in [0, 1), got '1'");
	section("adapt.section.bad_replicates", "[onset]\nreplicates = many\n",
		":8: replicates: expected auto or an integer in [1, 1000], got 'many'");
	section("adapt.section.bad_max", "[onset]\nmax_replicates = 0\n",
		":8: max_replicates: expected an integer in [1, 1000], got '0'");
	section("adapt.section.bad_level", "[onset]\nlevel = 1\n", ":8: level: expected a number in [0.5, 0.999], got '1'");
	section("adapt.section.max_too_small", "[onset]\nobservable = flux\nfrom = 2.5\nto = 3.2\ntolerance = 0.02\n"
		"threshold = 1\nmax_replicates = 4\n", ":13: max_replicates: at least 6 replicates are needed");
	section("adapt.section.auto_only", "[onset]\nobservable = flux\nfrom = 2.5\nto = 3.2\ntolerance = 0.02\n"
		"threshold = 1\nreplicates = 5\nbatch = 2\n", ":14: batch: only with replicates = auto (line 13 says 5)");
	section("adapt.section.twice", "[onset]\nfrom = 2.5\nfrom = 2.6\n", ":9: from: given twice (first on line 8)");
	section("adapt.section.unknown_key", "[onset]\nfrequency = 2.5\n", ":8: unknown key 'frequency' in [onset] (observable, from,");
	/* a typo gets the nearest key, in every section; another word gets none */
	section("adapt.section.typo_onset", "[onset]\ntolerence = 0.02\n", "unknown key 'tolerence' in [onset]; did you mean tolerance? (");
	section("adapt.section.typo_scene", "frequncy = 3\n", "unknown key 'frequncy'; did you mean frequency? (");
	section("adapt.section.typo_derived", "[grid]\nvelocty = 10, 20\n", "unknown key 'velocty'; did you mean velocity? (");
	section("adapt.section.typo_none", "xyzzy = 3\n", "unknown key 'xyzzy' (shake --help");
	section("adapt.section.frequency_elsewhere", "[grid]\nfrequency = 2.6, 2.8\n[onset]\nobservable = flux\nfrom = 2.5\n"
		"to = 3.2\ntolerance = 0.02\nthreshold = 1\n", ":8: frequency: chosen by the [onset] search");
	rc = sf_load("[campaign]\nname = t\nseeed = 1\n", &c, &e);
	CHECK("adapt.section.typo_campaign", rc && strstr(e.msg, "unknown key 'seeed' in [campaign]; did you mean seed? ("),
	      "got %s", rc ? e.msg : "no error");
	campaign_free(&c);
	snprintf(text, sizeof text, "[campaign]\nname = t\nseed = 1\nreplicates = 4\n[scene]\nflux = yes\n[onset]\n"
		 "observable = flux\nfrom = 2.5\nto = 3.2\ntolerance = 0.02\nthreshold = 1\n");
	rc = sf_load(text, &c, &e);
	CHECK("adapt.section.replicates_elsewhere", rc && strstr(e.msg, ":4: replicates: an [onset] campaign sets its "
	      "replicates under [onset]"), "got %s", rc ? e.msg : "no error");
	campaign_free(&c);
	section("adapt.section.seed_elsewhere", "[grid]\nseed = 1..4\n[onset]\nobservable = flux\nfrom = 2.5\nto = 3.2\n"
		"tolerance = 0.02\nthreshold = 1\n", ":8: seed: the [onset] search numbers its replicates");
	/* what a group needs is checked when the grid of groups is expanded */
	grid g;
	snprintf(text, sizeof text, "%s[grid]\ndepth = 1, 2\n[onset]\nobservable = rise\nfrom = 2.5\nto = 3.2\n"
		 "tolerance = 0.02\n", HEAD);
	rc = sf_expand(text, &c, &g, &e);
	CHECK("adapt.groups.rise_needs_intruder", rc && strstr(e.msg, ":10: observable: rise needs an intruder, but "
	      "group depth=1 has radius_ratio = 0"), "got %s", rc ? e.msg : "no error");
	if (!rc)
		sf_free(&c, &g);
	snprintf(text, sizeof text, "[campaign]\nname = t\nseed = 1\n[grid]\nradius_ratio = 2, 3\n[onset]\n"
		 "observable = flux\nfrom = 2.5\nto = 3.2\ntolerance = 0.02\nthreshold = 1\n");
	rc = sf_expand(text, &c, &g, &e);
	CHECK("adapt.groups.flux_needs_records", rc && strstr(e.msg, ":7: observable: flux needs the flux records: set "
	      "flux = yes"), "got %s", rc ? e.msg : "no error");
	if (!rc)
		sf_free(&c, &g);
	snprintf(text, sizeof text, "[campaign]\nname = t\nseed = 1\n[grid]\nradius_ratio = 2, 3\n[onset]\n"
		 "observable = rise\nfrom = 2.5\nto = 3.2\ntolerance = 0.02\n");
	rc = sf_expand(text, &c, &g, &e);
	CHECK("adapt.groups.no_runs_before_search", !rc && g.points == 2 && g.n == 0, "%s points %ld runs %ld",
	      rc ? e.msg : "ok", g.points, g.n);
	if (!rc)
		sf_free(&c, &g);
	/* a search in Gamma: one range serves groups of every amplitude, each at its own
	 * frequencies f = sqrt(Gamma g / A) / 2 pi */
	snprintf(text, sizeof text, "[campaign]\nname = t\nseed = 1\n[grid]\namplitude = 1, 2, 3\n[onset]\n"
		 "observable = rise\naxis = gamma\nfrom = 0.5\nto = 2.5\ntolerance = 0.1\n");
	rc = sf_expand(text, &c, &g, &e);
	int fok = !rc && c.onset.axis == AXIS_GAMMA && g.points == 3;
	for (long p = 0; fok && p < 3; p++) {
		sb_scene sc;
		grid_point_scene(&c, p, &sc);
		double want = sqrt(2.5 * 981 / (double)(p + 1)) / (2 * M_PI);
		fok = sc.amplitude == p + 1 && fabs(grid_onset_frequency(&c, &sc, 2.5) - want) < 1e-9 * want;
	}
	CHECK("adapt.groups.gamma_axis_frequencies", fok, "%s", rc ? e.msg : "a group's frequency differs");
	if (!rc) {
		/* the first point is Gamma 1.5 in every group: at A = 3 cm, 3.52484 Hz; the
		 * preview warns when the table of axes.c says the model fails there */
		char pv[2048];
		int warned = search_preview(&c, 2, pv, sizeof pv);
		double limit;
		int want = axes_model_fails(1.5, &limit) != NULL;
		CHECK("adapt.preview.gamma_axis", warned == want && strstr(pv, "group amplitude=3 (amplitude 3 cm): first "
		      "point 3.52484 Hz (Gamma 1.5, v 66.4 cm/s)") && strstr(pv, "(Gamma 1.5, v "), "%s", pv);
		sf_free(&c, &g);
	}
	/* issue's campaign: 1.5 to 6.5 Hz at A = 1, 2, 3 cm; every group's first point is
	 * 4 Hz, Gamma 1.93 at A = 3 cm (above the model's limit: a warning), 0.644 at 1 cm
	 * (none) */
	snprintf(text, sizeof text, "[campaign]\nname = t\nseed = 1\n[grid]\namplitude = 1, 2, 3\n[onset]\n"
		 "observable = rise\nfrom = 1.5\nto = 6.5\ntolerance = 0.1\n");
	rc = sf_expand(text, &c, &g, &e);
	if (!rc) {
		char p1[2048], p3[2048];
		int w1 = search_preview(&c, 0, p1, sizeof p1), w3 = search_preview(&c, 2, p3, sizeof p3);
		CHECK("adapt.preview.warns_above_limit", w3 && strstr(p3, "first point 4 Hz (Gamma 1.93, v 75.4 cm/s)") &&
		      strstr(p3, "warning: group amplitude=3: the first point, 4 Hz, is at Gamma 1.93, at or above 1.6 where "
			     "runs have ended with grains thrown"), "%s", p3);
		CHECK("adapt.preview.quiet_below_limit", !w1 && strstr(p1, "first point 4 Hz (Gamma 0.644, v 25.1 cm/s)") &&
		      !strstr(p1, "warning"), "%s", p1);
		sf_free(&c, &g);
	} else
		CHECK("adapt.preview.warns_above_limit", 0, "%s", e.msg);
	snprintf(text, sizeof text, "[campaign]\nname = t\nseed = 1\n[grid]\namplitude = 0, 1\n[onset]\n"
		 "observable = rise\naxis = velocity\nfrom = 10\nto = 50\ntolerance = 1\n");
	rc = sf_expand(text, &c, &g, &e);
	CHECK("adapt.groups.velocity_needs_amplitude", rc && strstr(e.msg, ":8: axis: a search in velocity needs an "
	      "amplitude above 0, but group amplitude=0 has amplitude = 0"), "got %s", rc ? e.msg : "no error");
	if (!rc)
		sf_free(&c, &g);
	section("adapt.section.bad_axis", "[onset]\naxis = g\n", ":8: axis: expected one of frequency|gamma|velocity, got 'g'");
	section("adapt.section.axis_unit", "[onset]\naxis = velocity\nobservable = flux\nfrom = 10\nto = 30\n"
		"tolerance = 25\nthreshold = 1\n", ":12: tolerance: expected a width in [1.91e-05, 20) cm/s (from 10 to 30");
	section("adapt.section.gamma_to_below_from", "[onset]\naxis = gamma\nobservable = flux\nfrom = 1\nto = 0.5\n"
		"tolerance = 0.1\nthreshold = 1\n", ":11: to: expected a gamma above from = 1 (line 10), got 0.5");
	section("adapt.section.fixed_replicates", "[onset]\nobservable = rise\nfrom = 2.5\nto = 3.2\ntolerance = 0.02\n"
		"replicates = 3\n", NULL);
}

int main(void)
{
	if (sf_init()) {
		printf("FAIL adapt.setup: cannot make a temporary directory\n");
		return 1;
	}
	test_brackets();
	test_chains();
	test_interval();
	test_group();
	test_search();
	test_section();
	sf_cleanup();
	return tl_done();
}
