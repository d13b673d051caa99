/* forces.c - the contact law (docs/model.md, "Contact law") in plain C: the reference
 * every path of the vector kernel (kvec.c) gives to the bit, and the scans over the
 * list that need no speed. Conventions: n = (r_i - r_j)/d,
 * t = n rotated by +90 deg, overlap xi = R_i + R_j - d.
 *   F_N = Y xi + gamma_N m_eff xidot,  xidot = -(v_i - v_j).n          (eq. 2, signed)
 *   v_t = (v_i - v_j).t - (R_i w_i + R_j w_j)   (surface slip of i against j at the
 *         contact point: the contact point is r_i - R_i n, and z x n = t)
 *   F_S = -sign(v_t) min(gamma_S m_eff |v_t|, mu |F_N|)                  (eq. 3)
 *   force on i: F_N n + F_S t, on j the opposite;
 *   torque on i: (-R_i n) x (F_S t) = -R_i F_S, on j: (R_j n) x (-F_S t) = -R_j F_S.
 * Both torques have the sign that reduces the slip; eq. (6) of the paper prints
 * +/- because its orientation convention differs (tests/physics prove this one).
 * tangential = spring replaces eq. 3 (docs/model.md, "Tangential law"):
 *   xi_t += v_t dt,  F_S = -(k_t xi_t + gamma_S m_eff v_t),
 *   |F_S| > mu |F_N|: xi_t rescaled so that |F_S| = mu |F_N| (LAMMPS gran/hooke/history). */
#include "forces.h"

#include <assert.h>
#include <math.h>
#include <string.h>

#include "dtguard.h"
#include "paircoef.h"
#include "periodic.h"

double forces_gz(double Y, double e)
{
	return 2 * dtguard_zeta(e) * sqrt(Y);
}

/* F_N of contact() below (xidot = -(v_i - v_j).n); *ph gets hertz's sqrt(xi R_eff), else 1 */
static inline __attribute__((always_inline)) double normal_force(const double Y, const double gn, const int resti,
								 const int hertz, const int clip, const double xi,
								 const double xidot, const double ri, const double rj,
								 const double meff, double *ph)
{
	const double c = resti ? gn * sqrt(meff) : gn * meff;
	*ph = hertz ? sqrt(xi * (ri * rj / (ri + rj))) : 1;
	double fn = Y * xi + c * xidot;
	if (hertz)
		fn = *ph * fn;
	if (clip)
		fn = fn > 0 ? fn : 0;
	return fn;
}

/* gn: gamma_N, or with resti gz (forces.h); the damping gn m_eff or gz sqrt(m_eff);
 * hertz: the normal force and the shear damping times sqrt(xi R_eff) */
static inline __attribute__((always_inline)) void contact(
	const double Y, const double gn, const int resti, const int hertz, const double gs, const double mu, const int clip,
	const double dx, const double dy, const double d, const double inv, const double ri,
	const double rj, const double dvx, const double dvy, const double wi, const double wj,
	const double meff, double *fx, double *fy, double *fs_out, double *xi_out, int *capped)
{
	const double nx = dx * inv, ny = dy * inv;
	const double xi = ri + rj - d;
	double ph;
	const double fn = normal_force(Y, gn, resti, hertz, clip, xi, -(dvx * nx + dvy * ny), ri, rj, meff, &ph);
	const double vt = -dvx * ny + dvy * nx - (ri * wi + rj * wj);
	double fv = gs * meff * fabs(vt);
	if (hertz)
		fv = ph * fv;
	const double fc = mu * fabs(fn);
	const double fs = copysign(fv < fc ? fv : fc, -vt);
	*capped = !(fv < fc);
	*fx = fn * nx - fs * ny;
	*fy = fn * ny + fs * nx;
	*fs_out = fs;
	*xi_out = xi;
}

/* tangential = spring (forces.h, forces_pair_spring): contact()'s normal force, then
 * the shear spring in LAMMPS gran/hooke/history's order of operations (its 3-vector
 * shear is the scalar h along t here); gn, gs carry inv_dt */
