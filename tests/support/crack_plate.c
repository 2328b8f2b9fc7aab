/* The crack driver's mode-I plate (crack_plate.h). */
#include "support/crack_plate.h"

#include <math.h>
#include <stdio.h>

#include "run/model.h"

char *crack_plate_scene(char *buf, size_t size, double lx_mm, double ly_mm, double end, int grow)
{
    const double x0 = -0.010, x1 = x0 + 1e-3 * lx_mm, y1 = 0.5e-3 * ly_mm;
    snprintf(buf, size,
             "{\"dimension\":3,\"parameters\":{\"vmax\":5,\"tau\":5e-6},"
             "\"time\":{\"end\":%.17g,\"cfl\":0.3},"
             "\"discretization\":{\"hourglass\":{\"enabled\":true,\"coefficient\":1.0}},"
             "\"contact\":{\"enabled\":false},"
             "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2.1e11,"
             "\"poisson_ratio\":0.3,\"strength\":{\"type\":\"linear_hardening\","
             "\"yield_stress\":3e8,\"hardening_modulus\":5e8},"
             "\"damage\":{\"type\":\"johnson_cook\",\"d1\":0.08,\"d2\":0,\"d3\":0}}},"
             "\"bodies\":[{\"name\":\"plate\",\"material\":\"steel\",\"spacing\":0.001,"
             "\"thickness_axis\":\"z\","
             "\"geometry\":{\"box\":{\"min\":[%.17g,%.17g,0],\"max\":[%.17g,%.17g,0.003]}}}],"
             "\"cracks\":[{\"polygon\":[[-0.011,0,-0.001],[0,0,-0.001],[0,0,0.004],"
             "[-0.011,0,0.004]]}],%s"
             "\"boundary_conditions\":["
             "{\"type\":\"velocity\",\"name\":\"bottom\",\"select\":{\"box\":"
             "{\"min\":[-1,-1,-1],\"max\":[1,%.17g,1]}},"
             "\"velocity\":[null,\"-vmax*(1-exp(-t/tau))\",null]},"
             "{\"type\":\"velocity\",\"name\":\"top\",\"select\":{\"box\":"
             "{\"min\":[-1,%.17g,-1],\"max\":[1,1,1]}},"
             "\"velocity\":[null,\"vmax*(1-exp(-t/tau))\",null]}]}",
             end, x0, -y1, x1, y1, grow ? "\"crack_growth\":{\"tips\":[[0,0,0.0015]]}," : "",
             -y1 + 1.5e-3, y1 - 1.5e-3);
    return buf;
}

struct crack_totals crack_totals(const struct tlsph_model *m)
{
    struct crack_totals t = {0};
    for (size_t i = 0; i < m->p.n; i++) {
        t.mass += m->p.mass[i];
        t.vol += m->p.vol0[i];
        double v2 = 0.0;
        for (int c = 0; c < 3; c++) {
            t.mom[c] += m->p.mass[i] * m->p.v[3 * i + c];
            v2 += m->p.v[3 * i + c] * m->p.v[3 * i + c];
        }
        t.scale += m->p.mass[i] * sqrt(v2);
    }
    return t;
}
