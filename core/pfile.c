/* pfile.c - reading and writing particle files. */
#include "pfile.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fsutil.h"
#include "prepare.h"

typedef struct disk {
	double x, y, r, vx, vy, w;
	int kind;
} disk;

typedef struct dlist {
	disk *d;
	int n, cap;
} dlist;

static int dl_push(dlist *l, disk d, sb_err *e)
{
	if (l->n == l->cap) {
		int nc = l->cap ? 2 * l->cap : 1024;
		disk *p = realloc(l->d, sizeof(disk) * (size_t)nc);
		if (!p)
			return sb_errf(e, SB_ENOMEM, "out of memory reading particles");
		l->d = p;
		l->cap = nc;
	}
	l->d[l->n++] = d;
	return 0;
}

static int blank_or_comment(const char *s)
{
	while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n')
		s++;
	return *s == 0 || *s == '#';
}

static int is_lammps(FILE *f)
{
	char line[1024];
	long n;
	char word[64];
	int found = 0;
	for (int k = 0; k < 50 && fgets(line, sizeof line, f); k++)
		if (sscanf(line, "%ld %63s", &n, word) == 2 && strcmp(word, "atoms") == 0) {
			found = 1;
			break;
		}
	rewind(f);
	return found;
}

static int read_text(FILE *f, const char *path, dlist *l, sb_err *e)
{
	char line[1024];
	int ln = 0;
	while (fgets(line, sizeof line, f)) {
		ln++;
		if (blank_or_comment(line))
			continue;
		char *hash = strchr(line, '#');
		if (hash)
			*hash = 0;
		disk d = {0};
		char kind[32], extra[8];
		int k = sscanf(line, "%lf %lf %lf %31s %lf %lf %lf %7s", &d.x, &d.y, &d.r, kind, &d.vx,
			       &d.vy, &d.w, extra);
		if (k != 4 && k != 7)
			return sb_errf(e, SB_EUSAGE, "%s:%d: expected 'x y r kind [vx vy omega]'", path, ln);
		if (!isfinite(d.x) || !isfinite(d.y) || !isfinite(d.vx) || !isfinite(d.vy) ||
		    !isfinite(d.w) || !(d.r > 0) || !isfinite(d.r))
			return sb_errf(e, SB_EUSAGE, "%s:%d: numbers must be finite and the radius positive",
				       path, ln);
		if (!strcmp(kind, "grain"))
			d.kind = KIND_GRAIN;
		else if (!strcmp(kind, "intruder"))
			d.kind = KIND_INTRUDER;
		else if (!strcmp(kind, "wall"))
			d.kind = KIND_WALL;
		else
			return sb_errf(e, SB_EUSAGE, "%s:%d: kind: expected grain, intruder or wall, got '%s'",
				       path, ln, kind);
		if (dl_push(l, d, e))
			return e->code;
	}
	return 0;
}

/* LAMMPS data file, atom_style sphere: Atoms lines are
 * "id type diameter density x y z [ix iy iz]", Velocities "id vx vy vz wx wy wz".
 * The density column is ignored: masses follow the scene's mass model. */
