/* dumpflux.c - Phi(D) of a dumped run by the engine's crossing code (dumpflux.h). */
#include "dumpflux.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "crossing.h"
#include "drive.h"
#include "dump.h"

long dumpflux_due_step(long k, double frequency, double dt)
{
	/* as core/run/run.c's due_step(k, 1.0 / frequency, dt) */
	const double interval = 1.0 / frequency;
	return (long)ceil(k * interval / dt - 1e-6);
}

/* Appends one period to d (capacity *cap periods). */
static int add_period(flux_data *d, size_t *cap, double t, double f, const double *jtop, const double *jbot,
		      sb_err *e)
{
	if (d->P == *cap) {
		size_t nc = *cap ? 2 * *cap : 64;
		double *nt = realloc(d->t, sizeof *nt * nc);
		if (nt)
			d->t = nt;
		double *nf = realloc(d->f, sizeof *nf * nc);
		if (nf)
			d->f = nf;
		double *np = realloc(d->phi, sizeof *np * nc * (d->L ? d->L : 1));
		if (np)
			d->phi = np;
		if (!nt || !nf || !np)
			return sb_errf(e, SB_ENOMEM, "out of memory for %zu periods of flux", nc);
		*cap = nc;
	}
	d->t[d->P] = t;
	d->f[d->P] = f;
	for (size_t l = 0; l < d->L; l++)
		d->phi[d->P * d->L + l] = jtop[l] - jbot[l];
	d->P++;
	return 0;
}

