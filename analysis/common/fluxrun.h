/* fluxrun.h - a campaign run's flux (lib/flux.h) for a statistic: read only when
 * the run's accounting (acct.h) says there is something to read. */
#ifndef AN_FLUXRUN_H
#define AN_FLUXRUN_H

#include "flux.h"
#include "acct.h"
#include "adb.h"

/* A run's flux for a statistic (acct.h): returns 1 when there is nothing to read
 * (pending, running, no file, unreadable file, unusable values: r->use and r->why say
 * which), else 0
 * with d read; for a failed run d->planned is the number of periods its duration
 * holds at its frequency (fixed frequency), so that its transient is the planned one. */
int fluxrun_load(an_run *r, flux_data *d);

#endif
