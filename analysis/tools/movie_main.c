/* movie_main.c - bin/movie: a run file's snapshots as a movie (MP4 or GIF). Each frame
 * is drawn here (common/raster.h: the disks to scale, the intruder marked, the walls
 * where the box was, time and drive phase stamped, optionally coloured by speed) and
 * handed as raw RGB to ffmpeg, which encodes it; the movie is written under a
 * temporary name beside its place and renamed there only when ffmpeg succeeded
 * (docs/output.md, "Movies"). Only this file prints and exits. */
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "clock.h"
#include "fsutil.h"
#include "h5read.h"
#include "provenance.h"
#include "common/raster.h"

extern char **environ;

static const char *HELP =
	"usage: movie RUN.h5 [-o OUT.mp4|OUT.gif|OUT.png] [--color kind|speed] [--fps N] [--width PX]\n"
	"             [--from T] [--to T] [--speed-max V] [--full] [--no-progress]\n"
	"\n"
	"Draws a run file's snapshots as a movie: every disk to scale (grains grey or by\n"
	"speed, the intruder red, the wall disks dark), time, drive phase and frequency\n"
	"stamped on each frame; encoded by ffmpeg (H.264 in MP4, or a GIF with its own\n"
	"palette). A snapshot is a frame: snapshots = yes takes one per drive period, at phase\n"
	"0 (the stroboscopic view: the box stands still, the bed moves by what a period\n"
	"changed); snapshots_per_period = N (e.g. 12) shows the motion within each period.\n"
	"\n"
	"  -o FILE          the movie (.mp4 or .gif; default: RUN's name with .mp4, in the\n"
	"                   current directory), or .png: one picture, the first frame drawn\n"
	"                   (--from T picks it); written whole or not at all\n"
	"  --color kind     grains grey, the intruder red (default)\n"
	"  --color speed    every mobile disk by its speed in the box frame, |v - v_box|, on a\n"
	"                   scale from 0 to --speed-max (default: the 95th percentile of the\n"
	"                   speeds of the frames drawn; printed), drawn as a bar on the frame\n"
	"  --fps N          frames per second of the movie (default 10; 1 to 120)\n"
	"  --width PX       frame width in pixels (default 640; 64 to 4096); the height follows\n"
	"                   the box's aspect\n"
	"  --from T, --to T only the snapshots at times in [T_from, T_to] (s)\n"
	"  --full           the whole height of the side walls (default: up to a tenth of the\n"
	"                   box's width above the highest disk of any frame drawn)\n"
	"  --no-progress    no progress line on stderr\n"
	"\n"
	"Needs ffmpeg (Debian package ffmpeg; make deps installs it). Exit codes: 0 written,\n"
	"1 usage or a run file without snapshots, 2 the run file unreadable, 3 ffmpeg failed.\n";

static int usage(const char *msg)
{
	fprintf(stderr, "movie: %s\n(movie --help for the usage)\n", msg);
	return 1;
}

/* a number option's value in [lo, hi], or -1 with the message */
static int num_arg(const char *opt, const char *s, double lo, double hi, double *v)
{
	char *end;
	errno = 0;
	const double x = s ? strtod(s, &end) : NAN;
	if (!s || end == s || *end || errno || !(x >= lo && x <= hi)) {
		fprintf(stderr, "movie: %s: expected a number in [%g, %g], got '%s'\n(movie --help for the usage)\n", opt, lo,
			hi, s ? s : "");
		return -1;
	}
	*v = x;
	return 0;
}

typedef struct run {
	size_t K, nm, nw;
	double *pos, *vel, *t, *off, *offv; /* [K][nm][2], [K][nm][2], [K], [K][2], [K][2] */
	double *r, *species, *wpos, *wr, *wsnap; /* [nm], [nm], [nw][2], [nw], [K][nw][2] or NULL */
	double freq, amp;
	char ramp[32];
} run;

