/* hyst.c - hysteresis on synthetic up-down ramps with known transitions: the legs
 * (split at the extreme frequency, the hold before the ramp left out even when the
 * samples fall a step late, one leg for a linear ramp), smoothing that stays within a
 * leg, and the up and down midpoints, their difference and its paired bootstrap
 * interval recovered from noisy data of several seeds (true difference inside, zero
 * outside), reproducibly. */
#include <gsl/gsl_randist.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "boot.h"
#include "measure/hyst.h"
#include "testlib.h"

enum { NHOLD = 6, NLEG = 80, P = NHOLD + 2 * NLEG, NS = 6 };

static const double F_UP = 5.0, F_DOWN = 4.6, WIDTH = 0.1, STEP = 10;

/* One run: 2 s hold at 3 Hz (Phi = 100, a start-of-shaking transient), then 3 -> 7 Hz
 * in NLEG periods and back in NLEG periods; Phi a logistic step at F_UP going up and at
 * F_DOWN coming down, plus Gaussian noise sigma. Sample times late by `late` s. */
static void synth(flux_data *d, gsl_rng *r, double sigma, double late)
{
	static double t[P], f[P], phi[P], h[1] = {10};
	double now = 0;
	for (int p = 0; p < P; p++) {
		double fr, mid;
		if (p < NHOLD) {
			fr = 3;
			mid = NAN;
		} else if (p < NHOLD + NLEG) {
			fr = 3 + 4.0 * (p - NHOLD + 1) / NLEG; /* the last up period is at 7 Hz */
			mid = F_UP;
		} else {
			fr = 7 - 4.0 * (p - NHOLD - NLEG + 1) / NLEG;
			mid = F_DOWN;
		}
		now += 1 / fr;
		t[p] = now + late;
		f[p] = fr;
		phi[p] = isnan(mid) ? 100 : STEP / (1 + exp(-(fr - mid) / WIDTH)) + gsl_ran_gaussian(r, sigma);
	}
	memset(d, 0, sizeof *d);
	d->P = P;
	d->L = 1;
	d->t = t;
	d->f = f;
	d->phi = phi;
	d->h = h;
	d->surface = 20;
}

static void test_legs(gsl_rng *r)
{
	flux_data d;
	hyst_leg leg[2];
	synth(&d, r, 0, 0);
	/* the hold ends at t = 2 s exactly: periods 0..5 */
	int n = hyst_legs(&d, 1, 3, 7, 2.0, leg);
	CHECK("hyst.legs.updown", n == 2 && leg[0].a == NHOLD && leg[0].b == NHOLD + NLEG && leg[0].branch == HYST_UP &&
					  leg[1].a == NHOLD + NLEG && leg[1].b == P && leg[1].branch == HYST_DOWN,
	      "n %d up [%zu, %zu) br %d, down [%zu, %zu) br %d", n, leg[0].a, leg[0].b, leg[0].branch, leg[1].a, leg[1].b,
	      leg[1].branch);
	/* samples one step late (the first step after each phase-0 crossing) */
	synth(&d, r, 0, 5e-5);
	n = hyst_legs(&d, 1, 3, 7, 2.0, leg);
	CHECK("hyst.legs.hold_samples_late", n == 2 && leg[0].a == NHOLD, "n %d first period %zu, want %d", n, leg[0].a,
	      NHOLD);
	n = hyst_legs(&d, 1, 3, 7, 0, leg);
	CHECK("hyst.legs.no_hold", n == 2 && leg[0].a == 0, "n %d first period %zu", n, leg[0].a);
	/* a linear ramp is one leg; from > to makes it a down leg */
	n = hyst_legs(&d, 0, 7, 3, 2.0, leg);
	CHECK("hyst.legs.linear_down", n == 1 && leg[0].a == NHOLD && leg[0].b == P && leg[0].branch == HYST_DOWN,
	      "n %d [%zu, %zu) branch %d", n, leg[0].a, leg[0].b, leg[0].branch);
	n = hyst_legs(&d, 1, 3, 7, 1e4, leg);
	CHECK("hyst.legs.all_hold", n == 0, "n %d legs in a run that never left the hold", n);
}

static void test_smooth(void)
{
	/* 0 1 2 3 4 | 50 50 50: a running mean of 3 never mixes the two legs */
	double v[8] = {0, 1, 2, 3, 4, 50, 50, 50}, out[8];
	hyst_smooth(v, 0, 5, 3, out);
	hyst_smooth(v, 5, 8, 3, out);
	CHECK("hyst.smooth.interior", out[2] == 2 && out[3] == 3, "out %g %g", out[2], out[3]);
	CHECK("hyst.smooth.cut_at_leg_end", out[0] == 0.5 && out[4] == 3.5 && out[5] == 50,
	      "ends %g %g, next leg %g (want 0.5 3.5 50)", out[0], out[4], out[5]);
	hyst_smooth(v, 0, 5, 1, out);
	CHECK("hyst.smooth.k1_is_identity", out[0] == 0 && out[4] == 4, "out %g %g", out[0], out[4]);
}

