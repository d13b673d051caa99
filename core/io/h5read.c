/* h5read.c - attributes and datasets of run files, checked before use (h5read.h). */
#include "h5read.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "fsutil.h"
#include "h5md.h"
#include "h5seal.h"

/* A filtered (compressed) chunk holds at most this many times its stored bytes:
 * deflate, the engine's filter, packs at most 1032:1 (zlib's technical notes), and
 * shuffle packs nothing (docs/inputs.md, "Run files"). */
#define H5R_MAX_RATIO 1100
/* The longest fixed-length string attribute read: run files hold names and messages. */
#define H5R_STR_MAX (1 << 20)

/* Every attribute of an object read whole, in its file type: what a reader's digest
 * and attribute reads will touch (the child's memory is never freed: it exits). */
static herr_t walk_attr(hid_t o, const char *name, const H5A_info_t *info, void *data)
{
	(void)info;
	(void)data;
	const hid_t a = H5Aopen(o, name, H5P_DEFAULT);
	const hid_t t = a >= 0 ? H5Aget_type(a) : -1;
	const hsize_t n = a >= 0 ? H5Aget_storage_size(a) : 0;
	if (t >= 0 && n > 0 && n <= H5R_STR_MAX * (hsize_t)16) {
		/* a variable-length element is a pointer in memory, no larger than its
		 * 16-byte reference in the file */
		void *buf = calloc(1, (size_t)n + 64);
		if (buf)
			H5Aread(a, t, buf);
	}
	return 0;
}

static herr_t walk_object(hid_t f, const char *name, const H5O_info_t *info, void *data)
{
	(void)info;
	(void)data;
	const hid_t o = H5Oopen(f, name, H5P_DEFAULT);
	if (o >= 0)
		H5Aiterate2(o, H5_INDEX_NAME, H5_ITER_INC, NULL, walk_attr, NULL);
	return 0;
}

/* HDF5 1.10 walks a damaged link table with less care than a hostile file needs: 38
 * bytes of 0xff in a dense group's link messages, the file sealed again, made H5Lvisit
 * free a wild pointer (docs/inputs.md, "Run files"). The seal's byte check cannot see
 * such a file (its hand re-sealed it), and HDF5 is not ours to fix, so the first walk
 * over every link, object and attribute (each read whole) runs in a child process: a
 * crash there refuses the file instead of taking the reader with it, and the reader's
 * own walk afterwards (h5r_contained, the digest) goes through the same bytes. */
/* The time limit of the walk, s: WALK_ENV when set (a number in [0.1, 3600], else -1),
 * WALK_SECONDS when not. */
#define WALK_ENV "SHAKEBOX_H5_WALK_SECONDS"
#define WALK_SECONDS 5.0
static double walk_limit(void)
{
	const char *v = getenv(WALK_ENV);
	if (!v)
		return WALK_SECONDS;
	char *end;
	const double s = strtod(v, &end);
	return *v && !*end && s >= 0.1 && s <= 3600 ? s : -1;
}

int h5r_walk_env(sb_err *e)
{
	if (walk_limit() < 0)
		return sb_errf(e, SB_EUSAGE, WALK_ENV " = '%s': expected a number of seconds in [0.1, 3600]", getenv(WALK_ENV));
	return 0;
}

