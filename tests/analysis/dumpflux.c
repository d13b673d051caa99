/* dumpflux.c - the path from another code's position dump to Phi(D) (analysis/measure/dump.c,
 * analysis/measure/dumpflux.c, core/model/crossing.c) and the two-code comparison
 * (analysis/measure/pairdiff.c):
 *   - the dump reader: frames, columns by name, rows sorted by id, skipped ITEM
 *     sections; a truncated frame, a missing column, a repeated id are errors;
 *   - the crossing rule at the lines' edges (yp < h <= y up, y < h <= yp down) and the
 *     centre/outside split;
 *   - the consistency check: an engine run (SHAKE, default build/san/bin/shake or
 *     bin/shake) with flux and snapshots, its snapshots dumped by
 *     scripts/dump_lammps.sh and read back through dumpflux_read, gives exactly the
 *     engine's own flux record (flux_read), period by period and line by line; without
 *     the box offset taken off it would not; a dump with a frame missing is refused;
 *   - the comparison: means, Student-t half-widths, the paired difference and the exact
 *     sign-flip p-values on made-up profiles.
 * Run from the repository root (tests/run.sh does). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "crossing.h"
#include "measure/dump.h"
#include "measure/dumpflux.h"
#include "flux.h"
#include "measure/pairdiff.h"
#include "testlib.h"

static void write_file(const char *path, const char *text)
{
	FILE *f = fopen(path, "w");
	if (f) {
		fputs(text, f);
		fclose(f);
	}
}

static void test_reader(const char *dir)
{
	char p[512];
	snprintf(p, sizeof p, "%s/a.dump", dir);
	write_file(p, "ITEM: TIME\n0.5\nITEM: TIMESTEP\n10\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS mm mm pp\n"
		      "0 1\n0 1\n-0.5 0.5\nITEM: ATOMS type id vx x y radius\n3 7 0 1.5 2.5 1\n1 2 9 0.25 0.75 0.5\n"
		      "2 5 0 3 4 2\nITEM: TIMESTEP\n20\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff pp\n0 1\n0 1\n"
		      "-0.5 0.5\nITEM: ATOMS id type x y\n4 1 -1e-3 2e+2\n");
	dump_reader rd;
	dump_frame fr = {0};
	sb_err e = {0};
	CHECK("dump.open", dump_open(&rd, p, &e) == 0, "%s", e.msg);
	int got = dump_next(&rd, &fr, &e);
	CHECK("dump.frame1", got == 1 && fr.step == 10 && fr.n == 3, "got %d step %ld n %ld: %s", got, fr.step, fr.n,
	      e.msg);
	CHECK("dump.sorted_by_id_columns_by_name",
	      fr.n == 3 && fr.id[0] == 2 && fr.id[1] == 5 && fr.id[2] == 7 && fr.type[0] == 1 && fr.type[2] == 3 &&
		      fr.x[0] == 0.25 && fr.y[0] == 0.75 && fr.r[0] == 0.5 && fr.x[2] == 1.5 && fr.r[1] == 2 && fr.has_r,
	      "rows not as written");
	got = dump_next(&rd, &fr, &e);
	CHECK("dump.frame2_no_radius", got == 1 && fr.step == 20 && fr.n == 1 && fr.x[0] == -1e-3 && fr.y[0] == 200 &&
					       !fr.has_r && isnan(fr.r[0]),
	      "got %d step %ld: %s", got, fr.step, e.msg);
	CHECK("dump.end", dump_next(&rd, &fr, &e) == 0, "%s", e.msg);
	dump_close(&rd);

	const char *bad[][2] = {
		{"truncated", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff pp\n0 1\n0 1\n0 1\n"
			      "ITEM: ATOMS id type x y\n1 1 0 0\n"},
		{"no_y_column", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff pp\n0 1\n0 1\n0 1\n"
				"ITEM: ATOMS id type x z\n1 1 0 0\n"},
		{"repeated_id", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff pp\n0 1\n0 1\n0 1\n"
				"ITEM: ATOMS id type x y\n1 1 0 0\n1 1 1 1\n"},
		{"bad_number", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff pp\n0 1\n0 1\n0 1\n"
			       "ITEM: ATOMS id type x y\n1 1 0 nan\n"},
	};
	for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
		write_file(p, bad[k][1]);
		char id[96];
		snprintf(id, sizeof id, "dump.refuses.%s", bad[k][0]);
		sb_err e2 = {0};
		int rc = dump_open(&rd, p, &e2) ? -2 : dump_next(&rd, &fr, &e2);
		CHECK(id, rc == -1 && strstr(e2.msg, "a.dump:"), "rc %d, message '%s'", rc, e2.msg);
		dump_close(&rd);
	}
	dump_frame_free(&fr);
	unlink(p);
}

static void test_crossing(void)
{
	/* surface 4, 4 lines at 0.5, 1.5, 2.5, 3.5; box [0, 8]: centre |x - 4| < 2 */
	double h[4];
	crossing_lines(4, 4, h);
	CHECK("crossing.lines", h[0] == 0.5 && h[1] == 1.5 && h[2] == 2.5 && h[3] == 3.5, "%g %g %g %g", h[0], h[1],
	      h[2], h[3]);
	/* disk 0: centre, 0.9 -> 3.1, up across 1.5 and 2.5;
	 * disk 1: centre, 2.5 -> 1.5 (starts on a line, ends on one): down across 2.5 only
	 *   (y < h <= yp);
	 * disk 2: outside (midpoint x 1), 1.5 -> 2.5: up across 2.5 only;
	 * disk 3: midpoint x exactly 2 = W/4 from the centre: outside; 0 -> 4 up across all;
	 * disk 4: centre, no motion */
	const double xp[] = {4, 3, 0.5, 1, 4}, yp[] = {0.9, 2.5, 1.5, 0, 2};
	const double x[] = {4, 5, 1.5, 3, 4}, y[] = {3.1, 1.5, 2.5, 4, 2};
	double jt[4] = {0}, jb[4] = {0};
	crossing_count(5, xp, yp, x, y, 0, 8, 4, 4, h, jt, jb);
	CHECK("crossing.centre", jt[0] == 0 && jt[1] == 1 && jt[2] == 0 && jt[3] == 0, "jtop %g %g %g %g", jt[0], jt[1],
	      jt[2], jt[3]);
	CHECK("crossing.outside", jb[0] == 1 && jb[1] == 1 && jb[2] == 2 && jb[3] == 1, "jbot %g %g %g %g", jb[0], jb[1],
	      jb[2], jb[3]);
}

