/* hd_mixture: the Maxwellian-approximation HCS of a mixture of smooth inelastic disks. */
#include "hd_mixture.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_multiroots.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_vector.h>
#include <math.h>
#include <string.h>

void hd_mixture_chi2d(int k, const hd_mix_species *sp, double *chi) {
  double ntot = 0, phi = 0, m1 = 0, m2 = 0;
  for (int l = 0; l < k; l++) ntot += sp[l].n;
  for (int l = 0; l < k; l++) {
    double x = sp[l].n / ntot, s = sp[l].sigma;
    phi += sp[l].n * M_PI * s * s / 4, m1 += x * s, m2 += x * s * s;
  }
  for (int i = 0; i < k; i++)
    for (int j = 0; j < k; j++) {
      double si = sp[i].sigma, sj = sp[j].sigma, sij = 0.5 * (si + sj);
      chi[i * k + j] =
          1 / (1 - phi) + 9.0 / 16.0 * phi / ((1 - phi) * (1 - phi)) * (si * sj * m1) / (sij * m2);
    }
}

void hd_mixture_zeta(int k, const hd_mix_species *sp, const double *alpha, const double *chi,
                     int dim, const double *T, double *zeta) {
  double d = dim;
  /* 2^{3/2} pi^{(d-1)/2}/Gamma(d/2): the angular integral of (g.s)^3 over the half sphere
   * (4/3 at d = 2) times <g^3>/(2 T_i/m_i + ...)^{3/2} of the relative velocity; 2/d from
   * the energy d T_i/2 per body */
  double pref = 2.0 / d * pow(2.0, 1.5) * pow(M_PI, 0.5 * (d - 1)) / tgamma(0.5 * d);
  for (int i = 0; i < k; i++) {
    double z = 0;
    for (int j = 0; j < k; j++) {
      double mi = sp[i].m, mj = sp[j].m, M = mi + mj, mij = mi * mj / M, muji = mj / M;
      double a = alpha[i * k + j], c = chi ? chi[i * k + j] : 1;
      double sij = 0.5 * (sp[i].sigma + sp[j].sigma);
      double v2 = T[i] / mi + T[j] / mj, v3 = v2 * sqrt(v2);
      z += sp[j].n * c * pow(sij, d - 1) * (1 + a) * mij * v3 *
           ((T[i] - T[j]) / (M * v2) + 0.5 * muji * (1 - a));
    }
    zeta[i] = pref * z / T[i];
  }
}

/* The problem handed to the GSL solvers: temperatures from ln(T_i / T_{k-1}). */
typedef struct prob {
  int k, dim;
  const hd_mix_species *sp;
  const double *alpha, *chi;
  double scale; /* zeta_1 at equal temperatures, |.|: makes the residuals of order one */
} prob;

/* zeta_i - zeta_{k-1} (i < k-1) over the scale, at T_i = exp(y_i), T_{k-1} = 1. */
static void residuals(const prob *p, const double *y, double *f) {
  double T[HD_MIX_MAX], z[HD_MIX_MAX];
  for (int i = 0; i < p->k - 1; i++) T[i] = exp(y[i]);
  T[p->k - 1] = 1;
  hd_mixture_zeta(p->k, p->sp, p->alpha, p->chi, p->dim, T, z);
  for (int i = 0; i < p->k - 1; i++) f[i] = (z[i] - z[p->k - 1]) / p->scale;
}

static double f_one(double y, void *v) {
  double f;
  residuals(v, &y, &f);
  return f;
}

static int f_multi(const gsl_vector *y, void *v, gsl_vector *f) {
  residuals(v, y->data, f->data);
  for (size_t i = 0; i < f->size; i++)
    if (!isfinite(gsl_vector_get(f, i))) return GSL_EDOM;
  return GSL_SUCCESS;
}

/* Brent on [-40, 40] for k = 2: y = ln(T_0 / T_1). */
static int solve_two(prob *p, double *y, hd_error *err) {
  gsl_function F = {f_one, p};
  double lo = -40, hi = 40;
  if (!(f_one(lo, p) < 0 && f_one(hi, p) > 0))
    return hd_error_set(err, HD_EINPUT,
                        "mixture HCS: zeta_1 - zeta_2 does not change sign "
                        "for T_1/T_2 in [e^-40, e^40]");
  gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (!s) return hd_error_set(err, HD_ENOMEM, "out of memory");
  gsl_root_fsolver_set(s, &F, lo, hi);
  int st = GSL_CONTINUE;
  for (int it = 0; it < 200 && st == GSL_CONTINUE; it++) {
    if (gsl_root_fsolver_iterate(s)) break;
    st = gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), 1e-14, 0);
  }
  *y = gsl_root_fsolver_root(s);
  gsl_root_fsolver_free(s);
  if (st != GSL_SUCCESS) return hd_error_set(err, HD_EINPUT, "mixture HCS: Brent did not converge");
  return HD_OK;
}

