/* maxoverlap.c - the largest overlap (as a fraction of the smaller radius) in the
 * recorded states of a run file: /final (every disk, walls included) and each
 * stroboscopic snapshot (/particles/bed/position, lab frame, with the walls of
 * /particles/walls where they stand at every snapshot: phase 0, the box at rest).
 *
 * usage: maxoverlap RUN.h5  ->  "final F snapshots S n_snapshots K n_disks N pair I J"
 * F, S are the largest overlaps / smaller radius (0 when nothing touches); I J the
 * pair (indices into /final) of the larger of the two. A cell grid one largest
 * diameter wide makes it O(N) for 1e5 disks; the intruder is checked against all. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double *read_ds(hid_t f, const char *name, hsize_t *d0, hsize_t *d1)
{
	if (H5Lexists(f, name, H5P_DEFAULT) <= 0)
		return NULL;
	hid_t ds = H5Dopen2(f, name, H5P_DEFAULT);
	if (ds < 0)
		return NULL;
	hid_t sp = H5Dget_space(ds);
	hsize_t dims[3] = {0, 1, 1};
	int nd = H5Sget_simple_extent_ndims(sp);
	H5Sget_simple_extent_dims(sp, dims, NULL);
	if (nd == 1)
		dims[1] = 1;
	if (nd == 3) /* [K][n][2]: n x 2 values per row */
		dims[1] *= dims[2];
	*d0 = dims[0];
	*d1 = dims[1];
	size_t n = (size_t)(dims[0] * dims[1]);
	double *v = malloc((n ? n : 1) * sizeof *v);
	if (n && H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0) {
		free(v);
		v = NULL;
	}
	H5Sclose(sp);
	H5Dclose(ds);
	return v;
}

typedef struct best {
	double f;
	int i, j;
} best;

static void pair(const double *x, const double *y, const double *r, int i, int j, best *b)
{
	double dx = x[i] - x[j], dy = y[i] - y[j], rs = r[i] + r[j];
	double d2 = dx * dx + dy * dy;
	if (d2 >= rs * rs)
		return;
	double f = (rs - sqrt(d2)) / fmin(r[i], r[j]);
	if (f > b->f) {
		b->f = f;
		b->i = i;
		b->j = j;
	}
}

/* largest overlap among n disks; disks with r > 3 * rtyp are checked against all */
static best scan(int n, const double *x, const double *y, const double *r, const int *wall)
{
	best b = {0, -1, -1};
	double rtyp = 0, x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
	int nbig = 0;
	int *big = malloc((size_t)n * sizeof *big);
	for (int i = 0; i < n; i++)
		rtyp += r[i] / n;
	double rmax = 0;
	for (int i = 0; i < n; i++) {
		if (r[i] > 3 * rtyp) {
			big[nbig++] = i;
			continue;
		}
		rmax = fmax(rmax, r[i]);
		x0 = fmin(x0, x[i]);
		x1 = fmax(x1, x[i]);
		y0 = fmin(y0, y[i]);
		y1 = fmax(y1, y[i]);
	}
	double h = 2 * rmax;
	long nx = (long)((x1 - x0) / h) + 1, ny = (long)((y1 - y0) / h) + 1;
	while (nx * ny > 8L * n + 64) { /* a flying grain must not blow the grid up */
		h *= 2;
		nx = (long)((x1 - x0) / h) + 1;
		ny = (long)((y1 - y0) / h) + 1;
	}
	long *head = malloc((size_t)(nx * ny) * sizeof *head), *next = malloc((size_t)n * sizeof *next);
	for (long c = 0; c < nx * ny; c++)
		head[c] = -1;
	for (int i = 0; i < n; i++) {
		if (r[i] > 3 * rtyp)
			continue;
		long c = (long)((y[i] - y0) / h) * nx + (long)((x[i] - x0) / h);
		next[i] = head[c];
		head[c] = i;
	}
	for (int i = 0; i < n; i++) {
		if (r[i] > 3 * rtyp)
			continue;
		long cx = (long)((x[i] - x0) / h), cy = (long)((y[i] - y0) / h);
		for (long ey = cy - 1; ey <= cy + 1; ey++)
			for (long ex = cx - 1; ex <= cx + 1; ex++) {
				if (ex < 0 || ey < 0 || ex >= nx || ey >= ny)
					continue;
				for (long j = head[ey * nx + ex]; j >= 0; j = next[j])
					if (j > i && !(wall[i] && wall[j]))
						pair(x, y, r, i, (int)j, &b);
			}
	}
	for (int k = 0; k < nbig; k++)
		for (int j = 0; j < n; j++)
			if (j != big[k] && !(wall[big[k]] && wall[j]))
				pair(x, y, r, big[k], j, &b);
	free(head);
	free(next);
	free(big);
	return b;
}

int main(int argc, char **argv)
{
	if (argc != 2) {
		fprintf(stderr, "usage: maxoverlap RUN.h5\n");
		return 1;
	}
	H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
	hid_t f = H5Fopen(argv[1], H5F_ACC_RDONLY, H5P_DEFAULT);
	if (f < 0) {
		fprintf(stderr, "maxoverlap: cannot open '%s'\n", argv[1]);
		return 2;
	}
	hsize_t n, one, k = 0, nm = 0;
	double *r = read_ds(f, "/final/radius", &n, &one);
	double *kind = NULL, *x = read_ds(f, "/final/x", &n, &one), *y = read_ds(f, "/final/y", &n, &one);
	hsize_t nk;
	{ /* kind is an integer dataset: read it as double */
		kind = read_ds(f, "/final/species", &nk, &one);
	}
	if (!r || !x || !y || !kind || nk != n) {
		fprintf(stderr, "maxoverlap: '%s' lacks /final\n", argv[1]);
		return 2;
	}
	int *wall = malloc(n * sizeof *wall);
	for (hsize_t i = 0; i < n; i++)
		wall[i] = kind[i] == 2;
	best bf = scan((int)n, x, y, r, wall), bs = {0, -1, -1};
	hsize_t nw = 0, two = 0;
	double *sp = read_ds(f, "/particles/bed/position/value", &k, &nm);
	double *wp = read_ds(f, "/particles/walls/position", &nw, &two);
	if (sp && k > 0 && nm / 2 + (wp ? nw : 0) == n) {
		double *tx = malloc(n * sizeof *tx), *ty = malloc(n * sizeof *ty);
		const hsize_t nmob = nm / 2;
		for (hsize_t s = 0; s < k; s++) {
			for (hsize_t i = 0; i < n; i++) {
				tx[i] = i < nmob ? sp[s * nm + 2 * i] : wp[2 * (i - nmob)];
				ty[i] = i < nmob ? sp[s * nm + 2 * i + 1] : wp[2 * (i - nmob) + 1];
			}
			best b = scan((int)n, tx, ty, r, wall);
			if (b.f > bs.f)
				bs = b;
		}
		free(tx);
		free(ty);
	} else
		k = 0;
	best w = bf.f >= bs.f ? bf : bs;
	printf("final %.6f snapshots %.6f n_snapshots %llu n_disks %llu pair %d %d\n", bf.f, bs.f,
	       (unsigned long long)k, (unsigned long long)n, w.i, w.j);
	H5Fclose(f);
	free(sp);
	free(wp);
	free(wall);
	free(kind);
	free(r);
	free(x);
	free(y);
	return 0;
}