static void run_free(run *R)
{
	free(R->pos), free(R->vel), free(R->t), free(R->off), free(R->offv);
	free(R->r), free(R->species), free(R->wpos), free(R->wr), free(R->wsnap);
}

/* a dataset of the shape asked for (a dims entry 0: any), or an error naming it */
static int rd(hid_t f, const char *file, const char *path, double **d, int rank, size_t d0, size_t d1, size_t d2,
	      sb_err *e)
{
	int rk;
	size_t dims[3];
	if (h5r_read(f, path, d, &rk, dims, e))
		return e->code;
	const size_t want[3] = {d0, d1, d2};
	for (int k = 0; k < rank; k++)
		if (rk != rank || (want[k] && dims[k] != want[k])) {
			free(*d);
			*d = NULL;
			return sb_errf(e, SB_EIO, "%s: %s: not of the shape a run file has", file, path);
		}
	return 0;
}

static int run_read(const char *file, run *R, sb_err *e)
{
	hid_t f;
	if (fs_check_input(file, "run file", SB_EIO, e) || h5r_open(file, &f, e))
		return e->code;
	int rc = 0;
	if (!h5r_exists(f, "/particles/bed/position/value")) {
		h5r_close(f);
		return sb_errf(e, SB_EUSAGE, "%s: the run has no snapshots (run it with snapshots = yes; "
					     "snapshots_per_period = N for the motion within a period)", file);
	}
	int rk;
	size_t dims[8], count;
	if (h5r_shape(f, "/particles/bed/position/value", &rk, dims, &count, e) || rk != 3 || dims[2] != 2) {
		h5r_close(f);
		return e->code ? e->code : sb_errf(e, SB_EIO, "%s: /particles/bed/position/value: not [K x n x 2]", file);
	}
	R->K = dims[0], R->nm = dims[1];
	if (!rc)
		rc = rd(f, file, "/particles/bed/position/value", &R->pos, 3, R->K, R->nm, 2, e);
	if (!rc)
		rc = rd(f, file, "/particles/bed/velocity/value", &R->vel, 3, R->K, R->nm, 2, e);
	if (!rc)
		rc = rd(f, file, "/particles/bed/position/time", &R->t, 1, R->K, 0, 0, e);
	if (!rc)
		rc = rd(f, file, "/particles/bed/box/offset/value", &R->off, 2, R->K, 2, 0, e);
	if (!rc)
		rc = rd(f, file, "/particles/bed/box/offset_velocity/value", &R->offv, 2, R->K, 2, 0, e);
	if (!rc)
		rc = rd(f, file, "/particles/bed/radius", &R->r, 1, R->nm, 0, 0, e);
	if (!rc)
		rc = rd(f, file, "/particles/bed/species", &R->species, 1, R->nm, 0, 0, e);
	if (!rc && h5r_exists(f, "/particles/walls/position")) {
		rc = rd(f, file, "/particles/walls/position", &R->wpos, 2, 0, 2, 0, e);
		if (!rc) {
			if (h5r_shape(f, "/particles/walls/position", &rk, dims, &count, e))
				rc = e->code;
			R->nw = dims[0];
		}
		if (!rc)
			rc = rd(f, file, "/particles/walls/radius", &R->wr, 1, R->nw, 0, 0, e);
		if (!rc && h5r_exists(f, "/particles/walls/snapshot_position/value"))
			rc = rd(f, file, "/particles/walls/snapshot_position/value", &R->wsnap, 3, R->K, R->nw, 2, e);
	}
	if (!rc && (h5r_attr_num(f, "/parameters", "frequency", &R->freq) ||
		    h5r_attr_num(f, "/parameters", "amplitude", &R->amp) ||
		    h5r_attr_str(f, "/parameters", "ramp", R->ramp, sizeof R->ramp)))
		rc = sb_errf(e, SB_EIO, "%s: /parameters lacks frequency, amplitude or ramp", file);
	h5r_close(f);
	return rc;
}

