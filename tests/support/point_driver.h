/* Drivers for single-material-point tests: materials from scene JSON (so the
 * parameter names tested are the ones users write) and homogeneous deformation
 * paths through the engine's own tlsph_point_update. */
#ifndef TLSPH_TEST_POINT_DRIVER_H
#define TLSPH_TEST_POINT_DRIVER_H

#include "material/material_point.h"
#include "scene/scene.h"

/* The material of a one-material scene whose "m" entry is json; fails the test
 * (printing the parser's errors) when the scene is rejected. */
struct tlsph_material material(const char *json);
/* Von Mises equivalent of a symmetric tensor (6 components, xx xy xz yy yz zz). */
double von_mises(const double *s);
/* F = diag(exp(ea), exp(et), exp(et)). */
void diag_F(double ea, double et, double *F);
/* One uniaxial-stress increment to axial log strain ea: solves the lateral log
 * strain *et by Newton (numerical slope) so that the lateral Cauchy stress
 * vanishes, commits the state *s, returns the result in *r. */
void uniaxial_step(const struct tlsph_material *m, double ea, double *et, double dt,
                   struct tlsph_point_state *s, struct tlsph_point_result *r);

/* The plastic strain increment from `old` to `now` (stored in the lab frame:
 * paths without rotation): returns its equivalent deviatoric part
 * sqrt(2/3 |dev dEp|^2), *dv its trace. */
double plastic_increment(const struct tlsph_point_state *old, const struct tlsph_point_state *now,
                         double *dv);

#endif
