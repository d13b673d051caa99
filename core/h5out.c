/* h5out.c - the run's HDF5 file and its XDMF sidecar, assembled when the run ends:
 *   /            attributes: every scene parameter (typed), status, preparation results
 *   /provenance  attributes: git hash, dirty flag, compiler, flags, host, times
 *   /particles   id, kind (0 grain, 1 intruder, 2 wall), radius, mass
 *   /intruder/trajectory  [n x 6]: t, x, y, vx, vy, omega (lab frame)
 *   /snapshots/time [K], x, y, theta [K x n_mobile] (lab frame, phase 0 of each period)
 *   /final       x, y, vx, vy, omega, theta of every disk (lab frame)
 * Object time stamps are switched off so that two runs of the same scene give
 * identical files apart from /provenance. */
#include <hdf5.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fsutil.h"
#include "h5out.h"

typedef struct h5 {
	hid_t file, gcpl, dcpl;
	int bad;
} h5;

static void attr_double(h5 *h, hid_t obj, const char *name, double v)
{
	hid_t sp = H5Screate(H5S_SCALAR);
	hid_t a = H5Acreate2(obj, name, H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
	if (a < 0 || H5Awrite(a, H5T_NATIVE_DOUBLE, &v) < 0)
		h->bad = 1;
	H5Aclose(a);
	H5Sclose(sp);
}

static void attr_long(h5 *h, hid_t obj, const char *name, long v)
{
	long long x = v;
	hid_t sp = H5Screate(H5S_SCALAR);
	hid_t a = H5Acreate2(obj, name, H5T_STD_I64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
	if (a < 0 || H5Awrite(a, H5T_NATIVE_LLONG, &x) < 0)
		h->bad = 1;
	H5Aclose(a);
	H5Sclose(sp);
}

static void attr_str(h5 *h, hid_t obj, const char *name, const char *v)
{
	hid_t t = H5Tcopy(H5T_C_S1);
	H5Tset_size(t, strlen(v) + 1);
	H5Tset_strpad(t, H5T_STR_NULLTERM);
	hid_t sp = H5Screate(H5S_SCALAR);
	hid_t a = H5Acreate2(obj, name, t, sp, H5P_DEFAULT, H5P_DEFAULT);
	if (a < 0 || H5Awrite(a, t, v) < 0)
		h->bad = 1;
	H5Aclose(a);
	H5Sclose(sp);
	H5Tclose(t);
}

static hid_t group(h5 *h, const char *name)
{
	hid_t g = H5Gcreate2(h->file, name, H5P_DEFAULT, h->gcpl, H5P_DEFAULT);
	if (g < 0)
		h->bad = 1;
	return g;
}

/* A 1-D or 2-D dataset written at once from memory. */
static void dset(h5 *h, hid_t loc, const char *name, hid_t ftype, hid_t mtype, int rank,
		 hsize_t d0, hsize_t d1, const void *data)
{
	hsize_t dims[2] = {d0, d1};
	hid_t sp = H5Screate_simple(rank, dims, NULL);
	hid_t d = H5Dcreate2(loc, name, ftype, sp, H5P_DEFAULT, h->dcpl, H5P_DEFAULT);
	if (d < 0 || (d0 * (rank > 1 ? d1 : 1) > 0 && H5Dwrite(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0))
		h->bad = 1;
	H5Dclose(d);
	H5Sclose(sp);
}

static void write_params(h5 *h, const sb_scene *sc)
{
	size_t n;
	const sb_param *t = params_table(&n);
	for (size_t i = 0; i < n; i++) {
		const char *base = (const char *)sc + t[i].offset;
		char buf[SB_STR_MAX + 32];
		switch (t[i].type) {
		case PT_INT: attr_long(h, h->file, t[i].name, *(const long *)base); break;
		case PT_REAL: attr_double(h, h->file, t[i].name, *(const double *)base); break;
		default:
			params_format(sc, &t[i], buf, sizeof buf);
			attr_str(h, h->file, t[i].name, buf);
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

static void write_flux(h5 *h, const sb_sim *s, const dbuf *fl)
{
	const sb_obs *o = &s->obs;
	const int nl = o->nlines, len = obs_flux_len(o);
	const hsize_t P = (hsize_t)s->n_flux;
	double *t = malloc(sizeof(double) * (P ? P : 1)), *f = malloc(sizeof(double) * (P ? P : 1));
	double *jt = malloc(sizeof(double) * (P ? P : 1) * nl), *jb = malloc(sizeof(double) * (P ? P : 1) * nl);
	double *phi = malloc(sizeof(double) * (P ? P : 1) * nl);
	if (!t || !f || !jt || !jb || !phi) {
		h->bad = 1;
	} else {
		for (hsize_t k = 0; k < P; k++) {
			const double *r = fl->d + k * len;
			t[k] = r[0];
			f[k] = r[1];
			for (int l = 0; l < nl; l++) {
				jt[k * nl + l] = r[2 + l];
				jb[k * nl + l] = r[2 + nl + l];
				phi[k * nl + l] = r[2 + l] - r[2 + nl + l];
			}
		}
		hid_t g = group(h, "/flux");
		dset(h, g, "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, P, 0, t);
		dset(h, g, "frequency", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, P, 0, f);
		dset(h, g, "j_top", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 2, P, (hsize_t)nl, jt);
		dset(h, g, "j_bot", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 2, P, (hsize_t)nl, jb);
		dset(h, g, "phi", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 2, P, (hsize_t)nl, phi);
		dset(h, g, "heights", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, (hsize_t)nl, 0, o->hline);
		attr_str(h, g, "definition",
			 "per period (between successive phase-0 samples): j_top = upward - downward crossings of "
			 "each height line by disks whose mean x lies within W/4 of the box centre, j_bot the same "
			 "outside; phi = j_top - j_bot (particles per period); heights in cm above the bottom");
		attr_double(h, g, "surface_height", o->surface);
		H5Gclose(g);
	}
	free(t);
	free(f);
	free(jt);
	free(jb);
	free(phi);
}

static void write_field(h5 *h, const sb_sim *s, const dbuf *fd)
{
	const sb_obs *o = &s->obs;
	const size_t nc = (size_t)o->nx * o->ny;
	const int len = obs_field_len(o);
	const hsize_t B = (hsize_t)s->n_field;
	double *t = malloc(sizeof(double) * (B ? B : 1));
	double *ux = malloc(sizeof(double) * (B ? B : 1) * nc), *uy = malloc(sizeof(double) * (B ? B : 1) * nc);
	double *cnt = malloc(sizeof(double) * (B ? B : 1) * nc);
	if (!t || !ux || !uy || !cnt) {
		h->bad = 1;
	} else {
		for (hsize_t k = 0; k < B; k++) {
			const double *r = fd->d + k * len;
			t[k] = r[0];
			for (size_t c = 0; c < nc; c++) {
				double n = r[2 + 2 * nc + c];
				/* mean displacement per period of the disks that passed the cell */
				ux[k * nc + c] = n > 0 ? r[2 + c] / n : 0;
				uy[k * nc + c] = n > 0 ? r[2 + nc + c] / n : 0;
				cnt[k * nc + c] = n;
			}
		}
		hid_t g = group(h, "/field");
		hsize_t dims[3] = {B, (hsize_t)o->ny, (hsize_t)o->nx};
		const char *names[3] = {"ux", "uy", "count"};
		double *data[3] = {ux, uy, cnt};
		for (int q = 0; q < 3; q++) {
			hid_t sp = H5Screate_simple(3, dims, NULL);
			hid_t d = H5Dcreate2(g, names[q], H5T_IEEE_F64LE, sp, H5P_DEFAULT, h->dcpl, H5P_DEFAULT);
			if (d < 0 || (B && H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data[q]) < 0))
				h->bad = 1;
			H5Dclose(d);
			H5Sclose(sp);
		}
		dset(h, g, "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, B, 0, t);
		attr_double(h, g, "cell", o->cell);
		attr_double(h, g, "x0", o->x0);
		attr_long(h, g, "periods_per_block", o->K);
		attr_str(h, g, "definition",
			 "[block, row, column]: cell (c, r) spans x0 + c*cell .. x0 + (c+1)*cell and r*cell .. (r+1)*cell "
			 "above the bottom; ux, uy = mean displacement per period of the disks whose midpoint between "
			 "successive phase-0 samples lies in the cell, over periods_per_block periods (cm); count = samples");
		H5Gclose(g);
	}
	free(t);
	free(ux);
	free(uy);
	free(cnt);
}

/* The energy series (energy_rate): one dataset per column, each with its unit. The
 * energies are the box frame's (the box's own motion is not the bed's). */
static void write_energy(h5 *h, const dbuf *en, long T)
{
	static const char *const names[JR_ENERGY_COLS] = {"time", "kinetic_translational", "kinetic_rotational",
							  "elastic", "com_height_box", "max_overlap", "contacts"};
	static const char *const units[JR_ENERGY_COLS] = {"s", "erg", "erg", "erg", "cm", "1", "1"};
	double *col = malloc(sizeof(double) * (size_t)(T ? T : 1));
	if (!col) {
		h->bad = 1;
		return;
	}
	hid_t go = group(h, "/observables");
	hid_t g = H5Gcreate2(go, "energy", H5P_DEFAULT, h->gcpl, H5P_DEFAULT);
	for (int c = 0; c < JR_ENERGY_COLS; c++) {
		for (long k = 0; k < T; k++)
			col[k] = en->d[k * JR_ENERGY_COLS + c];
		dset(h, g, names[c], H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, (hsize_t)T, 0, col);
		hid_t d = H5Dopen2(g, names[c], H5P_DEFAULT);
		if (d >= 0) {
			attr_str(h, d, "unit", units[c]);
			H5Dclose(d);
		}
	}
	attr_str(h, g, "definition",
		 "box frame: kinetic = sum m v^2 / 2 and I w^2 / 2 of the mobile disks; elastic = sum Y xi^2 / 2 over "
		 "the contacts; com_height_box = mass-weighted mean y of the mobile disks; max_overlap = largest xi / "
		 "min(R_i, R_j) at the sample (docs/model.md, \"Observables\")");
	H5Gclose(g);
	H5Gclose(go);
	free(col);
}

/* The contact dump (contact_rate): frames of every contact, flattened - frame k's
 * contacts are rows offset[k] .. offset[k] + count[k] of the per-contact datasets. */
static void write_contacts(h5 *h, const dbuf *c, long F)
{
	static const char *const names[JR_CONTACT_COLS] = {"id_a", "id_b", "normal_force", "tangential_force",
							   "normal_x", "normal_y", "x", "y_box"};
	static const char *const units[JR_CONTACT_COLS] = {"1", "1", "dyn", "dyn", "1", "1", "cm", "cm"};
	double *t = malloc(sizeof(double) * (size_t)(F ? F : 1)), *cnt = malloc(sizeof(double) * (size_t)(F ? F : 1)),
	       *off = malloc(sizeof(double) * (size_t)(F ? F : 1));
	size_t C = 0, pos = 0;
	for (long k = 0; k < F && t && cnt && off; k++) { /* frame k: t, n, n x 8 values */
		t[k] = c->d[pos];
		cnt[k] = c->d[pos + 1];
		off[k] = (double)C;
		C += (size_t)cnt[k];
		pos += 2 + JR_CONTACT_COLS * (size_t)cnt[k];
	}
	double *col = malloc(sizeof(double) * (C ? C : 1));
	if (!t || !cnt || !off || !col) {
		h->bad = 1;
	} else {
		hid_t go = H5Lexists(h->file, "/observables", H5P_DEFAULT) > 0 ? H5Gopen2(h->file, "/observables", H5P_DEFAULT)
										   : group(h, "/observables");
		hid_t g = H5Gcreate2(go, "contacts", H5P_DEFAULT, h->gcpl, H5P_DEFAULT);
		dset(h, g, "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, (hsize_t)F, 0, t);
		dset(h, g, "count", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, (hsize_t)F, 0, cnt);
		dset(h, g, "offset", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, (hsize_t)F, 0, off);
		for (int k = 0; k < JR_CONTACT_COLS; k++) {
			size_t row = 0;
			pos = 0;
			for (long fr = 0; fr < F; fr++) {
				const size_t n = (size_t)cnt[fr];
				for (size_t q = 0; q < n; q++)
					col[row++] = c->d[pos + 2 + JR_CONTACT_COLS * q + (size_t)k];
				pos += 2 + JR_CONTACT_COLS * n;
			}
			dset(h, g, names[k], H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, (hsize_t)C, 0, col);
			hid_t d = H5Dopen2(g, names[k], H5P_DEFAULT);
			if (d >= 0) {
				attr_str(h, d, "unit", units[k]);
				H5Dclose(d);
			}
		}
		attr_str(h, g, "definition",
			 "every contact at each sample: disks id_a, id_b; the force on id_a is normal_force n + "
			 "tangential_force t with n = (r_a - r_b)/d = (normal_x, normal_y), t = n turned by +90 deg; "
			 "x, y_box: midpoint of the centres (box frame); frame k is rows offset[k] .. offset[k] + count[k]");
		H5Gclose(g);
		H5Gclose(go);
	}
	free(t);
	free(cnt);
	free(off);
	free(col);
}

static void write_ring(h5 *h, const sb_sim *s)
{
	const sb_obs *o = &s->obs;
	hid_t g = group(h, "/ring");
	double n = o->ring_samples ? (double)o->ring_samples : 1; /* no samples: zeros, never NaN */
	attr_double(h, g, "inner", o->rin);
	attr_double(h, g, "outer", o->rout);
	attr_long(h, g, "samples", o->ring_samples);
	attr_double(h, g, "mean_force", o->acc[0] / n);
	attr_double(h, g, "mean_force_lower", o->acc[1] / n);
	attr_double(h, g, "sum_force", o->acc[2] / n);
	attr_double(h, g, "sum_force_lower", o->acc[3] / n);
	attr_double(h, g, "temperature", o->acc[4] / n);
	attr_double(h, g, "temperature_lower", o->acc[5] / n);
	attr_double(h, g, "grains", o->acc[6] / n);
	attr_double(h, g, "grains_lower", o->acc[7] / n);
	attr_str(h, g, "definition",
		 "time averages over samples every ring_every steps of grains whose centres lie inner..outer cm "
		 "from the intruder centre (or ring_x, ring_y): mean_force = mean over grains of the sum of the "
		 "magnitudes of their contact forces (dyn), sum_force = its sum over the ring, temperature = half "
		 "the mean squared velocity fluctuation about the ring's mean velocity (cm^2/s^2); _lower: grains "
		 "below the centre");
	H5Gclose(g);
}

/* Snapshots stream from the journal into [K x nm] datasets, one row at a time; the
 * other record types are small and gathered in memory first. */
/* The intruder's height over the recorded trajectory rows in the box frame (the
 * trajectory holds lab-frame y; the box frame is the one its settled height and the
 * waiting time are measured in, so a rise never counts the box's own motion). */
static void intruder_summary(h5 *h, const sb_sim *s, const double *traj, long T)
{
	double ymax = -INFINITY, ymin = INFINITY, sum = 0, y = 0;
	for (long k = 0; k < T; k++) {
		const double *row = traj + k * JR_TRAJ_COLS;
		y = row[2] - sim_box_y(s, row[0]);
		ymax = y > ymax ? y : ymax;
		ymin = y < ymin ? y : ymin;
		sum += y;
	}
	attr_double(h, h->file, "intruder_final_y_box", y);
	attr_double(h, h->file, "intruder_max_y_box", ymax);
	attr_double(h, h->file, "intruder_min_y_box", ymin);
	attr_double(h, h->file, "intruder_mean_y_box", sum / (double)T);
}

static int copy_journal(h5 *h, const sb_sim *s, sb_err *e)
{
	const int nm = s->st.nm;
	const hsize_t K = (hsize_t)s->n_snap, T = (hsize_t)s->n_traj;
	long cap = 3L * nm + 1;
	if (cap < JR_TRAJ_COLS) /* an intruder and no grains: a trajectory row is longer */
		cap = JR_TRAJ_COLS;
	if (cap < JR_ENERGY_COLS)
		cap = JR_ENERGY_COLS;
	if (cap < 2 + JR_CONTACT_COLS * s->max_contacts)
		cap = 2 + JR_CONTACT_COLS * s->max_contacts;
	if (s->obs.flux_on && obs_flux_len(&s->obs) > cap)
		cap = obs_flux_len(&s->obs);
	if (s->obs.field_on && obs_field_len(&s->obs) > cap)
		cap = obs_field_len(&s->obs);
	dbuf traj = {0}, flux = {0}, field = {0}, energy = {0}, contacts = {0};
	double *times = malloc(sizeof(double) * (K ? K : 1));
	double *buf = malloc(sizeof(double) * (size_t)cap);
	if (!times || !buf) {
		free(times);
		free(buf);
		return sb_errf(e, SB_ENOMEM, "out of memory writing the output");
	}
	hid_t gs = group(h, "/snapshots");
	hsize_t dims[2] = {K, (hsize_t)nm};
	hid_t sp = H5Screate_simple(2, dims, NULL);
	const char *names[3] = {"x", "y", "theta"};
	hid_t ds[3];
	for (int c = 0; c < 3; c++) {
		ds[c] = H5Dcreate2(gs, names[c], H5T_IEEE_F64LE, sp, H5P_DEFAULT, h->dcpl, H5P_DEFAULT);
		if (ds[c] < 0)
			h->bad = 1;
	}
	hsize_t row[2] = {1, (hsize_t)nm};
	hid_t msp = H5Screate_simple(2, row, NULL);
	sb_jreader r = {0};
	long ks = 0;
	/* a run that failed while preparing has no journal */
	int rc = (s->jr.f || K || T || s->n_flux || s->n_field || s->n_energy || s->n_contact) ? journal_reader_open(&r, s->journal_path, e)
										    : 1;
	while (!rc && !h->bad) {
		int count = 0;
		int tag = journal_next(&r, buf, cap, &count, e);
		if (tag <= 0) {
			rc = tag < 0 ? e->code : 0;
			break;
		}
		if (tag == JR_TRAJ)
			rc = dbuf_add(&traj, buf, JR_TRAJ_COLS) ? SB_ENOMEM : 0;
		else if (tag == JR_FLUX)
			rc = dbuf_add(&flux, buf, (size_t)count) ? SB_ENOMEM : 0;
		else if (tag == JR_FIELD)
			rc = dbuf_add(&field, buf, (size_t)count) ? SB_ENOMEM : 0;
		else if (tag == JR_ENERGY)
			rc = dbuf_add(&energy, buf, JR_ENERGY_COLS) ? SB_ENOMEM : 0;
		else if (tag == JR_CONTACT)
			rc = dbuf_add(&contacts, buf, (size_t)count) ? SB_ENOMEM : 0;
		else if (tag == JR_SNAP && (hsize_t)ks < K) {
			times[ks] = buf[0];
			hsize_t start[2] = {(hsize_t)ks, 0};
			for (int c = 0; c < 3; c++) {
				hid_t fsp = H5Dget_space(ds[c]);
				H5Sselect_hyperslab(fsp, H5S_SELECT_SET, start, NULL, row, NULL);
				if (H5Dwrite(ds[c], H5T_NATIVE_DOUBLE, msp, fsp, H5P_DEFAULT, buf + 1 + (size_t)c * nm) < 0)
					h->bad = 1;
				H5Sclose(fsp);
			}
			ks++;
		}
		if (rc == SB_ENOMEM)
			rc = sb_errf(e, SB_ENOMEM, "out of memory reading the journal");
	}
	journal_reader_close(&r);
	if (rc == 1)
		rc = 0;
	long kt = (long)(traj.n / JR_TRAJ_COLS);
	long kf = s->obs.flux_on ? (long)(flux.n / obs_flux_len(&s->obs)) : 0;
	long kd = s->obs.field_on ? (long)(field.n / obs_field_len(&s->obs)) : 0;
	if (!rc && (kt != (long)T || ks != (long)K || kf != s->n_flux || kd != s->n_field))
		rc = sb_errf(e, SB_EIO, "%s: journal holds %ld/%ld/%ld/%ld trajectory/snapshot/flux/field records, expected %ld/%ld/%ld/%ld",
			     s->journal_path, kt, ks, kf, kd, s->n_traj, s->n_snap, s->n_flux, s->n_field);
	dset(h, gs, "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, K, 0, times);
	for (int c = 0; c < 3; c++)
		H5Dclose(ds[c]);
	H5Sclose(msp);
	H5Sclose(sp);
	H5Gclose(gs);
	if (s->intruder >= 0) {
		hid_t gi = group(h, "/intruder");
		dset(h, gi, "trajectory", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 2, T, JR_TRAJ_COLS, traj.d);
		attr_str(h, gi, "columns", "t x y vx vy omega");
		attr_long(h, gi, "index", s->intruder);
		H5Gclose(gi);
		if (!rc && T > 0)
			intruder_summary(h, s, traj.d, (long)T);
	}
	if (!rc && s->obs.flux_on)
		write_flux(h, s, &flux);
	if (!rc && s->obs.field_on)
		write_field(h, s, &field);
	if (!rc && s->obs.ring_on)
		write_ring(h, s);
	long ke = (long)(energy.n / JR_ENERGY_COLS);
	if (!rc && ke != s->n_energy)
		rc = sb_errf(e, SB_EIO, "%s: journal holds %ld energy records, expected %ld", s->journal_path, ke, s->n_energy);
	if (!rc && s->sc.energy_rate > 0)
		write_energy(h, &energy, ke);
	long kc = 0;
	for (size_t pos = 0; pos + 2 <= contacts.n; kc++)
		pos += 2 + JR_CONTACT_COLS * (size_t)contacts.d[pos + 1];
	if (!rc && kc != s->n_contact)
		rc = sb_errf(e, SB_EIO, "%s: journal holds %ld contact frames, expected %ld", s->journal_path, kc,
			     s->n_contact);
	if (!rc && s->sc.contact_rate > 0)
		write_contacts(h, &contacts, kc);
	free(traj.d);
	free(flux.d);
	free(field.d);
	free(energy.d);
	free(contacts.d);
	free(times);
	free(buf);
	return rc;
}

static void write_final(h5 *h, const sb_sim *s, double t)
{
	const sb_state *st = &s->st;
	size_t n = (size_t)st->n;
	double *v = malloc(sizeof(double) * n * 6);
	if (!v) {
		h->bad = 1;
		return;
	}
	double idt = 1.0 / s->sc.dt, yb = sim_box_y(s, t), vb = sim_box_v(s, t);
	for (size_t i = 0; i < n; i++) {
		v[i] = st->q[C_X][0][i];
		v[n + i] = st->q[C_Y][0][i] + yb;
		v[2 * n + i] = st->q[C_X][1][i] * idt;
		v[3 * n + i] = st->q[C_Y][1][i] * idt + vb;
		v[4 * n + i] = st->q[C_TH][1][i] * idt;
		v[5 * n + i] = st->q[C_TH][0][i];
	}
	hid_t g = group(h, "/final");
	const char *names[6] = {"x", "y", "vx", "vy", "omega", "theta"};
	for (int c = 0; c < 6; c++)
		dset(h, g, names[c], H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, n, 0, v + c * n);
	attr_double(h, g, "time", t);
	H5Gclose(g);

	int *ki = malloc(sizeof(int) * n);
	if (ki) {
		g = group(h, "/particles");
		dset(h, g, "id", H5T_STD_I32LE, H5T_NATIVE_INT, 1, n, 0, st->id);
		for (size_t i = 0; i < n; i++)
			ki[i] = st->kind[i];
		dset(h, g, "kind", H5T_STD_I32LE, H5T_NATIVE_INT, 1, n, 0, ki);
		dset(h, g, "radius", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, n, 0, st->r);
		dset(h, g, "mass", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 1, n, 0, st->m);
		attr_str(h, g, "kinds", "0 grain, 1 intruder, 2 wall");
		attr_long(h, g, "n_mobile", st->nm);
		H5Gclose(g);
		free(ki);
	} else
		h->bad = 1;
	free(v);
}

/* XDMF sidecar: ParaView reads the snapshots as a temporal collection of point sets. */
static int write_xdmf(const sb_sim *s, const char *h5path, sb_err *e)
{
	char path[4200];
	snprintf(path, sizeof path, "%.*s.xmf",
		 (int)(strlen(h5path) > 3 && !strcmp(h5path + strlen(h5path) - 3, ".h5") ? strlen(h5path) - 3 : strlen(h5path)),
		 h5path);
	const char *base = strrchr(h5path, '/');
	base = base ? base + 1 : h5path;
	sb_file out;
	if (fs_open_tmp(&out, path, e))
		return e->code;
	FILE *f = out.f;
	int nm = s->st.nm;
	fprintf(f, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n<Domain>\n"
		   "<Grid Name=\"snapshots\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
	/* snapshot times are read back from the file so the sidecar matches it exactly */
	hid_t fid = H5Fopen(h5path, H5F_ACC_RDONLY, H5P_DEFAULT);
	double *times = malloc(sizeof(double) * (size_t)(s->n_snap ? s->n_snap : 1));
	if (fid >= 0 && times) {
		hid_t d = H5Dopen2(fid, "/snapshots/time", H5P_DEFAULT);
		if (d >= 0 && s->n_snap)
			H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, times);
		H5Dclose(d);
	}
	if (fid >= 0)
		H5Fclose(fid);
	for (long k = 0; k < s->n_snap && times; k++) {
		fprintf(f, "  <Grid Name=\"t%ld\" GridType=\"Uniform\">\n    <Time Value=\"%.9g\"/>\n", k, times[k]);
		fprintf(f, "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%d\"/>\n", nm);
		fprintf(f, "    <Geometry GeometryType=\"X_Y\">\n");
		for (int c = 0; c < 2; c++)
			fprintf(f,
				"      <DataItem ItemType=\"HyperSlab\" Dimensions=\"1 %d\">\n"
				"        <DataItem Dimensions=\"3 2\" Format=\"XML\">%ld 0 1 1 1 %d</DataItem>\n"
				"        <DataItem Dimensions=\"%ld %d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/snapshots/%s</DataItem>\n"
				"      </DataItem>\n",
				nm, k, nm, s->n_snap, nm, base, c ? "y" : "x");
		fprintf(f, "    </Geometry>\n");
		fprintf(f, "    <Attribute Name=\"radius\" Center=\"Node\">\n"
			   "      <DataItem ItemType=\"HyperSlab\" Dimensions=\"%d\">\n"
			   "        <DataItem Dimensions=\"3 1\" Format=\"XML\">0 1 %d</DataItem>\n"
			   "        <DataItem Dimensions=\"%d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/particles/radius</DataItem>\n"
			   "      </DataItem>\n    </Attribute>\n  </Grid>\n",
			nm, nm, s->st.n, base);
	}
	free(times);
	fprintf(f, "</Grid>\n</Domain>\n</Xdmf>\n");
	return fs_commit(&out, e);
}

int h5out_write(const sb_sim *s, const char *path, sb_err *e)
{
	char tmp[4200];
	fs_tmp_name(path, tmp, sizeof tmp);
	H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* errors are reported through sb_err */
	h5 h = {0};
	hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
	H5Pset_obj_track_times(fcpl, 0);
	h.gcpl = H5Pcreate(H5P_GROUP_CREATE);
	H5Pset_obj_track_times(h.gcpl, 0);
	h.dcpl = H5Pcreate(H5P_DATASET_CREATE);
	H5Pset_obj_track_times(h.dcpl, 0);
	h.file = H5Fcreate(tmp, H5F_ACC_TRUNC, fcpl, H5P_DEFAULT);
	H5Pclose(fcpl);
	if (h.file < 0) {
		H5Pclose(h.gcpl);
		H5Pclose(h.dcpl);
		return sb_errf(e, SB_EIO, "%s: cannot create HDF5 file", tmp);
	}
	const double t = s->step * s->sc.dt;
	attr_str(&h, h.file, "format", "shakebox-run-1");
	write_params(&h, &s->sc);
	attr_str(&h, h.file, "status", sb_code_name(s->status));
	attr_long(&h, h.file, "exit_code", s->status);
	attr_str(&h, h.file, "status_message", s->status_msg);
	attr_double(&h, h.file, "status_time", s->status ? s->status_time : t);
	attr_long(&h, h.file, "status_step", s->status ? s->status_step : s->step);
	attr_long(&h, h.file, "steps", s->step);
	attr_long(&h, h.file, "settle_steps", s->settle_steps);
	attr_double(&h, h.file, "settle_time", s->settle_time);
	attr_double(&h, h.file, "surface_height", s->surface0);
	if (s->intruder >= 0) { /* no NaN placeholders: absent when there is no intruder */
		attr_double(&h, h.file, "intruder_settled_y", s->intruder_y0);
		attr_double(&h, h.file, "intruder_settled_depth", s->surface0 - s->intruder_y0);
		attr_double(&h, h.file, "intruder_radius", s->st.r[s->intruder]);
	}
	attr_long(&h, h.file, "n_mobile", s->st.nm);
	attr_long(&h, h.file, "n_walls", s->st.n - s->st.nm);
	attr_long(&h, h.file, "neighbour_builds", s->nl.builds);
	/* docs/model.md, "Waiting time": the waiting time is the first time the intruder's centre is one
	 * diameter above its settled height. A run that ends first is right-censored:
	 * risen = 0 and waiting_time = the time observed (the survival-analysis pair). */
	/* which stop rule ended the run (docs/model.md, "Stop rules"), and when */
	{
		sb_scene r = s->sc;
		r.stop = s->obs.stop_rule;
		char rule[32];
		params_format(&r, params_find("stop"), rule, sizeof rule);
		attr_str(&h, h.file, "stopped_by", rule);
		if (s->obs.stop_rule)
			attr_double(&h, h.file, "stop_time", s->obs.stop_step * s->sc.dt);
	}
	/* the largest overlap of the shaking, and where (0 when nothing touched) */
	attr_double(&h, h.file, "overlap_max", s->obs.ov_max);
	if (s->obs.ov_max > 0) {
		attr_double(&h, h.file, "overlap_max_time", s->obs.ov_t);
		attr_long(&h, h.file, "overlap_max_disk_a", s->obs.ov_i);
		attr_long(&h, h.file, "overlap_max_disk_b", s->obs.ov_j);
		attr_double(&h, h.file, "overlap_max_x", s->obs.ov_x);
		attr_double(&h, h.file, "overlap_max_y_box", s->obs.ov_y);
	}
	if (s->intruder >= 0) {
		attr_long(&h, h.file, "risen", s->obs.risen);
		attr_double(&h, h.file, "waiting_time", s->obs.risen ? s->obs.wait_time : t);
	}

	hid_t g = group(&h, "/provenance");
	sb_prov p = s->prov;
	prov_now(p.end_time);
	attr_str(&h, g, "git_hash", p.git_hash);
	attr_long(&h, g, "git_dirty", p.git_dirty);
	attr_str(&h, g, "compiler", p.compiler);
	attr_str(&h, g, "cflags", p.cflags);
	attr_str(&h, g, "host", p.host);
	attr_str(&h, g, "start_time", p.start_time);
	attr_str(&h, g, "end_time", p.end_time);
	attr_double(&h, g, "loop_seconds", s->loop_seconds);
	H5Gclose(g);

	int rc = copy_journal(&h, s, e);
	write_final(&h, s, t);
	H5Pclose(h.gcpl);
	H5Pclose(h.dcpl);
	if (H5Fclose(h.file) < 0)
		h.bad = 1;
	if (!rc && h.bad)
		rc = sb_errf(e, SB_EIO, "%s: writing the HDF5 output failed", tmp);
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
