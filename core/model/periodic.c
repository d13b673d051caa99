/* periodic.c - the wrap of the state into the period (periodic.h). */
#include "periodic.h"

int periodic_wrap_state(sb_state *st, double W)
{
	if (!(W > 0))
		return 0;
	double *x = st->q[C_X][0];
	int moved = 0;
	for (int i = 0; i < st->nm; i++) {
		const double w = periodic_wrap(x[i], W);
		moved += w != x[i];
		x[i] = w;
	}
	return moved;
}
