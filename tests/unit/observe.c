/* observe.c - the observables on synthetic motions with known answers: flux
 * crossings, the displacement field of a uniform motion, the ring selection and
 * its averages. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "crossing.h"
#include "observe.h"
#include "place.h"
#include "record.h"
#include "sample.h"
#include "testlib.h"

static char jpath[] = "/tmp/sb_obs_test_XXXXXX";

/* Read the records of one tag back from the journal into out (count doubles each). */
static int read_back(int want, double *out, int cap)
{
	sb_jreader r;
	sb_err e = {0};
	if (journal_reader_open(&r, jpath, &e))
		return -1;
	static double buf[100000];
	int n = 0, count;
	for (int tag; (tag = journal_next(&r, buf, 100000, &count, &e)) > 0;)
		if (tag == want && n + count <= cap) {
			memcpy(out + n, buf, sizeof(double) * (size_t)count);
			n += count;
		}
	journal_reader_close(&r);
	return n;
}

static void set_pos(sb_state *st, const double *x, const double *y)
{
	for (int i = 0; i < st->nm; i++) {
		st->q[C_X][0][i] = x[i];
		st->q[C_Y][0][i] = y[i];
	}
}

static void test_flux(void)
{
	sb_scene sc;
	params_defaults(&sc);
	sc.flux = 1;
	sc.flux_lines = 10; /* lines at 0.5, 1.5, ..., 9.5 for a surface at 10 */
	sb_state st = {0};
	sb_err e = {0};
	/* box [0, 40]: centre region |x - 20| < 10 */
	double x0[4] = {20, 22, 5, 35}, y0[4] = {1.0, 8.0, 2.0, 6.0};
	double x1[4] = {20, 22, 5, 36}, y1[4] = {4.2, 3.0, 2.4, 9.9};
	for (int i = 0; i < 4; i++)
		place_push(&sc, &st, x0[i], y0[i], 1, KIND_GRAIN, &e);
	sb_obs o;
	int rc = obs_init(&o, &sc, &st, -1, 10.0, 0, 40, &e);
	CHECK("observe.flux.init", rc == 0 && o.nlines == 10 && fabs(o.hline[0] - 0.5) < 1e-15 &&
					   fabs(o.hline[9] - 9.5) < 1e-15, "rc %d %s", rc, e.msg);
	sb_journal jr;
	journal_open(&jr, jpath, st.nm, -1, &e);
	long nf = 0, nd = 0;
	set_pos(&st, x0, y0);
	sample_obs_strobe(&o, &st, 0, 3, &jr, &nf, &nd, &e);
	CHECK("observe.flux.first_sample_no_record", nf == 0, "nf %ld", nf);
	set_pos(&st, x1, y1);
	sample_obs_strobe(&o, &st, 0.3, 3, &jr, &nf, &nd, &e);
	long off;
	journal_sync(&jr, &off, &e);
	journal_close(&jr);
	double rec[22];
	int n = read_back(REC_TAG(REC_FLUX), rec, 22);
	CHECK("observe.flux.one_record", nf == 1 && n == 22, "nf %ld n %d", nf, n);
	/* disk 0 (centre) rises 1.0 -> 4.2: crosses 1.5, 2.5, 3.5 upwards (+1 each)
	 * disk 1 (centre) sinks 8.0 -> 3.0: crosses 7.5 .. 3.5 downwards (-1 each)
	 * disk 2 (outer) 2.0 -> 2.4: crosses nothing
	 * disk 3 (outer) 6.0 -> 9.9: crosses 6.5, 7.5, 8.5, 9.5 upwards */
	double want_top[10] = {0, 1, 1, 0, -1, -1, -1, -1, 0, 0};
	double want_bot[10] = {0, 0, 0, 0, 0, 0, 1, 1, 1, 1};
	int good = n == 22 && rec[0] == 0.3 && rec[1] == 3;
	for (int l = 0; l < 10 && good; l++)
		good = rec[2 + l] == want_top[l] && rec[12 + l] == want_bot[l];
	CHECK("observe.flux.crossings", good, "record differs from the hand count (t %g f %g top[1] %g top[4] %g bot[6] %g)",
	      rec[0], rec[1], rec[2 + 1], rec[2 + 4], rec[12 + 6]);
	/* a disk exactly on a line counts once, when it leaves from below to it */
	obs_free(&o);
	state_free(&st);
}

