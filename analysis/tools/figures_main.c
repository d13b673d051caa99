/* figures_main.c - bin/figures: the paper's Fig. 1 (arrow field of the averaged
 * displacement), Fig. 3 (Phi versus height D with and without intruder) and Fig. 4
 * (intruder height versus time) from a campaign. Only this file prints and exits. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "flux.h"
#include "fsutil.h"
#include "h5read.h"
#include "num.h"
#include "runfile.h"
#include "common/acct.h"
#include "common/adb.h"
#include "common/cli.h"
#include "common/fluxrun.h"
#include "common/label.h"
#include "common/tool.h"
#include "measure/convect.h"
#include "measure/wmean.h"
#include "measure/traj.h"

#define VERSION "5"

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

static const char HELP[] =
	"usage: figures CAMPAIGN [--db FILE] [--runs DIR] [--out DIR] [--freq F1,F2,...]\n"
	"               [--ratio R] [--skip FRAC] [--level L] [--where KEY=VALUE ...] [--all-versions]\n"
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
	"            systems in one panel per frequency, each curve in its band: the\n"
	"            interval at level L (--level, default 0.95) of its mean across its\n"
	"            runs (Student t with runs - 1 degrees of freedom, each run weighted\n"
	"            by its periods; none for a curve of one run), the runs it rests on\n"
	"            in each panel's title and the table's 'used';\n"
	"  fig4.png  Fig. 4: the intruder's height y(t) above the box floor\n"
	"            (/particles/intruder/position less the box motion A sin(2 pi f t)) at\n"
	"            the highest selected frequency, one panel per radius ratio > 0: every\n"
	"            replicate as a thin line, and thick the representative, the run whose\n"
	"            waiting time is the panel's median (risen runs ordered by waiting time,\n"
	"            then the censored ones by the time observed; the lower middle of an even\n"
	"            count), with its settled height and the surface.\n"
	"A figure without data is skipped with a note. A failed run is drawn with what it\n"
	"recorded before its failure (Fig. 3: its periods after the transient of the run as\n"
	"planned, pooled with the other runs' periods; Fig. 1: its samples; Fig. 4: its\n"
	"trajectory up to the failure). Per panel (frequency, radius ratio) the output,\n"
	"figures_accounting.csv and the stored rows count the runs used, failed (by status;\n"
	"used up to the failure or unusable), unreadable, pending and running.\n\n"
	"  --db FILE, --runs DIR, --out DIR   as for every tool (waiting --help)\n"
	"  --all-versions   also the runs of earlier versions of the campaign file (run.current = 0)\n"
	"  --no-plot, --no-store\n\n"
	"Writes fig1_field.csv, fig3_profile.csv (with the band: phi_lo, phi_hi),\n"
	"fig4_traj.csv and the figures; stores per\n"
	"panel of Fig. 3 in `analysis` (tool 'figures', grp 'fig3 f=F radius_ratio=R'):\n"
	"phi_max (largest |Phi(D)|; lo, hi: the band of |Phi| on its line, as the table's\n"
	"phi_lo, phi_hi), half_height (lowest D where |Phi| >= phi_max / 2: how\n"
	"deep the rolls reach), runs (used) and the accounting (runs_failed, runs_failed_used,\n"
	"..., as onset --help lists).\n"
	"Options take their value as --opt VALUE or --opt=VALUE. Figures are written as PNG\n"
	"and PDF (vector) with their gnuplot scripts. A stored row has its group's value of\n"
	"each grouping key in that key's column (radius_ratio, depth, ...; docs/analysis.md).\n";

static int near(double a, double b)
{
	return fabs(a - b) <= 1e-9 * fmax(1, fabs(b));
}

/* The panels: one row per frequency; the system without intruder and, when R > 0,
 * the one with an intruder of radius ratio R. Panel (row r, system sys) is group
 * r * nsys + sys of the accounting. */
typedef struct panels {
	flux_opts fo;
	double freqs[64];  /* the campaign's frequencies, then the rows' */
	double ratios[64]; /* the campaign's radius ratios > 0 */
	int nf, nra;
	double R;
	int nsys;
	double level;      /* Fig. 3's band (--level) */
	int runs[64][2];   /* Fig. 3: the runs of each row's curves */
	double hs[64][2];  /* Fig. 3: their mean settled surface height h_s */
} panels;

static double sys_ratio(const panels *P, int sys)
{
	return sys ? P->R : 0;
}

/* "no intruder" or "𝓡 = 2.5", and with the frequency: "𝓡 = 2.5, 4.5 Hz" */
static void sys_words(const panels *P, int sys, double f, char *buf, size_t n)
{
	char w[96], fw[64];
	label_num(w, sizeof w, "radius_ratio", sys_ratio(P, sys));
	if (isnan(f))
		snprintf(buf, n, "%s", w);
	else {
		label_num(fw, sizeof fw, "frequency", f);
		snprintf(buf, n, "%.80s, %.40s", w, fw);
	}
}

/* Adds x to v[0..*n) unless it is there already, ok is false or v is full. */
static void add_value(double *v, int *n, double x, int ok)
{
	int seen = 0;
	for (int j = 0; j < *n; j++)
		seen |= near(v[j], x);
	if (!seen && *n < 64 && ok)
		v[(*n)++] = x;
}

/* Every fixed-frequency run that matches --where is considered, whatever its state;
 * their frequencies and radius ratios are noted. */
static int consider(an_tool *t, panels *P)
{
	const an_opts *o = t->o;
	for (int i = 0; i < t->nr; i++) {
		const char *ramp = an_str(&t->runs[i], "ramp");
		if ((ramp && strcmp(ramp, "none")) || !tool_where_ok(o, &t->runs[i]) || tool_old(t, &t->runs[i]))
			continue;
		const an_run *r = &t->runs[tool_keep(t, i)];
		/* the panels are its groups */
		if (tool_key_known(t, r, "frequency") || tool_key_known(t, r, "radius_ratio"))
			return t->e.code;
		const double fr = an_num(r, "frequency", NAN), ra = an_num(r, "radius_ratio", 0);
		add_value(P->freqs, &P->nf, fr, isfinite(fr));
		add_value(P->ratios, &P->nra, ra, ra > 0);
	}
	return t->k ? 0 : tool_none(t, "fixed-frequency run", o->nwhere ? " that matches --where" : "");
}

/* A panel averages its runs: runs that differ in another swept key (depth, width...)
 * would be averaged silently, so that is an error naming the key and two values. */
static int pooled_axis(an_tool *t)
{
	const an_opts *o = t->o;
	char axes[AN_MAXKEYS][48];
	int na = 0;
	if (adb_axes(&t->d, o->campaign, axes, AN_MAXKEYS, &na, &t->e))
		return t->e.code;
	for (int a = 0; a < na; a++) {
		if (!strcmp(axes[a], "frequency") || !strcmp(axes[a], "radius_ratio") || !strcmp(axes[a], "seed"))
			continue;
		const char *first = an_str(&t->runs[0], axes[a]);
		for (int i = 1; i < t->k; i++) {
			const char *v = an_str(&t->runs[i], axes[a]);
			if (first && v && strcmp(first, v))
				return sb_errf(&t->e, SB_EUSAGE,
					       "campaign '%s' sweeps %s (%s, %s, ...): a panel would average over it; "
					       "choose with --where %s=VALUE", o->campaign, axes[a], first, v, axes[a]);
		}
	}
	return 0;
}

/* What of a run the figures can draw (acct.h): with flux = yes its periods after the
 * transient (a failed run's up to the failure; none when it failed within the
 * transient), else its file up to its status time. */
