/* traj.c - the intruder's trajectory in the box frame and the fraction rise (traj.h). */
#include "traj.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "drive.h"
#include "h5read.h"
#include "runfile.h"

/* The box motion of the run, from its /parameters (the engine's core/run/sim.c setup). */
static void drive_of(hid_t f, sb_drive *d)
{
	char ramp[32] = "none";
	double A = 0, fr = 0, f0 = 0, f1 = 0, hold = 0, dur = 0;
	h5r_attr_str(f, RUNFILE_PARAMS, "ramp", ramp, sizeof ramp);
	h5r_attr_num(f, RUNFILE_PARAMS, "amplitude", &A);
	h5r_attr_num(f, RUNFILE_PARAMS, "frequency", &fr);
	h5r_attr_num(f, RUNFILE_PARAMS, "ramp_from", &f0);
	h5r_attr_num(f, RUNFILE_PARAMS, "ramp_to", &f1);
	h5r_attr_num(f, RUNFILE_PARAMS, "ramp_hold", &hold);
	h5r_attr_num(f, RUNFILE_PARAMS, "duration", &dur);
	const int r = !strcmp(ramp, "linear") ? RAMP_LINEAR : !strcmp(ramp, "updown") ? RAMP_UPDOWN : RAMP_NONE;
	*d = (sb_drive){r, A, fr, f0, f1, dur - hold, hold};
}

int traj_read(const char *path, traj *tr, sb_err *e)
{
	memset(tr, 0, sizeof *tr);
	tr->y0 = tr->surface = tr->radius = tr->x0 = NAN;
	hid_t f;
	if (h5r_open(path, &f, e))
		return e->code;
	h5r_attr_num(f, "/", "intruder_settled_y", &tr->y0);
	h5r_attr_num(f, "/", "surface_height", &tr->surface);
	h5r_attr_num(f, "/", "intruder_radius", &tr->radius);
	h5r_attr_str(f, "/", "stopped_by", tr->stopped_by, sizeof tr->stopped_by);
	if (!h5r_exists(f, RUNFILE_INTRUDER)) {
		h5r_close(f);
		return 1;
	}
	double *pos = NULL;
	size_t dt[3], dp[3];
	int rt, rp;
	sb_err re = {0};
	if (h5r_read(f, RUNFILE_INTRUDER_TIME, &tr->t, &rt, dt, &re) ||
	    h5r_read(f, RUNFILE_INTRUDER_POS, &pos, &rp, dp, &re)) {
		h5r_close(f);
		free(pos);
		traj_free(tr);
		return sb_errf(e, re.code ? re.code : SB_EIO, "%.500s: %.500s", path, re.msg);
	}
	if (rp != 3 || dp[1] != 1 || dp[2] != 2 || dt[0] != dp[0]) {
		h5r_close(f);
		free(pos);
		traj_free(tr);
		return sb_errf(e, SB_EIO, "%s: /particles/intruder/position is not [T x 1 x 2] with T times", path);
	}
	for (size_t i = 0; i < dp[0]; i++)
		if (!isfinite(tr->t[i]) || !isfinite(pos[2 * i]) || !isfinite(pos[2 * i + 1])) {
			h5r_close(f);
			sb_errf(e, SB_ENAN, "%s: /particles/intruder/position row %zu (t = %g, y = %g): not a finite number",
				path, i, tr->t[i], pos[2 * i + 1]);
			free(pos);
			traj_free(tr);
			return e->code;
		}
	sb_drive d;
	drive_of(f, &d);
	h5r_close(f);
	tr->n = dp[0];
	tr->y = malloc(sizeof *tr->y * (tr->n ? tr->n : 1));
	tr->ybox = malloc(sizeof *tr->ybox * (tr->n ? tr->n : 1));
	if (!tr->y || !tr->ybox) {
		free(pos);
		traj_free(tr);
		return sb_errf(e, SB_ENOMEM, "out of memory");
	}
	for (size_t i = 0; i < tr->n; i++) {
		tr->y[i] = pos[2 * i + 1];
		tr->ybox[i] = tr->y[i] - drive_y(&d, tr->t[i]);
	}
	if (tr->n)
		tr->x0 = pos[0];
	free(pos);
	return tr->n ? 0 : 1;
}

void traj_free(traj *tr)
{
	free(tr->t);
	free(tr->y);
	free(tr->ybox);
	tr->t = tr->y = tr->ybox = NULL;
	tr->n = 0;
}

double traj_crossing(const double *t, const double *y, size_t n, double level)
{
	for (size_t i = 0; i < n; i++)
		if (y[i] >= level) {
			if (i == 0 || !(y[i] > y[i - 1]))
				return t[i];
			return t[i - 1] + (t[i] - t[i - 1]) * (level - y[i - 1]) / (y[i] - y[i - 1]);
		}
	return NAN;
}

int traj_fraction(const traj *tr, double q, double *time)
{
	*time = NAN;
	if (!tr->n || !isfinite(tr->y0) || !isfinite(tr->surface))
		return -1;
	const double c = traj_crossing(tr->t, tr->ybox, tr->n, tr->y0 + q * (tr->surface - tr->y0));
	if (isfinite(c)) {
		*time = c;
		return 1;
	}
	*time = tr->t[tr->n - 1];
	return 0;
}

int traj_rise(hid_t f, const char *path, double *risen, double *wait, sb_err *e)
{
	double rs, w;
	if (h5r_attr_num(f, "/", "risen", &rs) || h5r_attr_num(f, "/", "waiting_time", &w))
		return sb_errf(e, SB_EIO, "%s: no valid root attributes risen, waiting_time", path);
	if (rs != 0 && rs != 1)
		return sb_errf(e, SB_ENAN, "%s: risen = %g: expected 0 or 1", path, rs);
	if (!isfinite(w) || w < 0)
		return sb_errf(e, SB_ENAN, "%s: waiting_time = %g: not a finite time >= 0", path, w);
	*risen = rs;
	*wait = w;
	return 0;
}