/* With periodic sides a disk that crosses the seam x = 0 = W while it rises is near
 * the seam, an outer column: its crossings count into j_bot. The plain midpoint of
 * 39.5 and 0.5 is the box centre (20), which would count them into j_top. */
static void test_flux_seam(void)
{
	sb_scene sc;
	params_defaults(&sc);
	sc.flux = 1;
	sc.flux_lines = 10;
	sc.sides = SIDES_PERIODIC;
	sb_state st = {0};
	sb_err e = {0};
	/* box [0, 40): centre columns |x - 20| < 10; disk 0 moves right across the seam,
	 * disk 1 left across it, disk 2 stays in the centre; all three rise 1.0 -> 4.2
	 * (lines 1.5, 2.5, 3.5) */
	double x0[3] = {39.5, 0.5, 20}, y0[3] = {1.0, 1.0, 1.0};
	double x1[3] = {0.5, 39.5, 20}, y1[3] = {4.2, 4.2, 4.2};
	for (int i = 0; i < 3; i++)
		place_push(&sc, &st, x0[i], y0[i], 1, KIND_GRAIN, &e);
	sb_obs o;
	int rc = obs_init(&o, &sc, &st, -1, 10.0, 0, 40, &e);
	CHECK("observe.flux.seam.init", rc == 0 && o.period == 40, "rc %d period %g %s", rc, o.period, e.msg);
	sb_journal jr;
	journal_open(&jr, jpath, st.nm, -1, &e);
	long nf = 0, nd = 0;
	set_pos(&st, x0, y0);
	sample_obs_strobe(&o, &st, 0, 3, &jr, &nf, &nd, &e);
	set_pos(&st, x1, y1);
	sample_obs_strobe(&o, &st, 0.3, 3, &jr, &nf, &nd, &e);
	long off;
	journal_sync(&jr, &off, &e);
	journal_close(&jr);
	double rec[22];
	int n = read_back(REC_TAG(REC_FLUX), rec, 22);
	int good = nf == 1 && n == 22;
	for (int l = 0; l < 10 && good; l++) {
		double top = l >= 1 && l <= 3 ? 1 : 0, bot = l >= 1 && l <= 3 ? 2 : 0;
		good = rec[2 + l] == top && rec[12 + l] == bot;
	}
	CHECK("observe.flux.seam.minimum_image", good,
	      "the seam crossers counted in the wrong columns: top[1..3] %g %g %g (want 1), bot[1..3] %g %g %g (want 2)",
	      rec[3], rec[4], rec[5], rec[13], rec[14], rec[15]);
	obs_free(&o);
	state_free(&st);
}

/* The crossing rule at its edges (core/model/crossing.h): upwards yp < h <= y, downwards
 * y < h <= yp. A disk that ends exactly on a line has crossed it; one that starts on it
 * and moves up has not crossed it again; one that sinks from it has crossed it down. */
static void test_crossing_edges(void)
{
	double h[10], top[10], bot[10];
	crossing_lines(10, 10, h); /* 0.5, 1.5, ..., 9.5 */
	/* one disk at the centre column: x0 = 0, x1 = 40 */
	const double xc[1] = {20};
	struct {
		const char *id;
		double y0, y1;
		int line, want; /* the one line counted (-1: none) and its sign */
	} c[] = {
		{"crossing.ends_on_line_up", 1.6, 2.5, 2, +1},
		{"crossing.starts_on_line_up", 2.5, 3.0, -1, 0},
		{"crossing.starts_on_line_down", 2.5, 2.0, 2, -1},
		{"crossing.ends_on_line_down", 3.0, 2.5, -1, 0},
	};
	for (size_t k = 0; k < sizeof c / sizeof c[0]; k++) {
		memset(top, 0, sizeof top);
		memset(bot, 0, sizeof bot);
		const double yp[1] = {c[k].y0}, y[1] = {c[k].y1};
		crossing_count(1, xc, yp, xc, y, 0, 40, 10, 10, h, top, bot);
		int good = 1;
		for (int l = 0; l < 10; l++)
			good &= top[l] == (l == c[k].line ? c[k].want : 0) && bot[l] == 0;
		CHECK(c[k].id, good, "%g -> %g: top[1..3] %g %g %g", c[k].y0, c[k].y1, top[1], top[2], top[3]);
	}
}

