/* provenance.h - where a result came from: code version, compiler, host, times. */
#ifndef SB_PROVENANCE_H
#define SB_PROVENANCE_H

typedef struct sb_prov {
	char git_hash[64];
	int git_dirty;
	char compiler[256];
	char cflags[512];
	char host[256];
	char start_time[32]; /* ISO 8601 UTC, fixed length */
	char end_time[32];
	double wall_seconds;
} sb_prov;

void prov_init(sb_prov *p);     /* fills everything but end_time, wall_seconds */
void prov_now(char out[32]);    /* current UTC time, ISO 8601 */
const char *prov_version(void); /* "shakebox <hash>[-dirty]" */

#endif
