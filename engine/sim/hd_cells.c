/* Cell lists: a grid of cells at least as wide as the largest body, each holding a singly
 * linked list of the bodies whose centre of mass is in it. */
#include <math.h>
#include <stdlib.h>

#include "hd_mem.h"
#include "hd_sim_internal.h"

int hd_cells_alloc(hd_sim *s, hd_error *err) {
  double range = 0.0; /* largest centre distance at contact: the largest body's diameter */
  for (int sp = 0; sp < s->nsp; sp++)
    if (s->n_species[sp] > 0) range = fmax(range, 2.0 * hd_shape_radius(&s->shape[sp]));
  if (range <= 0.0) range = 1.0;
  double fx = floor(s->lx / range), fy = floor(s->ly / range);
  /* cap the grid at ~4 cells per body so that a dilute gas does not pay for empty cells; a box
   * of more than ~1e308 diameters gives inf, which halving never brings down: that one starts
   * at cap (a finite count halves as it always did: the grid is part of a checkpoint) */
  double cap = fmax(1.0, 4.0 * (double)s->n);
  if (!isfinite(fx)) fx = cap;
  if (!isfinite(fy)) fy = cap;
  while (fx * fy > cap && (fx > 1 || fy > 1)) {
    if (fx >= fy)
      fx = floor(fx / 2);
    else
      fy = floor(fy / 2);
  }
  s->ncx = (int32_t)fmax(1.0, fx);
  s->ncy = (int32_t)fmax(1.0, fy);
  s->cwx = s->lx / s->ncx;
  s->cwy = s->ly / s->ncy;
  free(s->head);
  s->head = hd_mem_alloc(sizeof(int32_t) * (size_t)s->ncx * (size_t)s->ncy);
  if (!s->head)
    return hd_error_set(err, HD_ENOMEM, "out of memory for %d x %d cells", s->ncx, s->ncy);
  for (int64_t c = 0; c < (int64_t)s->ncx * s->ncy; c++) s->head[c] = -1;
  return HD_OK;
}

int32_t hd_cells_of(const hd_sim *s, double x, double y) {
  int32_t cx = (int32_t)floor(x / s->cwx), cy = (int32_t)floor(y / s->cwy);
  if (cx < 0) cx = 0;
  if (cx >= s->ncx) cx = s->ncx - 1;
  if (cy < 0) cy = 0;
  if (cy >= s->ncy) cy = s->ncy - 1;
  return cy * s->ncx + cx;
}

void hd_cells_insert(hd_sim *s, int32_t i, int32_t c) {
  hd_cells_insert_xy(s, i, c % s->ncx, c / s->ncx);
}

void hd_cells_insert_xy(hd_sim *s, int32_t i, int32_t cx, int32_t cy) {
  hd_body *b = &s->b[i];
  int32_t c = cy * s->ncx + cx;
  b->cell = c;
  b->cy = cy;
  b->next = s->head[c];
  s->head[c] = i;
}

void hd_cells_remove(hd_sim *s, int32_t i) {
  /* singly linked: the lists are short (about one body per cell), and unlinking touches no
   * body but the predecessor, which a doubly linked list would touch too, with the successor */
  hd_body *b = &s->b[i];
  int32_t *link = &s->head[b->cell];
  while (*link != i) link = &s->b[*link].next;
  *link = b->next;
  b->next = -1;
}

void hd_cells_rebuild(hd_sim *s) {
  for (int64_t c = 0; c < (int64_t)s->ncx * s->ncy; c++) s->head[c] = -1;
  for (int32_t i = s->n - 1; i >= 0; i--) hd_cells_insert(s, i, s->b[i].cell);
}
