/* cli.c - shared options, paths, grouping keys, CSV and gnuplot helpers. */
#include "cli.h"

#include "dirs.h"
#include "drive.h"
#include "fsutil.h"
#include "inifile.h"
#include "label.h"
#include "layout.h"
#include "num.h"
#include "words.h"

#include <errno.h>
#include <getopt.h>
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

/* Every option some tool takes; a tool accepts the first NCOMMON and its own
 * (cli_parse's allowed). The flags take no value. */
static const char *const OPTS[] = {"help", "db", "runs", "out", "no-plot", "no-store", "all-versions",
				   "by", "band", "skip", "threshold", "boot", "seed", "level", "bins",
				   "smooth", "freq", "ratio", "where", NULL};
enum { NCOMMON = 7 };

static int is_flag(const char *name)
{
	return !strcmp(name, "help") || !strcmp(name, "no-plot") || !strcmp(name, "no-store") ||
	       !strcmp(name, "all-versions");
}

/* the options that say where output goes, or whether it is drawn or stored: not part
 * of what a tool computes (cli_options) */
static int is_output(const char *name)
{
	return !strcmp(name, "help") || !strcmp(name, "db") || !strcmp(name, "runs") || !strcmp(name, "out") ||
	       !strcmp(name, "no-plot") || !strcmp(name, "no-store");
}

static int allowed_opt(const char *allowed, const char *name)
{
	char pat[64];
	for (int i = 0; i < NCOMMON; i++)
		if (!strcmp(OPTS[i], name))
			return 1;
	snprintf(pat, sizeof pat, " %s ", name);
	return strstr(allowed, pat) != NULL;
}

int cli_distance(const char *a, const char *b)
{
	return words_distance(a, b);
}

const char *cli_nearest(const char *name, const char *allowed)
{
	const char *best = NULL;
	int bd = 1 << 20;
	for (int i = 0; OPTS[i]; i++) {
		if (!allowed_opt(allowed, OPTS[i]))
			continue;
		const int d = cli_distance(name, OPTS[i]);
		if (d < bd) {
			bd = d;
			best = OPTS[i];
		}
	}
	/* a guess further away than a third of the word (at least one edit) is noise */
	const int len = (int)strlen(name), lim = len >= 6 ? len / 3 : 1;
	return bd <= lim ? best : NULL;
}

static int num(sb_err *e, const char *opt, const char *s, double lo, double hi, double *v)
{
	double x;
	if (num_real(s, &x) || !(x >= lo && x <= hi))
		return sb_errf(e, SB_EUSAGE, "--%s: expected a number in [%g, %g], got '%s'", opt, lo, hi, s);
	*v = x;
	return 0;
}

