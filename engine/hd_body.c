/* PLACEHOLDER (disk bodies only) until the dimer kinematics of the body branch land: hd_body.h
 * is the contract; this file implements it for disk bodies so that the engine builds. */
#include <math.h>
#include "hd_body.h"
#include "hd_disk.h"
double hd_shape_mass(const hd_shape *s) { return s->kind == HD_KIND_DIMER ? 2 * s->m : s->m; }
double hd_shape_inertia(const hd_shape *s) { return s->kind == HD_KIND_DIMER ? 0.5 * s->m * s->a * s->a : 0; }
double hd_shape_radius(const hd_shape *s) { return 0.5 * (s->a + s->d); }
void hd_kin_advance(hd_kin *k, double dt) { k->x += k->vx * dt; k->y += k->vy * dt; k->phi = remainder(k->phi + k->omega * dt, 2 * M_PI); }
void hd_kin_disk_pos(const hd_kin *k, const hd_shape *s, int w, double *px, double *py) {
  double h = s->kind == HD_KIND_DIMER ? (w ? 0.5 : -0.5) * s->a : 0;
  *px = k->x + h * cos(k->phi); *py = k->y + h * sin(k->phi); }
int hd_predict_pair(const hd_kin *A, const hd_shape *sa, const hd_kin *B, const hd_shape *sb, double tmax, hd_contact *c) {
  double t = hd_disk_contact_time(B->x - A->x, B->y - A->y, B->vx - A->vx, B->vy - A->vy, 0.5 * (sa->d + sb->d));
  if (t > tmax) return 0;
  c->t = t; c->ka = c->kb = 0; return 1; }
int hd_predict_wall(const hd_kin *A, const hd_shape *sa, const hd_wall *w, double tmax, hd_contact *c) {
  double p = w->axis ? A->y : A->x, v = w->axis ? A->vy : A->vx;
  if (v * w->normal >= 0) return 0;
  double t = (w->pos + w->normal * 0.5 * sa->d - p) / v;
  if (t < 0) t = 0;
  if (t > tmax) return 0;
  c->t = t; c->ka = 0; c->kb = 0; return 1; }
int hd_collide_pair(hd_kin *A, const hd_shape *sa, hd_kin *B, const hd_shape *sb, int ka, int kb, double alpha, hd_collision_info *info) {
  (void)ka; (void)kb;
  double rx = B->x - A->x, ry = B->y - A->y, r = hypot(rx, ry); rx /= r; ry /= r;
  double vn = (B->vx - A->vx) * rx + (B->vy - A->vy) * ry;
  double ma = sa->m, mb = sb->m, mu = ma * mb / (ma + mb), J = -(1 + alpha) * mu * vn;
  A->vx -= J / ma * rx; A->vy -= J / ma * ry; B->vx += J / mb * rx; B->vy += J / mb * ry;
  info->theta_i = info->theta_j = NAN; info->f = mu / ma; info->vn = vn; info->de = -0.5 * (1 - alpha * alpha) * mu * vn * vn; return 0; }
int hd_collide_wall(hd_kin *A, const hd_shape *sa, int ka, const hd_wall *w, double alpha, hd_collision_info *info) {
  (void)ka; double *v = w->axis ? &A->vy : &A->vx; double vn = *v * w->normal;
  info->de = -0.5 * sa->m * (1 - alpha * alpha) * vn * vn; *v = -alpha * *v; info->vn = vn; info->f = 1; info->theta_i = info->theta_j = NAN; return 0; }