/* ffmpeg reading raw RGB frames on its stdin and writing out (a temporary name) */
typedef struct enc {
	pid_t pid;
	FILE *in;
} enc;

static int enc_start(enc *E, int w, int h, double fps, int gif, int png, const char *out, sb_err *e)
{
	int p[2];
	if (pipe(p))
		return sb_errf(e, SB_EIO, "cannot make a pipe: %s", strerror(errno));
	char size[32], rate[32];
	snprintf(size, sizeof size, "%dx%d", w, h);
	snprintf(rate, sizeof rate, "%g", fps);
	char *mp4[] = {"ffmpeg", "-hide_banner", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt",
		       "rgb24", "-s", size, "-framerate", rate, "-i", "pipe:0", "-c:v", "libx264", "-pix_fmt",
		       "yuv420p", "-movflags", "+faststart", "-f", "mp4", "-y", (char *)out, NULL};
	char *pngv[] = {"ffmpeg", "-hide_banner", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s",
			size, "-i", "pipe:0", "-frames:v", "1", "-c:v", "png", "-f", "image2", "-update", "1", "-y",
			(char *)out, NULL};
	char *gifv[] = {"ffmpeg", "-hide_banner", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s",
			size, "-framerate", rate, "-i", "pipe:0", "-filter_complex",
			"[0:v]split[a][b];[a]palettegen=stats_mode=diff[p];[b][p]paletteuse", "-f", "gif", "-y",
			(char *)out, NULL};
	posix_spawn_file_actions_t fa;
	posix_spawn_file_actions_init(&fa);
	posix_spawn_file_actions_adddup2(&fa, p[0], 0);
	posix_spawn_file_actions_addclose(&fa, p[1]);
	posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", 0, 0);
	const int rc = posix_spawnp(&E->pid, "ffmpeg", &fa, NULL, png ? pngv : gif ? gifv : mp4, environ);
	posix_spawn_file_actions_destroy(&fa);
	close(p[0]);
	if (rc) {
		close(p[1]);
		return sb_errf(e, SB_EIO, "cannot run ffmpeg: %s (Debian package ffmpeg; make deps installs it)",
			       strerror(rc));
	}
	E->in = fdopen(p[1], "wb");
	if (!E->in) {
		close(p[1]);
		kill(E->pid, SIGTERM);
		waitpid(E->pid, NULL, 0);
		return sb_errf(e, SB_EIO, "cannot write to ffmpeg: %s", strerror(errno));
	}
	return 0;
}

static int enc_end(enc *E, int ok, sb_err *e)
{
	if (E->in && fclose(E->in) && ok)
		ok = 0;
	int st = 0;
	while (waitpid(E->pid, &st, 0) < 0 && errno == EINTR)
		;
	if (!(WIFEXITED(st) && WEXITSTATUS(st) == 0))
		return sb_errf(e, SB_EIO, "ffmpeg failed (%s %d; its message above)",
			       WIFEXITED(st) ? "exit" : "signal", WIFEXITED(st) ? WEXITSTATUS(st) : WTERMSIG(st));
	return ok ? 0 : sb_errf(e, SB_EIO, "writing the frames to ffmpeg failed");
}