static inline void contact_spring(const sb_law *law, const sb_kc *c, const double gn, const double gs, const double dx,
				  const double dy, const double d, const double ri, const double rj, const double dvx,
				  const double dvy, const double wi, const double wj, const double meff, double *h,
				  const int update, double *fx, double *fy, double *fs_out, double *xi_out, int *capped)
{
	const double inv = 1.0 / d, nx = dx * inv, ny = dy * inv;
	const double xi = ri + rj - d;
	double ph;
	const double fn = normal_force(c->Y, gn, law->resti, law->hertz, law->clip, xi, -(dvx * nx + dvy * ny), ri, rj,
				       meff, &ph);
	const double vt = -dvx * ny + dvy * nx - (ri * wi + rj * wj);
	const double s = update ? *h + vt : *h; /* v_t dt: the velocities are scaled */
	const double damp = gs * meff * vt;
	double fs = -(c->kt * s + damp);
	if (law->hertz)
		fs = ph * fs;
	const double fc = c->mu * fabs(fn), fa = fabs(fs);
	double snew = s;
	*capped = fa > fc;
	if (fa > fc) { /* sliding: the spring stretched only as far as Coulomb allows */
		if (s != 0) {
			const double q = damp / c->kt, r = fc / fa;
			snew = r * (s + q) - q;
			fs *= r;
		} else {
			fs = 0;
		}
	}
	if (update)
		*h = snew;
	*fx = fn * nx - fs * ny;
	*fy = fn * ny + fs * nx;
	*fs_out = fs;
	*xi_out = xi;
}

int forces_pairclass(int ki, int kj)
{
	const int lo = ki < kj ? ki : kj, hi = ki < kj ? kj : ki;
	if (hi == KIND_WALL)
		return lo == KIND_GRAIN ? PC_GRAIN_WALL : lo == KIND_INTRUDER ? PC_INTRUDER_WALL : -1;
	if (hi == KIND_INTRUDER)
		return lo == KIND_GRAIN ? PC_GRAIN_INTRUDER : PC_INTRUDER_INTRUDER;
	return -1;
}

static void pair_spring(const sb_law *law, const sb_kc *c, double dx, double dy, double ri, double rj, double dvx,
			double dvy, double wi, double wj, double meff, double inv_dt, double *h, int update, double *fx,
			double *fy, double *ti, double *tj)
{
	const double d2 = dx * dx + dy * dy, rs = ri + rj;
	if (!(d2 < rs * rs)) {
		*fx = *fy = *ti = *tj = 0;
		return;
	}
	double fs, xi;
	int capped;
	contact_spring(law, c, c->gn * inv_dt, c->gs * inv_dt, dx, dy, sqrt(d2), ri, rj, dvx, dvy, wi, wj, meff, h,
		       update, fx, fy, &fs, &xi, &capped);
	*ti = -ri * fs;
	*tj = -rj * fs;
}

void forces_pair_spring(const sb_law *law, double dx, double dy, double ri, double rj, double dvx, double dvy,
			double wi, double wj, double meff, double inv_dt, double *h, int update, double *fx, double *fy,
			double *ti, double *tj)
{
	const sb_kc c = forces_kc(law, KIND_GRAIN, KIND_GRAIN);
	pair_spring(law, &c, dx, dy, ri, rj, dvx, dvy, wi, wj, meff, inv_dt, h, update, fx, fy, ti, tj);
}

static void pair_viscous(const sb_law *law, const sb_kc *c, double dx, double dy, double ri, double rj, double dvx,
			 double dvy, double wi, double wj, double meff, double *fx, double *fy, double *ti, double *tj)
{
	double d2 = dx * dx + dy * dy, rs = ri + rj;
	if (d2 >= rs * rs) {
		*fx = *fy = *ti = *tj = 0;
		return;
	}
	double fs, xi, d = sqrt(d2);
	int capped;
	contact(c->Y, c->gn, law->resti, law->hertz, c->gs, c->mu, law->clip, dx, dy, d, 1.0 / d, ri, rj, dvx, dvy, wi,
		wj, meff, fx, fy, &fs, &xi, &capped);
	*ti = -ri * fs;
	*tj = -rj * fs;
}

