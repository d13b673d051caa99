/* checkpoint.c - the full state of a shaking run, enough to continue bit-identically:
 * every Nordsieck array, the neighbour-list reference positions (so the list is
 * rebuilt exactly as it was, with the same pair order and so the same force sums),
 * the contacts' shear displacements in that order (tangential = spring),
 * the recording schedule and the journal length. Written crash-safe; a checksum
 * rejects a damaged file. */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/stat.h>

#include "fnv.h"
#include "fsutil.h"
#include "checkpoint.h"

/* 12: the shear displacements of tangential = spring follow the observables (a count,
 * 0 without them, and one double per pair of the list). 11: a journal record is laid out by the table's columns (record.h), and a per-period
 * row's holds no drive frequency (the writer takes it from the drive), so a journal
 * an older engine wrote is not continued. 10: the recording counters are the table's
 * (core/scene/record.h), one array each, and the header holds REC_N: a row added to the
 * table changes the layout, and the format (version/REC_N) says so. 09: the scene hash
 * covers the key sides; the seam pairs are rebuilt from xref like the list. */
static const char MAGIC[8] = {'S', 'B', 'C', 'K', 'P', 'T', '1', '2'};

typedef struct hw {
	FILE *f;
	uint64_t h;
	int bad;
} hw;

static void hw_put(hw *w, const void *p, size_t n)
{
	w->h = sb_fnv(w->h, p, n);
	if (fwrite(p, 1, n, w->f) != n)
		w->bad = 1;
}

static void hw_get(hw *w, void *p, size_t n)
{
	if (w->bad || fread(p, 1, n, w->f) != n) {
		w->bad = 1;
		memset(p, 0, n);
		return;
	}
	w->h = sb_fnv(w->h, p, n);
}

/* The same field list serves writing and reading, so they cannot drift apart. */
typedef struct extra {
	long joff, builds;
	double *xref, *yref; /* neighbour-list reference positions */
} extra;

static void fields(hw *w, sb_sim *s, int nval, extra *x, void (*io)(hw *, void *, size_t))
{
	sb_state *st = &s->st;
	size_t n = (size_t)st->n;
	io(w, &s->settle_steps, sizeof s->settle_steps);
	io(w, &s->settle_time, sizeof s->settle_time);
	io(w, &s->surface0, sizeof s->surface0);
	io(w, &s->intruder_y0, sizeof s->intruder_y0);
	io(w, &s->step, sizeof s->step);
	io(w, s->rec_n, sizeof s->rec_n); /* every recorded quantity's, in the table's order */
	io(w, s->rec_next, sizeof s->rec_next);
	io(w, &s->n_strobe, sizeof s->n_strobe);
	io(w, &s->next_strobe_step, sizeof s->next_strobe_step);
	io(w, &s->next_ckpt_step, sizeof s->next_ckpt_step);
	io(w, &s->n_ckpt, sizeof s->n_ckpt);
	io(w, &s->max_contacts, sizeof s->max_contacts);
	io(w, &s->loop_seconds, sizeof s->loop_seconds); /* a resumed run's CPU time is the sum */
	io(w, &x->builds, sizeof x->builds);
	io(w, &x->joff, sizeof x->joff);
	io(w, s->prov.start_time, sizeof s->prov.start_time);
	io(w, st->id, sizeof(int) * n);
	io(w, st->kind, n);
	io(w, st->r, sizeof(double) * n);
	io(w, st->m, sizeof(double) * n);
	io(w, st->inv_m, sizeof(double) * n);
	io(w, st->inv_i, sizeof(double) * n);
	for (int c = 0; c < SB_NCOORD; c++)
		for (int k = 0; k < nval; k++)
			io(w, st->q[c][k], sizeof(double) * n);
	io(w, x->xref, sizeof(double) * n);
	io(w, x->yref, sizeof(double) * n);
}

static void put_v(hw *w, void *p, size_t n) { hw_put(w, p, n); }
static void put_obs(void *w, void *p, size_t n) { hw_put(w, p, n); }
static void get_obs(void *w, void *p, size_t n) { hw_get(w, p, n); }

