/* Event prediction for one body: its next cell crossing, its wall contacts (edge cells only)
 * and its contacts with the bodies of the 3x3 neighbouring cells, all searched only up to the
 * earliest event found so far (the crossing bounds the search; see hd_sim.h). */
#include <math.h>

#include "hd_disk.h"
#include "hd_sim_internal.h"

/* Time until body b leaves its cell, or INFINITY; *dir: 0 +x, 1 -x, 2 +y, 3 -y. */
static double crossing_time(const hd_sim *s, const hd_body *b, int32_t *dir) {
  int32_t cx = b->cell % s->ncx, cy = b->cell / s->ncx;
  double best = INFINITY, t;
  if (b->k.vx > 0.0 && !(cx == s->ncx - 1 && (s->walls & HD_WALL_RIGHT))) {
    t = ((cx + 1) * s->cwx - b->k.x) / b->k.vx;
    if (t < best) best = t, *dir = 0;
  } else if (b->k.vx < 0.0 && !(cx == 0 && (s->walls & HD_WALL_LEFT))) {
    t = (cx * s->cwx - b->k.x) / b->k.vx;
    if (t < best) best = t, *dir = 1;
  }
  if (b->k.vy > 0.0 && !(cy == s->ncy - 1 && (s->walls & HD_WALL_TOP))) {
    t = ((cy + 1) * s->cwy - b->k.y) / b->k.vy;
    if (t < best) best = t, *dir = 2;
  } else if (b->k.vy < 0.0 && !(cy == 0 && (s->walls & HD_WALL_BOTTOM))) {
    t = (cy * s->cwy - b->k.y) / b->k.vy;
    if (t < best) best = t, *dir = 3;
  }
  return best < 0.0 ? 0.0 : best;
}

/* Wall contacts of body i (only bodies in edge cells can reach a wall). */
static void predict_walls(hd_sim *s, int32_t i, double *best) {
  hd_body *b = &s->b[i];
  int32_t cx = b->cell % s->ncx, cy = b->cell / s->ncx;
  int near[4] = {cx == 0, cx == s->ncx - 1, cy == 0, cy == s->ncy - 1};
  static const unsigned bit[4] = {HD_WALL_LEFT, HD_WALL_RIGHT, HD_WALL_BOTTOM, HD_WALL_TOP};
  for (int w = 0; w < 4; w++) {
    if (!near[w] || !(s->walls & bit[w])) continue;
    hd_contact c;
    if (hd_predict_wall(&b->k, &s->shape[b->species], &s->wall[w], *best, &c) && c.t < *best) {
      *best = c.t;
      b->ev_type = HD_EV_WALL;
      b->ev_partner = w;
      b->ev_ka = (int16_t)c.ka;
    }
  }
}

void hd_predict(hd_sim *s, int32_t i) {
  hd_body *bi = &s->b[i];
  const double now = s->c.t;
  int32_t dir = -1;
  double best = crossing_time(s, bi, &dir); /* relative to now */
  bi->ev_type = best < INFINITY ? HD_EV_CELL : HD_EV_NONE;
  bi->ev_partner = dir;

  if (s->walls) predict_walls(s, i, &best);

  const hd_shape *si = &s->shape[bi->species];
  const int disk_i = bi->species == HD_SP_DISK;
  HD_FOR_NEIGHBOURS(s, bi->cell, {
    if (j == i) continue;
    const hd_body *bj = &s->b[j];
    const double dtj = now - bj->t;
    if (disk_i && bj->species == HD_SP_DISK) {
      /* disk-disk: closed form, no copies */
      double rx = bj->k.x + bj->k.vx * dtj + sx - bi->k.x;
      double ry = bj->k.y + bj->k.vy * dtj + sy - bi->k.y;
      double D = 0.5 * (si->d + s->shape[HD_SP_DISK].d);
      double t = hd_disk_contact_time(rx, ry, bj->k.vx - bi->k.vx, bj->k.vy - bi->k.vy, D);
      if (t < best) {
        best = t;
        bi->ev_type = HD_EV_PAIR;
        bi->ev_partner = j;
        bi->ev_pcount = bj->ncoll;
        bi->ev_ka = bi->ev_kb = 0;
        bi->ev_shift = (int32_t)((sx > 0) - (sx < 0) + 1 + 3 * ((sy > 0) - (sy < 0) + 1));
      }
    } else {
      hd_kin kj = bj->k;
      hd_kin_advance(&kj, dtj);
      kj.x += sx;
      kj.y += sy;
      hd_contact c;
      if (hd_predict_pair(&bi->k, si, &kj, &s->shape[bj->species], best, &c) && c.t < best) {
        best = c.t;
        bi->ev_type = HD_EV_PAIR;
        bi->ev_partner = j;
        bi->ev_pcount = bj->ncoll;
        bi->ev_ka = (int16_t)c.ka;
        bi->ev_kb = (int16_t)c.kb;
        bi->ev_shift = (int32_t)((sx > 0) - (sx < 0) + 1 + 3 * ((sy > 0) - (sy < 0) + 1));
      }
    }
  });
  bi->ev_t = bi->ev_type == HD_EV_NONE ? INFINITY : now + best;
  hd_queue_update(s->q, i);
}
