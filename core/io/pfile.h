/* pfile.h - particle files: plain text (x y r kind [vx vy omega]) and LAMMPS data
 * files (atom_style sphere; types 1 grain, 2 intruder, 3 wall), read and written so
 * that the same state runs here and in LAMMPS. */
#ifndef SB_PFILE_H
#define SB_PFILE_H

#include "params.h"
#include "state.h"

/* Read either format (a LAMMPS file is recognised by its "N atoms" header line).
 * Disks get the masses particle_mass says (docs/inputs.md, "Particle masses"); velocities
 * (if present) are lab-frame and are stored as given. Errors name file and line: a file
 * that is not a regular one, a line too long or with a NUL byte, a radius that is no
 * grain's (pfile.c), coincident disks or an overlap beyond max_overlap, a mass or
 * density column that disagrees with the scene's mass model (particle_mass = scene) or
 * is missing (particle_mass = file), a mobile disk far outside
 * the box of the walls (or, in a LAMMPS file, outside the box of its header), a repeated
 * atom id, an atom style other than sphere. SIGINT and SIGTERM end a long read (SB_EINTR). */
int pfile_read(const sb_scene *sc, const char *path, sb_state *st, sb_err *e);

/* The radius_ratio a particle file gives (docs/model.md, "Units and the paper's
 * values"): its first intruder's radius over the scene's mean grain radius
 * (params_grain_radii), rounded to 12 significant digits, and that intruder's line; 0
 * and line 0 when it holds none. The file is read and checked as pfile_read reads it,
 * with its errors; a ratio beyond the key's range is refused. */
int pfile_intruder_ratio(const sb_scene *sc, const char *path, double *ratio, long *line, sb_err *e);

/* A scene's radius_ratio made the file's (ratio and line from pfile_intruder_ratio of
 * path, the file sc->particles names): a radius_ratio set explicitly (params_where) that
 * disagrees beyond PFILE_RATIO_REL is refused, naming the file, the intruder's line, the
 * key, where it was set and both values; one that agrees is kept as given (a packing
 * the study driver settled reads back its own run's value, bit for bit); else the
 * file's value is set, and params_where names the particle file. */
#define PFILE_RATIO_REL 1e-6
int pfile_ratio_apply(sb_scene *sc, const char *path, double ratio, long line, sb_err *e);

/* Both, for a scene whose particles is set (bin/shake, before its cross-key checks). */
int pfile_scene_ratio(sb_scene *sc, sb_err *e);

/* Write the state at the start of shaking, lab frame: positions plus (0, yshift),
 * mobile velocities q1 * inv_dt, wall velocities (0, vshift) (the box's). Written
 * via a temporary file and rename. */
int pfile_write_text(const sb_state *st, const char *path, double inv_dt, double yshift,
		     double vshift, sb_err *e);
/* period > 0 (periodic sides): the box's x is [0, period), the atoms are wrapped into
 * it, and the header says the boundary is p f p (the input script's `boundary`). */
int pfile_write_lammps(const sb_state *st, const char *path, double inv_dt, double yshift,
		       double vshift, double period, sb_err *e);

#endif
