/* changes.h - a campaign file that changed since its runs were recorded: the recorded
 * runs of the campaign's current version that the file no longer asks for (a key of
 * the file changed, values left an axis) are never mixed with the new ones silently.
 * Without a choice the driver refuses, naming each key that changed (old -> new) and
 * counting the runs; with --keep-old they stay as an earlier version (run.current = 0,
 * campaign.version counted), with --forget-old their rows go and their files move to
 * NAME/forgotten/. */
#ifndef ST_CHANGES_H
#define ST_CHANGES_H

#include "campaign/campaign.h"
#include "campaign/grid.h"
#include "db.h"

enum { CHANGES_PATH = 4352 };

typedef struct changes_ctx {
	st_db *db;
	const campaign *c;
	const grid *g;           /* the file's runs, for the keys' new values */
	const char *dir;         /* RUNS/NAME */
	int keep_old, forget_old;
	/* does the file still ask for this recorded run (its id, replicate, frequency)? */
	int (*member)(void *ctx, const char *id, long replicate, double frequency);
	void *ctx;
} changes_ctx;

/* 0 when nothing left the file or the user's choice was carried out; SB_EUSAGE with
 * the message when a choice is needed. */
int changes_check(const changes_ctx *x, sb_err *e);

#endif
