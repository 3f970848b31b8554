/* hd_body_impulse: private helpers of hd_body — the contact geometry of a collision, the fields
 * of hd_collision_info, and the generic rigid-body impulse rule that the tests use to check the
 * paper's collision rules (hd_collide_pair, hd_collide_wall implement the paper's formulas).
 *
 * Generic rule: an impulse J n acts on B and -J n on A at the contact point, n the unit normal
 * from A's contacting disk to B's.  With vn = (v_B - v_A).n the normal velocity of the contact
 * points (rotation included; the disk centres have the same normal velocity as the contact
 * points) and, per body, 1/M + (rho x n)^2 / I, rho = contacting disk - centre of mass,
 *   1/mu_eff = sum over the two bodies,   J = -(1 + alpha) mu_eff vn,
 *   dE = -(1 - alpha^2) mu_eff vn^2 / 2.
 * For a dimer (rho x n)^2 / I = (e x n)^2 / (2 m) with e the unit axis: independent of a, so that
 * mu_eff / m = 2 / (2 + sin^2 th_i + sin^2 th_j) for every a > 0 (a dimer of a = 0 exactly has no
 * lever arm and is treated as a disk of mass 2m).  A wall has infinite mass.  A general cluster
 * uses the same rule with rho its contacting disk's offset and I its moment of inertia. */
#ifndef HD_BODY_IMPULSE_H
#define HD_BODY_IMPULSE_H

#include "hd_body.h"

/* One body's side of a contact. */
typedef struct hd_side {
  double ex, ey;  /* outward axis at the contacting disk (unit, centre of mass -> contacting
                   * disk; for a dimer partner disk -> contacting disk); 0 when the disk is at
                   * the centre of mass (a disk body) */
  double ox, oy;  /* contacting disk centre minus centre of mass ((a/2) e for a dimer) */
  double vx, vy;  /* velocity of the contacting disk centre */
  double m;       /* mass of the contacting disk (m of a dimer, the mass of a disk body) */
  double mass;    /* total mass */
  double a;       /* bond length of a dimer, else 0 */
  double inertia; /* moment of inertia about the centre of mass */
  int rot;        /* 1 for a body that turns under an impulse (a dimer with a > 0, a cluster
                   * with inertia > 0) */
  int gen;        /* 1: a general cluster (the rotational terms use ox, oy and inertia) */
} hd_side;

/* Fills the side of disk `which` of body k of shape s. */
void hd_side_of(const hd_kin *k, const hd_shape *s, int which, hd_side *o);

/* 1/M + (rho x n)^2 / I of one side for the unit normal n. */
double hd_side_inv_mass(const hd_side *o, double nx, double ny);

/* Signed angle in (-pi, pi] from the side's outward axis to the direction (nx, ny); NaN for a
 * disk body. */
double hd_side_theta(const hd_side *o, double nx, double ny);

/* Unit normal from A's contacting disk to B's, computed from the centre difference first. */
void hd_pair_normal(const hd_kin *A, const hd_side *sa, const hd_kin *B, const hd_side *sb,
                    double *nx, double *ny);

/* hd_pair_info from the two sides (hd_side_of of A's disk ka and B's disk kb), with the contact
 * angles theta_i, theta_j only if `angles` (else NaN: two atan2 saved per collision when nothing
 * logs them); vn, de and f are the same either way. */
void hd_pair_info_sides(const hd_kin *A, const hd_side *a, const hd_shape *sa, int ka,
                        const hd_kin *B, const hd_side *b, const hd_shape *sb, int kb, double alpha,
                        int angles, hd_collision_info *info);

/* hd_collision_info of a collision of A (disk ka) with B (disk kb) before it happens. */
void hd_pair_info(const hd_kin *A, const hd_shape *sa, const hd_kin *B, const hd_shape *sb, int ka,
                  int kb, double alpha, hd_collision_info *info);

/* hd_collision_info of a collision of disk ka of A with wall w before it happens. */
void hd_wall_info(const hd_kin *A, const hd_shape *sa, int ka, const hd_wall *w, double alpha,
                  hd_collision_info *info);

/* The generic rule for a body pair (same contract as hd_collide_pair).  Returns 0. */
int hd_impulse_pair(hd_kin *A, const hd_shape *sa, hd_kin *B, const hd_shape *sb, int ka, int kb,
                    double alpha, hd_collision_info *info);

/* hd_impulse_pair with the contact angles only if `angles` (hd_collide_pair_ex). */
int hd_impulse_pair_ex(hd_kin *A, const hd_shape *sa, hd_kin *B, const hd_shape *sb, int ka, int kb,
                       double alpha, int angles, hd_collision_info *info);

/* The generic rule against a wall (same contract as hd_collide_wall).  Returns 0. */
int hd_impulse_wall(hd_kin *A, const hd_shape *sa, int ka, const hd_wall *w, double alpha,
                    hd_collision_info *info);

#endif