/* Option name = value v into o (the paths into db, runs, out). */
static int set_opt(an_opts *o, const char *name, const char *v, const char **db, const char **runs,
		   const char **out, sb_err *e)
{
	double x = 0;
	if (!strcmp(name, "no-plot"))
		o->no_plot = 1;
	else if (!strcmp(name, "no-store"))
		o->no_store = 1;
	else if (!strcmp(name, "all-versions"))
		o->all_versions = 1;
	else if (!strcmp(name, "db"))
		*db = v;
	else if (!strcmp(name, "runs"))
		*runs = v;
	else if (!strcmp(name, "out"))
		*out = v;
	else if (!strcmp(name, "boot")) {
		if (num(e, name, v, 0, 1e7, &x))
			return 1;
		o->boot = (long)x;
	} else if (!strcmp(name, "seed")) {
		if (num(e, name, v, 0, 4294967295.0, &x))
			return 1;
		o->seed = (unsigned long)x;
	} else if (!strcmp(name, "level")) {
		o->level_set = 1;
		return num(e, name, v, 0.5, 0.999, &o->level);
	}
	else if (!strcmp(name, "threshold")) {
		o->threshold_set = 1;
		return num(e, name, v, -1e12, 1e12, &o->threshold);
	} else if (!strcmp(name, "skip")) {
		o->skip_set = 1;
		return num(e, name, v, 0, 0.99, &o->skip);
	} else if (!strcmp(name, "bins")) {
		if (num(e, name, v, 1, 1000, &x))
			return 1;
		o->bins = (long)x;
	} else if (!strcmp(name, "smooth")) {
		if (num(e, name, v, 1, 100000, &x))
			return 1;
		o->smooth = (long)x;
	} else if (!strcmp(name, "where")) {
		const char *eq = strchr(v, '=');
		if (!eq || eq == v || (size_t)(eq - v) >= sizeof o->where_key[0] || strlen(eq + 1) >= sizeof o->where_val[0] ||
		    !eq[1])
			return sb_errf(e, SB_EUSAGE, "--where: expected KEY=VALUE, got '%s'", v);
		if (o->nwhere == 8)
			return sb_errf(e, SB_EUSAGE, "--where: at most 8 selections");
		snprintf(o->where_key[o->nwhere], sizeof o->where_key[0], "%.*s", (int)(eq - v), v);
		snprintf(o->where_val[o->nwhere], sizeof o->where_val[0], "%s", eq + 1);
		o->nwhere++;
	} else if (!strcmp(name, "ratio"))
		return num(e, name, v, 0, 1e6, &o->ratio);
	else if (!strcmp(name, "band")) {
		char buf[128], *c;
		o->band_set = 1;
		snprintf(buf, sizeof buf, "%s", v);
		if (!(c = strchr(buf, ':')))
			return sb_errf(e, SB_EUSAGE, "--band: expected LO:HI (fractions of the surface height), got '%s'", v);
		*c = 0;
		if (num(e, name, buf, 0, 2, &o->band_lo) || num(e, name, c + 1, 0, 2, &o->band_hi))
			return 1;
		if (o->band_lo > o->band_hi)
			return sb_errf(e, SB_EUSAGE, "--band: LO must not exceed HI, got '%s'", v);
	} else if (!strcmp(name, "by") || !strcmp(name, "freq")) {
		char buf[1024];
		snprintf(buf, sizeof buf, "%s", v);
		const int isby = name[0] == 'b';
		if (isby)
			o->nby = 0;
		for (char *sv, *t = strtok_r(buf, ",", &sv); t; t = strtok_r(NULL, ",", &sv)) {
			if (isby) {
				if (o->nby == AN_MAXKEYS || strlen(t) >= 48)
					return sb_errf(e, SB_EUSAGE, "--by: too many or too long keys");
				snprintf(o->by[o->nby++], 48, "%s", t);
			} else {
				if (o->nfreq == 16)
					return sb_errf(e, SB_EUSAGE, "--freq: at most 16 frequencies");
				if (num(e, name, t, 0, 1000, &o->freqs[o->nfreq]))
					return 1;
				o->nfreq++;
			}
		}
	}
	return 0;
}

/* The usage error of the option argument arg that getopt_long refused: unknown (with
 * the nearest option of this tool, or the note that another tool takes it), ambiguous,
 * without its value or with a value it does not take. */
static int bad_opt(const char *tool, const char *arg, const char *allowed, int missing, sb_err *e)
{
	char name[64];
	const char *s = arg[0] == '-' && arg[1] == '-' ? arg + 2 : arg[0] == '-' ? arg + 1 : arg;
	snprintf(name, sizeof name, "%.*s", (int)strcspn(s, "="), s);
	const int dashes = arg[1] == '-' ? 2 : 1;
	if (missing)
		return sb_errf(e, SB_EUSAGE, "--%s needs a value", name);
	int exact = 0, prefixed = 0;
	char cands[256] = "";
	for (int i = 0; OPTS[i]; i++) {
		if (!allowed_opt(allowed, OPTS[i]))
			continue;
		exact |= !strcmp(OPTS[i], name);
		if (*name && !strncmp(OPTS[i], name, strlen(name)) && strlen(cands) + strlen(OPTS[i]) + 5 < sizeof cands) {
			snprintf(cands + strlen(cands), sizeof cands - strlen(cands), "%s--%s", prefixed ? ", " : "", OPTS[i]);
			prefixed++;
		}
	}
	if (dashes == 2 && exact && s[strlen(name)] == '=')
		return sb_errf(e, SB_EUSAGE, "--%s takes no value", name);
	if (dashes == 2 && prefixed > 1)
		return sb_errf(e, SB_EUSAGE, "--%s: ambiguous option; one of %s", name, cands);
	for (int i = 0; dashes == 2 && OPTS[i]; i++)
		if (!strcmp(OPTS[i], name))
			return sb_errf(e, SB_EUSAGE, "--%s: not an option of %s (%s --help)", name, tool, tool);
	const char *near = cli_nearest(name, allowed);
	if (near)
		return sb_errf(e, SB_EUSAGE, "%.*s%s: unknown option; did you mean --%s?", dashes, "--", name, near);
	return sb_errf(e, SB_EUSAGE, "%.*s%s: unknown option (%s --help)", dashes, "--", name, tool);
}

