/* h5out.c - the run's HDF5 file (H5MD 1.1; layout: docs/output.md) and its XDMF
 * sidecar, assembled from the journal and the final state when the run ends:
 *   /             attributes: status, results (waiting time, overlap record, ...)
 *   /h5md         version 1.1, author, creator
 *   /parameters   attributes: every scene parameter (typed)
 *   /particles/bed_xyz  the bed as a flat 3-D system (z = 0, virtual: no storage) for
 *                       readers that know only three dimensions
 *   /particles/bed      the mobile disks (grains, intruder; lab frame): id, species,
 *                       mass, radius; box; position, velocity, angle at the snapshots
 *   /particles/walls    the wall disks: id, species, mass, radius, position (at rest)
 *   /particles/intruder the intruder at traj_rate: position, velocity, angular_velocity
 *   /observables  energy, flux, field, ring (time-dependent elements), contacts (frames)
 *   /ring         the ring's averages: over the run and before the rise
 *   /final        every disk at the end (lab frame): x, y, vx, vy, omega, theta and
 *                 id, species, radius, mass
 *   /provenance   git hash, compiler, flags, host, CPU model, force kernel path, times
 *   /@digest      the attributes' digest, written last (core/io/h5id.h)
 * Every dataset that holds data carries a Fletcher32 checksum per chunk.
 * Object time stamps are off, so two runs of one scene give identical files apart
 * from /provenance and /h5md (who ran it - the environment's USER - and which build). */
#include <assert.h>
#include <hdf5.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fsutil.h"
#include "h5id.h"
#include "h5seal.h"
#include "h5md.h"
#include "h5out.h"

#include "pclass.h"
#include "kernel.h"
#include "provenance.h"
#include "record.h"
#include "sample.h"

/* The engine step of a recorded time (times are step * dt exactly). */
static long step_of(const sb_sim *s, double t) { return lround(t / s->sc.dt); }

static void write_params(h5w *h, hid_t g, const sb_scene *sc)
{
	size_t n;
	const sb_param *t = params_table(&n);
	for (size_t i = 0; i < n; i++) {
		const char *base = (const char *)sc + t[i].offset;
		char buf[SB_STR_MAX + 32];
		switch (t[i].type) {
		case PT_INT: h5w_attr_long(h, g, t[i].name, *(const long *)base); break;
		case PT_REAL: h5w_attr_double(h, g, t[i].name, *(const double *)base); break;
		default:
			params_format(sc, &t[i], buf, sizeof buf);
			h5w_attr_str(h, g, t[i].name, buf);
		}
	}
}

/* A growable block of doubles for the small record types. */
typedef struct dbuf {
	double *d;
	size_t n, cap;
} dbuf;

static int dbuf_add(dbuf *b, const double *v, size_t n)
{
	if (b->n + n > b->cap) {
		size_t c = b->cap ? b->cap : 1024;
		while (c < b->n + n)
			c *= 2;
		double *p = realloc(b->d, sizeof(double) * c);
		if (!p)
			return -1;
		b->d = p;
		b->cap = c;
	}
	memcpy(b->d + b->n, v, sizeof(double) * n);
	b->n += n;
	return 0;
}

/* Records of len doubles, column c of each, and their steps (from column 0, time). */
static int columns(const sb_sim *s, const dbuf *b, size_t len, size_t T, double **t, long **st)
{
	*t = malloc(sizeof(double) * (T ? T : 1));
	*st = malloc(sizeof(long) * (T ? T : 1));
	if (!*t || !*st)
		return -1;
	for (size_t k = 0; k < T; k++) {
		(*t)[k] = b->d[k * len];
		(*st)[k] = step_of(s, (*t)[k]);
	}
	return 0;
}

static void write_flux(h5w *h, const sb_sim *s, hid_t g, const dbuf *fl, long n)
{
	const sb_obs *o = &s->obs;
	const int nl = o->nlines, len = obs_flux_len(o);
	const size_t P = (size_t)n;
	double *t = NULL, *f = malloc(sizeof(double) * (P ? P : 1));
	long *st = NULL;
	double *jt = malloc(sizeof(double) * (P ? P : 1) * nl), *jb = malloc(sizeof(double) * (P ? P : 1) * nl);
	double *phi = malloc(sizeof(double) * (P ? P : 1) * nl);
	if (columns(s, fl, (size_t)len, P, &t, &st) || !f || !jt || !jb || !phi) {
		h5w_fail(h);
	} else {
		for (size_t k = 0; k < P; k++) {
			const double *r = fl->d + k * len;
			f[k] = r[1];
			for (int l = 0; l < nl; l++) {
				jt[k * nl + l] = r[2 + l];
				jb[k * nl + l] = r[2 + nl + l];
				phi[k * nl + l] = r[2 + l] - r[2 + nl + l];
			}
		}
		const hsize_t tail = (hsize_t)nl;
		h5elem e0, e;
		h5w_elem_create(h, &e0, g, "phi", P, 1, &tail, "1", NULL);
		h5w_elem_all(h, &e0, st, t, phi);
		h5w_elem_create(h, &e, g, "j_top", P, 1, &tail, "1", &e0);
		h5w_elem_all(h, &e, NULL, NULL, jt);
		h5w_elem_close(h, &e);
		h5w_elem_create(h, &e, g, "j_bot", P, 1, &tail, "1", &e0);
		h5w_elem_all(h, &e, NULL, NULL, jb);
		h5w_elem_close(h, &e);
		h5w_elem_create(h, &e, g, "frequency", P, 0, NULL, "Hz", &e0);
		h5w_elem_all(h, &e, NULL, NULL, f);
		h5w_elem_close(h, &e);
		h5w_elem_close(h, &e0);
		h5w_dset(h, g, "heights", 1, &tail, o->hline, "cm");
		h5w_attr_str(h, g, "definition",
			     "per period (between successive phase-0 samples; time and step: the period's end): j_top = "
			     "upward - downward crossings of each height line by disks whose mean x lies within W/4 of the "
			     "box centre, j_bot the same outside; phi = j_top - j_bot (particles per period); heights in "
			     "cm above the bottom");
		h5w_attr_double(h, g, "surface_height", o->surface);
	}
	free(t);
	free(st);
	free(f);
	free(jt);
	free(jb);
	free(phi);
}

static void write_field(h5w *h, const sb_sim *s, hid_t g, const dbuf *fd, long n)
{
	const sb_obs *o = &s->obs;
	const size_t nc = (size_t)o->nx * o->ny;
	const int len = obs_field_len(o);
	const size_t B = (size_t)n;
	double *t = NULL;
	long *st = NULL;
	double *ux = malloc(sizeof(double) * (B ? B : 1) * nc), *uy = malloc(sizeof(double) * (B ? B : 1) * nc);
	double *cnt = malloc(sizeof(double) * (B ? B : 1) * nc);
	if (columns(s, fd, (size_t)len, B, &t, &st) || !ux || !uy || !cnt) {
		h5w_fail(h);
	} else {
		for (size_t k = 0; k < B; k++) {
			const double *r = fd->d + k * len;
			for (size_t c = 0; c < nc; c++) {
				double n = r[2 + 2 * nc + c];
				/* mean displacement per period of the disks that passed the cell */
				ux[k * nc + c] = n > 0 ? r[2 + c] / n : 0;
				uy[k * nc + c] = n > 0 ? r[2 + nc + c] / n : 0;
				cnt[k * nc + c] = n;
			}
		}
		const hsize_t tail[2] = {(hsize_t)o->ny, (hsize_t)o->nx};
		h5elem e0, e;
		h5w_elem_create(h, &e0, g, "ux", B, 2, tail, "cm", NULL);
		h5w_elem_all(h, &e0, st, t, ux);
		h5w_elem_create(h, &e, g, "uy", B, 2, tail, "cm", &e0);
		h5w_elem_all(h, &e, NULL, NULL, uy);
		h5w_elem_close(h, &e);
		h5w_elem_create(h, &e, g, "count", B, 2, tail, "1", &e0);
		h5w_elem_all(h, &e, NULL, NULL, cnt);
		h5w_elem_close(h, &e);
		h5w_elem_close(h, &e0);
		h5w_attr_double(h, g, "cell", o->cell);
		h5w_attr_double(h, g, "x0", o->x0);
		h5w_attr_long(h, g, "periods_per_block", o->K);
		h5w_attr_str(h, g, "definition",
			     "value[block][row][column]: cell (c, r) spans x0 + c*cell .. x0 + (c+1)*cell and r*cell .. "
			     "(r+1)*cell above the bottom; ux, uy = mean displacement per period of the disks whose "
			     "midpoint between successive phase-0 samples lies in the cell, over periods_per_block periods "
			     "(cm); count = samples; time and step: the block's end");
	}
	free(t);
	free(st);
	free(ux);
	free(uy);
	free(cnt);
}

