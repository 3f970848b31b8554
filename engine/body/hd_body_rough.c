/* hd_body_rough.c: rough bodies (issue 29 item 5) — each disk's own moment of inertia
 * (hd_shape_set_q) and the collision rule with a tangential coefficient of restitution beta
 * (hd_collide_rough_pair, hd_collide_rough_wall).  docs/analysis.md ("Rough disks") derives
 * the rule and the homogeneous cooling state it leads to.
 *
 * The rule.  At the contact point P, r_A = P - R_A and r_B = P - R_B (P on each body's own
 * contacting disk: r_A = o_A + (d_A/2) n, r_B = o_B - (d_B/2) n, n the unit normal from A's
 * contacting disk to B's, t = z x n).  The relative velocity of the contact points is
 *   g = (V_B + omega_B z x r_B) - (V_A + omega_A z x r_A),   g_n = g.n < 0: approaching.
 * An impulse J on B (-J on A) at P changes it by K J, with the 2x2 collision matrix
 *   K = (1/M_A + 1/M_B) 1 + s_A s_A^T / I_A + s_B s_B^T / I_B,   s = z x r.
 * The energy of the pair changes by J.g + J.K J / 2 = (|g'|^2_M - |g|^2_M) / 2 in the metric
 * M = K^-1.  The smooth rule (beta = -1, today's, J along n) reverses, in that metric, the
 * component of g along w = K n: g = (g_n / K_nn) w + g_s with g_s . n = 0, i.e.
 *   g_s = (g_t - g_n K_nt / K_nn) t,
 * the slip that is left when a frictionless impulse stops the normal approach.  The rough rule
 * scales the two M-orthogonal parts by -alpha and -beta:
 *   g' = -alpha (g_n / K_nn) w - beta g_s,
 * so that  g'_n = -alpha g_n  always,  g'_t = -beta g_t  for disks (K_nt = 0: the standard
 * rough-sphere model), beta = -1 is the smooth rule, and
 *   dE = -[(1 - alpha^2) g_n^2 / K_nn + (1 - beta^2) g_st^2 K_nn / det K] / 2  <= 0,
 * zero exactly when alpha = 1 and beta = +-1 (g_st = g_s . t).  The impulse is
 *   J = -(1 + alpha) (g_n / K_nn) n - (1 + beta) g_st (-K_nt n + K_nn t) / det K.
 * (Asking g'_t = -beta g_t of a body with K_nt != 0, a dimer hit off its axis, would give a
 * tangential impulse at beta = -1 and dE = -2 M_nt g_n g_t != 0 at alpha = 1, beta = -1.)
 * Momentum, and angular momentum about P, are conserved by any impulse at P.  A body of zero
 * moment of inertia (a disk of q = 0) cannot take a torque: its K_tt is infinite, and the limit
 * of the rule is the smooth one (J_t = 0). */
#include "hd_body.h"
#include "hd_body_impulse.h"

#include <math.h>
#include <stddef.h>

int hd_shape_set_q(hd_shape *s, double q) {
  if (!(q >= 0.0 && q <= 1.0)) return -1;
  if (q == 0.0) return 0; /* the point masses of the dimer paper, bit for bit */
  double own = 0.0;
  for (int k = 0; k < s->n; k++) own += q * s->mk[k] * 0.25 * s->dk[k] * s->dk[k];
  s->inertia += own;
  if (s->tag == HD_KIND_DIMER) s->tag = HD_KIND_BODY; /* I is no longer m a^2 / 2 */
  return 0;
}

/* One body's side of a rough contact: lever r = P - R, inverse mass, inverse inertia (0 for a
 * body that cannot turn). */
typedef struct rside {
  double rx, ry; /* contact point minus centre of mass */
  double ux, uy; /* velocity of the body's material point at P */
  double w;      /* 1 / M */
  double iw;     /* 1 / I, 0 when I = 0 */
} rside;

/* The side of disk k of body (K, s); h = +d_k/2 (A: towards n) or -d_k/2 (B). */
static void rough_side(const hd_kin *K, const hd_shape *s, int k, double h, double nx, double ny,
                       rside *o) {
  double px, py;
  hd_kin_disk_pos(K, s, k, &px, &py);
  o->rx = (px - K->x) + h * s->dk[k] * nx;
  o->ry = (py - K->y) + h * s->dk[k] * ny;
  o->ux = K->vx - K->omega * o->ry;
  o->uy = K->vy + K->omega * o->rx;
  o->w = 1.0 / s->mass;
  o->iw = s->inertia > 0.0 ? 1.0 / s->inertia : 0.0;
}

static void rough_apply(hd_kin *K, const rside *o, double jx, double jy) {
  K->vx += jx * o->w;
  K->vy += jy * o->w;
  if (o->iw > 0.0) K->omega += (o->rx * jy - o->ry * jx) * o->iw;
}

