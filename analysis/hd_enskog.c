#include "hd_enskog.h"

#include <math.h>

double hd_enskog_g2d(double eta) {
  return (1.0 - 7.0 * eta / 16.0) / ((1.0 - eta) * (1.0 - eta));
}

double hd_enskog_nu0(double n, double sigma, double T0, double m, double eta) {
  return 2.0 * sqrt(M_PI) * n * sigma * sqrt(T0 / m) * hd_enskog_g2d(eta);
}
