/* Event prediction for one body.  A body holds two pending events (hd_sim.h): its earliest
 * contact (with a body of the 3x3 neighbouring cells, or with a wall from an edge cell) and its
 * next cell crossing.  A full prediction searches all 9 cells.  After a crossing in a pure disk
 * scene only the 3 cells that became adjacent are searched, and the stored contact is kept if
 * still valid: disk-disk contact times are exact and unbounded (closed form), so the stored one
 * is the earliest with every body of the cells that stay adjacent.  Contacts involving a dimer
 * are searched by i only up to the earlier of i's next crossing and j's next event, whatever it
 * is (which bounds the root search): in every scene but pure disks (the only ones with partial
 * crossings, `partial_cross`) every event of a body (a collision, a wall, a crossing, a wake-up,
 * a stale contact) is followed by its full prediction, so a contact after i's crossing is found
 * by i's prediction then, and one after j's next event by j's, since bodies in contact are in
 * adjacent cells (a contact after j's next event found now would be computed from a course that
 * j may not keep: the search of it was the engine's largest waste).  After a collision of i and
 * j their own pair is searched once, by j (hd_predict_after_pair).  In a pure disk scene a
 * prediction walks interior cells by index offsets, without the periodic and wall logic of
 * HD_FOR_NEIGHBOURS, and takes their list heads without a branch on whether each is empty
 * (gather_cells).  hd_predict_prefetch_near and _far are the event queue's prefetch hints
 * (hd_queue.h) for large systems. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "hd_disk.h"
#include "hd_sim_internal.h"
#include "hd_stop.h"

/* c ? a : b (c 0 or 1) by masks on the bits: gcc 12 turns the conditional into a branch on c,
 * which here is the sign of a velocity, random from body to body (mispredicted half the time). */
static inline double select_bits(int c, double a, double b) {
  uint64_t ua, ub, m = (uint64_t)0 - (uint64_t)c;
  memcpy(&ua, &a, sizeof ua);
  memcpy(&ub, &b, sizeof ub);
  ua = (ua & m) | (ub & ~m);
  memcpy(&a, &ua, sizeof a);
  return a;
}

/* Time until body b, in cell (cx, cy), leaves it (>= 0), or INFINITY; sets b->c_dir.  A body
 * that never leaves its cell but spins gets a wake-up HD_WAKE_TURNS turns ahead instead (c_dir
 * HD_WAKE): the contact searches of dimers end at a body's crossing or its partner's next event,
 * and without it two dimers at rest that spin at nearly one rate were searched without end (10^8
 * steps, ~7 s, then "no contact": a contact at t ~ 7e7 was missed; review). */
static inline double crossing_time(const hd_sim *s, hd_body *b, int32_t cx, int32_t cy) {
  /* Both faces ahead are timed side by side and chosen without branches on the signs of the
   * velocity (random from body to body: mispredicted half the time), each with the expression
   * ((c + 1) w - x) / v moving up, (c w - x) / v moving down, as before: the same times bit for
   * bit, x first on a tie.  A face is open unless a wall closes it (or v is 0). */
  const double vx = b->k.vx, vy = b->k.vy;
  const unsigned w = s->walls;
  const int px = vx > 0.0, py = vy > 0.0; /* moving up in x, in y */
  const int mx = vx < 0.0, my = vy < 0.0; /* moving down */
  const int ox = (px & !((cx == s->ncx - 1) & ((w & HD_WALL_RIGHT) != 0))) |
                 (mx & !((cx == 0) & ((w & HD_WALL_LEFT) != 0)));
  const int oy = (py & !((cy == s->ncy - 1) & ((w & HD_WALL_TOP) != 0))) |
                 (my & !((cy == 0) & ((w & HD_WALL_BOTTOM) != 0)));
  double tx = ((double)(cx + px) * s->cwx - b->k.x) / vx;
  double ty = ((double)(cy + py) * s->cwy - b->k.y) / vy;
  tx = select_bits(ox, tx, INFINITY);
  ty = select_bits(oy, ty, INFINITY);
  const int ylt = ty < tx;
  double best = select_bits(ylt, ty, tx);
  if (best < INFINITY) {
    b->c_dir = (int16_t)(ylt * (3 - py) + (1 - ylt) * (1 - px));
  } else if (b->k.omega != 0.0 && s->shape[b->species].tag != HD_KIND_DISK) {
    /* (a rough disk's spin does not move its contacts: no wake-up) */
    best = HD_WAKE_TURNS * 2.0 * M_PI / fabs(b->k.omega);
    b->c_dir = HD_WAKE;
  }
  return best < 0.0 ? 0.0 : best;
}

