/* hd_mixture: the homogeneous cooling state of a mixture of smooth inelastic hard disks in the
 * Maxwellian approximation of Garzo and Dufty (PRE 60, 5706, 1999), written for any dimension
 * d and used at d = 2 (docs/analysis.md, "Mixtures: the temperature ratio").  Each species i
 * has its own Maxwellian of temperature T_i (kinetic energy per body d T_i / 2); the cooling
 * rates zeta_i = -d ln T_i / dt follow from the Boltzmann-Enskog collision integral, and the
 * HCS is where they are all equal, which fixes the ratios T_i / T.  These functions never
 * print; the solver returns an hd_status. */
#ifndef HD_MIXTURE_H
#define HD_MIXTURE_H

#include "hd_error.h"

/* Most species of one mixture (the engine's HD_MAX_SPECIES). */
#define HD_MIX_MAX 8

/* One species of the mixture. */
typedef struct hd_mix_species {
  double n;     /* number density, > 0 (bodies per unit area at d = 2) */
  double sigma; /* diameter, > 0 */
  double m;     /* mass, > 0 */
} hd_mix_species;

/* The Enskog pair correlation at contact of species i and j of a mixture of k hard disks
 * (d = 2): chi_ij = 1/(1 - phi) + (9/16) phi/(1 - phi)^2 (sigma_i sigma_j M1)/(sigma_ij M2),
 * phi = sum_l n_l pi sigma_l^2/4, sigma_ij = (sigma_i + sigma_j)/2, M_p = sum_l x_l sigma_l^p
 * (Jenkins and Mancini, J. Appl. Mech. 54, 27, 1987); one species: (1 - 7 phi/16)/(1 - phi)^2, eq.
 * (30) (hd_enskog_g2d).  Fills chi[i * k + j] for i, j < k. */
void hd_mixture_chi2d(int k, const hd_mix_species *sp, double *chi);

/* The cooling rates zeta[i] (per unit time) of the k species at temperatures T[0..k) in the
 * Maxwellian approximation, in dimension dim (2 or 3; docs/analysis.md):
 *   zeta_i = 2^{5/2} pi^{(d-1)/2} / (d Gamma(d/2)) / T_i  sum_j n_j chi_ij sigma_ij^{d-1}
 *            (1 + alpha_ij) m_ij v_ij^3 [ (T_i - T_j)/((m_i + m_j) v_ij^2) + mu_ji (1-alpha_ij)/2 ]
 * with m_ij = m_i m_j/(m_i + m_j), mu_ji = m_j/(m_i + m_j), v_ij^2 = T_i/m_i + T_j/m_j.  alpha and
 * chi are k x k (row-major, symmetric); chi NULL means every chi_ij = 1 (the dilute limit). */
void hd_mixture_zeta(int k, const hd_mix_species *sp, const double *alpha, const double *chi,
                     int dim, const double *T, double *zeta);

/* The HCS of the k species (1 <= k <= HD_MIX_MAX): ratio[i] = T_i / T with T = sum_i x_i T_i,
 * x_i = n_i / sum n, where zeta_1 = ... = zeta_k (hd_mixture_zeta).  Two species: GSL's Brent
 * root finder on ln(T_1/T_2) in [-40, 40] (the difference zeta_1 - zeta_2 changes sign there:
 * a species much colder than the other is heated by it); more: GSL's hybrid multidimensional
 * solver on ln(T_i/T_k) from equal temperatures.  Returns HD_OK, or HD_EINPUT with err set
 * for bad input (k out of range, n, sigma, m not > 0, alpha outside [0, 1], dim not 2 or 3)
 * or a solver that did not converge. */
int hd_mixture_hcs(int k, const hd_mix_species *sp, const double *alpha, const double *chi, int dim,
                   double *ratio, hd_error *err);

#endif
