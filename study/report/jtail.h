/* jtail.h - how far a running engine has got: the simulated time of the last record
 * in its journal (RUN.h5.journal, format in core/io/journal.c: "SBJRNL01", int32 nm,
 * then records of int32 tag, int32 count and count doubles, the first of which is
 * the time of every kind of record). Read incrementally: a watcher that polls keeps
 * its place and reads only what was appended since. Read-only; never the engine's
 * writer, so a journal being written, truncated by a restart or replaced by a new
 * attempt is read as far as it is whole. */
#ifndef ST_JTAIL_H
#define ST_JTAIL_H

typedef struct jtail {
	long offset;   /* where the next record header starts (0: header not read yet) */
	unsigned long ino; /* the file read: a new attempt's journal is a new file */
	double t;      /* the time of the last whole record; < 0 when there is none */
} jtail;

void jtail_init(jtail *j);
/* Reads what was appended to the journal at path since the last call. Returns 1 when
 * j->t is known, 0 when the journal does not exist or holds no record yet (an engine
 * still settling writes none). */
int jtail_poll(jtail *j, const char *path);

#endif
