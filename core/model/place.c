/* place.c - loose placement of grains and intruder on a lattice, walls of disks. */
#include "place.h"

#include <gsl/gsl_rng.h>
#include <math.h>

#include "guard.h"

const char *place_density_key(const sb_scene *sc, int kind)
{
	return kind == KIND_INTRUDER && sc->intruder_density > 0 ? "intruder_density" : "density";
}

double place_density(const sb_scene *sc, int kind)
{
	return kind == KIND_INTRUDER && sc->intruder_density > 0 ? sc->intruder_density : sc->density;
}

double place_mass(const sb_scene *sc, double r, int kind)
{
	return sc->mass_factor * place_density(sc, kind) * r * r;
}

/* A mass the dynamics can divide by: every key is in range and still the product can
 * underflow (r = 1e-160) or the moment of inertia alone does. */
static int mass_bad(double m, double r)
{
	return !(m > 0) || !isfinite(1.0 / m) || !isfinite(1.0 / (0.5 * m * r * r));
}

int place_push_mass(const sb_scene *sc, sb_state *st, double x, double y, double r, int kind, double m, sb_err *e)
{
	if (mass_bad(m, r))
		return sb_errf(e, SB_EUSAGE, "a disk of radius %g cm with mass %g g has moment of inertia %g g cm^2: "
			       "both must be positive and finite", r, m, 0.5 * m * r * r);
	double inv_m = 1.0 / m, inv_i = 1.0 / (0.5 * m * r * r);
	if (kind == KIND_WALL && sc->wall_mass == WALLMASS_INFINITE)
		inv_m = 0;
	return state_push(st, x, y, r, kind, m, inv_m, inv_i, e);
}

int place_push(const sb_scene *sc, sb_state *st, double x, double y, double r, int kind, sb_err *e)
{
	const double m = place_mass(sc, r, kind);
	if (mass_bad(m, r))
		return sb_errf(e, SB_EUSAGE,
			       "a disk of radius %g cm gets mass %g g and moment of inertia %g g cm^2 from mass_factor %g (%s) "
			       "and %s %g (%s): both must be positive and finite",
			       r, m, 0.5 * m * r * r, sc->mass_factor, params_where(sc, "mass_factor"),
			       place_density_key(sc, kind), place_density(sc, kind),
			       params_where(sc, place_density_key(sc, kind)));
	return place_push_mass(sc, st, x, y, r, kind, m, e);
}

/* How many evenly spaced points from a to b (both included) no farther apart than s:
 * as a double, so that a count beyond int is seen before it is cast. */
static double n_span(double a, double b, double s)
{
	return ceil((b - a) / s - 1e-9) + 1;
}

/* The wall disks of a box of side walls H high, checked before the count is cast. */
static int check_walls(const sb_scene *sc, double nb, double H, double ns, sb_err *e)
{
	const double total = nb + 2 * (ns - 1);
	if (total <= GUARD_MAX_WALLS)
		return 0;
	char height[200] = "";
	if (sc->wall_height > 0)
		snprintf(height, sizeof height, " and wall_height %g cm (%s)", H, params_where(sc, "wall_height"));
	else if (ns > 1)
		snprintf(height, sizeof height,
			 " and side walls %.3g cm high (wall_height 0: twice the loose bed of n_grains %ld, %s)", H,
			 sc->n_grains, params_where(sc, "n_grains"));
	return sb_errf(e, SB_EUSAGE,
		       "%s: wall_spacing %g cm makes %.3g wall disks for width %g cm (%s)%s; a box takes at most %d: "
		       "a larger wall_spacing (at most 2 wall_radius) or a smaller box",
		       params_where(sc, "wall_spacing"), sc->wall_spacing, total, sc->width, params_where(sc, "width"),
		       height, GUARD_MAX_WALLS);
}

/* the key of the largest grain radius, for errors */
#define RHI_KEY(sc) ((sc)->size_dist == SIZE_BINARY ? "r_large" : "r_max")