static int cmp_d(const void *a, const void *b)
{
	const double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* the speed of mobile disk i in frame k, in the box frame */
static double speed(const run *R, size_t k, size_t i)
{
	const double *v = R->vel + 2 * (k * R->nm + i);
	return hypot(v[0] - R->offv[2 * k], v[1] - R->offv[2 * k + 1]);
}

int main(int argc, char **argv)
{
	if (argc >= 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
		fputs(HELP, stdout);
		return 0;
	}
	if (argc == 2 && !strcmp(argv[1], "--version")) {
		printf("movie (%s)\n", prov_version());
		return 0;
	}
	const char *file = NULL, *out = NULL;
	int by_speed = 0, progress = 1, full = 0;
	double fps = 10, width = 640, from = -INFINITY, to = INFINITY, vmax = 0;
	for (int k = 1; k < argc; k++) {
		const char *a = argv[k], *v = k + 1 < argc ? argv[k + 1] : NULL;
		if (!strcmp(a, "-o")) {
			if (!v || !*v)
				return usage("-o: which file?");
			out = v, k++;
		} else if (!strcmp(a, "--color")) {
			if (!v || (strcmp(v, "kind") && strcmp(v, "speed")))
				return usage("--color: kind or speed");
			by_speed = !strcmp(v, "speed"), k++;
		} else if (!strcmp(a, "--fps")) {
			if (num_arg(a, v, 1, 120, &fps))
				return 1;
			k++;
		} else if (!strcmp(a, "--width")) {
			if (num_arg(a, v, 64, 4096, &width))
				return 1;
			k++;
		} else if (!strcmp(a, "--from") || !strcmp(a, "--to")) {
			if (num_arg(a, v, 0, 1e12, a[2] == 'f' ? &from : &to))
				return 1;
			k++;
		} else if (!strcmp(a, "--speed-max")) {
			if (num_arg(a, v, 1e-9, 1e9, &vmax))
				return 1;
			k++;
		} else if (!strcmp(a, "--full")) {
			full = 1;
		} else if (!strcmp(a, "--no-progress")) {
			progress = 0;
		} else if (a[0] == '-' && a[1]) {
			fprintf(stderr, "movie: unknown option '%s'\n(movie --help for the usage)\n", a);
			return 1;
		} else if (file) {
			return usage("one run file at a time");
		} else {
			file = a;
		}
	}
	if (!file)
		return usage("which run file?");
	if (from > to)
		return usage("--from is after --to");
	/* the movie's name and kind */
	char defname[4200];
	if (!out) {
		const char *b = strrchr(file, '/');
		b = b ? b + 1 : file;
		size_t l = strlen(b);
		if (l > 3 && !strcmp(b + l - 3, ".h5"))
			l -= 3;
		snprintf(defname, sizeof defname, "%.*s.mp4", (int)l, b);
		out = defname;
	}
	const size_t lo = strlen(out);
	const int gif = lo > 4 && !strcmp(out + lo - 4, ".gif"), png = lo > 4 && !strcmp(out + lo - 4, ".png");
	if (!gif && !png && !(lo > 4 && !strcmp(out + lo - 4, ".mp4")))
		return usage("-o: the movie's name ends in .mp4 or .gif (or .png: the first frame drawn, a picture)");
	const char *kind;
	if (!fs_replaceable(out, &kind)) {
		fprintf(stderr, "movie: %s: %s stands there; only a regular file is replaced\n", out, kind);
		return 1;
	}
	sb_err e = {0};
	if (h5r_walk_env(&e))
		return usage(e.msg);
	run R = {0};
	if (run_read(file, &R, &e)) {
		fprintf(stderr, "movie: %s\n", e.msg);
		run_free(&R);
		return e.code == SB_EUSAGE ? 1 : 2;
	}
	/* the frames drawn */
	size_t k0 = 0, k1 = R.K;
	while (k0 < R.K && R.t[k0] < from)
		k0++;
	while (k1 > k0 && R.t[k1 - 1] > to)
		k1--;
	if (png && k1 > k0) /* a picture: the first frame drawn */
		k1 = k0 + 1;
	if (k1 == k0) {
		fprintf(stderr, "movie: %s: no snapshot in the times asked for (%zu snapshots, t = %g to %g s)\n", file,
			R.K, R.K ? R.t[0] : 0.0, R.K ? R.t[R.K - 1] : 0.0);
		run_free(&R);
		return 1;
	}
	/* the view: every disk of every frame drawn, the walls where the box went */
	double xl = INFINITY, xh = -INFINITY, yl = INFINITY, yh = -INFINITY;
	for (size_t k = k0; k < k1; k++) {
		for (size_t i = 0; i < R.nm; i++) {
			const double *p = R.pos + 2 * (k * R.nm + i);
			if (!isfinite(p[0]) || !isfinite(p[1]))
				continue;
			xl = fmin(xl, p[0] - R.r[i]), xh = fmax(xh, p[0] + R.r[i]);
			yl = fmin(yl, p[1] - R.r[i]), yh = fmax(yh, p[1] + R.r[i]);
		}
		for (size_t i = 0; i < R.nw; i++) {
			const double *p = R.wsnap ? R.wsnap + 2 * (k * R.nw + i) : R.wpos + 2 * i;
			const double dy = R.wsnap ? 0 : R.off[2 * k + 1];
			xl = fmin(xl, p[0] - R.wr[i]), xh = fmax(xh, p[0] + R.wr[i]);
			yl = fmin(yl, p[1] + dy - R.wr[i]);
			if (full)
				yh = fmax(yh, p[1] + dy + R.wr[i]);
		}
	}
	if (!full) /* the walls' empty upper part left out: a tenth of the width above the bed */
		yh += 0.1 * (xh - xl);
	if (!(xh > xl && yh > yl)) {
		fprintf(stderr, "movie: %s: no finite position to draw\n", file);
		run_free(&R);
		return 2;
	}
	const int band = by_speed ? 46 : 28; /* the stamps' strip at the top, pixels (and the scale's) */
	const double pad = 0.02 * (xh - xl), scale = (width - 2) / (xh - xl + 2 * pad);
	const int W = (int)width, H = (int)ceil((yh - yl + 2 * pad) * scale) + band;
	if ((double)W * H > 4096.0 * 4096.0) {
		fprintf(stderr, "movie: %s: a frame of %d x %d pixels is too large (--width smaller)\n", file, W, H);
		run_free(&R);
		return 1;
	}
	if (by_speed && vmax <= 0) { /* the 95th percentile of the speeds drawn */
		const size_t n = (k1 - k0) * R.nm;
		double *s = malloc(sizeof(double) * (n ? n : 1));
		size_t m = 0;
		for (size_t k = k0; s && k < k1; k++)
			for (size_t i = 0; i < R.nm; i++) {
				const double v = speed(&R, k, i);
				if (isfinite(v))
					s[m++] = v;
			}
		if (s && m) {
			qsort(s, m, sizeof *s, cmp_d);
			vmax = s[(size_t)floor(0.95 * (double)(m - 1))];
		}
		free(s);
		if (!(vmax > 0))
			vmax = 1;
	}
	rs_frame F;
	if (rs_init(&F, W, H, xl - pad, yl - pad, scale)) {
		fprintf(stderr, "movie: out of memory for a frame of %d x %d pixels\n", W, H);
		run_free(&R);
		return 2;
	}
	char tmp[4300];
	fs_tmp_name(out, tmp, sizeof tmp);
	fprintf(stderr, "movie: %s: %zu frames (t = %.3f to %.3f s) of %zu disks and %zu wall disks, %d x %d pixels, %g fps%s -> %s\n",
		file, k1 - k0, R.t[k0], R.t[k1 - 1], R.nm, R.nw, F.w, F.h, fps, by_speed ? ", coloured by speed" : "", out);
	if (by_speed)
		fprintf(stderr, "movie: speed scale 0 to %.4g cm/s (box frame)%s\n", vmax,
			" - the 95th percentile of the frames' speeds unless --speed-max");
	enc E = {0};
	if (enc_start(&E, F.w, F.h, fps, gif, png, tmp, &e)) {
		fprintf(stderr, "movie: %s\n", e.msg);
		rs_free(&F);
		run_free(&R);
		return 3;
	}
	/* a writer that dies (ffmpeg gone) must not kill us: the error is said instead */
	signal(SIGPIPE, SIG_IGN);
	const rs_rgb white = {255, 255, 255}, grain = {150, 150, 150}, intr = {205, 30, 30}, wall = {60, 60, 60},
		     ink = {0, 0, 0};
	const int constant = !strcmp(R.ramp, "none") && R.freq > 0;
	double last = sb_now();
	int ok = 1;
	for (size_t k = k0; k < k1 && ok; k++) {
		rs_clear(&F, white);
		for (size_t i = 0; i < R.nw; i++) {
			const double *p = R.wsnap ? R.wsnap + 2 * (k * R.nw + i) : R.wpos + 2 * i;
			rs_disk(&F, p[0], p[1] + (R.wsnap ? 0 : R.off[2 * k + 1]), R.wr[i], wall);
		}
		for (int pass = 0; pass < 2; pass++) /* the intruder on top */
			for (size_t i = 0; i < R.nm; i++) {
				const int is_intr = R.species[i] == 1;
				if (is_intr != pass)
					continue;
				const double *p = R.pos + 2 * (k * R.nm + i);
				if (by_speed) {
					rs_disk(&F, p[0], p[1], R.r[i], is_intr ? ink : rs_scale(speed(&R, k, i) / vmax));
					if (is_intr) /* a ring of black round its speed's colour */
						rs_disk(&F, p[0], p[1], 0.8 * R.r[i], rs_scale(speed(&R, k, i) / vmax));
				} else {
					rs_disk(&F, p[0], p[1], R.r[i], is_intr ? intr : grain);
				}
			}
		char stamp[160];
		if (constant) {
			/* the drive's phase in periods, [0, 1): f t less its whole periods (a
			 * snapshot a rounding below a whole period is at phase 0) */
			double ph = R.freq * R.t[k] - floor(R.freq * R.t[k]);
			if (ph > 1 - 1e-6)
				ph = 0;
			snprintf(stamp, sizeof stamp, "t = %.3f s   phase %.2f   f = %.2f Hz  A = %.2f cm", R.t[k], ph,
				 R.freq, R.amp);
		} else {
			snprintf(stamp, sizeof stamp, "t = %.3f s   ramp (phase not stamped)   A = %.2f cm", R.t[k], R.amp);
		}
		rs_rect(&F, 0, 0, F.w, band, white);
		/* the stamp at twice the font's size where it fits */
		rs_text(&F, 6, 7, rs_text_width(stamp, 2) + 12 <= F.w ? 2 : 1, stamp, ink);
		if (by_speed) { /* the scale below it: a bar with its two ends */
			char hi[64];
			snprintf(hi, sizeof hi, "%.3g cm/s (speed, box frame)", vmax);
			const int bw = 120, bx = 18;
			rs_text(&F, 6, 30, 1, "0", ink);
			for (int x = 0; x < bw; x++)
				rs_rect(&F, bx + x, 28, 1, 11, rs_scale((x + 0.5) / bw));
			rs_text(&F, bx + bw + 6, 30, 1, hi, ink);
		}
		if (fwrite(F.rgb, 3, (size_t)F.w * (size_t)F.h, E.in) != (size_t)F.w * (size_t)F.h)
			ok = 0;
		const double w = sb_now();
		if (progress && (w - last >= 1.0 || k + 1 == k1)) {
			fprintf(stderr, "\rmovie: frame %zu of %zu", k - k0 + 1, k1 - k0);
			if (k + 1 == k1)
				fputc('\n', stderr);
			last = w;
		}
	}
	rs_free(&F);
	run_free(&R);
	if (enc_end(&E, ok, &e)) {
		unlink(tmp);
		fprintf(stderr, "movie: %s: %s\n", out, e.msg);
		return 3;
	}
	if (fs_fsync_path(tmp, &e) || fs_rename_durable(tmp, out, &e)) {
		unlink(tmp);
		fprintf(stderr, "movie: %s\n", e.msg);
		return 2;
	}
	printf("%s\n", out);
	return 0;
}