static int walk_isolated(const char *path, sb_err *e)
{
	const double limit = walk_limit();
	if (h5r_walk_env(e))
		return e->code;
	int fd[2];
	if (pipe(fd))
		return sb_errf(e, SB_EIO, "%s: cannot check the file's structure: pipe: %s", path, strerror(errno));
	const pid_t pid = fork();
	if (pid < 0) {
		const int er = errno;
		close(fd[0]);
		close(fd[1]);
		return sb_errf(e, SB_EIO, "%s: cannot check the file's structure: fork: %s", path, strerror(er));
	}
	if (pid == 0) {
		/* the child says only its verdict: HDF5's or a sanitizer's report of the fault
		 * would be noise beside the reader's refusal; _exit runs no handler of the
		 * reader's (no stdio flush, no leak check of a half-walked library) */
		close(fd[0]);
		const int null = open("/dev/null", O_WRONLY);
		if (null >= 0)
			dup2(null, 2);
		sb_err ce = {0, ""};
		const hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
		char why[256] = "";
		if (f < 0)
			h5w_last_error(why, sizeof why);
		int rc = f < 0 ? sb_errf(&ce, SB_EIO, "%s: cannot open HDF5 file%s%s", path, why[0] ? ": " : "", why)
			       : h5r_contained(f, path, &ce);
		if (!rc && H5Ovisit2(f, H5_INDEX_NAME, H5_ITER_INC, walk_object, NULL, H5O_INFO_ALL) < 0)
			rc = sb_errf(&ce, SB_EIO, "%s: cannot visit the file's objects", path);
		if (rc) {
			const size_t n = strlen(ce.msg);
			if (write(fd[1], ce.msg, n) != (ssize_t)n)
				_exit(4);
		}
		_exit(rc ? 3 : 0);
	}
	close(fd[1]);
	/* HDF5 can also loop forever on a damaged structure (make fuzz, run-file input 1047
	 * of seed 31: 37 bytes zeroed): the walk gets a time limit, far above a run file's
	 * (milliseconds: it reads the links and attributes, not the data) */
	struct timespec t0, t;
	clock_gettime(CLOCK_MONOTONIC, &t0);
	char msg[sizeof e->msg] = "";
	size_t got = 0;
	int late = 0;
	for (;;) {
		clock_gettime(CLOCK_MONOTONIC, &t);
		const double left = limit - (double)(t.tv_sec - t0.tv_sec) - 1e-9 * (double)(t.tv_nsec - t0.tv_nsec);
		struct pollfd p = {fd[0], POLLIN, 0};
		const int n = left > 0 ? poll(&p, 1, (int)(left * 1000) + 1) : 0;
		if (n < 0 && errno == EINTR)
			continue;
		if (n == 0) {
			late = 1;
			break;
		}
		const ssize_t r = read(fd[0], msg + got, sizeof msg - 1 - got);
		if (r > 0 && (got += (size_t)r) < sizeof msg - 1)
			continue;
		if (r < 0 && errno == EINTR)
			continue;
		break;
	}
	msg[got] = 0;
	close(fd[0]);
	if (late) {
		kill(pid, SIGKILL);
		while (waitpid(pid, NULL, 0) < 0 && errno == EINTR)
			;
		return sb_errf(e, SB_EIO, "%s: the HDF5 library did not finish walking the file's links and objects within "
			       "%g s (a loop on a damaged structure; " WALK_ENV " allows more on a slow file system): its "
			       "structure is damaged", path, limit);
	}
	int st = 0;
	while (waitpid(pid, &st, 0) < 0)
		if (errno != EINTR)
			return sb_errf(e, SB_EIO, "%s: cannot check the file's structure: waitpid: %s", path, strerror(errno));
	if (WIFEXITED(st) && WEXITSTATUS(st) == 0)
		return 0;
	if (WIFEXITED(st) && WEXITSTATUS(st) == 3 && got)
		return sb_errf(e, SB_EIO, "%s", msg);
	char how[64];
	if (WIFSIGNALED(st))
		snprintf(how, sizeof how, "signal %d, %s", WTERMSIG(st), strsignal(WTERMSIG(st)));
	else
		snprintf(how, sizeof how, "exit %d", WIFEXITED(st) ? WEXITSTATUS(st) : -1);
	return sb_errf(e, SB_EIO, "%s: the HDF5 library failed while walking the file's links and objects (%s): its "
		       "structure is damaged", path, how);
}

