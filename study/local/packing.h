/* packing.h - the packing cache as its files say: the packing a run's argument file
 * starts it from, and whether a packing's particle file exists. The files decide,
 * not the database (docs/driver.md, "What `study run` does"). */
#ifndef ST_PACKING_H
#define ST_PACKING_H

#include <stddef.h>

/* The key run id's argument file in campaign directory dir starts it from ("" none). */
void packing_of_args(const char *dir, const char *id, char *key, size_t len);
/* Does the packing's particle file (what the runs start from) exist? */
int packing_present(const char *dir, const char *key);

#endif