/* Checkpoints resume only under the same physics; with a frequency ramp the run
 * length sets the ramp rate, so it counts too. */
static unsigned long long ckpt_hash(const sb_scene *sc)
{
	return params_hash(sc, PF_PREP | PF_DYN | (sc->ramp != RAMP_NONE ? PF_LEN : 0));
}

int ckpt_write(sb_sim *s, sb_err *e)
{
	long joff;
	if (journal_sync(&s->jr, &joff, e))
		return e->code;
	sb_file out;
	if (fs_open_tmp(&out, s->ckpt_path, e))
		return e->code;
	hw w = {out.f, SB_FNV_BASIS, 0};
	uint64_t ph = ckpt_hash(&s->sc);
	int32_t hdr[4] = {s->st.n, s->st.nm, s->in.nval, REC_N};
	hw_put(&w, MAGIC, 8);
	hw_put(&w, &ph, sizeof ph);
	hw_put(&w, hdr, sizeof hdr);
	extra x = {joff, s->nl.builds, s->nl.xref, s->nl.yref};
	fields(&w, s, s->in.nval, &x, put_v);
	obs_fields(&s->obs, &w, put_obs);
	const sb_shear *sh = kernel_shear(s->kern);
	int64_t nsh = s->law.spring ? sh->n : 0;
	hw_put(&w, &nsh, sizeof nsh);
	if (nsh)
		hw_put(&w, sh->xi, sizeof(double) * (size_t)nsh);
	uint64_t sum = w.h;
	if (fwrite(&sum, sizeof sum, 1, out.f) != 1)
		w.bad = 1;
	if (w.bad) {
		fs_abort(&out);
		return sb_errf(e, SB_EIO, "%s: checkpoint write failed: %s", s->ckpt_path, strerror(errno));
	}
	return fs_commit(&out, e);
}

