/* runvals.h - a run file's values held to what the engine can have written
 * (docs/inputs.md, "Run files"): finite is not enough. A frequency of 1e30, a waiting
 * time of 1e9 s in a run of 1.5 s, a surface at or below the floor, an intruder of
 * radius 0 are numbers no run of the engine writes; a reader that believed them would
 * make a statistic of them. */
#ifndef LIB_RUNVALS_H
#define LIB_RUNVALS_H

#include <hdf5.h>

#include "err.h"

/* The scene's numbers (/parameters) within the engine's own ranges (params_set, the
 * check a scene file's value passes), and the run's results (root attributes) within
 * theirs: status_time >= 0, surface_height > 0, intruder_radius > 0, risen 0 or 1,
 * 0 <= waiting_time <= duration. SB_EIO naming path, the value and its range (SB_ENAN
 * for a result that is no finite number: the run is unusable, not unreadable). Only
 * what the file holds is checked: an absent attribute is the reader's to miss. */
int runvals_check(hid_t f, const char *path, sb_err *e);

#endif
