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
 * grain's (pfile.c), coincident disks or an overlap beyond max_overlap, a second
 * intruder, a mass or density column that disagrees with the scene's mass model
 * (particle_mass = scene) or is missing (particle_mass = file), a mobile disk far outside
 * the box of the walls (or, in a LAMMPS file, outside the box of its header), a repeated
 * atom id, an atom style other than sphere. SIGINT and SIGTERM end a long read (SB_EINTR). */
int pfile_read(const sb_scene *sc, const char *path, sb_state *st, sb_err *e);

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