/* max and min of doubles that are not NaN, inline (fmax and fmin are library calls) */
static inline double dmax(double a, double b) {
  return a > b ? a : b;
}
static inline double dmin(double a, double b) {
  return a < b ? a : b;
}

/* Wall contacts of body i, if it is in an edge cell; *best is relative to now. */
static void predict_walls(hd_sim *s, int32_t i, double horizon, double *best) {
  hd_body *b = &s->b[i];
  int32_t cx, cy;
  hd_body_cxy(s, b, &cx, &cy);
  int near[4] = {cx == 0, cx == s->ncx - 1, cy == 0, cy == s->ncy - 1};
  static const unsigned bit[4] = {HD_WALL_LEFT, HD_WALL_RIGHT, HD_WALL_BOTTOM, HD_WALL_TOP};
  for (int w = 0; w < 4; w++) {
    if (!near[w] || !(s->walls & bit[w])) continue;
    hd_contact c;
    double lim = fmin(*best, horizon);
    int r = hd_predict_wall(&b->k, &s->shape[b->species], &s->wall[w], lim, &c);
    if (r == HD_CA_CUT) {
      s->cut_t = dmin(s->cut_t, c.t);
    } else if (r && c.t < *best) {
      *best = c.t;
      b->p_type = HD_EV_WALL;
      b->p_partner = w;
      b->p_ka = (int16_t)c.ka;
    }
  }
}

/* Records a contact of i with j found at relative time t, seen through shift code (ix, iy). */
static inline void take_pair(hd_body *bi, const hd_body *bj, int32_t j, int ka, int kb, int ix,
                             int iy) {
  bi->p_type = HD_EV_PAIR;
  bi->p_partner = j;
  bi->p_pcount = bj->ncoll;
  bi->p_ka = (int16_t)ka;
  bi->p_kb = (int16_t)kb;
  bi->p_imx = (int16_t)hd_image_code(ix, bi->wx, bj->wx); /* ix - wx(j) + wx(i) */
  bi->p_imy = (int16_t)hd_image_code(iy, bi->wy, bj->wy);
}

/* disk-disk contact of bi with j seen through shift (sx, sy) = (ix, iy) box lengths: closed
 * form, no copies, no horizon. */
static inline void predict_disk_pair(const hd_sim *s, hd_body *bi, int32_t j, double sx, double sy,
                                     int ix, int iy, double D, double *best) {
  const hd_body *bj = &s->b[j];
  const double dtj = s->c.t - bj->t;
  double rx = bj->k.x + bj->k.vx * dtj + sx - bi->k.x;
  double ry = bj->k.y + bj->k.vy * dtj + sy - bi->k.y;
  double vs = fabs(bi->k.vx) + fabs(bi->k.vy) + fabs(bj->k.vx) + fabs(bj->k.vy);
  double t = hd_disk_contact_time(rx, ry, bj->k.vx - bi->k.vx, bj->k.vy - bi->k.vy, D, vs);
  if (t < *best) {
    *best = t;
    take_pair(bi, bj, j, 0, 0, ix, iy);
  }
}

/* Contact distance of two disk bodies (the diameter of a species with itself). */
static inline double disk_contact(const hd_sim *s, const hd_body *bi, const hd_body *bj) {
  return bi->species == bj->species ? s->shape[bi->species].d
                                    : 0.5 * (s->shape[bi->species].d + s->shape[bj->species].d);
}

/* Where a contact search of i against j ends, relative to now: at i's next crossing (cross)
 * or j's next event, whichever comes first (this file's head says why). */
static inline double search_end(const hd_sim *s, const hd_body *bj, double cross) {
  return dmin(cross, bj->ev_t - s->c.t);
}