void forces_pair(const sb_law *law, double dx, double dy, double ri, double rj,
		 double dvx, double dvy, double wi, double wj, double meff,
		 double *fx, double *fy, double *ti, double *tj)
{
	const sb_kc c = forces_kc(law, KIND_GRAIN, KIND_GRAIN);
	pair_viscous(law, &c, dx, dy, ri, rj, dvx, dvy, wi, wj, meff, fx, fy, ti, tj);
}

/* A contact's force on i and -force on j, its torques, into io (and |F| into fsum when
 * not NULL), in the order the kernel adds them; returns whether its overlap exceeds mo
 * of the smaller radius. */
static inline int add_contact(const sb_seam_io *io, double *fsum, int i, int j, double ri, double rj, double fx,
			      double fy, double f_s, double xi, double mo)
{
	const int fs = io->fs;
	if (fsum) {
		const double fa = sqrt(fx * fx + fy * fy);
		fsum[i] += fa;
		fsum[j] += fa;
	}
	io->fx[i * fs] += fx;
	io->fy[i * fs] += fy;
	io->t[i * fs] -= ri * f_s;
	io->fx[j * fs] -= fx;
	io->fy[j * fs] -= fy;
	io->t[j * fs] -= rj * f_s;
	return xi > mo * (ri < rj ? ri : rj);
}

/* One pair of the list, disk i's centre (or image) dx from j's in x: nothing when it does
 * not touch (its shear displacement *h, when the spring's, reset: its history ends, docs/model.md
 * "Tangential law"), else its class's law added into io. Returns add_contact's flag. */
static inline int one_pair(const sb_law *law, const sb_state *st, const sb_seam_io *io, double inv_dt, int i, int j,
			   double dx, double *h, double *fsum)
{
	const double *r = st->r, *w = st->q[C_TH][1], *im = st->inv_m;
	const int ps = io->ps;
	const double dy = io->y[i * ps] - io->y[j * ps], rs = r[i] + r[j], d2 = dx * dx + dy * dy;
	if (!(d2 < rs * rs)) {
		if (h)
			*h = 0;
		return 0;
	}
	const double d = sqrt(d2), ri = r[i], rj = r[j];
	double fx, fy, f_s, xi;
	int capped;
	/* the pair's coefficients (a table of materials') */
	const sb_kc c = forces_kc(law, st->kind[i], st->kind[j]);
	const double gn = c.gn * inv_dt, gs = c.gs * inv_dt;
	if (h)
		contact_spring(law, &c, gn, gs, dx, dy, d, ri, rj, io->vx[i * ps] - io->vx[j * ps],
			       io->vy[i * ps] - io->vy[j * ps], w[i], w[j], 1.0 / (im[i] + im[j]), h, 1, &fx, &fy, &f_s,
			       &xi, &capped);
	else
		contact(c.Y, gn, law->resti, law->hertz, gs, c.mu, law->clip, dx, dy, d, 1.0 / d, ri, rj,
			io->vx[i * ps] - io->vx[j * ps], io->vy[i * ps] - io->vy[j * ps], w[i], w[j], 1.0 / (im[i] + im[j]),
			&fx, &fy, &f_s, &xi, &capped);
	return add_contact(io, fsum, i, j, ri, rj, fx, fy, f_s, xi, law->max_overlap);
}

int forces_seam(const sb_law *law, const sb_state *st, const sb_nlist *nl, const sb_seam_io *io, double inv_dt,
		double *hs, double *fsum)
{
	const int ps = io->ps;
	int bad = 0;
	for (int k = 0; k < nl->nseam; k++) {
		const int i = nl->si[k], j = nl->sj[k];
		bad |= one_pair(law, st, io, inv_dt, i, j, (io->x[i * ps] + nl->period) - io->x[j * ps], hs ? &hs[k] : NULL,
				fsum);
	}
	return bad;
}

/* Pair p of the flat list (p < nflat) or seam pair p - nflat: its disks and the
 * x distance of i's centre (or image) from j's; 0 for the flat list's padding. */
