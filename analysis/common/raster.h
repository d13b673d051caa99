/* raster.h - an RGB frame to draw a bed into: filled disks to scale (anti-aliased by
 * 4 x 4 subsamples of each pixel's area), a 5 x 7 bitmap font for the stamps, and a
 * colour scale. What bin/movie draws its frames with (docs/output.md, "Movies"); no
 * file and no encoder here: the frame's bytes go to whoever encodes them. */
#ifndef SB_RASTER_H
#define SB_RASTER_H
#include <stddef.h>

typedef struct rs_frame {
	int w, h;               /* pixels; w and h even (what yuv420p encoders need) */
	unsigned char *rgb;     /* w * h * 3 bytes, row 0 at the top */
	double x0, y0, scale;   /* the world (cm) to pixels: px = (x - x0) * scale, py = h - (y - y0) * scale */
} rs_frame;

typedef struct rs_rgb {
	unsigned char r, g, b;
} rs_rgb;

/* A frame of w x h pixels (rounded up to even) showing [x0, x0 + w / scale] x
 * [y0, y0 + h / scale]; 0, or -1 when out of memory (rgb NULL). */
int rs_init(rs_frame *f, int w, int h, double x0, double y0, double scale);
void rs_free(rs_frame *f);
void rs_clear(rs_frame *f, rs_rgb c);
/* A filled disk of radius r (world units) at (x, y), blended over what is there by the
 * share of each pixel it covers. */
void rs_disk(rs_frame *f, double x, double y, double r, rs_rgb c);
/* Text with its top left corner at pixel (px, py), each font pixel drawn as a
 * size x size block. Characters the font lacks are drawn as a hollow box. */
void rs_text(rs_frame *f, int px, int py, int size, const char *s, rs_rgb c);
/* Does the font have every character of s? (the stamps are checked against it) */
int rs_font_has(const char *s);
/* Width in pixels of s at size. */
int rs_text_width(const char *s, int size);
/* A filled rectangle of pixels [px, px + w) x [py, py + h), clipped. */
void rs_rect(rs_frame *f, int px, int py, int w, int h, rs_rgb c);
/* The colour of u in [0, 1] (clamped) on a perceptually ordered scale (viridis' five
 * anchors, interpolated): dark violet at 0, yellow at 1. */
rs_rgb rs_scale(double u);
#endif
