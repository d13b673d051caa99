/* runfile.h - where the readers find what they read in a run's HDF5 file: the groups
 * and datasets the engine writes (core/run/h5out.c, core/io/h5md.c; docs/inputs.md, "Run
 * files"), for lib/ and the analysis tools; each group is the engine's table of
 * recorded quantities' (core/scene/record.h), the members below are its writer's. Root
 * attributes (@status, @waiting_time, ...) and /provenance are the result columns'
 * (results.c). */
#ifndef LIB_RUNFILE_H
#define LIB_RUNFILE_H

#include "h5id.h"
#include "record.h"

/* every scene parameter as an attribute (the run's identity is digested from them) */
#define RUNFILE_PARAMS H5ID_RUN_OBJ

/* the flux through the height lines per drive period (H5MD elements) */
#define RUNFILE_FLUX REC_H5_FLUX
#define RUNFILE_FLUX_TIME RUNFILE_FLUX "/phi/time"
#define RUNFILE_FLUX_PHI RUNFILE_FLUX "/phi/value"
#define RUNFILE_FLUX_FREQ RUNFILE_FLUX "/frequency/value"
#define RUNFILE_FLUX_HEIGHTS RUNFILE_FLUX "/heights"

/* the averaged displacement field per block of periods */
#define RUNFILE_FIELD REC_H5_FIELD
#define RUNFILE_FIELD_TIME RUNFILE_FIELD "/ux/time"
#define RUNFILE_FIELD_UX RUNFILE_FIELD "/ux/value"
#define RUNFILE_FIELD_UY RUNFILE_FIELD "/uy/value"
#define RUNFILE_FIELD_COUNT RUNFILE_FIELD "/count/value"

/* the intruder's trajectory (lab frame) */
#define RUNFILE_INTRUDER REC_H5_INTRUDER "/position"
#define RUNFILE_INTRUDER_TIME RUNFILE_INTRUDER "/time"
#define RUNFILE_INTRUDER_POS RUNFILE_INTRUDER "/value"

/* the ring force around the intruder (attributes) */
#define RUNFILE_RING "/ring"

#endif
