/* Helpers of the tests that look inside the 2D engine (hd_sim_internal.h). */
#ifndef HD_TEST_SIM_H
#define HD_TEST_SIM_H

#include "hd_sim_internal.h"

/* Total momentum (*px, *py) of the bodies of s (was hd_sim_momentum of the library, which only
 * the tests called). */
static inline void test_sim_momentum(const hd_sim *s, double *px, double *py) {
  double x = 0.0, y = 0.0;
  for (int32_t i = 0; i < s->n; i++) {
    double m = hd_shape_mass(&s->shape[s->b[i].species]);
    x += m * s->b[i].k.vx;
    y += m * s->b[i].k.vy;
  }
  *px = x;
  *py = y;
}

/* Kinetic energy (translational + rotational) of a body from its mass and moment of inertia
 * (hd_shape_mass, hd_shape_inertia: what the engine uses; a disk turns only with q > 0,
 * hd_shape_set_q); was hd_kin_energy of the library, which only the tests called. */
static inline double test_kin_energy(const hd_kin *k, const hd_shape *s) {
  double e = 0.5 * hd_shape_mass(s) * (k->vx * k->vx + k->vy * k->vy);
  if (s->tag != HD_KIND_DISK || s->inertia > 0.0)
    e += 0.5 * hd_shape_inertia(s) * k->omega * k->omega;
  return e;
}

#endif