/* The [campaign] name of a campaign file, read with the driver's INI reader (the
 * driver checks the file itself; here only the name is wanted). */
typedef struct camp_name {
	int in_campaign;
	char *out;
	size_t len;
} camp_name;

static int cn_section(void *user, const char *header, const char *name, int len, int line, sb_err *e)
{
	(void)header, (void)line, (void)e;
	((camp_name *)user)->in_campaign = len == 8 && !strncmp(name, "campaign", 8);
	return 0;
}

static int cn_key(void *user, const char *name, const char *value, int line, sb_err *e)
{
	(void)line, (void)e;
	camp_name *c = user;
	if (c->in_campaign && !strcmp(name, "name"))
		snprintf(c->out, c->len, "%s", value);
	return 0;
}

static int file_name(an_opts *o, an_camp *k, const char *arg, sb_err *e)
{
	camp_name c = {0, k->file_name, sizeof k->file_name};
	k->file_name[0] = 0;
	const inifile in = {arg, "campaign file", 100000, cn_section, cn_key, &c};
	if (inifile_read(&in, e))
		return e->code;
	if (!k->file_name[0] || strchr(k->file_name, '/'))
		return sb_errf(e, SB_EUSAGE, "%s: no [campaign] name = NAME in it (%s --help)", arg, o->tool);
	k->name = k->file_name;
	return 0;
}

/* A campaign of the command line: NAME, DIR/NAME (campaign names have no '/'), or a
 * campaign file FILE.campaign (its [campaign] name, in the runs directory of --runs). */
static int add_camp(an_opts *o, const char *arg, sb_err *e)
{
	if (o->ncamp == AN_MAXCAMP)
		return sb_errf(e, SB_EUSAGE, "'%s': at most %d campaigns (%s --help)", arg, AN_MAXCAMP, o->tool);
	an_camp *k = &o->camp[o->ncamp];
	const char *sl = strrchr(arg, '/');
	const size_t al = strlen(arg);
	k->runs[0] = 0;
	if (al > 9 && !strcmp(arg + al - 9, ".campaign")) {
		if (file_name(o, k, arg, e))
			return e->code;
		o->ncamp++;
		return 0;
	}
	k->name = sl ? sl + 1 : arg;
	if (!*k->name || *k->name == '.')
		return sb_errf(e, SB_EUSAGE, "'%s': expected a campaign's name, or DIR/NAME for one in the runs directory"
			       " DIR (%s --help)", arg, o->tool);
	if (sl && (size_t)(sl - arg) + 1 >= sizeof k->runs)
		return sb_errf(e, SB_EUSAGE, "path too long");
	if (sl)
		snprintf(k->runs, sizeof k->runs, "%.*s", sl == arg ? 1 : (int)(sl - arg), arg);
	o->ncamp++;
	return 0;
}

