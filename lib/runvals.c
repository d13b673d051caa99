/* runvals.c - a run file's values within their ranges (runvals.h). */
#include "runvals.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "h5read.h"
#include "params.h"
#include "runfile.h"

/* The scene keys that are numbers, each through the engine's own parser: its range and
 * its integer check are the one place those live (core/scene/params.c). */
static int params_in_range(hid_t f, const char *path, sb_err *e)
{
	size_t n;
	const sb_param *t = params_table(&n);
	sb_scene sc;
	params_defaults(&sc);
	char where[600];
	snprintf(where, sizeof where, "%.500s: " RUNFILE_PARAMS, path);
	for (size_t i = 0; i < n; i++) {
		if (t[i].type != PT_INT && t[i].type != PT_REAL)
			continue;
		char v[64];
		if (t[i].type == PT_INT) {
			long long x;
			const int rc = h5r_attr_int(f, RUNFILE_PARAMS, t[i].name, &x);
			if (rc > 0)
				continue;
			if (rc < 0)
				return sb_errf(e, SB_EIO, "%s@%s: not one integer", where, t[i].name);
			snprintf(v, sizeof v, "%lld", x);
		} else {
			double x;
			const int rc = h5r_attr_num(f, RUNFILE_PARAMS, t[i].name, &x);
			if (rc > 0)
				continue;
			if (rc < 0)
				return sb_errf(e, SB_EIO, "%s@%s: not one number", where, t[i].name);
			snprintf(v, sizeof v, "%.17g", x);
		}
		sb_err pe = {0};
		if (params_set(&sc, t[i].name, v, where, &pe))
			return sb_errf(e, SB_EIO, "%s: a value the engine does not write", pe.msg);
	}
	return 0;
}

int runvals_check(hid_t f, const char *path, sb_err *e)
{
	if (params_in_range(f, path, e))
		return e->code;
	static const struct {
		const char *name;
		double lo;
		int lo_open; /* lo itself is out of range */
		int settled; /* only a run that settled has it: one that failed before may hold 0 */
	} ROOT[] = {{"status_time", 0, 0, 0}, {"surface_height", 0, 1, 1}, {"intruder_radius", 0, 1, 0},
		    {"waiting_time", 0, 0, 0}};
	long long steps = 0;
	char status[16];
	const int settled = (h5r_attr_int(f, "/", "settle_steps", &steps) == 0 && steps > 0) ||
			    (h5r_attr_str(f, "/", "status", status, sizeof status) == 0 && !strcmp(status, "ok"));
	for (size_t k = 0; k < sizeof ROOT / sizeof *ROOT; k++) {
		if (ROOT[k].settled && !settled)
			continue;
		double x;
		const int rc = h5r_attr_num(f, "/", ROOT[k].name, &x);
		if (rc)
			continue; /* absent, or not one number: the reader that needs it says so */
		if (!isfinite(x))
			return sb_errf(e, SB_ENAN, "%s: /@%s = %g: not a finite number", path, ROOT[k].name, x);
		if (ROOT[k].lo_open ? !(x > ROOT[k].lo) : !(x >= ROOT[k].lo))
			return sb_errf(e, SB_EIO, "%s: /@%s = %g: the engine writes %s %g", path, ROOT[k].name, x,
				       ROOT[k].lo_open ? "more than" : "at least", ROOT[k].lo);
	}
	long long risen;
	const int rr = h5r_attr_int(f, "/", "risen", &risen);
	if (rr == 0 && risen != 0 && risen != 1)
		return sb_errf(e, SB_EIO, "%s: /@risen = %lld: the engine writes 0 or 1", path, risen);
	/* a waiting time ends within the run: the engine writes the time it stopped at when
	 * the intruder did not rise, at most its duration (one step of rounding allowed) */
	double w, dur, dt = 0;
	if (h5r_attr_num(f, "/", "waiting_time", &w) == 0 && h5r_attr_num(f, RUNFILE_PARAMS, "duration", &dur) == 0) {
		h5r_attr_num(f, RUNFILE_PARAMS, "dt", &dt);
		const double end = dur * (1 + 1e-12) + (isfinite(dt) && dt > 0 ? dt : 0);
		if (w > end)
			return sb_errf(e, SB_EIO, "%s: /@waiting_time = %g s, after the run's end (duration %g s)", path, w,
				       dur);
	}
	return 0;
}
