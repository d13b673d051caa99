/* dumpflux_main.c - bin/dumpflux: Phi(D) of a run from another code's position dump,
 * counted by the engine's own crossing code, beside the engine's own; and the two
 * codes compared over an ensemble of beds (tests/bench/validate_lammps.sh); and the
 * exact small-sample statistics of that script's parts B-D (stats: analysis/measure/twocode.h).
 * Only this file prints and exits. */
#include <errno.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flux.h"
#include "provenance.h"
#include "fsutil.h"
#include "h5id.h"
#include "h5read.h"
#include "quantile.h"
#include "runvals.h"
#include "measure/dumpflux.h"
#include "measure/lowerrow.h"
#include "measure/pairdiff.h"
#include "measure/twocode.h"

#define TC_STR2(x) #x
#define TC_STR(x) TC_STR2(x)

static const char *HELP =
	"usage: dumpflux run RUN.h5 [--skip FRAC] [--periods]\n"
	"       dumpflux dump DUMP --like RUN.h5 --amplitude A --frequency F --dt DT\n"
	"                [--skip FRAC] [--periods]\n"
	"       dumpflux compare [--level L] A1.tsv ... -- B1.tsv ...\n"
	"       dumpflux stats binom K N | fisher K1 N1 K2 N2 | sign K N | paired FILE |\n"
	"                power N P0 | verdict PA PB PAB [--level L]\n\n"
	"The flux Phi(D) (docs/model.md, \"Flux Phi(D)\") of one run as a profile: per height\n"
	"line its time mean over the periods after the first FRAC of them (default 0.2, as\n"
	"the analysis tools), in particles per period. Prints TSV: line, height (cm above the\n"
	"floor), phi; with --periods one row per period instead: time, frequency, then phi of\n"
	"every line.\n\n"
	"  run    the engine's own record of a run file (flux = yes), read with flux_read.\n"
	"  dump   a text dump (LAMMPS `dump custom` with id type x y radius) holding the\n"
	"         positions at every stroboscopic sample (frame k at the first step at or\n"
	"         after k/F; checked) of a run of the same bed as RUN.h5, an engine run with\n"
	"         flux = yes whose settled surface height and lines are taken. The crossings\n"
	"         are counted by the engine's code (core/model/crossing.c) after the box offset\n"
	"         A sin(2 pi F step DT) is taken off the mobile disks' y. A comment line\n"
	"         reports the frames, the wall faces, the largest offset taken off, and how\n"
	"         the wall disks moved: wall_drive_dev (against the drive: ~0 for LAMMPS's\n"
	"         moving walls) and wall_rest_dev (against rest: 0 for walls at rest).\n"
	"  compare  the profiles A_b of one code and B_b of the other for the same beds b\n"
	"         (paired in the order given), TSV per line: l, height (mean of A's), mean A\n"
	"         and its interval half-width, mean B and half-width, mean difference A - B\n"
	"         and half-width (Student t over the beds at level L, default 0.95), the\n"
	"         difference's t, agree (1: the difference's interval holds 0); then\n"
	"         '# key value' lines: beds, lines, disagree (lines), max_abs_t, chi2_per_line\n"
	"         (mean t^2 over the lines with crossings), and their p-values from the exact\n"
	"         sign-flip test over the beds (p_max_abs_t, p_chi2, perms).\n"
	"  stats  exact small-sample statistics of two codes run on the same beds\n"
	"         (analysis/measure/twocode.h; tests/bench/validate_lammps.sh, parts B-D), at level L\n"
	"         (default 0.95):\n"
	"         binom K N    'k n fraction lo hi': K of N with its Clopper-Pearson interval;\n"
	"         fisher K1 N1 K2 N2  the two-sided Fisher exact p of K1 of N1 against K2 of N2;\n"
	"         sign K N     the two-sided exact binomial p of K of N at 1/2 (the sign test;\n"
	"                      McNemar's exact test with K the discordant beds one way, N all\n"
	"                      discordant beds);\n"
	"         paired FILE  rows 'a b', one bed each ('#' comments), as '# key value' lines:\n"
	"                      n, level; mean_a, half_a, median_a and the same of b: each\n"
	"                      column's mean, its Student-t half-width and median; of the\n"
	"                      difference d = b - a: mean_d, half_d, sd_d, median_d, detect80\n"
	"                      (the mean difference a two-sided paired t-test at 1 - L detects\n"
	"                      with 80 % power at this sd), pos, neg, zero (the signs of d),\n"
	"                      p_sign (sign test), p_flip (exact sign-flip test of the mean\n"
	"                      d), p_wilcoxon (exact signed-rank test), exact (1: all 2^m sign\n"
	"                      patterns of the m nonzero d; 0: 2^20 random ones);\n"
	"         power N P0   'up down': the smallest differences up and down from the\n"
	"                      fraction P0 that McNemar's exact test at 1 - L detects with\n"
	"                      80 % power over N beds, the codes' outcomes independent given\n"
	"                      the bed (nan: none within [0, 1]); N at most " TC_STR(TC_MCNEMAR_MAX) ".\n"
	"         verdict PA PB PAB [EFFECT [OWN PAIRED]]  the one sentence on an effect across\n"
	"                      the codes (tc_verdict_text): from its p in shakebox (PA) and in\n"
	"                      LAMMPS (PB), each code's own test (OWN, default Fisher), and the\n"
	"                      codes' paired test (PAB, PAIRED, default McNemar; the smallest p\n"
	"                      of its comparisons), at 1 - L: the codes differ; they agree and\n"
	"                      each shows EFFECT; they agree and neither can decide; or they are\n"
	"                      not told apart but one alone shows it.\n";