int cli_parse(an_opts *o, int argc, char **argv, const char *allowed, sb_err *e)
{
	o->ncamp = 0;
	o->campaign = NULL;
	const char *db = NULL, *runs = NULL, *out = NULL;
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
	/* the tool's options, for getopt_long: --opt value and --opt=value alike */
	struct option lo[sizeof OPTS / sizeof *OPTS];
	int nl = 0;
	for (int i = 0; OPTS[i]; i++)
		if (allowed_opt(allowed, OPTS[i]))
			lo[nl++] = (struct option){OPTS[i], is_flag(OPTS[i]) ? no_argument : required_argument, NULL, 256 + i};
	lo[nl] = (struct option){NULL, 0, NULL, 0};
	optind = 0; /* glibc: a full restart, also of a parse before this one */
	opterr = 0;
	int c;
	while ((c = getopt_long(argc, argv, ":h", lo, NULL)) != -1) {
		if (c == 'h' || c == 256) /* -h, --help */
			return -1;
		if (c == '?' && optopt > 0 && optopt < 256) {
			/* a short option: the word it is in is the one still being read, or the
			 * last one when it ended the word */
			const char *w = optind < argc && argv[optind][0] == '-' && strchr(argv[optind], optopt) ? argv[optind]
													: argv[optind - 1];
			return bad_opt(o->tool, w, allowed, 0, e);
		}
		if (c == '?' || c == ':')
			return bad_opt(o->tool, argv[optind - 1], allowed, c == ':', e);
		if (set_opt(o, OPTS[c - 256], optarg, &db, &runs, &out, e))
			return 1;
	}
	for (int i = optind; i < argc; i++)
		if (add_camp(o, argv[i], e))
			return 1;
	if (!o->ncamp)
		return sb_errf(e, SB_EUSAGE, "which campaign? (%s --help)", o->tool);
	/* bin/study's layout (lib/layout.h) */
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
	for (int c = 0; c < o->ncamp; c++) {
		an_camp *k = &o->camp[c];
		if (k->runs[0]) { /* DIR/NAME: its own runs directory and database */
			const int l = layout_db(k->runs, NULL, k->db, sizeof k->db);
			l1 = l > l1 ? l : l1;
		} else {
			snprintf(k->runs, sizeof k->runs, "%s", o->runs);
			snprintf(k->db, sizeof k->db, "%s", o->db);
		}
		for (int d = 0; d < c; d++)
			if (!strcmp(o->camp[d].name, k->name) && !strcmp(o->camp[d].db, k->db))
				return sb_errf(e, SB_EUSAGE, "campaign '%s' of %s given twice", k->name, k->db);
	}
	/* the first campaign's database holds the rows of the pooled ones too */
	snprintf(o->runs, sizeof o->runs, "%s", o->camp[0].runs);
	snprintf(o->db, sizeof o->db, "%s", o->camp[0].db);
	o->campaign = o->camp[0].name;
	if (o->ncamp > 1) {
		size_t l = 0;
		for (int c = 0; c < o->ncamp; c++)
			l += (size_t)snprintf(o->pooled + l, sizeof o->pooled - l, "%s%s", c ? "+" : "", o->camp[c].name);
		o->campaign = o->pooled;
	}
	if (out) {
		l2 = snprintf(o->out, sizeof o->out, "%s", out);
	} else {
		/* several campaigns: RUNS/A+B/analysis ('+' is in no campaign's name) */
		char dir[1200];
		layout_campaign(o->runs, o->campaign, dir, sizeof dir);
		l2 = layout_sub(dir, "analysis", o->out, sizeof o->out);
	}
	if (l1 >= (int)sizeof o->db || l2 >= (int)sizeof o->out - 300)
		return sb_errf(e, SB_EUSAGE, "path too long");
	return 0;
}

static int in_list(const char *const *l, const char *s)
{
	for (; l && *l; l++)
		if (!strcmp(*l, s))
			return 1;
	return 0;
}

/* Option name's value in effect into v (cli_options). */
static void opt_value(const an_opts *o, const char *name, char *v, size_t n)
{
	size_t l = 0;
	v[0] = 0;
	if (!strcmp(name, "all-versions"))
		snprintf(v, n, "%s", o->all_versions ? "yes" : "no");
	else if (!strcmp(name, "boot"))
		snprintf(v, n, "%ld", o->boot);
	else if (!strcmp(name, "seed"))
		snprintf(v, n, "%lu", o->seed);
	else if (!strcmp(name, "level"))
		snprintf(v, n, "%.15g", o->level);
	else if (!strcmp(name, "threshold"))
		snprintf(v, n, isnan(o->threshold) ? "halfway" : "%.15g", o->threshold);
	else if (!strcmp(name, "skip"))
		snprintf(v, n, "%.15g", o->skip);
	else if (!strcmp(name, "band"))
		snprintf(v, n, "%.15g:%.15g", o->band_lo, o->band_hi);
	else if (!strcmp(name, "bins"))
		snprintf(v, n, "%ld", o->bins);
	else if (!strcmp(name, "smooth"))
		snprintf(v, n, "%ld", o->smooth);
	else if (!strcmp(name, "ratio"))
		snprintf(v, n, isnan(o->ratio) ? "largest" : "%.15g", o->ratio);
	else if (!strcmp(name, "by")) {
		for (int i = 0; i < o->nby && l < n; i++)
			l += (size_t)snprintf(v + l, n - l, "%s%s", i ? "," : "", o->by[i]);
		if (o->nby < 0)
			snprintf(v, n, "axes");
	} else if (!strcmp(name, "freq")) {
		for (int i = 0; i < o->nfreq && l < n; i++)
			l += (size_t)snprintf(v + l, n - l, "%s%.15g", i ? "," : "", o->freqs[i]);
		if (!o->nfreq)
			snprintf(v, n, "all");
	} else if (!strcmp(name, "where")) {
		for (int i = 0; i < o->nwhere && l < n; i++)
			l += (size_t)snprintf(v + l, n - l, "%s%s=%s", i ? "," : "", o->where_key[i], o->where_val[i]);
		if (!o->nwhere)
			snprintf(v, n, "all");
	}
}

