/* observe.c - flux, displacement field, ring force and waiting time. */
#include "observe.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "crossing.h"
#include "periodic.h"

static double *zalloc(size_t n, int *bad)
{
	double *p = calloc(n ? n : 1, sizeof(double));
	if (!p)
		*bad = 1;
	return p;
}

int obs_init(sb_obs *o, const sb_scene *sc, const sb_state *st, int intruder, double surface,
	     double x0, double x1, sb_err *e)
{
	memset(o, 0, sizeof *o);
	o->flux_on = sc->flux;
	o->field_on = sc->field;
	o->ring_on = sc->ring;
	o->x0 = x0;
	o->x1 = x1;
	o->surface = surface;
	o->period = sc->sides == SIDES_PERIODIC ? x1 - x0 : 0;
	o->nm = st->nm;
	o->wait_time = NAN;
	o->rise_height = intruder >= 0 ? 2 * st->r[intruder] : NAN;
	int bad = 0;
	for (int i = 0; i < st->nm; i++)
		o->nint += st->kind[i] == KIND_INTRUDER;
	if (o->nint > 1) {
		o->iidx = calloc((size_t)o->nint, sizeof *o->iidx);
		o->irisen = calloc((size_t)o->nint, sizeof *o->irisen);
		o->iy0 = zalloc((size_t)o->nint, &bad);
		o->irise_h = zalloc((size_t)o->nint, &bad);
		o->iwait = zalloc((size_t)o->nint, &bad);
		bad |= !o->iidx || !o->irisen;
		for (int i = 0, k = 0; i < st->nm && !bad; i++)
			if (st->kind[i] == KIND_INTRUDER) { /* the rise as the first's: one diameter */
				o->iidx[k] = i;
				o->iy0[k] = st->q[C_Y][0][i];
				o->irise_h[k] = 2 * st->r[i];
				o->iwait[k++] = NAN;
			}
	}
	if (o->flux_on || o->field_on) {
		o->xp = zalloc((size_t)st->nm, &bad);
		o->yp = zalloc((size_t)st->nm, &bad);
	}
	if (o->flux_on) {
		/* nlines lines at the midpoints of nlines equal slices of [0, surface] */
		o->nlines = (int)sc->flux_lines;
		o->hline = zalloc((size_t)o->nlines, &bad);
		o->jtop = zalloc((size_t)o->nlines, &bad);
		o->jbot = zalloc((size_t)o->nlines, &bad);
		if (o->period > 0)
			o->xmid = zalloc((size_t)st->nm, &bad);
		if (!bad)
			crossing_lines(surface, o->nlines, o->hline);
		/* the stop rule's band: the lines within it (the nearest one when none is),
		 * as the analysis tools choose their plane */
		const double lo = sc->stop_flux_lo * surface, hi = sc->stop_flux_hi * surface;
		o->band_l0 = o->nlines;
		o->band_l1 = 0;
		for (int l = 0; l < o->nlines && !bad; l++)
			if (o->hline[l] >= lo && o->hline[l] <= hi) {
				o->band_l0 = l < o->band_l0 ? l : o->band_l0;
				o->band_l1 = l + 1;
			}
		if (o->band_l1 <= o->band_l0 && !bad) {
			int k = (int)floor(0.5 * (sc->stop_flux_lo + sc->stop_flux_hi) * o->nlines);
			o->band_l0 = k < 0 ? 0 : k >= o->nlines ? o->nlines - 1 : k;
			o->band_l1 = o->band_l0 + 1;
		}
	}
	if (o->field_on) {
		double rs = 0;
		int ng = 0;
		for (int i = 0; i < st->nm; i++)
			if (st->kind[i] == KIND_GRAIN) {
				rs += st->r[i];
				ng++;
			}
		o->cell = 2 * (ng ? rs / ng : 1); /* one mean diameter */
		o->nx = (int)ceil((x1 - x0) / o->cell);
		o->ny = (int)ceil(1.25 * surface / o->cell); /* room for the surface to breathe */
		if (o->nx < 1)
			o->nx = 1;
		if (o->ny < 1)
			o->ny = 1;
		o->K = (int)sc->field_periods;
		size_t nc = (size_t)o->nx * (size_t)o->ny;
		o->sx = zalloc(nc, &bad);
		o->sy = zalloc(nc, &bad);
		o->cnt = zalloc(nc, &bad);
	}
	if (o->ring_on) {
		/* the centre (docs/model.md, "Ring force"): the intruder's, sample by sample;
		 * or fixed in the box, where the intruder settled (this is t = 0: the state is
		 * the settled one; a restart takes the centre from the checkpoint) or at
		 * (ring_x, ring_y) */
		const int mode = sc->ring_centre == RING_AUTO ? (sc->ring_y >= 0 ? RING_FIXED : RING_INTRUDER)
							       : sc->ring_centre;
		o->rin = sc->ring_inner;
		o->rout = sc->ring_outer;
		o->ring_every = (int)sc->ring_every;
		o->ring_interval = 1.0 / sc->ring_rate;
		o->ring_dt = sc->dt;
		o->ring_from = sc->ring_from;
		o->ring_until = sc->ring_until;
		o->gravity = sc->gravity;
		o->ring_x = sc->ring_x >= 0 ? sc->ring_x : 0.5 * (x0 + x1);
		o->ring_y = sc->ring_y;
		o->ring_follow = mode == RING_INTRUDER;
		if (mode == RING_SETTLED && intruder >= 0) {
			o->ring_x = st->q[C_X][0][intruder];
			o->ring_y = st->q[C_Y][0][intruder];
		}
		if (o->ring_follow ? intruder < 0 : o->ring_y < 0)
			return sb_errf(e, SB_EUSAGE, "ring: %s", o->ring_follow ? "ring_centre = intruder, but there is no intruder"
									  : "without an intruder the ring needs a centre (ring_y >= 0)");
		o->ring_before_end = NAN;
		o->fabs_sum = zalloc((size_t)st->n, &bad);
	}
	if (bad)
		return sb_errf(e, SB_ENOMEM, "out of memory for the observables");
	return 0;
}

