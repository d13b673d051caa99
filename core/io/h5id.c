/* h5id.c - a run file's format, run id, attribute digest and seal (h5id.h). */
#include "h5id.h"
#include "h5read.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* An attribute of a run file holds names, messages or a few numbers; one of more
 * elements than this is no run file's. */
#define H5ID_MAX_ELEMS (1 << 20)

typedef struct dg {
	uint64_t h;
	int bad;         /* an attribute could not be read */
	char what[300];  /* ... which one */
} dg;

/* FNV-1a/64 (as params_hash): every change of a single byte changes the result. */
static void mix(dg *d, const void *p, size_t n)
{
	const unsigned char *b = p;
	for (size_t k = 0; k < n; k++) {
		d->h ^= b[k];
		d->h *= 1099511628211ULL;
	}
}

/* A number in 8 little-endian bytes, whatever this machine's order. */
static void mix_u64(dg *d, uint64_t v)
{
	unsigned char b[8];
	for (int k = 0; k < 8; k++)
		b[k] = (unsigned char)(v >> (8 * k));
	mix(d, b, 8);
}

/* The values of attribute a (n elements of file type t) in a form that does not
 * depend on this machine: integers as 64-bit, floats as doubles, strings up to their
 * end, anything else as the file's bytes. */
static int mix_values(dg *d, hid_t a, hid_t t, size_t n)
{
	const H5T_class_t c = H5Tget_class(t);
	const size_t ts = H5Tget_size(t);
	int rc = -1;
	if (c == H5T_STRING && H5Tis_variable_str(t) > 0) {
		char **s = calloc(n ? n : 1, sizeof *s);
		hid_t mt = H5Tcopy(H5T_C_S1);
		/* in the file's character set: HDF5 converts none into another (units are UTF-8) */
		if (s && mt >= 0 && H5Tset_size(mt, H5T_VARIABLE) >= 0 && H5Tset_cset(mt, H5Tget_cset(t)) >= 0 &&
		    H5Aread(a, mt, s) >= 0) {
			for (size_t k = 0; k < n; k++)
				mix(d, s[k] ? s[k] : "", s[k] ? strlen(s[k]) + 1 : 1);
			rc = 0;
		}
		for (size_t k = 0; s && k < n; k++)
			if (s[k])
				H5free_memory(s[k]);
		if (mt >= 0)
			H5Tclose(mt);
		free(s);
	} else if (c == H5T_INTEGER || c == H5T_FLOAT) {
		const int isint = c == H5T_INTEGER;
		uint64_t *v = malloc(sizeof *v * (n ? n : 1));
		if (v && H5Aread(a, isint ? H5T_NATIVE_LLONG : H5T_NATIVE_DOUBLE, v) >= 0) {
			for (size_t k = 0; k < n; k++)
				mix_u64(d, v[k]); /* a double's bits, or a long long's */
			rc = 0;
		}
		free(v);
	} else if (ts > 0 && n <= SIZE_MAX / ts) {
		unsigned char *v = malloc(n > 0 ? n * ts : 1);
		if (v && H5Aread(a, t, v) >= 0) {
			for (size_t k = 0; k < n; k++)
				mix(d, v + k * ts, c == H5T_STRING ? strnlen((char *)v + k * ts, ts) : ts);
			rc = 0;
		}
		free(v);
	}
	return rc;
}

typedef struct visit {
	dg *d;
	const char *obj;
} visit;

static herr_t one_attr(hid_t loc, const char *name, const H5A_info_t *info, void *data)
{
	(void)info;
	visit *v = data;
	dg *d = v->d;
	if (!strcmp(v->obj, ".") && !strcmp(name, H5ID_DIGEST_ATTR))
		return 0;
	hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
	hid_t t = a >= 0 ? H5Aget_type(a) : -1, sp = a >= 0 ? H5Aget_space(a) : -1;
	const hssize_t np = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
	int ok = a >= 0 && t >= 0 && np >= 0 && np <= H5ID_MAX_ELEMS;
	if (ok) {
		mix(d, v->obj, strlen(v->obj) + 1);
		mix(d, name, strlen(name) + 1);
		mix_u64(d, (uint64_t)H5Tget_class(t));
		mix_u64(d, (uint64_t)H5Tget_size(t));
		mix_u64(d, (uint64_t)np);
		ok = mix_values(d, a, t, (size_t)np) == 0;
	}
	if (!ok && !d->bad) {
		d->bad = 1;
		snprintf(d->what, sizeof d->what, "%s@%s", v->obj, name);
	}
	if (sp >= 0)
		H5Sclose(sp);
	if (t >= 0)
		H5Tclose(t);
	if (a >= 0)
		H5Aclose(a);
	return 0;
}

