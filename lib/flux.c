/* flux.c - plane flux and profiles from a run's /observables/flux group (H5MD elements). */
#include "flux.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "h5read.h"
#include "h5sum.h"
#include "layout.h"
#include "params.h"
#include "runfile.h"

/* What the engine writes (core/model/crossing.c, core/model/observe.c): the lines at the slice
 * midpoints of the settled bed, surface (l + 1/2) / L, so increasing, above the floor
 * and below the surface the group records; each period's frequency that of the drive,
 * above 0 and at most the scene's largest; the periods' times from 0 on, in order. A
 * file with other values (heights reversed or constant, a frequency of 0 or 1e30) is
 * refused, naming the value: a band or a period count made of them would be a number
 * of nothing (and GSL's solvers abort on some). */
static int flux_ranges(const flux_data *d, double surface, const char *path, sb_err *e)
{
	const double fmax = params_find("frequency")->max;
	for (size_t l = 0; l < d->L; l++) {
		if (!(d->h[l] > (l ? d->h[l - 1] : 0)))
			return sb_errf(e, SB_EIO, "%s: /observables/flux/heights[%zu] = %g: the lines rise from above the "
				       "floor (%s %g)", path, l, d->h[l], l ? "the line below is at" : "the floor is at",
				       l ? d->h[l - 1] : 0.0);
		if (isfinite(surface) && !(d->h[l] < surface))
			return sb_errf(e, SB_EIO, "%s: /observables/flux/heights[%zu] = %g: not below the surface the "
				       "group records (%g)", path, l, d->h[l], surface);
	}
	for (size_t p = 0; p < d->P; p++) {
		if (!(d->f[p] > 0 && d->f[p] <= fmax))
			return sb_errf(e, SB_EIO, "%s: /observables/flux/frequency/value[%zu] = %g: a drive frequency is in "
				       "(0, %g] Hz", path, p, d->f[p], fmax);
		if (!(d->t[p] >= (p ? d->t[p - 1] : 0)))
			return sb_errf(e, SB_EIO, "%s: /observables/flux/phi/time[%zu] = %g: the periods' times run from 0 "
				       "in order", path, p, d->t[p]);
	}
	return 0;
}

int flux_read(const char *path, flux_data *d, sb_err *e)
{
	memset(d, 0, sizeof *d);
	hid_t f;
	if (h5r_open(path, &f, e))
		return e->code;
	int r;
	size_t dt[3], df[3], dp[3], dh[3];
	if (!h5r_exists(f, RUNFILE_FLUX)) {
		h5r_close(f);
		return sb_errf(e, SB_EIO, "%s: no /observables/flux group (run with flux = yes)", path);
	}
	sb_err re = {0};
	if (h5r_read(f, RUNFILE_FLUX_TIME, &d->t, &r, dt, &re) ||
	    h5r_read(f, RUNFILE_FLUX_FREQ, &d->f, &r, df, &re) ||
	    h5r_read(f, RUNFILE_FLUX_PHI, &d->phi, &r, dp, &re) ||
	    h5r_read(f, RUNFILE_FLUX_HEIGHTS, &d->h, &r, dh, &re)) {
		h5r_close(f);
		flux_free(d);
		return sb_errf(e, re.code, "%.500s: %.500s", path, re.msg);
	}
	d->P = dt[0];
	d->L = dh[0];
	if (df[0] != d->P || (d->P && (dp[0] != d->P || dp[1] != d->L))) {
		h5r_close(f);
		flux_free(d);
		return sb_errf(e, SB_EIO, "%s: /observables/flux datasets have inconsistent sizes", path);
	}
	/* a NaN or Inf would become a mean and an interval printed as numbers; the engine
	 * writes none (docs/scene.md, "Exit codes"), so a file that has one is refused
	 * (docs/inputs.md, "Run files") */
	const struct {
		const char *name;
		const double *v;
		size_t n;
	} series[] = {{"phi/time", d->t, d->P}, {"frequency/value", d->f, d->P}, {"phi/value", d->phi, d->P * d->L},
		      {"heights", d->h, d->L}};
	for (size_t k = 0; k < sizeof series / sizeof *series; k++)
		for (size_t i = 0; i < series[k].n; i++)
			if (!isfinite(series[k].v[i])) {
				h5r_close(f);
				sb_errf(e, SB_ENAN, "%s: /observables/flux/%s[%zu] = %g: not a finite number", path,
					series[k].name, i, series[k].v[i]);
				flux_free(d);
				return e->code;
			}
	d->surface = NAN;
	double own = NAN;
	const int has_own = h5r_attr_num(f, RUNFILE_FLUX, "surface_height", &own) == 0;
	if (has_own)
		d->surface = own;
	else
		h5r_attr_num(f, "/", "surface_height", &d->surface);
	if (!isfinite(d->surface) && d->L)
		d->surface = d->h[d->L - 1] * d->L / (d->L - 0.5); /* lines sit at slice midpoints */
	h5r_close(f);
	if (flux_ranges(d, has_own ? own : NAN, path, e)) {
		flux_free(d);
		return e->code;
	}
	return 0;
}