int dumpflux_read(const char *path, const dumpflux_opts *o, flux_data *d, dumpflux_info *info, sb_err *e)
{
	memset(d, 0, sizeof *d);
	memset(info, 0, sizeof *info);
	if (!(o->surface > 0) || o->nlines < 1 || !(o->frequency > 0) || !(o->dt > 0) || !isfinite(o->amplitude))
		return sb_errf(e, SB_EUSAGE, "dumpflux: needs surface > 0, nlines >= 1, frequency > 0, dt > 0 and an amplitude");
	const sb_drive drive = {.ramp = RAMP_NONE, .A = o->amplitude, .f = o->frequency};
	dump_reader rd;
	if (dump_open(&rd, path, e))
		return e->code;
	dump_frame fr = {0}, ref = {0};
	d->L = (size_t)o->nlines;
	d->surface = o->surface;
	d->h = malloc(sizeof *d->h * d->L);
	double *jtop = calloc(d->L, sizeof *jtop), *jbot = calloc(d->L, sizeof *jbot);
	double *xp = NULL, *yp = NULL, *x = NULL, *y = NULL, *wrest = NULL;
	size_t cap = 0;
	int rc = 0;
	if (!d->h || !jtop || !jbot) {
		rc = sb_errf(e, SB_ENOMEM, "out of memory");
		goto out;
	}
	crossing_lines(o->surface, o->nlines, d->h);
	double yb0 = 0;
	for (long k = 0;; k++) {
		int got = dump_next(&rd, &fr, e);
		if (got < 0) {
			rc = e->code;
			goto out;
		}
		if (!got)
			break;
		const long due = dumpflux_due_step(k, o->frequency, o->dt);
		if (fr.step != due) {
			rc = sb_errf(e, SB_EIO,
				     "%s: frame %ld is at step %ld, but sample %ld of f = %g Hz, dt = %g s is due at step %ld "
				     "(a frame missing, or not a phase-0 dump)",
				     path, k, fr.step, k, o->frequency, o->dt, due);
			goto out;
		}
		if (k == 0) { /* the atoms of every frame: frame 0's, in its order */
			ref = (dump_frame){0};
			ref.n = fr.n;
			ref.id = malloc(sizeof *ref.id * (size_t)(fr.n ? fr.n : 1));
			ref.type = malloc(sizeof *ref.type * (size_t)(fr.n ? fr.n : 1));
			if (!ref.id || !ref.type) {
				rc = sb_errf(e, SB_ENOMEM, "out of memory");
				goto out;
			}
			memcpy(ref.id, fr.id, sizeof *ref.id * (size_t)fr.n);
			memcpy(ref.type, fr.type, sizeof *ref.type * (size_t)fr.n);
			for (long i = 0; i < fr.n; i++) {
				if (fr.type[i] < 1 || fr.type[i] > 3) {
					rc = sb_errf(e, SB_EIO, "%s: atom %ld has type %d (1 grain, 2 intruder, 3 wall)", path,
						     fr.id[i], fr.type[i]);
					goto out;
				}
				if (fr.type[i] == 3)
					info->walls++;
				else
					info->mobile++;
			}
			if (!fr.has_r && info->walls) {
				rc = sb_errf(e, SB_EIO, "%s: no radius column: the wall faces need the wall disks' radii", path);
				goto out;
			}
			/* inner wall faces as core/run/sim.c takes them */
			double x0 = INFINITY, x1 = -INFINITY;
			for (long i = 0; i < fr.n; i++)
				if (fr.type[i] == 3) {
					x0 = fmin(x0, fr.x[i] + fr.r[i]);
					x1 = fmax(x1, fr.x[i] - fr.r[i]);
				}
			if (!(x0 < x1)) {
				rc = sb_errf(e, SB_EIO, "%s: no side walls (type 3 disks) to take the box width from", path);
				goto out;
			}
			info->x0 = x0;
			info->x1 = x1;
			size_t nm = (size_t)(info->mobile ? info->mobile : 1), nw = (size_t)(info->walls ? info->walls : 1);
			xp = malloc(sizeof *xp * nm);
			yp = malloc(sizeof *yp * nm);
			x = malloc(sizeof *x * nm);
			y = malloc(sizeof *y * nm);
			wrest = malloc(sizeof *wrest * nw);
			if (!xp || !yp || !x || !y || !wrest) {
				rc = sb_errf(e, SB_ENOMEM, "out of memory");
				goto out;
			}
		} else {
			int same = fr.n == ref.n;
			for (long i = 0; i < fr.n && same; i++)
				same = fr.id[i] == ref.id[i] && fr.type[i] == ref.type[i];
			if (!same) {
				rc = sb_errf(e, SB_EIO, "%s: the frame of step %ld has other atoms than the first frame", path,
					     fr.step);
				goto out;
			}
		}
		/* box frame: y - y_box(t), t = step * dt as the engine's time */
		const double t = fr.step * o->dt;
		const double yb = drive_y(&drive, t);
		if (k == 0)
			yb0 = yb;
		info->ybox_max = fmax(info->ybox_max, fabs(yb));
		long m = 0, w = 0;
		for (long i = 0; i < fr.n; i++) {
			if (fr.type[i] == 3) {
				if (k == 0)
					wrest[w] = fr.y[i];
				const double dev = fr.y[i] - wrest[w];
				info->wall_rest_dev = fmax(info->wall_rest_dev, fabs(dev));
				info->wall_drive_dev = fmax(info->wall_drive_dev, fabs(dev - (yb - yb0)));
				w++;
				continue;
			}
			x[m] = fr.x[i];
			y[m] = fr.y[i] - yb;
			m++;
		}
		if (k > 0) {
			memset(jtop, 0, sizeof *jtop * d->L);
			memset(jbot, 0, sizeof *jbot * d->L);
			crossing_count((int)m, xp, yp, x, y, info->x0, info->x1, o->surface, o->nlines, d->h, jtop, jbot);
			if (add_period(d, &cap, t, o->frequency, jtop, jbot, e)) {
				rc = e->code;
				goto out;
			}
		}
		double *s = xp;
		xp = x;
		x = s;
		s = yp;
		yp = y;
		y = s;
		info->frames++;
	}
	if (info->frames < 2)
		rc = sb_errf(e, SB_EIO, "%s: %ld frame%s: the flux needs two samples at least", path, info->frames,
			     info->frames == 1 ? "" : "s");
out:
	dump_close(&rd);
	dump_frame_free(&fr);
	dump_frame_free(&ref);
	free(jtop);
	free(jbot);
	free(xp);
	free(yp);
	free(x);
	free(y);
	free(wrest);
	if (rc)
		flux_free(d);
	return rc;
}