static int read_lammps(FILE *f, const char *path, dlist *l, sb_err *e)
{
	char line[1024];
	int ln = 0;
	long natoms = -1;
	enum { HEAD, ATOMS, VELS, OTHER } sec = HEAD;
	long *ids = NULL;
	int idcap = 0;
	int err = 0;
	while (!err && fgets(line, sizeof line, f)) {
		ln++;
		if (ln == 1)
			continue; /* the first line of a data file is a free comment */
		char *hash = strchr(line, '#');
		char tag[64] = "";
		if (sscanf(line, "%63s", tag) != 1)
			continue;
		if (hash)
			*hash = 0;
		if (!strcmp(tag, "Atoms")) {
			sec = ATOMS;
			continue;
		}
		if (!strcmp(tag, "Velocities")) {
			sec = VELS;
			continue;
		}
		if (isalpha((unsigned char)tag[0])) {
			sec = OTHER;
			continue;
		}
		if (blank_or_comment(line))
			continue;
		if (sec == HEAD) {
			long n;
			char w[64];
			if (sscanf(line, "%ld %63s", &n, w) == 2 && !strcmp(w, "atoms"))
				natoms = n;
		} else if (sec == ATOMS) {
			long id;
			int type;
			double dia, rho, z;
			disk d = {0};
			if (sscanf(line, "%ld %d %lf %lf %lf %lf %lf", &id, &type, &dia, &rho, &d.x, &d.y, &z) != 7)
				err = sb_errf(e, SB_EUSAGE, "%s:%d: expected 'id type diameter density x y z' (atom_style sphere)",
					      path, ln);
			else if (type < 1 || type > 3)
				err = sb_errf(e, SB_EUSAGE, "%s:%d: atom type %d: expected 1 (grain), 2 (intruder) or 3 (wall)",
					      path, ln, type);
			else if (!(dia > 0) || !isfinite(dia) || !isfinite(d.x) || !isfinite(d.y))
				err = sb_errf(e, SB_EUSAGE, "%s:%d: numbers must be finite and the diameter positive", path, ln);
			else {
				d.r = 0.5 * dia;
				d.kind = type == 1 ? KIND_GRAIN : type == 2 ? KIND_INTRUDER : KIND_WALL;
				if (l->n == idcap) {
					idcap = idcap ? 2 * idcap : 1024;
					long *p = realloc(ids, sizeof(long) * (size_t)idcap);
					if (!p) {
						err = sb_errf(e, SB_ENOMEM, "out of memory reading particles");
						break;
					}
					ids = p;
				}
				ids[l->n] = id;
				err = dl_push(l, d, e);
			}
		} else if (sec == VELS) {
			long id;
			double vx, vy, vz, wx, wy, wz;
			if (sscanf(line, "%ld %lf %lf %lf %lf %lf %lf", &id, &vx, &vy, &vz, &wx, &wy, &wz) != 7) {
				err = sb_errf(e, SB_EUSAGE, "%s:%d: expected 'id vx vy vz wx wy wz'", path, ln);
				break;
			}
			int k;
			for (k = 0; k < l->n && ids[k] != id; k++)
				;
			if (k == l->n) {
				err = sb_errf(e, SB_EUSAGE, "%s:%d: velocity for unknown atom id %ld", path, ln, id);
				break;
			}
			l->d[k].vx = vx;
			l->d[k].vy = vy;
			l->d[k].w = wz;
		}
	}
	free(ids);
	if (!err && natoms >= 0 && natoms != l->n)
		err = sb_errf(e, SB_EUSAGE, "%s: header says %ld atoms, the Atoms section has %d", path, natoms, l->n);
	if (!err && natoms < 0)
		err = sb_errf(e, SB_EUSAGE, "%s: no 'N atoms' line in the header", path);
	return err;
}

int pfile_read(const sb_scene *sc, const char *path, sb_state *st, sb_err *e)
{
	FILE *f = fopen(path, "r");
	if (!f)
		return sb_errf(e, SB_EUSAGE, "%s: cannot open particle file: %s", path, strerror(errno));
	dlist l = {0};
	int err = is_lammps(f) ? read_lammps(f, path, &l, e) : read_text(f, path, &l, e);
	fclose(f);
	if (!err && l.n == 0)
		err = sb_errf(e, SB_EUSAGE, "%s: no particles", path);
	/* mobile disks first, in file order, then the walls */
	for (int pass = 0; pass < 2 && !err; pass++)
		for (int i = 0; i < l.n && !err; i++) {
			const disk *d = &l.d[i];
			if ((d->kind == KIND_WALL) != pass)
				continue;
			err = prepare_push(sc, st, d->x, d->y, d->r, d->kind, e);
			if (!err && d->kind != KIND_WALL) {
				int k = st->n - 1;
				st->q[C_X][1][k] = d->vx * sc->dt;
				st->q[C_Y][1][k] = d->vy * sc->dt;
				st->q[C_TH][1][k] = d->w * sc->dt;
			}
		}
	free(l.d);
	return err;
}