/* The contact dump (contact_rate): frames of every contact, flattened - frame k's
 * contacts are rows offset[k] .. offset[k] + count[k] of the per-contact datasets (a
 * number of contacts that changes from frame to frame is not an H5MD element). */
static void write_contacts(h5w *h, const sb_sim *s, hid_t g, const dbuf *c, long F)
{
	const rec_col *cols = rec_table()[REC_CONTACT].cols;
	(void)s;
	double *t = malloc(sizeof(double) * (size_t)(F ? F : 1)), *cnt = malloc(sizeof(double) * (size_t)(F ? F : 1)),
	       *off = malloc(sizeof(double) * (size_t)(F ? F : 1));
	size_t C = 0, pos = 0;
	for (long k = 0; k < F && t && cnt && off; k++) { /* frame k: t, n, n x 8 values */
		t[k] = c->d[pos];
		cnt[k] = c->d[pos + 1];
		off[k] = (double)C;
		C += (size_t)cnt[k];
		pos += 2 + REC_NCOLS(REC_COLS_CONTACT) * (size_t)cnt[k];
	}
	double *col = malloc(sizeof(double) * (C ? C : 1));
	if (!t || !cnt || !off || !col) {
		h5w_fail(h);
	} else {
		const hsize_t nf = (hsize_t)F, nc = (hsize_t)C;
		h5w_dset(h, g, "time", 1, &nf, t, "s");
		h5w_dset(h, g, "count", 1, &nf, cnt, "1");
		h5w_dset(h, g, "offset", 1, &nf, off, "1");
		for (int k = 0; k < REC_NCOLS(REC_COLS_CONTACT); k++) {
			size_t row = 0;
			pos = 0;
			for (long fr = 0; fr < F; fr++) {
				const size_t n = (size_t)cnt[fr];
				for (size_t q = 0; q < n; q++)
					col[row++] = c->d[pos + 2 + REC_NCOLS(REC_COLS_CONTACT) * q + (size_t)k];
				pos += 2 + REC_NCOLS(REC_COLS_CONTACT) * n;
			}
			h5w_dset(h, g, cols[k].name, 1, &nc, col, cols[k].unit);
		}
		h5w_attr_str(h, g, "definition",
			     "every contact at each sample: disks id_a, id_b; the force on id_a is normal_force n + "
			     "tangential_force t with n = (r_a - r_b)/d = (normal_x, normal_y), t = n turned by +90 deg; "
			     "x, y_box: midpoint of the centres (box frame); frame k is rows offset[k] .. offset[k] + count[k]");
	}
	free(t);
	free(cnt);
	free(off);
	free(col);
}

/* The ring's series (docs/model.md, "Ring force"): one row per sample, every quantity
 * an element sharing the first one's clock; centre is [T][2] (box frame). */
static void write_ring_series(h5w *h, const sb_sim *s, hid_t g, const dbuf *rg, long n)
{
	const rec_col *cols = rec_table()[REC_RING].cols;
	const size_t T = (size_t)n;
	double *col = malloc(sizeof(double) * 2 * (T ? T : 1)), *t = NULL;
	long *st = NULL;
	if (!col || columns(s, rg, REC_NCOLS(REC_COLS_RING), T, &t, &st)) {
		h5w_fail(h);
	} else {
		h5elem e0, e;
		for (int c = OBS_RR_MEAN; c <= OBS_RR_N; c++) {
			for (size_t k = 0; k < T; k++)
				col[k] = rg->d[k * REC_NCOLS(REC_COLS_RING) + c];
			h5elem *el = c == OBS_RR_MEAN ? &e0 : &e;
			h5w_elem_create(h, el, g, cols[c].name, T, 0, NULL, cols[c].unit, c == OBS_RR_MEAN ? NULL : &e0);
			h5w_elem_all(h, el, st, t, col);
			if (c != OBS_RR_MEAN)
				h5w_elem_close(h, &e);
		}
		for (size_t k = 0; k < T; k++) {
			col[2 * k] = rg->d[k * REC_NCOLS(REC_COLS_RING) + OBS_RR_CX];
			col[2 * k + 1] = rg->d[k * REC_NCOLS(REC_COLS_RING) + OBS_RR_CY];
		}
		const hsize_t two = 2;
		h5w_elem_create(h, &e, g, "centre", T, 1, &two, cols[OBS_RR_CX].unit, &e0);
		h5w_elem_all(h, &e, NULL, NULL, col);
		h5w_elem_close(h, &e);
		h5w_elem_close(h, &e0);
		h5w_attr_str(h, g, "definition",
			     "one row per ring sample, over the grains whose centres lie inner..outer cm (/ring) from "
			     "centre (box frame): mean_force = mean over them of the sum of the magnitudes of each grain's "
			     "contact forces (dyn); net_force = mean of the magnitude of each grain's net force, contact "
			     "forces plus weight, lab frame (dyn); temperature = half the mean squared velocity "
			     "fluctuation about their mean velocity (cm^2/s^2); grains = how many (0: the means are 0)");
	}
	free(col);
	free(t);
	free(st);
}

/* The ring's averages (/ring attributes): over every sample, and over the window
 * before the rise (ring_from <= t < min(ring_until, the waiting time)). No sample:
 * zeros, never NaN. */
static void write_ring(h5w *h, const sb_sim *s, double t_end)
{
	const sb_obs *o = &s->obs;
	hid_t g = h5w_group(h, h->file, "ring", 0);
	double n = o->ring_samples ? (double)o->ring_samples : 1;
	h5w_attr_double(h, g, "inner", o->rin);
	h5w_attr_double(h, g, "outer", o->rout);
	h5w_attr_long(h, g, "samples", o->ring_samples);
	h5w_attr_double(h, g, "mean_force", o->acc[OBS_RA_MEAN] / n);
	h5w_attr_double(h, g, "mean_force_lower", o->acc[OBS_RA_MEAN_LO] / n);
	h5w_attr_double(h, g, "sum_force", o->acc[OBS_RA_SUM] / n);
	h5w_attr_double(h, g, "sum_force_lower", o->acc[OBS_RA_SUM_LO] / n);
	h5w_attr_double(h, g, "net_force", o->acc[OBS_RA_NET] / n);
	h5w_attr_double(h, g, "net_force_lower", o->acc[OBS_RA_NET_LO] / n);
	h5w_attr_double(h, g, "temperature", o->acc[OBS_RA_T] / n);
	h5w_attr_double(h, g, "temperature_lower", o->acc[OBS_RA_T_LO] / n);
	h5w_attr_double(h, g, "grains", o->acc[OBS_RA_N] / n);
	h5w_attr_double(h, g, "grains_lower", o->acc[OBS_RA_N_LO] / n);
	h5w_attr_str(h, g, "centre", o->ring_follow ? "intruder"
				     : s->sc.ring_centre == RING_SETTLED && s->intruder >= 0 ? "settled" : "fixed");
	if (!o->ring_follow) {
		h5w_attr_double(h, g, "centre_x", o->ring_x);
		h5w_attr_double(h, g, "centre_y", o->ring_y);
	}
	/* the window before the rise */
	double to = t_end;
	if (s->intruder >= 0 && o->risen && o->wait_time < to)
		to = o->wait_time;
	if (o->ring_until > 0 && o->ring_until < to)
		to = o->ring_until;
	const double nb = o->ring_before ? (double)o->ring_before : 1;
	h5w_attr_long(h, g, "samples_before", o->ring_before);
	h5w_attr_double(h, g, "before_from", o->ring_from);
	h5w_attr_double(h, g, "before_to", to);
	h5w_attr_double(h, g, "mean_force_before", o->before[OBS_RB_MEAN] / nb);
	h5w_attr_double(h, g, "net_force_before", o->before[OBS_RB_NET] / nb);
	h5w_attr_double(h, g, "temperature_before", o->before[OBS_RB_T] / nb);
	h5w_attr_double(h, g, "grains_before", o->before[OBS_RB_N] / nb);
	h5w_attr_double(h, g, "sum_force_before", o->before[OBS_RB_SUM] / nb);
	h5w_attr_str(h, g, "definition",
		     "averages over the ring samples (/observables/ring) of grains whose centres lie inner..outer cm "
		     "from the centre (the intruder's, sample by sample, or fixed: centre_x, centre_y, box frame): "
		     "mean_force = mean over the grains of the sum of the magnitudes of their contact forces (dyn), "
		     "sum_force = its sum over the ring, net_force = mean magnitude of the grains' net force (contact "
		     "forces plus weight, lab frame; dyn), temperature = half the mean squared velocity fluctuation "
		     "about the ring's mean velocity (cm^2/s^2); _lower: grains below the centre; _before: the "
		     "samples at before_from <= t < before_to, before the intruder rose (docs/model.md, \"Ring force\")");
	h5w_close_obj(h, g);
}