/* Contacts of body i with body j (shifted by sx, sy); *best relative to now. */
static inline void predict_one(hd_sim *s, hd_body *bi, int32_t j, double sx, double sy,
                               double horizon, double *best) {
  const hd_body *bj = &s->b[j];
  const double dtj = s->c.t - bj->t;
  const hd_shape *si = &s->shape[bi->species];
  int ix = (sx > 0) - (sx < 0), iy = (sy > 0) - (sy < 0);
  if (si->tag == HD_KIND_DISK && s->shape[bj->species].tag == HD_KIND_DISK) {
    predict_disk_pair(s, bi, j, sx, sy, ix, iy, disk_contact(s, bi, bj), best);
    return;
  }
  double lim = dmin(*best, search_end(s, bj, horizon));
  if (lim < 0.0) lim = 0.0;
  hd_kin kj = bj->k;
  hd_kin_advance(&kj, dtj);
  kj.x += sx;
  kj.y += sy;
  hd_contact c;
  int r = hd_predict_pair(&bi->k, si, &kj, &s->shape[bj->species], lim, &c);
  if (r == HD_CA_CUT) {
    s->cut_t = dmin(s->cut_t, c.t);
  } else if (r && c.t < *best) {
    *best = c.t;
    take_pair(bi, bj, j, c.ka, c.kb, ix, iy);
  }
}

/* Sets ev_t from the two slots and updates the queue. */
static inline void commit(hd_sim *s, int32_t i) {
  hd_body *b = &s->b[i];
  b->ev_t = b->p_t < b->c_t ? b->p_t : b->c_t;
  hd_queue_update(s->q, i, b->ev_t);
}

/* The bodies of rows x 3 interior cells (cells c0 + k step, k = 0..2, each row ncx further on)
 * into js (room for 9), in the order in which the nested loops over the cell lists would visit
 * them; returns their number, or -1 if a cell holds more than one body: then the caller walks
 * the lists itself.  Whether a cell is empty is random (at area fraction 0.25 a cell of width d
 * holds 0.32 disks on average), and the loop over a list mispredicted its end at each cell; the
 * heads are taken here without a branch on it. */
static inline int gather_cells(const hd_sim *s, int32_t c0, int32_t step, int32_t ncx, int rows,
                               int32_t *js) {
  const int32_t *head = s->head;
  int n = 0, chained = 0;
  for (int r = 0; r < rows; r++)
    for (int k = 0; k < 3; k++) {
      int32_t j = head[c0 + r * ncx + k * step];
      js[n] = j;
      n += j >= 0;
    }
  for (int k = 0; k < n; k++) chained |= s->b[js[k]].next >= 0;
  return __builtin_expect(chained, 0) ? -1 : n;
}

/* The full prediction in a scene of disks only: the 9 cells around i; an interior cell (no
 * periodic image, no wall) walks its neighbours by index offsets. */
static void predict_disks(hd_sim *s, int32_t i, int32_t cx, int32_t cy, double cross,
                          double *best) {
  hd_body *bi = &s->b[i];
  const double D = s->disks_d;
  int32_t c = bi->cell, ncx = s->ncx;
  if (cx >= 1 && cx < ncx - 1 && cy >= 1 && cy < s->ncy - 1) {
    const int32_t *head = s->head;
    int32_t js[9];
    int n = gather_cells(s, c - ncx - 1, 1, ncx, 3, js);
    for (int k = 0; k < n; k++)
      if (js[k] != i) predict_disk_pair(s, bi, js[k], 0.0, 0.0, 0, 0, D, best);
    if (n >= 0) return;
    for (int32_t row = c - ncx; row <= c + ncx; row += ncx)
      for (int32_t cc = row - 1; cc <= row + 1; cc++)
        for (int32_t j = head[cc]; j >= 0; j = s->b[j].next)
          if (j != i) predict_disk_pair(s, bi, j, 0.0, 0.0, 0, 0, D, best);
    return;
  }
  if (s->walls) predict_walls(s, i, cross, best);
  HD_FOR_NEIGHBOURS(s, c, {
    if (j != i)
      predict_disk_pair(s, bi, j, sx, sy, (sx > 0) - (sx < 0), (sy > 0) - (sy < 0), D, best);
  });
}

/* A neighbour whose contact search is pending, with a lower bound on its contact time. */
typedef struct hd_cand {
  double t;              /* no contact before t (relative to now) */
  double lim;            /* the search ends at i's next crossing or j's next event, if earlier */
  double sx, sy;         /* periodic shift of the neighbour */
  int32_t j;             /* the neighbour */
  int begun;             /* ca is under way (else t is the enclosing circles' bound) */
  double c, b, v2, disc; /* the circles' window before it is begun: t = its start */
  hd_ca ca;              /* its root search, once begun */
} hd_cand;

