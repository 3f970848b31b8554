/* hd_enskog: the hard-disk reference of Table I: Enskog collision frequency eq. (29) with
 * the pair correlation at contact eq. (30). */
#ifndef HD_ENSKOG_H
#define HD_ENSKOG_H

/* g(sigma) = (1 - 7 eta/16) / (1 - eta)^2 for area fraction eta in [0, 1). */
double hd_enskog_g2d(double eta);

/* nu0 = 2 sqrt(pi) n sigma sqrt(T0/m) g(sigma), eq. (29): collisions per particle per unit time
 * of hard disks of diameter sigma and mass m at number density n, area fraction eta and
 * temperature T0 (energy units, kT per degree of freedom). */
double hd_enskog_nu0(double n, double sigma, double T0, double m, double eta);

#endif