static void classify_data(an_run *r, const flux_opts *fo)
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
		if (fluxrun_load(r, &fd)) {
			if (r->use == AN_UNREADABLE)
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

/* ... and what Fig. 1 and Fig. 4 read of it later is checked now, as the accounting
 * is printed before they are drawn: a run recorded with field = yes whose displacement
 * field cannot be read whole (missing, a shape the file cannot hold, a chunk that fails
 * its checksum, a cell size that is no length) is unreadable, one whose field holds a
 * value that is no number (a count of inf) unusable, through the reader bin/convect
 * uses; and a run with an intruder whose rise is no number (Fig. 4 orders the runs by
 * it) is unusable. Fig. 1 then adds exactly the runs counted used. */
static void classify(an_run *r, const flux_opts *fo)
{
	classify_data(r, fo);
	if (r->use != AN_USED && r->use != AN_PARTLY)
		return;
	hid_t h;
	sb_err he = {0};
	if (h5r_open(r->path, &h, &he))
		return; /* classify_data read it */
	const char *fld = an_str(r, "field");
	const int has = h5r_exists(h, RUNFILE_FIELD), want = has || (fld && !strcmp(fld, "yes"));
	double rs, w;
	if (an_num(r, "radius_ratio", 0) > 0 && traj_rise(h, r->path, &rs, &w, &he) == SB_ENAN)
		acct_set(r, AN_UNUSABLE, NAN, NAN, "%s", he.msg);
	h5r_close(h);
	if (!want || (r->use != AN_USED && r->use != AN_PARTLY))
		return;
	convect_field cf;
	sb_err fe = {0};
	if (!has) {
		acct_set(r, AN_UNREADABLE, NAN, NAN, "%s: no /observables/field, though the run was recorded with "
			 "field = yes", r->path);
		fprintf(stderr, "figures: warning: %s (counted as unreadable)\n", r->why);
		return;
	}
	if (convect_read(r->path, &cf, &fe)) {
		acct_set(r, fe.code == SB_ENAN ? AN_UNUSABLE : AN_UNREADABLE, NAN, NAN, "%s", fe.msg);
		fprintf(stderr, "figures: warning: %s (counted as %s)\n", r->why, acct_use_name(r->use));
		return;
	}
	convect_free(&cf);
}

/* The rows (--freq, else the campaign's frequencies, at most MAXROWS), the systems
 * (--ratio, else the largest radius ratio), the panels' labels, each considered run's
 * panel and what of it is drawn. */
static int layout(an_tool *t, panels *P)
{
	const an_opts *o = t->o;
	qsort(P->freqs, (size_t)P->nf, sizeof *P->freqs, cmp_dbl);
	qsort(P->ratios, (size_t)P->nra, sizeof *P->ratios, cmp_dbl);
	if (o->nfreq) {
		/* a frequency without runs would be an empty row of panels: refused, with the
		 * frequencies there are */
		for (int i = 0; i < o->nfreq; i++) {
			int have = 0;
			for (int j = 0; j < P->nf && !have; j++)
				have = near(o->freqs[i], P->freqs[j]);
			if (!have) {
				char list[512];
				size_t l = 0;
				for (int j = 0; j < P->nf && l < sizeof list - 32; j++)
					l += (size_t)snprintf(list + l, sizeof list - l, "%s%g", j ? ", " : "", P->freqs[j]);
				return sb_errf(&t->e, SB_EUSAGE, "--freq %g: no fixed-frequency run at this frequency%s "
					       "(the runs' frequencies: %s)", o->freqs[i],
					       o->nwhere ? " that matches --where" : "", list);
			}
		}
		P->nf = o->nfreq;
		memcpy(P->freqs, o->freqs, sizeof(double) * (size_t)P->nf);
	}
	if (P->nf > MAXROWS)
		P->nf = MAXROWS;
	P->R = isnan(o->ratio) ? (P->nra ? P->ratios[P->nra - 1] : 0) : o->ratio;
	/* the second system is the one with an intruder: none when R = 0 */
	P->nsys = P->R > 0 ? 2 : 1;
	t->ng = P->nf * P->nsys;
	if (!(t->labels = calloc((size_t)t->ng, sizeof *t->labels)))
		return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	for (int j = 0; j < t->ng; j++) {
		char l[96];
		snprintf(l, sizeof l, "f=%g radius_ratio=%g", P->freqs[j / P->nsys], sys_ratio(P, j % P->nsys));
		if (!(t->labels[j] = strdup(l)))
			return sb_errf(&t->e, SB_ENOMEM, "out of memory");
	}
	/* the panels are groups by frequency and radius ratio: their stored rows say so */
	char keys[2][48] = {"frequency", "radius_ratio"};
	if (tool_keys(t, keys, 2))
		return t->e.code;
	for (int j = 0; j < t->ng; j++) {
		char v[2][64];
		snprintf(v[0], sizeof v[0], "%.17g", P->freqs[j / P->nsys]);
		snprintf(v[1], sizeof v[1], "%.17g", sys_ratio(P, j % P->nsys));
		if (tool_value(t, j, 0, v[0]) || tool_value(t, j, 1, v[1]))
			return t->e.code;
	}
	for (int i = 0; i < t->k; i++) {
		an_run *r = &t->runs[i];
		r->group = -1;
		for (int j = 0; j < t->ng; j++)
			if (near(an_num(r, "frequency", NAN), P->freqs[j / P->nsys]) &&
			    near(an_num(r, "radius_ratio", 0), sys_ratio(P, j % P->nsys)))
				r->group = j;
		if (r->group >= 0)
			classify(r, &P->fo);
	}
	return tool_tally(t, stdout, "the runs of the panels drawn");
}

/* The end of every figure's script: its multiplot closed, the figure drawn (PNG and
 * PDF), and its line in the output naming what it shows ("panel", "curve"). */
static int plot_end(an_tool *t, FILE *f, const char *name, const char *script, const char *png, int drawn,
		    const char *what)
{
	fprintf(f, "unset multiplot\n");
	if (tool_plot(t, f, script, png))
		return t->e.code;
	printf("# %s: %s (and .pdf, %d %s%s)\n", name, png, drawn, what, drawn == 1 ? "" : "s");
	return 0;
}

/* ---- Fig. 1: displacement field ---- */

/* One panel's field: the cells of its runs, count-weighted, on the grid of its first run. */
typedef struct field {
	size_t ny, nx;
	double cell, x0;      /* the grid: cell size, left edge (cell 0: none yet) */
	double *sx, *sy, *sc; /* [ny * nx] sums of count * ux, count * uy and of count */
	int runs;
} field;

static void field_free(field *fl)
{
	free(fl->sx);
	free(fl->sy);
	free(fl->sc);
}

/* Adds a run's field (read and checked by convect_read, as classify did). The grid is
 * one mean diameter of the run's own grains, so replicates differ slightly: the panel
 * takes the grid of its first run, and every run's cells go, by their centres, into
 * the cell of that grid that holds them. */
static int field_sum(field *fl, const convect_field *cf)
{
	const double ci = cf->cell, xi = cf->x0;
	if (!fl->runs) {
		field_free(fl);
		fl->ny = cf->ny;
		fl->nx = cf->nx;
		fl->sx = calloc(cf->ny * cf->nx, sizeof *fl->sx);
		fl->sy = calloc(cf->ny * cf->nx, sizeof *fl->sy);
		fl->sc = calloc(cf->ny * cf->nx, sizeof *fl->sc);
		fl->cell = ci;
		fl->x0 = xi;
		if (!fl->sx || !fl->sy || !fl->sc)
			return -1;
	}
	for (size_t b = 0; b < cf->B; b++)
		for (size_t rr = 0; rr < cf->ny; rr++)
			for (size_t c = 0; c < cf->nx; c++) {
				const size_t q = (b * cf->ny + rr) * cf->nx + c;
				const double n = cf->n[q];
				const double gx = floor((xi + ((double)c + 0.5) * ci - fl->x0) / fl->cell);
				const double gy = floor(((double)rr + 0.5) * ci / fl->cell);
				if (!(n > 0) || gx < 0 || gy < 0 || gx >= (double)fl->nx || gy >= (double)fl->ny)
					continue;
				const size_t g = (size_t)gy * fl->nx + (size_t)gx;
				fl->sx[g] += n * cf->ux[q];
				fl->sy[g] += n * cf->uy[q];
				fl->sc[g] += n;
			}
	fl->runs++;
	return 0;
}

/* Adds run r's field to fl when it has one (field = no: none to add). A run counted
 * used whose field can no longer be read (the file changed since classify) stops the
 * figure: a panel made of fewer runs than the accounting says is not drawn. */
static int field_add(field *fl, const an_run *r, sb_err *e)
{
	convect_field cf;
	sb_err fe = {0};
	const int rc = convect_read(r->path, &cf, &fe);
	if (rc == SB_EUSAGE)
		return 0;
	if (rc)
		return sb_errf(e, SB_EIO, "%s (counted as used)", fe.msg);
	const int bad = field_sum(fl, &cf);
	convect_free(&cf);
	return bad ? sb_errf(e, SB_ENOMEM, "out of memory") : 0;
}

/* The arrows of every panel on one scale. The scale is the 95th percentile of the
 * arrow lengths, not the longest: a grain thrown off the surface in a thinly sampled
 * cell would otherwise shrink every arrow of the bulk to a dot. Longer arrows are
 * drawn at that length (their direction kept), and cells sampled less than a fifth as
 * often as the panel's median cell are left out. */
typedef struct arrows {
	double umax;         /* the common length (0 before it is known) */
	double *lens;        /* every arrow's length, to find it */
	size_t n, cap;
	double xlo, xhi, yhi; /* the extent of the panels' grids */
	double head;         /* the cell of the last panel drawn: the arrow heads' size */
	double cell[2 * MAXROWS]; /* per panel (2 row + system): its cell size, 0 when not drawn */
	int runs[2 * MAXROWS];    /* the runs it averages */
	int settled[2 * MAXROWS]; /* its runs with an intruder's settled place (fig1_intruder.csv) */
} arrows;

static void arrows_note(arrows *a, const field *fl, double len)
{
	if (a->n == a->cap) {
		size_t cap = a->cap ? 2 * a->cap : 1024;
		double *p = realloc(a->lens, cap * sizeof *a->lens);
		if (!p)
			return;
		a->lens = p;
		a->cap = cap;
	}
	a->lens[a->n++] = len;
	a->xlo = fmin(a->xlo, fl->x0);
	a->xhi = fmax(a->xhi, fl->x0 + fl->nx * fl->cell);
	a->yhi = fmax(a->yhi, fl->ny * fl->cell);
}

/* Panel (r, sys)'s arrows: their lengths into a (f NULL), or their rows into f, as
 * panel 2 r + sys, clipped to the common length. */
static void field_arrows(const field *fl, arrows *a, FILE *f, const panels *P, int r, int sys)
{
	const double cell = fl->cell, scale = a->umax > 0 ? 0.9 * cell / a->umax : 1;
	const double cmin = 0.2 * median_positive(fl->sc, fl->ny * fl->nx);
	for (size_t rr = 0; rr < fl->ny; rr++)
		for (size_t c = 0; c < fl->nx; c++) {
			const size_t q = rr * fl->nx + c;
			if (fl->sc[q] <= 0 || fl->sc[q] < cmin)
				continue;
			double ux = fl->sx[q] / fl->sc[q], uy = fl->sy[q] / fl->sc[q];
			const double x = fl->x0 + (c + 0.5) * cell, y = (rr + 0.5) * cell;
			if (!f) {
				arrows_note(a, fl, hypot(ux, uy));
				continue;
			}
			if (a->umax > 0 && hypot(ux, uy) > a->umax) {
				const double shrink = a->umax / hypot(ux, uy); /* clipped */
				ux *= shrink;
				uy *= shrink;
			}
			fprintf(f, "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", 2 * r + sys, P->freqs[r],
				sys_ratio(P, sys), x - 0.5 * ux * scale, y - 0.5 * uy * scale, ux, uy, fl->sc[q], ux * scale,
				uy * scale);
		}
}

/* Run r's intruder where it settled (x at the first sample of its trajectory, the
 * settled height y0, its radius) into fi as panel p's; 1 when it has one. */
static int settled_place(const an_run *r, int p, FILE *fi)
{
	traj tr;
	sb_err e = {0};
	const int rc = traj_read(r->path, &tr, &e);
	const int ok = !rc && isfinite(tr.x0) && isfinite(tr.y0) && isfinite(tr.radius);
	if (ok)
		fprintf(fi, "%d,%s,%.17g,%.17g,%.17g\n", p, r->id, tr.x0, tr.y0, tr.radius);
	traj_free(&tr);
	return ok;
}

/* Every panel's field, in two passes (f NULL: the lengths, to find the common scale;
 * then the rows into f and the intruder's settled places into fi); the panels drawn,
 * or -1 with the error in e. */
static int fig1_pass(const an_tool *t, const panels *P, arrows *a, FILE *f, FILE *fi, sb_err *e)
{
	int drawn = 0;
	for (int r = 0; r < P->nf; r++)
		for (int sys = 0; sys < P->nsys; sys++) {
			field fl = {0};
			for (int i = 0; i < t->k; i++) {
				const an_run *run = &t->runs[i];
				if (USED(run) && near(an_num(run, "frequency", NAN), P->freqs[r]) &&
				    near(an_num(run, "radius_ratio", 0), sys_ratio(P, sys)) && field_add(&fl, run, e)) {
					field_free(&fl);
					return -1;
				}
			}
			if (fl.runs && fl.sx && fl.sy && fl.sc) {
				field_arrows(&fl, a, f, P, r, sys);
				drawn++;
				a->cell[2 * r + sys] = fl.cell;
				a->runs[2 * r + sys] = fl.runs;
				for (int i = 0; f && sys && i < t->k; i++) {
					const an_run *run = &t->runs[i];
					if (USED(run) && near(an_num(run, "frequency", NAN), P->freqs[r]) &&
					    near(an_num(run, "radius_ratio", 0), sys_ratio(P, sys)))
						a->settled[2 * r + sys] += settled_place(run, 2 * r + sys, fi);
				}
			}
			if (fl.cell > 0)
				a->head = fl.cell;
			field_free(&fl);
		}
	return drawn;
}

/* The box of the runs drawn: its inner width W and the radius of its wall disks. */
static void box_of(const an_tool *t, double *W, double *rw)
{
	*W = NAN;
	*rw = 1;
	for (int i = 0; i < t->k && isnan(*W); i++)
		if (t->runs[i].group >= 0) {
			*W = an_num(&t->runs[i], "width", NAN);
			*rw = an_num(&t->runs[i], "wall_radius", 1);
		}
}

static int fig1_plot(an_tool *t, const panels *P, const arrows *a, int drawn)
{
	char script[1400], png[1400], set[512];
	/* the panels show the box: the inner width W between the side walls, the floor at
	 * 0, a wall (one disk diameter) on either side; at one scale in x and y, so the
	 * canvas takes the box's shape (a panel's margins are about 75 pixels) */
	double W, rw;
	box_of(t, &W, &rw);
	if (!(W > 0))
		W = a->xhi - a->xlo;
	/* above the grid, a strip of 1.2 cells for the reference arrow */
	const double x0 = -2 * rw, x1 = W + 2 * rw, y0 = -2 * rw, y1 = a->yhi + 1.2 * a->head;
	/* a row per frequency with both systems; one system alone fills rows of up to 3 */
	const int cols = P->nsys > 1 ? P->nsys : (P->nf < 3 ? P->nf : 3), rows = (P->nf * P->nsys + cols - 1) / cols;
	const int pw = cols > 1 ? 450 : 600, aw = pw - 80;
	const int ph = (int)(aw * (y1 - y0) / (x1 - x0)) + 80;
	FILE *f = tool_gp_open(t, "fig1", pw * cols, ph * rows + 50, script, png, sizeof script);
	if (!f)
		return t->e.code;
	tool_setting(t, set, sizeof set);
	fprintf(f, "set multiplot layout %d,%d title \"Fig. 1: mean displacement per period%s%s\\n"
		   "arrows to scale, the 95th percentile (%.3g cm) = 0.9 cell (the black reference arrow); longer ones "
		   "clipped\\ncircles: the intruder where it settled, each run\"\n"
		   "set size ratio -1\nunset key\nset xrange [%g:%g]\nset yrange [%g:%g]\n"
		   "set xlabel 'x (cm)'\nset ylabel 'height above the floor (cm)'\nunset grid\nset tics out\n"
		   		   "set object 1 rect from %g, %g to 0, graph 1 fc rgb '#b0b0b0' fs solid 1 noborder behind\n"
		   "set object 2 rect from %g, %g to %g, graph 1 fc rgb '#b0b0b0' fs solid 1 noborder behind\n"
		   "set object 3 rect from %g, %g to %g, 0 fc rgb '#b0b0b0' fs solid 1 noborder behind\n",
		rows, cols, *set ? ", " : "", set, a->umax, x0, x1, y0, y1, x0, y0, W, y0, x1, x0, y0, x1);
	for (int r = 0; r < P->nf; r++)
		for (int sys = 0; sys < P->nsys; sys++) {
			char words[128], title[256], ref[64];
			const int p = 2 * r + sys;
			const double cell = a->cell[p];
			sys_words(P, sys, P->freqs[r], words, sizeof words);
			snprintf(title, sizeof title, "%s; %d run%s averaged, cell %.3g cm", words, a->runs[p],
				 a->runs[p] == 1 ? "" : "s", cell);
			fprintf(f, "set title ");
			gp_str(f, title);
			/* the reference arrow: the common length umax drawn at this panel's 0.9 cell,
			 * at the top right of the box, its length in words at its left */
			fprintf(f, "\nunset arrow\nunset label\n");
			if (cell > 0 && a->umax > 0) {
				const double xe = W - 0.5 * cell, ye = a->yhi + 0.6 * a->head;
				snprintf(ref, sizeof ref, "%.3g cm per period", a->umax);
				fprintf(f, "set arrow 1 from %.17g, %.17g to %.17g, %.17g head filled size %.3g,20 lw 1.5 "
					   "lc rgb 'black' front\nset label 1 ", xe - 0.9 * cell, ye, xe, ye, 0.25 * cell);
				gp_str(f, ref);
				fprintf(f, " at %.17g, %.17g right offset -0.5, 0 front\n", xe - 0.9 * cell, ye);
			}
			fprintf(f, "plot 'fig1_field.csv' skip 1 using 4:5:($1==%d?$9:1/0):10 with vectors head filled size %.3g,20 lc rgb '#1f4e9c'",
				p, 0.25 * a->head);
			if (a->settled[p])
				fprintf(f, ", \\\n  'fig1_intruder.csv' skip 1 using 3:($1==%d?$4:1/0):5 with circles lw 1.5 "
					   "lc rgb '#cc3311' fs empty", p);
			fputc('\n', f);
		}
	return plot_end(t, f, "fig1", script, png, drawn, "panel");
}

/* fig1_field.csv and fig1.png */
static int fig1(an_tool *t, const panels *P)
{
	FILE *f = tool_out_open(t, "fig1_field.csv");
	if (!f)
		return t->e.code;
	fprintf(f, "panel,frequency,radius_ratio,x,y,ux,uy,count,dx,dy\n");
	FILE *fi = tool_out_open(t, "fig1_intruder.csv");
	if (!fi)
		return tool_out_close(t, f);
	fprintf(fi, "panel,run,x,y,radius\n");
	arrows a = {.xlo = INFINITY, .xhi = -INFINITY, .head = 1};
	int drawn = fig1_pass(t, P, &a, NULL, NULL, &t->e);
	a.umax = percentile(a.lens, a.n, 0.95);
	if (drawn >= 0)
		drawn = fig1_pass(t, P, &a, f, fi, &t->e);
	free(a.lens);
	/* no half-made table beside an accounting it contradicts: one not written whole
	 * is not put in place (tool_out_close) */
	tool_out_close(t, fi);
	if (tool_out_close(t, f) || drawn < 0)
		return t->e.code;
	if (!drawn)
		printf("# fig1: no run with field = yes; skipped\n");
	else if (!t->o->no_plot)
		return fig1_plot(t, P, &a, drawn);
	return 0;
}

/* ---- Fig. 3: Phi(D) ---- */

/* One panel's profile: Phi(D) of its runs, pooled by their periods after the
 * transient; each run's own profile is kept for the band (measure/wmean.h). */
typedef struct profile {
	size_t L;
	double *phi;  /* [runs][L] each run's time-mean Phi per line */
	double *sh;   /* [L] sums of w * D over the runs, w their periods */
	double *w;    /* [runs] their periods after the transient */
	double wsum;
	double hs;    /* sum of the runs' settled surface heights h_s */
	int runs, cap;
} profile;

static void profile_add(profile *pr, an_run *r, const flux_opts *fo)
{
	flux_data fd;
	if (fluxrun_load(r, &fd))
		return; /* classified as usable: only a file changed since could fail */
	if (!pr->runs) {
		free(pr->sh);
		pr->L = fd.L;
		pr->sh = calloc(pr->L ? pr->L : 1, sizeof *pr->sh);
	}
	const size_t p0 = flux_first(&fd, fo);
	/* the runs' periods pooled: a failed run weighs what it recorded */
	const double w = fd.P > p0 ? (double)(fd.P - p0) : 0;
	if (pr->runs == pr->cap) {
		const int cap = pr->cap ? 2 * pr->cap : 8;
		double *phi = realloc(pr->phi, sizeof *phi * (size_t)cap * (pr->L ? pr->L : 1));
		double *ws = realloc(pr->w, sizeof *ws * (size_t)cap);
		if (phi)
			pr->phi = phi;
		if (ws)
			pr->w = ws;
		if (phi && ws)
			pr->cap = cap;
	}
	if (pr->sh && pr->runs < pr->cap && fd.L == pr->L && w > 0) {
		double *prof = pr->phi + (size_t)pr->runs * pr->L;
		flux_profile(&fd, fo, prof);
		for (size_t l = 0; l < pr->L; l++)
			pr->sh[l] += w * fd.h[l];
		pr->w[pr->runs++] = w;
		pr->wsum += w;
		pr->hs += fd.surface;
	}
	flux_free(&fd);
}

static void profile_free(profile *pr)
{
	free(pr->phi);
	free(pr->sh);
	free(pr->w);
}

/* Panel (r, sys)'s curve and band into f and its table row; its phi_max with the band
 * of |Phi| on its line, and half height. */
static void profile_out(const profile *pr, const panels *P, int r, int sys, const an_acct *a, FILE *f,
			wmean_res *pm, double *half, int *headed)
{
	wmean_res *m = malloc(sizeof *m * (pr->L ? pr->L : 1));
	*pm = (wmean_res){0, 0, NAN, NAN, NAN};
	*half = NAN;
	for (size_t l = 0; m && l < pr->L; l++) {
		wmean_ci(pr->phi + l, pr->L, pr->w, (size_t)pr->runs, P->level, &m[l]);
		fprintf(f, "%d,%d,%.17g,%.17g,%zu,%.17g,%.17g,%d,%.17g,%.17g\n", r, sys, P->freqs[r], sys_ratio(P, sys), l,
			pr->sh[l] / pr->wsum, m[l].mean, pr->runs, m[l].lo, m[l].hi);
		if (fabs(m[l].mean) > pm->mean) {
			/* the band of |Phi|: a negative Phi's mirrored */
			const int neg = m[l].mean < 0;
			*pm = (wmean_res){m[l].n, fabs(m[l].mean), m[l].se, neg ? -m[l].hi : m[l].lo, neg ? -m[l].lo : m[l].hi};
		}
	}
	for (size_t l = 0; m && l < pr->L && isnan(*half); l++)
		if (pm->mean > 0 && fabs(m[l].mean) >= 0.5 * pm->mean)
			*half = pr->sh[l] / pr->wsum;
	free(m);
	if (!(*headed)++)
		printf("%-10s %-6s %5s %10s %10s %10s %12s %6s %10s\n", "frequency", "R", "used", "phi_max", "phi_lo", "phi_hi",
		       "half_height", "failed", "unfinished");
	printf("%-10g %-6g %5d %10.4g %10.4g %10.4g %12.4g %6ld %10ld\n", P->freqs[r], sys_ratio(P, sys), pr->runs, pm->mean,
	       pm->lo, pm->hi, *half, a->failed, a->n[AN_PENDING] + a->n[AN_RUNNING]);
}

/* Panel (r, sys): its curve and table row when a run is drawn; its stored rows when
 * it has runs of any kind. Returns the runs drawn (0: none). */
static int fig3_panel(an_tool *t, panels *P, int r, int sys, FILE *f, int *headed)
{
	const int j = r * P->nsys + sys;
	const an_acct *a = &t->A[j];
	profile pr = {0};
	wmean_res pm = {0, 0, NAN, NAN, NAN};
	double half = NAN;
	for (int i = 0; i < t->k; i++)
		if (USED(&t->runs[i]) && t->runs[i].group == j)
			profile_add(&pr, &t->runs[i], &P->fo);
	if (pr.runs)
		profile_out(&pr, P, r, sys, a, f, &pm, &half, headed);
	P->hs[r][sys] = pr.runs ? pr.hs / pr.runs : NAN;
	long any = 0;
	for (int u = 0; u < AN_NUSE; u++)
		any += a->n[u];
	if (any) {
		char g[128];
		snprintf(g, sizeof g, "fig3 f=%g radius_ratio=%g", P->freqs[r], sys_ratio(P, sys));
		if (pr.runs) {
			tool_store(t, j, g, "phi_max", pm.mean, pm.lo, pm.hi, pr.runs);
			tool_store(t, j, g, "half_height", half, NAN, NAN, pr.runs);
		}
		tool_store(t, j, g, "runs", pr.runs, NAN, NAN, pr.runs);
		tool_store_acct(t, g, j);
	}
	profile_free(&pr);
	return pr.runs;
}

/* Fig. 3's band in words, for the figure and the output */
static void band_words(const panels *P, char *buf, size_t n)
{
	snprintf(buf, n, "%g %% CI of the mean over a curve's runs (Student t, each run weighted by its periods)",
		 100 * P->level);
}

static int fig3_plot(an_tool *t, const panels *P, int drawn)
{
	char script[1400], png[1400], set[512], w[2][96], band[160];
	FILE *f = tool_gp_open(t, "fig3", 800, 270 * P->nf + 100, script, png, sizeof script);
	if (!f)
		return t->e.code;
	tool_setting(t, set, sizeof set);
	sys_words(P, 0, NAN, w[0], sizeof w[0]);
	sys_words(P, 1, NAN, w[1], sizeof w[1]);
	band_words(P, band, sizeof band);
	fprintf(f, "set multiplot layout %d,1 title \"Fig. 3: convective flux Φ through planes at height D%s%s\\n"
		   "band: %s\"\n"
		   "set xlabel 'D (cm above the floor)'\nset ylabel 'Φ (particles per period)'\n"
		   "set style fill transparent solid 0.2 noborder\n",
		P->nf, *set ? "\\n" : "", set, band);
	for (int r = 0; r < P->nf; r++) {
		/* one legend, below the last panel: the systems are the same in every row */
		fprintf(f, "%s", r + 1 < P->nf ? "unset key\n" : "set key below height 1\n");
		/* the runs each band rests on, in the row's title */
		char fw[64], title[320];
		label_num(fw, sizeof fw, "frequency", P->freqs[r]);
		int l = snprintf(title, sizeof title, "%s; runs:", fw);
		for (int sys = 0; sys < P->nsys && l > 0 && (size_t)l < sizeof title; sys++)
			l += snprintf(title + l, sizeof title - (size_t)l, "%s %d %s", sys ? "," : "", P->runs[r][sys], w[sys]);
		fprintf(f, "set title ");
		gp_str(f, title);
		fputc('\n', f);
		/* the settled surface h_s of each curve's runs: a dotted line in its colour */
		fprintf(f, "unset arrow\n");
		for (int sys = 0; sys < P->nsys; sys++)
			if (P->runs[r][sys] > 0 && isfinite(P->hs[r][sys]))
				fprintf(f, "set arrow %d from %.17g, graph 0 to %.17g, graph 1 nohead lt %d dt 3 lw 1.5\n", sys + 1,
					P->hs[r][sys], P->hs[r][sys], sys + 1);
		fprintf(f, "plot ");
		for (int sys = 0; sys < P->nsys; sys++) {
			/* the band behind its curve; a curve of one run has none */
			if (P->runs[r][sys] > 1)
				fprintf(f, "'fig3_profile.csv' skip 1 using 6:($1==%d&&$2==%d?$9:1/0):10 with filledcurves lt %d notitle, "
					   "\\\n  ", r, sys, sys + 1);
			fprintf(f, "'fig3_profile.csv' skip 1 using 6:($1==%d&&$2==%d?$7:1/0) with linespoints pt %d ps 0.5 lt %d title ",
				r, sys, sys ? 5 : 7, sys + 1);
			gp_str(f, w[sys]);
			fprintf(f, ", \\\n  ");
			if (P->runs[r][sys] > 0 && isfinite(P->hs[r][sys])) {
				char hl[256];
				snprintf(hl, sizeof hl, "settled surface h_s = %.3g cm (%s)", P->hs[r][sys], w[sys]);
				fprintf(f, "keyentry with lines lt %d dt 3 lw 1.5 title ", sys + 1);
				gp_str(f, hl);
				fprintf(f, ", \\\n  ");
			}
		}
		fprintf(f, "0 with lines lc 'gray' notitle\n");
	}
	return plot_end(t, f, "fig3", script, png, drawn, "curve");
}

/* fig3_profile.csv, the table of the curves, their stored rows and fig3.png */
static int fig3(an_tool *t, panels *P)
{
	FILE *f = tool_out_open(t, "fig3_profile.csv");
	if (!f)
		return t->e.code;
	fprintf(f, "row,system,frequency,radius_ratio,line,D,phi,runs,phi_lo,phi_hi\n");
	int drawn = 0, headed = 0;
	for (int r = 0; r < P->nf; r++)
		for (int sys = 0; sys < P->nsys; sys++) {
			P->runs[r][sys] = fig3_panel(t, P, r, sys, f, &headed);
			drawn += P->runs[r][sys] > 0;
		}
	if (tool_out_close(t, f))
		return t->e.code;
	if (!drawn) {
		printf("# fig3: no run with flux = yes; skipped\n");
		return 0;
	}
	char band[160];
	band_words(P, band, sizeof band);
	printf("# fig3: band: %s; it rests on a curve's used runs (none for one run)\n", band);
	return t->o->no_plot ? 0 : fig3_plot(t, P, drawn);
}

/* ---- Fig. 4: intruder height ---- */

#define MAXREP 64

/* One panel of Fig. 4: the runs drawn (every replicate), their waiting times, and the
 * representative. */
typedef struct f4panel {
	double ra;
	int run[MAXREP], n;
	double wt[MAXREP];  /* the engine's waiting time, or the time observed when not risen */
	int risen[MAXREP];
	int rep;            /* index into run[] of the representative */
	double y0, surface; /* the representative's settled height and surface (box frame) */
	double radius;      /* its intruder's radius: risen at y0 + 2 radius (docs/model.md, "Waiting time") */
} f4panel;

/* order of runs for the representative: risen ones by waiting time, then the censored
 * ones by the time observed; ties by replicate */
static const f4panel *f4_sort_panel;
static const an_tool *f4_sort_tool;
static int f4_cmp(const void *a, const void *b)
{
	const f4panel *P = f4_sort_panel;
	const int i = *(const int *)a, j = *(const int *)b;
	if (P->risen[i] != P->risen[j])
		return P->risen[j] - P->risen[i];
	if (P->wt[i] != P->wt[j])
		return P->wt[i] < P->wt[j] ? -1 : 1;
	const long ri = f4_sort_tool->runs[P->run[i]].replicate, rj = f4_sort_tool->runs[P->run[j]].replicate;
	return (ri > rj) - (ri < rj);
}

/* Panel ra at f4: every used run (finished or failed up to its failure) with a
 * trajectory, and the representative: the run whose waiting time is the group's median
 * (the runs ordered by waiting time, the censored ones after every risen one; the
 * lower middle one of an even count). 0 when the panel has no run. */
static int fig4_panel(const an_tool *t, double f4, double ra, f4panel *P)
{
	memset(P, 0, sizeof *P);
	P->ra = ra;
	for (int i = 0; i < t->k && P->n < MAXREP; i++) {
		const an_run *r = &t->runs[i];
		if (!USED(r) || !near(an_num(r, "frequency", NAN), f4) || !near(an_num(r, "radius_ratio", 0), ra))
			continue;
		hid_t h;
		sb_err he = {0};
		double rs = 0, w = NAN;
		if (h5r_open(r->path, &h, &he))
			continue;
		const int has = h5r_exists(h, RUNFILE_INTRUDER);
		sb_err re = {0};
		if (traj_rise(h, r->path, &rs, &w, &re)) /* not risen, observed for an unknown time */
			rs = 0, w = NAN;
		h5r_close(h);
		if (!has)
			continue;
		P->run[P->n] = i;
		P->risen[P->n] = rs != 0;
		P->wt[P->n++] = isfinite(w) ? w : INFINITY;
	}
	if (!P->n)
		return 0;
	int ord[MAXREP];
	for (int k = 0; k < P->n; k++)
		ord[k] = k;
	f4_sort_panel = P;
	f4_sort_tool = t;
	qsort(ord, (size_t)P->n, sizeof *ord, f4_cmp);
	P->rep = ord[(P->n - 1) / 2];
	return 1;
}

/* Panel p's trajectories into f (lab frame and box frame); the representative's
 * settled height and surface into P. 1 when the representative's was read. */
static int fig4_traj(const an_tool *t, f4panel *P, int p, FILE *f)
{
	int ok = 0;
	for (int k = 0; k < P->n; k++) {
		const an_run *r = &t->runs[P->run[k]];
		traj tr;
		sb_err e = {0};
		if (traj_read(r->path, &tr, &e)) {
			traj_free(&tr);
			continue;
		}
		for (size_t j = 0; j < tr.n; j++)
			fprintf(f, "%d,%.17g,%s,%ld,%d,%.17g,%.17g,%.17g,%d\n", p, P->ra, r->id, r->replicate, k, tr.t[j], tr.y[j],
				tr.ybox[j], k == P->rep);
		if (k == P->rep) {
			P->y0 = tr.y0;
			P->surface = tr.surface;
			P->radius = tr.radius;
			ok = 1;
		}
		traj_free(&tr);
	}
	return ok;
}

static int fig4_plot(an_tool *t, double f4, const f4panel *F, int drawn)
{
	char script[1400], png[1400], set[512];
	FILE *f = tool_gp_open(t, "fig4", 800, 290 * drawn + 110, script, png, sizeof script);
	if (!f)
		return t->e.code;
	tool_setting(t, set, sizeof set);
	char fw[64];
	label_num(fw, sizeof fw, "frequency", f4);
	fprintf(f, "set multiplot layout %d,1 title \"Fig. 4: height of the intruder, %s%s%s\\n"
		   "every replicate (thin); thick: the run whose waiting time is the median of its panel\"\n"
		   "set xlabel 't (s)'\nset ylabel 'y (cm above the box floor)'\n", drawn, fw, *set ? ", " : "", set);
	for (int p = 0; p < drawn; p++) {
		const f4panel *P = &F[p];
		const an_run *rep = &t->runs[P->run[P->rep]];
		char v[64], w[96], lr[256], le[64];
		snprintf(v, sizeof v, "%.17g", P->ra);
		label_param(w, sizeof w, "radius_ratio", v);
		snprintf(le, sizeof le, "each replicate (%d runs)", P->n);
		if (P->risen[P->rep])
			snprintf(lr, sizeof lr, "median run: replicate %ld, rose at %.3g s", rep->replicate, P->wt[P->rep]);
		else
			snprintf(lr, sizeof lr, "median run: replicate %ld, not risen in %.3g s", rep->replicate, P->wt[P->rep]);
		fprintf(f, "set key below height 1\nset title ");
		gp_str(f, w);
		fprintf(f, "\nplot ");
		for (int k = 0; k < P->n; k++) {
			fprintf(f, "%s'fig4_traj.csv' skip 1 using 6:($1==%d&&$5==%d?$8:1/0) with lines lw 0.7 lc rgb '#909cc8' ",
				k ? ", \\\n  " : "", p, k);
			if (k)
				fprintf(f, "notitle");
			else {
				fprintf(f, "title ");
				gp_str(f, le);
			}
		}
		fprintf(f, ", \\\n  'fig4_traj.csv' skip 1 using 6:($1==%d&&$9==1?$8:1/0) with lines lw 2 lc rgb '#1f4e9c' title ",
			p);
		gp_str(f, lr);
		fprintf(f, ", \\\n  %.17g with lines dt 2 lc 'gray' title 'settled height', %.17g with lines dt 3 lc 'black' "
			   "title 'free surface (t = 0)'", P->y0, P->surface);
		/* the engine's rule: risen once the centre is one diameter above the settled
		 * height (docs/model.md, "Waiting time"; the representative's) */
		if (isfinite(P->y0) && isfinite(P->radius))
			fprintf(f, ", \\\n  %.17g with lines dt 4 lw 1.5 lc rgb '#cc3311' title 'risen level y₀ + 2R = %.3g cm "
				   "(the engine''s rule)'", P->y0 + 2 * P->radius, P->y0 + 2 * P->radius);
		fputc('\n', f);
	}
	return plot_end(t, f, "fig4", script, png, drawn, "panel");
}

/* fig4_traj.csv and fig4.png: one panel per radius ratio > 0 of the campaign (at most
 * 8), at the highest row's frequency, every replicate */
static int fig4(an_tool *t, const panels *P)
{
	FILE *f = tool_out_open(t, "fig4_traj.csv");
	if (!f)
		return t->e.code;
	fprintf(f, "panel,radius_ratio,run,replicate,index,t,y,y_box,representative\n");
	const double f4 = P->nf ? P->freqs[P->nf - 1] : NAN;
	f4panel F[8];
	int drawn = 0;
	for (int q = 0; q < P->nra && drawn < 8; q++)
		if (fig4_panel(t, f4, P->ratios[q], &F[drawn]) && fig4_traj(t, &F[drawn], drawn, f))
			drawn++;
	if (tool_out_close(t, f))
		return t->e.code;
	char fw[64];
	label_num(fw, sizeof fw, "frequency", f4);
	if (!drawn)
		printf("# fig4: no run with an intruder at %s; skipped\n", fw);
	else {
		printf("# fig4: %s, every replicate; the representative is the run whose waiting time is its panel's median"
		       " (risen runs by waiting time, then the censored ones; the lower middle of an even count):", fw);
		for (int p = 0; p < drawn; p++)
			printf("%s 𝓡 = %g: replicate %ld of %d runs", p ? ";" : "", F[p].ra, t->runs[F[p].run[F[p].rep]].replicate,
			       F[p].n);
		printf("\n");
		if (!t->o->no_plot)
			return fig4_plot(t, f4, F, drawn);
	}
	return 0;
}

static int init(an_tool *t, void *vs, const xopt *x)
{
	(void)x;
	panels *P = vs;
	P->fo = (flux_opts){0.4, 0.6, t->o->skip};
	P->level = t->o->level;
	return 0;
}

static int run(an_tool *t, void *vs)
{
	panels *P = vs;
	if (tool_where_known(t) || consider(t, P) || pooled_axis(t) || layout(t, P) || cli_outdir(t->o, &t->e) ||
	    tool_accounting_csv(t) || tool_store_begin(t) || fig1(t, P) || fig3(t, P) || fig4(t, P) ||
	    tool_store_end(t))
		return t->e.code;
	tool_report(t, stdout, "what they recorded before the failure: Fig. 3 with their periods after the transient"
			       " of the run as planned (the runs' periods are pooled), Fig. 1 with their samples");
	printf("# csv: %s/fig{1_field,1_intruder,3_profile,4_traj}.csv %s/figures_accounting.csv\n", t->o->out, t->o->out);
	return 0;
}

static const tool_spec SPEC = {.name = "figures", .version = VERSION, .help = HELP,
			       .allowed = " freq ratio skip level where ", .init = init, .run = run};

/* ---- figures --run: one run file, no campaign ---- */

static const char RUN_HELP[] =
	"usage: figures --run RUN.h5 [--out DIR] [--skip FRAC]\n\n"
	"One run's figures, from its file alone (no campaign, no database), each drawn when\n"
	"the run recorded what it needs and else named as not drawn:\n"
	"  RUN_field.png   the displacement field (field = yes): per cell the mean displacement\n"
	"                  per period over the blocks after the first FRAC (count-weighted), as\n"
	"                  arrows (the 95th percentile = 0.9 cell; cells sampled < 1/5 of the\n"
	"                  median left out), the settled surface dashed;\n"
	"  RUN_phi.png     Phi(D) (flux = yes): the time-mean flux per height line over the\n"
	"                  periods after the first FRAC, with the standard error of that mean\n"
	"                  over the periods as a band, the settled surface dashed;\n"
	"  RUN_height.png  the intruder's height above the box floor against time (traj_rate >\n"
	"                  0), with its settled height, the surface and the engine's waiting\n"
	"                  time when it rose.\n"
	"RUN is the file's name without .h5; DIR defaults to the current directory. With each\n"
	"figure its PDF, gnuplot script and data (CSV). Exit codes: 0 at least one drawn, 1\n"
	"usage or nothing to draw, 2 the file unreadable or a figure not written.\n";

/* the figure's name: DIR/RUN_what, RUN the file's name without .h5 */
static void run_fig_name(const char *file, const char *what, char *out, size_t len)
{
	const char *b = strrchr(file, '/');
	b = b ? b + 1 : file;
	size_t l = strlen(b);
	if (l > 3 && !strcmp(b + l - 3, ".h5"))
		l -= 3;
	snprintf(out, len, "%.*s_%s", (int)l, b, what);
}

/* a figure from its script's body (gp_open's frame), drawn by gnuplot into o->out */
static int run_fig_draw(const an_opts *o, const char *name, const char *body, sb_err *e)
{
	sb_file sc;
	char png[1400];
	FILE *f = gp_open(o, name, 800, 640, &sc, png, sizeof png, e);
	if (!f)
		return e->code;
	fputs(body, f);
	gp_close(f);
	if (cli_close_out(&sc, e))
		return e->code;
	char script[1400];
	snprintf(script, sizeof script, "%s/%s.gp", o->out, name);
	if (gp_run(script, png, e))
		return e->code;
	printf("# figure: %s\n", png);
	return 0;
}

/* After a figure: one that could not be written (a node at its place, a full disk) makes
 * the exit 2; any other error was the reason it was not drawn, said already. */
static void run_fig_settle(sb_err *e, int *rc)
{
	if (e->code && strstr(e->msg, "not written"))
		*rc = 2;
	e->code = 0;
}

static int run_figures(int argc, char **argv)
{
	const char *file = NULL, *out = ".";
	double skip = 0.2;
	for (int k = 1; k < argc; k++) {
		const char *a = argv[k], *v = k + 1 < argc ? argv[k + 1] : NULL;
		if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
			fputs(RUN_HELP, stdout);
			return 0;
		} else if (!strcmp(a, "--run") && v) {
			file = v, k++;
		} else if (!strcmp(a, "--out") && v) {
			out = v, k++;
		} else if (!strcmp(a, "--skip") && v) {
			char *end;
			skip = strtod(v, &end);
			if (end == v || *end || !(skip >= 0 && skip < 1)) {
				fprintf(stderr, "figures: --skip: expected a fraction in [0, 1), got '%s'\n", v);
				return 1;
			}
			k++;
		} else {
			fprintf(stderr, "figures: --run: unknown or extra argument '%s' (figures --run RUN.h5 [--out DIR] "
					"[--skip FRAC]; figures --run --help)\n", a);
			return 1;
		}
	}
	if (!file) {
		fprintf(stderr, "figures: --run: which run file?\n");
		return 1;
	}
	sb_err e = {0};
	if (h5r_walk_env(&e) || fs_check_input(file, "run file", SB_EIO, &e)) {
		fprintf(stderr, "figures: %s\n", e.msg);
		return e.code == SB_EUSAGE ? 1 : 2;
	}
	an_opts o = {.tool = "figures", .version = VERSION};
	snprintf(o.out, sizeof o.out, "%s", out);
	struct stat st;
	if (stat(out, &st) || !S_ISDIR(st.st_mode)) {
		fprintf(stderr, "figures: --out %s: no such directory\n", out);
		return 1;
	}
	int drawn = 0, rc = 0;
	char name[600], body[4096], csvname[700];
	sb_file csv;
	/* the field */
	convect_field cf = {0};
	const int cf_rc = convect_read(file, &cf, &e);
	if (cf_rc == 0 && cf.B == 0) {
		printf("# not drawn: the field (no block of field_periods periods was completed)\n");
	} else if (cf_rc == 0) {
		const size_t cells = cf.ny * cf.nx, b0 = (size_t)floor(skip * (double)cf.B);
		double *ux = calloc(cells, sizeof *ux), *uy = calloc(cells, sizeof *uy), *w = calloc(cells, sizeof *w);
		double *len = malloc(cells * sizeof *len);
		size_t nl = 0;
		for (size_t b = b0; ux && uy && w && b < cf.B; b++)
			for (size_t c = 0; c < cells; c++) {
				const double n = cf.n[b * cells + c];
				if (n > 0 && isfinite(cf.ux[b * cells + c]) && isfinite(cf.uy[b * cells + c])) {
					ux[c] += n * cf.ux[b * cells + c], uy[c] += n * cf.uy[b * cells + c], w[c] += n;
				}
			}
		const double wmed = ux && w ? median_positive(w, cells) : 0;
		for (size_t c = 0; len && w && c < cells; c++)
			if (w[c] > 0 && w[c] >= wmed / 5)
				len[nl++] = hypot(ux[c] / w[c], uy[c] / w[c]);
		const double p95 = len ? percentile(len, nl, 0.95) : 0, scale = p95 > 0 ? 0.9 * cf.cell / p95 : 1;
		run_fig_name(file, "field", name, sizeof name);
		snprintf(csvname, sizeof csvname, "%s.csv", name);
		if (ux && uy && w && len && nl && !cli_open_out(&o, csvname, &csv, &e)) {
			fprintf(csv.f, "x,y,ux,uy,samples\n");
			for (size_t r = 0; r < cf.ny; r++)
				for (size_t c = 0; c < cf.nx; c++) {
					const size_t i = r * cf.nx + c;
					if (w[i] > 0 && w[i] >= wmed / 5)
						fprintf(csv.f, "%.6g,%.6g,%.6g,%.6g,%.6g\n", cf.x0 + (c + 0.5) * cf.cell,
							(r + 0.5) * cf.cell, ux[i] / w[i], uy[i] / w[i], w[i]);
				}
			if (!cli_close_out(&csv, &e)) {
				snprintf(body, sizeof body,
					 "set title '%s: displacement field, %zu blocks of %ld periods after the first %.0f %% (arrow 0.9 cell = %.3g cm/period)'\n"
					 "set xlabel 'x (cm)'\nset ylabel 'height above the floor (cm)'\nset size ratio -1\n"
					 "set xrange [%g:%g]\nset yrange [0:%g]\n"
					 "plot '%s' skip 1 using 1:2:($3*%.9g):($4*%.9g) with vectors head size 0.3,20 lc rgb '#1f4e9a' title 'mean displacement per period', "
					 "%g with lines dt 2 lc rgb '#888888' title sprintf('settled surface %%.1f cm', %g)\n",
					 file, cf.B - b0, cf.K, 100 * skip, p95, cf.x0, cf.x0 + cf.nx * cf.cell, cf.ny * cf.cell, csvname,
					 scale, scale, cf.surface, cf.surface);
				if (!run_fig_draw(&o, name, body, &e))
					drawn++;
			}
		}
		if (!nl)
			printf("# not drawn: the field (no cell sampled after the first %.0f %% of the blocks)\n", 100 * skip);
		free(ux), free(uy), free(w), free(len);
	} else {
		printf("# not drawn: the field (%s)\n", e.code ? e.msg : "field = no: no field recorded");
	}
	convect_free(&cf);
	run_fig_settle(&e, &rc);
	/* Phi(D) */
	flux_data fd = {0};
	if (flux_read(file, &fd, &e) == 0 && fd.P > 0) {
		flux_opts fo = FLUX_OPTS_DEFAULT;
		fo.skip = skip;
		const size_t p0 = flux_first(&fd, &fo), m = fd.P > p0 ? fd.P - p0 : 0;
		run_fig_name(file, "phi", name, sizeof name);
		snprintf(csvname, sizeof csvname, "%s.csv", name);
		if (m >= 1 && !cli_open_out(&o, csvname, &csv, &e)) {
			fprintf(csv.f, "height,phi,phi_lo,phi_hi\n");
			for (size_t l = 0; l < fd.L; l++) {
				double s1 = 0, s2 = 0;
				for (size_t p = p0; p < fd.P; p++)
					s1 += fd.phi[p * fd.L + l], s2 += fd.phi[p * fd.L + l] * fd.phi[p * fd.L + l];
				const double mean = s1 / (double)m,
					     se = m > 1 ? sqrt(fmax(0, (s2 - s1 * mean) / (double)(m - 1)) / (double)m) : 0;
				fprintf(csv.f, "%.6g,%.6g,%.6g,%.6g\n", fd.h[l], mean, mean - se, mean + se);
			}
			if (!cli_close_out(&csv, &e)) {
				snprintf(body, sizeof body,
					 "set title '%s: Phi(D) over %zu periods after the first %.0f %%, band: standard error over the periods'\n"
					 "set xlabel 'height D above the floor (cm)'\nset ylabel 'Phi (particles per period)'\n"
					 "set arrow from %g, graph 0 to %g, graph 1 nohead dt 2 lc rgb '#888888'\n"
					 "set label sprintf('settled surface %%.1f cm', %g) at %g, graph 0.95 right offset -0.5,0\n"
					 "plot '%s' skip 1 using 1:3:4 with filledcurves fc rgb '#c6d4ef' title 'standard error', "
					 "'' skip 1 using 1:2 with lines lw 2 lc rgb '#1f4e9a' title 'Phi(D)'\n",
					 file, m, 100 * skip, fd.surface, fd.surface, fd.surface, fd.surface, csvname);
				if (!run_fig_draw(&o, name, body, &e))
					drawn++;
			}
		} else if (!m) {
			printf("# not drawn: Phi(D) (no period after the first %.0f %%)\n", 100 * skip);
		}
	} else {
		printf("# not drawn: Phi(D) (%s)\n", e.code ? e.msg : "flux = no: no flux recorded");
	}
	flux_free(&fd);
	run_fig_settle(&e, &rc);
	/* the intruder's height */
	traj tr = {0};
	const int tr_rc = traj_read(file, &tr, &e);
	if (tr_rc == 0 && tr.n > 0) {
		double risen = 0, wait = NAN;
		hid_t f;
		if (!h5r_open(file, &f, &e)) {
			if (traj_rise(f, file, &risen, &wait, &e))
				risen = 0, e.code = 0;
			h5r_close(f);
		}
		run_fig_name(file, "height", name, sizeof name);
		snprintf(csvname, sizeof csvname, "%s.csv", name);
		if (!cli_open_out(&o, csvname, &csv, &e)) {
			fprintf(csv.f, "time,height_box\n");
			for (size_t i = 0; i < tr.n; i++)
				fprintf(csv.f, "%.9g,%.6g\n", tr.t[i], tr.ybox[i]);
			if (!cli_close_out(&csv, &e)) {
				char rise[200] = "";
				if (risen > 0)
					snprintf(rise, sizeof rise,
						 "set arrow from %g, graph 0 to %g, graph 1 nohead lc rgb '#cc2222'\n"
						 "set label 'risen at %.2f s (the engine''s rule)' at %g, graph 0.05 left offset 0.5,0 tc rgb '#cc2222'\n",
						 wait, wait, wait, wait);
				snprintf(body, sizeof body,
					 "set title '%s: the intruder''s height above the box floor (%s)'\n"
					 "set xlabel 'time (s)'\nset ylabel 'height above the box floor (cm)'\n%s"
					 "plot '%s' skip 1 using 1:2 with lines lw 1.5 lc rgb '#1f4e9a' title 'intruder', "
					 "%g with lines dt 2 lc rgb '#444444' title 'settled height', "
					 "%g with lines dt 3 lc rgb '#888888' title 'settled surface'\n",
					 file, risen > 0 ? "risen" : "not risen within the run", rise, csvname,
					 isfinite(tr.y0) ? tr.y0 : NAN, isfinite(tr.surface) ? tr.surface : NAN);
				if (!run_fig_draw(&o, name, body, &e))
					drawn++;
			}
		}
	} else {
		printf("# not drawn: the intruder's height (%s)\n",
		       tr_rc == 1 ? "no trajectory: no intruder or traj_rate = 0" : e.msg);
		if (tr_rc > 1 && tr_rc != SB_ENAN)
			rc = 2;
	}
	traj_free(&tr);
	if (e.code)
		fprintf(stderr, "figures: %s\n", e.msg), rc = 2;
	if (!drawn && !rc) {
		fprintf(stderr, "figures: %s: nothing to draw (no field, flux or intruder trajectory recorded)\n", file);
		return 1;
	}
	return rc;
}

int main(int argc, char **argv)
{
	for (int k = 1; k < argc; k++) /* one run file, not a campaign */
		if (!strcmp(argv[k], "--run"))
			return run_figures(argc, argv);
	panels P = {0};
	return tool_main(argc, argv, &SPEC, &P);
}
