/* whalerun.c - one run's whale observables read from its output file (whalerun.h). */
#include "whalerun.h"

#include <math.h>
#include <stdlib.h>

#include "h5read.h"
#include "runfile.h"
#include "traj.h"

const char *whale_status_name(int s)
{
	static const char *const n[WHALE_NSTATUS] = {"analysed", "not_risen", "no_trajectory", "too_short"};
	return s >= 0 && s < WHALE_NSTATUS ? n[s] : "?";
}

/* The root attributes of the rise, the radius and the drive frequency. */
static int read_attrs(const char *path, whale_obs *ob, sb_err *e)
{
	hid_t h;
	if (h5r_open(path, &h, e))
		return e->code;
	double rs = NAN, w = NAN, rr = NAN, rmin = NAN, rmax = NAN, f = 0;
	sb_err re = {0};
	const int bad = traj_rise(h, path, &rs, &w, &re);
	if (h5r_attr_num(h, "/", "intruder_radius", &ob->radius) || !(ob->radius > 0)) {
		h5r_attr_num(h, RUNFILE_PARAMS, "radius_ratio", &rr);
		h5r_attr_num(h, RUNFILE_PARAMS, "r_min", &rmin);
		h5r_attr_num(h, RUNFILE_PARAMS, "r_max", &rmax);
		ob->radius = rr * 0.5 * (rmin + rmax);
	}
	h5r_attr_num(h, RUNFILE_PARAMS, "frequency", &f);
	h5r_close(h);
	if (bad)
		return sb_errf(e, bad, "%s", re.msg);
	ob->risen = rs != 0;
	ob->wait = w;
	ob->drive_f = f > 0 ? f : 0;
	return 0;
}

int whale_read(const char *path, const whale_cfg *c, whale_obs *ob, sb_err *e)
{
	*ob = (whale_obs){.status = WHALE_NOT_RISEN, .wait = NAN, .radius = NAN, .dive = NAN, .t_end = NAN};
	whale_run_init(&ob->run, NAN);
	ob->spec = (whale_spec){NAN, NAN, NAN, 0, 0};
	if (read_attrs(path, ob, e))
		return e->code;
	ob->dive = isfinite(c->dive) ? c->dive : c->dive_radii * ob->radius;
	traj tr;
	const int rc = traj_read(path, &tr, e);
	if (rc > 1)
		return rc;
	if (rc == 0)
		ob->t_end = tr.t[tr.n - 1];
	if (!ob->risen)
		ob->status = WHALE_NOT_RISEN;
	else if (rc == 1)
		ob->status = WHALE_NO_TRAJ;
	else if (!(ob->dive > 0)) {
		traj_free(&tr);
		return sb_errf(e, SB_EIO, "%s: no intruder radius (intruder_radius) for the dive threshold", path);
	} else {
		const whale_opts o = {ob->dive, c->top_q, ob->drive_f};
		const double t0 = ob->wait + c->skip;
		const double need = ob->drive_f > 0 ? WHALE_MIN_PERIODS / ob->drive_f : 0;
		const int dr = whale_dives(tr.t, tr.ybox, tr.n, t0, &o, &ob->run, NULL);
		if (dr < 0) {
			traj_free(&tr);
			return sb_errf(e, SB_ENOMEM, "out of memory");
		}
		if (dr == 1 || ob->run.samples < 10 || !(ob->run.t1 - ob->run.t0 >= need))
			ob->status = WHALE_SHORT;
		else {
			ob->status = WHALE_OK;
			/* the spectrum of the same period-averaged series the dives were read off */
			size_t i0 = 0;
			while (i0 < tr.n && tr.t[i0] < t0)
				i0++;
			const size_t m = tr.n - i0;
			double *ys = malloc(sizeof *ys * m);
			int bad = !ys || whale_smooth(tr.t + i0, tr.ybox + i0, m, ob->drive_f > 0 ? 1 / ob->drive_f : 0, ys) ||
				  whale_spectrum(tr.t + i0, ys, m, ob->drive_f, &ob->spec);
			free(ys);
			if (bad) {
				traj_free(&tr);
				return sb_errf(e, SB_ENOMEM, "out of memory");
			}
		}
	}
	traj_free(&tr);
	return e->code;
}

int whale_trace(const char *path, double t_from, double step, double **t, double **y, size_t *n, sb_err *e)
{
	*t = *y = NULL;
	*n = 0;
	traj tr;
	const int rc = traj_read(path, &tr, e);
	if (rc) {
		traj_free(&tr);
		return rc == 1 ? 0 : rc;
	}
	size_t i0 = 0;
	while (i0 < tr.n && tr.t[i0] < t_from)
		i0++;
	const size_t m = tr.n - i0;
	double *ys = malloc(sizeof *ys * (m ? m : 1));
	*t = malloc(sizeof **t * (m ? m : 1));
	*y = malloc(sizeof **y * (m ? m : 1));
	if (!ys || !*t || !*y || whale_smooth(tr.t + i0, tr.ybox + i0, m, step, ys)) {
		free(ys);
		free(*t);
		free(*y);
		*t = *y = NULL;
		traj_free(&tr);
		return sb_errf(e, SB_ENOMEM, "out of memory");
	}
	/* on the grid t_from + k step, so that the samples' spacing does not make it drift */
	double k = 0;
	for (size_t i = 0; i < m; i++)
		if (!(step > 0) || tr.t[i0 + i] >= t_from + k * step) {
			(*t)[*n] = tr.t[i0 + i];
			(*y)[(*n)++] = ys[i];
			if (step > 0)
				k = floor((tr.t[i0 + i] - t_from) / step) + 1;
		}
	free(ys);
	traj_free(&tr);
	return 0;
}
