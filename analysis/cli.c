/* cli.c - shared options, paths, grouping keys, CSV and gnuplot helpers. */
#include "cli.h"

#include "layout.h"

#include <errno.h>
#include <math.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

/* Bounded copy (the truncation is intended: keys are checked when parsed). */
static void scopy(char *d, size_t n, const char *s)
{
	size_t l = strlen(s);
	if (l >= n)
		l = n - 1;
	memcpy(d, s, l);
	d[l] = 0;
}

static int allowed_opt(const char *allowed, const char *name)
{
	char pat[64];
	snprintf(pat, sizeof pat, " %s ", name);
	return strstr(allowed, pat) != NULL;
}

static int num(const char *tool, const char *opt, const char *s, double lo, double hi, double *v)
{
	char *end;
	errno = 0;
	double x = s ? strtod(s, &end) : 0;
	if (!s || !*s || *end || errno || !(x >= lo && x <= hi)) {
		fprintf(stderr, "%s: --%s: expected a number in [%g, %g], got '%s'\n", tool, opt, lo, hi, s ? s : "");
		return 1;
	}
	*v = x;
	return 0;
}

int cli_parse(an_opts *o, int argc, char **argv, const char *help, const char *allowed)
{
	const char *tool = o->tool, *db = NULL, *runs = NULL, *out = NULL;
	o->boot = 1000;
	o->seed = 1;
	o->level = 0.95;
	o->nby = -1;
	o->band_lo = 0.4;
	o->band_hi = 0.6;
	o->skip = 0.2;
	o->threshold = NAN;
	o->bins = 10;
	o->smooth = 5;
	o->ratio = NAN;
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
		if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
			fputs(help, stdout);
			return -1;
		}
		if (a[0] != '-' || !a[1]) {
			if (o->campaign) {
				fprintf(stderr, "%s: unexpected argument '%s' (%s --help)\n", tool, a, tool);
				return 1;
			}
			o->campaign = a;
			continue;
		}
		const char *name = a + (a[1] == '-' ? 2 : 1);
		int flag = !strcmp(name, "no-plot") || !strcmp(name, "no-store") || !strcmp(name, "all-versions");
		if (strcmp(name, "db") && strcmp(name, "runs") && strcmp(name, "out") && !flag && !allowed_opt(allowed, name)) {
			fprintf(stderr, "%s: unknown option '%s' (%s --help)\n", tool, a, tool);
			return 1;
		}
		if (flag) {
			if (!strcmp(name, "no-plot"))
				o->no_plot = 1;
			else if (!strcmp(name, "no-store"))
				o->no_store = 1;
			else
				o->all_versions = 1;
			continue;
		}
		if (!v) {
			fprintf(stderr, "%s: %s needs a value\n", tool, a);
			return 1;
		}
		i++;
		double x;
		if (!strcmp(name, "db"))
			db = v;
		else if (!strcmp(name, "runs"))
			runs = v;
		else if (!strcmp(name, "out"))
			out = v;
		else if (!strcmp(name, "boot")) {
			if (num(tool, name, v, 0, 1e7, &x))
				return 1;
			o->boot = (long)x;
		} else if (!strcmp(name, "seed")) {
			if (num(tool, name, v, 0, 4294967295.0, &x))
				return 1;
			o->seed = (unsigned long)x;
		} else if (!strcmp(name, "level")) {
			if (num(tool, name, v, 0.5, 0.999, &o->level))
				return 1;
		} else if (!strcmp(name, "threshold")) {
			if (num(tool, name, v, -1e12, 1e12, &o->threshold))
				return 1;
		} else if (!strcmp(name, "skip")) {
			if (num(tool, name, v, 0, 0.99, &o->skip))
				return 1;
		} else if (!strcmp(name, "bins")) {
			if (num(tool, name, v, 1, 1000, &x))
				return 1;
			o->bins = (long)x;
		} else if (!strcmp(name, "smooth")) {
			if (num(tool, name, v, 1, 100000, &x))
				return 1;
			o->smooth = (long)x;
		} else if (!strcmp(name, "where")) {
			const char *eq = strchr(v, '=');
			if (!eq || eq == v || (size_t)(eq - v) >= sizeof o->where_key[0] ||
			    strlen(eq + 1) >= sizeof o->where_val[0] || !eq[1]) {
				fprintf(stderr, "%s: --where: expected KEY=VALUE, got '%s'\n", tool, v);
				return 1;
			}
			if (o->nwhere == 8) {
				fprintf(stderr, "%s: --where: at most 8 selections\n", tool);
				return 1;
			}
			snprintf(o->where_key[o->nwhere], sizeof o->where_key[0], "%.*s", (int)(eq - v), v);
			snprintf(o->where_val[o->nwhere], sizeof o->where_val[0], "%s", eq + 1);
			o->nwhere++;
		} else if (!strcmp(name, "ratio")) {
			if (num(tool, name, v, 0, 1e6, &o->ratio))
				return 1;
		} else if (!strcmp(name, "band")) {
			char buf[128], *c;
			snprintf(buf, sizeof buf, "%s", v);
			if (!(c = strchr(buf, ':'))) {
				fprintf(stderr, "%s: --band: expected LO:HI (fractions of the surface height), got '%s'\n", tool, v);
				return 1;
			}
			*c = 0;
			if (num(tool, name, buf, 0, 2, &o->band_lo) || num(tool, name, c + 1, 0, 2, &o->band_hi))
				return 1;
			if (o->band_lo > o->band_hi) {
				fprintf(stderr, "%s: --band: LO must not exceed HI, got '%s'\n", tool, v);
				return 1;
			}
		} else if (!strcmp(name, "by") || !strcmp(name, "freq")) {
			char buf[1024];
			snprintf(buf, sizeof buf, "%s", v);
			int isby = name[0] == 'b';
			if (isby)
				o->nby = 0;
			for (char *sv, *t = strtok_r(buf, ",", &sv); t; t = strtok_r(NULL, ",", &sv)) {
				if (isby) {
					if (o->nby == AN_MAXKEYS || strlen(t) >= 48) {
						fprintf(stderr, "%s: --by: too many or too long keys\n", tool);
						return 1;
					}
					snprintf(o->by[o->nby++], 48, "%s", t);
				} else {
					if (o->nfreq == 16) {
						fprintf(stderr, "%s: --freq: at most 16 frequencies\n", tool);
						return 1;
					}
					if (num(tool, name, t, 0, 1000, &o->freqs[o->nfreq]))
						return 1;
					o->nfreq++;
				}
			}
		}
	}
	if (!o->campaign) {
		fprintf(stderr, "%s: which campaign? (%s --help)\n", tool, tool);
		return 1;
	}
	/* bin/study's layout (study/layout.h) */
	if (runs)
		snprintf(o->runs, sizeof o->runs, "%s", runs);
	else if (db) {
		snprintf(o->runs, sizeof o->runs, "%s", db);
		char *sl = strrchr(o->runs, '/');
		if (sl)
			*sl = 0;
		else
			snprintf(o->runs, sizeof o->runs, ".");
	} else
		snprintf(o->runs, sizeof o->runs, "runs");
	int l1 = layout_db(o->runs, db, o->db, sizeof o->db), l2;
	if (out) {
		l2 = snprintf(o->out, sizeof o->out, "%s", out);
	} else {
		char dir[1200];
		layout_campaign(o->runs, o->campaign, dir, sizeof dir);
		l2 = layout_sub(dir, "analysis", o->out, sizeof o->out);
	}
	if (l1 >= (int)sizeof o->db || l2 >= (int)sizeof o->out - 300) {
		fprintf(stderr, "%s: path too long\n", tool);
		return 1;
	}
	return 0;
}

