/* hd_body_impulse.c: contact geometry, collision info and the generic rigid-body impulse rule
 * (see hd_body_impulse.h).  f = mu_eff / m_ref with m_ref the disk mass m of the dimer involved
 * (A's if both are dimers), or A's mass for disk-disk and disk-wall collisions:
 *   dimer-dimer (same m)  f = 1 / (2 - (cos^2 th_i + cos^2 th_j)/2)        (eq. 36)
 *   dimer-disk            f = 1 / (1 + m/M - cos^2 th / 2)                  (eq. 22-23)
 *   dimer-wall            f = 1 / (1 - cos^2 th / 2)                        (eq. 25-26)
 *   disk-disk             f = M_B / (M_A + M_B)  (1/2 for equal masses)     (eq. 20)
 *   disk-wall             f = 1. */
#include "hd_body_impulse.h"

#include <math.h>

void hd_side_of(const hd_kin *k, const hd_shape *s, int which, hd_side *o) {
  o->mass = hd_shape_mass(s);
  o->inertia = hd_shape_inertia(s);
  o->gen = 0;
  if (s->tag == HD_KIND_BODY) {
    double sn, cs, bx = s->ox[which], by = s->oy[which];
    sincos(k->phi, &sn, &cs);
    o->m = s->mk[which];
    o->ox = bx * cs - by * sn;
    o->oy = bx * sn + by * cs;
    double r = hypot(o->ox, o->oy);
    o->ex = r > 0.0 ? o->ox / r : 0.0;
    o->ey = r > 0.0 ? o->oy / r : 0.0;
    o->vx = k->vx - k->omega * o->oy;
    o->vy = k->vy + k->omega * o->ox;
    o->a = 0.0;
    o->rot = o->inertia > 0.0;
    o->gen = 1;
    return;
  }
  o->m = s->m;
  if (s->tag != HD_KIND_DIMER) {
    o->ex = o->ey = o->ox = o->oy = 0.0;
    o->vx = k->vx;
    o->vy = k->vy;
    o->a = 0.0;
    o->rot = 0;
    return;
  }
  double sn, cs, sg = which ? 1.0 : -1.0, h = 0.5 * s->a;
  sincos(k->phi, &sn, &cs);
  o->ex = sg * cs;
  o->ey = sg * sn;
  o->ox = h * o->ex;
  o->oy = h * o->ey;
  o->vx = k->vx - k->omega * o->oy;
  o->vy = k->vy + k->omega * o->ox;
  o->a = s->a;
  o->rot = s->a > 0.0;
}

double hd_side_inv_mass(const hd_side *o, double nx, double ny) {
  double w = 1.0 / o->mass;
  if (o->rot && o->gen) {
    double x = o->ox * ny - o->oy * nx; /* rho x n */
    w += x * x / o->inertia;
  } else if (o->rot) {
    double x = o->ex * ny - o->ey * nx;
    w += x * x / (2.0 * o->m);
  }
  return w;
}

double hd_side_theta(const hd_side *o, double nx, double ny) {
  if (o->ex == 0.0 && o->ey == 0.0) return NAN;
  double t = atan2(o->ex * ny - o->ey * nx, o->ex * nx + o->ey * ny);
  return t <= -M_PI ? M_PI : t;
}

void hd_pair_normal(const hd_kin *A, const hd_side *sa, const hd_kin *B, const hd_side *sb,
                    double *nx, double *ny) {
  double rx = (B->x - A->x) + (sb->ox - sa->ox), ry = (B->y - A->y) + (sb->oy - sa->oy);
  double r = sqrt(rx * rx + ry * ry);
  *nx = rx / r;
  *ny = ry / r;
}

/* m_ref of a pair (see the head of this file): the contacting disk's mass of the first body
 * with more than one disk (A's if both or neither have). */
static double pair_mref(const hd_shape *sa, int ka, const hd_shape *sb, int kb) {
  if (sa->n > 1) return sa->mk[ka];
  if (sb->n > 1) return sb->mk[kb];
  return sa->mk[ka];
}

/* Energy change -(1 - alpha^2) mu vn^2 / 2 of an approaching contact (0 otherwise). */
static double loss(double alpha, double vn, double inv_mu) {
  return vn < 0.0 ? -0.5 * (1.0 - alpha) * (1.0 + alpha) * vn * vn / inv_mu : 0.0;
}

