/* hd_rough: the homogeneous cooling state of rough disks (issue 29 item 5; derivation in
 * docs/analysis.md, "Rough disks"): the cooling rates of the translational and rotational
 * temperatures of a dilute gas of equal disks with normal restitution alpha, tangential
 * restitution beta and reduced moment of inertia kappa = 4 I / (m d^2) (= q of the scene key),
 * in the Maxwellian (two-temperature Gaussian) approximation, and the ratio
 * R = T_rot / T_tr at which they are equal.  T_tr = m <v^2> / 2 and T_rot = I <omega^2> (kT per
 * degree of freedom: E_tr / N = T_tr, E_rot / N = T_rot / 2). */
#ifndef HD_ROUGH_H
#define HD_ROUGH_H

#include <stddef.h>

/* eta_t = (1 + beta) kappa / (2 (1 + kappa)): the share of the tangential slip a collision of
 * two equal disks removes from each disk's velocity. */
double hd_rough_eta_t(double beta, double kappa);

/* Mean energy changes per collision of two equal disks at temperatures t_tr, t_rot (Maxwellian,
 * collisions weighted by their normal speed): *de_tr (translational, both disks) and *de_rot.
 * Then dT_tr/dt = nu de_tr / 2 and dT_rot/dt = nu de_rot (nu: collisions per disk per time). */
void hd_rough_collision_de(double alpha, double beta, double kappa, double t_tr, double t_rot,
                           double *de_tr, double *de_rot);

/* The HCS ratio R = T_rot / T_tr: the positive root of
 *   (eta_t^2 / kappa) R^2 + [2 (eta_t / kappa)(1 - eta_t / kappa) - eta_t (1 - eta_t)
 *                             - (1 - alpha^2) / 2] R - 2 eta_t^2 / kappa = 0.
 * alpha in [0, 1], beta in (-1, 1], kappa in (0, 1]; NaN otherwise (beta = -1: smooth disks keep
 * their spins, there is no ratio). */
double hd_rough_hcs_ratio(double alpha, double beta, double kappa);

/* The measured ratio over samples [n0, n1) of a run whose every body turns (one rotational
 * degree of freedom each): R = 2 e_rot / e_tr averaged over the samples, *err the standard error
 * of that mean from HD_ROUGH_BLOCKS consecutive blocks (the samples of a block are correlated,
 * the blocks nearly not).  Returns 0, or -1 (NaNs) with fewer than 2 samples per block or an
 * e_tr <= 0. */
#define HD_ROUGH_BLOCKS 8
int hd_rough_window_ratio(const double *e_tr, const double *e_rot, size_t n0, size_t n1, double *r,
                          double *err);

#endif
