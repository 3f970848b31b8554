/* hd_body_collide.c: the collision rules of Costantini et al. (2005), Sec. II B, written with the
 * paper's vectors and per-disk velocity updates, then converted to (V, omega):
 *   colliding disk "1" = disk ka of A, its partner "2"; B's colliding disk "3" = kb, partner "4";
 *   r_jk = r_j - r_k, so r_12 = a e_A (e_A: A's outward axis), r_34 = a e_B, and r_13 points from
 *   B's colliding disk to A's (|r_13| = d at contact; we use its actual length).
 * Each dimer's disks change by (eq. 10) dv_1 = Dv - (Dv.r12) r12 / (2a^2), dv_2 = (Dv.r12) r12 /
 * (2a^2), with Dv the impulse on the body divided by m; then
 *   dV = (dv_1 + dv_2) / 2,   domega = r_12 x (dv_1 - dv_2) / a^2
 * (omega = (r_+ - r_-) x (v_+ - v_-) / a^2 for disk 0 at -, 1 at +; r_+ - r_- = s r_12 and
 * v_+ - v_- = s (v_1 - v_2) with s = +-1, so the sign of s cancels).
 *
 * Magnitudes: dimer-dimer eq. 18 (same m; different bond lengths enter through their own a);
 * dimer-disk eq. 22 (C = |r_13| = (d + sigma)/2, either order); dimer-wall eq. 25; disk-disk the
 * usual rule P = (1 + alpha) mu g, mu = M_A M_B / (M_A + M_B).  Dimers of unequal disk mass use
 * the same per-disk updates with P = (1 + alpha) g / sum((1 - c^2/2)/m), which is eq. 18 when the
 * masses are equal.  A dimer of a = 0 has no lever arm and moves as a disk of mass 2m.
 * The products with r12 = a e_A enter as e_A alone (r13.r12 / a): the formulas divide (r13.r12)^2
 * by a^2, which for a < 1e-154 underflowed to 0/0. A pair that is not approaching (normal velocity
 * >= 0) is left unchanged. tests/test_body.c checks every rule against the generic impulse rule of
 * hd_body_impulse.c.  A pair with a general cluster (HD_KIND_BODY) takes that generic rule. */
#include "hd_body.h"
#include "hd_body_impulse.h"

#include <math.h>

/* Applies the impulse (px, py) at side o of body k through the paper's per-disk updates. */
static void paper_apply(hd_kin *k, const hd_side *o, double px, double py) {
  if (!o->rot) {
    k->vx += px / o->mass;
    k->vy += py / o->mass;
    return;
  }
  double dvx = px / o->m, dvy = py / o->m;                           /* Dv of eq. 10 */
  double du = dvx * o->ex + dvy * o->ey;                             /* Dv . r12 / a */
  double c1x = dvx - 0.5 * du * o->ex, c1y = dvy - 0.5 * du * o->ey; /* disk 1 (colliding) */
  double c2x = 0.5 * du * o->ex, c2y = 0.5 * du * o->ey;             /* disk 2 (partner) */
  k->vx += 0.5 * (c1x + c2x);
  k->vy += 0.5 * (c1y + c2y);
  k->omega += (o->ex * (c1y - c2y) - o->ey * (c1x - c2x)) / o->a;
}

/* Two disk bodies, the hot path of a disk gas: the rule and the info of the general code below
 * for that case (P = (1 + alpha) mu (v3 - v1).r13 r13 / |r13|^2 on A, hd_pair_info's fields),
 * the same expressions, without building the two sides. */
static int collide_disks(hd_kin *A, const hd_shape *sa, hd_kin *B, const hd_shape *sb, double alpha,
                         hd_collision_info *info) {
  double r13x = A->x - B->x, r13y = A->y - B->y;
  double dd = sqrt(r13x * r13x + r13y * r13y);
  double dvx = B->vx - A->vx, dvy = B->vy - A->vy;
  if (info) {
    double nx = -r13x / dd, ny = -r13y / dd, inv_mu = 1.0 / sa->m + 1.0 / sb->m;
    info->vn = dvx * nx + dvy * ny;
    info->theta_i = info->theta_j = NAN;
    info->f = 1.0 / (inv_mu * sa->m);
    info->de =
        info->vn < 0.0 ? -0.5 * (1.0 - alpha) * (1.0 + alpha) * info->vn * info->vn / inv_mu : 0.0;
  }
  double g = dvx * r13x + dvy * r13y;
  if (!(g > 0.0)) return 0;
  double mu = sa->m * sb->m / (sa->m + sb->m);
  double px = (1.0 + alpha) * mu * g / (dd * dd) * r13x;
  double py = (1.0 + alpha) * mu * g / (dd * dd) * r13y;
  A->vx += px / sa->m;
  A->vy += py / sa->m;
  B->vx += -px / sb->m;
  B->vy += -py / sb->m;
  return 0;
}

int hd_collide_pair(hd_kin *A, const hd_shape *sa, hd_kin *B, const hd_shape *sb, int ka, int kb,
                    double alpha, hd_collision_info *info) {
  return hd_collide_pair_ex(A, sa, B, sb, ka, kb, alpha, 1, info);
}

