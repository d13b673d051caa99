/* sample.h - the sampling functions of the recorded quantities (record.h's table):
 * each takes one sample of the corrected state at time t, journals it and counts it
 * in s->rec_n. Definitions: docs/model.md, "Observables"; layout: docs/output.md. */
#ifndef SB_SAMPLE_H
#define SB_SAMPLE_H

#include "sim.h"

int sample_traj(sb_sim *s, double t, sb_err *e);     /* the intruder, lab frame */
int sample_energy(sb_sim *s, double t, sb_err *e);   /* energies, box frame */
int sample_contacts(sb_sim *s, double t, sb_err *e); /* every contact, box frame */
int sample_snap(sb_sim *s, double t, sb_err *e);     /* every mobile disk, lab frame */
int sample_flux(sb_sim *s, double t, sb_err *e);     /* crossings since the last strobe */
int sample_field(sb_sim *s, double t, sb_err *e);    /* displacements since the last strobe */
int sample_ring(sb_sim *s, double t, sb_err *e);     /* the ring around its centre */
int sample_kinetic(sb_sim *s, double t, sb_err *e);  /* the bed's kinetic energy, box frame */
int sample_height(sb_sim *s, double t, sb_err *e);   /* the bed's centre-of-mass height, box frame */

#endif
