/* stop.h - the driver's stop: SIGINT or SIGTERM (or a halt the driver decides on)
 * means no new jobs, and the running ones checkpoint. The one process to tell is GNU
 * parallel, while it runs. Signal state is process-wide by nature: it lives here
 * alone, behind these calls. */
#ifndef ST_STOP_H
#define ST_STOP_H

#include <sys/types.h>

/* Install the handler: the first signal sends SIGTERM to the child (when there is
 * one) and marks the driver stopped. */
void stop_signals(void);
/* Was the driver stopped by a signal? */
int stop_requested(void);
/* The child to pass a stop on to (GNU parallel), 0 when none runs. */
void stop_child(pid_t pid);
/* SIGTERM to the child now (an I/O fault: launch nothing more), whether or not a
 * signal came. */
void stop_halt(void);

#endif