/* The intruder's height over the recorded trajectory rows in the box frame (the
 * trajectory holds lab-frame y; the box frame is the one its settled height and the
 * waiting time are measured in, so a rise never counts the box's own motion). */
static void intruder_summary(h5w *h, const sb_sim *s, const double *traj, long T)
{
	double ymax = -INFINITY, ymin = INFINITY, sum = 0, y = 0;
	for (long k = 0; k < T; k++) {
		const double *row = traj + k * REC_NCOLS(REC_COLS_TRAJ);
		y = row[2] - sim_box_y(s, row[0]);
		ymax = y > ymax ? y : ymax;
		ymin = y < ymin ? y : ymin;
		sum += y;
	}
	h5w_attr_double(h, h->file, rec_summary_attr(RSUM_intruder_final_y_box), y);
	h5w_attr_double(h, h->file, rec_summary_attr(RSUM_intruder_max_y_box), ymax);
	h5w_attr_double(h, h->file, rec_summary_attr(RSUM_intruder_min_y_box), ymin);
	h5w_attr_double(h, h->file, rec_summary_attr(RSUM_intruder_mean_y_box), sum / (double)T);
}

static void box_size(const sb_sim *s, double *w, double *hgt);

/* An H5MD particle group's box: two dimensions, no periodic boundary with walls;
 * with periodic sides x is periodic (y is not) and the box has its edges (H5MD
 * needs them for a periodic dimension), which edges = 1 asks for with walls too. */
static hid_t plain_box(h5w *h, const sb_sim *s, hid_t g, int edges)
{
	hid_t b = h5w_group(h, g, "box", 0);
	static const char *const none2[2] = {"none", "none"}, *const px2[2] = {"periodic", "none"};
	const int periodic = s->nl.period > 0;
	h5w_attr_long(h, b, "dimension", 2);
	h5w_attr_strs(h, b, "boundary", periodic ? px2 : none2, 2);
	if (edges || periodic) {
		double wd, ht;
		box_size(s, &wd, &ht);
		const double e2[2] = {wd, ht};
		const hsize_t two = 2;
		h5w_dset(h, b, "edges", 1, &two, e2, "cm");
	}
	return b;
}

/* /particles/intruder: the intruder alone at traj_rate, as an H5MD particle group of
 * one particle (lab frame). */
/* /particles/intruders (several intruders: docs/model.md, "Several intruders"): their
 * positions at the trajectory's rate as one H5MD element [T x n x 2] (lab frame), and
 * their ids in the element's order. */
static void write_intruders_pos(h5w *h, const sb_sim *s, hid_t parts, const double *rec, long T)
{
	const int n = s->n_intruders;
	const size_t len = (size_t)(1 + 2 * n), nt = (size_t)T;
	double *p = malloc(sizeof(double) * 2 * (size_t)n * (nt ? nt : 1)), *t = malloc(sizeof(double) * (nt ? nt : 1));
	long *st = malloc(sizeof(long) * (nt ? nt : 1));
	int *id = malloc(sizeof(int) * (size_t)n);
	if (!p || !t || !st || !id) {
		h5w_fail(h);
	} else {
		for (size_t k = 0; k < nt; k++) {
			t[k] = rec[k * len];
			st[k] = step_of(s, t[k]);
			memcpy(p + k * 2 * (size_t)n, rec + k * len + 1, sizeof(double) * 2 * (size_t)n);
		}
		for (int k = 0; k < n; k++)
			id[k] = s->st.id[s->obs.iidx[k]];
		hid_t g = h5w_group(h, parts, "intruders", 0);
		const hsize_t tail[2] = {(hsize_t)n, 2};
		h5elem e0;
		h5w_elem_create(h, &e0, g, "position", nt, 2, tail, "cm", NULL);
		h5w_elem_all(h, &e0, st, t, p);
		h5w_elem_close(h, &e0);
		h5w_dset_int(h, g, "id", (hsize_t)n, id, "1");
		h5w_close_obj(h, g);
	}
	free(p);
	free(t);
	free(st);
	free(id);
}

static void write_intruder(h5w *h, const sb_sim *s, hid_t parts, const double *traj, long T)
{
	hid_t g = h5w_group(h, parts, "intruder", 0);
	const size_t n = (size_t)T;
	double *p = malloc(sizeof(double) * 2 * (n ? n : 1)), *v = malloc(sizeof(double) * 2 * (n ? n : 1));
	double *w = malloc(sizeof(double) * (n ? n : 1)), *t = malloc(sizeof(double) * (n ? n : 1));
	long *st = malloc(sizeof(long) * (n ? n : 1));
	if (!p || !v || !w || !t || !st) {
		h5w_fail(h);
	} else {
		for (size_t k = 0; k < n; k++) {
			const double *r = traj + k * REC_NCOLS(REC_COLS_TRAJ); /* t x y vx vy omega */
			t[k] = r[0];
			st[k] = step_of(s, r[0]);
			p[2 * k] = r[1];
			p[2 * k + 1] = r[2];
			v[2 * k] = r[3];
			v[2 * k + 1] = r[4];
			w[k] = r[5];
		}
		const hsize_t tail[2] = {1, 2}, one = 1;
		h5elem e0, e;
		h5w_elem_create(h, &e0, g, "position", n, 2, tail, "cm", NULL);
		h5w_elem_all(h, &e0, st, t, p);
		h5w_elem_create(h, &e, g, "velocity", n, 2, tail, "cm s-1", &e0);
		h5w_elem_all(h, &e, NULL, NULL, v);
		h5w_elem_close(h, &e);
		h5w_elem_create(h, &e, g, "angular_velocity", n, 1, &one, "rad s-1", &e0);
		h5w_elem_all(h, &e, NULL, NULL, w);
		h5w_elem_close(h, &e);
		h5w_elem_close(h, &e0);
		const int id = s->st.id[s->intruder], sp = KIND_INTRUDER;
		h5w_dset_int(h, g, "id", 1, &id, "1");
		h5w_dset_int(h, g, "species", 1, &sp, "1");
		h5w_close_obj(h, plain_box(h, s, g, 0));
		h5w_attr_long(h, g, "index", s->intruder);
	}
	free(p);
	free(v);
	free(w);
	free(t);
	free(st);
	h5w_close_obj(h, g);
}

/* The box of /particles/bed: the side walls' inner faces and the highest wall disk's
 * top (box frame), placed in the lab frame by a time-dependent offset. With periodic
 * sides: the period, and twice the settled surface (no side wall sets a height; it is
 * what the side walls would have by default). */
static void box_size(const sb_sim *s, double *w, double *hgt)
{
	const sb_state *st = &s->st;
	double top = 0;
	for (int i = st->nm; i < st->n; i++)
		top = fmax(top, st->q[C_Y][0][i] + st->r[i]);
	*w = s->obs.x1 - s->obs.x0;
	*hgt = s->nl.period > 0 ? 2 * s->surface0 : top;
}

/* The snapshot elements of /particles/bed, streamed from the journal one frame at a
 * time. */
typedef struct snapw {
	h5elem pos, vel, ang, off, offv;
	h5elem wpos; /* the walls at each snapshot (snapshots_per_period > 1 only) */
	hid_t walls;
	double *p, *v, *wp;
	hsize_t k;
} snapw;

