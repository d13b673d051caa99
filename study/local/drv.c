/* drv.c - the per-run arrays of a drv (drv.h), made and freed in this one place. */
#include <stdlib.h>

#include "drv.h"

void drv_runs_free(drv *d)
{
	drv_runs *r = &d->runs;
	free(r->cache_ok);
	free(r->started);
	free(r->logfrom);
	free(r->pend);
	free(r->names);
	free(r->transient);
	free(r->outcome);
	*r = (drv_runs){0};
}

int drv_runs_alloc(drv *d, sb_err *e)
{
	drv_runs_free(d);
	size_t n = (size_t)d->g.n + 1;
	drv_runs *r = &d->runs;
	r->cache_ok = calloc(n, 1);
	r->started = calloc(n, 1);
	r->logfrom = calloc(n, sizeof *r->logfrom);
	r->pend = calloc(n, sizeof *r->pend);
	r->names = calloc(n, sizeof *r->names);
	r->transient = calloc(n, sizeof *r->transient);
	r->outcome = calloc(n, 1);
	if (!r->cache_ok || !r->started || !r->logfrom || !r->pend || !r->names || !r->transient || !r->outcome)
		return sb_errf(e, SB_ENOMEM, "out of memory");
	return 0;
}
