/* convect.c - the roll strength of a displacement field (analysis/measure/convect.h) on
 * synthetic fields whose answer is known: a sine of uy across the band gives A/sqrt(2)
 * wherever the pattern sits in x, the count weights, cells outside the band and cells
 * without samples carry no weight, the transient and empty blocks of a run, a run that
 * failed within its transient, the persistence of a steady roll under noise and of noise
 * alone, and a synthetic run file read end to end. */
#include <hdf5.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "measure/convect.h"
#include "testlib.h"

#define NX 40
#define NY 20
#define CELL 0.75
#define SURF 12.0 /* the band 0.3..0.7: 3.6 .. 8.4 cm, rows 5..10 (centres 4.125 .. 7.875 cm) */

/* uy = A sin(2 pi x / L + phase) and ux = B cos(...) in the band's rows, count m there;
 * outside it large noise with counts, so that it would show if it were taken. */
static void fill(double *ux, double *uy, double *n, double A, double B, double phase, double m, unsigned *seed)
{
	for (int r = 0; r < NY; r++)
		for (int c = 0; c < NX; c++) {
			const int q = r * NX + c;
			const double yc = (r + 0.5) * CELL, th = 2 * M_PI * (c + 0.5) / NX + phase;
			if (yc >= 0.3 * SURF && yc <= 0.7 * SURF) {
				uy[q] = A * sin(th);
				ux[q] = B * cos(th);
				n[q] = m;
			} else {
				uy[q] = 50.0 * (rand_r(seed) / (double)RAND_MAX - 0.5);
				ux[q] = 50.0 * (rand_r(seed) / (double)RAND_MAX - 0.5);
				n[q] = 1 + rand_r(seed) % 9;
			}
		}
}

#include "h5synth.h"