int h5r_open_sealed(const char *path, const char *want_seal, hid_t *f, char seal[17], sb_err *e)
{
	*f = -1;
	seal[0] = 0;
	H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
	if (fs_check_input(path, "run file", SB_EIO, e))
		return e->code;
	/* HDF5 parses what it reads with less care than a hostile file needs (a flipped
	 * bit in its global heap ran strlen past a buffer): the bytes are checked first */
	if (h5seal_check(path, seal, e))
		return e->code;
	if (want_seal && want_seal[0] && strcmp(seal, want_seal))
		return sb_errf(e, SB_EIO, "%s: sealed %s, but the database recorded %.16s when the run was done: not "
			       "the file the engine wrote for it (copied, replaced, or edited and sealed again)", path,
			       seal[0] ? seal : "not at all (an older format)", want_seal);
	/* bytes that match the seal the driver recorded are the engine's own: no need to
	 * prove HDF5 can walk them */
	if (!(want_seal && want_seal[0]) && walk_isolated(path, e))
		return e->code;
	*f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
	if (*f < 0) {
		char why[256] = "";
		h5w_last_error(why, sizeof why); /* HDF5's word: not HDF5, a lock held, ... */
		return sb_errf(e, SB_EIO, "%s: cannot open HDF5 file%s%s", path, why[0] ? ": " : "", why);
	}
	if (h5r_contained(*f, path, e)) {
		H5Fclose(*f);
		*f = -1;
		return e->code;
	}
	return 0;
}

int h5r_open(const char *path, hid_t *f, sb_err *e)
{
	char seal[17];
	return h5r_open_sealed(path, NULL, f, seal, e);
}

typedef struct cctx {
	const char *path;
	sb_err *e;
	int err;
} cctx;

static herr_t contained_link(hid_t g, const char *name, const H5L_info_t *info, void *data)
{
	cctx *c = data;
	if (info->type == H5L_TYPE_HARD)
		return 0;
	char val[512] = "";
	const char *file = NULL, *obj = NULL;
	if (info->type != H5L_TYPE_ERROR && info->u.val_size > 0 && info->u.val_size <= sizeof val &&
	    H5Lget_val(g, name, val, sizeof val, H5P_DEFAULT) >= 0) {
		val[sizeof val - 1] = 0;
		unsigned flags;
		if (info->type == H5L_TYPE_EXTERNAL && H5Lunpack_elink_val(val, info->u.val_size, &flags, &file, &obj) < 0)
			file = obj = NULL;
	}
	if (info->type == H5L_TYPE_EXTERNAL)
		c->err = sb_errf(c->e, SB_EIO, "%s: /%s is an external link (to %.200s:%.200s): a run file holds only its "
				 "own objects", c->path, name, file ? file : "?", obj ? obj : "?");
	else if (info->type == H5L_TYPE_SOFT)
		c->err = sb_errf(c->e, SB_EIO, "%s: /%s is a soft link (to %.200s): a run file holds only hard links",
				 c->path, name, val);
	else
		c->err = sb_errf(c->e, SB_EIO, "%s: /%s is a link of user-defined type %d: a run file holds only hard "
				 "links", c->path, name, (int)info->type);
	return 1;
}

/* Is dataset path of f virtual itself (or no dataset at all)? Its layout is read from
 * its creation properties: opening a virtual dataset does not resolve its sources. */
static int source_virtual(hid_t f, const char *path)
{
	const hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
	const hid_t pl = d >= 0 ? H5Dget_create_plist(d) : -1;
	const int virt = pl < 0 || H5Pget_layout(pl) == H5D_VIRTUAL;
	if (pl >= 0)
		H5Pclose(pl);
	if (d >= 0)
		H5Dclose(d);
	return virt;
}

