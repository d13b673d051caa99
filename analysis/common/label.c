/* label.c - parameters in figure text (label.h). */
#include "label.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The words of a key: the format of its value (%s: the number or text) and, for
 * radius_ratio, what 0 means. One row per key a campaign sweeps or a reader looks for;
 * the symbols are docs/model.md's. */
static const struct {
	const char *key, *fmt, *zero;
} WORDS[] = {
	{"radius_ratio", "𝓡 = %s", "no intruder"},
	{"frequency", "%s Hz", NULL},
	{"amplitude", "A = %s cm", NULL},
	{"width", "W = %s cm", NULL},
	{"depth", "depth %s", NULL},
	{"n_grains", "N = %s", NULL},
	{"gravity", "g = %s cm/s²", NULL},
	{"mu", "μ = %s", NULL},
	{"gamma_n", "γ_N = %s s⁻¹", NULL},
	{"gamma_s", "γ_S = %s s⁻¹", NULL},
	{"stiffness", "Y = %s g/s²", NULL},
	{"dt", "Δt = %s s", NULL},
	{"duration", "%s s runs", NULL},
	{"integrator", "%s", NULL},
	{"preset", "preset %s", NULL},
	{"ramp", "%s ramp", NULL},
	{"r_min", "r_min = %s cm", NULL},
	{"r_max", "r_max = %s cm", NULL},
};

void label_param(char *buf, size_t n, const char *key, const char *val)
{
	char v[64], *end;
	const double x = val && *val ? strtod(val, &end) : 0;
	if (val && *val && !*end)
		snprintf(v, sizeof v, "%g", x);
	else
		snprintf(v, sizeof v, "%s", val ? val : "");
	for (size_t i = 0; i < sizeof WORDS / sizeof *WORDS; i++)
		if (!strcmp(WORDS[i].key, key)) {
			if (WORDS[i].zero && val && *val && !*end && x == 0)
				snprintf(buf, n, "%s", WORDS[i].zero);
			else
				snprintf(buf, n, WORDS[i].fmt, v);
			return;
		}
	snprintf(buf, n, "%s = %s", key, v);
}

static const char *val_of(const char *const *vals, int nk, int j, int k)
{
	const char *v = vals ? vals[j * nk + k] : NULL;
	return v ? v : "";
}

void label_group(char *buf, size_t n, const char keys[][48], int nk, const char *const *vals, int ng, int j, int vary)
{
	size_t l = 0;
	if (n)
		buf[0] = 0;
	for (int k = 0; k < nk && l + 1 < n; k++) {
		int differs = 0;
		for (int g = 1; g < ng && !differs; g++)
			differs = strcmp(val_of(vals, nk, g, k), val_of(vals, nk, 0, k)) != 0;
		if (differs != vary || !*val_of(vals, nk, j, k))
			continue;
		char w[160];
		label_param(w, sizeof w, keys[k], val_of(vals, nk, j, k));
		l += (size_t)snprintf(buf + l, n - l, "%s%s", l ? ", " : "", w);
	}
}
