/* rate: the molecular-chaos collision frequency of hard bodies by Monte Carlo (see rate.h). */
#include "rate.h"

#include <gsl/gsl_math.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <time.h>

#include "fmean.h"
#include "hd_body_impulse.h"

static double now_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int hd_rate_run(const hd_rate_opts *o, hd_rate_result *r, hd_error *err) {
  hd_error_clear(err);
  *r = (hd_rate_result){NAN, NAN, NAN, 0, 0, 0};
  if (!o->shape) return hd_error_set(err, HD_EINPUT, "no shape");
  if (o->samples == 1) return hd_error_set(err, HD_EINPUT, "need at least 2 samples");
  if (o->samples == 0 && !(o->seconds > 0 && isfinite(o->seconds)))
    return hd_error_set(err, HD_EINPUT, "need samples > 0 or seconds > 0");
  const hd_shape *sh = o->shape;
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  if (!rng) return hd_error_set(err, HD_ENOMEM, "cannot allocate the random number generator");
  gsl_rng_set(rng, o->seed);
  double W = 0; /* sum over disk pairs of the contact distance: the total arc per unit angle */
  for (int p = 0; p < sh->n; p++)
    for (int q = 0; q < sh->n; q++) W += 0.5 * (sh->dk[p] + sh->dk[q]);
  /* Welford's mean and variance of w = [accepted] sqrt(1/mu_eff) at T = 1 */
  double mean = 0, m2 = 0, t0 = now_seconds();
  unsigned long n = 0, acc = 0;
  for (;;) {
    if (o->samples ? n >= o->samples : (n % 4096 == 0 && n > 0 && now_seconds() - t0 >= o->seconds))
      break;
    hd_kin A, B;
    int ka, kb;
    double w = 0;
    if (hd_fmean_sample_shape(rng, sh, 1, &A, &B, &ka, &kb)) {
      hd_side a, b;
      double nx, ny;
      hd_side_of(&A, sh, ka, &a);
      hd_side_of(&B, sh, kb, &b);
      hd_pair_normal(&A, &a, &B, &b, &nx, &ny);
      w = sqrt(hd_side_inv_mass(&a, nx, ny) + hd_side_inv_mass(&b, nx, ny));
      acc++;
    }
    n++;
    double dlt = w - mean;
    mean += dlt / (double)n;
    m2 += dlt * (w - mean);
  }
  r->seconds = now_seconds() - t0;
  gsl_rng_free(rng);
  r->samples = n, r->accepted = acc;
  double se = n > 1 ? sqrt(m2 / (double)(n - 1) / (double)n) : NAN;
  /* nu / n = W 2 pi <w> / sqrt(2 pi); nu0 / n = 2 sigma sqrt(pi / M) (T = 1) */
  double c = W * sqrt(2.0 * M_PI), nu0 = 2.0 * sh->d * sqrt(M_PI / sh->mass);
  r->k = c * mean / (sh->d * sqrt(1.0 / sh->mk[0]));
  r->ratio = c * mean / nu0;
  r->ratio_err = c * se / nu0;
  return HD_OK;
}