#define HD_MAX_CAND 64

/* The contacts of body i with its neighbours (but skip) in a scene with dimers, best first.
 * Each neighbour's root search (conservative advancement, hd_ca_step) only moves forward in
 * time and its current time is a lower bound on its contact time; the first bound is when the
 * enclosing circles (radius (a + d)/2 about the centres of mass, in linear motion, widened
 * against round-off: hd_ca_reach) first meet, the start of the search's window, which is handed
 * to it (hd_ca_begin_in) rather than computed twice.  The search that is furthest behind takes
 * the next step,
 * and all stop once the smallest bound is not below the earliest contact found: no step is
 * taken past the final answer, and every other pair touches later, if at all.  Disk-disk
 * pairs take the closed form at once. */
static void predict_sorted(hd_sim *s, int32_t i, int32_t skip, double cross, double *best) {
  hd_body *bi = &s->b[i];
  const double now = s->c.t;
  const hd_shape *si = &s->shape[bi->species];
  const double *rad = s->ca_reach[bi->species]; /* the windows' radii (hd_ca_reach) */
  const int i_disk = si->tag == HD_KIND_DISK;   /* (locals: the stores below may alias s) */
  hd_cand cs[HD_MAX_CAND];
  int nc = 0, ord[HD_MAX_CAND];
  double sca[2]; /* sin and cos of i's orientation, shared by its searches */
  hd_ca_sincos(bi->k.phi, &sca[0], &sca[1]);
  HD_FOR_NEIGHBOURS(s, bi->cell, {
    if (j == i || j == skip) continue;
    const hd_body *bj = &s->b[j];
    if (i_disk && s->shape[bj->species].tag == HD_KIND_DISK) {
      predict_disk_pair(s, bi, j, sx, sy, (sx > 0) - (sx < 0), (sy > 0) - (sy < 0),
                        disk_contact(s, bi, bj), best);
      continue;
    }
    double dtj = now - bj->t, R = rad[bj->species];
    double rx = bj->k.x + bj->k.vx * dtj + sx - bi->k.x,
           ry = bj->k.y + bj->k.vy * dtj + sy - bi->k.y;
    /* the circles' first meeting, without branches on the data (they would be mispredicted):
     * 0 if they overlap (c <= 0), else c / (sqrt(b^2 - v^2 c) - b) when they meet (b < 0 and
     * disc > 0); a denominator floored at DBL_MIN only lowers the bound */
    double vx = bj->k.vx - bi->k.vx, vy = bj->k.vy - bi->k.vy;
    double c = rx * rx + ry * ry - R * R, b = rx * vx + ry * vy, v2 = vx * vx + vy * vy,
           disc = b * b - v2 * c;
    double t = dmax(c, 0.0) / dmax(sqrt(dmax(disc, 0.0)) - b, DBL_MIN);
    double lim = search_end(s, bj, cross);
    /* kept unless it cannot touch before the earliest contact so far, or within the horizon */
    int keep = ((c <= 0.0) | ((b < 0.0) & (disc > 0.0))) & (t < *best) & (t <= lim);
    if (nc == HD_MAX_CAND) { /* a crowd: the rest one by one (still exact, only slower) */
      if (keep) predict_one(s, bi, j, sx, sy, cross, best);
      continue;
    }
    hd_cand *cd = &cs[nc];
    cd->t = t;
    cd->lim = dmax(lim, 0.0);
    cd->sx = sx;
    cd->sy = sy;
    cd->j = j;
    cd->begun = 0;
    cd->c = c, cd->b = b, cd->v2 = v2, cd->disc = disc;
    nc += keep;
  });
  for (int k = 0; k < nc; k++) ord[k] = k;
  for (long steps = 1; nc > 0; steps++) {
    int k = 0; /* the pending search furthest behind */
    for (int q = 1; q < nc; q++)
      if (cs[ord[q]].t < cs[ord[k]].t) k = q;
    hd_cand *c = &cs[ord[k]];
    if (!(c->t < *best)) break;
    /* a stop request is looked at every HD_CA_POLL + 1 calls, and when a search's own count of
     * steps (the single steps of clusters included) reaches such a multiple */
    if (((steps & HD_CA_POLL) == 0 || (c->begun && (c->ca.it & HD_CA_POLL) == 0)) &&
        hd_stop_requested) { /* cut: no contact before c->t */
      s->cut_t = dmin(s->cut_t, c->t);
      break;
    }
    const hd_body *bj = &s->b[c->j];
    double lim = dmin(*best, c->lim);
    hd_contact ct;
    int r;
    if (c->begun) {
      r = hd_ca_step(&c->ca, lim, &ct);
    } else {
      hd_kin kj = bj->k;
      hd_kin_advance(&kj, now - bj->t);
      kj.x += c->sx;
      kj.y += c->sy;
      r = hd_ca_begin_in(&c->ca, &bi->k, si, &kj, &s->shape[bj->species], lim, sca, c->t,
                         hd_circle_exit(c->c, c->b, c->v2, c->disc), &ct);
      c->begun = 1;
    }
    if (r == 2) {
      c->t = c->ca.t;
      continue;
    }
    if (r == 1 && ct.t < *best) {
      *best = ct.t;
      take_pair(bi, bj, c->j, ct.ka, ct.kb, (c->sx > 0) - (c->sx < 0), (c->sy > 0) - (c->sy < 0));
    }
    ord[k] = ord[--nc];
  }
}