static herr_t contained_object(hid_t f, const char *name, const H5O_info_t *info, void *data)
{
	cctx *c = data;
	if (info->type != H5O_TYPE_DATASET)
		return 0;
	hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
	hid_t pl = d >= 0 ? H5Dget_create_plist(d) : -1;
	if (pl < 0) {
		c->err = sb_errf(c->e, SB_EIO, "%s: /%s: cannot open dataset", c->path, name);
	} else if (H5Pget_external_count(pl) != 0) {
		char ext[256] = "?";
		off_t off;
		hsize_t size;
		if (H5Pget_external(pl, 0, sizeof ext, ext, &off, &size) < 0)
			snprintf(ext, sizeof ext, "?");
		c->err = sb_errf(c->e, SB_EIO, "%s: /%s keeps its data in another file (%.200s): a run file holds its own "
				 "data", c->path, name, ext);
	} else if (H5Pget_layout(pl) == H5D_VIRTUAL) {
		size_t n = 0;
		if (H5Pget_virtual_count(pl, &n) < 0)
			c->err = sb_errf(c->e, SB_EIO, "%s: /%s: cannot read its virtual mappings", c->path, name);
		for (size_t k = 0; k < n && !c->err; k++) {
			char src[256] = "", dset[512] = "";
			const ssize_t ls = H5Pget_virtual_filename(pl, k, src, sizeof src);
			const ssize_t ld = H5Pget_virtual_dsetname(pl, k, dset, sizeof dset);
			if (ls < 0 || ld < 0 || (size_t)ls >= sizeof src || (size_t)ld >= sizeof dset)
				c->err = sb_errf(c->e, SB_EIO, "%s: /%s: cannot read its virtual mapping %zu", c->path, name, k);
			else if (strcmp(src, "."))
				c->err = sb_errf(c->e, SB_EIO, "%s: /%s is a virtual dataset of another file (%.200s:%.200s): a "
						 "run file's are views of its own datasets", c->path, name, src, dset);
			else if (!h5r_exists(f, dset))
				c->err = sb_errf(c->e, SB_EIO, "%s: /%s is a virtual dataset of %.200s, which the file does not "
						 "hold", c->path, name, dset);
			else if (source_virtual(f, dset))
				/* a view of a view may be a view of itself: HDF5 1.10.8 resolves such a
				 * circle by recursing until the stack is gone (make fuzz, links) */
				c->err = sb_errf(c->e, SB_EIO, "%s: /%s is a virtual dataset of %.200s, itself virtual (or not a "
						 "dataset): a run file's views are of its stored datasets", c->path, name, dset);
		}
	}
	if (pl >= 0)
		H5Pclose(pl);
	if (d >= 0)
		H5Dclose(d);
	return c->err ? 1 : 0;
}

int h5r_contained(hid_t f, const char *path, sb_err *e)
{
	cctx c = {path, e, 0};
	/* links first: H5Ovisit does not follow external or soft links, so what they point
	 * at would pass unseen, and opening it is what must not happen */
	if (H5Lvisit(f, H5_INDEX_NAME, H5_ITER_INC, contained_link, &c) < 0 && !c.err)
		return sb_errf(e, SB_EIO, "%s: cannot visit the file's links", path);
	if (c.err)
		return c.err;
	if (H5Ovisit2(f, H5_INDEX_NAME, H5_ITER_INC, contained_object, &c, H5O_INFO_BASIC) < 0 && !c.err)
		return sb_errf(e, SB_EIO, "%s: cannot visit the file's objects", path);
	return c.err;
}

void h5r_close(hid_t f)
{
	if (f >= 0)
		H5Fclose(f);
}

int h5r_exists(hid_t f, const char *path)
{
	/* every prefix must exist for H5Lexists to answer without an error */
	char buf[512];
	if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf)
		return 0;
	for (char *p = buf + 1; *p; p++) {
		if (*p != '/')
			continue;
		*p = 0;
		if (H5Lexists(f, buf, H5P_DEFAULT) <= 0)
			return 0;
		*p = '/';
	}
	return H5Lexists(f, buf, H5P_DEFAULT) > 0;
}

/* The attribute when it is there (0, *a open), 1 when missing, -1 when it is not one
 * value: H5Aread writes every element of an array attribute, and the callers have room
 * for one. */
