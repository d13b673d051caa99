/* rolls.c - the roll reach of synthetic profiles with a known answer (a linear flank
 * whose crossing of half the maximum is at D = 10 cm, either sign, smoothed or not, a
 * noise spike below the rolls, rolls down to the floor, no flux at all), and the
 * Student and Welch intervals against hand-computed values (t quantiles from tables). */
#include <math.h>
#include <stdio.h>

#include "measure/rolls.h"
#include "testlib.h"

enum { L = 20 };

int main(void)
{
	double h[L], phi[L], neg[L], out[L];
	/* lines at 0.5, 1.5, ..., 19.5 cm, surface 20 cm; Phi = 0 below 8 cm, 10 above
	 * 12 cm, linear between: half the maximum (5) at D = 10 cm exactly */
	for (int l = 0; l < L; l++) {
		h[l] = l + 0.5;
		phi[l] = fmax(0, fmin(10, (h[l] - 8) * 2.5));
		neg[l] = -phi[l];
	}
	rolls_reach r;
	CHECK("rolls.depth.ok", rolls_depth(h, phi, L, 20, 0.5, 1, &r) == 0, "returned -1");
	CHECK_REL("rolls.depth.bottom_linear_flank", r.bottom, 10.0, 1e-12);
	CHECK_REL("rolls.depth.reach_below_surface", r.reach, 10.0, 1e-12);
	CHECK("rolls.depth.max", r.phi_max == 10 && r.sign == 1 && r.lmax == 12 && !r.to_floor, "max %g sign %d line %zu",
	      r.phi_max, r.sign, r.lmax);
	rolls_depth(h, neg, L, 20, 0.5, 1, &r);
	CHECK("rolls.depth.negative_rolls", r.sign == -1 && fabs(r.bottom - 10) < 1e-12, "sign %d bottom %g", r.sign,
	      r.bottom);
	/* a quarter of the maximum (2.5) is crossed at D = 9 cm */
	rolls_depth(h, phi, L, 20, 0.25, 1, &r);
	CHECK_REL("rolls.depth.fraction_quarter", r.bottom, 9.0, 1e-12);
	/* a running mean over 3 lines leaves the linear flank as it is */
	rolls_depth(h, phi, L, 20, 0.5, 3, &r);
	CHECK_REL("rolls.depth.smoothed_same_crossing", r.bottom, 10.0, 1e-12);
	/* a spike below the rolls, not connected to them, does not count */
	phi[2] = 9;
	rolls_depth(h, phi, L, 20, 0.5, 1, &r);
	CHECK_REL("rolls.depth.spike_below_ignored", r.bottom, 10.0, 1e-12);
	phi[2] = 0;
	/* rolls down to the lowest line */
	double c[L];
	for (int l = 0; l < L; l++)
		c[l] = 3 + 0.01 * l;
	rolls_depth(h, c, L, 20, 0.5, 1, &r);
	CHECK("rolls.depth.to_floor", r.to_floor && r.bottom == 0.5 && r.reach == 19.5, "to_floor %d bottom %g",
	      r.to_floor, r.bottom);
	double z[L] = {0};
	CHECK("rolls.depth.no_flux_no_rolls", rolls_depth(h, z, L, 20, 0.5, 1, &r) == -1 && isnan(r.reach),
	      "reach %g", r.reach);
	z[3] = NAN;
	CHECK("rolls.depth.nan_refused", rolls_depth(h, z, L, 20, 0.5, 1, &r) == -1, "accepted a NaN");
	/* running mean: the ends average over fewer lines */
	const double v[5] = {1, 2, 3, 4, 10};
	rolls_smooth(v, 5, 3, out);
	CHECK("rolls.smooth.ends", out[0] == 1.5 && out[2] == 3 && out[4] == 7, "%g %g %g", out[0], out[2], out[4]);

	/* Student: 2, 4, 6, 8: mean 5, sd sqrt(20/3), t(0.975, 3) = 3.182446305 */
	const double m4[4] = {2, 4, 6, 8};
	rolls_mean m;
	rolls_mean_ci(m4, 4, 0.95, &m);
	const double hw = 3.182446305 * sqrt(20.0 / 3) / 2;
	CHECK_REL("rolls.mean.lo", m.lo, 5 - hw, 1e-8);
	CHECK_REL("rolls.mean.hi", m.hi, 5 + hw, 1e-8);
	rolls_mean_ci(m4, 1, 0.95, &m);
	CHECK("rolls.mean.one_value_no_interval", m.mean == 2 && isnan(m.lo), "mean %g lo %g", m.mean, m.lo);
	/* Welch, equal spread and size: df = 6, t(0.975, 6) = 2.446911851, se = sqrt(5/6) */
	const double a[4] = {1, 2, 3, 4}, b[4] = {3, 4, 5, 6};
	rolls_diff d;
	rolls_welch(a, 4, b, 4, 0.95, &d);
	CHECK_REL("rolls.welch.df_equal", d.df, 6.0, 1e-12);
	CHECK_REL("rolls.welch.lo", d.lo, -2 - 2.446911851 * sqrt(5.0 / 6), 1e-8);
	CHECK_REL("rolls.welch.hi", d.hi, -2 + 2.446911851 * sqrt(5.0 / 6), 1e-8);
	/* unequal: 1..5 against 2, 4, 6: df = 3.532847 (R's t.test: 3.5328) */
	const double a5[5] = {1, 2, 3, 4, 5}, b3[3] = {2, 4, 6};
	rolls_welch(a5, 5, b3, 3, 0.95, &d);
	CHECK_REL("rolls.welch.df_satterthwaite", d.df, 3.532847, 1e-6);
	CHECK("rolls.welch.covers", d.d == -1 && d.lo < -1 && d.hi > -1, "d %g [%g, %g]", d.d, d.lo, d.hi);
	const double k1[3] = {2, 2, 2}, k2[2] = {1, 1};
	rolls_welch(k1, 3, k2, 2, 0.95, &d);
	CHECK("rolls.welch.no_spread", d.d == 1 && d.lo == 1 && d.hi == 1, "d %g [%g, %g]", d.d, d.lo, d.hi);
	rolls_welch(k1, 3, k2, 1, 0.95, &d);
	CHECK("rolls.welch.one_run_no_interval", d.d == 1 && isnan(d.lo), "d %g lo %g", d.d, d.lo);
	return tl_done();
}