/* The full prediction of body i, leaving out body skip (-1: none). */
static void predict_full(hd_sim *s, int32_t i, int32_t skip) {
  hd_body *bi = &s->b[i];
  const double now = s->c.t;
  int32_t cx, cy;
  hd_body_cxy(s, bi, &cx, &cy);
  double cross = crossing_time(s, bi, cx, cy);
  double best = INFINITY; /* earliest contact, relative to now */
  bi->p_type = HD_EV_NONE;
  if (s->disks_only) {
    predict_disks(s, i, cx, cy, cross, &best);
  } else {
    s->cut_t = INFINITY;
    if (s->walls) predict_walls(s, i, cross, &best);
    predict_sorted(s, i, skip, cross, &best);
    if (s->cut_t < best && s->cut_t < cross) {
      /* a search cut by a stop request: no contact before cut_t is known, so the body wakes up
       * then to be predicted again (a state as valid as any: a checkpoint of it resumes) */
      cross = s->cut_t;
      bi->c_dir = HD_WAKE;
      s->cut = 1;
    }
  }
  bi->c_t = now + cross;
  bi->p_t = now + best;
  commit(s, i);
}

void hd_predict(hd_sim *s, int32_t i) {
  predict_full(s, i, -1);
}

void hd_predict_after_pair(hd_sim *s, int32_t i, int32_t j) {
  /* disk pairs that have just collided recede (the closed form gives no contact), so only
   * pairs with a dimer, whose search is long near contact, are worth leaving out */
  predict_full(s, i, j);
  predict_full(s, j, -1);
}

/* The cell dist cells from cell c across face dir (0 +x, 1 -x, 2 +y, 3 -y) of a grid ncx
 * cells wide, without wrapping (for cells far enough from the edges). */
static inline int32_t cell_beyond(int32_t c, int dir, int32_t dist, int32_t ncx) {
  return c + dist * (hd_face_step[dir][0] + hd_face_step[dir][1] * ncx);
}

/* After body i crossed face `dir` (without wrapping) in a pure disk scene: searches the 3 cells
 * that became adjacent, keeping the stored contact if it is still valid.  Returns 0 when a full
 * prediction is needed instead (the stored contact is stale). */
