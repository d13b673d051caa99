/* fnv.h - FNV-1a/64, the one hash of shakebox's identities and seals: run ids and
 * cache keys (params.c), the checkpoint's checksum, the run file's digest (h5id.c) and
 * seal (h5seal.c), the database's row seal (lib/rowseal.c). Every change of a single
 * byte changes the result; it guards against accidents, not against an adversary.
 *
 * SB_FNV_BASIS is the project's offset basis since its first run id: the published
 * basis (14695981039346656037) with its last digit lost. It is kept, since every run id
 * and seal already written depends on it; the hash is as good with it. */
#ifndef SB_FNV_H
#define SB_FNV_H

#include <stddef.h>
#include <stdint.h>

#define SB_FNV_BASIS 1469598103934665603ULL
#define SB_FNV_PRIME 1099511628211ULL

/* h with the n bytes at p mixed in, one at a time */
static inline uint64_t sb_fnv(uint64_t h, const void *p, size_t n)
{
	const unsigned char *b = p;
	for (size_t k = 0; k < n; k++) {
		h ^= b[k];
		h *= SB_FNV_PRIME;
	}
	return h;
}

#endif
