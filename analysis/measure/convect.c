/* convect.c - the roll strength of a run's displacement field (convect.h). */
#include "convect.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "h5read.h"
#include "runfile.h"

void convect_strength(const double *ux, const double *uy, const double *n, size_t ny, size_t nx, double cell,
		      double ylo, double yhi, convect_block *out)
{
	double w = 0, sy = 0, su = 0;
	size_t cells = 0;
	for (size_t r = 0; r < ny; r++) {
		const double yc = ((double)r + 0.5) * cell;
		if (yc < ylo || yc > yhi)
			continue;
		for (size_t c = 0; c < nx; c++) {
			const size_t q = r * nx + c;
			/* a cell no disk passed has ux = uy = 0 in the file: it is no sample of 0 */
			if (!(n[q] > 0) || !isfinite(ux[q]) || !isfinite(uy[q]))
				continue;
			w += n[q];
			sy += n[q] * uy[q] * uy[q];
			su += n[q] * (ux[q] * ux[q] + uy[q] * uy[q]);
			cells++;
		}
	}
	out->w = w;
	out->cells = cells;
	out->S = w > 0 ? sqrt(sy / w) : NAN;
	out->Su = w > 0 ? sqrt(su / w) : NAN;
}

double convect_cov(const double *uya, const double *na, const double *uyb, const double *nb, size_t ny, size_t nx,
		   double cell, double ylo, double yhi)
{
	double w = 0, s = 0;
	for (size_t r = 0; r < ny; r++) {
		const double yc = ((double)r + 0.5) * cell;
		if (yc < ylo || yc > yhi)
			continue;
		for (size_t c = 0; c < nx; c++) {
			const size_t q = r * nx + c;
			if (!(na[q] > 0) || !(nb[q] > 0) || !isfinite(uya[q]) || !isfinite(uyb[q]))
				continue;
			const double wq = fmin(na[q], nb[q]);
			w += wq;
			s += wq * uya[q] * uyb[q];
		}
	}
	return w > 0 ? s / w : NAN;
}

int convect_summary(const convect_field *f, const convect_cfg *c, size_t planned, convect_run *r)
{
	memset(r, 0, sizeof *r);
	r->S = r->Su = r->C = NAN;
	r->blocks = f->B;
	const double ylo = c->band_lo * f->surface, yhi = c->band_hi * f->surface;
	for (size_t q = 0; q < f->ny; q++) {
		const double yc = ((double)q + 0.5) * f->cell;
		r->rows += yc >= ylo && yc <= yhi;
	}
	/* the transient is a fraction of the run as planned (as flux_first): a run that
	 * failed early does not have a shorter one */
	const size_t B = planned > f->B ? planned : f->B;
	r->first = (size_t)floor(c->skip * (double)B);
	if (planned <= f->B && f->B && r->first >= f->B)
		r->first = f->B - 1;
	double s = 0, su = 0;
	const size_t cells = f->ny * f->nx;
	for (size_t b = r->first; b < f->B; b++) {
		convect_block k;
		convect_strength(f->ux + b * cells, f->uy + b * cells, f->n + b * cells, f->ny, f->nx, f->cell, ylo, yhi,
				 &k);
		if (isnan(k.S)) {
			r->empty++;
			continue;
		}
		s += k.S;
		su += k.Su;
		r->used++;
	}
	double cs = 0;
	for (size_t b = r->first; b + 1 < f->B; b++) {
		const double v = convect_cov(f->uy + b * cells, f->n + b * cells, f->uy + (b + 1) * cells,
					     f->n + (b + 1) * cells, f->ny, f->nx, f->cell, ylo, yhi);
		if (isfinite(v)) {
			cs += v;
			r->pairs++;
		}
	}
	if (r->pairs)
		r->C = cs / (double)r->pairs;
	if (!r->used)
		return 1;
	r->S = s / (double)r->used;
	r->Su = su / (double)r->used;
	return 0;
}

void convect_free(convect_field *f)
{
	free(f->t);
	free(f->ux);
	free(f->uy);
	free(f->n);
	memset(f, 0, sizeof *f);
}

int convect_read(const char *path, convect_field *f, sb_err *e)
{
	memset(f, 0, sizeof *f);
	hid_t h;
	if (h5r_open(path, &h, e))
		return e->code;
	if (!h5r_exists(h, RUNFILE_FIELD)) {
		h5r_close(h);
		return sb_errf(e, SB_EUSAGE, "%s: no /observables/field (the run had field = no)", path);
	}
	size_t d1[3] = {0}, d2[3] = {0}, d3[3] = {0}, dt[3] = {0};
	int r1 = 0, r2 = 0, r3 = 0, rt = 0;
	sb_err re = {0};
	if (h5r_read(h, RUNFILE_FIELD_UX, &f->ux, &r1, d1, &re) ||
	    h5r_read(h, RUNFILE_FIELD_UY, &f->uy, &r2, d2, &re) ||
	    h5r_read(h, RUNFILE_FIELD_COUNT, &f->n, &r3, d3, &re) ||
	    h5r_read(h, RUNFILE_FIELD_TIME, &f->t, &rt, dt, &re)) {
		h5r_close(h);
		convect_free(f);
		return sb_errf(e, re.code ? re.code : SB_EIO, "%.500s: %.500s", path, re.msg);
	}
	double cell = NAN, x0 = 0, K = NAN, hs = NAN;
	h5r_attr_num(h, RUNFILE_FIELD, "cell", &cell);
	h5r_attr_num(h, RUNFILE_FIELD, "x0", &x0);
	h5r_attr_num(h, RUNFILE_FIELD, "periods_per_block", &K);
	h5r_attr_num(h, "/", "surface_height", &hs);
	h5r_close(h);
	if (r1 != 3 || r2 != 3 || r3 != 3 || memcmp(d1, d2, sizeof d1) || memcmp(d1, d3, sizeof d1) || dt[0] != d1[0]) {
		convect_free(f);
		return sb_errf(e, SB_EIO, "%s: /observables/field datasets have inconsistent shapes", path);
	}
	/* a count or displacement that is no number, or a negative count: the engine writes
	 * none (an empty cell is 0), so the file is unusable, not a cell to skip */
	const size_t nv = d1[0] * d1[1] * d1[2];
	for (size_t q = 0; q < nv; q++)
		if (!isfinite(f->ux[q]) || !isfinite(f->uy[q]) || !isfinite(f->n[q]) || f->n[q] < 0) {
			sb_errf(e, SB_ENAN, "%s: /observables/field value %zu (ux %g, uy %g, count %g): not a finite number%s",
				path, q, f->ux[q], f->uy[q], f->n[q], f->n[q] < 0 ? " (or a negative count)" : "");
			convect_free(f);
			return e->code;
		}
	for (size_t b = 0; b < d1[0]; b++)
		if (!isfinite(f->t[b])) {
			sb_errf(e, SB_ENAN, "%s: /observables/field/ux/time[%zu] = %g: not a finite number", path, b, f->t[b]);
			convect_free(f);
			return e->code;
		}
	if (!(cell > 0) || !(hs > 0)) {
		convect_free(f);
		return sb_errf(e, SB_EIO, "%s: no field cell size or settled surface height", path);
	}
	f->B = d1[0];
	f->ny = d1[1];
	f->nx = d1[2];
	f->cell = cell;
	f->x0 = x0;
	f->K = isfinite(K) ? (long)K : 0;
	f->surface = hs;
	return 0;
}
