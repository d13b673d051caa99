/* stopdef.h - one threshold per campaign: a campaign with an [onset] search over the
 * flux classifies its runs by [onset] threshold (and band), and its runs' stop = flux
 * rule decides by the engine's stop_flux_threshold (and stop_flux_lo, stop_flux_hi);
 * the two are one definition (docs/campaigns.md, "One onset definition"). */
#ifndef ST_STOPDEF_H
#define ST_STOPDEF_H

#include "campaign.h"

/* On an [onset] campaign over the flux: an engine key of the pair set in [scene],
 * [grid] or the scene file to another value than [onset]'s is refused ("FILE:LINE:
 * KEY: ..." naming both lines); one not set is set in c->base from [onset] when the
 * runs stop by the flux (stop = flux in the scene, or a stop axis with flux). [onset]
 * skip has no engine twin: stop_skip is in seconds. Anything else: nothing. */
int stopdef_apply(campaign *c, sb_err *e);

#endif
