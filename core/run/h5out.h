/* h5out.h - a run's HDF5 output (and its XDMF sidecar), assembled from the journal
 * and the final state (h5out.c; layout in docs/output.md). */
#ifndef SB_H5OUT_H
#define SB_H5OUT_H

#include "sim.h"

/* Write the run's file to path (under a temporary name, renamed when complete). */
int h5out_write(const sb_sim *s, const char *path, sb_err *e);
/* Sync the journal and write the run's output (the scene's output key). */
int h5out_write_run(sb_sim *s, sb_err *e);

#endif