void obs_free(sb_obs *o)
{
	free(o->xp);
	free(o->yp);
	free(o->hline);
	free(o->jtop);
	free(o->jbot);
	free(o->xmid);
	free(o->sx);
	free(o->sy);
	free(o->cnt);
	free(o->fabs_sum);
	free(o->iidx);
	free(o->irisen);
	free(o->iy0);
	free(o->irise_h);
	free(o->iwait);
	memset(o, 0, sizeof *o);
}

int obs_flux_len(const sb_obs *o) { return 2 + 2 * o->nlines; }
int obs_field_len(const sb_obs *o) { return 2 + 3 * o->nx * o->ny; }

/* Crossings between the previous and this sample (core/model/crossing.h). With periodic
 * sides a disk's x midpoint is taken through the minimum image and wrapped into the
 * period (a disk that crossed the seam is near it, not at the box centre); given as
 * both samples' x, crossing_count's midpoint is that number exactly. */
static void flux_count(sb_obs *o, const double *x, const double *y)
{
	const double *xa = o->xp, *xb = x;
	if (o->period > 0) {
		for (int i = 0; i < o->nm; i++)
			o->xmid[i] = periodic_mid(o->xp[i], x[i], o->period);
		xa = xb = o->xmid;
	}
	crossing_count(o->nm, xa, o->yp, xb, y, o->x0, o->x1, o->surface, o->nlines, o->hline, o->jtop, o->jbot);
}

/* With periodic sides the displacement is the minimum image and the midpoint is
 * wrapped into the period (periodic.h); with walls both are the plain ones. */
static void field_add(sb_obs *o, const double *x, const double *y)
{
	for (int i = 0; i < o->nm; i++) {
		const double ux = periodic_image(x[i] - o->xp[i], o->period);
		double mx = periodic_mid(o->xp[i], x[i], o->period) - o->x0, my = 0.5 * (o->yp[i] + y[i]);
		int cx = (int)floor(mx / o->cell), cy = (int)floor(my / o->cell);
		if (cx < 0 || cx >= o->nx || cy < 0 || cy >= o->ny)
			continue;
		size_t c = (size_t)cy * o->nx + cx;
		o->sx[c] += ux;
		o->sy[c] += y[i] - o->yp[i];
		o->cnt[c] += 1;
	}
}