/* The walls stand where they stand at rest only at phase 0; with snapshots within a
 * period (snapshots_per_period > 1) their place at each snapshot is written too, on the
 * snapshots' clock, so that a reader (the XDMF sidecar, ParaView) draws the box where
 * it was. */
static int snap_walls_moving(const sb_sim *s) { return s->sc.snapshots_per_period > 1 && s->st.n > s->st.nm; }

static int snap_open(h5w *h, snapw *w, const sb_sim *s, hid_t parts, hid_t bed, hid_t box, hsize_t K)
{
	const hsize_t nm = (hsize_t)s->st.nm, tail[2] = {nm, 2}, two = 2, nw = (hsize_t)(s->st.n - s->st.nm);
	const hsize_t wtail[2] = {nw, 2};
	const hid_t ft = s->sc.snapshot_precision ? H5T_IEEE_F32LE : H5T_IEEE_F64LE;
	w->p = malloc(sizeof(double) * 2 * (nm ? nm : 1));
	w->v = malloc(sizeof(double) * 2 * (nm ? nm : 1));
	w->wp = malloc(sizeof(double) * 2 * (nw ? nw : 1));
	if (!w->p || !w->v || !w->wp)
		return -1;
	h5w_elem_create_as(h, &w->pos, bed, "position", K, 2, tail, "cm", NULL, ft);
	h5w_elem_create_as(h, &w->vel, bed, "velocity", K, 2, tail, "cm s-1", &w->pos, ft);
	h5w_elem_create_as(h, &w->ang, bed, "angle", K, 1, &nm, "rad", &w->pos, ft);
	h5w_elem_create(h, &w->off, box, "offset", K, 1, &two, "cm", &w->pos);
	h5w_elem_create(h, &w->offv, box, "offset_velocity", K, 1, &two, "cm s-1", &w->pos);
	if (snap_walls_moving(s)) {
		w->walls = H5Gopen2(parts, "walls", H5P_DEFAULT);
		if (w->walls < 0)
			return -1;
		h5w_elem_create_as(h, &w->wpos, w->walls, "snapshot_position", K, 2, wtail, "cm", &w->pos, ft);
	}
	return h->bad ? -1 : 0;
}

/* rec: t, x[nm], y[nm], theta[nm], vx[nm], vy[nm] (lab frame) */
static void snap_row(h5w *h, snapw *w, const sb_sim *s, const double *rec)
{
	const int nm = s->st.nm;
	const double t = rec[0];
	const double *x = rec + 1, *y = x + nm, *th = y + nm, *vx = th + nm, *vy = vx + nm;
	for (int i = 0; i < nm; i++) {
		w->p[2 * i] = x[i];
		w->p[2 * i + 1] = y[i];
		w->v[2 * i] = vx[i];
		w->v[2 * i + 1] = vy[i];
	}
	const double off[2] = {s->obs.x0, sim_box_y(s, t)}, offv[2] = {0, sim_box_v(s, t)};
	const long step = step_of(s, t);
	h5w_elem_row(h, &w->pos, w->k, step, t, w->p);
	h5w_elem_row(h, &w->vel, w->k, step, t, w->v);
	h5w_elem_row(h, &w->ang, w->k, step, t, th);
	h5w_elem_row(h, &w->off, w->k, step, t, off);
	h5w_elem_row(h, &w->offv, w->k, step, t, offv);
	if (w->wpos.g > 0) { /* the walls: at rest, moved with the box (write_walls) */
		const int nw = s->st.n - s->st.nm;
		for (int i = 0; i < nw; i++) {
			w->wp[2 * i] = s->st.q[C_X][0][s->st.nm + i];
			w->wp[2 * i + 1] = s->st.q[C_Y][0][s->st.nm + i] + off[1];
		}
		h5w_elem_row(h, &w->wpos, w->k, step, t, w->wp);
	}
	w->k++;
}

static void snap_close(h5w *h, snapw *w)
{
	if (w->wpos.g > 0)
		h5w_elem_close(h, &w->wpos);
	if (w->walls > 0)
		h5w_close_obj(h, w->walls);
	if (w->pos.g > 0) {
		h5w_elem_close(h, &w->offv);
		h5w_elem_close(h, &w->off);
		h5w_elem_close(h, &w->ang);
		h5w_elem_close(h, &w->vel);
		h5w_elem_close(h, &w->pos);
	}
	free(w->p);
	free(w->v);
	free(w->wp);
}

/* /particles/bed_xyz: position and velocity of /particles/bed as [K][n][3] virtual
 * datasets whose z is the fill value 0, and the same step and time (hard links).
 * MDAnalysis' H5MD reader, for one, refuses a box of dimension 2. */
static void write_xyz(h5w *h, hid_t xyz, hid_t bed, hsize_t K, hsize_t n, hid_t ftype, int periodic)
{
	static const char *const names[2] = {"position", "velocity"};
	static const char *const units[2] = {"cm", "cm s-1"};
	for (int q = 0; q < 2; q++) {
		hid_t g = h5w_group(h, xyz, names[q], 0);
		hid_t src = H5Gopen2(bed, names[q], H5P_DEFAULT);
		if (g < 0 || src < 0 || H5Lcreate_hard(src, "step", g, "step", H5P_DEFAULT, H5P_DEFAULT) < 0 ||
		    H5Lcreate_hard(src, "time", g, "time", H5P_DEFAULT, H5P_DEFAULT) < 0)
			h5w_fail(h);
		h5w_close_obj(h, src);
		hsize_t vd[3] = {K, n, 3}, sd[3] = {K, n, 2}, start[3] = {0, 0, 0};
		hid_t vsp = H5Screate_simple(3, vd, NULL), ssp = H5Screate_simple(3, sd, NULL);
		H5Sselect_hyperslab(vsp, H5S_SELECT_SET, start, NULL, sd, NULL);
		hid_t p = H5Pcreate(H5P_DATASET_CREATE);
		const double zero = 0;
		char path[64];
		snprintf(path, sizeof path, "/particles/bed/%s/value", names[q]);
		H5Pset_fill_value(p, H5T_NATIVE_DOUBLE, &zero);
		H5Pset_obj_track_times(p, 0);
		if (H5Pset_virtual(p, vsp, ".", path, ssp) < 0)
			h5w_fail(h);
		H5Sselect_all(vsp);
		hid_t d = H5Dcreate2(g, "value", ftype, vsp, H5P_DEFAULT, p, H5P_DEFAULT);
		/* no unit attribute: MDAnalysis refuses units it does not know (cm) even when
		 * told not to convert; the unit is that of the dataset this one shows */
		if (d < 0)
			h5w_fail(h);
		else
			h5w_attr_str(h, d, "unit_of_source", units[q]);
		h5w_close_obj(h, d);
		H5Pclose(p);
		H5Sclose(vsp);
		H5Sclose(ssp);
		h5w_close_obj(h, g);
	}
	hid_t b = h5w_group(h, xyz, "box", 0);
	/* no edges: MDAnalysis reads box/edges as a time series (edges/value) and would
	 * take a fixed one for a broken file; /particles/bed/box has them */
	static const char *const none3[3] = {"none", "none", "none"}, *const px3[3] = {"periodic", "none", "none"};
	h5w_attr_long(h, b, "dimension", 3);
	h5w_attr_strs(h, b, "boundary", periodic ? px3 : none3, 3);
	h5w_close_obj(h, b);
	h5w_attr_str(h, xyz, "description",
		     "/particles/bed as a flat 3-D system (z = 0): virtual datasets, no storage of their own");
}

/* The per-disk constants of disks i0 .. i1 - 1 into group g. */
static void disk_constants(h5w *h, const sb_state *st, hid_t g, int i0, int i1)
{
	const hsize_t n = (hsize_t)(i1 - i0);
	int *ki = malloc(sizeof(int) * (n ? n : 1));
	if (!ki) {
		h5w_fail(h);
		return;
	}
	for (hsize_t i = 0; i < n; i++)
		ki[i] = st->kind[i0 + (int)i];
	h5w_dset_int(h, g, "id", n, st->id + i0, "1");
	h5w_dset_int(h, g, "species", n, ki, "1");
	h5w_dset(h, g, "radius", 1, &n, st->r + i0, "cm");
	h5w_dset(h, g, "mass", 1, &n, st->m + i0, "g");
	h5w_attr_str(h, g, "species_names", "0 grain, 1 intruder, 2 wall");
	free(ki);
}

