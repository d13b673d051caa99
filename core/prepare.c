/* prepare.c - loose placement of grains and intruder on a lattice, walls of disks. */
#include "prepare.h"

#include <gsl/gsl_rng.h>
#include <math.h>

double prepare_mass(const sb_scene *sc, double r)
{
	return sc->mass_factor * sc->density * r * r;
}

int prepare_push(const sb_scene *sc, sb_state *st, double x, double y, double r, int kind, sb_err *e)
{
	double m = prepare_mass(sc, r);
	double inv_m = 1.0 / m;
	if (kind == KIND_WALL && sc->wall_mass == WALLMASS_INFINITE)
		inv_m = 0;
	return state_push(st, x, y, r, kind, m, inv_m, 1.0 / (0.5 * m * r * r), e);
}

/* Evenly spaced points from a to b (both included) no farther apart than s. */
static int n_span(double a, double b, double s)
{
	return (int)ceil((b - a) / s - 1e-9) + 1;
}

int prepare_place(const sb_scene *sc, sb_state *st, sb_err *e)
{
	const double W = sc->width, rw = sc->wall_radius;
	const double rmean = 0.5 * (sc->r_min + sc->r_max);
	const double R1 = sc->radius_ratio * rmean;
	/* Loose square lattice 10 % wider than the largest grain: nobody overlaps and the
	 * bed compacts by only a few percent while settling. */
	const double pitch = 2.2 * sc->r_max;
	const int ncol = (int)floor(W / pitch);
	const double xoff = 0.5 * (W - ncol * pitch) + 0.5 * pitch;
	const double jit = 0.5 * pitch - sc->r_max; /* free play of a grain in its site */
	const double gap = 0.05 * sc->r_max;
	const double ix = 0.5 * W, iy = sc->depth * pitch + R1 + gap;

	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	if (!rng)
		return sb_errf(e, SB_ENOMEM, "out of memory for the random generator");
	gsl_rng_set(rng, (unsigned long)sc->seed);

	int err = 0;
	if (R1 > 0)
		err = prepare_push(sc, st, ix, iy, R1, KIND_INTRUDER, e);
	long placed = 0;
	double top = R1 > 0 ? iy + R1 : 0;
	for (long row = 0; placed < sc->n_grains && !err; row++) {
		const double y = (row + 0.5) * pitch;
		for (int c = 0; c < ncol && placed < sc->n_grains && !err; c++) {
			/* draw first so that a skipped site still advances the stream alike */
			const double r = sc->r_min + (sc->r_max - sc->r_min) * gsl_rng_uniform(rng);
			const double dx = jit * (2 * gsl_rng_uniform(rng) - 1);
			const double x = xoff + c * pitch + dx;
			if (R1 > 0 && hypot(x - ix, y - iy) < R1 + r + gap)
				continue;
			err = prepare_push(sc, st, x, y, r, KIND_GRAIN, e);
			placed++;
			top = fmax(top, y + r);
		}
		if (ncol == 0)
			break;
	}
	gsl_rng_free(rng);
	if (err)
		return err;

	/* Walls: a bottom row with centres at y = -rw (its top touches y = 0) and two side
	 * columns at x = -rw and W + rw, so the inner box is [0, W] x [0, height]. */
	const double H = sc->wall_height > 0 ? sc->wall_height : 2 * top;
	const int nb = n_span(-rw, W + rw, sc->wall_spacing);
	for (int k = 0; k < nb && !err; k++)
		err = prepare_push(sc, st, -rw + (W + 2 * rw) * k / (nb - 1), -rw, rw, KIND_WALL, e);
	const int ns = n_span(-rw, H, sc->wall_spacing);
	for (int k = 1; k < ns && !err; k++) {
		const double y = -rw + (H + rw) * k / (ns - 1);
		err = prepare_push(sc, st, -rw, y, rw, KIND_WALL, e);
		if (!err)
			err = prepare_push(sc, st, W + rw, y, rw, KIND_WALL, e);
	}
	return err;
}