static void test_field(void)
{
	sb_scene sc;
	params_defaults(&sc);
	sc.field = 1;
	sc.field_periods = 3;
	sb_state st = {0};
	sb_err e = {0};
	enum { N = 50 };
	double x[N], y[N];
	unsigned s = 7;
	for (int i = 0; i < N; i++) {
		s = s * 1103515245u + 12345u;
		x[i] = 2 + 30.0 * (s >> 8) / (1u << 24);
		s = s * 1103515245u + 12345u;
		y[i] = 1 + 15.0 * (s >> 8) / (1u << 24);
		place_push(&sc, &st, x[i], y[i], 1, KIND_GRAIN, &e);
	}
	sb_obs o;
	obs_init(&o, &sc, &st, -1, 20.0, 0, 40, &e);
	CHECK("observe.field.grid", o.cell == 2.0 && o.nx == 20 && o.ny == 13, "cell %g nx %d ny %d", o.cell,
	      o.nx, o.ny);
	sb_journal jr;
	journal_open(&jr, jpath, st.nm, -1, &e);
	long nf = 0, nd = 0;
	/* uniform motion by (0.3, -0.1) per period: every occupied cell's mean is that */
	for (int k = 0; k <= 3; k++) {
		for (int i = 0; i < N; i++) {
			st.q[C_X][0][i] = x[i] + 0.3 * k;
			st.q[C_Y][0][i] = y[i] - 0.1 * k;
		}
		sample_obs_strobe(&o, &st, k * 0.25, 4, &jr, &nf, &nd, &e);
	}
	long off;
	journal_sync(&jr, &off, &e);
	journal_close(&jr);
	int len = obs_field_len(&o);
	double *rec = malloc(sizeof(double) * (size_t)len);
	int n = read_back(REC_TAG(REC_FIELD), rec, len);
	CHECK("observe.field.one_block", nd == 1 && n == len && rec[1] == 3, "nd %ld n %d", nd, n);
	size_t nc = (size_t)o.nx * o.ny;
	double total = 0, worst = 0;
	for (size_t c = 0; c < nc && n == len; c++) {
		double cnt = rec[2 + 2 * nc + c];
		total += cnt;
		if (cnt > 0) {
			worst = fmax(worst, fabs(rec[2 + c] / cnt - 0.3));
			worst = fmax(worst, fabs(rec[2 + nc + c] / cnt + 0.1));
		}
	}
	/* three periods of 50 disks, all inside the grid */
	CHECK("observe.field.count", total == 3 * N, "total count %g", total);
	CHECK("observe.field.uniform_motion", worst < 1e-12, "worst deviation %g", worst);
	free(rec);
	obs_free(&o);
	state_free(&st);
}