void obs_band_add(sb_obs *o)
{
	o->band_n += 1;
	o->band_sum += o->band_last;
	o->band_sum2 += o->band_last * o->band_last;
	o->have_band = 0;
}

double obs_band_se(const sb_obs *o, double min_n)
{
	if (o->band_n < min_n)
		return INFINITY;
	const double n = o->band_n, mean = o->band_sum / n;
	const double var = (o->band_sum2 - n * mean * mean) / (n - 1);
	return sqrt(var > 0 ? var / n : 0);
}

int obs_band_answered(const sb_obs *o, double min_n, double se, double thr, double k)
{
	const double e = obs_band_se(o, min_n);
	if (!isfinite(e))
		return 0;
	if (!(thr > 0))
		return e < se;
	const double mean = o->band_sum / o->band_n, lo = mean - k * e, hi = mean + k * e;
	const int on = lo >= thr || hi <= -thr; /* the class test is |Phi| >= thr */
	const int off = lo > -thr && hi < thr;
	return on || off;
}

int obs_flux_due(const sb_obs *o) { return o->flux_on && o->have_prev; }

void obs_flux(sb_obs *o, const sb_state *st, double t, double f, double *rec)
{
	const double *x = st->q[C_X][0], *y = st->q[C_Y][0];
	flux_count(o, x, y);
	const int n = o->nlines;
	rec[0] = t;
	rec[1] = f;
	/* the band's flux of this period: Phi = j_top - j_bot, averaged over its lines */
	double band = 0;
	for (int l = o->band_l0; l < o->band_l1; l++)
		band += o->jtop[l] - o->jbot[l];
	o->band_last = o->band_l1 > o->band_l0 ? band / (o->band_l1 - o->band_l0) : 0;
	o->have_band = 1;
	memcpy(rec + 2, o->jtop, sizeof(double) * (size_t)n);
	memcpy(rec + 2 + n, o->jbot, sizeof(double) * (size_t)n);
	memset(o->jtop, 0, sizeof(double) * (size_t)n);
	memset(o->jbot, 0, sizeof(double) * (size_t)n);
}

int obs_field_add(sb_obs *o, const sb_state *st)
{
	if (!o->field_on || !o->have_prev)
		return 0;
	field_add(o, st->q[C_X][0], st->q[C_Y][0]);
	return ++o->kdone >= o->K;
}

void obs_field_take(sb_obs *o, double t, double *rec)
{
	size_t nc = (size_t)o->nx * o->ny;
	rec[0] = t;
	rec[1] = o->K;
	memcpy(rec + 2, o->sx, sizeof(double) * nc);
	memcpy(rec + 2 + nc, o->sy, sizeof(double) * nc);
	memcpy(rec + 2 + 2 * nc, o->cnt, sizeof(double) * nc);
	o->kdone = 0;
	memset(o->sx, 0, sizeof(double) * nc);
	memset(o->sy, 0, sizeof(double) * nc);
	memset(o->cnt, 0, sizeof(double) * nc);
}

void obs_strobe_keep(sb_obs *o, const sb_state *st)
{
	if (!o->flux_on && !o->field_on)
		return;
	memcpy(o->xp, st->q[C_X][0], sizeof(double) * (size_t)o->nm);
	memcpy(o->yp, st->q[C_Y][0], sizeof(double) * (size_t)o->nm);
	o->have_prev = 1;
}

/* First step at or after time k * interval (run.c's schedule). */
static long ring_step(const sb_obs *o, long k)
{
	return (long)ceil(k * o->ring_interval / o->ring_dt - 1e-6);
}

int obs_ring_due(const sb_obs *o, long n)
{
	if (!o->ring_on)
		return 0;
	return o->ring_every > 0 ? n % o->ring_every == 0 : n >= ring_step(o, o->ring_samples + 1);
}

