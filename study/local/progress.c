/* progress.c - the progress line of `study run` (progress.h). */
#include "progress.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <time.h>

#include "report/watch.h"

struct drv_progress {
	watch w;
	int tty;
};

drv_progress *progress_open(const char *name, const char *dir, int tty)
{
	drv_progress *p = malloc(sizeof *p);
	if (!p)
		return NULL;
	watch_init(&p->w, name, dir);
	p->tty = tty;
	return p;
}

void progress_close(drv_progress *p)
{
	if (!p)
		return;
	watch_free(&p->w);
	free(p);
}

int progress_tty(const drv_progress *p)
{
	return p && p->tty;
}

void progress_show(drv_progress *p, st_db *db, int final)
{
	if (!p)
		return;
	sb_err e = {0};
	/* a look that fails is skipped (the next one comes in a second), but the last one is
	 * the campaign's summary: tried again, and its failure said, never dropped unseen */
	for (int tries = final ? 3 : 1; watch_poll(&p->w, db, &e); e = (sb_err){0}) {
		if (--tries > 0) {
			nanosleep(&(struct timespec){0, 100000000}, NULL);
			continue;
		}
		if (final)
			fprintf(stderr, "%sstudy: the last progress line could not be read from the database: %s\n",
				p->tty ? "\r\033[K" : "", e.msg);
		return;
	}
	char line[4096];
	size_t width = sizeof line;
	struct winsize ws;
	if (p->tty && ioctl(2, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 20 && ws.ws_col < sizeof line)
		width = ws.ws_col; /* one screen line: "study: " and the look, cut */
	memcpy(line, "study: ", 8);
	watch_line(&p->w, line + 7, width - 7);
	if (p->tty)
		fprintf(stderr, "\r%s\033[K%s", line, final ? "\n" : "");
	else
		fprintf(stderr, "%s\n", line);
}
