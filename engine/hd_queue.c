#include "hd_queue.h"

#include <stdlib.h>

/* a before b: earlier time, ties by lower index. */
static inline int before(const hd_qentry *a, const hd_qentry *b) {
  return a->t < b->t || (a->t == b->t && a->id < b->id);
}

hd_queue *hd_queue_alloc(int32_t cap) {
  hd_queue *q = calloc(1, sizeof *q);
  if (!q) return NULL;
  size_t c = (size_t)(cap > 0 ? cap : 1);
  q->e = malloc(sizeof(hd_qentry) * c);
  q->slot = malloc(sizeof(int32_t) * c);
  if (!q->e || !q->slot) {
    hd_queue_free(q);
    return NULL;
  }
  q->cap = cap;
  return q;
}

void hd_queue_free(hd_queue *q) {
  if (!q) return;
  free(q->e);
  free(q->slot);
  free(q);
}

static void sift_up(hd_queue *q, int32_t k) {
  hd_qentry x = q->e[k];
  while (k > 0) {
    int32_t p = (k - 1) / 2;
    if (!before(&x, &q->e[p])) break;
    q->e[k] = q->e[p];
    q->slot[q->e[k].id] = k;
    k = p;
  }
  q->e[k] = x;
  q->slot[x.id] = k;
}

static void sift_down(hd_queue *q, int32_t k) {
  hd_qentry x = q->e[k];
  int32_t n = q->n;
  for (;;) {
    int32_t c = 2 * k + 1;
    if (c >= n) break;
    if (c + 1 < n && before(&q->e[c + 1], &q->e[c])) c++;
    if (!before(&q->e[c], &x)) break;
    q->e[k] = q->e[c];
    q->slot[q->e[k].id] = k;
    k = c;
  }
  q->e[k] = x;
  q->slot[x.id] = k;
}

void hd_queue_build(hd_queue *q, int32_t n, const double *t, int32_t stride) {
  q->n = n;
  for (int32_t i = 0; i < n; i++) {
    q->e[i] = (hd_qentry){t[(int64_t)i * stride], i, 0};
    q->slot[i] = i;
  }
  for (int32_t k = n / 2 - 1; k >= 0; k--) sift_down(q, k);
}

void hd_queue_update(hd_queue *q, int32_t i, double t) {
  int32_t k = q->slot[i];
  q->e[k].t = t;
  if (k > 0 && before(&q->e[k], &q->e[(k - 1) / 2]))
    sift_up(q, k);
  else
    sift_down(q, k);
}
