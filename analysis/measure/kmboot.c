/* kmboot.c - the Kaplan-Meier median's bootstrap over runs (kmboot.h). */
#include "kmboot.h"

#include <math.h>
#include <stdlib.h>

#include "boot.h"
#include "km.h"

typedef struct kb_ctx {
	const double *t;
	const int *ev;
	double *rt; /* [n] the resample's times and events */
	int *rev;
	int err;
} kb_ctx;

/* out[0]: the resample's median (NaN: its curve never reaches 1/2); out[1]: its longest
 * observation */
static void stat(void *vc, const size_t *idx, size_t n, double *out)
{
	kb_ctx *c = vc;
	double tm = 0;
	for (size_t i = 0; i < n; i++) {
		c->rt[i] = c->t[idx[i]];
		c->rev[i] = c->ev[idx[i]];
		tm = fmax(tm, c->rt[i]);
	}
	km_curve k;
	double l, h;
	out[0] = NAN;
	out[1] = tm;
	if (km_fit(c->rt, c->rev, n, &k)) {
		c->err = 1;
		return;
	}
	out[0] = km_median(&k, 0, &l, &h);
	km_free(&k);
}

int kmboot_median(const double *t, const int *ev, size_t n, size_t B, unsigned long seed, double *lo, double *hi,
		  size_t *censored)
{
	*censored = 0;
	if (!n)
		return -1;
	kb_ctx c = {t, ev, malloc(sizeof(double) * n), malloc(sizeof(int) * n), 0};
	double *out = malloc(sizeof *out * 2 * (B ? B : 1));
	int rc = -1;
	if (c.rt && c.rev && out && !boot_run(seed, n, B, 2, stat, &c, out) && !c.err) {
		for (size_t k = 0; k < B; k++) {
			const int reached = !isnan(out[k]);
			lo[k] = reached ? out[k] : out[B + k];
			hi[k] = reached ? out[k] : INFINITY;
			*censored += !reached;
		}
		rc = 0;
	}
	free(c.rt);
	free(c.rev);
	free(out);
	return rc;
}
