/* study_files.h - campaign files for the study unit tests: written into a temporary
 * directory (mkdtemp) that sf_cleanup removes, then loaded and expanded as bin/study
 * does. Included by one test file each (static helpers). */
#ifndef SB_STUDY_FILES_H
#define SB_STUDY_FILES_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "campaign/campaign.h"
#include "campaign/grid.h"

static char sf_dir[] = "/tmp/sb_study_XXXXXX";
static int sf_count;

static int sf_init(void)
{
	return mkdtemp(sf_dir) ? 0 : -1;
}

/* Writes text to DIR/name; the file's path into path. */
static int sf_write(const char *name, const char *text, char *path, size_t len)
{
	snprintf(path, len, "%s/%s", sf_dir, name);
	FILE *f = fopen(path, "w");
	if (!f)
		return -1;
	fputs(text, f);
	return fclose(f) ? -1 : 0;
}

/* A campaign from text (a file of its own in DIR): campaign_load's return value, with
 * its message in e. */
static int sf_load(const char *text, campaign *c, sb_err *e)
{
	char name[32], path[256];
	snprintf(name, sizeof name, "c%03d.campaign", sf_count++);
	memset(e, 0, sizeof *e);
	if (sf_write(name, text, path, sizeof path)) {
		memset(c, 0, sizeof *c);
		return sb_errf(e, SB_EIO, "%s: cannot write the test's campaign file", path);
	}
	return campaign_load(c, path, e);
}

/* Loads and expands a campaign; on failure c is freed and the error is in e. */
static int sf_expand(const char *text, campaign *c, grid *g, sb_err *e)
{
	memset(g, 0, sizeof *g);
	if (sf_load(text, c, e)) {
		campaign_free(c);
		return e->code;
	}
	if (grid_expand(g, c, e)) {
		campaign_free(c);
		return e->code;
	}
	return 0;
}

static void sf_free(campaign *c, grid *g)
{
	grid_free(g);
	campaign_free(c);
}

/* Removes the directory and every file the test wrote into it. */
static void sf_cleanup(void)
{
	DIR *d = opendir(sf_dir);
	if (!d)
		return;
	struct dirent *de;
	while ((de = readdir(d))) {
		if (!strcmp(de->d_name, ".") || !strcmp(de->d_name, ".."))
			continue;
		char p[512];
		snprintf(p, sizeof p, "%s/%s", sf_dir, de->d_name);
		unlink(p);
	}
	closedir(d);
	rmdir(sf_dir);
}

#endif
