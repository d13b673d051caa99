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

/* What a particle file's intruders make of the scene's keys (docs/model.md, "Units and
 * the paper's values"): radius_ratio, its first intruder's radius over the scene's mean
 * grain radius (params_grain_radii), rounded to 12 significant digits, with that
 * intruder's line (0 and line 0 when it holds none), and n_intruders, how many it holds. */
typedef struct sb_pintr {
	double ratio;
	long line;
	long count;
} sb_pintr;

/* Reads and checks the file as pfile_read does, with its errors; a ratio or a count
 * beyond its key's range is refused. */
int pfile_intruders(const sb_scene *sc, const char *path, sb_pintr *out, sb_err *e);

/* A scene's radius_ratio and n_intruders made the file's (from pfile_intruders of path,
 * the file sc->particles names): a key set explicitly (params_where) that disagrees - a
 * radius_ratio beyond PFILE_RATIO_REL, an n_intruders other than a file's count of one or
 * more intruders - is refused, naming the file, the first intruder's line, the key, where
 * it was set and both values; one that agrees is kept as given (a packing the study
 * driver settled reads back its own run's value, bit for bit); else the file's value is
 * set, and params_where names the particle file. A file without intruder leaves
 * n_intruders as it is: with radius_ratio 0 it counts nothing. */
#define PFILE_RATIO_REL 1e-6
int pfile_intruders_apply(sb_scene *sc, const char *path, const sb_pintr *in, sb_err *e);

/* Both, for a scene whose particles is set (bin/shake, before its cross-key checks). */
int pfile_scene_intruders(sb_scene *sc, sb_err *e);

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