static void test_ring(void)
{
	sb_scene sc;
	params_defaults(&sc);
	sc.ring = 1;
	sb_state st = {0};
	sb_err e = {0};
	/* intruder at (30, 10); grains at distances 3 (out), 5 (in, below), 6 (in, above),
	 * 7.9 (in, below), 9 (out) */
	place_push(&sc, &st, 30, 10, 4, KIND_INTRUDER, &e);
	double gx[5] = {33, 30, 36, 30, 39}, gy[5] = {10, 5, 10, 2.1, 10};
	for (int i = 0; i < 5; i++)
		place_push(&sc, &st, gx[i], gy[i], 1, KIND_GRAIN, &e);
	sb_obs o;
	obs_init(&o, &sc, &st, 0, 20, 0, 60, &e);
	double fa[6] = {100, 1, 10, 20, 30, 2};
	memcpy(o.fabs_sum, fa, sizeof fa);
	/* velocities (v dt with inv_dt = 1): two of the ring grains move, one rests */
	st.q[C_X][1][2] = 2;
	st.q[C_Y][1][3] = -2;
	/* contact forces (the net force adds the weight -m g) */
	st.f[C_X][2] = 3;
	st.f[C_Y][2] = 4 + st.m[2] * sc.gravity; /* net (3, 4): 5 */
	st.f[C_Y][3] = st.m[3] * sc.gravity;     /* at rest: 0 */
	st.f[C_Y][4] = st.m[4] * sc.gravity - 6; /* net (0, -6): 6 */
	double row[OBS_RING_COLS];
	obs_ring_sample(&o, &st, 0, 0.5, 1.0, row);
	/* ring grains: 2 (|F| 10, v (2,0), lower), 3 (20, (0,0), upper), 4 (30, (0,-2), lower) */
	CHECK_REL("observe.ring.net_force", o.acc[OBS_RA_NET], 11.0 / 3, 1e-12);
	CHECK_REL("observe.ring.net_force_lower", o.acc[OBS_RA_NET_LO], 5.5, 1e-12);
	CHECK("observe.ring.row", row[OBS_RR_TIME] == 0.5 && row[OBS_RR_MEAN] == 20 && row[OBS_RR_N] == 3 &&
		      row[OBS_RR_CX] == 30 && row[OBS_RR_CY] == 10 && fabs(row[OBS_RR_NET] - 11.0 / 3) < 1e-12,
	      "row t %g mean %g n %g centre (%g, %g) net %g", row[0], row[1], row[4], row[5], row[6], row[2]);
	/* before the rise (no rise yet, ring_from 0): the sample is in the window */
	CHECK("observe.ring.before", o.ring_before == 1 && o.before[OBS_RB_MEAN] == 20 && o.ring_before_end == 0.5,
	      "before %ld mean %g end %g", o.ring_before, o.before[OBS_RB_MEAN], o.ring_before_end);
	CHECK_REL("observe.ring.mean_force", o.acc[0], 20.0, 1e-15);
	CHECK_REL("observe.ring.mean_force_lower", o.acc[1], 20.0, 1e-15);
	CHECK_REL("observe.ring.sum_force", o.acc[2], 60.0, 1e-15);
	CHECK_REL("observe.ring.sum_force_lower", o.acc[3], 40.0, 1e-15);
	CHECK("observe.ring.grains", o.acc[6] == 3 && o.acc[7] == 2, "grains %g lower %g", o.acc[6], o.acc[7]);
	/* T = 0.5 (<v^2> - <v>^2): v = (2,0), (0,0), (0,-2): <v^2> = 8/3, <v> = (2/3, -2/3) */
	CHECK_REL("observe.ring.temperature", o.acc[4], 0.5 * (8.0 / 3 - 8.0 / 9), 1e-14);
	CHECK("observe.ring.cleared", o.fabs_sum[0] == 0 && o.fabs_sum[5] == 0, "fabs_sum not cleared");
	/* after the rise: in the averages, not in the window */
	o.risen = 1;
	memcpy(o.fabs_sum, fa, sizeof fa);
	obs_ring_sample(&o, &st, 0, 0.6, 1.0, row);
	CHECK("observe.ring.after_rise", o.ring_samples == 2 && o.ring_before == 1 && o.acc[OBS_RA_MEAN] == 40,
	      "samples %ld before %ld", o.ring_samples, o.ring_before);
	obs_free(&o);
	/* ring_centre = settled: the centre stays where the intruder was at t = 0 */
	sc.ring_centre = RING_SETTLED;
	obs_init(&o, &sc, &st, 0, 20, 0, 60, &e);
	st.q[C_Y][0][0] = 14;
	obs_ring_sample(&o, &st, 0, 0.1, 1.0, row);
	CHECK("observe.ring.settled_centre", !o.ring_follow && row[OBS_RR_CX] == 30 && row[OBS_RR_CY] == 10,
	      "centre (%g, %g)", row[OBS_RR_CX], row[OBS_RR_CY]);
	obs_free(&o);
	state_free(&st);
}

