/* crossing.h - the crossings of height lines between two stroboscopic samples, the
 * counting behind the flux Phi(D) (docs/model.md, "Flux Phi(D)"): one definition, used
 * by the engine during a run (core/model/observe.c) and by the analysis of position dumps
 * written by other codes (analysis/measure/dumpflux.c). */
#ifndef SB_CROSSING_H
#define SB_CROSSING_H

/* The lines: nlines heights at the midpoints of nlines equal slices of [0, surface]
 * (box frame, cm above the floor), into h[nlines]. */
void crossing_lines(double surface, int nlines, double *h);

/* Adds the crossings of the n disks between the previous sample (xp, yp) and this one
 * (x, y), box frame: a disk crosses line h upwards when yp < h <= y, downwards when
 * y < h <= yp. It counts (+1 up, -1 down) into jtop[l] when the midpoint of its two
 * sample x lies within W/4 of the box centre, |x_mid - (x0 + x1)/2| < (x1 - x0)/4
 * (x0, x1 the inner wall faces), else into jbot[l]. h are the lines of
 * crossing_lines(surface, nlines, h). */
void crossing_count(int n, const double *xp, const double *yp, const double *x, const double *y, double x0,
		    double x1, double surface, int nlines, const double *h, double *jtop, double *jbot);

#endif