static inline int pair_at_x(const double *x, int ps, const sb_nlist *nl, int p, int *i, int *j, double *dx)
{
	if (p < nl->nflat) {
		*i = nl->pi[p] >> nl->pshift;
		*j = nl->pj[p] >> nl->pshift;
		*dx = x[*i * ps] - x[*j * ps];
		return *i != *j;
	}
	*i = nl->si[p - nl->nflat];
	*j = nl->sj[p - nl->nflat];
	*dx = (x[*i * ps] + nl->period) - x[*j * ps];
	return 1;
}

static inline int pair_at(const sb_state *st, const sb_nlist *nl, int p, int *i, int *j, double *dx)
{
	return pair_at_x(st->q[C_X][0], 1, nl, p, i, j, dx);
}

int forces_scalar(const sb_law *law, const sb_state *st, const sb_nlist *nl, sb_shear *sh, const sb_seam_io *io,
		  double inv_dt, double *fsum)
{
	const int ps = io->ps, sh_of = nl->pshift;
	double *const hs = law->spring ? sh->xi : NULL;
	int bad = 0;
	for (int p = 0; p < nl->nflat; p++) {
		const int i = nl->pi[p] >> sh_of, j = nl->pj[p] >> sh_of;
		bad |= one_pair(law, st, io, inv_dt, i, j, io->x[i * ps] - io->x[j * ps], hs ? &hs[p] : NULL, fsum);
	}
	return bad | forces_seam(law, st, nl, io, inv_dt, hs ? hs + nl->nflat : NULL, fsum);
}

/* The scans below take a contact's distance as sqrt(dx^2 + dy^2), as the kernel does:
 * sqrt is correctly rounded on every machine, glibc's hypot is not (its x86-64 and
 * aarch64 code differ in the last bit for about 13 % of contact distances:
 * docs/cross.md). */
void forces_contact_energy(const sb_law *law, const sb_state *st, const sb_nlist *nl, const sb_shear *sh,
			   double *elastic, double *max_overlap, long *contacts)
{
	const double *hs = law->spring && sh && shear_current(sh, nl) ? sh->xi : NULL;
	const double *y = st->q[C_Y][0], *r = st->r;
	double el = 0, worst = 0;
	long n = 0;
	for (int p = 0; p < nl->nflat + nl->nseam; p++) {
		int i, j;
		double dx;
		if (!pair_at(st, nl, p, &i, &j, &dx)) /* the list's padding */
			continue;
		const double dy = y[i] - y[j], xi = r[i] + r[j] - sqrt(dx * dx + dy * dy);
		if (xi <= 0)
			continue;
		/* the work of the normal spring: Y xi^2 / 2, Hertz's 2/5 Y sqrt(R_eff) xi^5/2 */
		const sb_kc c = forces_kc(law, st->kind[i], st->kind[j]);
		const double ph = law->hertz ? sqrt(xi * (r[i] * r[j] / (r[i] + r[j]))) : 1;
		el += law->hertz ? 0.4 * c.Y * xi * xi * ph : 0.5 * c.Y * xi * xi;
		/* the shear spring's, k_t xi_t^2 / 2 (hertz: its stiffness k_t sqrt(xi R_eff)) */
		if (hs)
			el += 0.5 * ph * c.kt * hs[p] * hs[p];
		worst = fmax(worst, xi / fmin(r[i], r[j]));
		n++;
	}
	*elastic = el;
	*max_overlap = worst;
	*contacts = n;
}

