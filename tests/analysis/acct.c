/* acct.c - the accounting of runs per group: uses counted per group, failed runs by
 * status (and how many of them are used), the seconds of failed runs used, statuses
 * beyond the table's room collected as "other", runs in no group left out; runs that
 * are pending, running or without an output file classified before any file is read;
 * the versions rule. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "common/acct.h"
#include "h5id.h"
#include "h5seal.h"
#include "testlib.h"

static an_run run(int group, const char *state, const char *status, int use)
{
	an_run r;
	memset(&r, 0, sizeof r);
	r.group = group;
	r.current = 1;
	snprintf(r.state, sizeof r.state, "%s", state);
	snprintf(r.status, sizeof r.status, "%s", status);
	acct_set(&r, use, NAN, NAN, NULL);
	return r;
}

int main(void)
{
	an_run r[20];
	int n = 0;
	r[n++] = run(0, "done", "ok", AN_USED);
	r[n++] = run(0, "failed", "overlap", AN_PARTLY);
	r[n - 1].used_s = 0.5;
	r[n - 1].planned_s = 2;
	r[n++] = run(0, "failed", "overlap", AN_UNUSABLE);
	r[n++] = run(0, "failed", "nan", AN_PARTLY);
	r[n - 1].used_s = 1;
	r[n - 1].planned_s = 2;
	r[n++] = run(0, "done", "ok", AN_UNREADABLE);
	r[n++] = run(1, "pending", "", AN_PENDING);
	r[n++] = run(1, "running", "", AN_RUNNING);
	r[n++] = run(-1, "failed", "io", AN_UNUSABLE); /* in no group */
	const char *many[] = {"s1", "s2", "s3", "s4", "s5", "s6", "s7", "s8", "s9"};
	for (int k = 0; k < 9 && n < 20; k++)
		r[n++] = run(1, "failed", many[k], AN_UNUSABLE);
	an_acct *a;
	CHECK("acct.tally.ok", acct_tally(r, n, 2, &a) == 0, "out of memory");
	CHECK("acct.tally.uses", a[0].n[AN_USED] == 1 && a[0].n[AN_PARTLY] == 2 && a[0].n[AN_UNUSABLE] == 1 &&
				     a[0].n[AN_UNREADABLE] == 1 && acct_used(&a[0]) == 3,
	      "used %ld partly %ld unusable %ld unreadable %ld", a[0].n[AN_USED], a[0].n[AN_PARTLY], a[0].n[AN_UNUSABLE],
	      a[0].n[AN_UNREADABLE]);
	CHECK("acct.tally.failed", a[0].failed == 3, "failed %ld", a[0].failed);
	CHECK("acct.tally.seconds", a[0].used_s == 1.5 && a[0].planned_s == 4, "%g of %g", a[0].used_s, a[0].planned_s);
	CHECK("acct.tally.by_status", a[0].nreason == 2 && !strcmp(a[0].reason[0].status, "overlap") &&
					  a[0].reason[0].n == 2 && a[0].reason[0].used == 1 && a[0].reason[1].n == 1,
	      "%d statuses, first %s %ld (%ld used)", a[0].nreason, a[0].reason[0].status, a[0].reason[0].n,
	      a[0].reason[0].used);
	char buf[256];
	acct_reasons(&a[0], buf, sizeof buf);
	CHECK("acct.reasons.text", !strcmp(buf, "overlap=2;nan=1"), "'%s'", buf);
	CHECK("acct.tally.unfinished", a[1].n[AN_PENDING] == 1 && a[1].n[AN_RUNNING] == 1, "pending %ld running %ld",
	      a[1].n[AN_PENDING], a[1].n[AN_RUNNING]);
	CHECK("acct.tally.other_status", a[1].failed == 9 && a[1].nreason == AN_MAXREASON &&
					     !strcmp(a[1].reason[AN_MAXREASON - 1].status, "other") &&
					     a[1].reason[AN_MAXREASON - 1].n == 2,
	      "failed %ld, %d statuses, last %s %ld", a[1].failed, a[1].nreason, a[1].reason[AN_MAXREASON - 1].status,
	      a[1].reason[AN_MAXREASON - 1].n);
	free(a);

	/* classified before reading: unfinished runs, and files that do not exist */
	an_run x = run(0, "pending", "", AN_USED);
	CHECK("acct.classify.pending", acct_classify(&x) == 1 && x.use == AN_PENDING, "use %d", x.use);
	x = run(0, "running", "", AN_USED);
	CHECK("acct.classify.running", acct_classify(&x) == 1 && x.use == AN_RUNNING, "use %d", x.use);
	x = run(0, "failed", "io", AN_USED);
	snprintf(x.path, sizeof x.path, "/nonexistent/run.h5");
	snprintf(x.message, sizeof x.message, "cannot create HDF5 file");
	CHECK("acct.classify.failed_without_file", acct_classify(&x) == 1 && x.use == AN_UNUSABLE &&
							 strstr(x.why, "without an output file (io: cannot create"),
	      "use %d why '%s'", x.use, x.why);
	x = run(0, "done", "ok", AN_USED);
	snprintf(x.path, sizeof x.path, "/nonexistent/run.h5");
	CHECK("acct.classify.done_without_file", acct_classify(&x) == 1 && x.use == AN_UNREADABLE, "use %d", x.use);
	/* a path that is no run file (a directory) is unreadable, said so */
	x = run(0, "done", "ok", AN_USED);
	snprintf(x.path, sizeof x.path, "/");
	CHECK("acct.classify.no_run_file", acct_classify(&x) == 1 && x.use == AN_UNREADABLE && x.why[0], "use %d",
	      x.use);
	/* a file that is this run's (format, run id, sealed) is the tool's to read; the
	 * same file under another run's id is not */
	char path[] = "/tmp/acct-run-XXXXXX";
	int fd = mkstemp(path);
	hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
	H5Pset_userblock(fcpl, H5SEAL_BYTES);
	hid_t f = fd < 0 ? -1 : H5Fcreate(path, H5F_ACC_TRUNC, fcpl, H5P_DEFAULT);
	H5Pclose(fcpl);
	if (fd >= 0)
		close(fd);
	sb_err e = {0};
	hid_t sp = H5Screate(H5S_SCALAR), ty = H5Tcopy(H5T_C_S1);
	H5Tset_size(ty, 32);
	char fmt[32] = H5ID_FORMAT, id[32] = "0123456789abcdef";
	hid_t g = f < 0 ? -1 : H5Gcreate2(f, H5ID_RUN_OBJ, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
	hid_t a1 = f < 0 ? -1 : H5Acreate2(f, H5ID_FORMAT_ATTR, ty, sp, H5P_DEFAULT, H5P_DEFAULT);
	hid_t a2 = g < 0 ? -1 : H5Acreate2(g, H5ID_RUN_ATTR, ty, sp, H5P_DEFAULT, H5P_DEFAULT);
	int made = a1 >= 0 && a2 >= 0 && H5Awrite(a1, ty, fmt) >= 0 && H5Awrite(a2, ty, id) >= 0;
	H5Aclose(a1);
	H5Aclose(a2);
	H5Gclose(g);
	made = made && !h5id_seal(f, &e);
	H5Tclose(ty);
	H5Sclose(sp);
	H5Fclose(f);
	made = made && !h5seal_write(path, &e);
	char seal[17] = "";
	made = made && !h5seal_check(path, seal, &e) && strlen(seal) == 16;
	x = run(0, "done", "ok", AN_USED);
	snprintf(x.path, sizeof x.path, "%s", path);
	snprintf(x.id, sizeof x.id, "%s", id);
	CHECK("acct.classify.existing_file_is_the_tools", made && acct_classify(&x) == 0, "made %d, use %d: %s %s", made,
	      x.use, x.why, e.msg);
	/* ... and with the seal the database recorded; another seal is another file */
	snprintf(x.seal, sizeof x.seal, "%s", seal);
	CHECK("acct.classify.recorded_seal", made && acct_classify(&x) == 0, "use %d: %s", x.use, x.why);
	x = run(0, "done", "ok", AN_USED);
	snprintf(x.path, sizeof x.path, "%s", path);
	snprintf(x.id, sizeof x.id, "%s", id);
	snprintf(x.seal, sizeof x.seal, "%s", "0123456789abcdef");
	CHECK("acct.classify.other_seal", made && acct_classify(&x) == 1 && x.use == AN_UNREADABLE &&
	      strstr(x.why, "but the database recorded 0123456789abcdef"), "use %d: %s", x.use, x.why);
	x = run(0, "done", "ok", AN_USED);
	snprintf(x.path, sizeof x.path, "%s", path);
	snprintf(x.id, sizeof x.id, "%s", "fedcba9876543210");
	CHECK("acct.classify.another_runs_file", made && acct_classify(&x) == 1 && x.use == AN_UNREADABLE,
	      "made %d, use %d", made, x.use);
	/* one byte after the seal changed: refused before HDF5 reads the file */
	FILE *fp = fopen(path, "r+b");
	int c = fp && !fseek(fp, -3, SEEK_END) ? fgetc(fp) : EOF;
	const int flipped = c != EOF && !fseek(fp, -3, SEEK_END) && fputc(c ^ 1, fp) != EOF;
	if (fp)
		fclose(fp);
	x = run(0, "done", "ok", AN_USED);
	snprintf(x.path, sizeof x.path, "%s", path);
	snprintf(x.id, sizeof x.id, "%s", id);
	CHECK("acct.classify.changed_byte", flipped && acct_classify(&x) == 1 && x.use == AN_UNREADABLE &&
	      strstr(x.why, "its bytes do not match its seal"), "use %d: %s", x.use, x.why);
	unlink(path);

	/* versions: an earlier version's run is counted, and left out unless asked for */
	long nold = 0;
	x.current = 0;
	CHECK("acct.version.left_out", acct_version_skip(&x, 0, &nold) == 1 && nold == 1, "nold %ld", nold);
	CHECK("acct.version.all", acct_version_skip(&x, 1, &nold) == 0 && nold == 2, "nold %ld", nold);
	x.current = 1;
	CHECK("acct.version.current", acct_version_skip(&x, 0, &nold) == 0 && nold == 2, "nold %ld", nold);
	return tl_done();
}
