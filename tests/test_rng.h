/* The random cases of the tests: GSL's mt19937 with a fixed seed, and uniform numbers on an
 * interval (test_body.c, test_rough.c). */
#ifndef HD_TEST_RNG_H
#define HD_TEST_RNG_H

#include <gsl/gsl_rng.h>

/* A new gsl_rng_mt19937 seeded with seed; the caller frees it (gsl_rng_free). */
static inline gsl_rng *rng_new(unsigned long seed) {
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, seed);
  return r;
}

/* A uniform number in [lo, hi) drawn from r. */
static inline double unif(gsl_rng *r, double lo, double hi) {
  return lo + (hi - lo) * gsl_rng_uniform(r);
}

#endif