static herr_t one_object(hid_t f, const char *name, const H5O_info_t *info, void *data)
{
	(void)info;
	dg *d = data;
	hid_t o = H5Oopen(f, name, H5P_DEFAULT);
	if (o < 0) {
		if (!d->bad) {
			d->bad = 1;
			snprintf(d->what, sizeof d->what, "%s", name);
		}
		return 0;
	}
	visit v = {d, name};
	hsize_t ix = 0;
	if (H5Aiterate2(o, H5_INDEX_NAME, H5_ITER_INC, &ix, one_attr, &v) < 0 && !d->bad) {
		d->bad = 1;
		snprintf(d->what, sizeof d->what, "%s (its attributes)", name);
	}
	H5Oclose(o);
	return 0;
}

int h5id_digest(hid_t f, char out[17], sb_err *e)
{
	dg d = {1469598103934665603ULL, 0, ""};
	out[0] = 0;
	if (H5Ovisit2(f, H5_INDEX_NAME, H5_ITER_INC, one_object, &d, H5O_INFO_BASIC) < 0 && !d.bad)
		return sb_errf(e, SB_EIO, "cannot visit the file's objects");
	if (d.bad)
		return sb_errf(e, SB_EIO, "%s: cannot read it", d.what);
	snprintf(out, 17, "%016llx", (unsigned long long)d.h);
	return 0;
}

int h5id_seal(hid_t f, sb_err *e)
{
	char dgst[17];
	if (h5id_digest(f, dgst, e))
		return e->code;
	if (H5Aexists(f, H5ID_DIGEST_ATTR) > 0 && H5Adelete(f, H5ID_DIGEST_ATTR) < 0)
		return sb_errf(e, SB_EIO, "cannot replace the %s attribute", H5ID_DIGEST_ATTR);
	hid_t sp = H5Screate(H5S_SCALAR), t = H5Tcopy(H5T_C_S1);
	H5Tset_size(t, sizeof dgst);
	hid_t a = H5Acreate2(f, H5ID_DIGEST_ATTR, t, sp, H5P_DEFAULT, H5P_DEFAULT);
	int bad = a < 0 || H5Awrite(a, t, dgst) < 0;
	if (a >= 0 && H5Aclose(a) < 0)
		bad = 1;
	H5Tclose(t);
	H5Sclose(sp);
	return bad ? sb_errf(e, SB_EIO, "cannot write the %s attribute", H5ID_DIGEST_ATTR) : 0;
}

