/* axis.c - the drive's axes of a figure (axis.h). */
#include "axis.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "drive.h"
#include "label.h"
#include "params.h"

static const char *const NAME[AXIS_N] = {"frequency", "gamma", "velocity"};
static const char *const WORDS[AXIS_N] = {"frequency", "peak acceleration", "peak velocity"};

int axis_parse(const char *name)
{
	for (int k = 0; k < AXIS_N; k++)
		if (!strcmp(NAME[k], name))
			return k;
	return -1;
}

const char *axis_name(int kind)
{
	return kind >= 0 && kind < AXIS_N ? NAME[kind] : "?";
}

double axis_of(int kind, double A, double f, double g)
{
	switch (kind) {
	case AXIS_GAMMA:
		return drive_gamma(A, f, g);
	case AXIS_VELOCITY:
		return drive_velocity(A, f);
	default:
		return f;
	}
}

double axis_gravity(const an_run *r)
{
	const sb_param *G = params_find("gravity");
	return an_num(r, "gravity", G ? strtod(G->def, NULL) : NAN);
}

double axis_run(int kind, const an_run *r)
{
	return axis_of(kind, an_num(r, "amplitude", NAN), an_num(r, "frequency", NAN), axis_gravity(r));
}

void axis_gp_freq(FILE *f, int kind, double A, double g)
{
	/* both are a constant times f^2 or f: the constant is the axis at f = 1 */
	if (kind == AXIS_GAMMA)
		fprintf(f, "sqrt(x/%.17g)", drive_gamma(A, 1, g));
	else if (kind == AXIS_VELOCITY)
		fprintf(f, "(x/%.17g)", drive_velocity(A, 1));
	else
		fputc('x', f);
}

void axis_label(char *buf, size_t n, int kind)
{
	label_axis(buf, n, axis_name(kind), WORDS[kind >= 0 && kind < AXIS_N ? kind : 0]);
}