static int attr_open(hid_t f, const char *obj, const char *name, hid_t *a)
{
	if (H5Aexists_by_name(f, obj, name, H5P_DEFAULT) <= 0)
		return 1;
	*a = H5Aopen_by_name(f, obj, name, H5P_DEFAULT, H5P_DEFAULT);
	if (*a < 0)
		return -1;
	hid_t sp = H5Aget_space(*a);
	const hssize_t np = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
	if (sp >= 0)
		H5Sclose(sp);
	if (np != 1) {
		H5Aclose(*a);
		return -1;
	}
	return 0;
}

static H5T_class_t attr_class(hid_t a)
{
	hid_t t = H5Aget_type(a);
	const H5T_class_t c = t >= 0 ? H5Tget_class(t) : H5T_NO_CLASS;
	if (t >= 0)
		H5Tclose(t);
	return c;
}

int h5r_attr_num(hid_t f, const char *obj, const char *name, double *v)
{
	hid_t a;
	int rc = attr_open(f, obj, name, &a);
	if (rc)
		return rc;
	const H5T_class_t c = attr_class(a);
	double x;
	rc = (c != H5T_INTEGER && c != H5T_FLOAT) || H5Aread(a, H5T_NATIVE_DOUBLE, &x) < 0 ? -1 : 0;
	H5Aclose(a);
	if (!rc)
		*v = x;
	return rc;
}

int h5r_attr_int(hid_t f, const char *obj, const char *name, long long *v)
{
	hid_t a;
	int rc = attr_open(f, obj, name, &a);
	if (rc)
		return rc;
	const H5T_class_t c = attr_class(a);
	long long x = 0;
	double d;
	if (c == H5T_INTEGER)
		rc = H5Aread(a, H5T_NATIVE_LLONG, &x) < 0 ? -1 : 0;
	else if (c == H5T_FLOAT && H5Aread(a, H5T_NATIVE_DOUBLE, &d) >= 0 && d == (double)(long long)d &&
		 d >= -9.2e18 && d <= 9.2e18)
		x = (long long)d;
	else
		rc = -1;
	H5Aclose(a);
	if (!rc)
		*v = x;
	return rc;
}

int h5r_attr_str(hid_t f, const char *obj, const char *name, char *buf, size_t len)
{
	buf[0] = 0;
	hid_t a;
	int rc = attr_open(f, obj, name, &a);
	if (rc)
		return rc;
	hid_t t = H5Aget_type(a);
	rc = -1;
	if (t >= 0 && H5Tget_class(t) == H5T_STRING && H5Tis_variable_str(t) > 0) {
		/* variable length, as other tools write them */
		hid_t mt = H5Tcopy(H5T_C_S1);
		char *p = NULL;
		if (mt >= 0 && H5Tset_size(mt, H5T_VARIABLE) >= 0 && H5Aread(a, mt, &p) >= 0 && p) {
			snprintf(buf, len, "%s", p);
			rc = 0;
		}
		if (p)
			H5free_memory(p);
		if (mt >= 0)
			H5Tclose(mt);
	} else if (t >= 0 && H5Tget_class(t) == H5T_STRING) {
		const size_t n = H5Tget_size(t);
		char *tmp = n && n <= H5R_STR_MAX ? calloc(n + 1, 1) : NULL;
		if (tmp && H5Aread(a, t, tmp) >= 0) {
			snprintf(buf, len, "%s", tmp);
			rc = 0;
		}
		free(tmp);
	}
	if (t >= 0)
		H5Tclose(t);
	H5Aclose(a);
	return rc;
}

/* The bytes this machine has: no dataset can be read into more. */
static size_t memory_bytes(void)
{
	const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
	if (pages <= 0 || size <= 0)
		return SIZE_MAX / 2;
	return (size_t)pages > SIZE_MAX / (size_t)size ? SIZE_MAX : (size_t)pages * (size_t)size;
}

