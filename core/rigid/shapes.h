/* Signed distance and outward normal of each rigid shape, in the shape's own
 * frame (rigid.h: origin at the reference point c, z along the axis), exact.
 *
 * Each function takes the point y (m) and returns d (m): > 0 outside, < 0
 * inside, |d| the distance to the surface; n gets the outward unit normal of
 * the surface at the closest point (the gradient of d).  They are inlined into
 * the contact loop compiled for their shape (core/rigid/contact.c), so no
 * particle dispatches on the shape.
 *
 * size[] (struct tlsph_rigid_spec):
 *   plane     -                        d = y_z
 *   box       half sizes a, b, c       (2-D: c = INFINITY, a prism along z)
 *   sphere    radius r
 *   cylinder  radius r, half length l  (axis z from -l to l, flat end caps)
 *   cone      base radius R, height h, apex-to-centroid distance za
 *             (apex at z = -za, base disc at z = h - za)
 * A cylinder or cone is a solid of revolution: its distance is that of the
 * section (rho = distance from the axis, z) to the section's boundary, which
 * for a point in a plane through the axis is attained in that plane; so the
 * same functions are exact for the 2-D sections (a rectangle, a triangle) when
 * the axis lies in the x-y plane. */
#ifndef TLSPH_RIGID_SHAPES_H
#define TLSPH_RIGID_SHAPES_H

#include <math.h>

static inline __attribute__((always_inline)) double
rigid_plane_distance(const double *size, const double y[3], double n[3])
{
    (void)size;
    n[0] = 0.0;
    n[1] = 0.0;
    n[2] = 1.0;
    return y[2];
}

static inline __attribute__((always_inline)) double
rigid_box_distance(const double *size, const double y[3], double n[3])
{
    double q[3], o[3], out2 = 0.0, inner = -INFINITY;
    int face = 0;
    for (int k = 0; k < 3; k++) {
        q[k] = fabs(y[k]) - size[k];
        o[k] = q[k] > 0.0 ? q[k] : 0.0;
        out2 += o[k] * o[k];
        if (q[k] > inner) {
            inner = q[k];
            face = k;
        }
    }
    if (out2 > 0.0) { /* outside: towards the closest point of a face, edge or corner */
        const double d = sqrt(out2);
        for (int k = 0; k < 3; k++)
            n[k] = copysign(o[k], y[k]) / d;
        return d;
    }
    /* inside (or on the surface): the nearest face */
    n[0] = n[1] = n[2] = 0.0;
    n[face] = y[face] < 0.0 ? -1.0 : 1.0;
    return inner;
}

static inline __attribute__((always_inline)) double
rigid_sphere_distance(const double *size, const double y[3], double n[3])
{
    const double r = sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
    if (r > 0.0) {
        n[0] = y[0] / r;
        n[1] = y[1] / r;
        n[2] = y[2] / r;
    } else {
        n[0] = n[1] = 0.0;
        n[2] = 1.0;
    }
    return r - size[0];
}

/* (rho, z) section normal -> 3-D: n = n_rho e_rho + n_z e_z, e_rho the
 * direction from the axis (x when the point is on it). */
static inline __attribute__((always_inline)) void rigid_revolve(const double y[3], double rho,
                                                                double nr, double nz, double n[3])
{
    if (rho > 0.0) {
        n[0] = nr * y[0] / rho;
        n[1] = nr * y[1] / rho;
    } else {
        n[0] = nr;
        n[1] = 0.0;
    }
    n[2] = nz;
}

static inline __attribute__((always_inline)) double
rigid_cylinder_distance(const double *size, const double y[3], double n[3])
{
    const double rho = sqrt(y[0] * y[0] + y[1] * y[1]);
    const double q0 = rho - size[0], q1 = fabs(y[2]) - size[1];
    const double o0 = q0 > 0.0 ? q0 : 0.0, o1 = q1 > 0.0 ? q1 : 0.0;
    const double sz = y[2] < 0.0 ? -1.0 : 1.0;
    if (o0 > 0.0 || o1 > 0.0) {
        const double d = sqrt(o0 * o0 + o1 * o1);
        rigid_revolve(y, rho, o0 / d, sz * o1 / d, n);
        return d;
    }
    if (q0 > q1) { /* nearest: the curved surface */
        rigid_revolve(y, rho, 1.0, 0.0, n);
        return q0;
    }
    rigid_revolve(y, rho, 0.0, sz, n); /* nearest: an end cap */
    return q1;
}

/* Squared distance from (px, pz) to the segment a-b of the section, and the
 * closest point (cx, cz). */
static inline __attribute__((always_inline)) double rigid_segment(double px, double pz, double ax,
                                                                  double az, double bx, double bz,
                                                                  double *cx, double *cz)
{
    const double ex = bx - ax, ez = bz - az;
    double s = ((px - ax) * ex + (pz - az) * ez) / (ex * ex + ez * ez);
    s = s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
    *cx = ax + s * ex;
    *cz = az + s * ez;
    return (px - *cx) * (px - *cx) + (pz - *cz) * (pz - *cz);
}

static inline __attribute__((always_inline)) double
rigid_cone_distance(const double *size, const double y[3], double n[3])
{
    const double R = size[0], h = size[1];
    const double rho = sqrt(y[0] * y[0] + y[1] * y[1]);
    const double z = y[2] + size[2]; /* from the apex, along the axis */
    /* the section's surface: the slant apex (0,0) - rim (R,h), the base (0,h) - (R,h) */
    double sx, sz, bx, bz;
    const double ds = rigid_segment(rho, z, 0.0, 0.0, R, h, &sx, &sz);
    const double db = rigid_segment(rho, z, 0.0, h, R, h, &bx, &bz);
    const int slant = ds <= db;
    const double cx = slant ? sx : bx, cz = slant ? sz : bz;
    const double dist = sqrt(slant ? ds : db);
    const int inside = z >= 0.0 && z <= h && rho * h <= R * z;
    if (dist > 0.0) {
        const double s = inside ? -1.0 : 1.0; /* outward: from the surface to p, or back */
        rigid_revolve(y, rho, s * (rho - cx) / dist, s * (z - cz) / dist, n);
    } else if (slant) { /* on the slant: its outward normal (h, -R)/|.| */
        const double l = sqrt(R * R + h * h);
        rigid_revolve(y, rho, h / l, -R / l, n);
    } else {
        rigid_revolve(y, rho, 0.0, 1.0, n);
    }
    return inside ? -dist : dist;
}

#endif