int ckpt_load(sb_sim *s, sb_err *e)
{
	const char *path = s->ckpt_path;
	if (!path[0] || access(path, F_OK) != 0) { /* "": no run file to resume into */
		if (s->sc.restart == TRI_YES)
			return sb_errf(e, SB_EUSAGE, "%s: restart = yes but there is no checkpoint", path);
		return 0;
	}
	FILE *f = fopen(path, "rb");
	if (!f)
		return sb_errf(e, SB_EIO, "%s: cannot open checkpoint: %s", path, strerror(errno));
	hw r = {f, SB_FNV_BASIS, 0};
	char m[8];
	uint64_t ph;
	int32_t hdr[4];
	hw_get(&r, m, 8);
	hw_get(&r, &ph, sizeof ph);
	hw_get(&r, hdr, sizeof hdr);
	int err = 0;
	/* the format: the version, and how many quantities the engine records (a row added
	 * to core/scene/record.h's table adds a pair of counters) */
	char fmt[40], mine[40];
	snprintf(fmt, sizeof fmt, "%.2s/%d", m + 6, (int)hdr[3]);
	snprintf(mine, sizeof mine, "%.2s/%d", MAGIC + 6, REC_N);
	if (!r.bad && !memcmp(m, MAGIC, 6) && strcmp(fmt, mine)) {
		/* another engine version's checkpoint: restart = auto starts over (only
		 * time is lost), restart = yes cannot do what it was asked */
		if (s->sc.restart != TRI_YES) {
			snprintf(s->warning, sizeof s->warning,
				 "%.400s: a checkpoint of format %.20s (this engine writes %.20s): starting over", path, fmt, mine);
			fclose(f);
			return 0;
		}
		err = sb_errf(e, SB_EUSAGE, "%s: a checkpoint of format %s, this engine writes %s; remove it or set restart = no",
			      path, fmt, mine);
	} else if (r.bad || memcmp(m, MAGIC, 8))
		err = sb_errf(e, SB_EIO, "%s: not a shakebox checkpoint", path);
	else if (ph != ckpt_hash(&s->sc))
		err = sb_errf(e, SB_EUSAGE,
			      "%s: written by a run with other parameters; remove it or set restart = no", path);
	else if (hdr[2] != s->in.nval || hdr[0] < hdr[1] || hdr[1] < 1)
		err = sb_errf(e, SB_EIO, "%s: inconsistent checkpoint header", path);
	if (!err && state_alloc(&s->st, hdr[0], e))
		err = e->code;
	extra x = {0, 0, NULL, NULL};
	if (!err) {
		s->st.n = hdr[0];
		s->st.nm = hdr[1];
		x.xref = malloc(sizeof(double) * (size_t)hdr[0]);
		x.yref = malloc(sizeof(double) * (size_t)hdr[0]);
		if (!x.xref || !x.yref)
			err = sb_errf(e, SB_ENOMEM, "out of memory loading the checkpoint");
	}
	if (!err)
		fields(&r, s, s->in.nval, &x, hw_get);
	/* Rebuild the neighbour list from the stored reference positions: the same list,
	 * in the same order, as the interrupted run had. Then the observables, whose
	 * accumulators follow in the file. */
	if (!err && !r.bad && !sim_derive(s, e)) {
		memcpy(s->nl.xref, x.xref, sizeof(double) * (size_t)s->st.n);
		memcpy(s->nl.yref, x.yref, sizeof(double) * (size_t)s->st.n);
		if (!nlist_build_from_ref(&s->nl, &s->st, e))
			s->nl.builds = x.builds;
		if (!e->code && !sim_obs_init(s, e))
			obs_fields(&s->obs, &r, get_obs);
	}
	/* the shear displacements, in the order of the list just rebuilt */
	if (!err && !e->code && !r.bad) {
		int64_t nsh = 0;
		hw_get(&r, &nsh, sizeof nsh);
		const long np = (long)s->nl.nflat + s->nl.nseam;
		if (!r.bad && nsh != 0 && (!s->law.spring || nsh != np))
			err = sb_errf(e, SB_EIO, "%s: inconsistent checkpoint (%lld shear displacements, %ld pairs)", path,
				      (long long)nsh, s->law.spring ? np : 0L);
		else if (!r.bad && nsh) {
			double *xi = malloc(sizeof(double) * (size_t)nsh);
			if (!xi)
				err = sb_errf(e, SB_ENOMEM, "out of memory loading the checkpoint");
			else {
				hw_get(&r, xi, sizeof(double) * (size_t)nsh);
				if (!r.bad)
					err = shear_restore(kernel_shear(s->kern), &s->nl, xi, (long)nsh, e);
				free(xi);
			}
		}
	}
	err = err ? err : e->code;
	if (!err) {
		uint64_t want = r.h, got = 0;
		if (r.bad || fread(&got, sizeof got, 1, f) != 1 || got != want)
			err = sb_errf(e, SB_EIO, "%s: checkpoint damaged (checksum mismatch)", path);
	}
	/* the checkpoint resumes into its journal cut to the length it stored: without it
	 * (gone with a run directory deleted while the run wrote; docs/scene.md, "Determinism,
	 * checkpoints, restart"), or shorter (cutting would pad it with zeros), the records
	 * since the start are lost, and restart = auto starts over - time lost, not a fault
	 * of the disk. The checkpoint goes first: a new journal beside it would be taken
	 * for its own by the next restart. */
	struct stat js;
	const int jst = lstat(s->journal_path, &js), nojournal = jst != 0 && errno == ENOENT;
	if (!err && (nojournal || (!jst && S_ISREG(js.st_mode) && js.st_size < x.joff))) {
		if (s->sc.restart == TRI_YES)
			err = sb_errf(e, SB_EUSAGE, "%s: restart = yes, but its journal %s %s; remove the checkpoint or set restart = auto",
				      path, s->journal_path, nojournal ? "is missing" : "is shorter than the checkpoint says");
		else {
			snprintf(s->warning, sizeof s->warning, "%.200s: its journal %.200s %s: starting the run over", path,
				 s->journal_path, nojournal ? "is missing" : "is shorter than the checkpoint says");
			unlink(path);
			free(x.xref);
			free(x.yref);
			fclose(f);
			return 0;
		}
	}
	if (!err)
		err = journal_open(&s->jr, s->journal_path, s->st.nm, x.joff, e);
	free(x.xref);
	free(x.yref);
	fclose(f);
	return err ? err : 1;
}
