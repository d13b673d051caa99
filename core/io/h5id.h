/* h5id.h - a run file's identity: the format it declares, the run it claims to be and
 * a digest of its attributes (docs/inputs.md, "Run files"). The engine digests a file
 * with h5id_seal as the last thing it writes into it (and then seals its bytes:
 * h5seal.h); the readers check the rest with h5id_check, after h5r_open checked the
 * seal, before they believe a value of it. */
#ifndef SB_H5ID_H
#define SB_H5ID_H

#include <hdf5.h>
#include <stddef.h>

#include "err.h"

/* The root attribute naming the file's layout, and the layout this engine writes.
 * shakebox-run-3 added the run id and the digest, shakebox-run-4 the seal of the whole
 * file; files of the older formats are read with a note (docs/inputs.md, "Run files"):
 * run-3 with its attributes' digest checked, run-2 unchecked. */
#define H5ID_FORMAT_ATTR "format"
#define H5ID_FORMAT "shakebox-run-4"
#define H5ID_FORMAT_OLD3 "shakebox-run-3"
#define H5ID_FORMAT_OLD "shakebox-run-2"

/* Where the run's id sits: the scene key run_id (set by the study driver's worker for
 * every run, the campaign's id of the run; "" for a run outside a campaign), recorded
 * like every key as an attribute of /parameters. */
#define H5ID_RUN_OBJ "/parameters"
#define H5ID_RUN_ATTR "run_id"

/* The root attribute holding the digest: 16 hex digits of FNV-1a/64 over every
 * attribute of every object in the file (its object's path, its name, its type class
 * and size, its values), objects and attributes in name order, itself left out. */
#define H5ID_DIGEST_ATTR "digest"

/* The digest of the attributes of open file f as 16 hex digits (out holds 17). */
int h5id_digest(hid_t f, char out[17], sb_err *e);

/* Writes the digest attribute of f (replacing one there); call after the last
 * attribute is written. */
int h5id_seal(hid_t f, sb_err *e);

/* What h5id_check found beyond an error. */
enum h5id_note {
	H5ID_OK = 0,
	H5ID_UNSEALED = 1, /* a file of H5ID_FORMAT_OLD: neither id nor digest to check */
	H5ID_OLD3 = 2,     /* a file of H5ID_FORMAT_OLD3: no seal, only the attributes' digest */
};

/* The file is a run file of this engine's format, sealed (a user block: h5r_open has
 * checked the seal), its attributes match its digest, and, when want_id is not NULL, it
 * claims to be run want_id. An error names path and what mismatched (SB_EIO). *note
 * (may be NULL) says whether an older file was let through less checked. */
int h5id_check(hid_t f, const char *path, const char *want_id, int *note, sb_err *e);

#endif