/* /particles/bed: the mobile disks' constants and their box. */
static hid_t write_bed(h5w *h, const sb_sim *s, hid_t parts, hid_t *box)
{
	hid_t g = h5w_group(h, parts, "bed", 0);
	disk_constants(h, &s->st, g, 0, s->st.nm);
	h5w_attr_long(h, g, "n_mobile", s->st.nm);
	*box = plain_box(h, s, g, 1);
	h5w_attr_str(h, *box, "description",
		     s->nl.period > 0
			     ? "periodic in x (sides = periodic): edges: the period and twice the settled surface height; "
			       "positions are as the engine holds them, wrapped into [0, period) at neighbour-list "
			       "builds only, so a disk may stand up to a skin outside; "
			       "offset: the lower left corner in the lab frame (the bottom moves with the drive), "
			       "offset_velocity: its velocity (the bottom wall's)"
			     : "edges: the side walls' inner faces apart and the highest wall disk's top above the bottom; "
			       "offset: the lower left corner in the lab frame (the bottom moves with the drive), "
			       "offset_velocity: its velocity (the walls')");
	return g;
}

/* /particles/walls: the wall disks, fixed in the box. Their place at rest is their
 * place in every snapshot (taken at phase 0, where the box is at rest); at time t
 * they are shifted by the box's offset. */
static void write_walls(h5w *h, const sb_sim *s, hid_t parts)
{
	const sb_state *st = &s->st;
	const hsize_t nw = (hsize_t)(st->n - st->nm), dims[2] = {nw, 2};
	hid_t g = h5w_group(h, parts, "walls", 0);
	disk_constants(h, st, g, st->nm, st->n);
	double *p = malloc(sizeof(double) * 2 * (nw ? nw : 1));
	if (!p) {
		h5w_fail(h);
	} else {
		for (hsize_t i = 0; i < nw; i++) {
			p[2 * i] = st->q[C_X][0][st->nm + (int)i];
			p[2 * i + 1] = st->q[C_Y][0][st->nm + (int)i];
		}
		h5w_dset(h, g, "position", 2, dims, p, "cm");
	}
	free(p);
	h5w_close_obj(h, plain_box(h, s, g, 0));
	h5w_attr_str(h, g, "description",
		     s->sc.snapshots_per_period > 1
			     ? "position: the wall disks with the box at rest (lab frame at phase 0); "
			       "snapshot_position: where they stand at each snapshot (the box's offset added)"
			     : "position: the wall disks with the box at rest (lab frame at phase 0, where every "
			       "snapshot is taken); at time t add /particles/bed/box/offset minus its value at rest");
	h5w_close_obj(h, g);
}

/* A fixed-length observable without a writer of its own (record.h's table): every value
 * column an H5MD element, named and in the unit of the table's column, on the first
 * one's clock, and the row's definition. A per-period row (RC_PHASE) is first reduced
 * to one row per drive period: the mean of its N samples (time and step: the last
 * one's, the period's end), with the drive frequency there as one more element; a
 * period whose samples the run did not finish is left out. The row's summaries
 * (record.h): the mean of its first value column over the rows written, or its last. */
static void write_series(h5w *h, const sb_sim *s, int id, hid_t g, const dbuf *b, long n)
{
	const sb_record *r = &rec_table()[id];
	const long len = r->len, N = r->clock == RC_PHASE ? (long)rec_rate(&s->sc, id) : 1, T = N > 0 ? n / N : 0;
	const size_t T1 = (size_t)(T ? T : 1);
	double *d = malloc(sizeof(double) * T1 * (size_t)len), *col = malloc(sizeof(double) * T1);
	double *t = malloc(sizeof(double) * T1);
	long *st = malloc(sizeof(long) * T1);
	if (!d || !col || !t || !st) {
		h5w_fail(h);
		goto out;
	}
	for (long p = 0; p < T; p++) { /* row p: the mean of samples pN .. pN + N - 1 */
		const double *last = b->d + (p * N + N - 1) * len;
		for (long c = 1; c < len; c++) {
			double m = b->d[p * N * len + c];
			for (long k = 1; k < N; k++)
				m += b->d[(p * N + k) * len + c];
			d[p * len + c] = N > 1 ? m / (double)N : m;
		}
		t[p] = last[0];
		st[p] = step_of(s, t[p]);
	}
	h5elem e0 = {.g = -1}, e;
	for (long c = 1; c < len; c++) {
		for (long p = 0; p < T; p++)
			col[p] = d[p * len + c];
		h5elem *el = c == 1 ? &e0 : &e;
		h5w_elem_create(h, el, g, r->cols[c].name, (hsize_t)T, 0, NULL, r->cols[c].unit, c == 1 ? NULL : &e0);
		h5w_elem_all(h, el, st, t, col);
		if (c > 1)
			h5w_elem_close(h, &e);
	}
	if (r->clock == RC_PHASE) {
		for (long p = 0; p < T; p++)
			col[p] = drive_freq(&s->drive, t[p]);
		h5w_elem_create(h, &e, g, "frequency", (hsize_t)T, 0, NULL, "Hz", &e0);
		h5w_elem_all(h, &e, NULL, NULL, col);
		h5w_elem_close(h, &e);
	}
	h5w_elem_close(h, &e0);
	if (r->clock == RC_PHASE)
		h5w_attr_long(h, g, "samples_per_period", N);
	if (r->def)
		h5w_attr_str(h, g, "definition", r->def);
	for (int k = 0; k < RSUM_N && T > 0; k++)
		if (rec_summary_row(k) == id && rec_summary_how(k) == RR_MEAN) {
			double sum = 0;
			for (long p = 0; p < T; p++)
				sum += d[p * len + 1];
			h5w_attr_double(h, h->file, rec_summary_attr(k), sum / (double)T);
		} else if (rec_summary_row(k) == id && rec_summary_how(k) == RR_LAST) {
			h5w_attr_double(h, h->file, rec_summary_attr(k), d[(T - 1) * len + 1]);
		}
out:
	free(d);
	free(col);
	free(t);
	free(st);
}

/* The groups of /observables whose layout is their own (a variable record, columns
 * gathered into one element): a writer each, given the group (made from the row's
 * path), the row's records and how many. Every other row with RECF_OBS is a
 * fixed-length series, written by write_series from the table alone. */
typedef void (*obs_writer)(h5w *h, const sb_sim *s, hid_t g, const dbuf *b, long n);
static const obs_writer WRITERS[REC_N] = {
	[REC_CONTACT] = write_contacts, [REC_FLUX] = write_flux, [REC_FIELD] = write_field,
	[REC_RING] = write_ring_series,
};

