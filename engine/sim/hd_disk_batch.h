/* hd_disk_batch: the closed-form disk-disk contact time (hd_disk_contact_time, hd_disk.h) of
 * several pairs at once, two per SSE2 instruction, for the candidates of one prediction
 * gathered into small arrays (issue 27 item 3: measured, see bench/issue27-ab.md). */
#ifndef HD_DISK_BATCH_H
#define HD_DISK_BATCH_H

#include <stdint.h>

#include "hd_disk.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

/* Most pairs one batch holds (a multiple of 2). */
#define HD_DISK_BATCH 32

/* The contact times t[k] of lanes k < n (n <= HD_DISK_BATCH; the arrays hold n rounded up to
 * even, the lane past an odd n any finite numbers) of relative positions (rx, ry) and
 * velocities (vx, vy), for contact distance D: t[k] is what hd_disk_contact_time gives, bit for
 * bit, except in the lanes of the returned mask (bit k), where the pair overlaps to round-off
 * (|r| <= D) or is far (|r|^2 - D^2 > HD_DISK_FAR D^2): those take hd_disk_contact_time, which
 * needs the speed bound vs, from the caller.  Each lane does the same IEEE operations as
 * hd_disk_contact_time (multiply, add, sqrt, divide, correctly rounded in SSE2 as in the scalar
 * unit), so the two agree exactly as long as neither is contracted to fused multiply-adds
 * (the build's -O2 without -march: none on x86-64). */
static inline uint64_t hd_disk_contact_batch(int n, const double *restrict rx,
                                             const double *restrict ry, const double *restrict vx,
                                             const double *restrict vy, double D,
                                             double *restrict t) {
  uint64_t odd = 0;
  const double DD = D * D, far = HD_DISK_FAR * D * D;
#if defined(__SSE2__)
  const __m128d zero = _mm_setzero_pd(), inf = _mm_set1_pd(INFINITY), dd = _mm_set1_pd(DD),
                fr = _mm_set1_pd(far);
  for (int k = 0; k < n; k += 2) {
    __m128d x = _mm_loadu_pd(rx + k), y = _mm_loadu_pd(ry + k), u = _mm_loadu_pd(vx + k),
            v = _mm_loadu_pd(vy + k);
    __m128d b = _mm_add_pd(_mm_mul_pd(x, u), _mm_mul_pd(y, v));
    __m128d c = _mm_sub_pd(_mm_add_pd(_mm_mul_pd(x, x), _mm_mul_pd(y, y)), dd);
    __m128d v2 = _mm_add_pd(_mm_mul_pd(u, u), _mm_mul_pd(v, v));
    __m128d disc = _mm_sub_pd(_mm_mul_pd(b, b), _mm_mul_pd(v2, c));
    /* c / (-b + sqrt(disc)): -b as 0 - b is the same number (b < 0 where it is used) */
    __m128d r = _mm_div_pd(c, _mm_add_pd(_mm_sub_pd(zero, b), _mm_sqrt_pd(disc)));
    __m128d ok = _mm_and_pd(_mm_cmplt_pd(b, zero), _mm_cmpgt_pd(disc, zero));
    _mm_storeu_pd(t + k, _mm_or_pd(_mm_and_pd(ok, r), _mm_andnot_pd(ok, inf)));
    /* the lanes the scalar form takes: b < 0 and (c <= 0 or c > far) */
    __m128d bad =
        _mm_and_pd(_mm_cmplt_pd(b, zero), _mm_or_pd(_mm_cmple_pd(c, zero), _mm_cmpgt_pd(c, fr)));
    odd |= (uint64_t)_mm_movemask_pd(bad) << k;
  }
#else
  for (int k = 0; k < n; k++) {
    double b = rx[k] * vx[k] + ry[k] * vy[k];
    double c = rx[k] * rx[k] + ry[k] * ry[k] - DD;
    double v2 = vx[k] * vx[k] + vy[k] * vy[k];
    double disc = b * b - v2 * c;
    t[k] = b < 0.0 && disc > 0.0 ? c / (-b + sqrt(disc)) : INFINITY;
    if (b < 0.0 && (c <= 0.0 || c > far)) odd |= (uint64_t)1 << k;
  }
#endif
  return odd & ((n < 64 ? (uint64_t)1 << n : 0) - 1);
}

#endif
