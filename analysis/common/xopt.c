/* xopt.c - a tool's own options, taken out of argv before cli_parse (xopt.h). */
#include "xopt.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "num.h"

/* cli.c's options that every tool takes; the tool's others are in its allowed list */
static const char COMMON[] = " help db runs out no-plot no-store all-versions ";

/* 1 when name is a prefix of a word of the space-separated list l (exact: equal) */
static int in_words(const char *l, const char *name, size_t len, int exact)
{
	for (const char *p = l; *p;) {
		while (*p == ' ')
			p++;
		const size_t w = strcspn(p, " ");
		if (w && len <= w && !strncmp(p, name, len) && (!exact || len == w))
			return 1;
		p += w;
	}
	return 0;
}

static int cli_knows(const char *allowed, const char *name, size_t len, int exact)
{
	return in_words(COMMON, name, len, exact) || in_words(allowed, name, len, exact);
}

int xopt_take(int *argc, char **argv, xopt *x, int nx, const char *allowed, sb_err *e)
{
	int out = 1, i = 1;
	for (; i < *argc; i++) {
		char *a = argv[i];
		if (!strcmp(a, "--"))
			break; /* the rest is cli_parse's */
		if (strncmp(a, "--", 2) || !a[2]) {
			argv[out++] = a;
			continue;
		}
		const char *name = a + 2, *eq = strchr(name, '=');
		const size_t len = eq ? (size_t)(eq - name) : strlen(name);
		int hit = -1, nhit = 0;
		for (int k = 0; k < nx; k++)
			if (strlen(x[k].name) >= len && !strncmp(x[k].name, name, len)) {
				if (strlen(x[k].name) == len) { /* an exact name wins over prefixes */
					hit = k;
					nhit = 1;
					break;
				}
				hit = k;
				nhit++;
			}
		if (!nhit || (strlen(x[hit].name) != len && cli_knows(allowed, name, len, 1))) {
			argv[out++] = a; /* cli's (or unknown: cli_parse reports it) */
			continue;
		}
		if (nhit > 1 || (strlen(x[hit].name) != len && cli_knows(allowed, name, len, 0)))
			return sb_errf(e, SB_EUSAGE, "--%.*s: ambiguous option (--help lists them)", (int)len, name);
		xopt *o = &x[hit];
		o->set = 1;
		if (!o->has_arg) {
			if (eq)
				return sb_errf(e, SB_EUSAGE, "--%s takes no value", o->name);
			continue;
		}
		if (eq)
			o->val = eq + 1;
		else if (i + 1 < *argc)
			o->val = argv[++i];
		else
			return sb_errf(e, SB_EUSAGE, "--%s needs a value", o->name);
	}
	for (; i < *argc; i++)
		argv[out++] = argv[i];
	argv[out] = NULL;
	*argc = out;
	return 0;
}

/* The first --word of argv that neither cli nor x knows, when it is nearer to one of
 * x than to any of cli's options: that one of x (else NULL); the word into w. */
static const char *misspelt(int argc, char **argv, const xopt *x, int nx, const char *allowed, char *w, size_t n)
{
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i];
		if (!strcmp(a, "--"))
			break;
		if (strncmp(a, "--", 2) || !a[2])
			continue;
		snprintf(w, n, "%.*s", (int)strcspn(a + 2, "="), a + 2);
		if (cli_knows(allowed, w, strlen(w), 0))
			continue;
		const char *best = NULL;
		int bd = 1 << 20;
		for (int k = 0; k < nx; k++) {
			const int d = cli_distance(w, x[k].name);
			if (d < bd) {
				bd = d;
				best = x[k].name;
			}
		}
		const int lim = strlen(w) >= 6 ? (int)strlen(w) / 3 : 1;
		const char *theirs = cli_nearest(w, allowed);
		if (best && bd <= lim && (!theirs || bd < cli_distance(w, theirs)))
			return best;
	}
	return NULL;
}

int xopt_args(an_opts *o, int argc, char **argv, const char *help, const char *allowed, xopt *x, int nx, FILE *out,
	      FILE *err)
{
	sb_err e = {0};
	if (xopt_take(&argc, argv, x, nx, allowed, &e)) {
		fprintf(err, "%s: %s\n", o->tool, e.msg);
		return 1;
	}
	char w[64];
	const char *near = misspelt(argc, argv, x, nx, allowed, w, sizeof w);
	const int pr = cli_parse(o, argc, argv, allowed, &e);
	if (pr < 0)
		fputs(help, out);
	else if (pr && near && strstr(e.msg, "unknown option"))
		fprintf(err, "%s: --%s: unknown option; did you mean --%s?\n", o->tool, w, near);
	else if (pr)
		fprintf(err, "%s: %s\n", o->tool, e.msg);
	return pr;
}

int xopt_num(const xopt *x, double lo, double hi, double dflt, double *v, sb_err *e)
{
	if (!x->set) {
		*v = dflt;
		return 0;
	}
	double d;
	if (num_real(x->val, &d) || !(d >= lo && d <= hi))
		return sb_errf(e, SB_EUSAGE, "--%s: expected a number in [%g, %g], got '%s'", x->name, lo, hi, x->val);
	*v = d;
	return 0;
}

void xopt_options(const xopt *x, int nx, char *buf, size_t n)
{
	size_t l = strlen(buf);
	for (int k = 0; k < nx && l < n; k++) {
		double d;
		if (!x[k].has_arg)
			l += (size_t)snprintf(buf + l, n - l, "%s%s=%s", l ? " " : "", x[k].name, x[k].set ? "yes" : "no");
		else if (!x[k].set)
			l += (size_t)snprintf(buf + l, n - l, "%s%s=default", l ? " " : "", x[k].name);
		else if (!num_real(x[k].val, &d))
			l += (size_t)snprintf(buf + l, n - l, "%s%s=%.15g", l ? " " : "", x[k].name, d);
		else
			l += (size_t)snprintf(buf + l, n - l, "%s%s=%s", l ? " " : "", x[k].name, x[k].val);
	}
}
