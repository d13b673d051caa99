/* axis.c - the drive's axes of a figure (axis.h). */
#include "axis.h"

#include <math.h>
#include <stdlib.h>

#include "drive.h"
#include "label.h"
#include "params.h"

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
	/* an axis is a constant times f^power (its row): the constant is the axis at f = 1 */
	const sb_axis_row *r = drive_axis_row(kind);
	if (!r || kind == AXIS_FREQUENCY)
		fputc('x', f);
	else if (r->power == 2)
		fprintf(f, "sqrt(x/%.17g)", drive_axis(kind, A, 1, g));
	else
		fprintf(f, "(x/%.17g)", drive_axis(kind, A, 1, g));
}

void axis_label(char *buf, size_t n, int kind)
{
	label_axis(buf, n, drive_axis_name(kind), drive_axis_row(kind >= 0 && kind < AXIS_N ? kind : 0)->words);
}