static const char *kind_name(int k)
{
	return k == KIND_GRAIN ? "grain" : k == KIND_INTRUDER ? "intruder" : "wall";
}

/* Lab frame: y + yshift; mobile velocities are taken as lab-frame already (the file
 * is written while the box is at rest), walls move with the box at vshift. Numbers use %.17g so that the file round-trips exactly. */
static void lab_velocity(const sb_state *st, int i, double inv_dt, double vshift, double *vx,
			 double *vy, double *w)
{
	if (st->kind[i] == KIND_WALL) {
		*vx = *w = 0;
		*vy = vshift;
		return;
	}
	*vx = st->q[C_X][1][i] * inv_dt;
	*vy = st->q[C_Y][1][i] * inv_dt;
	*w = st->q[C_TH][1][i] * inv_dt;
}

int pfile_write_text(const sb_state *st, const char *path, double inv_dt, double yshift,
		     double vshift, sb_err *e)
{
	sb_file out;
	if (fs_open_tmp(&out, path, e))
		return e->code;
	FILE *f = out.f;
	fprintf(f, "# shakebox particle file: x y r kind vx vy omega (cgs, lab frame)\n");
	fprintf(f, "# %d disks, %d mobile\n", st->n, st->nm);
	for (int i = 0; i < st->n; i++) {
		double vx, vy, w;
		lab_velocity(st, i, inv_dt, vshift, &vx, &vy, &w);
		fprintf(f, "%.17g %.17g %.17g %s %.17g %.17g %.17g\n", st->q[C_X][0][i],
			st->q[C_Y][0][i] + yshift, st->r[i], kind_name(st->kind[i]), vx, vy, w);
	}
	return fs_commit(&out, e);
}

int pfile_write_lammps(const sb_state *st, const char *path, double inv_dt, double yshift,
		       double vshift, sb_err *e)
{
	double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
	for (int i = 0; i < st->n; i++) {
		double y = st->q[C_Y][0][i] + yshift;
		xlo = fmin(xlo, st->q[C_X][0][i] - st->r[i]);
		xhi = fmax(xhi, st->q[C_X][0][i] + st->r[i]);
		ylo = fmin(ylo, y - st->r[i]);
		yhi = fmax(yhi, y + st->r[i]);
	}
	/* room above for grains thrown up and below for the box's swing */
	double h = yhi - ylo;
	yhi += h;
	ylo -= 0.25 * h;
	sb_file out;
	if (fs_open_tmp(&out, path, e))
		return e->code;
	FILE *f = out.f;
	fprintf(f, "# shakebox state (cgs, lab frame); types 1 grain, 2 intruder, 3 wall; "
		   "density column = 3 m / (4 pi R^3) so that LAMMPS gets m\n\n");
	fprintf(f, "%d atoms\n3 atom types\n\n", st->n);
	fprintf(f, "%.17g %.17g xlo xhi\n%.17g %.17g ylo yhi\n-0.5 0.5 zlo zhi\n\n", xlo, xhi, ylo, yhi);
	fprintf(f, "Atoms # sphere\n\n");
	for (int i = 0; i < st->n; i++) {
		double r = st->r[i];
		/* LAMMPS read_data computes 4/3 pi r^3 density even in 2D */
		double rho = 3.0 * st->m[i] / (4.0 * 3.14159265358979323846 * r * r * r);
		fprintf(f, "%d %d %.17g %.17g %.17g %.17g 0\n", i + 1, st->kind[i] + 1, 2 * r, rho,
			st->q[C_X][0][i], st->q[C_Y][0][i] + yshift);
	}
	fprintf(f, "\nVelocities\n\n");
	for (int i = 0; i < st->n; i++) {
		double vx, vy, w;
		lab_velocity(st, i, inv_dt, vshift, &vx, &vy, &w);
		fprintf(f, "%d %.17g %.17g 0 0 0 %.17g\n", i + 1, vx, vy, w);
	}
	return fs_commit(&out, e);
}