/* The rule for relative velocity (gn, gt) and the sides' collision matrix; either side may be
 * NULL (a wall: infinite mass and inertia).  Fills the impulse (jn, jt) on B and the energy
 * change; *knn for the info's f. */
static void rough_rule(const rside *a, const rside *b, double nx, double ny, double gn, double gt,
                       double alpha, double beta, double *jn, double *jt, double *de,
                       double *knn_out) {
  double knn = 0.0, knt = 0.0, ktt = 0.0;
  int stiff = 0; /* a side with a lever and no inertia: K_tt infinite */
  const rside *sd[2] = {a, b};
  for (int i = 0; i < 2; i++) {
    const rside *o = sd[i];
    if (!o) continue;
    knn += o->w;
    ktt += o->w;
    double sn = o->rx * ny - o->ry * nx; /* (z x r) . n = r x n */
    double st = o->rx * nx + o->ry * ny; /* (z x r) . t = r . n */
    if (o->iw > 0.0) {
      knn += sn * sn * o->iw;
      knt += sn * st * o->iw;
      ktt += st * st * o->iw;
    } else if (st != 0.0) {
      stiff = 1;
    }
  }
  *knn_out = knn;
  double js = -(1.0 + alpha) * gn / knn;
  double loss_n = -0.5 * (1.0 - alpha) * (1.0 + alpha) * gn * gn / knn;
  if (stiff) {
    *jn = js, *jt = 0.0, *de = loss_n;
    return;
  }
  double det = knn * ktt - knt * knt;
  double gst = gt - gn * knt / knn;
  *jn = js + (1.0 + beta) * gst * knt / det;
  *jt = -(1.0 + beta) * gst * knn / det;
  *de = loss_n - 0.5 * (1.0 - beta) * (1.0 + beta) * gst * gst * knn / det;
}

int hd_collide_rough_pair(hd_kin *A, const hd_shape *sa, hd_kin *B, const hd_shape *sb, int ka,
                          int kb, double alpha, double beta, hd_collision_info *info) {
  double cax, cay, cbx, cby;
  hd_kin_disk_pos(A, sa, ka, &cax, &cay);
  hd_kin_disk_pos(B, sb, kb, &cbx, &cby);
  double dx = cbx - cax, dy = cby - cay, dd = sqrt(dx * dx + dy * dy);
  double nx = dx / dd, ny = dy / dd, tx = -ny, ty = nx;
  rside a, b;
  rough_side(A, sa, ka, 0.5, nx, ny, &a);
  rough_side(B, sb, kb, -0.5, nx, ny, &b);
  double gx = b.ux - a.ux, gy = b.uy - a.uy;
  double gn = gx * nx + gy * ny, gt = gx * tx + gy * ty;
  double jn, jt, de, knn;
  rough_rule(&a, &b, nx, ny, gn, gt, alpha, beta, &jn, &jt, &de, &knn);
  if (info) {
    hd_side sda, sdb;
    hd_side_of(A, sa, ka, &sda);
    hd_side_of(B, sb, kb, &sdb);
    info->vn = gn;
    info->theta_i = hd_side_theta(&sda, nx, ny);
    info->theta_j = hd_side_theta(&sdb, -nx, -ny);
    double mref = sa->n > 1 ? sa->mk[ka] : sb->n > 1 ? sb->mk[kb] : sa->mk[ka];
    info->f = 1.0 / (knn * mref);
    info->de = gn < 0.0 ? de : 0.0;
  }
  if (!(gn < 0.0)) return 0;
  double jx = jn * nx + jt * tx, jy = jn * ny + jt * ty;
  rough_apply(A, &a, -jx, -jy);
  rough_apply(B, &b, jx, jy);
  return 0;
}

int hd_collide_rough_wall(hd_kin *A, const hd_shape *sa, int ka, const hd_wall *w, double alpha,
                          double beta, hd_collision_info *info) {
  double nx = w->axis ? 0.0 : -w->normal, ny = w->axis ? -w->normal : 0.0; /* disk -> wall */
  double tx = -ny, ty = nx;
  rside a;
  rough_side(A, sa, ka, 0.5, nx, ny, &a);
  double gn = -(a.ux * nx + a.uy * ny), gt = -(a.ux * tx + a.uy * ty);
  double jn, jt, de, knn;
  rough_rule(&a, NULL, nx, ny, gn, gt, alpha, beta, &jn, &jt, &de, &knn);
  if (info) {
    hd_side sda;
    hd_side_of(A, sa, ka, &sda);
    info->vn = gn;
    info->theta_i = hd_side_theta(&sda, nx, ny);
    info->theta_j = NAN;
    info->f = 1.0 / (knn * sa->mk[ka]);
    info->de = gn < 0.0 ? de : 0.0;
  }
  if (!(gn < 0.0)) return 0;
  rough_apply(A, &a, -(jn * nx + jt * tx), -(jn * ny + jt * ty));
  return 0;
}