/* A band whose n periods alternate mean + d, mean - d: its mean is mean and its
 * standard error d / sqrt(n - 1) (n even). */
static sb_obs band_of(int n, double mean, double se)
{
	sb_obs o;
	memset(&o, 0, sizeof o);
	const double d = se * sqrt(n - 1.0);
	for (int i = 0; i < n; i++) {
		o.band_last = mean + (i % 2 ? -d : d);
		obs_band_add(&o);
	}
	return o;
}

/* The flux stop rule's verdict, both ways: clear of the threshold on either side
 * and either sign ends the run; straddling it, or too few periods, does not. */
static void test_band_rule(void)
{
	const double thr = 2, k = 3, se = 0.05;
	struct {
		const char *id;
		int n;
		double mean, e, thr;
		int want;
	} c[] = {
		{"observe.band_rule.on_clear", 26, 20, 1, thr, 1},      /* 17..23 */
		{"observe.band_rule.on_negative", 26, -20, 1, thr, 1},  /* |Phi| >= 2 by k SE */
		{"observe.band_rule.off_clear", 26, 0.1, 0.3, thr, 1},  /* -0.8..1.0 */
		{"observe.band_rule.at_threshold", 26, 2.5, 1, thr, 0}, /* -0.5..5.5 straddles 2 */
		{"observe.band_rule.just_on", 26, 2.6, 0.19, thr, 1},   /* 2.03..3.17 */
		{"observe.band_rule.just_short", 26, 2.6, 0.21, thr, 0}, /* 1.97..3.23 */
		{"observe.band_rule.crosses_zero", 26, 0.5, 1, thr, 0}, /* -2.5..3.5 */
		{"observe.band_rule.too_few", 18, 20, 1, thr, 0},       /* 18 < 20 periods */
		{"observe.band_rule.se_rule_met", 26, 20, 0.04, 0, 1},  /* no threshold: SE < 0.05 */
		{"observe.band_rule.se_rule_not", 26, 0.1, 0.06, 0, 0},
	};
	for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
		const sb_obs o = band_of(c[i].n, c[i].mean, c[i].e);
		const int got = obs_band_answered(&o, 20, se, c[i].thr, k);
		CHECK(c[i].id, got == c[i].want, "mean %g SE %g (SE got %g) threshold %g: answered %d, want %d",
		      c[i].mean, c[i].e, obs_band_se(&o, 20), c[i].thr, got, c[i].want);
	}
}

/* The segregation index (docs/model.md, "Segregation index") on beds whose answer is
 * known: a bed of 12 columns and 10 rows, heights 2 row (plus a constant that must not
 * matter), large disks (r 2) in chosen places among small ones (r 1). */
enum { SEG_COLS = 12, SEG_ROWS = 10, SEG_N = SEG_COLS * SEG_ROWS + 1 };
static double seg_of(int (*large)(int row, int col), int intruder_on_top)
{
	static double y[SEG_N], r[SEG_N], work[SEG_N];
	static unsigned char kind[SEG_N];
	for (int row = 0; row < SEG_ROWS; row++)
		for (int col = 0; col < SEG_COLS; col++) {
			const int i = row * SEG_COLS + col;
			y[i] = 7.5 + 2.0 * row;
			r[i] = large(row, col) ? 2 : 1;
			kind[i] = KIND_GRAIN;
		}
	/* an intruder is no grain: above every grain, or below, it changes nothing */
	y[SEG_N - 1] = intruder_on_top ? 1e3 : -1e3;
	r[SEG_N - 1] = 4;
	kind[SEG_N - 1] = KIND_INTRUDER;
	double split;
	if (!obs_segregation_split(r, kind, SEG_N, &split) || split != 1.5)
		return NAN;
	return obs_segregation(y, r, kind, SEG_N, split, work);
}
static int top3(int row, int col) { return (void)col, row >= SEG_ROWS - 3; }
static int bottom3(int row, int col) { return (void)col, row < 3; }
static int every4th(int row, int col) { return (void)row, col % 4 == 1; }
static int top3_but_one(int row, int col) { return row == 0 && col == 0 ? 1 : row == SEG_ROWS - 1 && col == 5 ? 0 : top3(row, col); }
static int upper_half(int row, int col) { return (void)col, row >= SEG_ROWS / 2; }
/* a checkerboard of the bed's lower half and the upper half large: half the way */
static int half_way(int row, int col) { return row >= SEG_ROWS / 2 ? ((row + col) % 2 == 0) : 0; }

