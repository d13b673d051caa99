/* hysteresis_main.c - bin/hysteresis: transition frequencies of up and down frequency
 * ramps and their difference, bootstrap over seeds. Only this file prints and exits. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "adb.h"
#include "boot.h"
#include "cli.h"
#include "flux.h"
#include "sigmoid.h"

#define VERSION "1"

static const char *HELP =
	"usage: hysteresis CAMPAIGN [--db FILE] [--runs DIR] [--out DIR] [--by KEYS] [--band LO:HI]\n"
	"                  [--smooth K] [--threshold PHI] [--boot N] [--seed S] [--level L]\n"
	"                  [--no-plot] [--no-store]\n\n"
	"Hysteresis of the convection onset. Uses the finished runs with a frequency ramp\n"
	"(ramp = updown: ramp_from -> ramp_to -> ramp_from, split at the turning period; or\n"
	"ramp = linear, up when ramp_to > ramp_from, down otherwise) and a /flux group.\n"
	"Per period: Phi through the plane (mean over the height lines in the band LO..HI of\n"
	"the surface height, default 0.4:0.6) against the period's frequency (/flux/frequency),\n"
	"smoothed by a centred running mean over K periods of the same branch (default 5).\n"
	"Per group (default: radius_ratio, depth and every swept axis except frequency, seed\n"
	"and the ramp keys) and branch, with the seeds pooled: the transition frequency as\n"
	"the midpoint of a fitted sigmoid and as the threshold crossing (as in onset --help),\n"
	"f_up, f_down and their difference f_up - f_down, with percentile bootstrap intervals\n"
	"over seeds (a drawn seed brings both its branches, so the difference is paired).\n\n"
	"  --db FILE, --runs DIR, --out DIR   as for every tool (waiting --help)\n"
	"  --boot N, --seed S, --level L      bootstrap replicates (1000), seed (1), level (0.95)\n"
	"  --no-plot, --no-store\n\n"
	"Writes hysteresis_periods.csv, hysteresis_summary.csv, hysteresis.png; stores per\n"
	"group in `analysis` (tool 'hysteresis'): runs, seeds, up_sigmoid_f, down_sigmoid_f,\n"
	"diff_sigmoid, up_threshold_f, down_threshold_f, diff_threshold (value, lo, hi).\n"
	"Exit codes: 0 ok, 1 usage or no usable runs, 2 I/O.\n";

typedef struct pts {
	double *x, *y;
	long *u;
	size_t n, cap;
} pts;

static int add(pts *p, double x, double y, long u)
{
	if (p->n == p->cap) {
		p->cap = p->cap ? 2 * p->cap : 256;
		double *a = realloc(p->x, sizeof *a * p->cap);
		if (a)
			p->x = a;
		double *b = realloc(p->y, sizeof *b * p->cap);
		if (b)
			p->y = b;
		long *c = realloc(p->u, sizeof *c * p->cap);
		if (c)
			p->u = c;
		if (!a || !b || !c)
			return -1;
	}
	p->x[p->n] = x;
	p->y[p->n] = y;
	p->u[p->n++] = u;
	return 0;
}

typedef struct grp {
	pts br[2];      /* 0 up, 1 down */
	long units[4096];
	size_t nu, nruns;
	double thr;
	double *xs, *ys;
} grp;

static size_t gather(grp *g, int b, const size_t *idx, size_t n)
{
	size_t k = 0;
	for (size_t i = 0; i < n; i++)
		for (size_t j = 0; j < g->br[b].n; j++)
			if (g->br[b].u[j] == g->units[idx[i]]) {
				g->xs[k] = g->br[b].x[j];
				g->ys[k++] = g->br[b].y[j];
			}
	return k;
}

