/* pfile.c - reading and writing particle files. */
#include "pfile.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fsutil.h"
#include "guard.h"
#include "num.h"
#include "periodic.h"
#include "place.h"
#include "textline.h"
#include "units.h"

/* What a particle file may hold. A line is at most PF_LINE_MAX characters (the
 * engine writes about 170); a longer one is refused rather than read in pieces, whose
 * tail would be read as a disk of its own. A file is a regular file of at most
 * PF_MAX_BYTES (the largest scene the engine makes, 2 10^7 disks, writes about 4 GB):
 * a FIFO or a device would be read without end. Radii are cm-sized: one beyond
 * [PF_R_MIN, PF_R_MAX] is a slip of units (m or um for cm) or a corrupt number; the
 * run would end in a non-finite position (a mass that underflows, a disk that dwarfs
 * the box) instead of naming the line. */
#define PF_LINE_MAX 1023
#define PF_MAX_BYTES (8LL << 30)
#define PF_R_MIN 1e-4
#define PF_R_MAX 1e4

/* What a file says of a disk's mass (docs/inputs.md, "Particle masses"): nothing, a text
 * line's m column, or a LAMMPS Atoms line's density column. */
enum { MCOL_NONE, MCOL_TEXT, MCOL_LAMMPS };

typedef struct disk {
	double x, y, r, vx, vy, w;
	double m, col;    /* the mass the file gives (g) and the column it comes from, if mcol */
	int mcol;
	long line, vline; /* lines of the disk and of its velocity (LAMMPS), 0 if none */
	long id;          /* LAMMPS atom id */
	int kind;
} disk;

typedef struct dlist {
	disk *d;
	int n, cap, max;
} dlist;

/* Lines of a particle file, read byte by byte: fgets cannot tell a NUL byte from the
 * end of the line (the rest of the line would vanish). A byte-order mark and the CR of
 * a CRLF are dropped as textline.c drops them for scene and campaign files. */
typedef struct lreader {
	FILE *f;
	const char *path;
	long line;
	char buf[PF_LINE_MAX + 1];
} lreader;

/* The next line into r->buf, without its newline: 1, or 0 at the end of the file, or
 * -1 with the error in e (a NUL byte, a line too long, a read error, SIGINT/SIGTERM). */
static int lr_next(lreader *r, sb_err *e)
{
	int ch;
	long len = 0, nul = 0; /* nul: column of the first NUL byte, 1-based */
	while ((ch = getc_unlocked(r->f)) != EOF && ch != '\n') {
		if (ch == '\r') {
			/* CRLF: the line ends at the LF and is measured without the CR
			 * (docs/inputs.md, "Lines") */
			const int nx = getc_unlocked(r->f);
			if (nx == '\n') {
				ch = nx;
				break;
			}
			if (nx != EOF)
				ungetc(nx, r->f);
		}
		if (len == PF_LINE_MAX) {
			sb_errf(e, SB_EUSAGE, "%s:%ld: line too long (the limit is %d characters)", r->path, r->line + 1,
				PF_LINE_MAX);
			return -1;
		}
		if (!ch && !nul)
			nul = len + 1;
		r->buf[len++] = (char)ch;
		if (!r->line && len == TEXTLINE_BOM_LEN && !memcmp(r->buf, TEXTLINE_BOM, TEXTLINE_BOM_LEN))
			len = 0; /* a byte-order mark opens the file: no part of its first line */
	}
	if (ch == EOF && ferror(r->f)) {
		sb_errf(e, SB_EIO, "%s: cannot read particle file: %s", r->path, strerror(errno));
		return -1;
	}
	if (ch == EOF && !len)
		return 0;
	r->buf[len] = 0;
	r->line++;
	if (nul) {
		sb_errf(e, SB_EUSAGE, "%s:%ld: NUL byte in column %ld (a particle file is text)", r->path, r->line, nul);
		return -1;
	}
	if (r->line % 65536 == 0 && guard_stopped()) {
		sb_errf(e, SB_EINTR, "%s: interrupted while reading", r->path);
		return -1;
	}
	return 1;
}

static void lr_rewind(lreader *r)
{
	rewind(r->f);
	r->line = 0;
}

