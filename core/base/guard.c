/* guard.c - SIGINT/SIGTERM for the preparation's loops (the limits are in guard.h). */
#include "guard.h"

#include <stddef.h>

static void stop_signals(sigset_t *s)
{
	sigemptyset(s);
	sigaddset(s, SIGINT);
	sigaddset(s, SIGTERM);
}

void guard_hold(guard_sig *g)
{
	sigset_t s;
	stop_signals(&s);
	sigprocmask(SIG_BLOCK, &s, &g->old);
}

int guard_stopped(void)
{
	sigset_t p;
	if (sigpending(&p))
		return 0;
	static const int sigs[] = {SIGINT, SIGTERM};
	for (size_t k = 0; k < sizeof sigs / sizeof sigs[0]; k++) {
		struct sigaction sa;
		/* Linux keeps an ignored signal pending while it is blocked: that is no request
		 * to stop (e.g. SIGINT of a background job of a non-interactive shell) */
		if (sigismember(&p, sigs[k]) && !sigaction(sigs[k], NULL, &sa) && sa.sa_handler != SIG_IGN)
			return 1;
	}
	return 0;
}

void guard_release(const guard_sig *g)
{
	sigprocmask(SIG_SETMASK, &g->old, NULL);
}