void cli_options(const an_opts *o, const char *allowed, char *buf, size_t n)
{
	size_t l = 0;
	buf[0] = 0;
	for (int i = 0; OPTS[i] && l < n; i++) {
		if (is_output(OPTS[i]) || !allowed_opt(allowed, OPTS[i]))
			continue;
		char v[1024];
		opt_value(o, OPTS[i], v, sizeof v);
		l += (size_t)snprintf(buf + l, n - l, "%s%s=%s", l ? " " : "", OPTS[i], v);
	}
}

void cli_keys(const an_opts *o, char axes[][48], int na, const char *const *always, const char *const *drop,
	      char keys[][48], int *nk)
{
	*nk = 0;
	if (o->nby >= 0) {
		for (int i = 0; i < o->nby; i++)
			scopy(keys[(*nk)++], 48, o->by[i]);
		return;
	}
	for (const char *const *a = always; a && *a && *nk < AN_MAXKEYS; a++)
		scopy(keys[(*nk)++], 48, *a);
	for (int i = 0; i < na && *nk < AN_MAXKEYS; i++) {
		int dup = 0;
		for (int j = 0; j < *nk; j++)
			dup |= !strcmp(keys[j], axes[i]);
		if (!dup && !in_list(drop, axes[i]) && strcmp(axes[i], "seed"))
			scopy(keys[(*nk)++], 48, axes[i]);
	}
}

int cli_outdir(const an_opts *o, sb_err *e)
{
	/* the engine's rule for what it writes (docs/output.md): the output directory is
	 * one, not a link to somewhere else (written through, it would put the files
	 * outside the runs directory) nor a FIFO or device */
	struct stat st;
	if (lstat(o->out, &st) == 0 && !S_ISDIR(st.st_mode))
		return sb_errf(e, SB_EIO, "%s: %s stands there, not a directory: nothing written (remove it, or give "
			       "--out)", o->out, fs_kind((unsigned)st.st_mode));
	if (dirs_make(o->out, e))
		return e->code;
	if (lstat(o->out, &st) || !S_ISDIR(st.st_mode)) /* one that came meanwhile */
		return sb_errf(e, SB_EIO, "%s: not a directory: nothing written", o->out);
	return 0;
}

int cli_open_out(const an_opts *o, const char *name, sb_file *out, sb_err *e)
{
	char path[sizeof out->path];
	const char *kind;
	snprintf(path, sizeof path, "%s/%s", o->out, name);
	/* only over nothing or a regular file: a link is not followed, a FIFO would hang
	 * the tool, a device swallow the table; refused before anything is written (the
	 * rename into place checks again, fs_commit) */
	if (!fs_replaceable(path, &kind))
		return sb_errf(e, SB_EIO, "%s: %s stands there, not a regular file: not written", path, kind);
	/* written under a temporary name beside it and renamed into place when complete
	 * (fsutil.h): a reader never sees half a table, a failed write keeps the old one */
	return fs_open_tmp(out, path, e);
}

