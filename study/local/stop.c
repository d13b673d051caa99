/* stop.c - the driver's SIGINT/SIGTERM and the child it passes them on to (stop.h). */
#include "stop.h"

#include <signal.h>
#include <string.h>

static volatile sig_atomic_t g_stop;
static volatile sig_atomic_t g_child;

static void on_signal(int sig)
{
	(void)sig;
	if (!g_stop && g_child > 0)
		kill((pid_t)g_child, SIGTERM); /* no new jobs; running ones checkpoint */
	g_stop = 1;
}

void stop_signals(void)
{
	struct sigaction sa;
	memset(&sa, 0, sizeof sa);
	sa.sa_handler = on_signal;
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);
}

int stop_requested(void)
{
	return g_stop;
}

void stop_child(pid_t pid)
{
	g_child = pid;
}

void stop_halt(void)
{
	if (g_child > 0)
		kill((pid_t)g_child, SIGTERM);
}
