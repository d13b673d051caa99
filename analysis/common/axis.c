/* axis.c - the drive's axes of a figure (axis.h). */
#include "axis.h"

#include <math.h>
#include <stdlib.h>

#include "drive.h"
#include "label.h"
#include "params.h"

static const char *const WORDS[AXIS_N] = {"frequency", "peak acceleration", "peak velocity"};

double axis_gravity(const an_run *r)
{
	const sb_param *G = params_find("gravity");
	return an_num(r, "gravity", G ? strtod(G->def, NULL) : NAN);
}

double axis_run(int kind, const an_run *r)
{
	return drive_axis(kind, an_num(r, "amplitude", NAN), an_num(r, "frequency", NAN), axis_gravity(r));
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
	label_axis(buf, n, drive_axis_name(kind), WORDS[kind >= 0 && kind < AXIS_N ? kind : 0]);
}
