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
