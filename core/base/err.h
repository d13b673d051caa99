/* err.h - the one error type the engine returns up the stack (GSL style: libraries
 * return, only main() prints). */
#ifndef SB_ERR_H
#define SB_ERR_H

#include <stddef.h>

/* Exit codes are part of the CLI contract (docs/scene.md, "Exit codes"): the study driver
 * reads them to tell a bad scene from a physics blow-up. */
enum sb_code {
	SB_OK = 0,
	SB_EUSAGE = 1,     /* bad input: scene file, key, value, command line */
	SB_EIO = 2,        /* file system / HDF5 failure */
	SB_ENAN = 3,       /* NaN or Inf in the state */
	SB_EOVERLAP = 4,   /* overlap beyond max_overlap of the smaller radius */
	SB_ELEFT = 5,      /* a grain left the box */
	SB_ESETTLE = 6,    /* settling did not reach settle_ke within settle_max */
	SB_EINTR = 7,      /* stopped by a signal (checkpoint written if enabled) */
	SB_ENOMEM = 8,
};

typedef struct sb_err {
	int code;
	char msg[1024];
} sb_err;

/* Record an error (the first one wins, so the root cause is kept) and return code. */
int sb_errf(sb_err *e, int code, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* Short machine-readable name of a code ("ok", "nan", "overlap", ...). */
const char *sb_code_name(int code);

#endif
