/* h5read.c - reading run files (core/io/h5read.h): a dataset's shape is checked against
 * overflow and against the bytes the file holds before anything is allocated, an
 * attribute must be one value of the kind asked for, and a FIFO is refused at once. */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "h5read.h"
#include "h5seal.h"
#include "h5synth.h"
#include "testlib.h"

static char dir[] = "/tmp/sb_h5read_XXXXXX";

/* an unwritten dataset of a shape (contiguous, allocated late: the file holds none of
 * it), or chunked and deflated with its first chunk written */
static void claim(hid_t f, const char *name, int rank, const hsize_t *dims, int deflate)
{
	hid_t sp = H5Screate_simple(rank, dims, NULL), pl = H5Pcreate(H5P_DATASET_CREATE);
	if (deflate) {
		hsize_t c[3] = {1, 64, 64};
		H5Pset_chunk(pl, rank, c);
		H5Pset_deflate(pl, 9);
	}
	hid_t d = H5Dcreate2(f, name, H5T_IEEE_F64LE, sp, H5P_DEFAULT, pl, H5P_DEFAULT);
	if (deflate) { /* one chunk of zeros: a few bytes deflated */
		static double zero[64 * 64];
		hsize_t start[3] = {0, 0, 0}, count[3] = {1, 64, 64};
		hid_t ms = H5Screate_simple(3, count, NULL);
		H5Sselect_hyperslab(sp, H5S_SELECT_SET, start, NULL, count, NULL);
		H5Dwrite(d, H5T_NATIVE_DOUBLE, ms, sp, H5P_DEFAULT, zero);
		H5Sclose(ms);
	}
	H5Dclose(d);
	H5Pclose(pl);
	H5Sclose(sp);
}

