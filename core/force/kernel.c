/* kernel.c - the force evaluation of a step (kernel.h): picks the vector kernel's
 * instance for this CPU (kvec.h), owns the records and accumulators it works on, and
 * runs the seam pairs of periodic sides through the scalar law after the flat list. */
#include "kernel.h"

#include <assert.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bigmem.h"
#include "kvec.h"

struct sb_kernel {
	const sb_kvec *v; /* the instance that runs */
	sb_kdata d;
	int stale;  /* x, y, vx, vy of the mobile disks are in the records only */
	int packed; /* the records hold the current state, the accumulators are clear */
	sb_shear shear; /* tangential = spring: the contacts' history */
};

/* The instances of this build, widest first, with what the CPU must have for each. */
typedef struct path {
	const sb_kvec *v;
	const char *needs; /* for the error and the tests' skip lines */
	int test;          /* for tests and measurements only: never chosen by itself */
} path;

static int paths(path out[SB_KPATHS_MAX])
{
	int n = 0;
#if defined(__x86_64__)
	out[n++] = (path){&sb_kvec_avx512, "x86-64-v4 (AVX-512 F/VL/DQ/BW)", 0};
	out[n++] = (path){&sb_kvec_avx2, "x86-64-v3 (AVX2, FMA, BMI2)", 0};
	out[n++] = (path){&sb_kvec_sse2, "x86-64 (SSE2)", 0};
#elif defined(__aarch64__)
	out[n++] = (path){&sb_kvec_neon, "aarch64 (NEON)", 0};
#else
	out[n++] = (path){&sb_kvec_generic, "any CPU", 0};
#endif
	out[n++] = (path){&sb_kvec_w8, "any CPU", 1};
	return n;
}

/* can this CPU run path k of paths()? */
static int runnable(int k)
{
#if defined(__x86_64__)
	__builtin_cpu_init();
	if (k == 0)
		return __builtin_cpu_supports("x86-64-v4") != 0;
	if (k == 1)
		return __builtin_cpu_supports("x86-64-v3") != 0;
#endif
	(void)k;
	return 1;
}

int kernel_paths(sb_kpath *out)
{
	path p[SB_KPATHS_MAX];
	int n = paths(p);
	for (int k = 0; k < n; k++)
		out[k] = (sb_kpath){p[k].v->name, p[k].needs, runnable(k), p[k].test};
	return n;
}

/* name NULL or "" or "auto": the widest the CPU runs */
static int choose(const char *name, const sb_kvec **v, sb_err *e)
{
	path p[SB_KPATHS_MAX];
	const int n = paths(p);
	const int any = !name || !*name || !strcmp(name, "auto");
	char list[160] = "";
	for (int k = 0; k < n; k++) {
		if (any ? runnable(k) && !p[k].test : !strcmp(name, p[k].v->name)) {
			if (!runnable(k))
				return sb_errf(e, SB_EUSAGE, "%s=%s: this CPU cannot run it: it needs %s",
					       SB_KERNEL_ENV, name, p[k].needs);
			*v = p[k].v;
			return 0;
		}
		size_t l = strlen(list);
		snprintf(list + l, sizeof list - l, "%s%s", l ? ", " : "", p[k].v->name);
	}
	return sb_errf(e, SB_EUSAGE, "%s=%s: no such kernel path (this build has auto, %s)", SB_KERNEL_ENV,
		       name, list);
}

int kernel_init_path(sb_kernel **out, const sb_state *st, const char *name, sb_err *e)
{
	sb_kernel *k = calloc(1, sizeof *k);
	*out = k;
	if (!k)
		return sb_errf(e, SB_ENOMEM, "out of memory for the force kernel");
	shear_init(&k->shear);
	if (choose(name, &k->v, e))
		return e->code;
	/* whole 64-byte lines, so that a record is one aligned vector load; the
	 * accumulators have a spare block: the fused corrector clears whole blocks */
	k->d.rec = bigmem_alloc(sizeof(double) * 8 * ((size_t)st->n + 8));
	k->d.kb = bigmem_alloc(sizeof(sb_kbuf));
	k->d.facc = bigmem_alloc(sizeof(double) * 4 * ((size_t)st->n + 9));
	if (!k->d.rec || !k->d.kb || !k->d.facc)
		return sb_errf(e, SB_ENOMEM, "out of memory for the force kernel");
	k->d.walls_packed = -1;
	/* ~300 bytes a disk are swept every step (the state's arrays, record,
	 * accumulator, pairs); below half the last-level cache prefetches only cost
	 * (measured on the Zen 5: -6 % at 10^5 disks, +2 % at 10^4, +4.5 % at 10^3). They
	 * are on too beyond eight level-2 caches, where a VM reports a huge last level: an
	 * Intel Xeon reporting 480 MiB ran 10^5 disks 5 % faster with them (docs/benchmarks.md) */
	const double sweep = 300.0 * st->n, l2 = (double)bigmem_l2_bytes();
	k->d.prefetch = sweep > 0.5 * (double)bigmem_llc_bytes() || (l2 > 0 && sweep > 8 * l2);
	return 0;
}

