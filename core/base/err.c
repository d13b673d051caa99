/* err.c - recording errors for the caller. */
#include "err.h"

#include <stdarg.h>
#include <stdio.h>

int sb_errf(sb_err *e, int code, const char *fmt, ...)
{
	if (!e || e->code != SB_OK)
		return e ? e->code : code;
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(e->msg, sizeof e->msg, fmt, ap);
	va_end(ap);
	e->code = code;
	return code;
}

const char *sb_code_name(int code)
{
	switch (code) {
	case SB_OK: return "ok";
	case SB_EUSAGE: return "usage";
	case SB_EIO: return "io";
	case SB_ENAN: return "nan";
	case SB_EOVERLAP: return "overlap";
	case SB_ELEFT: return "left_box";
	case SB_ESETTLE: return "settle_failed";
	case SB_EINTR: return "interrupted";
	case SB_ENOMEM: return "nomem";
	}
	return "unknown";
}