int cli_close_out(sb_file *out, sb_err *e)
{
	if (!out->f)
		return 0;
	if (e->code) { /* an error on the way: the table is not complete */
		fs_abort(out);
		return e->code;
	}
	/* fs_commit's message names the file and the system's word ("No space left on
	 * device"); the temporary is gone either way */
	return fs_commit(out, e);
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

/* A figure's path: nothing or a regular file may stand there (fs_replaceable). */
static int gp_target(const char *path, sb_err *e)
{
	const char *kind;
	if (!fs_replaceable(path, &kind))
		return sb_errf(e, SB_EIO, "%s: %s stands there, not a regular file: not written", path, kind);
	return 0;
}

FILE *gp_open(const an_opts *o, const char *name, int w, int h, sb_file *script, char *png, size_t len, sb_err *e)
{
	char n[256], pdf[1400];
	snprintf(png, len, "%s/%s.png", o->out, name);
	snprintf(pdf, sizeof pdf, "%s/%s.pdf", o->out, name);
	/* gnuplot opens the figures itself, following what stands there: a node at
	 * either is refused before anything of the figure is written */
	if (gp_target(png, e) || gp_target(pdf, e))
		return NULL;
	snprintf(n, sizeof n, "%s.gp", name);
	if (cli_open_out(o, n, script, e))
		return NULL;
	FILE *f = script->f;
	/* data files and the figures are named relative to the output directory */
	fprintf(f, "cd ");
	gp_str(f, o->out);
	/* One figure, two files: the PNG to look at, the PDF (vector) for a paper. The PDF
	 * is the PNG's layout on w/100 x h/100 inches with 10-pt letters, so that scaled to
	 * a page's width (7 in) its letters are about 7 pt. The text is UTF-8 (Φ, 𝓡, f₀),
	 * taken literally (noenhanced: an underscore stays one). */
	/* gp_run has gnuplot draw into temporary names (gp_tmp, fs_tmp_name's suffix) that
	 * it renames into place; run by hand, the script writes the figures themselves */
	fprintf(f, "\nset encoding utf8\nset datafile separator ','\n"
		   "gp_tmp = exists('gp_tmp') ? gp_tmp : ''\n"
		   "do for [gp_fmt in 'png pdf'] {\n"
		   "if (gp_fmt eq 'png') {\n"
		   "  set terminal pngcairo size %d,%d font 'sans,10' noenhanced\n"
		   "} else {\n"
		   "  set terminal pdfcairo size %.2fin,%.2fin font 'sans,10' fontscale 1 noenhanced\n"
		   "}\n"
		   "set output '%s.'.gp_fmt.gp_tmp\n"
		   "unset object\nunset arrow\nunset label\nset grid lc rgb '#dddddd' lw 0.5 dt 1\nset key below height 1\n",
		w, h, w / 100.0, h / 100.0, name);
	/* The line types' colours: every one legible on white (a contrast of at least 3:1,
	 * docs/analysis.md "Common to every tool"); gnuplot's own fifth is a light yellow. */
	static const char *const pal[] = {"#0072b2", "#d55e00", "#009e73", "#882255",
					  "#6a3d9a", "#8c6d1f", "#000000", "#cc3311"};
	for (size_t i = 0; i < sizeof pal / sizeof *pal; i++)
		fprintf(f, "set linetype %zu lc rgb '%s'\n", i + 1, pal[i]);
	fprintf(f, "set linetype cycle %zu\n", sizeof pal / sizeof *pal);
	return f;
}

void gp_close(FILE *f)
{
	fprintf(f, "}\nset output\n");
}

void gp_xlabel(FILE *f, const char *key)
{
	char w[128];
	label_axis(w, sizeof w, key, key);
	fputs("set xlabel ", f);
	gp_str(f, w);
	fputc('\n', f);
}

void gp_gamma_axis(FILE *f, double A, double g, double f_lo, double f_hi)
{
	const double k = drive_gamma(A, 1, g), span = k * (f_hi * f_hi - f_lo * f_lo);
	/* about five ticks at 1, 2, 2.5 or 5 times a power of ten */
	double step = span > 0 ? pow(10, floor(log10(span / 5))) : 0.1;
	const double m = span > 0 ? span / 5 / step : 1;
	step *= m > 5 ? 5 : m > 2.5 ? 2.5 : m > 2 ? 2 : 1;
	fprintf(f, "set link x2 via %.17g*x**2 inverse sqrt(x/%.17g)\n"
		   "set x2tics %g format '%%g' nomirror\nset xtics nomirror\n"
		   "set x2label 'Γ = A(2πf)²/g'\n", k, k, step);
}

/* path's name with its extension replaced by ext */
static void with_ext(char *out, size_t n, const char *path, const char *ext)
{
	snprintf(out, n, "%s", path);
	char *dot = strrchr(out, '.'), *sl = strrchr(out, '/');
	if (dot && (!sl || dot > sl))
		*dot = 0;
	snprintf(out + strlen(out), n - strlen(out), ".%s", ext);
}

/* cairo stamps a PDF with the time it was written, so every regeneration of an
 * unchanged figure would differ; the stamp's digits become those of 1970-01-01 (the
 * same length: the offsets of the file's objects stay right). */
static char *find(char *buf, size_t n, const char *pat)
{
	const size_t m = strlen(pat);
	for (size_t i = 0; i + m <= n; i++)
		if (!memcmp(buf + i, pat, m))
			return buf + i;
	return NULL;
}

static int pdf_undate(const char *pdf, sb_err *e)
{
	FILE *f = fopen(pdf, "r+b");
	if (!f)
		return sb_errf(e, SB_EIO, "%s: %s", pdf, strerror(errno));
	char buf[1 << 16];
	const size_t n = fread(buf, 1, sizeof buf - 1, f);
	buf[n] = 0;
	/* the info dictionary is near the end; search the last 64 KiB as well */
	long base = 0;
	char *p = find(buf, n, "/CreationDate (D:");
	if (!p && !fseek(f, -(long)(sizeof buf - 1), SEEK_END)) {
		base = ftell(f);
		const size_t m = fread(buf, 1, sizeof buf - 1, f);
		p = find(buf, m, "/CreationDate (D:");
	}
	if (p) {
		static const char epoch[] = "19700101000000";
		char *d = p + 17;
		for (size_t i = 0; i < sizeof epoch - 1 && d[i] >= '0' && d[i] <= '9'; i++)
			d[i] = epoch[i];
		fseek(f, base + (long)(p - buf), SEEK_SET);
		fwrite(p, 1, 17 + sizeof epoch - 1, f);
	}
	if (fclose(f))
		return sb_errf(e, SB_EIO, "%s: %s", pdf, strerror(errno));
	return 0;
}

/* The temporary a figure is drawn into (fs_tmp_name), made here as an empty regular
 * file: gnuplot truncates what stands at it, and never meets a node planted there. */
static int gp_tmp_file(const char *path, char *tmp, size_t n, sb_err *e)
{
	fs_tmp_name(path, tmp, n);
	const int fd = fs_create(tmp, 0, e);
	if (fd < 0)
		return e->code;
	close(fd);
	return 0;
}

int gp_run(const char *script, const char *png, sb_err *e)
{
	char pdf[1400], tpng[1500], tpdf[1500], suffix[64], def[96];
	with_ext(pdf, sizeof pdf, png, "pdf");
	if (gp_target(png, e) || gp_target(pdf, e))
		return e->code;
	if (gp_tmp_file(png, tpng, sizeof tpng, e))
		return e->code;
	if (gp_tmp_file(pdf, tpdf, sizeof tpdf, e)) {
		unlink(tpng);
		return e->code;
	}
	snprintf(suffix, sizeof suffix, "%s", tpng + strlen(png));
	snprintf(def, sizeof def, "gp_tmp='%s'", suffix);
	char *argv[] = {"gnuplot", "-e", def, (char *)script, NULL};
	pid_t pid;
	posix_spawn_file_actions_t fa;
	posix_spawn_file_actions_init(&fa);
	/* gnuplot prints nothing on stdout that is ours to print; its stderr (warnings)
	 * stays the tool's, so that a figure drawn from nothing does not go unnoticed */
	posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", 0, 0);
	int rc = posix_spawnp(&pid, "gnuplot", &fa, NULL, argv, environ);
	posix_spawn_file_actions_destroy(&fa);
	int st, r = 0;
	struct stat sb;
	if (rc)
		r = sb_errf(e, SB_EIO, "cannot run gnuplot: %s", strerror(rc));
	else if (waitpid(pid, &st, 0) < 0 || !WIFEXITED(st) || WEXITSTATUS(st))
		r = sb_errf(e, SB_EIO, "%s: gnuplot failed", script);
	else if (stat(tpng, &sb) || !sb.st_size)
		r = sb_errf(e, SB_EIO, "%s: gnuplot wrote no %s", script, png);
	else if (stat(tpdf, &sb) || !sb.st_size)
		r = sb_errf(e, SB_EIO, "%s: gnuplot wrote no %s", script, pdf);
	else if (!(r = pdf_undate(tpdf, e)) && !(r = fs_rename_durable(tpng, png, e)))
		r = fs_rename_durable(tpdf, pdf, e);
	unlink(tpng); /* gone when renamed; a figure drawn in part is not left */
	unlink(tpdf);
	return r;
}