int kernel_init(sb_kernel **out, const sb_state *st, sb_err *e)
{
	return kernel_init_path(out, st, getenv(SB_KERNEL_ENV), e);
}

void kernel_free(sb_kernel *k)
{
	if (!k)
		return;
	free(k->d.rec);
	free(k->d.facc);
	free(k->d.kb);
	free(k->d.pm);
	free(k->d.prs);
	free(k->d.pc[0]);
	shear_free(&k->shear);
	free(k);
}

const char *kernel_path(const sb_kernel *k)
{
	return k->v->name;
}

sb_scan_fn kernel_scan(const sb_kernel *k)
{
	return k->v->scan;
}

int kernel_pair_shift(void)
{
	return SB_KSHIFT;
}

void kernel_sync(sb_kernel *k, sb_state *st)
{
	if (k->stale) {
		k->v->to_state(&k->d, st);
		k->stale = 0;
	}
}

double kernel_y(const sb_kernel *k, const sb_state *st, int i)
{
	return k->stale ? k->d.rec[8 * (size_t)i + 1] : st->q[C_Y][0][i];
}

sb_shear *kernel_shear(sb_kernel *k)
{
	return &k->shear;
}

/* The vector kernel's per-pair numbers (kvec.h, sb_kdata), once per list build: m_eff
 * and R_i + R_j of each listed pair, by the operations the lanes did on the records'
 * numbers (1/m_i + 1/m_j, its inverse, R_i + R_j: the same bits), so that no step
 * divides for them; with a table of materials also each pair's coefficients, as
 * forces_scalar forms them (forces_kc, the dampings times 1/dt: the same bits). */
static int pair_table_same(const sb_kdata *d, const sb_law *law, double inv_dt)
{
	if (!law->table)
		return !d->ptable;
	return d->ptable && d->pinv == inv_dt && !memcmp(d->pkc, law->kc, sizeof d->pkc);
}

static int pair_consts(sb_kdata *d, const sb_law *law, const sb_state *st, const sb_nlist *nl, double inv_dt,
		       sb_err *e)
{
	if (d->pfor == nl && d->pbuilt == nl->builds && d->pn == nl->nflat && pair_table_same(d, law, inv_dt))
		return 0;
	const int n = nl->nflat;
	if (n + 8 > d->pcap || (law->table && !d->pc[0])) {
		free(d->pm);
		free(d->prs);
		free(d->pc[0]);
		d->pc[0] = NULL;
		d->pcap = n + n / 4 + 64;
		d->pm = bigmem_alloc(sizeof(double) * (size_t)d->pcap);
		d->prs = bigmem_alloc(sizeof(double) * (size_t)d->pcap);
		/* the coefficients only for a table: the paper's law needs none */
		if (law->table)
			d->pc[0] = bigmem_alloc(5 * sizeof(double) * (size_t)d->pcap);
		if (!d->pm || !d->prs || (law->table && !d->pc[0])) {
			d->pcap = 0;
			d->pfor = NULL;
			return sb_errf(e, SB_ENOMEM, "out of memory for the force kernel's pair list (%d pairs)", n);
		}
		for (int c = 1; c < 5; c++)
			d->pc[c] = d->pc[0] ? d->pc[0] + (size_t)c * (size_t)d->pcap : NULL;
	}
	const int sh = nl->pshift;
	const double *im = st->inv_m, *r = st->r;
	for (int p = 0; p < n; p++) {
		const int i = nl->pi[p] >> sh, j = nl->pj[p] >> sh;
		d->pm[p] = 1.0 / (im[i] + im[j]);
		d->prs[p] = r[i] + r[j];
	}
	for (int p = n; p < n + 8; p++) {
		d->pm[p] = 1;
		d->prs[p] = 0;
	}
	if (law->table) {
		for (int p = 0; p < n; p++) {
			const int i = nl->pi[p] >> sh, j = nl->pj[p] >> sh;
			const sb_kc c = forces_kc(law, st->kind[i], st->kind[j]);
			d->pc[0][p] = c.Y;
			d->pc[1][p] = c.gn * inv_dt;
			d->pc[2][p] = c.gs * inv_dt;
			d->pc[3][p] = c.mu;
			d->pc[4][p] = c.kt;
		}
		for (int p = n; p < n + 8; p++)
			for (int c = 0; c < 5; c++)
				d->pc[c][p] = 0;
		memcpy(d->pkc, law->kc, sizeof d->pkc);
		d->pinv = inv_dt;
	}
	d->ptable = law->table;
	d->pfor = nl;
	d->pbuilt = nl->builds;
	d->pn = n;
	return 0;
}

