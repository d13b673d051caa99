/* h5seal.c - the seal over a run file's bytes (h5seal.h). */
#include "h5seal.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fnv.h"

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
	uint64_t x = SB_FNV_BASIS;
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
			x *= SB_FNV_PRIME;
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
		x *= SB_FNV_PRIME;
	}
	x ^= n;
	x *= SB_FNV_PRIME;
	free(buf);
	*h = x;
	*bytes = n;
	return 0;
}

/* The seal's text for a hash and a byte count, zero-padded to the block's size. */
static void seal_text(unsigned char block[H5SEAL_BYTES], uint64_t h, unsigned long long n)
{
	memset(block, 0, H5SEAL_BYTES);
	snprintf((char *)block, H5SEAL_BYTES, "shakebox-seal 1\nfnv1a64w %016llx\nbytes %llu\n", (unsigned long long)h,
		 n);
}

int h5seal_write(const char *path, sb_err *e)
{
	const int fd = open(path, O_RDWR | O_NOFOLLOW | O_CLOEXEC);
	if (fd < 0)
		return sb_errf(e, SB_EIO, "%s: cannot open to seal: %s", path, strerror(errno));
	unsigned char head[H5SEAL_BYTES + sizeof H5SIG];
	uint64_t h;
	unsigned long long n;
	int rc = 0;
	if (pread(fd, head, sizeof head, 0) != (ssize_t)sizeof head ||
	    memcmp(head + H5SEAL_BYTES, H5SIG, sizeof H5SIG))
		rc = sb_errf(e, SB_EIO, "%s: no HDF5 superblock after a %d-byte user block: cannot seal it", path,
			     H5SEAL_BYTES);
	else if (hash_rest(fd, H5SEAL_BYTES, &h, &n))
		rc = sb_errf(e, SB_EIO, "%s: cannot read it to seal it: %s", path, strerror(errno));
	else {
		unsigned char block[H5SEAL_BYTES];
		seal_text(block, h, n);
		if (pwrite(fd, block, sizeof block, 0) != (ssize_t)sizeof block)
			rc = sb_errf(e, SB_EIO, "%s: cannot write its seal: %s", path, strerror(errno));
	}
	if (close(fd) && !rc)
		rc = sb_errf(e, SB_EIO, "%s: cannot write its seal: %s", path, strerror(errno));
	return rc;
}

int h5seal_check(const char *path, char seal[17], sb_err *e)
{
	seal[0] = 0;
	/* O_NONBLOCK: a FIFO swapped in after the caller's check does not block the open */
	const int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
	if (fd < 0)
		return sb_errf(e, SB_EIO, "%s: cannot open: %s", path, strerror(errno));
	struct stat sb;
	unsigned char head[H5SEAL_BYTES + sizeof H5SIG];
	int rc = 0;
	ssize_t got = 0;
	if (fstat(fd, &sb) || !S_ISREG(sb.st_mode))
		rc = sb_errf(e, SB_EIO, "%s: not a regular file", path);
	else if ((got = pread(fd, head, sizeof head, 0)) >= (ssize_t)sizeof H5SIG && !memcmp(head, H5SIG, sizeof H5SIG))
		; /* no user block: a file of an older format (h5id_check says which are read) */
	else if (got < (ssize_t)sizeof head || memcmp(head + H5SEAL_BYTES, H5SIG, sizeof H5SIG))
		rc = sb_errf(e, SB_EIO, "%s: not a shakebox run file (no HDF5 signature at byte 0 or %d)", path,
			     H5SEAL_BYTES);
	else {
		/* the block must be exactly a seal's text and zeros: nothing else hides there */
		unsigned long long h = 0, n = 0;
		unsigned char want[H5SEAL_BYTES];
		uint64_t now;
		unsigned long long bytes;
		if (sscanf((const char *)head, "shakebox-seal 1\nfnv1a64w %16llx\nbytes %llu\n", &h, &n) != 2 ||
		    (seal_text(want, h, n), memcmp(want, head, H5SEAL_BYTES)))
			rc = sb_errf(e, SB_EIO, "%s: its first %d bytes are no shakebox seal (a damaged or foreign file)",
				     path, H5SEAL_BYTES);
		else if (hash_rest(fd, H5SEAL_BYTES, &now, &bytes))
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