void obs_ring_sample(sb_obs *o, const sb_state *st, int intruder, double t, double inv_dt, double *row)
{
	const double cx = o->ring_follow ? st->q[C_X][0][intruder] : o->ring_x;
	const double cy = o->ring_follow ? st->q[C_Y][0][intruder] : o->ring_y;
	const double r2in = o->rin * o->rin, r2out = o->rout * o->rout;
	double sf[2] = {0, 0}, nf[2] = {0, 0}, n[2] = {0, 0}, vx[2] = {0, 0}, vy[2] = {0, 0}, v2[2] = {0, 0};
	for (int i = 0; i < st->nm; i++) {
		if (st->kind[i] != KIND_GRAIN)
			continue;
		/* the minimum image with periodic sides: the ring reaches across the seam */
		double dx = periodic_image(st->q[C_X][0][i] - cx, o->period), dy = st->q[C_Y][0][i] - cy,
		       d2 = dx * dx + dy * dy;
		if (d2 < r2in || d2 > r2out)
			continue;
		double ux = st->q[C_X][1][i] * inv_dt, uy = st->q[C_Y][1][i] * inv_dt;
		/* the net force in the lab frame: the contact forces and the weight (the box's
		 * acceleration is not a force on the grain, it is the frame's) */
		double fx = st->f[C_X][i], fy = st->f[C_Y][i] - st->m[i] * o->gravity;
		double net = sqrt(fx * fx + fy * fy);
		for (int h = 0; h < 2; h++) { /* h = 0: whole ring, 1: lower half */
			if (h == 1 && dy >= 0)
				break;
			sf[h] += o->fabs_sum[i];
			nf[h] += net;
			n[h] += 1;
			vx[h] += ux;
			vy[h] += uy;
			v2[h] += ux * ux + uy * uy;
		}
	}
	/* per sample: means over the ring's grains (0 when it holds none) */
	double mean[2] = {0, 0}, mnet[2] = {0, 0}, temp[2] = {0, 0};
	for (int h = 0; h < 2; h++) {
		if (n[h] > 0) {
			/* granular temperature: half the mean squared velocity fluctuation
			 * about the ring's mean velocity (2D, per degree of freedom) */
			double mx = vx[h] / n[h], my = vy[h] / n[h];
			mean[h] = sf[h] / n[h];
			mnet[h] = nf[h] / n[h];
			temp[h] = 0.5 * (v2[h] / n[h] - mx * mx - my * my);
		}
		o->acc[OBS_RA_MEAN + h] += mean[h];
		o->acc[OBS_RA_NET + h] += mnet[h];
		o->acc[OBS_RA_T + h] += temp[h];
		o->acc[OBS_RA_SUM + h] += sf[h];
		o->acc[OBS_RA_N + h] += n[h];
	}
	o->ring_samples++;
	/* the window before the rise: from ring_from, up to ring_until, while the intruder
	 * has not risen (the rise is seen at the start of a step, before its sample) */
	if (!o->risen && t >= o->ring_from && (o->ring_until <= 0 || t < o->ring_until)) {
		o->before[OBS_RB_MEAN] += mean[0];
		o->before[OBS_RB_NET] += mnet[0];
		o->before[OBS_RB_T] += temp[0];
		o->before[OBS_RB_N] += n[0];
		o->before[OBS_RB_SUM] += sf[0];
		o->ring_before++;
		o->ring_before_end = t;
	}
	row[OBS_RR_TIME] = t;
	row[OBS_RR_MEAN] = mean[0];
	row[OBS_RR_NET] = mnet[0];
	row[OBS_RR_T] = temp[0];
	row[OBS_RR_N] = n[0];
	row[OBS_RR_CX] = cx;
	row[OBS_RR_CY] = cy;
	memset(o->fabs_sum, 0, sizeof(double) * (size_t)st->n);
}