static int copy_journal(h5w *h, const sb_sim *s, hid_t parts, hid_t bed, hid_t box, sb_err *e)
{
	const sb_record *R = rec_table();
	const hsize_t K = (hsize_t)s->rec_n[REC_SNAP], T = (hsize_t)s->rec_n[REC_TRAJ];
	long cap = 1, any = 0;
	for (int k = 0; k < REC_N; k++) {
		/* the longest record: a fixed one, the scene's, or the largest contact frame */
		long len = R[k].len;
		if (k == REC_CONTACT)
			len = 2 + REC_NCOLS(REC_COLS_CONTACT) * s->max_contacts;
		else if (!len && (sample_on(s, k) || k == REC_SNAP))
			len = sample_len(s, k, NULL);
		cap = len > cap ? len : cap;
		any |= s->rec_n[k];
	}
	dbuf rec[REC_N] = {{0}};
	double *buf = malloc(sizeof(double) * (size_t)cap);
	snapw sw = {0};
	sw.pos.g = sw.wpos.g = sw.walls = -1;
	if (!buf || (K > 0 && snap_open(h, &sw, s, parts, bed, box, K))) {
		free(buf);
		snap_close(h, &sw);
		/* a failed HDF5 call (a full disk) is said by the caller, with HDF5's word */
		return h->bad ? 0 : sb_errf(e, SB_ENOMEM, "out of memory writing the output");
	}
	sb_jreader r = {0};
	/* a run that failed while preparing has no journal */
	int rc = (s->jr.f || any) ? journal_reader_open(&r, s->journal_path, e) : 1;
	while (!rc && !h->bad) {
		int count = 0;
		int tag = journal_next(&r, buf, cap, &count, e);
		if (tag <= 0) {
			rc = tag < 0 ? e->code : 0;
			break;
		}
		const int k = rec_by_tag(tag);
		if (k < 0) {
			rc = sb_errf(e, SB_EIO, "%s: corrupt journal record (tag %d, count %d)", s->journal_path, tag, count);
		} else if (k == REC_SNAP) {
			if (sw.k < K)
				snap_row(h, &sw, s, buf);
		} else if (k >= 0 && dbuf_add(&rec[k], buf, (size_t)count)) {
			rc = sb_errf(e, SB_ENOMEM, "out of memory reading the journal");
		}
	}
	journal_reader_close(&r);
	if (rc == 1)
		rc = 0;
	const long ks = (long)sw.k;
	snap_close(h, &sw);
	/* the journal holds what the counters say, record by record */
	long got[REC_N] = {0};
	got[REC_SNAP] = ks;
	for (int k = 0; k < REC_N; k++)
		for (size_t pos = 0; k != REC_SNAP && pos < rec[k].n; got[k]++) {
			/* every record holds a time and one more value; one that runs past the end
			 * (a damaged journal) is counted as none */
			const long l = rec[k].n - pos >= 2 ? sample_len(s, k, rec[k].d + pos) : -1;
			if (l < 2 || (size_t)l > rec[k].n - pos) {
				got[k] = -1;
				break;
			}
			pos += (size_t)l;
		}
	/* (a write that failed stopped the reading: said as that, by the caller) */
	for (int k = 0; k < REC_N && !rc && !h->bad; k++)
		if (got[k] != s->rec_n[k])
			rc = sb_errf(e, SB_EIO, "%s: journal holds %ld %s records, expected %ld", s->journal_path, got[k],
				     R[k].name, s->rec_n[k]);
	/* a journal not read to its end (a write that failed first, a short journal) has
	 * not the records the counters say: nothing more is copied, the file is not kept */
	const int whole = !rc && !h->bad;
	if (s->intruder >= 0) {
		write_intruder(h, s, parts, rec[REC_TRAJ].d, whole ? (long)T : 0);
		if (whole && T > 0)
			intruder_summary(h, s, rec[REC_TRAJ].d, (long)T);
	}
	if (sample_on(s, REC_INTRUDERS))
		write_intruders_pos(h, s, parts, rec[REC_INTRUDERS].d, whole ? got[REC_INTRUDERS] : 0);
	int obs_on = 0;
	for (int k = 0; k < REC_N; k++)
		obs_on |= (R[k].flags & RECF_OBS) && sample_on(s, k);
	if (whole && obs_on) {
		h5w_close_obj(h, h5w_group(h, h->file, REC_H5_OBS, 0));
		for (int k = 0; k < REC_N; k++)
			if ((R[k].flags & RECF_OBS) && sample_on(s, k)) {
				hid_t g = h5w_group(h, h->file, R[k].h5, 0);
				assert(WRITERS[k] || R[k].len > 0); /* record.h: rec_table_check */
				if (WRITERS[k])
					WRITERS[k](h, s, g, &rec[k], got[k]);
				else
					write_series(h, s, k, g, &rec[k], got[k]);
				h5w_close_obj(h, g);
			}
	}
	if (whole && s->obs.ring_on)
		write_ring(h, s, s->step * s->sc.dt);
	for (int k = 0; k < REC_N; k++)
		free(rec[k].d);
	free(buf);
	return rc;
}

static void write_final(h5w *h, const sb_sim *s, double t)
{
	const sb_state *st = &s->st;
	const hsize_t n = (hsize_t)st->n;
	double *v = malloc(sizeof(double) * (n ? n : 1) * 6);
	if (!v) {
		h5w_fail(h);
		return;
	}
	double idt = 1.0 / s->sc.dt, yb = sim_box_y(s, t), vb = sim_box_v(s, t);
	for (hsize_t i = 0; i < n; i++) {
		v[i] = st->q[C_X][0][i];
		v[n + i] = st->q[C_Y][0][i] + yb;
		v[2 * n + i] = st->q[C_X][1][i] * idt;
		v[3 * n + i] = st->q[C_Y][1][i] * idt + vb;
		v[4 * n + i] = st->q[C_TH][1][i] * idt;
		v[5 * n + i] = st->q[C_TH][0][i];
	}
	hid_t g = h5w_group(h, h->file, "final", 0);
	static const char *const names[6] = {"x", "y", "vx", "vy", "omega", "theta"};
	static const char *const units[6] = {"cm", "cm", "cm s-1", "cm s-1", "rad s-1", "rad"};
	for (int c = 0; c < 6; c++)
		h5w_dset(h, g, names[c], 1, &n, v + c * n, units[c]);
	disk_constants(h, st, g, 0, st->n);
	h5w_attr_double(h, g, "time", t);
	h5w_attr_str(h, g, "description",
		     "every disk at the end: the mobile ones (/particles/bed), then the walls (/particles/walls)");
	h5w_close_obj(h, g);
	free(v);
}

/* XDMF sidecar: ParaView reads the snapshots as a temporal collection; each time is a
 * spatial collection of the bed and the walls, where they were at that snapshot. The
 * bed carries, per disk, radius, species (its kind: 0 grain, 1 intruder), id, angle and
 * velocity (a 3-vector from /particles/bed_xyz, so that ParaView can colour by speed or
 * orient a glyph); the walls radius, species (2) and id. Every array is a hyperslab of
 * a dataset of the run file: the sidecar holds no number of its own but the times. */

/* A hyperslab of row k of a [K x n (x c)] dataset of the run file, as an XDMF item of
 * n (x c) values. */
static void xdmf_slab(FILE *f, const char *indent, long k, long K, int n, int c, const char *type, int prec,
		      const char *base, const char *path)
{
	if (c > 1) {
		fprintf(f,
			"%s<DataItem ItemType=\"HyperSlab\" Dimensions=\"%d %d\">\n"
			"%s  <DataItem Dimensions=\"3 3\" Format=\"XML\">%ld 0 0 1 1 1 1 %d %d</DataItem>\n"
			"%s  <DataItem Dimensions=\"%ld %d %d\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">%s:%s</DataItem>\n"
			"%s</DataItem>\n",
			indent, n, c, indent, k, n, c, indent, K, n, c, type, prec, base, path, indent);
	} else {
		fprintf(f,
			"%s<DataItem ItemType=\"HyperSlab\" Dimensions=\"%d\">\n"
			"%s  <DataItem Dimensions=\"3 2\" Format=\"XML\">%ld 0 1 1 1 %d</DataItem>\n"
			"%s  <DataItem Dimensions=\"%ld %d\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">%s:%s</DataItem>\n"
			"%s</DataItem>\n",
			indent, n, indent, k, n, indent, K, n, type, prec, base, path, indent);
	}
}

/* A per-disk array that does not change: radius, species, id of a particle group. */
static void xdmf_const(FILE *f, const char *name, int n, const char *type, int prec, const char *base, const char *grp)
{
	fprintf(f,
		"      <Attribute Name=\"%s\" Center=\"Node\">\n"
		"        <DataItem Dimensions=\"%d\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">%s:/particles/%s/%s</DataItem>\n"
		"      </Attribute>\n",
		name, n, type, prec, base, grp, name);
}

static void xdmf_grid(FILE *f, const char *name, int n)
{
	fprintf(f, "    <Grid Name=\"%s\" GridType=\"Uniform\">\n", name);
	fprintf(f, "      <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%d\"/>\n", n);
}

