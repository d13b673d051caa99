/* packing.c - the packing cache as its files say (packing.h). */
#include "packing.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "fsutil.h"
#include "layout.h"
#include "campaign/safe.h"

/* The packing a run's argument file starts it from ("" when it settles itself, or has
 * no argument file): the argument file decides, since a resumed run keeps the one it
 * was given. */
void packing_of_args(const char *dir, const char *id, char *key, size_t len)
{
	char p[4400], line[1200];
	key[0] = 0;
	layout_file(dir, 0, id, LAY_ARGS, p, sizeof p);
	sb_err e = {0};
	FILE *f = fs_open_input(p, "argument file", 1 << 20, SB_EIO, &e); /* a regular file only */
	if (!f)
		return;
	while (fgets(line, sizeof line, f)) {
		line[strcspn(line, "\r\n")] = 0;
		static const char pre[] = "particles=cache/";
		size_t l = strlen(line);
		if (!strncmp(line, pre, sizeof pre - 1) && l > sizeof pre + 3 && !strcmp(line + l - 4, ".txt")) {
			snprintf(key, len, "%.*s", (int)(l - 4 - (sizeof pre - 1)), line + sizeof pre - 1);
			if (!safe_name(key))
				key[0] = 0;
		}
	}
	fclose(f);
}

int packing_present(const char *dir, const char *key)
{
	char txt[4400];
	layout_cache_particles(dir, key, txt, sizeof txt);
	return access(txt, F_OK) == 0;
}
