/* hd_disk: closed-form contact time of two hard disks in free flight, the engine's hot path for
 * disk-disk pairs (hd_predict_disks in hd_body.c shares its rule for a pair in contact). */
#ifndef HD_DISK_H
#define HD_DISK_H

#include <float.h>
#include <math.h>

/* A pair in contact "approaches" when its normal relative speed exceeds
 * HD_DISK_VTOL |v| + HD_DISK_VROUND vs: a share of the relative speed |v| (hd_body.c's VTOL) and
 * the round-off of the difference of the two velocities themselves (vs bounds their size: a
 * pair moving together at 1000 with a relative speed of 1 keeps ~1e-12 of round-off). */
#define HD_DISK_VTOL 1e-12
#define HD_DISK_VROUND (8 * DBL_EPSILON)
/* Pairs with |r|^2 - D^2 above this times D^2 take the discriminant without cancellation
 * (hd_disk_contact_time). */
#define HD_DISK_FAR 1e4

/* Earliest t >= 0 with |r + v t| = D for relative position r = rB - rA and relative velocity
 * v = vB - vA, while approaching (r.v < 0); vs >= |vA| + |vB| (any norm).  Returns INFINITY
 * when the disks never touch or are receding.  A round-off overlap (|r| < D) returns 0 (the
 * pair collides now) only if it approaches by the rule above: after an alpha = 0 collision the
 * normal velocity is 0 up to round-off, and an impulse that small no longer changes the
 * velocities, so the pair would otherwise collide again at t = 0 for ever.  A grazing contact
 * from a gap is taken whatever its normal speed (a tiny impulse, after which the pair recedes
 * or, at alpha = 0, falls under the rule above).  Uses the cancellation-free root
 * t = c / (-b + sqrt(b^2 - v^2 c)) with b = r.v, c = r^2 - D^2.  For a pair farther apart than
 * sqrt(HD_DISK_FAR) D the discriminant is computed as v^2 D^2 - (r x v)^2, the same number
 * without the cancellation of b^2 and v^2 c, both ~ r^2 v^2: their round-off, ~1e-16 r^2 v^2,
 * moved the contact by ~1e-16 r^2 / D, 1e-8 of a diameter at r = 1e4 D (5 disks at area
 * fraction 1e-9 failed verification with 6.3e-9; issue 24).  Nearer pairs, all of them in a
 * gas denser than ~1e-3, keep the first form, bit for bit. */
static inline double hd_disk_contact_time(double rx, double ry, double vx, double vy, double D,
                                          double vs) {
  double b = rx * vx + ry * vy;
  if (b >= 0.0) return INFINITY;
  double c = rx * rx + ry * ry - D * D;
  double v2 = vx * vx + vy * vy;
  if (c <= 0.0) /* |r| = D to round-off: collide now if b < -D (VTOL |v| + VROUND vs) */
    return b < -D * (HD_DISK_VTOL * sqrt(v2) + HD_DISK_VROUND * vs) ? 0.0 : INFINITY;
  double disc = b * b - v2 * c;
  if (c > HD_DISK_FAR * D * D) { /* far: b^2 and v^2 c cancel (see above) */
    double cr = rx * vy - ry * vx;
    disc = v2 * D * D - cr * cr;
  }
  if (disc <= 0.0) return INFINITY;
  return c / (-b + sqrt(disc));
}

#endif