static int usage(const char *msg)
{
	fprintf(stderr, "dumpflux: %s\n(dumpflux --help for the usage)\n", msg);
	return 1;
}

static int num(const char *s, double *v)
{
	char *end;
	errno = 0;
	*v = strtod(s, &end);
	return end != s && !*end && !errno && isfinite(*v);
}

static void print_flux(const flux_data *d, double skip, int periods, const char *what)
{
	if (periods) {
		printf("# %s: %zu periods x %zu lines; time frequency phi[0..%zu]\n", what, d->P, d->L,
		       d->L ? d->L - 1 : 0);
		for (size_t p = 0; p < d->P; p++) {
			printf("%.17g\t%.17g", d->t[p], d->f[p]);
			for (size_t l = 0; l < d->L; l++)
				printf("\t%.17g", d->phi[p * d->L + l]);
			printf("\n");
		}
		return;
	}
	flux_opts fo = FLUX_OPTS_DEFAULT;
	fo.skip = skip;
	double *prof = malloc(sizeof *prof * (d->L ? d->L : 1));
	if (!prof) {
		fprintf(stderr, "dumpflux: out of memory\n");
		exit(8);
	}
	flux_profile(d, &fo, prof);
	const size_t p0 = flux_first(d, &fo);
	printf("# %s: surface %.17g cm, %zu lines, periods %zu, averaged %zu (after the first %zu)\n", what,
	       d->surface, d->L, d->P, d->P > p0 ? d->P - p0 : 0, p0);
	printf("# line\theight\tphi\n");
	for (size_t l = 0; l < d->L; l++)
		printf("%zu\t%.17g\t%.17g\n", l, d->h[l], prof[l]);
	free(prof);
}

static int cmd_run(int argc, char **argv)
{
	const char *run = NULL;
	double skip = 0.2;
	int periods = 0;
	for (int i = 0; i < argc; i++) {
		if (!strcmp(argv[i], "--skip") && i + 1 < argc) {
			if (!num(argv[++i], &skip) || skip < 0 || skip >= 1)
				return usage("--skip: expected a fraction in [0, 1)");
		} else if (!strcmp(argv[i], "--periods"))
			periods = 1;
		else if (argv[i][0] == '-' || run)
			return usage("run: unknown or extra argument");
		else
			run = argv[i];
	}
	if (!run)
		return usage("run: which run file?");
	flux_data d;
	sb_err e = {0};
	/* the file is a run file of this engine, as its seal, format and digest say, with
	 * values the engine can have written, before a value of it is printed
	 * (docs/inputs.md, "Run files"); no run id to hold it to: it is named by hand */
	hid_t f;
	int note = H5ID_OK;
	if (h5r_open(run, &f, &e) || h5id_check(f, run, NULL, &note, &e) || runvals_check(f, run, &e)) {
		h5r_close(f);
		fprintf(stderr, "dumpflux: %s\n", e.msg);
		return SB_EIO;
	}
	h5r_close(f);
	if (note != H5ID_OK)
		fprintf(stderr, "note: %s: format %s: read with %s (docs/inputs.md, \"Run files\")\n", run,
			note == H5ID_UNSEALED ? H5ID_FORMAT_OLD : H5ID_FORMAT_OLD3,
			note == H5ID_UNSEALED ? "nothing checked" : "its attributes' digest checked, no seal");
	if (flux_read(run, &d, &e)) {
		fprintf(stderr, "dumpflux: %s\n", e.msg);
		return e.code;
	}
	print_flux(&d, skip, periods, run);
	flux_free(&d);
	return 0;
}