/* "(1, 4294967296, 4294967296)" */
static void shape_text(const hsize_t *hd, int r, char *buf, size_t len)
{
	size_t l = (size_t)snprintf(buf, len, "(");
	for (int k = 0; k < r && l < len; k++)
		l += (size_t)snprintf(buf + l, len - l, "%s%llu", k ? ", " : "", (unsigned long long)hd[k]);
	if (l < len)
		snprintf(buf + l, len - l, ")");
}

/* Whether a chunked dataset's filters may store fewer bytes than its data has: any
 * filter but shuffle (a permutation) and Fletcher32 (4 bytes more per chunk). */
static int compressed(hid_t pl)
{
	const int nf = H5Pget_nfilters(pl);
	for (int k = 0; k < nf; k++) {
		unsigned flags, cd[8];
		size_t ncd = 8;
		const H5Z_filter_t id = H5Pget_filter2(pl, (unsigned)k, &flags, &ncd, cd, 0, NULL, NULL);
		if (id != H5Z_FILTER_SHUFFLE && id != H5Z_FILTER_FLETCHER32)
			return 1;
	}
	return 0;
}

/* HDF5 found a chunk whose Fletcher32 checksum does not match its bytes. */
static herr_t is_checksum(unsigned n, const H5E_error2_t *err, void *data)
{
	(void)n;
	if (err->desc && strstr(err->desc, "Fletcher32"))
		*(int *)data = 1;
	return 0;
}

/* Why a read failed, from HDF5's error stack: call it before any other HDF5 call,
 * which would clear the stack. */
static int read_failed(const char *path, sb_err *e)
{
	int sum = 0;
	H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, is_checksum, &sum);
	if (sum)
		return sb_errf(e, SB_EIO, "%s: checksum error (Fletcher32): the stored data changed after it was "
			       "written", path);
	return sb_errf(e, SB_EIO, "%s: cannot read dataset", path);
}

/* A dataset's shape and element count, checked before anything is allocated for it:
 * a product of dimensions wraps (2^32 x 2^32 is 0 in 64 bits) and a shape is only a
 * claim, so the count must not overflow in elements nor in bytes (of the file's type
 * and of doubles), and the file must hold the bytes it claims: all of them for
 * contiguous, compact and unfiltered chunked storage, 1/H5R_MAX_RATIO of them for
 * compressed chunks; and the doubles must fit in this machine's memory. */