int h5id_check(hid_t f, const char *path, const char *want_id, int *note, sb_err *e)
{
	if (note)
		*note = H5ID_OK;
	char fmt[64], dgst[64], id[128], now[17];
	const int rf = h5r_attr_str(f, "/", H5ID_FORMAT_ATTR, fmt, sizeof fmt);
	if (rf)
		return sb_errf(e, SB_EIO, "%s: not a shakebox run file (%s)", path,
			       rf > 0 ? "no format attribute" : "its format attribute is not one string of at most 1 MiB");
	if (!strcmp(fmt, H5ID_FORMAT_OLD)) {
		/* written before run ids and digests: nothing to check it against */
		if (note)
			*note = H5ID_UNSEALED;
		return 0;
	}
	const int old3 = !strcmp(fmt, H5ID_FORMAT_OLD3);
	if (strcmp(fmt, H5ID_FORMAT) && !old3)
		return sb_errf(e, SB_EIO, "%s: format '%.40s', this version reads %s, %s and %s", path, fmt, H5ID_FORMAT,
			       H5ID_FORMAT_OLD3, H5ID_FORMAT_OLD);
	/* a file of this format is sealed: one without its user block had it stripped (and
	 * was never checked by h5r_open, which checks what is there) */
	hid_t cp = H5Fget_create_plist(f);
	hsize_t ub = 0;
	if (cp < 0 || H5Pget_userblock(cp, &ub) < 0)
		ub = 0;
	if (cp >= 0)
		H5Pclose(cp);
	if (!old3 && ub != H5ID_SEAL_BYTES)
		return sb_errf(e, SB_EIO, "%s: a %s file without its seal (a %llu-byte user block; the engine writes %d)",
			       path, H5ID_FORMAT, (unsigned long long)ub, H5ID_SEAL_BYTES);
	if (old3 && note)
		*note = H5ID_OLD3;
	const int rd = h5r_attr_str(f, "/", H5ID_DIGEST_ATTR, dgst, sizeof dgst);
	if (rd)
		return sb_errf(e, SB_EIO, "%s: %s", path,
			       rd > 0 ? "no digest attribute (a damaged " H5ID_FORMAT " file)"
				      : "its digest attribute is not one string");
	sb_err de = {0};
	if (h5id_digest(f, now, &de))
		return sb_errf(e, SB_EIO, "%s: digest: %s", path, de.msg);
	if (strcmp(now, dgst))
		return sb_errf(e, SB_EIO, "%s: attributes do not match their digest (%.20s recorded, %s now): the file "
			       "was changed after it was written", path, dgst, now);
	const int ri = h5r_attr_str(f, H5ID_RUN_OBJ, H5ID_RUN_ATTR, id, sizeof id);
	if (ri)
		return sb_errf(e, SB_EIO, "%s: %s", path, ri > 0 ? "no run id (" H5ID_RUN_OBJ "@" H5ID_RUN_ATTR ")"
							 : "its run id is not one string");
	if (want_id && strcmp(id, want_id))
		return sb_errf(e, SB_EIO, "%s: holds run '%.40s', not run '%.40s' (a file copied or linked into place)",
			       path, id[0] ? id : "(none: made outside a campaign)", want_id);
	return 0;
}

/* HDF5's format signature, at the start of its superblock. */
static const unsigned char H5SIG[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};

/* FNV-1a/64 over 8-byte little-endian words (eight times fewer multiplications than
 * over bytes: a run file of snapshots is hundreds of MB, and every reader hashes it):
 * each step is a bijection of the state for a given word, so any change within one
 * word changes the result. Reads fd from off to its end; *bytes is how many. */
static int hash_rest(int fd, off_t off, uint64_t *h, unsigned long long *bytes)
{
	enum { CHUNK = 1 << 20 };
	unsigned char *buf = malloc(CHUNK);
	if (!buf)
		return -1;
	uint64_t x = 1469598103934665603ULL;
	unsigned long long n = 0;
	size_t have = 0; /* bytes of a partial word carried into the next read */
	for (;;) {
		const ssize_t r = pread(fd, buf + have, CHUNK - have, off);
		if (r < 0 && errno == EINTR)
			continue;
		if (r < 0) {
			free(buf);
			return -1;
		}
		off += r;
		n += (unsigned long long)r;
		const size_t len = have + (size_t)r, whole = len / 8 * 8;
		for (size_t k = 0; k < whole; k += 8) {
			uint64_t w;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
			memcpy(&w, buf + k, 8); /* the bytes' little-endian value, in one load */
#else
			w = 0;
			for (int b = 7; b >= 0; b--)
				w = w << 8 | buf[k + (size_t)b];
#endif
			x ^= w;
			x *= 1099511628211ULL;
		}
		have = len - whole;
		memmove(buf, buf + whole, have);
		if (r == 0)
			break;
	}
	if (have) {
		uint64_t w = 0;
		for (size_t b = have; b-- > 0;)
			w = w << 8 | buf[b];
		x ^= w;
		x *= 1099511628211ULL;
	}
	x ^= n;
	x *= 1099511628211ULL;
	free(buf);
	*h = x;
	*bytes = n;
	return 0;
}

/* The seal's text for a hash and a byte count, zero-padded to the block's size. */
static void seal_text(unsigned char block[H5ID_SEAL_BYTES], uint64_t h, unsigned long long n)
{
	memset(block, 0, H5ID_SEAL_BYTES);
	snprintf((char *)block, H5ID_SEAL_BYTES, "shakebox-seal 1\nfnv1a64w %016llx\nbytes %llu\n", (unsigned long long)h,
		 n);
}