void flux_free(flux_data *d)
{
	free(d->t);
	free(d->f);
	free(d->phi);
	free(d->h);
	memset(d, 0, sizeof *d);
}

void flux_band(const flux_data *d, const flux_opts *o, size_t *l0, size_t *l1)
{
	double lo = o->band_lo * d->surface, hi = o->band_hi * d->surface;
	size_t a = d->L, b = 0;
	for (size_t l = 0; l < d->L; l++)
		if (d->h[l] >= lo && d->h[l] <= hi) {
			if (a == d->L)
				a = l;
			b = l + 1;
		}
	if (a == d->L) { /* band thinner than the line spacing: the line nearest its middle */
		double mid = 0.5 * (lo + hi), best = INFINITY;
		a = 0;
		for (size_t l = 0; l < d->L; l++)
			if (fabs(d->h[l] - mid) < best) {
				best = fabs(d->h[l] - mid);
				a = l;
			}
		b = d->L ? a + 1 : 0;
	}
	*l0 = a;
	*l1 = b;
}

double flux_plane(const flux_data *d, size_t p, size_t l0, size_t l1)
{
	if (l1 <= l0)
		return NAN;
	double s = 0;
	for (size_t l = l0; l < l1; l++)
		s += d->phi[p * d->L + l];
	return s / (double)(l1 - l0);
}

size_t flux_first(const flux_data *d, const flux_opts *o)
{
	/* the transient is the start of the shaking, a fraction of the run as planned:
	 * a run that failed early does not have a shorter transient */
	if (d->planned > d->P)
		return (size_t)floor(o->skip * (double)d->planned);
	size_t k = (size_t)floor(o->skip * (double)d->P);
	return d->P && k >= d->P ? d->P - 1 : k;
}

double flux_summary(const flux_data *d, const flux_opts *o)
{
	size_t l0, l1;
	flux_band(d, o, &l0, &l1);
	size_t p0 = flux_first(d, o);
	if (p0 >= d->P || l1 <= l0)
		return NAN;
	double s = 0;
	for (size_t p = p0; p < d->P; p++)
		s += flux_plane(d, p, l0, l1);
	return s / (double)(d->P - p0);
}

void flux_profile(const flux_data *d, const flux_opts *o, double *prof)
{
	size_t p0 = flux_first(d, o);
	for (size_t l = 0; l < d->L; l++) {
		double s = 0;
		for (size_t p = p0; p < d->P; p++)
			s += d->phi[p * d->L + l];
		prof[l] = d->P > p0 ? s / (double)(d->P - p0) : NAN;
	}
}

double flux_of_run(const char *dir, const char *id, const flux_opts *o, int *damaged)
{
	char path[4600];
	layout_file(dir, 0, id, LAY_OUTPUT, path, sizeof path);
	flux_data d;
	sb_err e = {0};
	*damaged = 0;
	if (flux_read(path, &d, &e)) {
		h5sum sum;
		sb_err se = {0};
		*damaged = h5sum_read(path, id, &sum, &se) != 0;
		return NAN;
	}
	double v = flux_summary(&d, o);
	flux_free(&d);
	return v;
}