#ifndef NDEBUG
/* the per-pair numbers are this list's (the test build asserts it at every call, on the
 * first, a middle and the last pair: a list rebuilt in place with the same count of
 * builds and pairs would otherwise go unseen) */
static int pair_consts_hold(const sb_kdata *d, const sb_state *st, const sb_nlist *nl)
{
	const int n = nl->nflat, sh = nl->pshift, at[3] = {0, n / 2, n - 1};
	for (int a = 0; a < 3 && n > 0; a++) {
		const int p = at[a], i = nl->pi[p] >> sh, j = nl->pj[p] >> sh;
		if (d->pm[p] != 1.0 / (st->inv_m[i] + st->inv_m[j]) || d->prs[p] != st->r[i] + st->r[j])
			return 0;
		if (d->ptable && d->pc[3][p] != d->pkc[st->kind[i]][st->kind[j]].mu)
			return 0;
	}
	return 1;
}
#endif

int kernel_forces(sb_kernel *k, const sb_law *law, sb_state *st, const sb_nlist *nl, double inv_dt,
		  int keep, double *fabs_sum, sb_err *e)
{
	/* packed: the last fused corrector wrote this state's records and cleared the
	 * accumulators; anything else packs the records from st, which must be current */
	const int packed = keep && !fabs_sum && k->packed;
	/* a list the kernel has not walked yet: its indices are record offsets the
	 * vector loads trust (checked once per list build) */
	assert(k->d.walls_packed == nl->builds || !nlist_check(nl, st->n, st->nm));
	k->packed = 0;
	/* the shear spring: its history in the order of this build */
	if (law->spring && shear_follow(&k->shear, nl, e))
		return -1;
	k->d.shx = law->spring ? k->shear.xi : NULL;
	if (!packed)
		kernel_sync(k, st);
	if (pair_consts(&k->d, law, st, nl, inv_dt, e))
		return -1;
	assert(pair_consts_hold(&k->d, st, nl));
	int bad = k->v->forces(&k->d, law, st, nl, inv_dt, keep, packed, fabs_sum);
	if (nl->nseam) { /* periodic sides only: the records hold this state either way */
		const double *rec = k->d.rec;
		double *facc = k->d.facc;
		const sb_seam_io io = keep ? (sb_seam_io){rec, rec + 1, rec + 2, rec + 3, facc, facc + 1, facc + 2, 8, 4}
					   : (sb_seam_io){rec, rec + 1, rec + 2, rec + 3, st->f[C_X], st->f[C_Y],
							  st->f[C_TH], 8, 1};
		bad |= forces_seam(law, st, nl, &io, inv_dt, law->spring ? k->shear.xi + nl->nflat : NULL, fabs_sum);
	}
	return bad;
}

void kernel_state_changed(sb_kernel *k)
{
	k->packed = 0;
}

void kernel_correct_predict(sb_kernel *k, const sb_integ *in, sb_state *st, double gy, const sb_nlist *nl,
			    sb_screen *scr)
{
	k->v->correct_predict(&k->d, in, st, gy, nl, scr);
	k->stale = 1;
	k->packed = 1;
	assert(!kernel_check(k, st));
}

const char *kernel_check(const sb_kernel *k, const sb_state *st)
{
	if (!k->packed)
		return NULL; /* nothing promised: the next force evaluation packs */
	const double *rec = k->d.rec, *acc = k->d.facc;
	for (int i = 0; i < st->nm; i++) {
		const double *q = rec + 8 * i;
		if (!(q[5] == st->inv_m[i] && q[6] == st->r[i] && q[7] == st->r[i]))
			return "a record's constant lanes are not (1/m, R, R) of its disk (kvec.h's layout)";
		if (acc[4 * i] != 0 || acc[4 * i + 1] != 0 || acc[4 * i + 2] != 0 || acc[4 * i + 3] != 0)
			return "an accumulator is not cleared for the next force evaluation";
	}
	return NULL;
}
