/* hd_disk: closed-form contact time of two hard disks in free flight — the engine's hot path
 * for disk-disk pairs, shared by hd_body.c's generic hd_predict_pair. */
#ifndef HD_DISK_H
#define HD_DISK_H

#include <math.h>

/* Earliest t >= 0 with |r + v t| = D for relative position r = rB - rA and relative velocity
 * v = vB - vA, while approaching (r.v < 0).  Returns INFINITY when the disks never touch or are
 * receding.  A round-off overlap (|r| < D) while approaching returns 0: the pair collides now;
 * while receding it is ignored (the pair has just collided).  Uses the cancellation-free root
 * t = c / (-b + sqrt(b^2 - v^2 c)) with b = r.v, c = r^2 - D^2. */
static inline double hd_disk_contact_time(double rx, double ry, double vx, double vy, double D) {
  double b = rx * vx + ry * vy;
  if (b >= 0.0) return INFINITY;
  double c = rx * rx + ry * ry - D * D;
  if (c <= 0.0) return 0.0;
  double v2 = vx * vx + vy * vy;
  double disc = b * b - v2 * c;
  if (disc <= 0.0) return INFINITY;
  return c / (-b + sqrt(disc));
}

#endif
