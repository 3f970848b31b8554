/* hd_scene_area: the area a body covers (hd_scene.h): a dimer's two disks, and the union of the
 * disks of a named species' body.
 *
 * The union of n disks, exactly (up to round-off, for any overlaps, containments or coincident
 * disks): by Green's theorem the area of a region is (1/2) of the integral of x dy - y dx round
 * its boundary, and the boundary of a union of disks is made of circular arcs: the arcs of each
 * circle that no other disk covers.  On circle (cx, cy, r) from angle t1 to t2 the integral is
 *   r^2 (t2 - t1) + cx r (sin t2 - sin t1) - cy r (cos t2 - cos t1)
 * in closed form.  A disk inside another (or equal to an earlier one) has no boundary arc.  No
 * inclusion-exclusion (whose terms need every triple and more) and no sampling. */
#include "hd_scene.h"

#include <math.h>
#include <stdlib.h>

double hd_dimer_area(double d, double a) {
  double r = d / 2, disk = M_PI * r * r;
  if (a >= d) return 2 * disk;
  /* lens of two circles of radius r at distance a < 2r */
  double lens = 2 * r * r * acos(a / (2 * r)) - (a / 2) * sqrt(4 * r * r - a * a);
  return 2 * disk - lens;
}

/* An angular interval [lo, hi] of a circle, lo in [0, 2 pi). */
typedef struct arc {
  double lo, hi;
} arc;

static int arc_cmp(const void *a, const void *b) {
  double x = ((const arc *)a)->lo, y = ((const arc *)b)->lo;
  return (x > y) - (x < y);
}

/* (1/2) integral of x dy - y dx over circle (cx, cy, r) from t1 to t2. */
static double arc_term(double cx, double cy, double r, double t1, double t2) {
  return 0.5 * (r * r * (t2 - t1) + cx * r * (sin(t2) - sin(t1)) - cy * r * (cos(t2) - cos(t1)));
}

double hd_disks_area(int n, const double *x, const double *y, const double *d) {
  double total = 0;
  for (int i = 0; i < n; i++) {
    double ri = d[i] / 2;
    int hidden = 0, na = 0;
    arc cov[2 * HD_MAX_BODY_DISKS + 2];
    for (int j = 0; j < n && !hidden; j++) {
      if (j == i) continue;
      double rj = d[j] / 2, dx = x[j] - x[i], dy = y[j] - y[i], dist = hypot(dx, dy);
      if (dist == 0 && rj == ri) { /* the same disk twice: the first one counts */
        hidden = j < i;
        continue;
      }
      if (dist + ri <= rj) hidden = 1;                  /* inside disk j: no boundary arc */
      if (hidden || dist >= ri + rj || dist + rj <= ri) /* apart, or j inside i */
        continue;
      /* the arc of circle i inside disk j: centred on the direction to j, half-angle h */
      double c = (ri * ri + dist * dist - rj * rj) / (2 * ri * dist);
      double h = acos(fmax(-1.0, fmin(1.0, c))), t = atan2(dy, dx);
      double lo = t - h, hi = t + h;
      while (lo < 0) lo += 2 * M_PI, hi += 2 * M_PI;
      while (lo >= 2 * M_PI) lo -= 2 * M_PI, hi -= 2 * M_PI;
      if (hi > 2 * M_PI) { /* wraps past 0: two pieces */
        cov[na++] = (arc){lo, 2 * M_PI};
        cov[na++] = (arc){0, hi - 2 * M_PI};
      } else {
        cov[na++] = (arc){lo, hi};
      }
    }
    if (hidden) continue;
    if (na == 0) { /* the whole circle is boundary */
      total += M_PI * ri * ri;
      continue;
    }
    qsort(cov, (size_t)na, sizeof cov[0], arc_cmp);
    double from = 0; /* the uncovered stretch starts here */
    for (int a = 0; a < na; a++) {
      if (cov[a].lo > from) total += arc_term(x[i], y[i], ri, from, cov[a].lo);
      from = fmax(from, cov[a].hi);
    }
    if (from < 2 * M_PI) total += arc_term(x[i], y[i], ri, from, 2 * M_PI);
  }
  return total;
}

double hd_species_area(const hd_scene_species *sp) {
  if (sp->ndisk == 1) return M_PI * sp->d[0] * sp->d[0] / 4;
  if (sp->ndisk == 2 && sp->d[0] == sp->d[1])
    return hd_dimer_area(sp->d[0], hypot(sp->x[1] - sp->x[0], sp->y[1] - sp->y[0]));
  return hd_disks_area(sp->ndisk, sp->x, sp->y, sp->d);
}

double hd_species_extent(const hd_scene_species *sp) {
  double ext = 0;
  for (int i = 0; i < sp->ndisk; i++)
    for (int j = i; j < sp->ndisk; j++)
      ext = fmax(ext, hypot(sp->x[i] - sp->x[j], sp->y[i] - sp->y[j]) + (sp->d[i] + sp->d[j]) / 2);
  return ext;
}