static int cmd_dump(int argc, char **argv)
{
	const char *dump = NULL, *like = NULL;
	double skip = 0.2;
	int periods = 0;
	dumpflux_opts o = {.amplitude = NAN, .frequency = NAN, .dt = NAN};
	for (int i = 0; i < argc; i++) {
		const char *a = argv[i];
		double *v = !strcmp(a, "--amplitude") ? &o.amplitude
			    : !strcmp(a, "--frequency") ? &o.frequency
			    : !strcmp(a, "--dt")        ? &o.dt
			    : !strcmp(a, "--skip")      ? &skip
							: NULL;
		if (v && i + 1 < argc) {
			if (!num(argv[++i], v))
				return usage("expected a number after an option");
		} else if (!strcmp(a, "--like") && i + 1 < argc)
			like = argv[++i];
		else if (!strcmp(a, "--periods"))
			periods = 1;
		else if (a[0] == '-' || dump)
			return usage("dump: unknown or extra argument, or an option without its value");
		else
			dump = a;
	}
	if (!dump || !like || isnan(o.amplitude) || isnan(o.frequency) || isnan(o.dt))
		return usage("dump: needs DUMP, --like RUN.h5, --amplitude, --frequency and --dt");
	if (skip < 0 || skip >= 1)
		return usage("--skip: expected a fraction in [0, 1)");
	flux_data ref, d;
	sb_err e = {0};
	if (flux_read(like, &ref, &e)) {
		fprintf(stderr, "dumpflux: %s\n", e.msg);
		return e.code;
	}
	o.surface = ref.surface;
	o.nlines = (int)ref.L;
	dumpflux_info info;
	int rc = dumpflux_read(dump, &o, &d, &info, &e);
	if (!rc)
		for (size_t l = 0; l < d.L; l++)
			if (d.h[l] != ref.h[l]) {
				rc = SB_EIO;
				fprintf(stderr, "dumpflux: line %zu at %.17g cm, the engine's at %.17g cm (%s)\n", l, d.h[l],
					ref.h[l], like);
				break;
			}
	flux_free(&ref);
	if (rc) {
		if (e.code)
			fprintf(stderr, "dumpflux: %s\n", e.msg);
		return rc;
	}
	printf("# frames %ld mobile %ld walls %ld x0 %.17g x1 %.17g ybox_max %.6g wall_rest_dev %.6g wall_drive_dev %.6g\n",
	       info.frames, info.mobile, info.walls, info.x0, info.x1, info.ybox_max, info.wall_rest_dev,
	       info.wall_drive_dev);
	print_flux(&d, skip, periods, dump);
	flux_free(&d);
	return 0;
}

/* A text input, a regular file only (docs/inputs.md, "Files": a FIFO would hang the
 * read, a device never end); NULL when refused, said on stderr. */
static FILE *open_input(const char *path, const char *what)
{
	sb_err e = {0};
	FILE *f = fs_open_input(path, what, 0, SB_EIO, &e);
	if (!f)
		fprintf(stderr, "dumpflux: %s\n", e.msg);
	return f;
}