/* GSL's hybrid solver for k > 2 from equal temperatures (y = 0). */
static int solve_many(prob *p, double *y, hd_error *err) {
  size_t n = (size_t)(p->k - 1);
  gsl_multiroot_function F = {f_multi, n, p};
  gsl_multiroot_fsolver *s = gsl_multiroot_fsolver_alloc(gsl_multiroot_fsolver_hybrids, n);
  gsl_vector *y0 = gsl_vector_calloc(n);
  if (!s || !y0) {
    if (s) gsl_multiroot_fsolver_free(s);
    if (y0) gsl_vector_free(y0);
    return hd_error_set(err, HD_ENOMEM, "out of memory");
  }
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  int st = gsl_multiroot_fsolver_set(s, &F, y0);
  for (int it = 0; it < 1000 && st == GSL_SUCCESS; it++) {
    if (gsl_multiroot_fsolver_iterate(s)) {
      st = GSL_EFAILED;
      break;
    }
    if (gsl_multiroot_test_residual(s->f, 1e-13) == GSL_SUCCESS) break;
  }
  if (st == GSL_SUCCESS && gsl_multiroot_test_residual(s->f, 1e-10) != GSL_SUCCESS)
    st = GSL_EFAILED;
  gsl_set_error_handler(old);
  for (size_t i = 0; i < n; i++) y[i] = gsl_vector_get(s->x, i);
  gsl_multiroot_fsolver_free(s), gsl_vector_free(y0);
  if (st != GSL_SUCCESS)
    return hd_error_set(err, HD_EINPUT, "mixture HCS: the hybrid solver did not converge");
  return HD_OK;
}

int hd_mixture_hcs(int k, const hd_mix_species *sp, const double *alpha, const double *chi, int dim,
                   double *ratio, hd_error *err) {
  if (k < 1 || k > HD_MIX_MAX)
    return hd_error_set(err, HD_EINPUT, "mixture HCS: %d species, need 1 to %d", k, HD_MIX_MAX);
  if (dim != 2 && dim != 3)
    return hd_error_set(err, HD_EINPUT, "mixture HCS: dimension %d, need 2 or 3", dim);
  for (int i = 0; i < k; i++) {
    if (!(sp[i].n > 0 && sp[i].sigma > 0 && sp[i].m > 0) ||
        !isfinite(sp[i].n * sp[i].sigma * sp[i].m))
      return hd_error_set(err, HD_EINPUT,
                          "mixture HCS: species %d: n = %g, sigma = %g, m = %g: each must be > 0",
                          i, sp[i].n, sp[i].sigma, sp[i].m);
    for (int j = 0; j < k; j++)
      if (!(alpha[i * k + j] >= 0 && alpha[i * k + j] <= 1))
        return hd_error_set(err, HD_EINPUT, "mixture HCS: alpha_%d%d = %g: must be in [0, 1]", i, j,
                            alpha[i * k + j]);
  }
  double y[HD_MIX_MAX] = {0}, T[HD_MIX_MAX], z[HD_MIX_MAX];
  for (int i = 0; i < k; i++) T[i] = 1;
  hd_mixture_zeta(k, sp, alpha, chi, dim, T, z);
  prob p = {k, dim, sp, alpha, chi, 0};
  for (int i = 0; i < k; i++) p.scale += fabs(z[i]);
  if (!(p.scale > 0)) { /* every alpha = 1 with equal temperatures: no cooling, no selection */
    double rate = 0;    /* then the scale of the exchange term picks equipartition */
    for (int j = 0; j < k; j++) rate += sp[j].n * sp[j].sigma * sqrt(1 / sp[j].m);
    p.scale = rate;
  }
  int rc = k == 1 ? HD_OK : k == 2 ? solve_two(&p, y, err) : solve_many(&p, y, err);
  if (rc) return rc;
  double ntot = 0, Tm = 0;
  for (int i = 0; i < k; i++) ntot += sp[i].n;
  for (int i = 0; i < k; i++) T[i] = i < k - 1 ? exp(y[i]) : 1, Tm += sp[i].n / ntot * T[i];
  for (int i = 0; i < k; i++) ratio[i] = T[i] / Tm;
  return HD_OK;
}
