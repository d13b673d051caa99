/* resolve.c - the precision floor of an onset's interval, with known answers both
 * ways: a bootstrap interval narrower than the spacing of the sampled frequencies
 * around the onset is widened to them, a wider one is left alone, a missing one stays
 * missing; the neighbours of an onset at, below and above the samples; two onsets
 * agree when their intervals overlap, and not when they are disjoint. */
#include <math.h>

#include "measure/resolve.h"
#include "testlib.h"

int main(void)
{
	/* the case: runs every 0.05 Hz, a crossing at 2.662 with a bootstrap
	 * interval [2.652, 2.675] (0.023 Hz) that claims more than the grid resolves */
	const double f[] = {2.75, 2.6, 2.65, 2.7, 2.65, 2.6, 2.8}; /* any order, repeats */
	const size_t n = sizeof f / sizeof *f;
	double a, b;
	CHECK("resolve.neighbours.inside", !resolve_neighbours(f, n, 2.662, &a, &b) && a == 2.65 && b == 2.7,
	      "got [%g, %g]", a, b);
	/* interpolated to the upper sample: the crossing lies in (2.65, 2.7] */
	CHECK("resolve.neighbours.at_sample", !resolve_neighbours(f, n, 2.7, &a, &b) && a == 2.65 && b == 2.7,
	      "got [%g, %g]", a, b);
	CHECK("resolve.neighbours.below_all", !resolve_neighbours(f, n, 2.5, &a, &b) && a == 2.5 && b == 2.6,
	      "got [%g, %g]", a, b);
	CHECK("resolve.neighbours.above_all", !resolve_neighbours(f, n, 2.9, &a, &b) && a == 2.8 && b == 2.9,
	      "got [%g, %g]", a, b);
	CHECK("resolve.neighbours.nan", resolve_neighbours(f, n, NAN, &a, &b) && isnan(a) && isnan(b),
	      "got [%g, %g]", a, b);

	double lo = 2.652, hi = 2.675;
	CHECK("resolve.grid.narrow_widened", resolve_grid(2.662, &lo, &hi, f, n) && lo == 2.65 && hi == 2.7,
	      "got [%g, %g], want [2.65, 2.7]", lo, hi);
	CHECK("resolve.grid.narrow_at_least_spacing", hi - lo >= 0.05 - 1e-12, "width %g", hi - lo);
	lo = 2.61, hi = 2.74;
	CHECK("resolve.grid.wide_untouched", !resolve_grid(2.662, &lo, &hi, f, n) && lo == 2.61 && hi == 2.74,
	      "got [%g, %g], want [2.61, 2.74]", lo, hi);
	/* one side short: only that side moves */
	lo = 2.64, hi = 2.68;
	CHECK("resolve.grid.one_side", resolve_grid(2.662, &lo, &hi, f, n) && lo == 2.64 && hi == 2.7,
	      "got [%g, %g], want [2.64, 2.7]", lo, hi);
	lo = NAN, hi = NAN;
	CHECK("resolve.grid.no_interval_stays", !resolve_grid(2.662, &lo, &hi, f, n) && isnan(lo) && isnan(hi),
	      "got [%g, %g]", lo, hi);

	/* a bisection's bracket: an interval inside it is widened, one around it not */
	lo = 2.66, hi = 2.665;
	CHECK("resolve.widen.bracket", resolve_widen(&lo, &hi, 2.65, 2.67) && lo == 2.65 && hi == 2.67,
	      "got [%g, %g]", lo, hi);
	lo = 2.6, hi = 2.7;
	CHECK("resolve.widen.holds", !resolve_widen(&lo, &hi, 2.65, 2.67) && lo == 2.6 && hi == 2.7, "got [%g, %g]",
	      lo, hi);

	/* agreement of two onsets: overlapping intervals agree, disjoint ones do not, a
	 * missing end is no agreement */
	CHECK("resolve.overlap.yes", resolve_overlap(2.6, 2.7, 2.65, 2.8), "[2.6, 2.7] and [2.65, 2.8]");
	CHECK("resolve.overlap.touching", resolve_overlap(2.6, 2.7, 2.7, 2.8), "[2.6, 2.7] and [2.7, 2.8]");
	CHECK("resolve.overlap.no", !resolve_overlap(2.633, 2.711, 2.721, 2.736), "the issue's [2.633, 2.711] and [2.721, 2.736]");
	CHECK("resolve.overlap.missing", !resolve_overlap(2.6, NAN, 2.65, 2.8), "a NaN end");
	CHECK("resolve.overlap.unbounded", !resolve_overlap(-INFINITY, 2.7, 2.65, 2.8), "an infinite end");
	return tl_done();
}