static int dl_push(dlist *l, disk d, const char *path, sb_err *e)
{
	if (l->n == l->max)
		return sb_errf(e, SB_EUSAGE, "%s:%ld: more than %d disks (10^7 grains, an intruder and the walls of a box)",
			       path, d.line, l->max);
	if (l->n == l->cap) {
		int nc = l->cap ? (l->cap > l->max / 2 ? l->max : 2 * l->cap) : 1024;
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

static int check_radius(const char *path, long line, double r, sb_err *e)
{
	if (r >= PF_R_MIN && r <= PF_R_MAX)
		return 0;
	return sb_errf(e, SB_EUSAGE, "%s:%ld: radius %g cm: expected a number in [%g, %g] cm", path, line, r, PF_R_MIN,
		       PF_R_MAX);
}

static int is_lammps(lreader *r, int *found, sb_err *e)
{
	long n;
	char word[64];
	*found = 0;
	while (r->line < 50 && lr_next(r, e) > 0)
		if (sscanf(r->buf, "%ld %63s", &n, word) == 2 && strcmp(word, "atoms") == 0) {
			*found = 1;
			break;
		}
	if (e->code)
		return e->code;
	lr_rewind(r);
	return 0;
}

/* The blank-separated fields of a line: at most max are kept in f; the count is
 * returned (more than max when there are more). */
typedef struct field {
	const char *s;
	size_t n;
} field;

static int split(const char *line, field *f, int max)
{
	int k = 0;
	for (const char *p = line;;) {
		p += strspn(p, " \t\r\f\v");
		if (!*p)
			return k;
		const size_t n = strcspn(p, " \t\r\f\v");
		if (k < max)
			f[k] = (field){p, n};
		k++;
		p += n;
	}
}

/* Field i of a line as a number: the strict reading of every input (num.h), so that
 * "1.5" is no atom type and "0x10" no coordinate; the error names the line, the
 * column's name and the text. */
static int field_real(const lreader *r, const field *f, const char *name, double *x, sb_err *e)
{
	if (!num_real_n(f->s, f->n, x))
		return 0;
	return sb_errf(e, SB_EUSAGE, "%s:%ld: %s: expected a finite decimal number, got '%.*s'", r->path, r->line, name,
		       (int)(f->n > 64 ? 64 : f->n), f->s);
}

static int field_int(const lreader *r, const field *f, const char *name, long long *x, sb_err *e)
{
	if (!num_int_n(f->s, f->n, x))
		return 0;
	return sb_errf(e, SB_EUSAGE, "%s:%ld: %s: expected an integer, got '%.*s'", r->path, r->line, name,
		       (int)(f->n > 64 ? 64 : f->n), f->s);
}

/* Text lines "x y r kind [vx vy omega [m]]": four, seven or eight fields, every one read
 * (a fifth word is no velocity: the line would start at rest unasked). */
static int read_text(lreader *r, dlist *l, sb_err *e)
{
	static const char *const NAME[8] = {"x", "y", "r", "kind", "vx", "vy", "omega", "m"};
	const char *path = r->path;
	int k;
	while ((k = lr_next(r, e)) > 0) {
		char *line = r->buf;
		if (blank_or_comment(line))
			continue;
		char *hash = strchr(line, '#');
		if (hash)
			*hash = 0;
		disk d = {.line = r->line};
		field f[8];
		const int nf = split(line, f, 8);
		if (nf != 4 && nf != 7 && nf != 8)
			return sb_errf(e, SB_EUSAGE, "%s:%ld: expected 'x y r kind [vx vy omega [m]]', got %d fields", path,
				       r->line, nf);
		double *v[8] = {&d.x, &d.y, &d.r, NULL, &d.vx, &d.vy, &d.w, &d.col};
		d.mcol = nf == 8 ? MCOL_TEXT : MCOL_NONE;
		for (int i = 0; i < nf; i++)
			if (v[i] && field_real(r, &f[i], NAME[i], v[i], e))
				return e->code;
		if (check_radius(path, r->line, d.r, e))
			return e->code;
		d.m = d.col;
		const char *kind = f[3].s;
		const size_t kl = f[3].n;
		if (kl == 5 && !strncmp(kind, "grain", 5))
			d.kind = KIND_GRAIN;
		else if (kl == 8 && !strncmp(kind, "intruder", 8))
			d.kind = KIND_INTRUDER;
		else if (kl == 4 && !strncmp(kind, "wall", 4))
			d.kind = KIND_WALL;
		else
			return sb_errf(e, SB_EUSAGE, "%s:%ld: kind: expected grain, intruder or wall, got '%.*s'", path,
				       r->line, (int)(kl > 64 ? 64 : kl), kind);
		if (dl_push(l, d, path, e))
			return e->code;
	}
	return k < 0 ? e->code : 0;
}

/* atom ids of a LAMMPS file in order, with the disk each belongs to */
typedef struct idref {
	long id;
	int k;
} idref;

static int cmp_idref(const void *a, const void *b)
{
	const idref *x = a, *y = b;
	if (x->id != y->id)
		return (x->id > y->id) - (x->id < y->id);
	return (x->k > y->k) - (x->k < y->k);
}

/* Sort the ids once the Atoms section is read (the Velocities section looks them up,
 * and a linear search per velocity made a 10^5-atom file take seconds). A duplicate is
 * named by its first repetition in the file. */
static int index_ids(const dlist *l, idref **out, const char *path, sb_err *e)
{
	idref *ref = *out = malloc(sizeof *ref * (size_t)(l->n ? l->n : 1));
	if (!ref)
		return sb_errf(e, SB_ENOMEM, "out of memory reading particles");
	for (int i = 0; i < l->n; i++)
		ref[i] = (idref){l->d[i].id, i};
	qsort(ref, (size_t)l->n, sizeof *ref, cmp_idref);
	long bad = 0, first = 0, id = 0;
	for (int i = 1; i < l->n; i++)
		if (ref[i].id == ref[i - 1].id) {
			const long ln = l->d[ref[i].k].line;
			if (!bad || ln < bad) {
				bad = ln;
				first = l->d[ref[i - 1].k].line;
				id = ref[i].id;
			}
		}
	if (bad)
		return sb_errf(e, SB_EUSAGE, "%s:%ld: duplicate atom id %ld, first at line %ld", path, bad, id, first);
	return 0;
}

static int find_id(const idref *ref, int n, long id)
{
	int lo = 0, hi = n;
	while (lo < hi) {
		int mid = lo + (hi - lo) / 2;
		if (ref[mid].id < id)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo < n && ref[lo].id == id ? ref[lo].k : -1;
}

/* LAMMPS data file, atom_style sphere: Atoms lines are
 * "id type diameter density x y z [ix iy iz]", Velocities "id vx vy vz wx wy wz".
 * The density column is the mass 4/3 pi R^3 density (LAMMPS's sphere, even in 2D),
 * checked against the scene's mass model or used (pfile_read). As LAMMPS's
 * read_data does, an atom outside the box of the header is an error, and so are a
 * repeated atom id, Velocities before Atoms and an Atoms section of another style. */
static int read_lammps(lreader *r, dlist *l, sb_err *e)
{
	const char *path = r->path;
	long natoms = -1, atoms_line = 0, natoms_line = 0;
	double box[2][2];
	int has_box[2] = {0, 0};
	enum { HEAD, ATOMS, VELS, OTHER } sec = HEAD;
	idref *ref = NULL;
	int indexed = 0;
	int err = 0;
	while (!err && lr_next(r, e) > 0) {
		char *line = r->buf;
		if (r->line == 1)
			continue; /* the first line of a data file is a free comment */
		char *hash = strchr(line, '#');
		char tag[64] = "";
		if (sscanf(line, "%63s", tag) != 1)
			continue;
		if (hash)
			*hash = 0;
		if (!strcmp(tag, "Atoms")) {
			char style[64] = "";
			if (atoms_line)
				err = sb_errf(e, SB_EUSAGE, "%s:%ld: a second Atoms section (the first on line %ld)", path,
					      r->line, atoms_line);
			else if (hash && sscanf(hash + 1, "%63s", style) == 1 && strcmp(style, "sphere"))
				err = sb_errf(e, SB_EUSAGE,
					      "%s:%ld: Atoms section of atom_style %s: only atom_style sphere is read "
					      "(id type diameter density x y z)",
					      path, r->line, style);
			atoms_line = r->line;
			sec = ATOMS;
			continue;
		}
		if (!strcmp(tag, "Velocities")) {
			if (!atoms_line)
				err = sb_errf(e, SB_EUSAGE, "%s:%ld: Velocities before the Atoms section", path, r->line);
			else if (!indexed) {
				err = index_ids(l, &ref, path, e);
				indexed = 1;
			}
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
			/* the lines read are "N atoms" and "lo hi xlo xhi", "lo hi ylo yhi", all of
			 * them: "10 atoms extra" is no count (the other header lines are LAMMPS's
			 * business, and not needed here) */
			field f[5];
			const int nf = split(line, f, 5);
			if (nf >= 2 && f[1].n == 5 && !strncmp(f[1].s, "atoms", 5)) {
				long long n;
				if (nf != 2 || num_int_n(f[0].s, f[0].n, &n)) {
					err = sb_errf(e, SB_EUSAGE, "%s:%ld: expected 'N atoms' (N an integer), got %d fields", path,
						      r->line, nf);
					break;
				}
				natoms = n < 0 ? -1 : n > l->max ? (long)l->max + 1 : (long)n;
				natoms_line = r->line;
				if (n < 0 || n > l->max)
					err = sb_errf(e, SB_EUSAGE, "%s:%ld: %lld atoms: expected at most %d (10^7 grains, an intruder and the walls of a box)",
						      path, r->line, n, l->max);
			} else if (nf >= 4 && f[2].n == 3 && f[3].n == 3 && (f[2].s[0] == 'x' || f[2].s[0] == 'y') &&
				   f[3].s[0] == f[2].s[0] && !strncmp(f[2].s + 1, "lo", 2) && !strncmp(f[3].s + 1, "hi", 2)) {
				const int a = f[2].s[0] == 'y';
				double lo = 0, hi = 0;
				/* read whole: "0 20 xlo xhi extra" was taken for another header line
				 * and the box went unread */
				if (nf != 4)
					err = sb_errf(e, SB_EUSAGE, "%s:%ld: expected 'lo hi %clo %chi', got words after %chi", path,
						      r->line, "xy"[a], "xy"[a], "xy"[a]);
				else if (num_real_n(f[0].s, f[0].n, &lo) || num_real_n(f[1].s, f[1].n, &hi) || !(lo < hi))
					err = sb_errf(e, SB_EUSAGE, "%s:%ld: %clo %chi: expected finite decimal numbers lo < hi", path,
						      r->line, "xy"[a], "xy"[a]);
				box[a][0] = lo;
				box[a][1] = hi;
				has_box[a] = 1;
			}
		} else if (sec == ATOMS) {
			/* id type diameter density x y z [ix iy iz]: every field read, each of its
			 * kind (an atom type 1.5 would shift the columns after it) */
			static const char *const NAME[7] = {"id", "type", "diameter", "density", "x", "y", "z"};
			field f[10];
			const int nf = split(line, f, 10);
			long long id = 0, type = 0, img;
			double dia = 0, rho, z;
			disk d = {.line = r->line};
			if (nf != 7 && nf != 10) {
				err = sb_errf(e, SB_EUSAGE, "%s:%ld: expected 'id type diameter density x y z [ix iy iz]' "
					      "(atom_style sphere), got %d fields", path, r->line, nf);
				break;
			}
			double *v[7] = {NULL, NULL, &dia, &rho, &d.x, &d.y, &z};
			if (field_int(r, &f[0], NAME[0], &id, e) || field_int(r, &f[1], NAME[1], &type, e))
				break;
			for (int i = 2; i < 7 && !err; i++)
				err = field_real(r, &f[i], NAME[i], v[i], e);
			for (int i = 7; i < nf && !err; i++)
				err = field_int(r, &f[i], "image flag", &img, e);
			if (err)
				break;
			if (id < 1 || id > LONG_MAX)
				err = sb_errf(e, SB_EUSAGE, "%s:%ld: atom id %lld: expected a positive integer", path, r->line,
					      id);
			else if (type < 1 || type > 3)
				err = sb_errf(e, SB_EUSAGE, "%s:%ld: atom type %lld: expected 1 (grain), 2 (intruder) or 3 (wall)",
					      path, r->line, type);
			else if (!(dia > 0))
				err = sb_errf(e, SB_EUSAGE, "%s:%ld: diameter %g: expected a positive number", path, r->line,
					      dia);
			else if (!check_radius(path, r->line, 0.5 * dia, e)) {
				for (int a = 0; a < 2 && !err; a++) {
					const double vv = a ? d.y : d.x;
					if (has_box[a] && !(vv >= box[a][0] && vv <= box[a][1]))
						err = sb_errf(e, SB_EUSAGE,
							      "%s:%ld: atom %lld at %c = %g lies outside the box of the header "
							      "(%clo %chi = %g %g), as LAMMPS would refuse it",
							      path, r->line, id, "xy"[a], vv, "xy"[a], "xy"[a], box[a][0],
							      box[a][1]);
				}
				d.r = 0.5 * dia;
				d.col = rho;
				d.m = rho * (4.0 * SB_PI * d.r * d.r * d.r) / 3.0;
				d.mcol = MCOL_LAMMPS;
				d.kind = type == 1 ? KIND_GRAIN : type == 2 ? KIND_INTRUDER : KIND_WALL;
				d.id = (long)id;
				if (!err)
					err = dl_push(l, d, path, e);
			} else
				err = e->code;
		} else if (sec == VELS) {
			static const char *const NAME[7] = {"id", "vx", "vy", "vz", "wx", "wy", "wz"};
			field f[8];
			const int nf = split(line, f, 8);
			long long id;
			double w[7];
			if (nf != 7) {
				err = sb_errf(e, SB_EUSAGE, "%s:%ld: expected 'id vx vy vz wx wy wz', got %d fields", path,
					      r->line, nf);
				break;
			}
			if (field_int(r, &f[0], NAME[0], &id, e))
				break;
			for (int i = 1; i < 7 && !err; i++)
				err = field_real(r, &f[i], NAME[i], &w[i], e);
			if (err)
				break;
			const int i = id >= 1 && id <= LONG_MAX ? find_id(ref, l->n, (long)id) : -1;
			if (i < 0) {
				err = sb_errf(e, SB_EUSAGE, "%s:%ld: velocity for unknown atom id %lld", path, r->line, id);
				break;
			}
			if (l->d[i].vline) {
				err = sb_errf(e, SB_EUSAGE, "%s:%ld: a second velocity for atom id %lld (the first on line %ld)",
					      path, r->line, id, l->d[i].vline);
				break;
			}
			l->d[i].vx = w[1];
			l->d[i].vy = w[2];
			l->d[i].w = w[6];
			l->d[i].vline = r->line;
		}
	}
	if (!err && e->code)
		err = e->code; /* from the line reader */
	if (!err && !indexed) /* no Velocities: the ids are checked all the same */
		err = index_ids(l, &ref, path, e);
	free(ref);
	if (!err && natoms >= 0 && natoms != l->n)
		err = sb_errf(e, SB_EUSAGE, "%s:%ld: the header says %ld atoms, the Atoms section has %d", path, natoms_line,
			      natoms, l->n);
	if (!err && natoms < 0)
		err = sb_errf(e, SB_EUSAGE, "%s: no 'N atoms' line in the header", path);
	return err;
}
static const char *kind_name(int k)
{
	return k == KIND_GRAIN ? "grain" : k == KIND_INTRUDER ? "intruder" : "wall";
}

/* Where the disks lie. Coordinates and extents are measured in mean diameters of the
 * mobile disks: within GUARD_MAX_SPAN of the origin a double resolves a contact's
 * overlap, and grids of one diameter per cell (free surface, displacement field, the
 * overlap check below) fit in int. */
static int check_span(const dlist *l, const char *path, sb_err *e)
{
	double rs = 0;
	int nm = 0;
	for (int i = 0; i < l->n; i++)
		if (l->d[i].kind != KIND_WALL) {
			rs += l->d[i].r;
			nm++;
		}
	if (!nm)
		return 0; /* nothing to shake: sim_derive says so */
	const double dia = 2 * rs / nm, lim = GUARD_MAX_SPAN * dia;
	int lo[2] = {0, 0}, hi[2] = {0, 0};
	for (int i = 0; i < l->n; i++) {
		const disk *d = &l->d[i];
		if (!(fabs(d->x) <= lim && fabs(d->y) <= lim))
			return sb_errf(e, SB_EUSAGE, "%s:%ld: %s at (%g, %g) cm is %.3g mean disk diameters (%g cm) from the origin; at most %g",
				       path, d->line, kind_name(d->kind), d->x, d->y, fmax(fabs(d->x), fabs(d->y)) / dia, dia,
				       GUARD_MAX_SPAN);
		if (d->x < l->d[lo[0]].x)
			lo[0] = i;
		if (d->x > l->d[hi[0]].x)
			hi[0] = i;
		if (d->y < l->d[lo[1]].y)
			lo[1] = i;
		if (d->y > l->d[hi[1]].y)
			hi[1] = i;
	}
	for (int a = 0; a < 2; a++) {
		const disk *p = &l->d[lo[a]], *q = &l->d[hi[a]];
		const double span = a ? q->y - p->y : q->x - p->x;
		if (span > lim)
			return sb_errf(e, SB_EUSAGE, "%s:%ld: the disks on lines %ld and %ld lie %g cm apart in %c, %.3g mean disk diameters (%g cm); at most %g",
				       path, p->line > q->line ? p->line : q->line, p->line < q->line ? p->line : q->line,
				       p->line < q->line ? q->line : p->line, span, "xy"[a], span / dia, dia, GUARD_MAX_SPAN);
	}
	return 0;
}

/* A mobile disk far outside the box its walls make. LAMMPS refuses an atom outside the
 * box of its data file (read_data), and read_lammps does the same; the text format has
 * no box of its own, so the box is the hull of the wall disks. A disk just outside it
 * is left to the run, which stops at its first step naming the disk that left the box
 * (exit code 5) as it would at any later step; one farther away than the box is large
 * (a grain at y = 1e6 cm over a 50 cm box) is no state of this box but a slip of units
 * or a typo, and is refused with its line. Without walls there is no box (main warns).
 * With periodic sides the walls are the bottom row only: the box has no height of its
 * own, and only x and the floor are measured. */
static int check_far(const sb_scene *sc, const dlist *l, const char *path, sb_err *e)
{
	double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
	for (int i = 0; i < l->n; i++) {
		const disk *d = &l->d[i];
		if (d->kind != KIND_WALL)
			continue;
		x0 = fmin(x0, d->x - d->r);
		x1 = fmax(x1, d->x + d->r);
		y0 = fmin(y0, d->y - d->r);
		y1 = fmax(y1, d->y + d->r);
	}
	if (!(x0 <= x1))
		return 0;
	const double size = fmax(x1 - x0, y1 - y0);
	for (int i = 0; i < l->n; i++) {
		const disk *d = &l->d[i];
		if (d->kind == KIND_WALL)
			continue;
		const double above = sc->sides == SIDES_PERIODIC ? -INFINITY : d->y - y1;
		const double off = fmax(fmax(x0 - d->x, d->x - x1), fmax(y0 - d->y, above));
		if (off > size)
			return sb_errf(e, SB_EUSAGE,
				       "%s:%ld: %s at (%g, %g) cm lies %g cm outside the box of the walls ([%g, %g] x [%g, %g] cm), "
				       "farther than the box is large: a slip of units?",
				       path, d->line, kind_name(d->kind), d->x, d->y, off, x0, x1, y0, y1);
	}
	return 0;
}

/* A grid of cells over a subset of the disks (the mobile ones or the walls), by cell
 * then file order. */
typedef struct grid {
	double x0, y0, inv;
	int nx, ny;
	int *start; /* [nx ny + 2] */
	int *idx;
} grid;

static int grid_cell(double v, double o, double inv, int n)
{
	const double c = floor((v - o) * inv);
	return c < 0 ? 0 : c >= n ? n - 1 : (int)c;
}

static int grid_of(const grid *g, const disk *d)
{
	return grid_cell(d->y, g->y0, g->inv, g->ny) * g->nx + grid_cell(d->x, g->x0, g->inv, g->nx);
}

static int grid_build(grid *g, const dlist *l, int walls, sb_err *e)
{
	const int nc = g->nx * g->ny;
	g->start = calloc((size_t)nc + 2, sizeof(int));
	g->idx = malloc(sizeof(int) * ((size_t)l->n + 1));
	if (!g->start || !g->idx)
		return sb_errf(e, SB_ENOMEM, "out of memory checking particles");
	for (int i = 0; i < l->n; i++)
		if ((l->d[i].kind == KIND_WALL) == walls)
			g->start[grid_of(g, &l->d[i]) + 2]++;
	for (int c = 0; c < nc; c++)
		g->start[c + 2] += g->start[c + 1];
	for (int i = 0; i < l->n; i++)
		if ((l->d[i].kind == KIND_WALL) == walls)
			g->idx[g->start[grid_of(g, &l->d[i]) + 1]++] = i;
	return 0;
}

/* Coincident or deeply overlapping disks (beyond max_overlap of the smaller radius,
 * where the run would stop at its first step): an input error naming both lines. Two
 * disks at the same place have no direction to be pushed apart, so they are refused
 * whatever max_overlap allows. */
static int pair_check(const sb_scene *sc, const disk *a, const disk *b, const char *path, sb_err *e)
{
	const double dx = a->x - b->x, dy = a->y - b->y, rs = a->r + b->r;
	const double d = sqrt(dx * dx + dy * dy);
	if (d >= rs)
		return 0;
	if (a->line < b->line) { /* named at the later line */
		const disk *t = a;
		a = b;
		b = t;
	}
	if (d <= 1e-12 * rs)
		return sb_errf(e, SB_EUSAGE, "%s:%ld: %s at (%g, %g) coincides with the %s on line %ld", path, a->line,
			       kind_name(a->kind), a->x, a->y, kind_name(b->kind), b->line);
	const double f = (rs - d) / fmin(a->r, b->r);
	if (f > sc->max_overlap)
		return sb_errf(e, SB_EUSAGE,
			       "%s:%ld: %s overlaps the %s on line %ld by %.3g of the smaller radius, beyond max_overlap %g (%s)",
			       path, a->line, kind_name(a->kind), kind_name(b->kind), b->line, f, sc->max_overlap,
			       params_where(sc, "max_overlap"));
	return 0;
}

/* Every overlapping pair is found from its larger disk, which looks 2 r around itself
 * for partners no larger than itself: in cells of a mean mobile diameter that is a
 * 3 x 3 block for an ordinary disk. Two walls are never a contact (sim.h): a wall looks
 * for mobile partners only, and a mobile disk for smaller walls, so a row of
 * overlapping wall disks costs nothing. */
static int check_overlaps(const sb_scene *sc, const dlist *l, const char *path, sb_err *e)
{
	double rs = 0, xl = INFINITY, xh = -INFINITY, yl = INFINITY, yh = -INFINITY;
	int nm = 0;
	for (int i = 0; i < l->n; i++) {
		const disk *d = &l->d[i];
		if (d->kind != KIND_WALL) {
			rs += d->r;
			nm++;
		}
		xl = fmin(xl, d->x);
		xh = fmax(xh, d->x);
		yl = fmin(yl, d->y);
		yh = fmax(yh, d->y);
	}
	if (!nm)
		return 0;
	/* as the neighbour list does: about 2 cells a disk at most, larger cells if need be
	 * (check_span keeps the counts far inside int) */
	double cell = 2 * rs / nm, cx, cy;
	for (;;) {
		cx = floor((xh - xl) / cell) + 1;
		cy = floor((yh - yl) / cell) + 1;
		if (cx * cy <= 2.0 * l->n + 64)
			break;
		cell *= 1.5;
	}
	grid gm = {xl, yl, 1 / cell, (int)cx, (int)cy, NULL, NULL}, gw = gm;
	int err = grid_build(&gm, l, 0, e) || grid_build(&gw, l, 1, e) ? e->code : 0;
	for (int i = 0; i < l->n && !err; i++) {
		if (i % 4096 == 4095 && guard_stopped()) {
			err = sb_errf(e, SB_EINTR, "%s: interrupted while checking the disks", path);
			break;
		}
		const disk *a = &l->d[i];
		const int wall = a->kind == KIND_WALL;
		const double reach = 2 * a->r;
		const int i0 = grid_cell(a->x - reach, gm.x0, gm.inv, gm.nx);
		const int i1 = grid_cell(a->x + reach, gm.x0, gm.inv, gm.nx);
		const int j0 = grid_cell(a->y - reach, gm.y0, gm.inv, gm.ny);
		const int j1 = grid_cell(a->y + reach, gm.y0, gm.inv, gm.ny);
		for (int pass = 0; pass < 2 - wall && !err; pass++) {
			const grid *g = pass ? &gw : &gm; /* a wall looks at mobile disks only */
			for (int cj = j0; cj <= j1 && !err; cj++)
				for (int ci = i0; ci <= i1 && !err; ci++) {
					const int c = cj * g->nx + ci;
					for (int q = g->start[c]; q < g->start[c + 1] && !err; q++) {
						const int j = g->idx[q];
						const disk *b = &l->d[j];
						/* the larger one looks; of two alike the later mobile
						 * disk, or the wall */
						const int mine = wall   ? b->r <= a->r
								 : pass ? b->r < a->r
									: b->r < a->r || (b->r == a->r && j < i);
						if (mine)
							err = pair_check(sc, a, b, path, e);
					}
				}
		}
	}
	free(gm.start);
	free(gm.idx);
	free(gw.start);
	free(gw.idx);
	return err;
}

static int read_file(const sb_scene *sc, const char *path, dlist *l, sb_err *e)
{
	FILE *f = fs_open_input(path, "particle file", PF_MAX_BYTES, SB_EUSAGE, e);
	if (!f)
		return e->code;
	lreader *r = malloc(sizeof *r);
	int lammps = 0;
	int err = !r ? sb_errf(e, SB_ENOMEM, "out of memory reading particles") : 0;
	if (!err) {
		*r = (lreader){.f = f, .path = path};
		err = is_lammps(r, &lammps, e);
	}
	if (!err)
		err = lammps ? read_lammps(r, l, e) : read_text(r, l, e);
	free(r);
	fclose(f);
	if (!err && l->n == 0)
		err = sb_errf(e, SB_EUSAGE, "%s: no particles", path);
	if (!err)
		err = check_span(l, path, e);
	if (!err)
		err = check_far(sc, l, path, e);
	if (!err)
		err = check_overlaps(sc, l, path, e);
	return err;
}

/* How much a file's mass may differ from the scene's and still be the scene's: the
 * rounding of a printed number (a LAMMPS density column is 3 m / (4 pi R^3), read back
 * to a few ulp) and no more; a density ratio of another material is far beyond it. */
#define PF_MASS_REL 1e-9

/* A disk's mass by particle_mass (docs/inputs.md, "Particle masses") is the scene's mass
 * model, which a column of the file must then agree with (a file of a heavier intruder
 * read under the default density is refused, never run with masses it did not ask
 * for), or the file's column, which every line must then have. */
static int check_mass(const sb_scene *sc, const disk *d, const char *path, sb_err *e)
{
	static const char *const COL[] = {"", "m", "density"};
	if (sc->particle_mass == PMASS_FILE) {
		if (d->mcol == MCOL_NONE)
			return sb_errf(e, SB_EUSAGE,
				       "%s:%ld: particle_mass = file (%s), but the line has no mass column "
				       "(expected 'x y r kind vx vy omega m')",
				       path, d->line, params_where(sc, "particle_mass"));
		return 0;
	}
	const double m = place_mass(sc, d->r, d->kind);
	if (d->mcol == MCOL_NONE || fabs(d->m - m) <= PF_MASS_REL * m)
		return 0;
	const char *key = place_density_key(sc, d->kind), *hint = d->kind == KIND_INTRUDER ? "intruder_density" : "density";
	return sb_errf(e, SB_EUSAGE,
		       "%s:%ld: %s of mass %.10g g (the file's %s column, %.17g), but the scene's mass model gives %.10g g "
		       "(mass_factor %g, %s; %s %g, %s): set %s to the file's material, or particle_mass = file to take "
		       "the file's masses",
		       path, d->line, kind_name(d->kind), d->m, COL[d->mcol], d->col, m, sc->mass_factor,
		       params_where(sc, "mass_factor"), key, place_density(sc, d->kind), params_where(sc, key), hint);
}

/* read_file with room for the most disks a scene may have; a file of 10^7 disks takes
 * seconds to read and check, so SIGINT and SIGTERM end it */
static int read_guarded(const sb_scene *sc, const char *path, dlist *l, sb_err *e)
{
	*l = (dlist){.max = (int)params_find("n_grains")->max + 1 + GUARD_MAX_WALLS};
	guard_sig g;
	guard_hold(&g);
	const int err = read_file(sc, path, l, e);
	guard_release(&g);
	return err;
}

int pfile_read(const sb_scene *sc, const char *path, sb_state *st, sb_err *e)
{
	dlist l;
	int err = read_guarded(sc, path, &l, e);
	/* mobile disks first, in file order, then the walls */
	for (int pass = 0; pass < 2 && !err; pass++)
		for (int i = 0; i < l.n && !err; i++) {
			const disk *d = &l.d[i];
			if ((d->kind == KIND_WALL) != pass)
				continue;
			sb_err pe = {0};
			if (check_mass(sc, d, path, e))
				return free(l.d), e->code;
			if (sc->particle_mass == PMASS_FILE)
				err = place_push_mass(sc, st, d->x, d->y, d->r, d->kind, d->m, &pe);
			else
				err = place_push(sc, st, d->x, d->y, d->r, d->kind, &pe);
			if (err == SB_EUSAGE) /* the mass: name the disk's line */
				sb_errf(e, err, "%s:%ld: %s", path, d->line, pe.msg);
			else if (err)
				sb_errf(e, err, "%s", pe.msg);
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

/* The recorded radius_ratio of a particle file (docs/model.md, "Units and the paper's
 * values"): the first intruder's, the one of the trajectory, risen and waiting_time,
 * over the scene's mean grain radius, never the file's grains' own mean: a packing a
 * run wrote (write_particles, the study driver's packing cache) reads back the ratio of
 * that run, where its grains' sample mean lies a few tenths of a percent off the
 * scene's. Rounded to the 12 digits a campaign prints its values with, so that a
 * radius of 2 over a mean of 1 is 2 and not 2 less an ulp. */
int pfile_intruders(const sb_scene *sc, const char *path, sb_pintr *out, sb_err *e)
{
	dlist l;
	int err = read_guarded(sc, path, &l, e);
	*out = (sb_pintr){0, 0, 0};
	double lo, hi, mean;
	params_grain_radii(sc, &lo, &hi, &mean);
	for (int i = 0; i < l.n && !err; i++) {
		const disk *d = &l.d[i];
		if (d->kind != KIND_INTRUDER)
			continue;
		if (out->count++)
			continue;
		char num[40];
		snprintf(num, sizeof num, "%.12g", d->r / mean);
		out->ratio = strtod(num, NULL);
		out->line = d->line;
		const double max = params_find("radius_ratio")->max;
		if (!(out->ratio <= max))
			err = sb_errf(e, SB_EUSAGE,
				      "%s:%ld: intruder of radius %g cm is radius_ratio %g over the scene's mean grain radius %g cm "
				      "(%s), beyond the key's range [0, %g]: set the grains' radii to the file's",
				      path, d->line, d->r, out->ratio, mean,
				      sc->size_dist == SIZE_BINARY ? "r_small, r_large, large_fraction" : "r_min, r_max", max);
	}
	const sb_param *ni = params_find("n_intruders");
	if (!err && out->count > (long)ni->max)
		err = sb_errf(e, SB_EUSAGE, "%s: %ld intruders, beyond n_intruders' range [%g, %g]", path, out->count,
			      ni->min, ni->max);
	free(l.d);
	return err;
}

static int apply_count(sb_scene *sc, const char *path, const sb_pintr *in, sb_err *e)
{
	if (in->count < 1)
		return 0;
	const char *set = params_where(sc, "n_intruders");
	if (strcmp(set, "default")) {
		if (sc->n_intruders == in->count)
			return 0;
		return sb_errf(e, SB_EUSAGE,
			       "%s:%ld: the file holds %ld intruder%s (the first on this line), but n_intruders = %ld is set at "
			       "%s: a particle file's intruders decide n_intruders; leave the key out, or set it to the file's",
			       path, in->line, in->count, in->count == 1 ? "" : "s", sc->n_intruders, set);
	}
	sb_err pe = {0};
	char num[32];
	snprintf(num, sizeof num, "%ld", in->count);
	return params_set(sc, "n_intruders", num, "particle file", &pe) ? sb_errf(e, pe.code, "%s: %s", path, pe.msg) : 0;
}

int pfile_intruders_apply(sb_scene *sc, const char *path, const sb_pintr *in, sb_err *e)
{
	if (apply_count(sc, path, in, e))
		return e->code;
	const double ratio = in->ratio;
	const long line = in->line;
	const char *set = params_where(sc, "radius_ratio");
	if (strcmp(set, "default")) {
		/* given: it must be the file's, to the rounding of a printed radius */
		const double key = sc->radius_ratio;
		if (fabs(key - ratio) <= PFILE_RATIO_REL * fmax(fabs(key), fabs(ratio)))
			return 0;
		double lo, hi, mean;
		params_grain_radii(sc, &lo, &hi, &mean);
		if (!line)
			return sb_errf(e, SB_EUSAGE,
				       "%s: no intruder, so the file's radius_ratio is 0, but radius_ratio = %g is set at %s: a "
				       "particle file's intruder decides radius_ratio; leave the key out, or set it to 0",
				       path, key, set);
		return sb_errf(e, SB_EUSAGE,
			       "%s:%ld: the file's first intruder makes radius_ratio %.12g (its radius over the scene's mean "
			       "grain radius %g cm), but radius_ratio = %g is set at %s: a particle file's first intruder "
			       "decides radius_ratio; leave the key out, or set it to the file's",
			       path, line, ratio, mean, key, set);
	}
	sb_err pe = {0};
	char num[40];
	snprintf(num, sizeof num, "%.17g", ratio);
	/* where it came from, for the cross-key checks' messages (validate.c) */
	return params_set(sc, "radius_ratio", num, line ? "particle file" : "particle file without intruder", &pe)
		       ? sb_errf(e, pe.code, "%s: %s", path, pe.msg)
		       : 0;
}

int pfile_scene_intruders(sb_scene *sc, sb_err *e)
{
	sb_pintr in;
	if (pfile_intruders(sc, sc->particles, &in, e))
		return e->code;
	return pfile_intruders_apply(sc, sc->particles, &in, e);
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
	fprintf(f, "# shakebox particle file: x y r kind vx vy omega m (cgs, lab frame)\n");
	fprintf(f, "# %d disks, %d mobile\n", st->n, st->nm);
	for (int i = 0; i < st->n; i++) {
		double vx, vy, w;
		lab_velocity(st, i, inv_dt, vshift, &vx, &vy, &w);
		fprintf(f, "%.17g %.17g %.17g %s %.17g %.17g %.17g %.17g\n", st->q[C_X][0][i],
			st->q[C_Y][0][i] + yshift, st->r[i], kind_name(st->kind[i]), vx, vy, w, st->m[i]);
	}
	return fs_commit(&out, e);
}

int pfile_write_lammps(const sb_state *st, const char *path, double inv_dt, double yshift,
		       double vshift, double period, sb_err *e)
{
	double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
	for (int i = 0; i < st->n; i++) {
		double y = st->q[C_Y][0][i] + yshift;
		xlo = fmin(xlo, st->q[C_X][0][i] - st->r[i]);
		xhi = fmax(xhi, st->q[C_X][0][i] + st->r[i]);
		ylo = fmin(ylo, y - st->r[i]);
		yhi = fmax(yhi, y + st->r[i]);
	}
	/* periodic sides: the box in x is the period, and the atoms are wrapped into it
	 * (a whole period is no change of the state; read_data wants them inside) */
	if (period > 0) {
		xlo = 0;
		xhi = period;
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
		   "density column = 3 m / (4 pi R^3) so that LAMMPS gets m%s\n\n",
		period > 0 ? "; periodic in x: boundary p f p" : "");
	fprintf(f, "%d atoms\n3 atom types\n\n", st->n);
	fprintf(f, "%.17g %.17g xlo xhi\n%.17g %.17g ylo yhi\n-0.5 0.5 zlo zhi\n\n", xlo, xhi, ylo, yhi);
	fprintf(f, "Atoms # sphere\n\n");
	for (int i = 0; i < st->n; i++) {
		double r = st->r[i];
		/* LAMMPS read_data computes 4/3 pi r^3 density even in 2D */
		double rho = 3.0 * st->m[i] / (4.0 * SB_PI * r * r * r);
		fprintf(f, "%d %d %.17g %.17g %.17g %.17g 0\n", i + 1, st->kind[i] + 1, 2 * r, rho,
			periodic_wrap(st->q[C_X][0][i], period), st->q[C_Y][0][i] + yshift);
	}
	fprintf(f, "\nVelocities\n\n");
	for (int i = 0; i < st->n; i++) {
		double vx, vy, w;
		lab_velocity(st, i, inv_dt, vshift, &vx, &vy, &w);
		fprintf(f, "%d %.17g %.17g 0 0 0 %.17g\n", i + 1, vx, vy, w);
	}
	return fs_commit(&out, e);
}
