/* units.h - the unit system, stated once: cgs throughout (cm, g, s, dyn = g cm/s^2).
 * Every parameter row in params.c names its unit; nothing converts units anywhere. */
#ifndef SB_UNITS_H
#define SB_UNITS_H

#define SB_PI 3.14159265358979323846
#define SB_TWO_PI 6.28318530717958647692

#endif
