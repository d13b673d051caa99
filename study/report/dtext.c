/* dtext.c - the shortest text of a double (dtext.h). */
#include "dtext.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

void dtext_shortest(double v, char *buf, size_t len)
{
	if (v == floor(v) && fabs(v) < 1e15) { /* 20, 3000000: no exponent */
		snprintf(buf, len, "%.0f", v);
		return;
	}
	for (int p = 1; p <= 17; p++) {
		snprintf(buf, len, "%.*g", p, v);
		if (strtod(buf, NULL) == v)
			return;
	}
}

void dtext_duration(double s, char *buf, size_t len)
{
	if (s < 0)
		snprintf(buf, len, "unknown");
	else if (s < 120)
		snprintf(buf, len, "%.0f s", s);
	else if (s < 7200)
		snprintf(buf, len, "%.1f min", s / 60);
	else
		snprintf(buf, len, "%.1f h", s / 3600);
}