static int place(const sb_scene *sc, sb_state *st, sb_err *e)
{
	const double W = sc->width, rw = sc->wall_radius;
	double rlo, rhi, rmean;
	params_grain_radii(sc, &rlo, &rhi, &rmean);
	const double R1 = sc->radius_ratio * rmean;
	/* Loose square lattice 10 % wider than the largest grain: nobody overlaps and the
	 * bed compacts by only a few percent while settling. */
	const double pitch = 2.2 * rhi;
	const double cols = floor(W / pitch);
	if (!(cols <= GUARD_MAX_COLUMNS))
		return sb_errf(e, SB_EUSAGE,
			       "%s: width %g cm holds %.3g lattice sites of 2.2 %s = %g cm in a row (%s %g cm, %s); "
			       "the placement takes at most %d: larger grains or a narrower box",
			       params_where(sc, "width"), W, cols, RHI_KEY(sc), pitch, RHI_KEY(sc), rhi,
			       params_where(sc, RHI_KEY(sc)),
			       GUARD_MAX_COLUMNS);
	const int ncol = (int)cols;
	/* depth rows of grains beneath the intruder: more rows than n_grains fill leave the
	 * intruder in the air above the bed, and its height sets the walls' (50000 rows over
	 * 150 grains built 2.5 10^5 wall disks and never settled). One row more than the
	 * grains fill is allowed: a few grains, or none, under an intruder is a valid scene. */
	const double filled = ncol > 0 ? ceil((double)sc->n_grains / ncol) : 0;
	if (sc->radius_ratio > 0 && (double)sc->depth > filled + 1)
		return sb_errf(e, SB_EUSAGE,
			       "%s: depth %ld rows beneath the intruder, but n_grains %ld (%s) fill %.0f rows of %d "
			       "in width %g cm: at most %.0f, or more grains",
			       params_where(sc, "depth"), sc->depth, sc->n_grains, params_where(sc, "n_grains"), filled,
			       ncol, W, filled + 1);
	/* The walls are counted before the placement too (it may take seconds), with the
	 * side walls no lower than the rows n_grains fill at least. */
	/* Periodic sides: the bottom row closes on itself, a whole number of disks over
	 * the period no farther apart than wall_spacing, and there are no side columns
	 * (ns = 1 below: no disks above the bottom row). */
	const int periodic = sc->sides == SIDES_PERIODIC;
	const double nb = periodic ? ceil(W / sc->wall_spacing - 1e-9) : n_span(-rw, W + rw, sc->wall_spacing);
	const double rows = ncol > 0 ? ceil((double)sc->n_grains / ncol) : 0;
	const double H0 = sc->wall_height > 0 ? sc->wall_height : 2 * fmax(0, rows - 0.5) * pitch;
	if (check_walls(sc, nb, H0, H0 > 0 && !periodic ? n_span(-rw, H0, sc->wall_spacing) : 1, e))
		return e->code;
	const double xoff = 0.5 * (W - ncol * pitch) + 0.5 * pitch;
	const double jit = 0.5 * pitch - rhi; /* free play of a grain in its site */
	const double gap = 0.05 * rhi;
	const double ix = 0.5 * W, iy = sc->depth * pitch + R1 + gap;
	/* the intruders (docs/model.md, "Several intruders"): the first where the paper's
	 * one stands when alone, the others side by side (row) or above it (column) */
	const long ni = R1 > 0 ? sc->n_intruders : 0;
	const int row_of = sc->intruder_place == IPLACE_ROW && ni > 1;
#define IX(k) (row_of ? W * (double)((k) + 1) / (double)(ni + 1) : ix)
#define IY(k) (row_of ? iy : iy + (double)(k) * (2 * R1 + gap))

	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	if (!rng)
		return sb_errf(e, SB_ENOMEM, "out of memory for the random generator");
	gsl_rng_set(rng, (unsigned long)sc->seed);

	int err = 0;
	for (long k = 0; k < ni && !err; k++)
		err = place_push(sc, st, IX(k), IY(k), R1, KIND_INTRUDER, e);
	long placed = 0, sites = 0;
	double top = ni > 0 ? IY(ni - 1) + R1 : 0;
	for (long row = 0; placed < sc->n_grains && !err; row++) {
		const double y = (row + 0.5) * pitch;
		for (int c = 0; c < ncol && placed < sc->n_grains && !err; c++) {
			if (++sites % 65536 == 0 && guard_stopped()) {
				err = sb_errf(e, SB_EINTR, "interrupted while placing the grains");
				break;
			}
			/* draw first so that a skipped site still advances the stream alike; one
			 * number per radius whatever size_dist, so both draw the same jitters */
			const double u = gsl_rng_uniform(rng);
			const double r = sc->size_dist == SIZE_BINARY ? (u < sc->large_fraction ? rhi : rlo)
								      : sc->r_min + (sc->r_max - sc->r_min) * u;
			const double dx = jit * (2 * gsl_rng_uniform(rng) - 1);
			const double x = xoff + c * pitch + dx;
			int taken = 0;
			for (long k = 0; k < ni && !taken; k++)
				taken = hypot(x - IX(k), y - IY(k)) < R1 + r + gap;
			if (taken)
				continue;
			err = place_push(sc, st, x, y, r, KIND_GRAIN, e);
			placed++;
			top = fmax(top, y + r);
		}
		if (ncol == 0)
			break;
	}
	gsl_rng_free(rng);
#undef IX
#undef IY
	if (err)
		return err;

	/* Walls: a bottom row with centres at y = -rw (its top touches y = 0) and two side
	 * columns at x = -rw and W + rw, so the inner box is [0, W] x [0, height]. With
	 * periodic sides the bottom row's centres sit at (k + 1/2) W / nb, k < nb, evenly
	 * round the period (the seam between the last and the first is a spacing like
	 * any other), and the columns are not built. */
	const double H = sc->wall_height > 0 ? sc->wall_height : 2 * top;
	const double ns = periodic ? 1 : n_span(-rw, H, sc->wall_spacing);
	if (check_walls(sc, nb, H, ns, e))
		return e->code;
	const int inb = (int)nb, ins = (int)ns;
	for (int k = 0; k < inb && !err; k++) {
		if (k % 65536 == 65535 && guard_stopped())
			return sb_errf(e, SB_EINTR, "interrupted while placing the walls");
		const double x = periodic ? W * (k + 0.5) / inb : -rw + (W + 2 * rw) * k / (inb - 1);
		err = place_push(sc, st, x, -rw, rw, KIND_WALL, e);
	}
	for (int k = 1; k < ins && !err; k++) {
		if (k % 65536 == 0 && guard_stopped())
			return sb_errf(e, SB_EINTR, "interrupted while placing the walls");
		const double y = -rw + (H + rw) * k / (ins - 1);
		err = place_push(sc, st, -rw, y, rw, KIND_WALL, e);
		if (!err)
			err = place_push(sc, st, W + rw, y, rw, KIND_WALL, e);
	}
	return err;
}

int place_scene(const sb_scene *sc, sb_state *st, sb_err *e)
{
	/* up to 10^7 grains and as many wall disks take seconds: a SIGINT or SIGTERM in
	 * them must end the run as one while settling does */
	guard_sig g;
	guard_hold(&g);
	int err = place(sc, st, e);
	guard_release(&g);
	return err;
}