int h5id_file_seal(const char *path, sb_err *e)
{
	const int fd = open(path, O_RDWR | O_NOFOLLOW | O_CLOEXEC);
	if (fd < 0)
		return sb_errf(e, SB_EIO, "%s: cannot open to seal: %s", path, strerror(errno));
	unsigned char head[H5ID_SEAL_BYTES + sizeof H5SIG];
	uint64_t h;
	unsigned long long n;
	int rc = 0;
	if (pread(fd, head, sizeof head, 0) != (ssize_t)sizeof head ||
	    memcmp(head + H5ID_SEAL_BYTES, H5SIG, sizeof H5SIG))
		rc = sb_errf(e, SB_EIO, "%s: no HDF5 superblock after a %d-byte user block: cannot seal it", path,
			     H5ID_SEAL_BYTES);
	else if (hash_rest(fd, H5ID_SEAL_BYTES, &h, &n))
		rc = sb_errf(e, SB_EIO, "%s: cannot read it to seal it: %s", path, strerror(errno));
	else {
		unsigned char block[H5ID_SEAL_BYTES];
		seal_text(block, h, n);
		if (pwrite(fd, block, sizeof block, 0) != (ssize_t)sizeof block)
			rc = sb_errf(e, SB_EIO, "%s: cannot write its seal: %s", path, strerror(errno));
	}
	if (close(fd) && !rc)
		rc = sb_errf(e, SB_EIO, "%s: cannot write its seal: %s", path, strerror(errno));
	return rc;
}

int h5id_file_check(const char *path, char seal[17], sb_err *e)
{
	seal[0] = 0;
	/* O_NONBLOCK: a FIFO swapped in after the caller's check does not block the open */
	const int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
	if (fd < 0)
		return sb_errf(e, SB_EIO, "%s: cannot open: %s", path, strerror(errno));
	struct stat sb;
	unsigned char head[H5ID_SEAL_BYTES + sizeof H5SIG];
	int rc = 0;
	ssize_t got = 0;
	if (fstat(fd, &sb) || !S_ISREG(sb.st_mode))
		rc = sb_errf(e, SB_EIO, "%s: not a regular file", path);
	else if ((got = pread(fd, head, sizeof head, 0)) >= (ssize_t)sizeof H5SIG && !memcmp(head, H5SIG, sizeof H5SIG))
		; /* no user block: a file of an older format (h5id_check says which are read) */
	else if (got < (ssize_t)sizeof head || memcmp(head + H5ID_SEAL_BYTES, H5SIG, sizeof H5SIG))
		rc = sb_errf(e, SB_EIO, "%s: not a shakebox run file (no HDF5 signature at byte 0 or %d)", path,
			     H5ID_SEAL_BYTES);
	else {
		/* the block must be exactly a seal's text and zeros: nothing else hides there */
		unsigned long long h = 0, n = 0;
		unsigned char want[H5ID_SEAL_BYTES];
		uint64_t now;
		unsigned long long bytes;
		if (sscanf((const char *)head, "shakebox-seal 1\nfnv1a64w %16llx\nbytes %llu\n", &h, &n) != 2 ||
		    (seal_text(want, h, n), memcmp(want, head, H5ID_SEAL_BYTES)))
			rc = sb_errf(e, SB_EIO, "%s: its first %d bytes are no shakebox seal (a damaged or foreign file)",
				     path, H5ID_SEAL_BYTES);
		else if (hash_rest(fd, H5ID_SEAL_BYTES, &now, &bytes))
			rc = sb_errf(e, SB_EIO, "%s: cannot read it: %s", path, strerror(errno));
		else if (bytes != n || now != h)
			rc = sb_errf(e, SB_EIO, "%s: its bytes do not match its seal (%016llx of %llu bytes sealed, %016llx "
				     "of %llu now): the file was changed after the engine wrote it", path, h, n,
				     (unsigned long long)now, bytes);
		else
			snprintf(seal, 17, "%016llx", h);
	}
	close(fd);
	return rc;
}