static int shape_of(hid_t d, const char *path, int maxrank, int *rank, size_t *dims, size_t *count, sb_err *e)
{
	hid_t sp = H5Dget_space(d), t = H5Dget_type(d), pl = H5Dget_create_plist(d);
	hsize_t hd[8] = {0};
	const int r = sp >= 0 ? H5Sget_simple_extent_ndims(sp) : -1;
	int err = 0;
	char shape[200] = "";
	if (r < 0 || t < 0 || pl < 0)
		err = sb_errf(e, SB_EIO, "%s: cannot read its shape", path);
	else if (r > maxrank)
		err = sb_errf(e, SB_EIO, "%s: rank %d (at most %d)", path, r, maxrank);
	else if (H5Sget_simple_extent_dims(sp, hd, NULL) < 0)
		err = sb_errf(e, SB_EIO, "%s: cannot read its shape", path);
	size_t n = 1;
	if (!err) {
		shape_text(hd, r, shape, sizeof shape);
		for (int k = 0; k < r && !err; k++) {
			if (hd[k] > SIZE_MAX || (hd[k] && n > SIZE_MAX / (size_t)hd[k]))
				err = sb_errf(e, SB_EIO, "%s: shape %s: its element count overflows", path, shape);
			else
				n *= (size_t)hd[k];
		}
		if (!err && H5Sget_simple_extent_type(sp) == H5S_NULL)
			n = 0;
	}
	const size_t ts = !err ? H5Tget_size(t) : 0;
	if (!err && !ts)
		err = sb_errf(e, SB_EIO, "%s: cannot read its type", path);
	if (!err && (n > SIZE_MAX / ts || n > SIZE_MAX / sizeof(double)))
		err = sb_errf(e, SB_EIO, "%s: shape %s of %zu-byte elements: its size in bytes overflows", path, shape,
			      ts);
	if (!err) {
		const unsigned long long need = (unsigned long long)n * ts;
		const unsigned long long held = H5Dget_storage_size(d);
		const H5D_layout_t lay = H5Pget_layout(pl);
		const int filtered = lay == H5D_CHUNKED && compressed(pl);
		if ((lay == H5D_CONTIGUOUS || lay == H5D_COMPACT || (lay == H5D_CHUNKED && !filtered)) && held < need)
			err = sb_errf(e, SB_EIO, "%s: shape %s of %zu-byte elements is %llu bytes, but the file holds %llu "
				      "for it", path, shape, ts, need, held);
		else if (filtered && held < (need + H5R_MAX_RATIO - 1) / H5R_MAX_RATIO)
			err = sb_errf(e, SB_EIO, "%s: shape %s of %zu-byte elements is %llu bytes, more than the %llu "
				      "compressed bytes the file holds for it can give (at most %d:1)", path, shape, ts,
				      need, held, H5R_MAX_RATIO);
		else if (n > memory_bytes() / sizeof(double))
			err = sb_errf(e, SB_EIO, "%s: shape %s: %zu values, more than this machine's memory holds", path,
				      shape, n);
	}
	if (pl >= 0)
		H5Pclose(pl);
	if (t >= 0)
		H5Tclose(t);
	if (sp >= 0)
		H5Sclose(sp);
	if (err)
		return err;
	*rank = r;
	for (int k = 0; k < maxrank; k++)
		dims[k] = k < r ? (size_t)hd[k] : 1;
	*count = n;
	return 0;
}

int h5r_shape(hid_t f, const char *path, int *rank, size_t dims[8], size_t *count, sb_err *e)
{
	if (!h5r_exists(f, path))
		return sb_errf(e, SB_EIO, "%s: no such dataset", path);
	hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
	if (d < 0)
		return sb_errf(e, SB_EIO, "%s: cannot open dataset", path);
	const int rc = shape_of(d, path, 8, rank, dims, count, e);
	H5Dclose(d);
	return rc;
}

int h5r_read(hid_t f, const char *path, double **data, int *rank, size_t dims[3], sb_err *e)
{
	*data = NULL;
	*rank = 0;
	dims[0] = dims[1] = dims[2] = 1;
	if (!h5r_exists(f, path))
		return sb_errf(e, SB_EIO, "%s: no such dataset", path);
	hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
	if (d < 0)
		return sb_errf(e, SB_EIO, "%s: cannot open dataset", path);
	size_t n, dd[3];
	int r;
	if (shape_of(d, path, 3, &r, dd, &n, e)) {
		H5Dclose(d);
		return e->code;
	}
	double *p = malloc(sizeof *p * (n ? n : 1));
	const int bad = !p || (n && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, p) < 0);
	if (bad) {
		const int nomem = !p;
		free(p);
		const int rc = nomem ? sb_errf(e, SB_ENOMEM, "%s: out of memory for %zu values", path, n)
				     : read_failed(path, e);
		H5Dclose(d);
		return rc;
	}
	H5Dclose(d);
	memcpy(dims, dd, sizeof dd);
	*data = p;
	*rank = r;
	return 0;
}

/* One dataset's every chunk, read a block of first-dimension rows at a time in its own
 * type: HDF5 verifies each chunk's Fletcher32 checksum on the way. */
