/* fluxrun.c - a campaign run's flux, classified and read (fluxrun.h). */
#include "fluxrun.h"

#include <math.h>
#include <string.h>

int fluxrun_load(an_run *r, flux_data *d)
{
	memset(d, 0, sizeof *d);
	if (acct_classify(r))
		return 1;
	sb_err e = {0};
	if (flux_read(r->path, d, &e)) {
		/* a value that is no number is there to read, and unusable */
		acct_set(r, e.code == SB_ENAN ? AN_UNUSABLE : AN_UNREADABLE, NAN, NAN, "%s", e.msg);
		return 1;
	}
	const char *ramp = an_str(r, "ramp");
	double per = an_num(r, "duration", NAN) * an_num(r, "frequency", NAN);
	if (!strcmp(r->state, "failed") && (!ramp || !strcmp(ramp, "none")) && per >= 0 && per < 1e12)
		d->planned = (size_t)floor(per + 1e-9);
	return 0;
}
