/* Functions shared by the engine's own files (not part of the public API). */
#ifndef HD_SIM_INTERNAL_H
#define HD_SIM_INTERNAL_H

#include <assert.h>

#include "hd_sim.h"

/* Distance in doubles between consecutive bodies' ev_t (for hd_queue_build). */
#define HD_BODY_STRIDE ((int32_t)(sizeof(hd_body) / sizeof(double)))

/* --- cells (hd_cells.c) --- */
/* Sizes the cell grid for the largest body and allocates head[]; HD_ENOMEM. */
int hd_cells_alloc(hd_sim *s, hd_error *err);
/* Cell index of a position (wrapped into the box). */
int32_t hd_cells_of(const hd_sim *s, double x, double y);
/* Links body i into cell c (or column cx, row cy) / unlinks it from its cell. */
void hd_cells_insert(hd_sim *s, int32_t i, int32_t c);
void hd_cells_insert_xy(hd_sim *s, int32_t i, int32_t cx, int32_t cy);
void hd_cells_remove(hd_sim *s, int32_t i);
/* Rebuilds every list (and the bodies' rows) from the bodies' cell fields, in body order. */
void hd_cells_rebuild(hd_sim *s);

/* --- prediction (hd_predict.c) --- */
/* Predicts body i's next event at the current time (i must be advanced to it) and updates
 * the queue. */
void hd_predict(hd_sim *s, int32_t i);
/* Predicts both bodies of the pair (i, j) that has just collided.  Their own pair is searched
 * once, by j's prediction: if its contact is not j's earliest event, j has an earlier event,
 * which predicts j again (a collision, a crossing or a stale event), so nothing is lost. */
void hd_predict_after_pair(hd_sim *s, int32_t i, int32_t j);
/* Prefetch hints for the event queue (hd_queue_prefetch_fn, ctx = the hd_sim), for bodies that
 * outgrow a core's L2 cache.  Near (2 stages, within the last-level cache): body i 2 buckets
 * ahead, then its 3 rows of cell list heads and its partner.  Far (3 stages, past it): body i 4
 * buckets ahead, then the list heads of the cells its event walks (all 9, or for a crossing the
 * 3 new ones and its own), its partner and, for a collision, both bodies' entries of id[] (the
 * collision's row names them: 2 misses per collision at N = 1e6), then the first body of each
 * of those cells. */
void hd_predict_prefetch_near(void *ctx, int32_t i, int stage);
void hd_predict_prefetch_far(void *ctx, int32_t i, int stage);
/* Predicts body i's events after it crossed a cell face (wrapped: through the box edge). */
void hd_predict_crossed(hd_sim *s, int32_t i, int wrapped);

/* Column and row of body b's cell. */
static inline void hd_body_cxy(const hd_sim *s, const hd_body *b, int32_t *cx, int32_t *cy) {
  *cy = b->cy;
  *cx = b->cell - b->cy * s->ncx;
  assert(*cx >= 0 && *cx < s->ncx); /* cy is the row of cell */
}

/* Brings body i's state to the current time. */
static inline void hd_body_sync(hd_sim *s, int32_t i) {
  hd_body *b = &s->b[i];
  double dt = s->c.t - b->t;
  if (dt != 0.0) {
    if (b->k.omega != 0.0) {
      hd_kin_advance(&b->k, dt);
    } else { /* pure translation: no trigonometry, no wrapping of phi */
      b->k.x += b->k.vx * dt;
      b->k.y += b->k.vy * dt;
    }
    b->t = s->c.t;
  }
}

/* The step in cells (x, y) across face dir of a cell (hd_body.c_dir: 0 +x, 1 -x, 2 +y, 3 -y). */
static const int8_t hd_face_step[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};

/* Runs BODY for every body j in the 3x3 cells around cell c (j may be the caller's own body),
 * with (sx, sy) the periodic shift that brings j next to cell c.  With fewer than 3 cells in a
 * periodic direction the same cell is visited at its distinct images (shifts -L, 0, +L), which
 * is what a small box needs. */
#define HD_FOR_NEIGHBOURS(s, c, ...)                                                               \
  do {                                                                                             \
    int32_t cx_ = (c) % (s)->ncx, cy_ = (c) / (s)->ncx;                                            \
    for (int32_t dy_ = -1; dy_ <= 1; dy_++) {                                                      \
      int32_t yy_ = cy_ + dy_;                                                                     \
      double sy = 0.0;                                                                             \
      if (yy_ < 0) {                                                                               \
        if ((s)->walls & HD_WALL_BOTTOM) continue;                                                 \
        yy_ += (s)->ncy;                                                                           \
        sy = -(s)->ly;                                                                             \
      } else if (yy_ >= (s)->ncy) {                                                                \
        if ((s)->walls & HD_WALL_TOP) continue;                                                    \
        yy_ -= (s)->ncy;                                                                           \
        sy = (s)->ly;                                                                              \
      }                                                                                            \
      for (int32_t dx_ = -1; dx_ <= 1; dx_++) {                                                    \
        int32_t xx_ = cx_ + dx_;                                                                   \
        double sx = 0.0;                                                                           \
        if (xx_ < 0) {                                                                             \
          if ((s)->walls & HD_WALL_LEFT) continue;                                                 \
          xx_ += (s)->ncx;                                                                         \
          sx = -(s)->lx;                                                                           \
        } else if (xx_ >= (s)->ncx) {                                                              \
          if ((s)->walls & HD_WALL_RIGHT) continue;                                                \
          xx_ -= (s)->ncx;                                                                         \
          sx = (s)->lx;                                                                            \
        }                                                                                          \
        for (int32_t j = (s)->head[yy_ * (s)->ncx + xx_]; j >= 0; j = (s)->b[j].next) {            \
          __VA_ARGS__                                                                              \
        }                                                                                          \
      }                                                                                            \
    }                                                                                              \
  } while (0)

/* --- set-up (hd_sim.c, hd_checkpoint.c) --- */
/* Allocates the queue for s->n bodies (keys not yet set). */
int hd_sim_queue_init(hd_sim *s, hd_error *err);
/* Fills a set-up simulation (species, box, RNG) from a checkpoint blob: bodies, cells, clocks,
 * RNG state, queue. */
int hd_sim_restore_blob(hd_sim *s, const void *blob, size_t n, hd_error *err);

/* --- initial state (hd_init.c) --- */
/* Places the bodies and draws velocities as the scene says; sets s->melt when the bodies were
 * put on a dense lattice that hd_sim_alloc must melt. */
int hd_init_state(hd_sim *s, const hd_scene *sc, hd_error *err);
/* Maxwellian velocities at temperature T, zero total momentum, rescaled so that the kinetic
 * energy is exactly T per body in translation and T/2 per rotating body in rotation. */
void hd_init_velocities(hd_sim *s, double T);

#endif
