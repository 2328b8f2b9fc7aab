/* The mode-I plate of the crack driver's test and bench
 * (tests/physics/test_crack_growth.c, bench/crack_growth_cost.c): steel with
 * linear hardening and Johnson-Cook damage (failure strain 8 %), LX x LY mm
 * in the plane from x = -10 mm, y = -LY/2, three layers of 1 mm along z
 * (thickness_axis z), an edge crack in y = 0 from beyond the left edge to
 * x = 0 through the thickness, the rows within 1.5 mm of the top and bottom
 * edges pulled apart in y at up to 5 m/s (5 us ramp), contact off, cfl 0.3,
 * end time END s; with grow, "crack_growth" from the tip (0, 0) with the
 * defaults. */
#ifndef TLSPH_TEST_CRACK_PLATE_H
#define TLSPH_TEST_CRACK_PLATE_H

#include <stddef.h>

/* Writes the scene's JSON into buf (size bytes; 4096 is enough); returns buf. */
char *crack_plate_scene(char *buf, size_t size, double lx_mm, double ly_mm, double end, int grow);

/* What a split must conserve (eqs. 21-30), summed over m's particles: mass
 * (kg), reference volume (m^3), linear momentum (kg m/s) and its scale
 * sum m |v| (kg m/s), the reference of the momentum tolerance. */
struct tlsph_model;
struct crack_totals {
    double mass, vol, mom[3], scale;
};
struct crack_totals crack_totals(const struct tlsph_model *m);

#endif