long forces_contacts(const sb_law *law, const sb_state *st, const sb_nlist *nl, const sb_shear *sh, double inv_dt,
		     double *out, long cap)
{
	const int hs = law->spring && sh && shear_current(sh, nl);
	const double *x = st->q[C_X][0], *y = st->q[C_Y][0], *r = st->r;
	long n = 0;
	for (int p = 0; p < nl->nflat + nl->nseam; p++) {
		int i, j;
		double dx;
		const int real = pair_at(st, nl, p, &i, &j, &dx);
		const double dy = y[i] - y[j], d = sqrt(dx * dx + dy * dy);
		if (!real || !(d < r[i] + r[j]))
			continue;
		double fx, fy, ti, tj;
		const sb_kc c = forces_kc(law, st->kind[i], st->kind[j]);
		if (law->spring) { /* the shear displacement as it is, not advanced */
			double h = hs ? sh->xi[p] : 0;
			pair_spring(law, &c, dx, dy, r[i], r[j], st->q[C_X][1][i] - st->q[C_X][1][j],
				    st->q[C_Y][1][i] - st->q[C_Y][1][j], st->q[C_TH][1][i], st->q[C_TH][1][j],
				    1.0 / (st->inv_m[i] + st->inv_m[j]), inv_dt, &h, 0, &fx, &fy, &ti, &tj);
		} else {
			pair_viscous(law, &c, dx, dy, r[i], r[j], (st->q[C_X][1][i] - st->q[C_X][1][j]) * inv_dt,
				     (st->q[C_Y][1][i] - st->q[C_Y][1][j]) * inv_dt, st->q[C_TH][1][i] * inv_dt,
				     st->q[C_TH][1][j] * inv_dt, 1.0 / (st->inv_m[i] + st->inv_m[j]), &fx, &fy, &ti, &tj);
		}
		const double nx = dx / d, ny = dy / d;
		if (n < cap) {
			double *c = out + 8 * n;
			c[0] = i;
			c[1] = j;
			c[2] = fx * nx + fy * ny;  /* F_N */
			c[3] = -fx * ny + fy * nx; /* F_S, along t = (-n_y, n_x) */
			c[4] = nx;
			c[5] = ny;
			c[6] = p < nl->nflat ? 0.5 * (x[i] + x[j]) : periodic_wrap(x[j] + 0.5 * dx, nl->period);
			c[7] = 0.5 * (y[i] + y[j]);
		}
		n++;
	}
	return n;
}

long forces_sliding(const sb_law *law, const sb_state *st, const sb_nlist *nl, const sb_shear *sh, double inv_dt,
		    long *contacts)
{
	const double *y = st->q[C_Y][0], *r = st->r, *vx = st->q[C_X][1], *vy = st->q[C_Y][1], *w = st->q[C_TH][1];
	const int hs = law->spring && sh && shear_current(sh, nl);
	long n = 0, slid = 0;
	for (int p = 0; p < nl->nflat + nl->nseam; p++) {
		int i, j;
		double dx;
		const int real = pair_at(st, nl, p, &i, &j, &dx);
		const double dy = y[i] - y[j], d2 = dx * dx + dy * dy, rs = r[i] + r[j];
		if (!real || !(d2 < rs * rs))
			continue;
		const double d = sqrt(d2), meff = 1.0 / (st->inv_m[i] + st->inv_m[j]);
		double fx, fy, fs, xi, h = hs ? sh->xi[p] : 0;
		int capped;
		const sb_kc c = forces_kc(law, st->kind[i], st->kind[j]);
		const double gn = c.gn * inv_dt, gs = c.gs * inv_dt;
		if (law->spring) /* a step's evaluation, on a copy of the displacement */
			contact_spring(law, &c, gn, gs, dx, dy, d, r[i], r[j], vx[i] - vx[j], vy[i] - vy[j], w[i], w[j], meff,
				       &h, 1, &fx, &fy, &fs, &xi, &capped);
		else
			contact(c.Y, gn, law->resti, law->hertz, gs, c.mu, law->clip, dx, dy, d, 1.0 / d, r[i], r[j],
				vx[i] - vx[j], vy[i] - vy[j], w[i], w[j], meff, &fx, &fy, &fs, &xi, &capped);
		slid += capped;
		n++;
	}
	*contacts = n;
	return slid;
}

double forces_max_overlap(const sb_state *st, const sb_nlist *nl, int *wi, int *wj)
{
	double worst = 0;
	const double *y = st->q[C_Y][0], *r = st->r;
	for (int p = 0; p < nl->nflat + nl->nseam; p++) {
		int i, j;
		double dx;
		pair_at(st, nl, p, &i, &j, &dx);
		const double dy = y[i] - y[j], f = (r[i] + r[j] - sqrt(dx * dx + dy * dy)) / fmin(r[i], r[j]);
		if (f > worst) {
			worst = f;
			*wi = i;
			*wj = j;
		}
	}
	return worst;
}