static int predict_after_crossing(hd_sim *s, int32_t i) {
  hd_body *bi = &s->b[i];
  if (bi->p_type == HD_EV_PAIR && s->b[bi->p_partner].ncoll != bi->p_pcount) return 0;
  const double now = s->c.t, D = s->disks_d;
  int dir = bi->c_dir;
  int32_t c = bi->cell, ncx = s->ncx, cx, cy;
  hd_body_cxy(s, bi, &cx, &cy);
  double cross = crossing_time(s, bi, cx, cy);
  double best = bi->p_type == HD_EV_NONE ? INFINITY : bi->p_t - now;
  if (s->walls) predict_walls(s, i, cross, &best);
  if (cx >= 1 && cx < ncx - 1 && cy >= 1 && cy < s->ncy - 1) { /* interior: index offsets */
    int32_t mid = cell_beyond(c, dir, 1, ncx);                 /* the new cell straight ahead */
    int32_t along = dir < 2 ? ncx : 1;                         /* along the new column or row */
    int32_t js[9];
    int n = gather_cells(s, mid - along, along, 0, 1, js);
    for (int k = 0; k < n; k++) predict_disk_pair(s, bi, js[k], 0.0, 0.0, 0, 0, D, &best);
    for (int32_t cc = mid - along; n < 0 && cc <= mid + along; cc += along)
      for (int32_t j = s->head[cc]; j >= 0; j = s->b[j].next)
        predict_disk_pair(s, bi, j, 0.0, 0.0, 0, 0, D, &best);
    bi->c_t = now + cross;
    bi->p_t = now + best;
    commit(s, i);
    return 1;
  }
  for (int k = -1; k <= 1; k++) {
    /* the new column (dir 0/1) or row (dir 2/3), k along it */
    int32_t xx = cx, yy = cy;
    if (dir < 2)
      xx += dir == 0 ? 1 : -1, yy += k;
    else
      yy += dir == 2 ? 1 : -1, xx += k;
    double sx = 0.0, sy = 0.0;
    if (xx < 0) {
      if (s->walls & HD_WALL_LEFT) continue;
      xx += s->ncx, sx = -s->lx;
    } else if (xx >= s->ncx) {
      if (s->walls & HD_WALL_RIGHT) continue;
      xx -= s->ncx, sx = s->lx;
    }
    if (yy < 0) {
      if (s->walls & HD_WALL_BOTTOM) continue;
      yy += s->ncy, sy = -s->ly;
    } else if (yy >= s->ncy) {
      if (s->walls & HD_WALL_TOP) continue;
      yy -= s->ncy, sy = s->ly;
    }
    int ix = (sx > 0) - (sx < 0), iy = (sy > 0) - (sy < 0);
    for (int32_t j = s->head[yy * s->ncx + xx]; j >= 0; j = s->b[j].next)
      predict_disk_pair(s, bi, j, sx, sy, ix, iy, D, &best);
  }
  bi->c_t = now + cross;
  bi->p_t = now + best;
  commit(s, i);
  return 1;
}

void hd_predict_crossed(hd_sim *s, int32_t i, int wrapped) {
  if (s->partial_cross && !wrapped && predict_after_crossing(s, i)) return;
  hd_predict(s, i);
}

/* Prefetches both lines of body b.  Macros, not functions: gcc 12 finds a static function that
 * only prefetches "pure" and deletes its calls. */
#define HD_PREFETCH_BODY(b)                                                                        \
  do {                                                                                             \
    __builtin_prefetch(b);                                                                         \
    __builtin_prefetch((const char *)(b) + 64);                                                    \
  } while (0)

/* Prefetches body b's partner, if any: both lines for a collision (or the stale check), the
 * second (ncoll) for the check that a crossing makes on the stored contact. */
#define HD_PREFETCH_PARTNER(s, b)                                                                  \
  do {                                                                                             \
    if ((b)->p_type == HD_EV_PAIR) {                                                               \
      const hd_body *p_ = &(s)->b[(b)->p_partner];                                                 \
      if ((b)->p_t < (b)->c_t) __builtin_prefetch(p_);                                             \
      __builtin_prefetch((const char *)p_ + 64);                                                   \
    }                                                                                              \
  } while (0)

/* Prefetches the first line of body j (the first of a cell's list), if any. */
#define HD_PREFETCH_FIRST(s, j)                                                                    \
  do {                                                                                             \
    int32_t j_ = (j);                                                                              \
    if (j_ >= 0) __builtin_prefetch(&(s)->b[j_]);                                                  \
  } while (0)

