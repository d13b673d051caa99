/* label.c - parameters in figure text (label.h). */
#include "label.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drive.h"
#include "params.h"

/* The words of a key: the format of its value and unit (two %s: the number or text,
 * then the unit of the parameter table, core/scene/params.c, as a reader writes it) and, for
 * radius_ratio, what 0 means. One row per key a campaign sweeps or a reader looks for;
 * the symbols are docs/model.md's. */
static const struct {
	const char *key, *fmt, *zero;
} WORDS[] = {
	{"radius_ratio", "𝓡 = %s", "no intruder"},
	{"frequency", "%s %s", NULL},
	{"amplitude", "A = %s %s", NULL},
	{"width", "W = %s %s", NULL},
	{"depth", "depth %s", NULL},
	{"n_grains", "N = %s", NULL},
	{"gravity", "g = %s %s", NULL},
	{"mu", "μ = %s", NULL},
	{"gamma_n", "γ_N = %s %s", NULL},
	{"gamma_s", "γ_S = %s %s", NULL},
	{"stiffness", "Y = %s %s", NULL},
	{"dt", "Δt = %s %s", NULL},
	{"duration", "%s %s runs", NULL},
	{"integrator", "%s", NULL},
	{"preset", "preset %s", NULL},
	{"ramp", "%s ramp", NULL},
	{"r_min", "r_min = %s %s", NULL},
	{"r_max", "r_max = %s %s", NULL},
};

void label_unit(char *buf, size_t n, const char *key)
{
	const sb_param *p = params_find(key);
	const char *u = p ? p->unit : "";
	if (!p && drive_axis_kind(key) >= 0)
		u = drive_axis_unit(drive_axis_kind(key));
	size_t l = 0;
	if (n)
		buf[0] = 0;
	/* the table's ASCII (cm/s^2, 1/s) as printed: cm/s², s⁻¹ */
	if (!strncmp(u, "1/", 2)) {
		snprintf(buf, n, "%s⁻¹", u + 2);
		return;
	}
	for (; *u && l + 4 < n; u++) {
		if (u[0] == '^' && (u[1] == '2' || u[1] == '3')) {
			l += (size_t)snprintf(buf + l, n - l, "%s", u[1] == '2' ? "²" : "³");
			u++;
		} else
			buf[l++] = *u, buf[l] = 0;
	}
}

void label_axis(char *buf, size_t n, const char *key, const char *words)
{
	char u[32];
	/* the drive's axes by their symbols (their rows, core/model/drive.h), any other key
	 * by its name */
	const sb_axis_row *ax = drive_axis_row(drive_axis_kind(key));
	const char *sym = ax ? ax->symbol : key;
	label_unit(u, sizeof u, key);
	snprintf(buf, n, "%s%s%s%s%s%s", words ? words : "", words && *words ? " " : "", sym, *u ? " (" : "", u,
		 *u ? ")" : "");
}

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
			else {
				char u[32];
				label_unit(u, sizeof u, key);
				snprintf(buf, n, WORDS[i].fmt, v, u);
			}
			return;
		}
	snprintf(buf, n, "%s = %s", key, v);
}

void label_num(char *buf, size_t n, const char *key, double x)
{
	char v[32];
	snprintf(v, sizeof v, "%.17g", x);
	label_param(buf, n, key, v);
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