static int in_list(const char *const *l, const char *s)
{
	for (; l && *l; l++)
		if (!strcmp(*l, s))
			return 1;
	return 0;
}

int cli_keys(const an_opts *o, adb *d, const char *const *always, const char *const *drop, char keys[][48],
	     int *nk, sb_err *e)
{
	*nk = 0;
	if (o->nby >= 0) {
		for (int i = 0; i < o->nby; i++)
			scopy(keys[(*nk)++], 48, o->by[i]);
		return 0;
	}
	char ax[AN_MAXKEYS][48];
	int na;
	if (adb_axes(d, o->campaign, ax, AN_MAXKEYS, &na, e))
		return e->code;
	for (const char *const *a = always; a && *a && *nk < AN_MAXKEYS; a++)
		scopy(keys[(*nk)++], 48, *a);
	for (int i = 0; i < na && *nk < AN_MAXKEYS; i++) {
		int dup = 0;
		for (int j = 0; j < *nk; j++)
			dup |= !strcmp(keys[j], ax[i]);
		if (!dup && !in_list(drop, ax[i]) && strcmp(ax[i], "seed"))
			scopy(keys[(*nk)++], 48, ax[i]);
	}
	return 0;
}

int cli_outdir(const an_opts *o, sb_err *e)
{
	char tmp[1024];
	snprintf(tmp, sizeof tmp, "%s", o->out);
	for (char *p = tmp + 1; *p; p++)
		if (*p == '/') {
			*p = 0;
			mkdir(tmp, 0777);
			*p = '/';
		}
	if (mkdir(tmp, 0777) && errno != EEXIST)
		return sb_errf(e, SB_EIO, "%s: cannot create directory: %s", o->out, strerror(errno));
	return 0;
}