/* The pooled seeds of one group, as bin/hysteresis builds them. */
static int fill(hyst_data *h, gsl_rng *r, double sigma, double hold)
{
	hyst_init(h, NAN);
	for (long s = 0; s < NS; s++) {
		flux_data d;
		synth(&d, r, sigma, 5e-5);
		hyst_leg leg[2];
		int n = hyst_legs(&d, 1, 3, 7, hold, leg);
		if (hyst_add_run(h, 10 + s))
			return -1;
		for (int q = 0; q < n; q++)
			for (size_t p = leg[q].a; p < leg[q].b; p++)
				if (hyst_add(h, leg[q].branch, d.f[p], d.phi[p], 10 + s))
					return -1;
	}
	return 0;
}

static void test_estimate(void)
{
	gsl_rng *r = boot_rng(77);
	hyst_data h;
	hyst_res a, b;
	CHECK("hyst.estimate.fill", fill(&h, r, 1.0, 2.0) == 0, "out of memory");
	CHECK("hyst.estimate.units", h.nu == NS && h.nruns == NS && h.br[0].n == NS * NLEG && h.br[1].n == NS * NLEG,
	      "seeds %zu runs %zu points up %zu down %zu", h.nu, h.nruns, h.br[0].n, h.br[1].n);
	CHECK("hyst.estimate.ok", hyst_estimate(&h, 200, 5, 0.95, &a) == 0, "hyst_estimate failed");
	CHECK("hyst.estimate.up", fabs(a.v[0] - F_UP) < 0.03, "f_up %.4f, true %.2f", a.v[0], F_UP);
	CHECK("hyst.estimate.down", fabs(a.v[1] - F_DOWN) < 0.03, "f_down %.4f, true %.2f", a.v[1], F_DOWN);
	CHECK("hyst.estimate.diff", fabs(a.v[2] - (F_UP - F_DOWN)) < 0.04 && a.v[2] == a.v[0] - a.v[1],
	      "diff %.4f, true %.2f", a.v[2], F_UP - F_DOWN);
	CHECK("hyst.estimate.threshold", fabs(a.v[3] - F_UP) < 0.06 && fabs(a.v[4] - F_DOWN) < 0.06 &&
						 fabs(a.v[5] - (F_UP - F_DOWN)) < 0.08,
	      "threshold up %.4f down %.4f diff %.4f", a.v[3], a.v[4], a.v[5]);
	CHECK("hyst.estimate.fits_kept", a.fit[0].ok && a.fit[1].ok && a.fit[0].x0 == a.v[0] && a.fit[1].x0 == a.v[1],
	      "fits ok %d %d", a.fit[0].ok, a.fit[1].ok);
	CHECK("hyst.ci.diff_covers_truth", a.lo[2] <= F_UP - F_DOWN && F_UP - F_DOWN <= a.hi[2], "[%.4f, %.4f] misses %.2f",
	      a.lo[2], a.hi[2], F_UP - F_DOWN);
	CHECK("hyst.ci.diff_excludes_zero", a.lo[2] > 0, "[%.4f, %.4f] contains 0", a.lo[2], a.hi[2]);
	CHECK("hyst.ci.boot_ok", a.boot_ok > 190 && a.boot_ok <= 200, "%zu of 200 replicates fitted", a.boot_ok);
	CHECK("hyst.ci.ordered", a.lo[0] <= a.v[0] + 0.02 && a.v[0] - 0.02 <= a.hi[0] && a.lo[1] < a.hi[1],
	      "up [%.4f, %.4f] around %.4f", a.lo[0], a.hi[0], a.v[0]);
	CHECK("hyst.estimate.reproducible", hyst_estimate(&h, 200, 5, 0.95, &b) == 0 && !memcmp(a.lo, b.lo, sizeof a.lo) &&
						    !memcmp(a.hi, b.hi, sizeof a.hi),
	      "same seed, different intervals");
	hyst_free(&h);
	/* the hold's transient (Phi = 100 at 3 Hz) kept in the up leg would wreck it */
	CHECK("hyst.estimate.hold_kept_fill", fill(&h, r, 1.0, 0) == 0, "out of memory");
	hyst_estimate(&h, 0, 5, 0.95, &b);
	CHECK("hyst.estimate.hold_matters", h.br[0].n == NS * (NLEG + NHOLD) && !(fabs(b.v[0] - F_UP) < 0.03),
	      "up points %zu, f_up %.4f with the transient in", h.br[0].n, b.v[0]);
	CHECK("hyst.estimate.no_boot", isnan(b.lo[2]) && isnan(b.hi[2]) && b.boot_ok == 0, "interval without bootstrap");
	hyst_free(&h);
	/* one seed: no interval (nothing to resample), estimates still there */
	hyst_init(&h, NAN);
	flux_data d;
	synth(&d, r, 0.2, 0);
	hyst_leg leg[2];
	int n = hyst_legs(&d, 1, 3, 7, 2.0, leg);
	hyst_add_run(&h, 1);
	for (int q = 0; q < n; q++)
		for (size_t p = leg[q].a; p < leg[q].b; p++)
			hyst_add(&h, leg[q].branch, d.f[p], d.phi[p], 1);
	hyst_estimate(&h, 100, 5, 0.95, &b);
	CHECK("hyst.one_seed", fabs(b.v[2] - (F_UP - F_DOWN)) < 0.05 && isnan(b.lo[2]), "diff %.4f [%g, %g]", b.v[2],
	      b.lo[2], b.hi[2]);
	hyst_free(&h);
	gsl_rng_free(r);
}

int main(void)
{
	gsl_rng *r = boot_rng(2025);
	test_legs(r);
	test_smooth();
	test_estimate();
	gsl_rng_free(r);
	return tl_done();
}