static int verify_dataset(hid_t d, const char *path, sb_err *e)
{
	hid_t pl = H5Dget_create_plist(d), sp = H5Dget_space(d), t = H5Dget_type(d);
	hid_t mt = t >= 0 ? H5Tget_native_type(t, H5T_DIR_DEFAULT) : -1;
	int err = 0, sum = 0;
	const int nf = pl >= 0 ? H5Pget_nfilters(pl) : 0;
	for (int k = 0; k < nf; k++) {
		unsigned flags, cd[8];
		size_t ncd = 8;
		if (H5Pget_filter2(pl, (unsigned)k, &flags, &ncd, cd, 0, NULL, NULL) == H5Z_FILTER_FLETCHER32)
			sum = 1;
	}
	hsize_t dims[8], chunk[8];
	const int r = sp >= 0 ? H5Sget_simple_extent_ndims(sp) : -1;
	if (!sum || pl < 0 || sp < 0 || mt < 0 || r < 1 || r > 8 || H5Pget_layout(pl) != H5D_CHUNKED)
		goto done; /* nothing to verify (old files, a virtual dataset): the reads check what they read */
	if (H5Sget_simple_extent_dims(sp, dims, NULL) < 0 || H5Pget_chunk(pl, r, chunk) != r) {
		err = sb_errf(e, SB_EIO, "%s: cannot read its shape", path);
		goto done;
	}
	size_t row = H5Tget_size(mt);
	for (int k = 1; k < r; k++)
		row *= (size_t)dims[k];
	/* shape_of has held dims to what the file holds and this machine's memory; a block
	 * is one chunk's rows, at most all of them */
	const hsize_t blk = chunk[0] < 1 ? 1 : chunk[0] < dims[0] ? chunk[0] : dims[0];
	void *buf = malloc(row > 0 ? row * (size_t)blk : 1);
	if (!buf) {
		err = sb_errf(e, SB_ENOMEM, "%s: out of memory", path);
		goto done;
	}
	for (hsize_t at = 0; at < dims[0] && !err; at += blk) {
		hsize_t start[8] = {0}, cnt[8];
		start[0] = at;
		cnt[0] = dims[0] - at < blk ? dims[0] - at : blk;
		for (int k = 1; k < r; k++)
			cnt[k] = dims[k];
		hid_t ms = H5Screate_simple(r, cnt, NULL);
		if (ms < 0 || H5Sselect_hyperslab(sp, H5S_SELECT_SET, start, NULL, cnt, NULL) < 0 ||
		    H5Dread(d, mt, ms, sp, H5P_DEFAULT, buf) < 0)
			err = read_failed(path, e);
		if (ms >= 0)
			H5Sclose(ms);
	}
	free(buf);
done:
	if (mt >= 0)
		H5Tclose(mt);
	if (t >= 0)
		H5Tclose(t);
	if (sp >= 0)
		H5Sclose(sp);
	if (pl >= 0)
		H5Pclose(pl);
	return err;
}

typedef struct vctx {
	sb_err *e;
	int err;
} vctx;

static herr_t verify_one(hid_t f, const char *name, const H5O_info_t *info, void *data)
{
	vctx *v = data;
	if (info->type != H5O_TYPE_DATASET)
		return 0;
	char path[512];
	snprintf(path, sizeof path, "/%s", name);
	hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
	if (d < 0) {
		v->err = sb_errf(v->e, SB_EIO, "%s: cannot open dataset", path);
		return 1;
	}
	int rank;
	size_t dims[8], n;
	v->err = shape_of(d, path, 8, &rank, dims, &n, v->e);
	if (!v->err && n > 0)
		v->err = verify_dataset(d, path, v->e);
	H5Dclose(d);
	return v->err ? 1 : 0;
}

int h5r_verify(hid_t f, sb_err *e)
{
	vctx v = {e, 0};
	if (H5Ovisit2(f, H5_INDEX_NAME, H5_ITER_INC, verify_one, &v, H5O_INFO_BASIC) < 0 && !v.err)
		return sb_errf(e, SB_EIO, "cannot visit the file's objects");
	return v.err;
}
