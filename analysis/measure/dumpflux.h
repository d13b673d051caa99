/* dumpflux.h - the flux Phi(D) of a run made by another code (LAMMPS), from a text dump
 * of its positions at every stroboscopic sample (docs/model.md, "Stroboscopic samples",
 * "Flux Phi(D)"), counted by the engine's own crossing code (core/model/crossing.h) into the
 * structure the analysis tools reduce (flux.h: flux_profile, flux_summary).
 *
 * The dump's frames must be the engine's samples: frame k at the first step at or
 * after k/f, k = 0, 1, ... (the engine's integer schedule; checked). Types 1 (grain)
 * and 2 (intruder) are the mobile disks, type 3 the wall disks (the engine's data
 * files), with a radius column. Positions are taken as lab frame: the box offset
 * y_box = A sin(2 pi f t) at the frame's time t = step * dt (core/model/drive.c; at phase
 * 0 it is at most one step of box motion) is subtracted from the mobile disks' y, so
 * the heights are box-frame heights as the engine's. The wall disks say which frame
 * the dump is in: LAMMPS moves them (fix move wiggle, the same A sin(2 pi f t)),
 * scripts/dump_lammps.sh writes them at rest; both are measured and reported. The
 * inner wall faces are the hull of the wall disks less their radii, as the engine
 * takes them (core/run/sim.c, sim_obs_init). */
#ifndef AN_DUMPFLUX_H
#define AN_DUMPFLUX_H

#include "err.h"
#include "flux.h"

typedef struct dumpflux_opts {
	double surface;   /* the settled free-surface height of the bed (the engine's) */
	int nlines;       /* flux lines (the engine's flux_lines) */
	double amplitude; /* A, cm */
	double frequency; /* f, Hz (constant) */
	double dt;        /* the time step of the dumped run, s */
} dumpflux_opts;

typedef struct dumpflux_info {
	long frames, mobile, walls;
	double x0, x1;          /* inner wall faces */
	double ybox_max;        /* largest |y_box| subtracted at a frame */
	double wall_rest_dev;   /* largest |y_wall - y_wall(frame 0)| */
	double wall_drive_dev;  /* largest |y_wall - y_wall(frame 0) - (y_box - y_box(frame 0))| */
} dumpflux_info;

/* The due step of sample k: the engine's schedule (core/run/run.c). */
long dumpflux_due_step(long k, double frequency, double dt);

/* Reads the dump and counts the crossings between successive frames: d gets P =
 * frames - 1 periods, the lines of crossing_lines(surface, nlines), t = step * dt of
 * each period's closing frame, f = frequency, phi = j_top - j_bot. */
int dumpflux_read(const char *path, const dumpflux_opts *o, flux_data *d, dumpflux_info *info, sb_err *e);

#endif