/* a shell command's exit status */
static int run(const char *cmd)
{
	int rc = system(cmd);
	return rc == -1 ? -1 : WIFEXITED(rc) ? WEXITSTATUS(rc) : 128;
}

static void test_engine(const char *dir)
{
	const char *shake = getenv("SHAKE");
	if (!shake || !*shake)
		shake = access("build/san/bin/shake", X_OK) == 0 ? "build/san/bin/shake" : "bin/shake";
	if (access(shake, X_OK) || access("scripts/dump_lammps.sh", R_OK)) {
		CHECK("engine.setup", 0, "needs %s and scripts/dump_lammps.sh (run from the repository root)", shake);
		return;
	}
	/* 150 grains at 3 Hz, A = 2 cm: convection and crossings at every line; the fast
	 * preset's dt = 2e-4 s puts the samples a third of a step past k/f, so the box
	 * offset at the samples is not zero; the snapshots in double precision (the
	 * default single precision would move a disk by up to ~1e-6 of its height, and
	 * one that close to a line would cross it or not: the check is for exact equality) */
	char cmd[2048], run_h5[512], dump[512];
	snprintf(run_h5, sizeof run_h5, "%s/run.h5", dir);
	snprintf(dump, sizeof dump, "%s/run.dump", dir);
	snprintf(cmd, sizeof cmd,
		 "'%s' n_grains=150 width=30 radius_ratio=0 seed=3 preset=fast frequency=3 amplitude=2 duration=5 "
		 "flux=yes snapshots=yes snapshot_precision=double traj_rate=0 progress=no output='%s' >'%s/run.log' "
		 "2>&1 && "
		 "bash scripts/dump_lammps.sh '%s' >'%s' 2>'%s/dump.err'",
		 shake, run_h5, dir, run_h5, dump, dir);
	int rc = run(cmd);
	CHECK("engine.run_and_dump", rc == 0, "exit %d: %s", rc, cmd);
	if (rc)
		return;
	flux_data ref, d;
	sb_err e = {0};
	CHECK("engine.flux_read", flux_read(run_h5, &ref, &e) == 0, "%s", e.msg);
	if (e.code)
		return;
	dumpflux_opts o = {.surface = ref.surface, .nlines = (int)ref.L, .amplitude = 2, .frequency = 3, .dt = 2e-4};
	dumpflux_info info;
	rc = dumpflux_read(dump, &o, &d, &info, &e);
	CHECK("engine.dumpflux_read", rc == 0, "%s", e.msg);
	if (rc) {
		flux_free(&ref);
		return;
	}
	CHECK("engine.periods", d.P == ref.P && d.P == 15 && d.L == ref.L && info.frames == 16 && info.mobile == 150,
	      "dump: %zu periods x %zu lines (%ld frames, %ld mobile); engine %zu x %zu", d.P, d.L, info.frames,
	      info.mobile, ref.P, ref.L);
	size_t nd = 0, nz = 0;
	double tot = 0;
	for (size_t p = 0; p < d.P && p < ref.P; p++) {
		nd += d.t[p] != ref.t[p] || d.f[p] != ref.f[p];
		for (size_t l = 0; l < d.L && l < ref.L; l++) {
			nd += d.phi[p * d.L + l] != ref.phi[p * ref.L + l];
			nz += d.phi[p * d.L + l] != 0;
			tot += fabs(d.phi[p * d.L + l]);
		}
	}
	for (size_t l = 0; l < d.L && l < ref.L; l++)
		nd += d.h[l] != ref.h[l];
	CHECK("engine.flux_identical", nd == 0, "%zu values differ from the engine's /flux", nd);
	CHECK("engine.flux_not_trivial", nz > d.P * d.L / 4 && tot > 100, "%zu nonzero, sum |phi| %g", nz, tot);
	CHECK("engine.frame", info.wall_rest_dev == 0 && info.ybox_max > 1e-4 && info.x0 == 0 && info.x1 == 30,
	      "walls moved %g, largest box offset %g, faces %g %g", info.wall_rest_dev, info.ybox_max, info.x0, info.x1);
	flux_free(&d);

	/* the box offset matters: without it (A = 0: nothing taken off) some period differs */
	dumpflux_opts o0 = o;
	o0.amplitude = 0;
	if (dumpflux_read(dump, &o0, &d, &info, &e) == 0) {
		nd = 0;
		for (size_t p = 0; p < d.P && p < ref.P; p++)
			for (size_t l = 0; l < d.L; l++)
				nd += d.phi[p * d.L + l] != ref.phi[p * ref.L + l];
		CHECK("engine.box_offset_matters", nd > 0, "the lab-frame heights gave the same flux");
		flux_free(&d);
	} else
		CHECK("engine.box_offset_matters", 0, "%s", e.msg);

	/* a frame missing: refused, naming the frame */
	char cut[512];
	snprintf(cut, sizeof cut, "%s/cut.dump", dir);
	snprintf(cmd, sizeof cmd, "awk '/^ITEM: TIMESTEP/ { k++ } k != 4' '%s' >'%s'", dump, cut);
	sb_err e3 = {0};
	rc = run(cmd) ? -2 : dumpflux_read(cut, &o, &d, &info, &e3);
	CHECK("engine.missing_frame_refused", rc != 0 && strstr(e3.msg, "frame 3 is at step"), "rc %d: %s", rc, e3.msg);
	/* another dt: not the engine's schedule */
	dumpflux_opts o2 = o;
	o2.dt = 5e-5;
	sb_err e4 = {0};
	rc = dumpflux_read(dump, &o2, &d, &info, &e4);
	CHECK("engine.wrong_dt_refused", rc != 0 && strstr(e4.msg, "phase-0"), "rc %d: %s", rc, e4.msg);
	flux_free(&ref);
	snprintf(cmd, sizeof cmd, "rm -f '%s' '%s' '%s' '%s/run.log' '%s/dump.err' '%s/run.xmf'", run_h5, dump, cut, dir,
		 dir, dir);
	run(cmd);
}

