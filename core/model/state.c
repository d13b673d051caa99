/* state.c - allocation of the struct-of-arrays particle state. */
#include "state.h"

#include <stdlib.h>
#include <string.h>

#include "bigmem.h"

static void *xrealloc(void *p, size_t n) { return realloc(p, n ? n : 1); }

/* the double arrays of the state, in the order of its slab */
enum { NDBL = SB_NCOORD * SB_MAXORDER + SB_NCOORD + 4 };

static void dbl_arrays(sb_state *s, double ***d)
{
	int k = 0;
	for (int c = 0; c < SB_NCOORD; c++)
		for (int o = 0; o < SB_MAXORDER; o++)
			d[k++] = &s->q[c][o];
	for (int c = 0; c < SB_NCOORD; c++)
		d[k++] = &s->f[c];
	d[k++] = &s->r;
	d[k++] = &s->m;
	d[k++] = &s->inv_m;
	d[k++] = &s->inv_i;
}

int state_alloc(sb_state *s, int cap, sb_err *e)
{
	if (cap < s->cap)
		return 0;
	/* one slab for all double arrays (bigmem.h: aligned, huge pages when large) */
	void *slab, *arr[NDBL];
	if (bigmem_slab(&slab, arr, NDBL, (size_t)cap, sizeof(double)))
		return sb_errf(e, SB_ENOMEM, "out of memory for %d particles", cap);
	int *pid = xrealloc(s->id, sizeof(int) * (size_t)cap);
	if (pid)
		s->id = pid;
	unsigned char *pk = xrealloc(s->kind, (size_t)cap);
	if (pk)
		s->kind = pk;
	if (!pid || !pk) {
		free(slab);
		return sb_errf(e, SB_ENOMEM, "out of memory for %d particles", cap);
	}
	double **d[NDBL];
	dbl_arrays(s, d);
	for (int k = 0; k < NDBL; k++) {
		double *p = arr[k];
		if (s->cap)
			memcpy(p, *d[k], sizeof(double) * (size_t)s->cap);
		memset(p + s->cap, 0, sizeof(double) * (size_t)(cap - s->cap));
		*d[k] = p;
	}
	free(s->slab);
	s->slab = slab;
	s->cap = cap;
	return 0;
}

void state_free(sb_state *s)
{
	free(s->slab);
	free(s->id);
	free(s->kind);
	memset(s, 0, sizeof *s);
}

int state_push(sb_state *s, double x, double y, double r, int kind, double m, double inv_m,
	       double inv_i, sb_err *e)
{
	if (kind != KIND_WALL && s->n != s->nm)
		return sb_errf(e, SB_EUSAGE, "internal: mobile disk pushed after a wall disk");
	if (s->n == s->cap && state_alloc(s, s->cap ? 2 * s->cap : 256, e))
		return e->code;
	int i = s->n++;
	if (kind != KIND_WALL)
		s->nm++;
	for (int c = 0; c < SB_NCOORD; c++) {
		for (int k = 0; k < SB_MAXORDER; k++)
			s->q[c][k][i] = 0;
		s->f[c][i] = 0;
	}
	s->q[C_X][0][i] = x;
	s->q[C_Y][0][i] = y;
	s->r[i] = r;
	s->m[i] = m;
	s->inv_m[i] = inv_m;
	s->inv_i[i] = inv_i;
	s->id[i] = i;
	s->kind[i] = (unsigned char)kind;
	return 0;
}

int state_find_intruder(const sb_state *s)
{
	for (int i = 0; i < s->nm; i++)
		if (s->kind[i] == KIND_INTRUDER)
			return i;
	return -1;
}