/* out: up fit, down fit, diff, up thr, down thr, diff */
static void stat6(void *ctx, const size_t *idx, size_t n, double *out)
{
	grp *g = ctx;
	for (int b = 0; b < 2; b++) {
		size_t k = gather(g, b, idx, n);
		sig_fit s;
		out[b] = sig_fit_data(g->xs, g->ys, k, &s) ? s.x0 : NAN;
		out[3 + b] = sig_threshold(g->xs, g->ys, k, g->thr);
	}
	out[2] = out[0] - out[1];
	out[5] = out[3] - out[4];
}

int main(int argc, char **argv)
{
	an_opts o = {.tool = "hysteresis", .version = VERSION};
	int pr = cli_parse(&o, argc, argv, HELP, " by band smooth threshold boot seed level ");
	if (pr)
		return pr < 0 ? 0 : 1;
	flux_opts fo = {o.band_lo, o.band_hi, 0};
	sb_err e = {0};
	adb d;
	an_run *runs = NULL;
	int nr = 0, ng = 0, k = 0;
	char **labels = NULL;
	grp *G = NULL;
	flux_data *F = NULL;
	double *bo = NULL;
	FILE *f = NULL, *s = NULL;
	char path[1400], script[1400], png[1400];
	if (adb_open(&d, o.db, !o.no_store, &e) || adb_runs(&d, o.campaign, o.runs, &runs, &nr, &e))
		goto out;
	F = calloc((size_t)(nr ? nr : 1), sizeof *F);
	if (!F) {
		sb_errf(&e, SB_ENOMEM, "out of memory");
		goto out;
	}
	for (int i = 0; i < nr; i++) {
		const char *ramp = an_str(&runs[i], "ramp");
		if (!ramp || !strcmp(ramp, "none"))
			continue;
		sb_err fe = {0};
		if (flux_read(runs[i].path, &F[k], &fe)) {
			fprintf(stderr, "hysteresis: skipping %s\n", fe.msg);
			continue;
		}
		if (F[k].P < 2) {
			flux_free(&F[k]);
			continue;
		}
		an_run t = runs[k];
		runs[k] = runs[i];
		runs[i] = t;
		k++;
	}
	if (!k) {
		sb_errf(&e, SB_EUSAGE, "campaign '%s': no finished ramp run (ramp = linear|updown) with flux = yes in %s",
			o.campaign, o.db);
		goto out;
	}
	static const char *const always[] = {"radius_ratio", "depth", NULL};
	static const char *const drop[] = {"frequency", "ramp", "ramp_from", "ramp_to", NULL};
	char keys[AN_MAXKEYS][48];
	int nk;
	if (cli_keys(&o, &d, always, drop, keys, &nk, &e))
		goto out;
	/* grouping reorders nothing: it only labels */
	ng = an_group_runs(runs, k, keys, nk, &labels);
	G = calloc((size_t)(ng > 0 ? ng : 1), sizeof *G);
	bo = malloc(sizeof *bo * 6 * (size_t)(o.boot > 1 ? o.boot : 1));
	if (ng < 0 || !G || !bo || cli_outdir(&o, &e)) {
		if (!e.code)
			sb_errf(&e, SB_ENOMEM, "out of memory");
		goto out;
	}
	if (!(f = cli_fopen(&o, "hysteresis_periods.csv", path, sizeof path, &e)))
		goto out;
	fprintf(f, "group_index,group,run,replicate,branch,period,frequency,phi,phi_smooth\n");
	for (int i = 0; i < k; i++) {
		grp *g = &G[runs[i].group];
		flux_data *D = &F[i];
		size_t l0, l1;
		flux_band(D, &fo, &l0, &l1);
		const char *ramp = an_str(&runs[i], "ramp");
		double from = an_num(&runs[i], "ramp_from", NAN), to = an_num(&runs[i], "ramp_to", NAN);
		int rising = !(to < from); /* the first leg goes up */
		size_t turn = D->P; /* first period of the second leg */
		if (!strcmp(ramp, "updown")) {
			size_t best = 0;
			for (size_t p = 1; p < D->P; p++)
				if (rising ? D->f[p] > D->f[best] : D->f[p] < D->f[best])
					best = p;
			turn = best + 1;
		}
		size_t u = 0;
		while (u < g->nu && g->units[u] != runs[i].replicate)
			u++;
		if (u == g->nu && g->nu < 4096)
			g->units[g->nu++] = runs[i].replicate;
		g->nruns++;
		for (int leg = 0; leg < 2; leg++) {
			size_t a = leg ? turn : 0, b = leg ? D->P : turn;
			int br = (leg == 0) == rising ? 0 : 1; /* 0 up, 1 down */
			for (size_t p = a; p < b; p++) {
				long h = o.smooth / 2;
				size_t q0 = p >= a + (size_t)h ? p - (size_t)h : a, q1 = p + (size_t)h + 1 < b ? p + (size_t)h + 1 : b;
				double sm = 0;
				for (size_t q = q0; q < q1; q++)
					sm += flux_plane(D, q, l0, l1);
				sm /= (double)(q1 - q0);
				double raw = flux_plane(D, p, l0, l1);
				if (add(&g->br[br], D->f[p], sm, runs[i].replicate)) {
					sb_errf(&e, SB_ENOMEM, "out of memory");
					goto out;
				}
				fprintf(f, "%d,", runs[i].group);
				csv_str(f, labels[runs[i].group]);
				fprintf(f, ",%s,%ld,%s,%zu,%.17g,%.17g,%.17g\n", runs[i].id, runs[i].replicate, br ? "down" : "up", p,
					D->f[p], raw, sm);
			}
		}
	}
	fclose(f);
	f = NULL;
	if (!(s = cli_fopen(&o, "hysteresis_summary.csv", path, sizeof path, &e)))
		goto out;
	fprintf(s, "group,runs,seeds,up_sigmoid_f,up_lo,up_hi,down_sigmoid_f,down_lo,down_hi,diff_sigmoid,diff_lo,diff_hi,"
		   "up_threshold_f,up_thr_lo,up_thr_hi,down_threshold_f,down_thr_lo,down_thr_hi,diff_threshold,"
		   "diff_thr_lo,diff_thr_hi\n");
	printf("%-26s %4s %5s %22s %22s %24s %8s %8s %8s\n", "group", "runs", "seeds", "f_up sigmoid [CI]",
	       "f_down sigmoid [CI]", "up - down [CI] (Hz)", "f_up_thr", "f_dn_thr", "diff_thr");
	if (!o.no_store && adb_store_begin(&d, o.campaign, "hysteresis", &e))
		goto out;
	double (*fitv)[6] = calloc((size_t)ng, sizeof *fitv);
	if (!fitv) {
		sb_errf(&e, SB_ENOMEM, "out of memory");
		goto out;
	}
	for (int j = 0; j < ng && !e.code; j++) {
		grp *g = &G[j];
		g->thr = o.threshold;
		size_t cap = (g->br[0].n > g->br[1].n ? g->br[0].n : g->br[1].n) * (g->nu ? g->nu : 1) + 1;
		g->xs = malloc(sizeof *g->xs * cap);
		g->ys = malloc(sizeof *g->ys * cap);
		size_t *all = malloc(sizeof *all * (g->nu + 1));
		if (!g->xs || !g->ys || !all) {
			free(all);
			sb_errf(&e, SB_ENOMEM, "out of memory");
			break;
		}
		for (size_t u = 0; u < g->nu; u++)
			all[u] = u;
		double *v = fitv[j], lo[6], hi[6];
		stat6(g, all, g->nu, v);
		free(all);
		for (int q = 0; q < 6; q++)
			lo[q] = hi[q] = NAN;
		if (o.boot > 1 && g->nu > 1) {
			if (boot_run(o.seed, g->nu, (size_t)o.boot, 6, stat6, g, bo)) {
				sb_errf(&e, SB_ENOMEM, "out of memory");
				break;
			}
			for (int q = 0; q < 6; q++)
				boot_percentile(bo + q * o.boot, (size_t)o.boot, o.level, &lo[q], &hi[q]);
		}
		char c[3][64];
		for (int q = 0; q < 3; q++)
			snprintf(c[q], sizeof c[q], "%.3f [%.3f, %.3f]", v[q], lo[q], hi[q]);
		printf("%-26s %4zu %5zu %22s %22s %24s %8.3f %8.3f %8.3f\n", labels[j], g->nruns, g->nu, c[0], c[1], c[2], v[3],
		       v[4], v[5]);
		csv_str(s, labels[j]);
		fprintf(s, ",%zu,%zu", g->nruns, g->nu);
		for (int q = 0; q < 6; q++)
			fprintf(s, ",%.17g,%.17g,%.17g", v[q], lo[q], hi[q]);
		fprintf(s, "\n");
		if (!o.no_store) {
			static const char *const names[6] = {"up_sigmoid_f", "down_sigmoid_f", "diff_sigmoid",
							     "up_threshold_f", "down_threshold_f", "diff_threshold"};
			long n = (long)g->nruns;
			adb_store(&d, o.campaign, "hysteresis", VERSION, labels[j], "runs", (double)g->nruns, NAN, NAN, n, &e);
			adb_store(&d, o.campaign, "hysteresis", VERSION, labels[j], "seeds", (double)g->nu, NAN, NAN, n, &e);
			for (int q = 0; q < 6; q++)
				adb_store(&d, o.campaign, "hysteresis", VERSION, labels[j], names[q], v[q], lo[q], hi[q], n, &e);
		}
	}
	free(fitv);
	fclose(s);
	s = NULL;
	if (!o.no_store && adb_store_end(&d, !e.code, &e))
		goto out;
	if (e.code)
		goto out;
	if (!o.no_plot) {
		if (!(f = gp_open(&o, "hysteresis", 1000, 560, script, png, sizeof script, &e)))
			goto out;
		fprintf(f, "set title 'Flux through the plane during frequency ramps (running mean of %ld periods)'\n"
			   "set xlabel 'frequency f (Hz)'\nset ylabel 'Phi (particles per period)'\nplot ",
			o.smooth);
		for (int j = 0; j < ng; j++)
			for (int b = 0; b < 2; b++) {
				fprintf(f, "%s'hysteresis_periods.csv' skip 1 using 7:($1==%d&&strcol(5)eq'%s'?$9:1/0) with points pt %d ps 0.6 lc %d title ",
					j || b ? ", \\\n  " : "", j, b ? "down" : "up", b ? 6 : 7, 2 * j + b + 1);
				char t[600];
				snprintf(t, sizeof t, "%s, %s", labels[j], b ? "down" : "up");
				gp_str(f, t);
			}
		fprintf(f, "\n");
		fclose(f);
		f = NULL;
		if (gp_run(script, png, &e))
			goto out;
		printf("# figure: %s\n", png);
	}
	printf("# csv: %s/hysteresis_{periods,summary}.csv\n", o.out);
out:
	if (f)
		fclose(f);
	if (s)
		fclose(s);
	for (int j = 0; G && j < ng; j++) {
		for (int b = 0; b < 2; b++) {
			free(G[j].br[b].x);
			free(G[j].br[b].y);
			free(G[j].br[b].u);
		}
		free(G[j].xs);
		free(G[j].ys);
	}
	free(G);
	for (int i = 0; F && i < k; i++)
		flux_free(&F[i]);
	free(F);
	free(bo);
	an_labels_free(labels, ng);
	adb_runs_free(runs, nr);
	adb_close(&d);
	if (e.code) {
		fprintf(stderr, "hysteresis: %s\n", e.msg);
		return e.code == SB_EUSAGE ? 1 : 2;
	}
	return 0;
}