static void test_segregation(void)
{
	double s = seg_of(top3, 1);
	CHECK("observe.segregation.large_all_on_top", fabs(s - 1) < 1e-12, "S = %.17g, want 1", s);
	s = seg_of(bottom3, 0);
	CHECK("observe.segregation.large_all_at_bottom", fabs(s + 1) < 1e-12, "S = %.17g, want -1", s);
	s = seg_of(every4th, 1);
	CHECK("observe.segregation.mixed", fabs(s) < 1e-12, "S = %.17g, want 0 (a quarter of every row large)", s);
	/* one large grain of the top row swapped with a small one of the bottom row: below
	 * +1, by the definition's closed form (heights 2 row; the constant cancels) */
	s = seg_of(top3_but_one, 1);
	{ /* large: rows 7-9 less one of row 9, plus one of row 0; small: the rest */
		const double hl = (2.0 * (12 * 7 + 12 * 8 + 11 * 9) + 0) / 36, hs = (2.0 * (12 * 21 + 11 * 0) + 18) / 84;
		const double hl_max = 2.0 * (12 * 7 + 12 * 8 + 12 * 9) / 36, hs_max = 2.0 * 12 * 21 / 84;
		const double want = (hl - hs) / (hl_max - hs_max);
		CHECK("observe.segregation.one_swapped", fabs(s - want) < 1e-12 && s < 1, "S = %.17g, want %.17g", s,
		      want);
	}
	/* equal numbers (60 large, 60 small): the upper half large is +1; half of the upper
	 * half large (a checkerboard, 30), by the closed form again */
	s = seg_of(upper_half, 0);
	CHECK("observe.segregation.upper_half", fabs(s - 1) < 1e-12, "S = %.17g, want 1", s);
	s = seg_of(half_way, 1);
	{
		/* large: 6 of each of rows 5-9 (mean 14); small: the other 30 there and rows 0-4 (mean 4) */
		const double hl = 14, hs = (30.0 * 14 + 60 * 4) / 90;
		/* all on top: the 30 large take rows 8-9 (24 grains, mean height 17) and 6 of row 7 (14) */
		const double top = (24.0 * 17 + 6 * 14) / 30, rest = (2.0 * 12 * (0 + 1 + 2 + 3 + 4 + 5 + 6) + 6 * 14) / 90;
		const double want = (hl - hs) / (top - rest);
		CHECK("observe.segregation.half_way", fabs(s - want) < 1e-12 && s > 0.2 && s < 0.8, "S = %.17g, want %.17g",
		      s, want);
	}
	double split;
	const double r1[3] = {1, 1, 3};
	const unsigned char k1[3] = {KIND_GRAIN, KIND_GRAIN, KIND_INTRUDER};
	CHECK("observe.segregation.one_size_has_none", !obs_segregation_split(r1, k1, 3, &split), "split %g", split);
}

int main(void)
{
	int fd = mkstemp(jpath);
	if (fd >= 0)
		close(fd);
	test_flux();
	test_flux_seam();
	test_crossing_edges();
	test_field();
	test_ring();
	test_band_rule();
	test_segregation();
	unlink(jpath);
	return tl_done();
}
