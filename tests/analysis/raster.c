/* raster.c - bin/movie's frames (analysis/common/raster.c) on known answers: a disk
 * covers its area (pi R^2 pixels, to the subsampling's error), blends by the share it
 * covers, draws nothing off the frame; text draws its glyphs' pixels and a box for a
 * character the font lacks; the colour scale's ends and order. */
#include <math.h>
#include <string.h>

#include "testlib.h"
#include "common/raster.h"

/* the summed darkness of a frame drawn black on white, in pixels */
static double ink(const rs_frame *f)
{
	double s = 0;
	for (int i = 0; i < f->w * f->h; i++)
		s += (255.0 - f->rgb[3 * i]) / 255.0;
	return s;
}

int main(void)
{
	const rs_rgb white = {255, 255, 255}, black = {0, 0, 0};
	rs_frame f;
	CHECK("init.even", !rs_init(&f, 201, 99, 0, 0, 10) && f.w == 202 && f.h == 100, "%d x %d", f.w, f.h);
	/* a disk of radius 3 cm at 10 px/cm: pi 30^2 pixels; the 4 x 4 subsamples' error on
	 * the rim is below one pixel per rim pixel's share, far below 0.5 % here */
	rs_clear(&f, white);
	rs_disk(&f, 10.05, 5.03, 3, black);
	CHECK_REL("disk.area", ink(&f), M_PI * 900, 5e-3);
	/* the centre fully covered, a pixel outside untouched */
	const int cx = (int)(10.05 * 10), cy = f.h - (int)(5.03 * 10);
	CHECK("disk.centre", f.rgb[3 * (cy * f.w + cx)] == 0, "%d", f.rgb[3 * (cy * f.w + cx)]);
	CHECK("disk.outside", f.rgb[0] == 255, "%d", f.rgb[0]);
	/* off the frame: nothing drawn, no write outside the buffer (ASan in SAN=1) */
	rs_clear(&f, white);
	rs_disk(&f, -50, -50, 3, black);
	rs_disk(&f, 500, 500, 3, black);
	CHECK("disk.off_frame", ink(&f) == 0, "%g", ink(&f));
	/* half off the left edge: half the area */
	rs_disk(&f, 0, 5, 3, black);
	CHECK_REL("disk.clipped_half", ink(&f), M_PI * 900 / 2, 1e-2);
	/* text: '1' has 10 lit font pixels, drawn at size 2 as 40 pixels; a character the
	 * font lacks is a hollow 5 x 7 box (20 pixels) */
	rs_clear(&f, white);
	rs_text(&f, 4, 4, 2, "1", black);
	CHECK("text.one", fabs(ink(&f) - 40) < 1e-9, "%g", ink(&f));
	rs_clear(&f, white);
	rs_text(&f, 4, 4, 1, "#", black);
	CHECK("text.missing_is_box", fabs(ink(&f) - 20) < 1e-9, "%g", ink(&f));
	CHECK("font.has", rs_font_has("t = 0.125 s   phase 0.38   f = 3.20 Hz  A = 2.00 cm") &&
				  rs_font_has("110 cm/s (speed, box frame)") && !rs_font_has("#"),
	      "the stamps' characters");
	CHECK("text.width", rs_text_width("abc", 2) == 36, "%d", rs_text_width("abc", 2));
	/* the scale: its ends are viridis' ends; darker to lighter (green rises) */
	const rs_rgb a = rs_scale(0), b = rs_scale(1), m = rs_scale(0.5), nan_ = rs_scale(NAN);
	CHECK("scale.ends", a.r == 0x44 && a.g == 0x01 && a.b == 0x54 && b.r == 0xfd && b.g == 0xe7 && b.b == 0x25,
	      "%d %d %d / %d %d %d", a.r, a.g, a.b, b.r, b.g, b.b);
	CHECK("scale.middle", m.r == 0x21 && m.g == 0x91 && m.b == 0x8c, "%d %d %d", m.r, m.g, m.b);
	CHECK("scale.clamped", rs_scale(-3).g == a.g && rs_scale(7).g == b.g && nan_.g == a.g, "clamp");
	int up = 1;
	for (int k = 1; k <= 100; k++)
		up &= rs_scale(k / 100.0).g >= rs_scale((k - 1) / 100.0).g;
	CHECK("scale.green_rises", up, "not monotone");
	rs_free(&f);
	return tl_done();
}