void hd_pair_info_sides(const hd_kin *A, const hd_side *a, const hd_shape *sa, int ka,
                        const hd_kin *B, const hd_side *b, const hd_shape *sb, int kb, double alpha,
                        int angles, hd_collision_info *info) {
  double nx, ny;
  hd_pair_normal(A, a, B, b, &nx, &ny);
  double inv_mu = hd_side_inv_mass(a, nx, ny) + hd_side_inv_mass(b, nx, ny);
  info->vn = (b->vx - a->vx) * nx + (b->vy - a->vy) * ny;
  info->theta_i = angles ? hd_side_theta(a, nx, ny) : NAN;
  info->theta_j = angles ? hd_side_theta(b, -nx, -ny) : NAN;
  info->f = 1.0 / (inv_mu * pair_mref(sa, ka, sb, kb));
  info->de = loss(alpha, info->vn, inv_mu);
}

void hd_pair_info(const hd_kin *A, const hd_shape *sa, const hd_kin *B, const hd_shape *sb, int ka,
                  int kb, double alpha, hd_collision_info *info) {
  hd_side a, b;
  hd_side_of(A, sa, ka, &a);
  hd_side_of(B, sb, kb, &b);
  hd_pair_info_sides(A, &a, sa, ka, B, &b, sb, kb, alpha, 1, info);
}

/* The unit normal from a disk to wall w. */
static void wall_normal(const hd_wall *w, double *nx, double *ny) {
  *nx = w->axis ? 0.0 : -w->normal;
  *ny = w->axis ? -w->normal : 0.0;
}

void hd_wall_info(const hd_kin *A, const hd_shape *sa, int ka, const hd_wall *w, double alpha,
                  hd_collision_info *info) {
  hd_side a;
  double nx, ny;
  hd_side_of(A, sa, ka, &a);
  wall_normal(w, &nx, &ny);
  double inv_mu = hd_side_inv_mass(&a, nx, ny);
  info->vn = -(a.vx * nx + a.vy * ny);
  info->theta_i = hd_side_theta(&a, nx, ny);
  info->theta_j = NAN;
  info->f = 1.0 / (inv_mu * sa->mk[ka]);
  info->de = loss(alpha, info->vn, inv_mu);
}

/* Applies the impulse (px, py) at side o of body k. */
static void apply(hd_kin *k, const hd_side *o, double px, double py) {
  k->vx += px / o->mass;
  k->vy += py / o->mass;
  if (o->rot && o->gen)
    k->omega += (o->ox * py - o->oy * px) / o->inertia; /* (rho x P) / I */
  else if (o->rot)
    k->omega += (o->ex * py - o->ey * px) / (o->m * o->a); /* (rho x P) / I for a dimer */
}

int hd_impulse_pair(hd_kin *A, const hd_shape *sa, hd_kin *B, const hd_shape *sb, int ka, int kb,
                    double alpha, hd_collision_info *info) {
  return hd_impulse_pair_ex(A, sa, B, sb, ka, kb, alpha, 1, info);
}

int hd_impulse_pair_ex(hd_kin *A, const hd_shape *sa, hd_kin *B, const hd_shape *sb, int ka, int kb,
                       double alpha, int angles, hd_collision_info *info) {
  hd_side a, b;
  double nx, ny;
  hd_side_of(A, sa, ka, &a);
  hd_side_of(B, sb, kb, &b);
  hd_pair_normal(A, &a, B, &b, &nx, &ny);
  double inv_mu = hd_side_inv_mass(&a, nx, ny) + hd_side_inv_mass(&b, nx, ny);
  double vn = (b.vx - a.vx) * nx + (b.vy - a.vy) * ny;
  if (info) hd_pair_info_sides(A, &a, sa, ka, B, &b, sb, kb, alpha, angles, info);
  if (!(vn < 0.0)) return 0;
  double J = -(1.0 + alpha) * vn / inv_mu;
  apply(A, &a, -J * nx, -J * ny);
  apply(B, &b, J * nx, J * ny);
  return 0;
}

int hd_impulse_wall(hd_kin *A, const hd_shape *sa, int ka, const hd_wall *w, double alpha,
                    hd_collision_info *info) {
  hd_side a;
  double nx, ny;
  hd_side_of(A, sa, ka, &a);
  wall_normal(w, &nx, &ny);
  double inv_mu = hd_side_inv_mass(&a, nx, ny);
  double vn = -(a.vx * nx + a.vy * ny);
  if (info) hd_wall_info(A, sa, ka, w, alpha, info);
  if (!(vn < 0.0)) return 0;
  double J = -(1.0 + alpha) * vn / inv_mu;
  apply(A, &a, -J * nx, -J * ny);
  return 0;
}