static void test_compare(void)
{
	enum { N = 8, L = 3 };
	double a[N * L], b[N * L];
	/* line 0: a = b exactly (no crossings differ); line 1: a = b + 5 + small symmetric
	 * noise (a clear difference); line 2: a and b differ by noise of both signs */
	const double noise[N] = {0.1, -0.2, 0.15, -0.05, 0.3, -0.1, 0.05, -0.25};
	for (int i = 0; i < N; i++) {
		b[i * L + 0] = a[i * L + 0] = i;
		b[i * L + 1] = 10 + i;
		a[i * L + 1] = b[i * L + 1] + 5 + noise[i];
		b[i * L + 2] = 3;
		a[i * L + 2] = 3 + noise[i] * (i % 2 ? -1 : 1) * (i < 4 ? 1 : -1);
	}
	pd_result r;
	sb_err e = {0};
	CHECK("compare.ok", pd_compare(N, L, a, b, 0.95, &r, &e) == 0, "%s", e.msg);
	if (e.code)
		return;
	/* line 1: a's mean 13.5 + 5 + mean noise; its sd that of 0..7 = sqrt(6), t(7) = 2.3646 */
	double mn = 0;
	for (int i = 0; i < N; i++)
		mn += noise[i] / N;
	CHECK_REL("compare.mean_b", r.mb[1], 13.5, 1e-12);
	CHECK_REL("compare.half_b", r.hb[1], 2.364624251592785 * sqrt(6.0) / sqrt(8.0), 1e-9);
	CHECK_REL("compare.mean_diff", r.md[1], 5 + mn, 1e-12);
	CHECK("compare.line0_agrees_unused", r.agree[0] && r.md[0] == 0 && r.t[0] == 0, "agree %d md %g", r.agree[0],
	      r.md[0]);
	CHECK("compare.line1_disagrees", !r.agree[1] && r.t[1] > 10, "agree %d t %g", r.agree[1], r.t[1]);
	CHECK("compare.counts", r.ndis == 1 + !r.agree[2] && r.lines_used == 2, "ndis %d used %zu", r.ndis,
	      r.lines_used);
	/* a shift no sign pattern but the data's and its mirror reaches: p = 2/256 */
	CHECK("compare.sign_flip_exact", r.exact && r.perms == 256 && fabs(r.p_maxt - 2.0 / 256) < 1e-12,
	      "exact %d perms %ld p %g", r.exact, r.perms, r.p_maxt);
	pd_free(&r);
	/* identical profiles: nothing differs, p = 1 */
	CHECK("compare.same_ok", pd_compare(N, L, b, b, 0.95, &r, &e) == 0, "%s", e.msg);
	CHECK("compare.same", r.ndis == 0 && r.lines_used == 0 && r.p_maxt == 1 && r.p_chi2 == 1,
	      "ndis %d used %zu p %g %g", r.ndis, r.lines_used, r.p_maxt, r.p_chi2);
	pd_free(&r);
	/* pure noise on line 2 alone: not significant */
	double a2[N * L], b2[N * L];
	memcpy(a2, b, sizeof b);
	memcpy(b2, b, sizeof b);
	for (int i = 0; i < N; i++)
		a2[i * L + 2] = a[i * L + 2];
	CHECK("compare.noise_ok", pd_compare(N, L, a2, b2, 0.95, &r, &e) == 0, "%s", e.msg);
	CHECK("compare.noise_not_significant", r.p_maxt > 0.2 && r.lines_used == 1, "p %g used %zu", r.p_maxt,
	      r.lines_used);
	pd_free(&r);
	CHECK("compare.one_bed_refused", pd_compare(1, L, a, b, 0.95, &r, &e) != 0, "accepted");
}

int main(void)
{
	char dir[] = "/tmp/an_dumpflux_XXXXXX";
	if (!mkdtemp(dir)) {
		CHECK("setup.tmpdir", 0, "mkdtemp failed");
		return tl_done();
	}
	test_reader(dir);
	test_crossing();
	test_compare();
	test_engine(dir);
	rmdir(dir);
	return tl_done();
}
