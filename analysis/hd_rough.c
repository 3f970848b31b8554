/* hd_rough: see hd_rough.h; the derivation is in docs/analysis.md ("Rough disks"). */
#include "hd_rough.h"

#include <math.h>

double hd_rough_eta_t(double beta, double kappa) {
  return (1.0 + beta) * kappa / (2.0 * (1.0 + kappa));
}

void hd_rough_collision_de(double alpha, double beta, double kappa, double t_tr, double t_rot,
                           double *de_tr, double *de_rot) {
  double et = hd_rough_eta_t(beta, kappa), slip = t_tr + t_rot / kappa; /* <g_t^2> m / 2 */
  *de_tr = -(1.0 - alpha * alpha) * t_tr - 2.0 * et * t_tr + 2.0 * et * et * slip;
  *de_rot = -2.0 * et * t_rot / kappa + 2.0 * et * et * slip / kappa;
}

double hd_rough_hcs_ratio(double alpha, double beta, double kappa) {
  if (!(alpha >= 0.0 && alpha <= 1.0 && beta > -1.0 && beta <= 1.0 && kappa > 0.0 && kappa <= 1.0))
    return NAN;
  double et = hd_rough_eta_t(beta, kappa);
  double a = et * et / kappa, c = -2.0 * et * et / kappa;
  double b = 2.0 * (et / kappa) * (1.0 - et / kappa) - et * (1.0 - et) -
             0.5 * (1.0 - alpha) * (1.0 + alpha);
  double disc = sqrt(b * b - 4.0 * a * c);
  /* the positive root without cancellation: 2c / (-b - disc) when b > 0 */
  return b > 0.0 ? 2.0 * c / (-b - disc) : (-b + disc) / (2.0 * a);
}

int hd_rough_window_ratio(const double *e_tr, const double *e_rot, size_t n0, size_t n1, double *r,
                          double *err) {
  *r = *err = NAN;
  if (n1 < n0 + 2 * HD_ROUGH_BLOCKS) return -1;
  size_t n = n1 - n0;
  double blk[HD_ROUGH_BLOCKS], sum = 0.0;
  for (int b = 0; b < HD_ROUGH_BLOCKS; b++) {
    size_t lo = n0 + n * (size_t)b / HD_ROUGH_BLOCKS,
           hi = n0 + n * (size_t)(b + 1) / HD_ROUGH_BLOCKS;
    double s = 0.0;
    for (size_t i = lo; i < hi; i++) {
      if (!(e_tr[i] > 0.0)) return -1;
      s += 2.0 * e_rot[i] / e_tr[i];
    }
    sum += s;
    blk[b] = s / (double)(hi - lo);
  }
  double mean = sum / (double)n, m = 0.0, v = 0.0;
  for (int b = 0; b < HD_ROUGH_BLOCKS; b++) m += blk[b] / HD_ROUGH_BLOCKS;
  for (int b = 0; b < HD_ROUGH_BLOCKS; b++) v += (blk[b] - m) * (blk[b] - m);
  *r = mean;
  *err = sqrt(v / (HD_ROUGH_BLOCKS - 1) / HD_ROUGH_BLOCKS);
  return 0;
}
