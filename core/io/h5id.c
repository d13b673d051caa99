/* h5id.c - a run file's format, run id and attribute digest (h5id.h). */
#include "h5id.h"
#include "h5read.h"
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
	d->h = sb_fnv(d->h, p, n);
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
	dg d = {SB_FNV_BASIS, 0, ""};
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
	if (!old3 && ub != H5SEAL_BYTES)
		return sb_errf(e, SB_EIO, "%s: a %s file without its seal (a %llu-byte user block; the engine writes %d)",
			       path, H5ID_FORMAT, (unsigned long long)ub, H5SEAL_BYTES);
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