void hd_predict_prefetch_far(void *ctx, int32_t i, int stage) {
  const hd_sim *s = ctx;
  const hd_body *b = &s->b[i];
  if (stage == 2) { /* 4 buckets ahead: the body itself */
    HD_PREFETCH_BODY(b);
    return;
  }
  if (stage == 1) { /* 2 ahead: its partner (and the rows that name a pair) */
    HD_PREFETCH_PARTNER(s, b);
    if (b->p_type == HD_EV_PAIR && b->p_t < b->c_t) { /* a collision: the row names both */
      __builtin_prefetch(&s->id[i]);
      __builtin_prefetch(&s->id[b->p_partner]);
    }
  }
  /* The cells whose lists body b's next event will walk (cells at least two from the edge
   * only; otherwise the event is left to the caches): for a crossing the current cell (its
   * list loses b) and the 3 cells that become adjacent, else the 3x3 block.  Walked in place,
   * no list built, and written out cell by cell (gcc -O2 does not unroll the loops, which
   * cost twice the instructions): the hint runs for every entry at two stages. */
  int32_t c = b->cell, ncx = s->ncx, cy = b->cy, cx = c - cy * ncx;
  if (cx < 2 || cx >= ncx - 2 || cy < 2 || cy >= s->ncy - 2) return;
  const int32_t *head = s->head;
  if (b->c_t <= b->p_t && s->partial_cross && b->c_dir != HD_WAKE) {
    int dir = b->c_dir;
    int32_t mid = cell_beyond(c, dir, 2, ncx), along = dir < 2 ? ncx : 1;
    if (stage == 1) { /* the list heads: its cell, the 3 that become adjacent, the one entered */
      __builtin_prefetch(&head[c]);
      __builtin_prefetch(&head[mid - along]);
      __builtin_prefetch(&head[mid]);
      __builtin_prefetch(&head[mid + along]);
      __builtin_prefetch(&head[cell_beyond(c, dir, 1, ncx)], 1); /* hd_cells_insert_xy */
      return;
    }
    /* 1 ahead: the line of a neighbour that a prediction reads */
    HD_PREFETCH_FIRST(s, head[c]);
    HD_PREFETCH_FIRST(s, head[mid - along]);
    HD_PREFETCH_FIRST(s, head[mid]);
    HD_PREFETCH_FIRST(s, head[mid + along]);
    return;
  }
  const int32_t *r0 = head + c - ncx, *r1 = head + c, *r2 = head + c + ncx;
  if (stage == 1) { /* the 3 rows of 3 list heads (each on one line, or two) */
    __builtin_prefetch(r0 - 1);
    __builtin_prefetch(r0 + 1);
    __builtin_prefetch(r1 - 1);
    __builtin_prefetch(r1 + 1);
    __builtin_prefetch(r2 - 1);
    __builtin_prefetch(r2 + 1);
    return;
  }
  HD_PREFETCH_FIRST(s, r0[-1]);
  HD_PREFETCH_FIRST(s, r0[0]);
  HD_PREFETCH_FIRST(s, r0[1]);
  HD_PREFETCH_FIRST(s, r1[-1]);
  HD_PREFETCH_FIRST(s, r1[0]);
  HD_PREFETCH_FIRST(s, r1[1]);
  HD_PREFETCH_FIRST(s, r2[-1]);
  HD_PREFETCH_FIRST(s, r2[0]);
  HD_PREFETCH_FIRST(s, r2[1]);
}

void hd_predict_prefetch_near(void *ctx, int32_t i, int stage) {
  const hd_sim *s = ctx;
  const hd_body *b = &s->b[i];
  if (stage == 1) { /* 2 buckets ahead: the body itself */
    HD_PREFETCH_BODY(b);
    return;
  }
  /* 1 ahead: the three rows of list heads around it (interior cells only) and its partner; in
   * dimer scenes also the first body of each cell, which a dimer's long prediction has time to
   * use (prefetched here, not in a helper: see HD_PREFETCH_PARTNER) */
  HD_PREFETCH_PARTNER(s, b);
  int32_t c = b->cell, ncx = s->ncx, cx, cy;
  hd_body_cxy(s, b, &cx, &cy);
  if (cx < 1 || cx >= ncx - 1 || cy < 1 || cy >= s->ncy - 1) return;
  for (int32_t row = c - ncx; row <= c + ncx; row += ncx) __builtin_prefetch(&s->head[row - 1]);
  if (!s->disks_only)
    for (int32_t row = c - ncx; row <= c + ncx; row += ncx)
      for (int32_t cc = row - 1; cc <= row + 1; cc++) {
        int32_t j = s->head[cc];
        if (j >= 0) __builtin_prefetch(&s->b[j]);
      }
}
