/* provenance.h - where a result came from: code version, compiler, host, times. */
#ifndef SB_PROVENANCE_H
#define SB_PROVENANCE_H

#include <stddef.h>

typedef struct sb_prov {
	char git_hash[64];
	int git_dirty;
	char compiler[256];
	char cflags[512];
	char host[256];
	char cpu[128];       /* the CPU's model name (/proc/cpuinfo), or "unknown" */
	char kernel[16];     /* the force kernel's path that ran (kernel.h), set by the caller */
	char start_time[32]; /* ISO 8601 UTC, fixed length */
	char end_time[32];
	double wall_seconds;
} sb_prov;

void prov_init(sb_prov *p);     /* fills everything but end_time, wall_seconds */
void prov_now(char out[32]);    /* current UTC time, ISO 8601 */
const char *prov_version(void); /* "shakebox <hash>[-dirty]" */
/* 1 when the build runs on every CPU of its architecture (built without MARCH), and
 * the MARCH it was built with ("" when none). */
int prov_portable(void);
const char *prov_march(void);

/* The CPU's model name: /proc/cpuinfo's "model name" (x86) or "Model name" of its
 * first processor, else "unknown". */
void prov_cpu(char *out, size_t n);

#endif