void obs_fields(sb_obs *o, void *ctx, void (*io)(void *, void *, size_t))
{
	io(ctx, &o->have_prev, sizeof o->have_prev);
	io(ctx, &o->risen, sizeof o->risen);
	io(ctx, &o->wait_time, sizeof o->wait_time);
	if (o->nint > 1) { /* the other intruders: their settled heights are t = 0's, not a restart's */
		io(ctx, o->iy0, sizeof *o->iy0 * (size_t)o->nint);
		io(ctx, o->irisen, sizeof *o->irisen * (size_t)o->nint);
		io(ctx, o->iwait, sizeof *o->iwait * (size_t)o->nint);
	}
	io(ctx, &o->ov_max, sizeof o->ov_max);
	io(ctx, &o->ov_t, sizeof o->ov_t);
	io(ctx, &o->ov_x, sizeof o->ov_x);
	io(ctx, &o->ov_y, sizeof o->ov_y);
	io(ctx, &o->ov_i, sizeof o->ov_i);
	io(ctx, &o->ov_j, sizeof o->ov_j);
	io(ctx, &o->band_n, sizeof o->band_n);
	io(ctx, &o->band_sum, sizeof o->band_sum);
	io(ctx, &o->band_sum2, sizeof o->band_sum2);
	io(ctx, &o->stop_step, sizeof o->stop_step);
	io(ctx, &o->stop_rule, sizeof o->stop_rule);
	if (o->flux_on || o->field_on) {
		io(ctx, o->xp, sizeof(double) * (size_t)o->nm);
		io(ctx, o->yp, sizeof(double) * (size_t)o->nm);
	}
	if (o->flux_on) {
		io(ctx, o->jtop, sizeof(double) * (size_t)o->nlines);
		io(ctx, o->jbot, sizeof(double) * (size_t)o->nlines);
	}
	if (o->field_on) {
		size_t nc = (size_t)o->nx * o->ny;
		io(ctx, &o->kdone, sizeof o->kdone);
		io(ctx, o->sx, sizeof(double) * nc);
		io(ctx, o->sy, sizeof(double) * nc);
		io(ctx, o->cnt, sizeof(double) * nc);
	}
	if (o->ring_on) {
		io(ctx, o->acc, sizeof o->acc);
		io(ctx, &o->ring_samples, sizeof o->ring_samples);
		io(ctx, o->before, sizeof o->before);
		io(ctx, &o->ring_before, sizeof o->ring_before);
		io(ctx, &o->ring_before_end, sizeof o->ring_before_end);
		io(ctx, &o->ring_x, sizeof o->ring_x); /* a settled centre is the t = 0 state's */
		io(ctx, &o->ring_y, sizeof o->ring_y);
	}
}

int obs_intruder_risen(const sb_obs *o, int k, double *wait)
{
	const int risen = k == 0 ? o->risen : o->irisen[k];
	*wait = !risen ? NAN : k == 0 ? o->wait_time : o->iwait[k];
	return risen;
}

int obs_segregation_split(const double *r, const unsigned char *kind, int n, double *split)
{
	double lo = INFINITY, hi = -INFINITY;
	for (int i = 0; i < n; i++)
		if (kind[i] == KIND_GRAIN) {
			lo = fmin(lo, r[i]);
			hi = fmax(hi, r[i]);
		}
	*split = 0.5 * (lo + hi);
	return lo < hi;
}

static int cmp_double(const void *a, const void *b)
{
	const double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

double obs_segregation(const double *y, const double *r, const unsigned char *kind, int n, double split, double *work)
{
	int nl = 0, ng = 0;
	double y0 = INFINITY;
	for (int i = 0; i < n; i++)
		if (kind[i] == KIND_GRAIN) {
			y0 = fmin(y0, y[i]);
			nl += r[i] > split;
			ng++;
		}
	const int ns = ng - nl;
	if (nl == 0 || ns == 0)
		return 0;
	/* heights above the lowest grain: the sums below stay small beside a bed far above
	 * its floor, and S does not depend on the origin */
	double sl = 0, ss = 0;
	for (int i = 0, k = 0; i < n; i++)
		if (kind[i] == KIND_GRAIN) {
			work[k++] = y[i] - y0;
			if (r[i] > split)
				sl += y[i] - y0;
			else
				ss += y[i] - y0;
		}
	/* the same heights sorted: the large grains all on top hold the highest nl, all
	 * at the bottom the lowest nl */
	qsort(work, (size_t)ng, sizeof *work, cmp_double);
	double low = 0, above_low = 0, high = 0, below_high = 0;
	for (int k = 0; k < ng; k++) {
		if (k < nl)
			low += work[k];
		else
			above_low += work[k];
		if (k >= ns)
			high += work[k];
		else
			below_high += work[k];
	}
	const double d = sl / nl - ss / ns;
	const double dmax = high / nl - below_high / ns, dmin = low / nl - above_low / ns;
	/* a sum in another order can put S a rounding beyond +-1 */
	if (d >= 0)
		return dmax > 0 ? fmin(1, d / dmax) : 0;
	return dmin < 0 ? fmax(-1, d / -dmin) : 0;
}