static void attr_array(hid_t o, const char *name, hsize_t n)
{
	double v[64] = {0};
	hid_t sp = H5Screate_simple(1, &n, NULL);
	hid_t a = H5Acreate2(o, name, H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
	H5Awrite(a, H5T_NATIVE_DOUBLE, v);
	H5Aclose(a);
	H5Sclose(sp);
}

static void on_alarm(int sig)
{
	(void)sig;
	static const char m[] = "FAIL h5read.fifo.no_wait: the open of a FIFO still waits after 5 s\n";
	if (write(1, m, sizeof m - 1) < 0)
		_exit(2);
	_exit(1);
}

int main(void)
{
	if (!mkdtemp(dir)) {
		CHECK("h5read.setup", 0, "mkdtemp failed");
		return tl_done();
	}
	char path[256];
	snprintf(path, sizeof path, "%s/run.h5", dir);
	H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
	/* sealed as the engine seals a run file, and opened with its seal: a file no seal
	 * vouches for is walked first in a child process (h5read.c), and no test program
	 * forks, since qemu-user cannot on every host (docs/cross.md); that walk is
	 * tests/integration/hostile_runs.sh's (h5walk_crash.*) */
	hid_t cp = H5Pcreate(H5P_FILE_CREATE);
	H5Pset_userblock(cp, H5SEAL_BYTES);
	hid_t f = H5Fcreate(path, H5F_ACC_TRUNC, cp, H5P_DEFAULT);
	H5Pclose(cp);
	const double v[6] = {1, 2, 3, 4, 5, 6};
	const hsize_t d23[2] = {2, 3}, wrap[3] = {1, 4294967296ULL, 4294967296ULL}, big[2] = {3, 2147483648ULL},
		      zip[3] = {1, 65536, 65536};
	dset(f, "ok", 2, d23, v);
	claim(f, "wrap", 3, wrap, 0);
	claim(f, "unwritten", 2, big, 0);
	claim(f, "zipped", 3, zip, 1);
	attr_d(f, "one", 2.5);
	attr_d(f, "whole", 3);
	attr_d(f, "nan", NAN);
	attr_s(f, "text", "ok");
	attr_array(f, "array", 40);
	H5Fclose(f);

	sb_err e = {0};
	char seal[17] = "", got[17];
	CHECK("h5read.seal", !h5seal_write(path, &e) && !h5seal_check(path, seal, &e) && seal[0], "%s", e.msg);
	CHECK("h5read.open", h5r_open_sealed(path, seal, &f, got, &e) == 0 && !strcmp(got, seal), "%s", e.msg);
	double *p = NULL;
	int r = 0;
	size_t dims[3], n;
	e = (sb_err){0};
	CHECK("h5read.read.ok", h5r_read(f, "/ok", &p, &r, dims, &e) == 0 && r == 2 && dims[0] == 2 && dims[1] == 3 &&
		  dims[2] == 1 && p && p[5] == 6, "rc %d: %s", e.code, e.msg);
	free(p);
	/* (1, 2^32, 2^32): the count wrapped to 0, and 8 bytes stood for the shape */
	e = (sb_err){0};
	p = NULL;
	CHECK("h5read.read.count_wraps", h5r_read(f, "/wrap", &p, &r, dims, &e) == SB_EIO && !p &&
		  strstr(e.msg, "/wrap") && strstr(e.msg, "overflows"), "rc %d: %s", e.code, e.msg);
	size_t d8[8];
	e = (sb_err){0};
	CHECK("h5read.shape.count_wraps", h5r_shape(f, "/wrap", &r, d8, &n, &e) == SB_EIO && strstr(e.msg, "overflows"),
	      "%s", e.msg);
	/* 3 x 2^31 doubles (48 GiB) the file does not hold */
	e = (sb_err){0};
	CHECK("h5read.read.not_held", h5r_read(f, "/unwritten", &p, &r, dims, &e) == SB_EIO && !p &&
		  strstr(e.msg, "51539607552 bytes, but the file holds 0"), "%s", e.msg);
	/* 32 GiB claimed by a few hundred deflated bytes: more than deflate can give */
	e = (sb_err){0};
	CHECK("h5read.read.compressed_claim", h5r_read(f, "/zipped", &p, &r, dims, &e) == SB_EIO && !p &&
		  strstr(e.msg, "compressed bytes"), "%s", e.msg);
	/* attributes: one value of the kind asked for */
	double x = -1;
	long long k = -1;
	char s[16];
	CHECK("h5read.attr.num", h5r_attr_num(f, "/", "one", &x) == 0 && x == 2.5, "%g", x);
	CHECK("h5read.attr.missing", h5r_attr_num(f, "/", "none", &x) == 1 && x == 2.5, "%g", x);
	CHECK("h5read.attr.missing_object", h5r_attr_num(f, "/nowhere", "one", &x) == 1, "a missing object");
	x = -1;
	CHECK("h5read.attr.array_refused", h5r_attr_num(f, "/", "array", &x) == -1 && x == -1, "%g", x);
	CHECK("h5read.attr.string_is_no_number", h5r_attr_num(f, "/", "text", &x) == -1, "read as %g", x);
	CHECK("h5read.attr.nan_read_as_is", h5r_attr_num(f, "/", "nan", &x) == 0 && isnan(x), "%g", x);
	CHECK("h5read.attr.int_of_whole_float", h5r_attr_int(f, "/", "whole", &k) == 0 && k == 3, "%lld", k);
	CHECK("h5read.attr.int_of_fraction", h5r_attr_int(f, "/", "one", &k) == -1 && k == 3, "%lld", k);
	CHECK("h5read.attr.int_of_nan", h5r_attr_int(f, "/", "nan", &k) == -1, "%lld", k);
	CHECK("h5read.attr.str", h5r_attr_str(f, "/", "text", s, sizeof s) == 0 && !strcmp(s, "ok"), "'%s'", s);
	CHECK("h5read.attr.str_of_number", h5r_attr_str(f, "/", "one", s, sizeof s) == -1 && !s[0], "'%s'", s);
	CHECK("h5read.attr.str_of_array", h5r_attr_str(f, "/", "array", s, sizeof s) == -1, "'%s'", s);
	h5r_close(f);

	/* a FIFO: refused at once, no open that waits for a writer */
	char fifo[256];
	snprintf(fifo, sizeof fifo, "%s/run.fifo", dir);
	mkfifo(fifo, 0600);
	signal(SIGALRM, on_alarm);
	alarm(5);
	e = (sb_err){0};
	CHECK("h5read.fifo.refused", h5r_open(fifo, &f, &e) == SB_EIO && strstr(e.msg, "not a regular file") && f < 0,
	      "rc %d: %s", e.code, e.msg);
	alarm(0);
	e = (sb_err){0};
	CHECK("h5read.directory.refused", h5r_open(dir, &f, &e) == SB_EIO && strstr(e.msg, "is a directory"), "%s", e.msg);

	unlink(fifo);
	unlink(path);
	rmdir(dir);
	return tl_done();
}