int hd_collide_pair_ex(hd_kin *A, const hd_shape *sa, hd_kin *B, const hd_shape *sb, int ka, int kb,
                       double alpha, int angles, hd_collision_info *info) {
  if (sa->tag == HD_KIND_DISK && sb->tag == HD_KIND_DISK)
    return collide_disks(A, sa, B, sb, alpha, info);
  if (sa->tag == HD_KIND_BODY || sb->tag == HD_KIND_BODY)
    return hd_impulse_pair_ex(A, sa, B, sb, ka, kb, alpha, angles, info); /* the general rule */
  hd_side a, b; /* (the info and the rule share them: the velocities change only below) */
  hd_side_of(A, sa, ka, &a);
  hd_side_of(B, sb, kb, &b);
  if (info) hd_pair_info_sides(A, &a, sa, ka, B, &b, sb, kb, alpha, angles, info);
  double r13x = (A->x - B->x) + (a.ox - b.ox), r13y = (A->y - B->y) + (a.oy - b.oy);
  double dd = sqrt(r13x * r13x + r13y * r13y);
  double g = (b.vx - a.vx) * r13x + (b.vy - a.vy) * r13y; /* (v3 - v1) . r13 */
  if (!(g > 0.0)) return 0;
  double px, py; /* impulse on A */
  if (a.rot && b.rot && a.m == b.m) {
    /* eq. 18: Dv = (1 + alpha)/(2d) (v3 - v1).r13 / (1 - [(r13.r12)^2 + (r13.r34)^2]/(4 a^2 d^2))
     */
    double c12 = r13x * a.ex + r13y * a.ey, c34 = r13x * b.ex + r13y * b.ey; /* r13.r12 / a */
    double den = 1.0 - (c12 * c12 + c34 * c34) / (4.0 * dd * dd);
    double dv = (1.0 + alpha) / (2.0 * dd) * g / den;
    px = a.m * dv * r13x / dd; /* m Dv r13 / d, eq. 12 */
    py = a.m * dv * r13y / dd;
  } else if (a.rot && !b.rot) {
    /* eq. 22 with R_d - r_1 = -r13, V_d - v_1 = v3 - v1, C = d:
     * Du = (1 + alpha) g / (1 + m/M - (r13.r12)^2/(2 a^2 C^2)) r13 / C^2, impulse on A = m Du */
    double c12 = r13x * a.ex + r13y * a.ey; /* r13.r12 / a */
    double den = 1.0 + a.m / b.mass - c12 * c12 / (2.0 * dd * dd);
    double du = (1.0 + alpha) * g / den / (dd * dd);
    px = a.m * du * r13x;
    py = a.m * du * r13y;
  } else if (!a.rot && b.rot) {
    /* eq. 22 for B's dimer: R_d - r_3 = r13, V_d - v_3 = v1 - v3: Du = -(1 + alpha) g / den
     * r13/C^2, impulse on B = m Du, on A = -m Du */
    double c34 = r13x * b.ex + r13y * b.ey; /* r13.r34 / a */
    double den = 1.0 + b.m / a.mass - c34 * c34 / (2.0 * dd * dd);
    double du = -(1.0 + alpha) * g / den / (dd * dd);
    px = -b.m * du * r13x;
    py = -b.m * du * r13y;
  } else if (!a.rot && !b.rot) {
    /* hard disks: P = (1 + alpha) mu (v3 - v1).n n, n = r13/d */
    double mu = a.mass * b.mass / (a.mass + b.mass);
    px = (1.0 + alpha) * mu * g / (dd * dd) * r13x;
    py = (1.0 + alpha) * mu * g / (dd * dd) * r13y;
  } else {
    /* dimers of unequal disk mass: eq. 18 with per-body masses */
    double ca = (r13x * a.ex + r13y * a.ey) / dd, cb = (r13x * b.ex + r13y * b.ey) / dd;
    double w = (1.0 - 0.5 * ca * ca) / a.m + (1.0 - 0.5 * cb * cb) / b.m;
    px = (1.0 + alpha) * g / (dd * dd) / w * r13x;
    py = (1.0 + alpha) * g / (dd * dd) / w * r13y;
  }
  paper_apply(A, &a, px, py);
  paper_apply(B, &b, -px, -py);
  return 0;
}

int hd_collide_wall(hd_kin *A, const hd_shape *sa, int ka, const hd_wall *w, double alpha,
                    hd_collision_info *info) {
  if (sa->tag == HD_KIND_BODY) return hd_impulse_wall(A, sa, ka, w, alpha, info);
  if (info) hd_wall_info(A, sa, ka, w, alpha, info);
  hd_side a;
  hd_side_of(A, sa, ka, &a);
  double nx = w->axis ? 0.0 : w->normal, ny = w->axis ? w->normal : 0.0; /* n-hat, inward */
  double v1n = a.vx * nx + a.vy * ny;
  if (!(v1n < 0.0)) return 0;
  double px, py;
  if (a.rot) {
    /* eq. 25: Dw = -(1 + alpha) (v1.n) / (1 - (n.r12)^2 / (2 a^2)) n, impulse m Dw */
    double c12 = nx * a.ex + ny * a.ey; /* n.r12 / a */
    double dw = -(1.0 + alpha) * v1n / (1.0 - 0.5 * c12 * c12);
    px = a.m * dw * nx;
    py = a.m * dw * ny;
  } else {
    px = -(1.0 + alpha) * a.mass * v1n * nx;
    py = -(1.0 + alpha) * a.mass * v1n * ny;
  }
  paper_apply(A, &a, px, py);
  return 0;
}