/* A profile TSV (line, height, phi) into h[], phi[] (L values; *L set by the first). */
static int read_profile(const char *path, size_t *L, double **h, double **phi)
{
	FILE *f = open_input(path, "profile");
	if (!f)
		return 2;
	char line[512];
	size_t n = 0, cap = 0;
	double *hh = NULL, *pp = NULL;
	int rc = 0;
	while (fgets(line, sizeof line, f)) {
		if (line[0] == '#' || line[0] == '\n')
			continue;
		size_t l;
		double a, b;
		if (sscanf(line, "%zu %lf %lf", &l, &a, &b) != 3 || l != n || !isfinite(a) || !isfinite(b)) {
			fprintf(stderr, "dumpflux: %s: line %zu of the profile: expected 'l height phi'\n", path, n);
			rc = 2;
			break;
		}
		if (n == cap) {
			cap = cap ? 2 * cap : 128;
			double *x = realloc(hh, sizeof *x * cap), *y = x ? realloc(pp, sizeof *y * cap) : NULL;
			if (x)
				hh = x;
			if (y)
				pp = y;
			if (!x || !y) {
				rc = 8;
				break;
			}
		}
		hh[n] = a;
		pp[n] = b;
		n++;
	}
	fclose(f);
	if (!rc && (n == 0 || (*L && n != *L))) {
		fprintf(stderr, "dumpflux: %s: %zu lines, expected %zu\n", path, n, *L);
		rc = 2;
	}
	if (rc) {
		free(hh);
		free(pp);
		return rc;
	}
	*L = n;
	*h = hh;
	*phi = pp;
	return 0;
}

static int cmd_compare(int argc, char **argv)
{
	double level = 0.95;
	const char *fa[4096], *fb[4096];
	size_t na = 0, nb = 0;
	int side = 0;
	for (int i = 0; i < argc; i++) {
		if (!strcmp(argv[i], "--level") && i + 1 < argc) {
			if (!num(argv[++i], &level) || !(level > 0 && level < 1))
				return usage("--level: expected a number in (0, 1)");
		} else if (!strcmp(argv[i], "--"))
			side++;
		else if (side == 0 && na < 4096)
			fa[na++] = argv[i];
		else if (side == 1 && nb < 4096)
			fb[nb++] = argv[i];
		else
			return usage("compare: too many files or '--' twice");
	}
	if (na != nb || na < 2)
		return usage("compare: give the same number (2 or more) of profiles on each side of '--'");
	size_t L = 0;
	double *A = NULL, *B = NULL, *H = NULL;
	int rc = 0;
	for (size_t k = 0; k < 2 * na && !rc; k++) {
		double *h, *p;
		rc = read_profile(k < na ? fa[k] : fb[k - na], &L, &h, &p);
		if (rc)
			break;
		if (!A) {
			A = calloc(na * L, sizeof *A);
			B = calloc(na * L, sizeof *B);
			H = calloc(L, sizeof *H);
			if (!A || !B || !H)
				rc = 8;
		}
		if (!rc) {
			double *dst = k < na ? A + k * L : B + (k - na) * L;
			memcpy(dst, p, sizeof *p * L);
			if (k < na)
				for (size_t l = 0; l < L; l++)
					H[l] += h[l] / (double)na;
		}
		free(h);
		free(p);
	}
	pd_result r;
	sb_err e = {0};
	if (!rc && pd_compare(na, L, A, B, level, &r, &e)) {
		fprintf(stderr, "dumpflux: %s\n", e.msg);
		rc = e.code;
	}
	if (!rc) {
		printf("# l\theight\tmean_a\thalf_a\tmean_b\thalf_b\tmean_diff\thalf_diff\tt\tagree\n");
		for (size_t l = 0; l < L; l++)
			printf("%zu\t%.6f\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.4g\t%d\n", l, H[l], r.ma[l], r.ha[l], r.mb[l],
			       r.hb[l], r.md[l], r.hd[l], r.t[l], r.agree[l]);
		printf("# beds %zu\n# level %g\n# lines %zu\n# lines_with_crossings %zu\n# disagree %d\n", r.n, r.level, r.L,
		       r.lines_used, r.ndis);
		printf("# max_abs_t %.4g\n# chi2_per_line %.4g\n# p_max_abs_t %.4g\n# p_chi2 %.4g\n# perms %ld%s\n", r.maxt,
		       r.chi2, r.p_maxt, r.p_chi2, r.perms, r.exact ? " (all sign patterns)" : " (random sign patterns)");
		pd_free(&r);
	}
	free(A);
	free(B);
	free(H);
	return rc;
}

/* a whole number >= 0 */
static int count(const char *s, long *v)
{
	double x;
	if (!num(s, &x) || x < 0 || x > 1e9 || x != floor(x))
		return 0;
	*v = (long)x;
	return 1;
}

static double tq(double level, size_t n)
{
	return n > 1 ? quant_student(level, (double)(n - 1)) : NAN;
}

