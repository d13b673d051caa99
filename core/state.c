/* state.c - allocation of the struct-of-arrays particle state. */
#include "state.h"

#include <stdlib.h>
#include <string.h>

static void *xrealloc(void *p, size_t n) { return realloc(p, n ? n : 1); }

int state_alloc(sb_state *s, int cap, sb_err *e)
{
	if (cap < s->cap)
		return 0;
	int old = s->cap;
	int ok = 1;
	for (int c = 0; c < SB_NCOORD; c++) {
		for (int k = 0; k < SB_MAXORDER; k++) {
			double *p = xrealloc(s->q[c][k], sizeof(double) * (size_t)cap);
			ok &= p != NULL;
			if (p) {
				memset(p + old, 0, sizeof(double) * (size_t)(cap - old));
				s->q[c][k] = p;
			}
		}
		double *p = xrealloc(s->f[c], sizeof(double) * (size_t)cap);
		ok &= p != NULL;
		if (p)
			s->f[c] = p;
	}
	double **d[] = {&s->r, &s->m, &s->inv_m, &s->inv_i};
	for (size_t i = 0; i < sizeof d / sizeof d[0]; i++) {
		double *p = xrealloc(*d[i], sizeof(double) * (size_t)cap);
		ok &= p != NULL;
		if (p)
			*d[i] = p;
	}
	int *pid = xrealloc(s->id, sizeof(int) * (size_t)cap);
	unsigned char *pk = xrealloc(s->kind, (size_t)cap);
	ok &= pid && pk;
	if (pid)
		s->id = pid;
	if (pk)
		s->kind = pk;
	if (!ok)
		return sb_errf(e, SB_ENOMEM, "out of memory for %d particles", cap);
	s->cap = cap;
	return 0;
}

void state_free(sb_state *s)
{
	for (int c = 0; c < SB_NCOORD; c++) {
		for (int k = 0; k < SB_MAXORDER; k++)
			free(s->q[c][k]);
		free(s->f[c]);
	}
	free(s->r);
	free(s->m);
	free(s->inv_m);
	free(s->inv_i);
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
