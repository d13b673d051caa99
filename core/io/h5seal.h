/* h5seal.h - the seal over all of a run file's bytes, checked before HDF5 parses one
 * (docs/inputs.md, "Run files"): the engine seals a file with h5seal_write once HDF5
 * has closed it; h5r_open checks it with h5seal_check. The digest of the attributes and
 * the run's identity, which need HDF5 to read, are h5id.h's. */
#ifndef SB_H5SEAL_H
#define SB_H5SEAL_H

#include "err.h"

/* The seal: HDF5's user block, the file's first H5SEAL_BYTES bytes (HDF5 then
 * finds its superblock right after it), holds the text
 *   "shakebox-seal 1\nfnv1a64w HEX16\nbytes N\n"
 * and zeros: HEX16 the hash of every byte after the block (FNV-1a/64 over 8-byte
 * little-endian words, the last one padded with zeros, then N mixed in), N their count.
 * Written after HDF5 closed the file; a reader checks it before HDF5 reads anything. */
#define H5SEAL_BYTES 512

/* Writes the seal into the user block of the closed HDF5 file at path (made with a
 * user block of H5SEAL_BYTES). */
int h5seal_write(const char *path, sb_err *e);

/* Checks the seal of the file at path (a regular file) before anything parses it:
 * seal holds its 16 hex digits, or "" when the file has no user block (an older file:
 * HDF5's signature at byte 0). SB_EIO, naming path, when the user block is no seal,
 * the bytes after it do not hash to it (a bit flipped, a value edited), or HDF5's
 * signature is at neither place. */
int h5seal_check(const char *path, char seal[17], sb_err *e);

#endif