static int write_xdmf(const sb_sim *s, const char *h5path, sb_err *e)
{
	char path[4200];
	sim_xmf_path(h5path, path, sizeof path);
	const char *base = strrchr(h5path, '/');
	base = base ? base + 1 : h5path;
	sb_file out;
	if (fs_open_tmp(&out, path, e))
		return e->code;
	FILE *f = out.f;
	const int nm = s->st.nm, nw = s->st.n - s->st.nm, prec = s->sc.snapshot_precision ? 4 : 8;
	long K = s->rec_n[REC_SNAP];
	fprintf(f, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n<Domain>\n"
		   "<Grid Name=\"snapshots\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
	/* snapshot times are read back from the file so the sidecar matches it exactly */
	hid_t fid = H5Fopen(h5path, H5F_ACC_RDONLY, H5P_DEFAULT);
	double *times = malloc(sizeof(double) * (size_t)(K ? K : 1));
	if (fid >= 0 && times && K) {
		hid_t d = H5Dopen2(fid, "/particles/bed/position/time", H5P_DEFAULT);
		if (d < 0 || H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, times) < 0)
			K = 0;
		H5Dclose(d);
	}
	if (fid >= 0)
		H5Fclose(fid);
	const char *in = "          ";
	for (long k = 0; k < K && times; k++) {
		fprintf(f, "  <Grid Name=\"t%ld\" GridType=\"Collection\" CollectionType=\"Spatial\">\n    <Time Value=\"%.9g\"/>\n",
			k, times[k]);
		xdmf_grid(f, "bed", nm);
		fputs("      <Geometry GeometryType=\"XY\">\n", f);
		xdmf_slab(f, "        ", k, K, nm, 2, "Float", prec, base, "/particles/bed/position/value");
		fputs("      </Geometry>\n", f);
		xdmf_const(f, "radius", nm, "Float", 8, base, "bed");
		xdmf_const(f, "species", nm, "Int", 4, base, "bed");
		xdmf_const(f, "id", nm, "Int", 4, base, "bed");
		fputs("      <Attribute Name=\"angle\" Center=\"Node\">\n", f);
		xdmf_slab(f, in, k, K, nm, 1, "Float", prec, base, "/particles/bed/angle/value");
		fputs("      </Attribute>\n      <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">\n", f);
		xdmf_slab(f, in, k, K, nm, 3, "Float", prec, base, "/particles/bed_xyz/velocity/value");
		fputs("      </Attribute>\n    </Grid>\n", f);
		if (nw > 0) {
			xdmf_grid(f, "walls", nw);
			fputs("      <Geometry GeometryType=\"XY\">\n", f);
			if (s->sc.snapshots_per_period > 1)
				xdmf_slab(f, "        ", k, K, nw, 2, "Float", prec, base,
					  "/particles/walls/snapshot_position/value");
			else /* at phase 0, where the walls stand at rest */
				fprintf(f,
					"        <DataItem Dimensions=\"%d 2\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/particles/walls/position</DataItem>\n",
					nw, base);
			fputs("      </Geometry>\n", f);
			xdmf_const(f, "radius", nw, "Float", 8, base, "walls");
			xdmf_const(f, "species", nw, "Int", 4, base, "walls");
			xdmf_const(f, "id", nw, "Int", 4, base, "walls");
			fputs("    </Grid>\n", f);
		}
		fprintf(f, "  </Grid>\n");
	}
	free(times);
	fprintf(f, "</Grid>\n</Domain>\n</Xdmf>\n");
	return fs_commit(&out, e);
}

/* /h5md: the convention's version, who wrote the file and with what. */
static void write_h5md(h5w *h)
{
	hid_t g = h5w_group(h, h->file, "h5md", 0);
	static const int version[2] = {1, 1};
	h5w_attr_ints(h, g, "version", version, 2);
	hid_t a = h5w_group(h, g, "author", 0);
	const char *user = getenv("USER");
	h5w_attr_str(h, a, "name", user && *user ? user : "unknown");
	h5w_close_obj(h, a);
	hid_t c = h5w_group(h, g, "creator", 0);
	h5w_attr_str(h, c, "name", "shakebox");
	h5w_attr_str(h, c, "version", prov_version());
	h5w_close_obj(h, c);
	/* the units module (version 1.0): every element's unit attribute is a string of its
	 * grammar, in the symbols of its "SI" system (which has cgs's dyn and erg too) */
	hid_t m = h5w_group(h, g, "modules", 0), u = h5w_group(h, m, "units", 0);
	static const int units_version[2] = {1, 0};
	h5w_attr_ints(h, u, "version", units_version, 2);
	h5w_attr_vstr(h, u, "system", "SI");
	h5w_close_obj(h, u);
	h5w_close_obj(h, m);
	h5w_close_obj(h, g);
}

static int cmp_wait(const void *a, const void *b)
{
	const double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* Several intruders (docs/model.md, "Several intruders"; nothing for one, whose file
 * keeps its bits): /intruders, each one's id, settled height, rise and waiting time (the
 * censoring time t when it has not risen), and the summaries of the root: how many and
 * how many rose, the first, median and last waiting time (the median once more than
 * half rose: the unrisen are later than any; the others once one rose). */
static void write_intruders(h5w *h, const sb_sim *s, double t)
{
	const sb_obs *o = &s->obs;
	const int n = o->nint;
	if (n < 2)
		return;
	int *id = malloc(sizeof(int) * (size_t)n), *risen = malloc(sizeof(int) * (size_t)n);
	double *y0 = malloc(sizeof(double) * (size_t)n), *w = malloc(sizeof(double) * (size_t)n);
	double *up = malloc(sizeof(double) * (size_t)n);
	if (!id || !risen || !y0 || !w || !up) {
		h5w_fail(h);
		goto out;
	}
	int nr = 0;
	for (int k = 0; k < n; k++) {
		double wt;
		id[k] = s->st.id[o->iidx[k]];
		risen[k] = obs_intruder_risen(o, k, &wt);
		y0[k] = k == 0 ? s->intruder_y0 : o->iy0[k];
		w[k] = risen[k] ? wt : t;
		if (risen[k])
			up[nr++] = wt;
	}
	hid_t g = h5w_group(h, h->file, "intruders", 0);
	const hsize_t dn = (hsize_t)n;
	h5w_dset_int(h, g, "id", dn, id, NULL);
	h5w_dset(h, g, "settled_y", 1, &dn, y0, "cm");
	h5w_dset_int(h, g, "risen", dn, risen, NULL);
	h5w_dset(h, g, "waiting_time", 1, &dn, w, "s");
	h5w_attr_str(h, g, "description",
		     "every intruder: id, settled_y (its centre's height after settling), risen (1: one diameter "
		     "above it), waiting_time (the first time it was, or the time observed when risen = 0; "
		     "docs/model.md, \"Several intruders\")");
	h5w_close_obj(h, g);
	qsort(up, (size_t)nr, sizeof *up, cmp_wait);
	h5w_attr_long(h, h->file, "intruders", n);
	h5w_attr_long(h, h->file, "intruders_risen", nr);
	if (nr > 0) {
		h5w_attr_double(h, h->file, "rise_first", up[0]);
		h5w_attr_double(h, h->file, "rise_last", up[nr - 1]);
	}
	if (2 * nr > n) /* the median of n, the unrisen last: element (n - 1) / 2, or the mean of two */
		h5w_attr_double(h, h->file, "rise_median",
				n % 2 ? up[(n - 1) / 2] : 0.5 * (up[n / 2 - 1] + up[n / 2]));
out:
	free(id);
	free(risen);
	free(y0);
	free(w);
	free(up);
}

/* The run's status and results: attributes of the root. */
static void write_results(h5w *h, const sb_sim *s, double t)
{
	const hid_t r = h->file;
	h5w_attr_str(h, r, H5ID_FORMAT_ATTR, H5ID_FORMAT);
	h5w_attr_str(h, r, "status", sb_code_name(s->status));
	h5w_attr_long(h, r, "exit_code", s->status);
	h5w_attr_str(h, r, "status_message", s->status_msg);
	h5w_attr_double(h, r, "status_time", s->status ? s->status_time : t);
	h5w_attr_long(h, r, "status_step", s->status ? s->status_step : s->step);
	h5w_attr_long(h, r, "steps", s->step);
	h5w_attr_long(h, r, "settle_steps", s->settle_steps);
	h5w_attr_double(h, r, "settle_time", s->settle_time);
	h5w_attr_double(h, r, "surface_height", s->surface0);
	if (s->intruder >= 0) { /* no NaN placeholders: absent when there is no intruder */
		h5w_attr_double(h, r, "intruder_settled_y", s->intruder_y0);
		h5w_attr_double(h, r, "intruder_settled_depth", s->surface0 - s->intruder_y0);
		h5w_attr_double(h, r, "intruder_radius", s->st.r[s->intruder]);
	}
	h5w_attr_long(h, r, "n_mobile", s->st.nm);
	h5w_attr_long(h, r, "n_walls", s->st.n - s->st.nm);
	h5w_attr_long(h, r, "neighbour_builds", s->nl.builds);
	/* which stop rule ended the run (docs/model.md, "Stop rules"), and when */
	sb_scene rs = s->sc;
	rs.stop = s->obs.stop_rule;
	char rule[32];
	params_format(&rs, params_find("stop"), rule, sizeof rule);
	h5w_attr_str(h, r, "stopped_by", rule);
	if (s->obs.stop_rule)
		h5w_attr_double(h, r, "stop_time", s->obs.stop_step * s->sc.dt);
	/* the largest overlap of the shaking, and where (0 when nothing touched) */
	h5w_attr_double(h, r, "overlap_max", s->obs.ov_max);
	if (s->obs.ov_max > 0) {
		h5w_attr_double(h, r, "overlap_max_time", s->obs.ov_t);
		h5w_attr_long(h, r, "overlap_max_disk_a", s->obs.ov_i);
		h5w_attr_long(h, r, "overlap_max_disk_b", s->obs.ov_j);
		h5w_attr_double(h, r, "overlap_max_x", s->obs.ov_x);
		h5w_attr_double(h, r, "overlap_max_y_box", s->obs.ov_y);
	}
	/* the survival-analysis pair risen, waiting_time: docs/model.md, "Waiting time" */
	if (s->intruder >= 0) {
		h5w_attr_long(h, r, "risen", s->obs.risen);
		h5w_attr_double(h, r, "waiting_time", s->obs.risen ? s->obs.wait_time : t);
	}
	write_intruders(h, s, t);
}

/* /contact_law: what the contact law gives each class of pair (pclass.h), so that a
 * reader sees the restitution and contact time without the formulas */
static void write_contact_law(h5w *h, const sb_sim *s)
{
	hid_t g = h5w_group(h, h->file, "contact_law", 0);
	h5w_attr_str(h, g, "damping", s->law.resti ? "restitution" : "gamma_n");
	h5w_attr_str(h, g, "normal", s->law.hertz ? "hertz" : "hooke");
	if (s->law.hertz) /* its restitution and contact time depend on the impact speed */
		h5w_attr_double(h, g, "impact_speed", PCLASS_HERTZ_V);
	h5w_attr_str(h, g, "tangential", s->law.spring ? "spring" : "viscous");
	h5w_attr_str(h, g, "materials", s->law.table ? "per_pair_class" : "one");
	if (s->law.spring) /* k_t, given or LAMMPS's default 2/7 of the normal stiffness */
		h5w_attr_double(h, g, "shear_stiffness", s->law.kt);
	h5w_attr_str(h, g, "definition",
		     "per class of pair: m_eff (g), gamma_n (1/s: the normal damping force is gamma_n m_eff xidot), "
		     "restitution and contact_time (s) of an unclipped head-on contact, a wall disk immobile; "
		     "normal = hertz: at impact_speed (cm/s) (docs/model.md, \"Restitution\"); tangential = spring: "
		     "shear_stiffness k_t (docs/model.md, \"Tangential law\"); each class's stiffness (the normal law's), mu "
		     "and gamma_s; materials: one, or per_pair_class when a class has coefficients of its own "
		     "(docs/model.md, \"Materials per pair of kinds\")");
	sb_pclass c[SB_NPCLASS];
	pclass_of_state(&s->law, &s->sc, &s->st, c);
	for (int k = 0; k < SB_NPCLASS; k++) {
		if (!c[k].present)
			continue;
		hid_t p = h5w_group(h, g, c[k].name, 0);
		h5w_attr_double(h, p, "m_eff", c[k].m_eff);
		h5w_attr_double(h, p, "gamma_n", c[k].gamma_n);
		h5w_attr_double(h, p, "restitution", c[k].e);
		h5w_attr_double(h, p, "contact_time", c[k].tc);
		h5w_attr_double(h, p, "stiffness", c[k].Y);
		h5w_attr_double(h, p, "mu", c[k].mu);
		h5w_attr_double(h, p, "gamma_s", c[k].gamma_s);
		h5w_close_obj(h, p);
	}
	h5w_close_obj(h, g);
}

static void write_provenance(h5w *h, const sb_sim *s)
{
	hid_t g = h5w_group(h, h->file, "provenance", 0);
	sb_prov p = s->prov;
	prov_now(p.end_time);
	h5w_attr_str(h, g, "git_hash", p.git_hash);
	h5w_attr_long(h, g, "git_dirty", p.git_dirty);
	h5w_attr_str(h, g, "compiler", p.compiler);
	h5w_attr_str(h, g, "cflags", p.cflags);
	h5w_attr_str(h, g, "host", p.host);
	h5w_attr_str(h, g, "cpu", p.cpu);
	h5w_attr_str(h, g, "kernel_path", kernel_path(s->kern));
	h5w_attr_str(h, g, "start_time", p.start_time);
	h5w_attr_str(h, g, "end_time", p.end_time);
	h5w_attr_double(h, g, "loop_seconds", s->loop_seconds);
	h5w_close_obj(h, g);
}

int h5out_write(const sb_sim *s, const char *path, sb_err *e)
{
	char tmp[4200];
	fs_tmp_name(path, tmp, sizeof tmp);
	/* made here first: HDF5's own create would follow a link planted at the name */
	int fd = fs_create(tmp, 0, e);
	if (fd < 0)
		return e->code;
	close(fd);
	h5w_init();
	H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* errors are reported through sb_err */
	h5w h;
	if (h5w_create(&h, tmp, (int)s->sc.compression)) {
		char why[256];
		h5w_last_error(why, sizeof why);
		unlink(tmp); /* HDF5 may have made it before it failed (a full disk) */
		return sb_errf(e, SB_EIO, "%s: cannot create HDF5 file%s%s", tmp, why[0] ? ": " : "", why);
	}
	const double t = s->step * s->sc.dt;
	write_h5md(&h);
	hid_t g = h5w_group(&h, h.file, "parameters", 0);
	write_params(&h, g, &s->sc);
	h5w_close_obj(&h, g);
	write_results(&h, s, t);
	write_contact_law(&h, s);
	write_provenance(&h, s);

	/* /particles lists bed_xyz first: readers that take the first particle group and
	 * know only 3-D (MDAnalysis) find the view they can read */
	hid_t parts = h5w_group(&h, h.file, "particles", 1);
	hid_t xyz = s->rec_n[REC_SNAP] > 0 ? h5w_group(&h, parts, "bed_xyz", 0) : -1;
	hid_t box = -1;
	hid_t bed = write_bed(&h, s, parts, &box);
	write_walls(&h, s, parts);
	int rc = copy_journal(&h, s, parts, bed, box, e);
	if (xyz >= 0) {
		if (!rc)
			write_xyz(&h, xyz, bed, (hsize_t)s->rec_n[REC_SNAP], (hsize_t)s->st.nm,
				  s->sc.snapshot_precision ? H5T_IEEE_F32LE : H5T_IEEE_F64LE, s->nl.period > 0);
		h5w_close_obj(&h, xyz);
	}
	h5w_close_obj(&h, box);
	h5w_close_obj(&h, bed);
	h5w_close_obj(&h, parts);
	write_final(&h, s, t);
	/* last: the digest covers every attribute written above (core/io/h5id.h) */
	if (!rc && !h.bad)
		rc = h5id_seal(h.file, e);
	if (h5w_close(&h) && !rc) {
		const char *why = h.why; /* the first failure; else the close's own */
		char last[256];
		if (!why[0]) {
			h5w_last_error(last, sizeof last);
			why = last;
		}
		rc = sb_errf(e, SB_EIO, "%s: writing the HDF5 output failed%s%s", tmp, why[0] ? ": " : "", why);
	}
	/* the seal covers every byte HDF5 wrote, so it comes after HDF5 closed the file */
	if (!rc)
		rc = h5seal_write(tmp, e);
	if (!rc)
		rc = fs_fsync_path(tmp, e);
	if (!rc)
		rc = fs_rename_durable(tmp, path, e);
	if (rc) {
		unlink(tmp);
		return rc;
	}
	return write_xdmf(s, path, e);
}

int h5out_write_run(sb_sim *s, sb_err *e)
{
	long off;
	if (s->jr.f && journal_sync(&s->jr, &off, e))
		return e->code;
	return h5out_write(s, s->sc.output, e);
}