FILE *cli_fopen(const an_opts *o, const char *name, char *path, size_t len, sb_err *e)
{
	snprintf(path, len, "%s/%s", o->out, name);
	FILE *f = fopen(path, "w");
	if (!f)
		sb_errf(e, SB_EIO, "%s: cannot write: %s", path, strerror(errno));
	return f;
}

void csv_str(FILE *f, const char *s)
{
	fputc('"', f);
	for (; *s; s++) {
		if (*s == '"')
			fputc('"', f);
		fputc(*s, f);
	}
	fputc('"', f);
}

void gp_str(FILE *f, const char *s)
{
	fputc('\'', f);
	for (; *s; s++) {
		if (*s == '\'')
			fputc('\'', f);
		fputc(*s, f);
	}
	fputc('\'', f);
}

FILE *gp_open(const an_opts *o, const char *name, int w, int h, char *script, char *png, size_t len, sb_err *e)
{
	char n[256];
	snprintf(n, sizeof n, "%s.gp", name);
	FILE *f = cli_fopen(o, n, script, len, e);
	if (!f)
		return NULL;
	snprintf(png, len, "%s/%s.png", o->out, name);
	/* data files and the PNG are named relative to the output directory */
	fprintf(f, "cd ");
	gp_str(f, o->out);
	fprintf(f, "\nset terminal pngcairo size %d,%d font 'sans,10'\nset output '%s.png'\n", w, h, name);
	fprintf(f, "set datafile separator ','\nset termoption noenhanced\nset grid\nset key outside right top\n");
	return f;
}

int gp_run(const char *script, const char *png, sb_err *e)
{
	unlink(png);
	char *argv[] = {"gnuplot", (char *)script, NULL};
	pid_t pid;
	posix_spawn_file_actions_t fa;
	posix_spawn_file_actions_init(&fa);
	/* gnuplot's warnings about empty plots are not ours to print */
	posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", 0, 0);
	int rc = posix_spawnp(&pid, "gnuplot", &fa, NULL, argv, environ);
	posix_spawn_file_actions_destroy(&fa);
	if (rc)
		return sb_errf(e, SB_EIO, "cannot run gnuplot: %s", strerror(rc));
	int st;
	if (waitpid(pid, &st, 0) < 0 || !WIFEXITED(st) || WEXITSTATUS(st))
		return sb_errf(e, SB_EIO, "%s: gnuplot failed", script);
	if (access(png, F_OK))
		return sb_errf(e, SB_EIO, "%s: gnuplot wrote no %s", script, png);
	return 0;
}