int main(void)
{
	const size_t C = NX * NY;
	double ux[NX * NY], uy[NX * NY], n[NX * NY];
	unsigned seed = 7;
	convect_block b;
	const double A = 0.4, B = 0.3;

	/* The mean of sin^2 over N >= 3 equally spaced points of a whole period is exactly
	 * 1/2 (the sum of cos(2 theta) over them is 0), so the count-weighted rms of a sine
	 * with equal counts is A/sqrt(2) up to rounding, for every phase: 1e-12. */
	double S0 = NAN;
	const double phases[] = {0, 0.37, 1.9, M_PI, 5.1};
	int shift_ok = 1;
	for (int k = 0; k < 5; k++) {
		fill(ux, uy, n, A, B, phases[k], 7, &seed);
		convect_strength(ux, uy, n, NY, NX, CELL, 0.3 * SURF, 0.7 * SURF, &b);
		if (k == 0) {
			S0 = b.S;
			CHECK_REL("convect.sine.strength", b.S, A / sqrt(2), 1e-12);
			CHECK_REL("convect.sine.strength_u", b.Su, sqrt((A * A + B * B) / 2), 1e-12);
			CHECK("convect.band.cells", b.cells == 6 * NX && b.w == 7.0 * 6 * NX, "%zu cells, weight %g", b.cells,
			      b.w);
		}
		shift_ok &= fabs(b.S - S0) <= 1e-12 * S0;
	}
	CHECK("convect.sine.shift_invariant", shift_ok, "S changes with the pattern's phase");
	/* a shift by whole cells permutes the cells: the same S to the bit after a cyclic
	 * shift of the columns by 13 */
	fill(ux, uy, n, A, B, 0.37, 7, &seed);
	double sx[NX * NY], sy[NX * NY], sn[NX * NY];
	for (int r = 0; r < NY; r++)
		for (int c = 0; c < NX; c++) {
			sx[r * NX + (c + 13) % NX] = ux[r * NX + c];
			sy[r * NX + (c + 13) % NX] = uy[r * NX + c];
			sn[r * NX + (c + 13) % NX] = n[r * NX + c];
		}
	convect_block b2;
	convect_strength(ux, uy, n, NY, NX, CELL, 0.3 * SURF, 0.7 * SURF, &b);
	convect_strength(sx, sy, sn, NY, NX, CELL, 0.3 * SURF, 0.7 * SURF, &b2);
	CHECK("convect.sine.cyclic_shift", fabs(b.S - b2.S) <= 1e-15 * b.S, "%.17g vs %.17g", b.S, b2.S);

	/* the noise outside the band is ignored: the same S with other noise there */
	fill(ux, uy, n, A, B, 0.37, 7, &seed);
	convect_strength(ux, uy, n, NY, NX, CELL, 0.3 * SURF, 0.7 * SURF, &b2);
	CHECK("convect.band.outside_ignored", b.S == b2.S && b.Su == b2.Su, "%.17g vs %.17g", b.S, b2.S);
	/* ... and counted when the band takes the whole bed */
	convect_strength(ux, uy, n, NY, NX, CELL, 0, 2 * SURF, &b2);
	CHECK("convect.band.whole_bed_differs", b2.S > 3 * b.S, "whole bed %g, band %g", b2.S, b.S);

	/* count weighting, by hand: two cells, uy = 1 with 3 samples and uy = 3 with 1:
	 * sqrt((3 * 1 + 1 * 9) / 4) = sqrt(3), not the unweighted sqrt(5) */
	double wx[2] = {2, 0}, wy[2] = {1, 3}, wn[2] = {3, 1};
	convect_strength(wx, wy, wn, 1, 2, 1, 0, 1, &b);
	CHECK_REL("convect.weights.by_count", b.S, sqrt(3), 1e-15);
	CHECK_REL("convect.weights.strength_u", b.Su, sqrt((3 * 5.0 + 9) / 4), 1e-15);
	/* a cell without samples (count 0; the engine writes 0 displacement there) weighs
	 * nothing whatever it holds, also a NaN */
	double zx[3] = {2, 0, 99}, zy[3] = {1, 3, 1000}, zn[3] = {3, 1, 0};
	convect_strength(zx, zy, zn, 1, 3, 1, 0, 1, &b);
	CHECK("convect.weights.zero_count_ignored", fabs(b.S - sqrt(3)) < 1e-15 && b.cells == 2, "S %g, %zu cells", b.S,
	      b.cells);
	zy[2] = NAN;
	zn[2] = 5;
	convect_strength(zx, zy, zn, 1, 3, 1, 0, 1, &b);
	CHECK("convect.weights.nan_ignored", fabs(b.S - sqrt(3)) < 1e-15, "S %g", b.S);
	zn[0] = zn[1] = zn[2] = 0;
	convect_strength(zx, zy, zn, 1, 3, 1, 0, 1, &b);
	CHECK("convect.weights.no_sample", isnan(b.S) && isnan(b.Su) && b.w == 0, "S %g", b.S);

	/* A run of 10 blocks: blocks 0, 1 (the transient at skip 0.2) strong, block 6
	 * without a sample in the band, the others A_k = 0.1 k: S = mean of A_k / sqrt(2)
	 * over blocks 2..9 but 6. */
	convect_field f = {.B = 10, .ny = NY, .nx = NX, .cell = CELL, .surface = SURF, .K = 5};
	f.ux = malloc(sizeof *f.ux * C * f.B);
	f.uy = malloc(sizeof *f.uy * C * f.B);
	f.n = malloc(sizeof *f.n * C * f.B);
	f.t = malloc(sizeof *f.t * f.B);
	double want = 0;
	for (size_t k = 0; k < f.B; k++) {
		const double a = k < 2 ? 5 : 0.1 * (double)k;
		fill(f.ux + k * C, f.uy + k * C, f.n + k * C, a, 0, 0.2 * (double)k, 1 + (double)k, &seed);
		if (k == 6)
			for (size_t q = 0; q < C; q++)
				f.n[k * C + q] = (q / NX >= 5 && q / NX <= 10) ? 0 : f.n[k * C + q];
		f.t[k] = (double)(k + 1);
		if (k >= 2 && k != 6)
			want += a / sqrt(2) / 7;
	}
	convect_cfg cfg = CONVECT_CFG_DEFAULT;
	convect_run r;
	CHECK("convect.run.ok", convect_summary(&f, &cfg, 0, &r) == 0, "no block used");
	CHECK("convect.run.blocks", r.blocks == 10 && r.first == 2 && r.used == 7 && r.empty == 1 && r.rows == 6,
	      "blocks %zu first %zu used %zu empty %zu rows %zu", r.blocks, r.first, r.used, r.empty, r.rows);
	CHECK_REL("convect.run.mean_after_transient", r.S, want, 1e-12);
	cfg.skip = 0;
	convect_summary(&f, &cfg, 0, &r);
	CHECK("convect.run.skip_0_takes_the_transient", r.first == 0 && r.used == 9 && r.S > want + 0.5, "S %g", r.S);
	/* a run that failed after 10 of a planned 60 blocks: its transient is 12 blocks */
	cfg.skip = 0.2;
	CHECK("convect.run.failed_within_transient", convect_summary(&f, &cfg, 60, &r) == 1 && isnan(r.S) && r.first == 12,
	      "first %zu, S %g", r.first, r.S);
	CHECK("convect.run.failed_after_transient", convect_summary(&f, &cfg, 12, &r) == 0 && r.first == 2 &&
	      fabs(r.S - want) < 1e-12, "first %zu, S %g", r.first, r.S);

	/* persistence: a steady roll uy = A sin under independent noise of sd sigma per block
	 * gives C = A^2/2, pure noise C = 0 while S sits at the noise floor. The noise
	 * terms of C have sd about sigma^2 / sqrt(cells * pairs) = 1/86 here and the cross
	 * terms about A sigma / sqrt(cells * pairs / 2) = 1/61: 0.08 is five of them. */
	for (int roll = 0; roll < 2; roll++) {
		const double A = roll ? 1 : 0, sig = 1;
		convect_field g = {.B = 40, .ny = NY, .nx = NX, .cell = CELL, .surface = SURF, .K = 10};
		g.ux = calloc(C * g.B, sizeof *g.ux);
		g.uy = calloc(C * g.B, sizeof *g.uy);
		g.n = calloc(C * g.B, sizeof *g.n);
		for (size_t k = 0; k < g.B; k++) {
			fill(g.ux + k * C, g.uy + k * C, g.n + k * C, A, 0, 0, 3, &seed);
			for (size_t q = 0; q < C; q++) /* uniform noise of sd sig */
				g.uy[k * C + q] += sig * sqrt(12.0) * (rand_r(&seed) / (double)RAND_MAX - 0.5);
		}
		convect_run pr;
		convect_summary(&g, &cfg, 0, &pr);
		if (roll)
			CHECK("convect.persistence.steady_roll", pr.pairs == 31 && fabs(pr.C - 0.5) < 0.08 && pr.S > 1.1,
			      "C %g (want 0.5), S %g, %zu pairs", pr.C, pr.S, pr.pairs);
		else
			CHECK("convect.persistence.noise_only", fabs(pr.C) < 0.08 && pr.S > 0.8,
			      "C %g (want 0), S %g (the noise floor, about 1)", pr.C, pr.S);
		free(g.ux);
		free(g.uy);
		free(g.n);
	}

	/* a run file like the engine's, read end to end */
	char path[] = "/tmp/convect-test-XXXXXX";
	int fd = mkstemp(path);
	close(fd);
	hid_t h = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
	const hsize_t d3[3] = {f.B, NY, NX}, d1[1] = {f.B};
	dset(h, "/observables/field/ux/value", 3, d3, f.ux);
	dset(h, "/observables/field/ux/time", 1, d1, f.t);
	dset(h, "/observables/field/uy/value", 3, d3, f.uy);
	dset(h, "/observables/field/count/value", 3, d3, f.n);
	hid_t g = H5Gopen2(h, "/observables/field", H5P_DEFAULT);
	attr_d(g, "cell", CELL);
	attr_d(g, "x0", 0);
	attr_d(g, "periods_per_block", 5);
	H5Gclose(g);
	g = H5Gopen2(h, "/", H5P_DEFAULT);
	attr_d(g, "surface_height", SURF);
	H5Gclose(g);
	H5Fclose(h);
	convect_field rf;
	sb_err e = {0};
	int rc = convect_read(path, &rf, &e);
	CHECK("convect.file.read", rc == 0 && rf.B == 10 && rf.ny == NY && rf.nx == NX && rf.cell == CELL &&
	      rf.surface == SURF && rf.K == 5, "rc %d: %s", rc, e.msg);
	if (!rc) {
		convect_summary(&rf, &cfg, 0, &r);
		CHECK_REL("convect.file.strength", r.S, want, 1e-12);
		convect_free(&rf);
	}
	/* a file without a field: the run had field = no */
	h = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
	g = H5Gopen2(h, "/", H5P_DEFAULT);
	attr_d(g, "surface_height", SURF);
	H5Gclose(g);
	H5Fclose(h);
	e = (sb_err){0};
	rc = convect_read(path, &rf, &e);
	CHECK("convect.file.no_field", rc == SB_EUSAGE && strstr(e.msg, "field = no"), "rc %d: %s", rc, e.msg);
	unlink(path);
	e = (sb_err){0};
	rc = convect_read(path, &rf, &e);
	CHECK("convect.file.missing", rc == SB_EIO, "rc %d: %s", rc, e.msg);
	convect_free(&f);
	return tl_done();
}
