/* hd_sim_state: O(N) measures of flow and density at a sample (hd_sim.h, hd_sim_state). */
#include <math.h>
#include <stdlib.h>

#include "hd_sim.h"

/* Side of the coarse grid: HD_STATE_GRID x HD_STATE_GRID cells, the box's largest scales,
 * where the shear instability of the homogeneous cooling state grows first. */
#define HD_STATE_GRID 4

void hd_sim_state(const hd_sim *s, hd_state_measures *out) {
  enum { G = HD_STATE_GRID, NC = G * G, NK = 4 };
  double cm[NC] = {0}, cpx[NC] = {0}, cpy[NC] = {0}, cw[NC] = {0};
  long cn[NC] = {0};
  /* the four smallest wave vectors of the box: k = 2 pi (nx/Lx, ny/Ly) for (nx, ny) = (1, 0),
   * (0, 1), (1, 1), (1, -1); rho_k = sum e^{i k.r}, p_k = sum m v e^{i k.r} */
  static const int kn[NK][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
  double kx[NK], ky[NK];
  double rr[NK] = {0}, ri[NK] = {0}, pxr[NK] = {0}, pxi[NK] = {0}, pyr[NK] = {0}, pyi[NK] = {0};
  double ax = 2.0 * M_PI / s->lx, ay = 2.0 * M_PI / s->ly;
  for (int q = 0; q < NK; q++) kx[q] = ax * kn[q][0], ky[q] = ay * kn[q][1];
  double m2vx2 = 0, m2vy2 = 0, m2vxy = 0, mv2 = 0;
  for (int32_t i = 0; i < s->n; i++) {
    hd_kin k;
    hd_sim_body_now(s, i, &k);
    double m = hd_shape_mass(&s->shape[s->b[i].species]);
    double x = k.x - s->lx * floor(k.x / s->lx), y = k.y - s->ly * floor(k.y / s->ly);
    int cx = (int)(x / s->lx * G), cy = (int)(y / s->ly * G);
    cx = cx < 0 ? 0 : cx >= G ? G - 1 : cx, cy = cy < 0 ? 0 : cy >= G ? G - 1 : cy;
    int c = cy * G + cx;
    cn[c]++, cm[c] += m, cpx[c] += m * k.vx, cpy[c] += m * k.vy;
    cw[c] += m * m * (k.vx * k.vx + k.vy * k.vy);
    mv2 += m * (k.vx * k.vx + k.vy * k.vy);
    m2vx2 += m * m * k.vx * k.vx, m2vy2 += m * m * k.vy * k.vy, m2vxy += m * m * k.vx * k.vy;
    /* e^{i(ax x)}, e^{i(ay y)} once, the sums by angle addition */
    double sx = sin(ax * x), cxs = cos(ax * x), sy = sin(ay * y), cys = cos(ay * y);
    double re[NK] = {cxs, cys, cxs * cys - sx * sy, cxs * cys + sx * sy};
    double im[NK] = {sx, sy, sx * cys + cxs * sy, sx * cys - cxs * sy};
    for (int q = 0; q < NK; q++) {
      rr[q] += re[q], ri[q] += im[q];
      pxr[q] += m * k.vx * re[q], pxi[q] += m * k.vx * im[q];
      pyr[q] += m * k.vy * re[q], pyi[q] += m * k.vy * im[q];
    }
  }
  double n = (double)s->n;
  /* coarse-grained flow: sum_c |P_c|^2 / M_c over the cells against sum m v^2; its value for
   * independent velocities of zero mean is sum_c (sum_{i in c} m_i^2 v_i^2) / M_c */
  double flow = 0, chaos = 0, mean = n / NC, var = 0;
  for (int c = 0; c < NC; c++) {
    if (cm[c] > 0) flow += (cpx[c] * cpx[c] + cpy[c] * cpy[c]) / cm[c], chaos += cw[c] / cm[c];
    var += ((double)cn[c] - mean) * ((double)cn[c] - mean);
  }
  out->flow_frac = mv2 > 0 ? flow / mv2 : NAN;
  out->flow_chaos = mv2 > 0 ? chaos / mv2 : NAN;
  out->count_var = n > 0 ? var / NC / mean : NAN;
  /* structure factors, averaged over the NK wave vectors (those where defined): S_rho = |rho_k|^2 /
   * N; transverse and longitudinal momentum |p_k . e|^2 over its value for independent velocities,
   * sum m^2 (v . e)^2 (e = k/|k| or its normal) */
  double sr = 0, st = 0, sl = 0;
  int nt = 0, nl = 0; /* modes where the normalisation is > 0 (not all velocities along k) */
  for (int q = 0; q < NK; q++) {
    double kk = hypot(kx[q], ky[q]), ex = kx[q] / kk, ey = ky[q] / kk;
    double lr = ex * pxr[q] + ey * pyr[q], li = ex * pxi[q] + ey * pyi[q];
    double tr = -ey * pxr[q] + ex * pyr[q], ti = -ey * pxi[q] + ex * pyi[q];
    double norm_l = ex * ex * m2vx2 + ey * ey * m2vy2 + 2 * ex * ey * m2vxy;
    double norm_t = ey * ey * m2vx2 + ex * ex * m2vy2 - 2 * ex * ey * m2vxy;
    sr += (rr[q] * rr[q] + ri[q] * ri[q]) / n;
    if (norm_l > 0) sl += (lr * lr + li * li) / norm_l, nl++;
    if (norm_t > 0) st += (tr * tr + ti * ti) / norm_t, nt++;
  }
  out->s_rho = n > 0 ? sr / NK : NAN;
  out->s_par = nl ? sl / nl : NAN;
  out->s_perp = nt ? st / nt : NAN;
}