static int cmp_double(const void *a, const void *b)
{
	const double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

/* mean, Student-t half-width, sd and median of v[n] (v is sorted) */
static void describe(double *v, size_t n, double level, double *mean, double *half, double *sd, double *median)
{
	double s = 0, q = 0;
	for (size_t i = 0; i < n; i++)
		s += v[i];
	*mean = s / (double)n;
	for (size_t i = 0; i < n; i++)
		q += (v[i] - *mean) * (v[i] - *mean);
	*sd = n > 1 ? sqrt(q / (double)(n - 1)) : NAN;
	*half = tq(level, n) * *sd / sqrt((double)n);
	qsort(v, n, sizeof *v, cmp_double);
	*median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static int stats_paired(const char *path, double level)
{
	FILE *f = open_input(path, "paired file");
	if (!f)
		return 2;
	char line[512];
	size_t n = 0, cap = 0, row = 0;
	double *a = NULL, *b = NULL, *d = NULL;
	int rc = 0;
	while (fgets(line, sizeof line, f)) {
		row++;
		if (line[0] == '#' || line[strspn(line, " \t\r\n")] == 0)
			continue;
		double x, y;
		char extra;
		if (sscanf(line, "%lf %lf %c", &x, &y, &extra) != 2 || !isfinite(x) || !isfinite(y)) {
			fprintf(stderr, "dumpflux: %s:%zu: expected two numbers 'a b'\n", path, row);
			rc = 2;
			break;
		}
		if (n == cap) {
			cap = cap ? 2 * cap : 64;
			double *na = realloc(a, sizeof *na * cap);
			if (na)
				a = na;
			double *nb = realloc(b, sizeof *nb * cap);
			if (nb)
				b = nb;
			double *nd = realloc(d, sizeof *nd * cap);
			if (nd)
				d = nd;
			if (!na || !nb || !nd) {
				rc = 8;
				break;
			}
		}
		a[n] = x;
		b[n] = y;
		d[n] = y - x;
		n++;
	}
	fclose(f);
	if (!rc && n < 2) {
		fprintf(stderr, "dumpflux: %s: %zu pairs, need 2 or more\n", path, n);
		rc = 2;
	}
	if (!rc) {
		long pos = 0, neg = 0;
		for (size_t i = 0; i < n; i++) {
			pos += d[i] > 0;
			neg += d[i] < 0;
		}
		double pf, pw;
		int ex1, ex2;
		sb_err e = {0};
		if (tc_flip_p(d, n, 0, &pf, &ex1, &e) || tc_flip_p(d, n, 1, &pw, &ex2, &e)) {
			fprintf(stderr, "dumpflux: %s: %s\n", path, e.msg);
			rc = e.code;
		} else {
			double m, h, sd, med;
			printf("# n %zu\n# level %g\n", n, level);
			describe(a, n, level, &m, &h, &sd, &med);
			printf("# mean_a %.6g\n# half_a %.6g\n# median_a %.6g\n", m, h, med);
			describe(b, n, level, &m, &h, &sd, &med);
			printf("# mean_b %.6g\n# half_b %.6g\n# median_b %.6g\n", m, h, med);
			describe(d, n, level, &m, &h, &sd, &med);
			const double det = (tq(level, n) + gsl_cdf_tdist_Pinv(0.8, (double)(n - 1))) * sd / sqrt((double)n);
			printf("# mean_d %.6g\n# half_d %.6g\n# sd_d %.6g\n# median_d %.6g\n# detect80 %.6g\n", m, h, sd,
			       med, det);
			printf("# pos %ld\n# neg %ld\n# zero %ld\n# p_sign %.6g\n# p_flip %.6g\n# p_wilcoxon %.6g\n"
			       "# exact %d\n",
			       pos, neg, (long)n - pos - neg, tc_sign_p(pos < neg ? pos : neg, pos + neg), pf, pw, ex1 && ex2);
		}
	}
	free(a);
	free(b);
	free(d);
	return rc;
}

static int cmd_stats(int argc, char **argv)
{
	double level = 0.95;
	const char *arg[8];
	int na = 0;
	for (int i = 0; i < argc; i++) {
		if (!strcmp(argv[i], "--level") && i + 1 < argc) {
			if (!num(argv[++i], &level) || !(level > 0 && level < 1))
				return usage("--level: expected a number in (0, 1)");
		} else if (na < 8)
			arg[na++] = argv[i];
		else
			return usage("stats: too many arguments");
	}
	long v[4];
	const char *what = na ? arg[0] : "";
	const int want = !strcmp(what, "binom") || !strcmp(what, "sign") ? 2
			 : !strcmp(what, "fisher")                     ? 4
			 : !strcmp(what, "paired")                     ? -1
			 : !strcmp(what, "power")                      ? -2
			 : !strcmp(what, "verdict")                    ? -3
								       : 0;
	if (!want)
		return usage("stats: which statistic: binom, fisher, sign, paired, power or verdict?");
	if (want == -3) {
		double p[3];
		if (na != 4 && na != 5 && na != 7)
			return usage("stats verdict: PA PB PAB [EFFECT [OWN PAIRED]] (the effect's p in shakebox and in LAMMPS, "
				     "the codes' paired p)");
		for (int i = 0; i < 3; i++)
			if (!num(arg[i + 1], &p[i]) || !(p[i] >= 0 && p[i] <= 1))
				return usage("stats verdict: PA PB PAB are p-values in [0, 1]");
		char t[800];
		tc_verdict_text(p[0], p[1], p[2], 1 - level, "shakebox", "LAMMPS", na >= 5 ? arg[4] : "the effect",
				na == 7 ? arg[5] : "Fisher", na == 7 ? arg[6] : "McNemar", t, sizeof t);
		printf("%s\n", t);
		return 0;
	}
	if (want == -1)
		return na == 2 ? stats_paired(arg[1], level) : usage("stats paired: one file of rows 'a b'");
	if (want == -2) {
		double p0;
		/* the sum grows as N^2 per difference tried: bounded, at most a few seconds */
		if (na != 3 || !count(arg[1], &v[0]) || v[0] < 1 || v[0] > TC_MCNEMAR_MAX || !num(arg[2], &p0) || p0 < 0 ||
		    p0 > 1)
			return usage("stats power: N (beds, 1 to " TC_STR(TC_MCNEMAR_MAX) ") and P0 (a fraction in [0, 1])");
		printf("%.3f\t%.3f\n", tc_mcnemar_detect(v[0], p0, 1, 1 - level, 0.8),
		       tc_mcnemar_detect(v[0], p0, -1, 1 - level, 0.8));
		return 0;
	}
	if (na != want + 1)
		return usage("stats: binom K N, sign K N, fisher K1 N1 K2 N2");
	for (int i = 0; i < want; i++)
		if (!count(arg[i + 1], &v[i]))
			return usage("stats: counts are whole numbers >= 0");
	if (v[0] > v[1] || (want == 4 && v[2] > v[3]))
		return usage("stats: a count K is larger than its N");
	if (!strcmp(what, "binom")) {
		double lo, hi;
		if (v[1] < 1)
			return usage("stats binom: N >= 1");
		quant_clopper_pearson(v[0], v[1], level, &lo, &hi);
		printf("%ld\t%ld\t%.6g\t%.6g\t%.6g\n", v[0], v[1], (double)v[0] / (double)v[1], lo, hi);
	} else if (!strcmp(what, "sign"))
		printf("%.6g\n", tc_sign_p(v[0], v[1]));
	else {
		if (v[1] < 1 || v[3] < 1)
			return usage("stats fisher: N1, N2 >= 1");
		printf("%.6g\n", lowerrow_fisher_p(v[0], v[1], v[2], v[3]));
	}
	return 0;
}

int main(int argc, char **argv)
{
	gsl_set_error_handler_off(); /* statuses are checked: GSL's default handler aborts */
	if (argc >= 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
		fputs(HELP, stdout);
		return 0;
	}
	if (argc == 2 && !strcmp(argv[1], "--version")) {
		printf("dumpflux (%s)\n", prov_version());
		return 0;
	}
	if (argc < 2)
		return usage("which command: run, dump, compare or stats?");
	sb_err we = {0};
	if (h5r_walk_env(&we)) /* it would refuse every run file */
		return usage(we.msg);
	if (!strcmp(argv[1], "run"))
		return cmd_run(argc - 2, argv + 2);
	if (!strcmp(argv[1], "dump"))
		return cmd_dump(argc - 2, argv + 2);
	if (!strcmp(argv[1], "compare"))
		return cmd_compare(argc - 2, argv + 2);
	if (!strcmp(argv[1], "stats"))
		return cmd_stats(argc - 2, argv + 2);
	return usage("unknown command (run, dump, compare, stats)");
}
