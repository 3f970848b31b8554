#include "hd_queue.h"

#include <stdlib.h>

static inline double qkey(const hd_queue *q, int32_t i) {
  return q->key[(int64_t)i * q->key_stride];
}

/* a before b: earlier time, ties by lower index. */
static inline int before(const hd_queue *q, int32_t a, int32_t b) {
  double ka = qkey(q, a), kb = qkey(q, b);
  return ka < kb || (ka == kb && a < b);
}

hd_queue *hd_queue_alloc(int32_t cap, const double *key, int32_t stride) {
  hd_queue *q = calloc(1, sizeof *q);
  if (!q) return NULL;
  q->heap = malloc(sizeof(int32_t) * (size_t)(cap > 0 ? cap : 1));
  q->slot = malloc(sizeof(int32_t) * (size_t)(cap > 0 ? cap : 1));
  if (!q->heap || !q->slot) {
    hd_queue_free(q);
    return NULL;
  }
  q->cap = cap;
  q->key = key;
  q->key_stride = stride;
  return q;
}

void hd_queue_free(hd_queue *q) {
  if (!q) return;
  free(q->heap);
  free(q->slot);
  free(q);
}

void hd_queue_rekey(hd_queue *q, const double *key) {
  q->key = key;
}

static void sift_up(hd_queue *q, int32_t k) {
  int32_t b = q->heap[k];
  while (k > 0) {
    int32_t p = (k - 1) / 2;
    if (!before(q, b, q->heap[p])) break;
    q->heap[k] = q->heap[p];
    q->slot[q->heap[k]] = k;
    k = p;
  }
  q->heap[k] = b;
  q->slot[b] = k;
}

static void sift_down(hd_queue *q, int32_t k) {
  int32_t b = q->heap[k], n = q->n;
  for (;;) {
    int32_t c = 2 * k + 1;
    if (c >= n) break;
    if (c + 1 < n && before(q, q->heap[c + 1], q->heap[c])) c++;
    if (!before(q, q->heap[c], b)) break;
    q->heap[k] = q->heap[c];
    q->slot[q->heap[k]] = k;
    k = c;
  }
  q->heap[k] = b;
  q->slot[b] = k;
}

void hd_queue_build(hd_queue *q, int32_t n) {
  q->n = n;
  for (int32_t i = 0; i < n; i++) {
    q->heap[i] = i;
    q->slot[i] = i;
  }
  for (int32_t k = n / 2 - 1; k >= 0; k--) sift_down(q, k);
}

void hd_queue_update(hd_queue *q, int32_t i) {
  int32_t k = q->slot[i];
  if (k > 0 && before(q, i, q->heap[(k - 1) / 2]))
    sift_up(q, k);
  else
    sift_down(q, k);
}
