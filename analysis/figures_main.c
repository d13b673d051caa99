/* figures_main.c - bin/figures: the paper's Fig. 1 (arrow field of the averaged
 * displacement), Fig. 3 (Phi versus height D with and without intruder) and Fig. 4
 * (intruder height versus time) from a campaign. Only this file prints and exits. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "acct.h"
#include "adb.h"
#include "cli.h"
#include "flux.h"
#include "h5read.h"

#define VERSION "3"

/* a run whose records are drawn: finished, or failed and used up to the failure */
#define USED(r) ((r)->use == AN_USED || (r)->use == AN_PARTLY)
#define MAXROWS 6

static int cmp_dbl(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* q-quantile of v[0..n) (sorts v); 0 when empty */
static double percentile(double *v, size_t n, double q)
{
	if (!n)
		return 0;
	qsort(v, n, sizeof *v, cmp_dbl);
	size_t k = (size_t)(q * (double)(n - 1) + 0.5);
	return v[k < n ? k : n - 1];
}

/* median of the positive entries of v[0..n), without changing v */
static double median_positive(const double *v, size_t n)
{
	double *t = malloc((n ? n : 1) * sizeof *t);
	size_t m = 0;
	if (!t)
		return 0;
	for (size_t i = 0; i < n; i++)
		if (v[i] > 0)
			t[m++] = v[i];
	double med = percentile(t, m, 0.5);
	free(t);
	return med;
}

static const char *HELP =
	"usage: figures CAMPAIGN [--db FILE] [--runs DIR] [--out DIR] [--freq F1,F2,...]\n"
	"               [--ratio R] [--skip FRAC] [--where KEY=VALUE ...] [--all-versions]\n"
	"               [--no-plot] [--no-store]\n\n"
	"The paper's figures from the fixed-frequency runs (ramp = none) of a\n"
	"campaign, one row per frequency (--freq, default every frequency in the campaign,\n"
	"at most 6) and two systems: without intruder (radius_ratio = 0) and with one of\n"
	"radius ratio R (--ratio, default the largest in the campaign; --ratio 0: without\n"
	"intruder only). Every replicate of a panel is averaged in. A campaign that sweeps\n"
	"other keys too (depth, width, ...) must say which runs to draw: --where KEY=VALUE\n"
	"(repeatable) keeps the runs whose KEY is VALUE; runs that still differ in a swept\n"
	"key other than frequency, radius_ratio and seed are an error, not an average.\n"
	"  fig1.png  Fig. 1: the displacement field (/field, field = yes): per cell the mean\n"
	"            displacement per period, weighted by the samples (count) of every block\n"
	"            and run (the grid of the panel's first run; the cells of the other\n"
	"            replicates, whose grids differ slightly, join it by their centres);\n"
	"            arrows on a common scale (the 95th percentile = 0.9 cell, longer\n"
	"            ones clipped; cells sampled < 1/5 of the median left out) in all panels;\n"
	"  fig3.png  Fig. 3: Phi(D), the time-mean flux per height line over the periods of\n"
	"            the panel's runs after the first FRAC of each (--skip, default 0.2),\n"
	"            against the line height D above the bottom (/flux, flux = yes), both\n"
	"            systems in one panel per frequency;\n"
	"  fig4.png  Fig. 4: the intruder's height y(t) (/intruder/trajectory, lab frame) at\n"
	"            the highest selected frequency, one panel per radius ratio > 0 (the\n"
	"            run with the lowest replicate), with its settled height and the surface.\n"
	"A figure without data is skipped with a note. A failed run is drawn with what it\n"
	"recorded before its failure (Fig. 3: its periods after the transient of the run as\n"
	"planned, pooled with the other runs' periods; Fig. 1: its samples); Fig. 4 draws a\n"
	"finished run when the panel has one. Per panel (frequency, radius ratio) the output,\n"
	"figures_accounting.csv and the stored rows count the runs used, failed (by status;\n"
	"used up to the failure or unusable), unreadable, pending and running.\n\n"
	"  --db FILE, --runs DIR, --out DIR   as for every tool (waiting --help)\n"
	"  --all-versions   also the runs of earlier versions of the campaign file (run.current = 0)\n"
	"  --no-plot, --no-store\n\n"
	"Writes fig1_field.csv, fig3_profile.csv, fig4_traj.csv and the PNGs; stores per\n"
	"panel of Fig. 3 in `analysis` (tool 'figures', grp 'fig3 f=F radius_ratio=R'):\n"
	"phi_max (largest |Phi(D)|), half_height (lowest D where |Phi| >= phi_max / 2: how\n"
	"deep the rolls reach), runs (used) and the accounting (runs_failed, runs_failed_used,\n"
	"..., as onset --help lists). Exit codes: 0 ok, 1 usage or no usable runs, 2 I/O.\n";

static int cmpd(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

static int near(double a, double b)
{
	return fabs(a - b) <= 1e-9 * fmax(1, fabs(b));
}

/* the run's KEY equals VALUE for every --where (as numbers when both are numbers) */
static int where_ok(const an_opts *o, const an_run *r)
{
	for (int w = 0; w < o->nwhere; w++) {
		const char *v = an_str(r, o->where_key[w]);
		if (!v)
			return 0;
		char *e1, *e2;
		const double a = strtod(v, &e1), b = strtod(o->where_val[w], &e2);
		const int numeric = e1 != v && !*e1 && e2 != o->where_val[w] && !*e2;
		if (numeric ? !near(a, b) : strcmp(v, o->where_val[w]) != 0)
			return 0;
	}
	return 1;
}

/* A panel averages its runs: runs that differ in another swept key (depth, width...)
 * would be averaged silently, so that is an error naming the key and two values. */
static int pooled_axis(adb *d, const an_opts *o, an_run *runs, int k, sb_err *e)
{
	char axes[AN_MAXKEYS][48];
	int na = 0;
	if (adb_axes(d, o->campaign, axes, AN_MAXKEYS, &na, e))
		return e->code;
	for (int a = 0; a < na; a++) {
		if (!strcmp(axes[a], "frequency") || !strcmp(axes[a], "radius_ratio") || !strcmp(axes[a], "seed"))
			continue;
		const char *first = an_str(&runs[0], axes[a]);
		for (int i = 1; i < k; i++) {
			const char *v = an_str(&runs[i], axes[a]);
			if (first && v && strcmp(first, v))
				return sb_errf(e, SB_EUSAGE,
					       "campaign '%s' sweeps %s (%s, %s, ...): a panel would average over it; "
					       "choose with --where %s=VALUE", o->campaign, axes[a], first, v, axes[a]);
		}
	}
	return 0;
}

/* What of a run the figures can draw (acct.h): with flux = yes its periods after the
 * transient (a failed run's up to the failure; none when it failed within the
 * transient), else its file up to its status time. */
static void classify(an_run *r, const flux_opts *fo)
{
	if (acct_classify(r)) {
		if (r->use == AN_UNREADABLE)
			fprintf(stderr, "figures: warning: %s (counted as unreadable)\n", r->why);
		return;
	}
	const int failed = !strcmp(r->state, "failed");
	const char *fl = an_str(r, "flux");
	const double dur = an_num(r, "duration", NAN);
	if (fl && !strcmp(fl, "yes")) {
		flux_data fd;
		if (flux_load(r, &fd)) {
			fprintf(stderr, "figures: warning: %s (counted as unreadable)\n", r->why);
			return;
		}
		size_t p0 = flux_first(&fd, fo);
		if (p0 >= fd.P)
			acct_set(r, AN_UNUSABLE, NAN, NAN, "%s%s%s: %zu periods recorded, none after the first %zu (transient)",
				 failed ? "failed (" : "finished", failed ? r->status : "", failed ? ")" : "", fd.P, p0);
		else if (failed)
			acct_set(r, AN_PARTLY, fd.t[fd.P - 1], dur, "failed at t = %g s (%s): the %zu periods before it used",
				 r->status_time, r->status, fd.P);
		else
			acct_set(r, AN_USED, NAN, NAN, NULL);
		flux_free(&fd);
		return;
	}
	hid_t h;
	sb_err he = {0};
	if (h5r_open(r->path, &h, &he)) {
		acct_set(r, AN_UNREADABLE, NAN, NAN, "%s", he.msg);
		fprintf(stderr, "figures: warning: %s (counted as unreadable)\n", r->why);
		return;
	}
	double st = r->status_time;
	h5r_attr_num(h, "/", "status_time", &st);
	h5r_close(h);
	if (!failed)
		acct_set(r, AN_USED, NAN, NAN, NULL);
	else if (st > 0)
		acct_set(r, AN_PARTLY, st, dur, "failed at t = %g s (%s): used up to it", st, r->status);
	else
		acct_set(r, AN_UNUSABLE, NAN, NAN, "failed before the shaking began (%s)", r->status);
}

int main(int argc, char **argv)
{
	an_opts o = {.tool = "figures", .version = VERSION};
	int pr = cli_parse(&o, argc, argv, HELP, " freq ratio skip where ");
	if (pr)
		return pr < 0 ? 0 : 1;
	flux_opts fo = {0.4, 0.6, o.skip};
	sb_err e = {0};
	adb d;
	an_run *runs = NULL;
	int nr = 0, k = 0, made = 0, stored = 0, ng = 0;
	char **labels = NULL;
	an_acct *A = NULL;
	FILE *f = NULL;
	char path[1400], script[1400], png[1400];
	double freqs[64], ratios[64];
	int nf = 0, nra = 0;
	if (adb_open(&d, o.db, !o.no_store, &e) || adb_runs(&d, o.campaign, o.runs, &runs, &nr, &e))
		goto out;
	for (int w = 0; w < o.nwhere; w++) {
		int known = 0;
		for (int i = 0; i < nr && !known; i++)
			known = an_str(&runs[i], o.where_key[w]) != NULL;
		if (nr && !known) {
			sb_errf(&e, SB_EUSAGE, "--where: '%s' is not a parameter of campaign '%s'", o.where_key[w], o.campaign);
			goto out;
		}
	}
	long nold = 0;
	for (int i = 0; i < nr; i++) {
		const char *ramp = an_str(&runs[i], "ramp");
		if (ramp && strcmp(ramp, "none"))
			continue;
		if (!where_ok(&o, &runs[i]) || acct_version_skip(&runs[i], o.all_versions, &nold))
			continue;
		an_run t = runs[k];
		runs[k] = runs[i];
		runs[i] = t;
		double fr = an_num(&runs[k], "frequency", NAN), ra = an_num(&runs[k], "radius_ratio", 0);
		int seen = 0;
		for (int j = 0; j < nf; j++)
			seen |= near(freqs[j], fr);
		if (!seen && nf < 64 && isfinite(fr))
			freqs[nf++] = fr;
		seen = 0;
		for (int j = 0; j < nra; j++)
			seen |= near(ratios[j], ra);
		if (!seen && nra < 64 && ra > 0)
			ratios[nra++] = ra;
		k++;
	}
	if (!k) {
		int known = 0;
		if (!adb_campaign_exists(&d, o.campaign, &known, &e) && !known)
			sb_errf(&e, SB_EUSAGE, "campaign '%s' is not in %s", o.campaign, o.db);
		else
			sb_errf(&e, SB_EUSAGE, "campaign '%s': no finished fixed-frequency run in %s%s%s", o.campaign, o.db,
				o.nwhere ? " that matches --where" : "", nold ? " of the current grid (--all-versions)" : "");
		goto out;
	}
	if (pooled_axis(&d, &o, runs, k, &e))
		goto out;
	qsort(freqs, (size_t)nf, sizeof *freqs, cmpd);
	qsort(ratios, (size_t)nra, sizeof *ratios, cmpd);
	if (o.nfreq) {
		nf = o.nfreq;
		memcpy(freqs, o.freqs, sizeof(double) * (size_t)nf);
	}
	if (nf > MAXROWS)
		nf = MAXROWS;
	double R = isnan(o.ratio) ? (nra ? ratios[nra - 1] : 0) : o.ratio;
	/* the second system is the one with an intruder: none when R = 0 */
	const int nsys = R > 0 ? 2 : 1;
	/* the panels are the groups of the accounting: row r, system sys is group r * nsys + sys */
	ng = nf * nsys;
	labels = calloc((size_t)ng, sizeof *labels);
	if (!labels) {
		sb_errf(&e, SB_ENOMEM, "out of memory");
		goto out;
	}
	for (int j = 0; j < ng; j++) {
		char l[96];
		snprintf(l, sizeof l, "f=%g radius_ratio=%g", freqs[j / nsys], j % nsys ? R : 0);
		if (!(labels[j] = strdup(l))) {
			sb_errf(&e, SB_ENOMEM, "out of memory");
			goto out;
		}
	}
	for (int i = 0; i < k; i++) {
		runs[i].group = -1;
		for (int j = 0; j < ng; j++)
			if (near(an_num(&runs[i], "frequency", NAN), freqs[j / nsys]) &&
			    near(an_num(&runs[i], "radius_ratio", 0), j % nsys ? R : 0))
				runs[i].group = j;
		if (runs[i].group >= 0)
			classify(&runs[i], &fo);
	}
	if (acct_tally(runs, k, ng, &A)) {
		sb_errf(&e, SB_ENOMEM, "out of memory");
		goto out;
	}
	long used = 0;
	for (int j = 0; j < ng; j++)
		used += acct_used(&A[j]);
	if (!used) {
		acct_print(stdout, "figures", labels, A, ng, nold, o.all_versions);
		sb_errf(&e, SB_EUSAGE, "campaign '%s': none of the runs of the panels drawn is usable yet", o.campaign);
		goto out;
	}
	if (cli_outdir(&o, &e))
		goto out;
	if (!(f = cli_fopen(&o, "figures_accounting.csv", path, sizeof path, &e)))
		goto out;
	acct_runs_csv(f, runs, k, labels);
	fclose(f);
	f = NULL;
	if (!o.no_store && adb_store_begin(&d, o.campaign, "figures", &e))
		goto out;

	/* ---- Fig. 1: displacement field ---- */
	{
		if (!(f = cli_fopen(&o, "fig1_field.csv", path, sizeof path, &e)))
			goto out;
		fprintf(f, "panel,frequency,radius_ratio,x,y,ux,uy,count,dx,dy\n");
		double umax = 0, cell = 1, xlo = INFINITY, xhi = -INFINITY, yhi = 0;
		int panels = 0;
		/* The arrow scale is the 95th percentile of the arrow lengths, not the longest:
		 * a grain thrown off the surface in a thinly sampled cell would otherwise
		 * shrink every arrow of the bulk to a dot. Longer arrows are drawn at that
		 * length (their direction kept), and cells sampled less than a fifth as often
		 * as the panel's median cell are left out. */
		double *lens = NULL;
		size_t nlens = 0, caplens = 0;
		/* two passes: the first finds the common arrow scale */
		for (int pass = 0; pass < 2; pass++)
			for (int r = 0; r < nf; r++)
				for (int sys = 0; sys < nsys; sys++) {
					double ra = sys ? R : 0, *sx = NULL, *sy = NULL, *sc = NULL, x0 = 0;
					size_t dims0[3] = {0, 0, 0};
					int used = 0;
					for (int i = 0; i < k; i++) {
						if (!USED(&runs[i]) || !near(an_num(&runs[i], "frequency", NAN), freqs[r]) ||
						    !near(an_num(&runs[i], "radius_ratio", 0), ra))
							continue;
						hid_t h;
						sb_err he = {0};
						if (h5r_open(runs[i].path, &h, &he) || !h5r_exists(h, "/field")) {
							if (!he.code)
								h5r_close(h);
							continue;
						}
						double *ux = NULL, *uy = NULL, *cn = NULL;
						size_t d1[3], d2[3], d3[3];
						int rk;
						if (!h5r_read(h, "/field/ux", &ux, &rk, d1, &he) && !h5r_read(h, "/field/uy", &uy, &rk, d2, &he) &&
						    !h5r_read(h, "/field/count", &cn, &rk, d3, &he) && rk == 3 &&
						    !memcmp(d1, d2, sizeof d1) && !memcmp(d1, d3, sizeof d1)) {
							/* The grid is one mean diameter of the run's own grains, so
							 * replicates differ slightly: the panel takes the grid of
							 * its first run, and every run's cells go, by their centres,
							 * into the cell of that grid that holds them. */
							double ci = 0, xi = 0;
							h5r_attr_num(h, "/field", "cell", &ci);
							h5r_attr_num(h, "/field", "x0", &xi);
							if (!used && ci > 0) {
								memcpy(dims0, d1, sizeof dims0);
								size_t nc = d1[1] * d1[2];
								sx = calloc(nc, sizeof *sx);
								sy = calloc(nc, sizeof *sy);
								sc = calloc(nc, sizeof *sc);
								cell = ci;
								x0 = xi;
							}
							for (size_t b = 0; sx && sy && sc && ci > 0 && b < d1[0]; b++)
								for (size_t rr = 0; rr < d1[1]; rr++)
									for (size_t c = 0; c < d1[2]; c++) {
										size_t q = (b * d1[1] + rr) * d1[2] + c;
										double n = cn[q];
										double gx = floor((xi + ((double)c + 0.5) * ci - x0) / cell);
										double gy = floor(((double)rr + 0.5) * ci / cell);
										if (!(n > 0) || gx < 0 || gy < 0 || gx >= (double)dims0[2] ||
										    gy >= (double)dims0[1])
											continue;
										size_t t = (size_t)gy * dims0[2] + (size_t)gx;
										sx[t] += n * ux[q];
										sy[t] += n * uy[q];
										sc[t] += n;
									}
							used += sx && ci > 0;
						}
						free(ux);
						free(uy);
						free(cn);
						h5r_close(h);
					}
					if (used && sx && sy && sc) {
						size_t ny = dims0[1], nx = dims0[2];
						double scale = umax > 0 ? 0.9 * cell / umax : 1;
						double cmin = 0.2 * median_positive(sc, ny * nx);
						for (size_t rr = 0; rr < ny; rr++)
							for (size_t c = 0; c < nx; c++) {
								size_t q = rr * nx + c;
								if (sc[q] <= 0 || sc[q] < cmin)
									continue;
								double ux = sx[q] / sc[q], uy = sy[q] / sc[q];
								double x = x0 + (c + 0.5) * cell, y = (rr + 0.5) * cell;
								if (pass == 1 && umax > 0 && hypot(ux, uy) > umax) {
									double shrink = umax / hypot(ux, uy); /* clipped */
									ux *= shrink;
									uy *= shrink;
								}
								if (pass == 0) {
									if (nlens == caplens) {
										caplens = caplens ? 2 * caplens : 1024;
										double *p = realloc(lens, caplens * sizeof *lens);
										if (!p)
											continue;
										lens = p;
									}
									lens[nlens++] = hypot(ux, uy);
									xlo = fmin(xlo, x0);
									xhi = fmax(xhi, x0 + nx * cell);
									yhi = fmax(yhi, ny * cell);
									continue;
								}
								fprintf(f, "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", 2 * r + sys,
									freqs[r], ra, x - 0.5 * ux * scale, y - 0.5 * uy * scale, ux, uy, sc[q],
									ux * scale, uy * scale);
							}
						panels += pass;
					}
					free(sx);
					free(sy);
					free(sc);
					if (pass == 0 && r == nf - 1 && sys == nsys - 1)
						umax = percentile(lens, nlens, 0.95);
				}
		free(lens);
		fclose(f);
		f = NULL;
		if (!panels)
			printf("# fig1: no run with field = yes; skipped\n");
		else if (!o.no_plot) {
			if (!(f = gp_open(&o, "fig1", 900, 330 * nf + 60, script, png, sizeof script, &e)))
				goto out;
			fprintf(f, "set multiplot layout %d,%d title 'Fig. 1: mean displacement per period (arrow scale: 95th percentile %.3g cm, longer arrows clipped)'\n"
				   "set size ratio -1\nunset key\nset xrange [%.17g:%.17g]\nset yrange [0:%.17g]\n"
				   "set xlabel 'x (cm)'\nset ylabel 'height above the bottom (cm)'\n",
				nf, nsys, umax, xlo, xhi, yhi);
			for (int r = 0; r < nf; r++)
				for (int sys = 0; sys < nsys; sys++) {
					if (sys)
						fprintf(f, "set title 'with intruder R = %g, f = %g Hz'\n", R, freqs[r]);
					else
						fprintf(f, "set title 'without intruder, f = %g Hz'\n", freqs[r]);
					fprintf(f, "plot 'fig1_field.csv' skip 1 using 4:5:($1==%d?$9:1/0):10 with vectors head filled size %.3g,20 lc rgb '#1f4e9c'\n",
						2 * r + sys, 0.25 * cell);
				}
			fprintf(f, "unset multiplot\n");
			fclose(f);
			f = NULL;
			if (gp_run(script, png, &e))
				goto out;
			made++;
			printf("# fig1: %s (%d panels)\n", png, panels);
		}
	}

	/* ---- Fig. 3: Phi(D) ---- */
	{
		if (!(f = cli_fopen(&o, "fig3_profile.csv", path, sizeof path, &e)))
			goto out;
		fprintf(f, "row,system,frequency,radius_ratio,line,D,phi,runs\n");
		int panels = 0;
		printf("%-10s %-6s %5s %10s %12s %6s %10s\n", "frequency", "R", "used", "phi_max", "half_height", "failed",
		       "unfinished");
		for (int r = 0; r < nf; r++)
			for (int sys = 0; sys < nsys; sys++) {
				double ra = sys ? R : 0, *sp = NULL, *sh = NULL, wsum = 0, pm = 0, half = NAN;
				const an_acct *a = &A[r * nsys + sys];
				size_t L = 0;
				int used = 0;
				for (int i = 0; i < k; i++) {
					if (!USED(&runs[i]) || runs[i].group != r * nsys + sys)
						continue;
					flux_data fd;
					if (flux_load(&runs[i], &fd))
						continue; /* classified as usable: only a file changed since could fail */
					if (!used) {
						L = fd.L;
						sp = calloc(L ? L : 1, sizeof *sp);
						sh = calloc(L ? L : 1, sizeof *sh);
					}
					double *prof = malloc(sizeof *prof * (fd.L ? fd.L : 1));
					size_t p0 = flux_first(&fd, &fo);
					/* the runs' periods pooled: a failed run weighs what it recorded */
					double w = fd.P > p0 ? (double)(fd.P - p0) : 0;
					if (sp && sh && prof && fd.L == L && w > 0) {
						flux_profile(&fd, &fo, prof);
						for (size_t l = 0; l < L; l++) {
							sp[l] += w * prof[l];
							sh[l] += w * fd.h[l];
						}
						wsum += w;
						used++;
					}
					free(prof);
					flux_free(&fd);
				}
				if (used) {
					for (size_t l = 0; l < L; l++) {
						fprintf(f, "%d,%d,%.17g,%.17g,%zu,%.17g,%.17g,%d\n", r, sys, freqs[r], ra, l, sh[l] / wsum,
							sp[l] / wsum, used);
						pm = fmax(pm, fabs(sp[l] / wsum));
					}
					for (size_t l = 0; l < L && isnan(half); l++)
						if (pm > 0 && fabs(sp[l] / wsum) >= 0.5 * pm)
							half = sh[l] / wsum;
					printf("%-10g %-6g %5d %10.4g %12.4g %6ld %10ld\n", freqs[r], ra, used, pm, half, a->failed,
					       a->n[AN_PENDING] + a->n[AN_RUNNING]);
					panels++;
				}
				long any = 0; /* a panel with runs of any kind has its accounting stored */
				for (int u = 0; u < AN_NUSE; u++)
					any += a->n[u];
				if (!o.no_store && any) {
					char g[128];
					snprintf(g, sizeof g, "fig3 f=%g radius_ratio=%g", freqs[r], ra);
					if (used) {
						adb_store(&d, o.campaign, "figures", VERSION, g, "phi_max", pm, NAN, NAN, used, &e);
						adb_store(&d, o.campaign, "figures", VERSION, g, "half_height", half, NAN, NAN, used, &e);
					}
					adb_store(&d, o.campaign, "figures", VERSION, g, "runs", used, NAN, NAN, used, &e);
					acct_store(&d, o.campaign, "figures", VERSION, g, a, &e);
					stored++;
				}
				free(sp);
				free(sh);
			}
		fclose(f);
		f = NULL;
		if (e.code)
			goto out;
		if (!panels)
			printf("# fig3: no run with flux = yes; skipped\n");
		else if (!o.no_plot) {
			if (!(f = gp_open(&o, "fig3", 800, 260 * nf + 60, script, png, sizeof script, &e)))
				goto out;
			fprintf(f, "set multiplot layout %d,1 title 'Fig. 3: convective flux Phi through planes at height D'\n"
				   "set xlabel 'D (cm above the bottom)'\nset ylabel 'Phi (particles/period)'\n", nf);
			for (int r = 0; r < nf; r++) {
				fprintf(f, "set title 'f = %g Hz'\nplot 'fig3_profile.csv' skip 1 using 6:($1==%d&&$2==0?$7:1/0) with linespoints pt 7 ps 0.5 lc 1 title 'without intruder', \\\n",
					freqs[r], r);
				if (nsys > 1)
					fprintf(f, "  'fig3_profile.csv' skip 1 using 6:($1==%d&&$2==1?$7:1/0) with linespoints pt 5 ps 0.5 lc 2 title 'with intruder R = %g', \\\n",
						r, R);
				fprintf(f, "  0 with lines lc 'gray' notitle\n");
			}
			fprintf(f, "unset multiplot\n");
			fclose(f);
			f = NULL;
			if (gp_run(script, png, &e))
				goto out;
			made++;
			printf("# fig3: %s (%d curves)\n", png, panels);
		}
	}

	/* ---- Fig. 4: intruder height ---- */
	{
		if (!(f = cli_fopen(&o, "fig4_traj.csv", path, sizeof path, &e)))
			goto out;
		fprintf(f, "panel,radius_ratio,run,t,y\n");
		double f4 = nf ? freqs[nf - 1] : NAN, meta[8][3];
		int panels = 0;
		for (int q = 0; q < nra && panels < 8; q++) {
			/* the finished run with the lowest replicate; a failed one only when none finished */
			int best = -1;
			for (int i = 0; i < k; i++)
				if (USED(&runs[i]) && near(an_num(&runs[i], "frequency", NAN), f4) &&
				    near(an_num(&runs[i], "radius_ratio", 0), ratios[q]) &&
				    (best < 0 || (runs[i].use == AN_USED) > (runs[best].use == AN_USED) ||
				     ((runs[i].use == AN_USED) == (runs[best].use == AN_USED) &&
				      runs[i].replicate < runs[best].replicate)))
					best = i;
			if (best < 0)
				continue;
			hid_t h;
			sb_err he = {0};
			if (h5r_open(runs[best].path, &h, &he))
				continue;
			double *tr = NULL;
			size_t dm[3];
			int rk;
			if (!h5r_read(h, "/intruder/trajectory", &tr, &rk, dm, &he) && rk == 2 && dm[1] >= 3 && dm[0] > 0) {
				for (size_t j = 0; j < dm[0]; j++)
					fprintf(f, "%d,%.17g,%s,%.17g,%.17g\n", panels, ratios[q], runs[best].id, tr[j * dm[1]],
						tr[j * dm[1] + 2]);
				meta[panels][0] = ratios[q];
				meta[panels][1] = meta[panels][2] = NAN;
				h5r_attr_num(h, "/", "intruder_settled_y", &meta[panels][1]);
				h5r_attr_num(h, "/", "surface_height", &meta[panels][2]);
				panels++;
			}
			free(tr);
			h5r_close(h);
		}
		fclose(f);
		f = NULL;
		if (!panels)
			printf("# fig4: no run with an intruder at %g Hz; skipped\n", f4);
		else if (!o.no_plot) {
			if (!(f = gp_open(&o, "fig4", 800, 260 * panels + 60, script, png, sizeof script, &e)))
				goto out;
			fprintf(f, "set multiplot layout %d,1 title 'Fig. 4: height of the intruder, f = %g Hz'\n"
				   "set xlabel 't (s)'\nset ylabel 'y (cm, lab frame)'\n", panels, f4);
			for (int p = 0; p < panels; p++)
				fprintf(f, "set title 'R = %g'\nplot 'fig4_traj.csv' skip 1 using 4:($1==%d?$5:1/0) with lines lc 1 title 'intruder centre', \\\n"
					   "  %.17g with lines dt 2 lc 'gray' title 'settled height', %.17g with lines dt 3 lc 'black' title 'free surface (t = 0)'\n",
					meta[p][0], p, meta[p][1], meta[p][2]);
			fprintf(f, "unset multiplot\n");
			fclose(f);
			f = NULL;
			if (gp_run(script, png, &e))
				goto out;
			made++;
			printf("# fig4: %s (%d panels)\n", png, panels);
		}
	}
	if (!o.no_store && adb_store_end(&d, !e.code, &e))
		goto out;
	acct_print(stdout, "figures", labels, A, ng, nold, o.all_versions);
	long partly = 0;
	for (int j = 0; j < ng; j++)
		partly += A[j].n[AN_PARTLY];
	if (partly)
		printf("# %ld failed run%s enter%s with what they recorded before the failure: Fig. 3 with their periods after"
		       " the transient of the run as planned (the runs' periods are pooled), Fig. 1 with their samples\n",
		       partly, partly == 1 ? "" : "s", partly == 1 ? "s" : "");
	printf("# csv: %s/fig{1_field,3_profile,4_traj}.csv %s/figures_accounting.csv\n", o.out, o.out);
out:
	if (f)
		fclose(f);
	if (e.code && !o.no_store && d.ins)
		adb_store_end(&d, 0, &e);
	free(A);
	for (int j = 0; labels && j < ng; j++)
		free(labels[j]);
	free(labels);
	adb_runs_free(runs, nr);
	adb_close(&d);
	(void)made;
	(void)stored;
	if (e.code) {
		fprintf(stderr, "figures: %s\n", e.msg);
		return e.code == SB_EUSAGE ? 1 : 2;
	}
	return 0;
}
