#include "hd_queue.h"

#include <math.h>
#include <stdlib.h>

#include "hd_mem.h"

enum { HD_Q_HEAP = -1, HD_Q_OVERFLOW = -2, HD_Q_NEVER = -3 };

/* a before b: earlier time, ties by lower index. */
static inline int before(const hd_qentry *a, const hd_qentry *b) {
  return a->t < b->t || (a->t == b->t && a->id < b->id);
}

hd_queue *hd_queue_alloc(int32_t cap) {
  hd_queue *q = calloc(1, sizeof *q);
  if (!q) return NULL;
  size_t c = (size_t)(cap > 0 ? cap : 1);
  int32_t nb = 16;
  while (nb < cap && nb < (1 << 30)) nb *= 2;
  q->node = hd_mem_alloc(sizeof(hd_qnode) * c);
  q->heap = hd_mem_alloc(sizeof(hd_qentry) * c);
  q->head = hd_mem_alloc(sizeof(int32_t) * (size_t)nb);
  if (!q->node || !q->heap || !q->head) {
    hd_queue_free(q);
    return NULL;
  }
  q->cap = cap;
  q->nb = nb;
  return q;
}

void hd_queue_free(hd_queue *q) {
  if (!q) return;
  free(q->node);
  free(q->heap);
  free(q->head);
  free(q);
}

/* --- the current bucket's heap --- */

static void heap_up(hd_queue *q, int32_t k) {
  hd_qentry x = q->heap[k];
  while (k > 0) {
    int32_t p = (k - 1) / 2;
    if (!before(&x, &q->heap[p])) break;
    q->heap[k] = q->heap[p];
    q->node[q->heap[k].id].pos = k;
    k = p;
  }
  q->heap[k] = x;
  q->node[x.id].pos = k;
}

static void heap_down(hd_queue *q, int32_t k) {
  hd_qentry x = q->heap[k];
  for (;;) {
    int32_t c = 2 * k + 1;
    if (c >= q->hn) break;
    if (c + 1 < q->hn && before(&q->heap[c + 1], &q->heap[c])) c++;
    if (!before(&q->heap[c], &x)) break;
    q->heap[k] = q->heap[c];
    q->node[q->heap[k].id].pos = k;
    k = c;
  }
  q->heap[k] = x;
  q->node[x.id].pos = k;
}

static void heap_push(hd_queue *q, int32_t i) {
  q->node[i].where = HD_Q_HEAP;
  q->heap[q->hn] = (hd_qentry){q->node[i].t, i, 0};
  heap_up(q, q->hn++);
}

static void heap_remove(hd_queue *q, int32_t i) {
  int32_t k = q->node[i].pos;
  q->hn--;
  if (k == q->hn) return;
  q->heap[k] = q->heap[q->hn];
  q->node[q->heap[k].id].pos = k;
  if (k > 0 && before(&q->heap[k], &q->heap[(k - 1) / 2]))
    heap_up(q, k);
  else
    heap_down(q, k);
}

/* --- lists --- */

static inline void list_push(hd_queue *q, int32_t *head, int32_t i) {
  hd_qnode *x = &q->node[i];
  x->prev = -1;
  x->next = *head;
  if (*head >= 0) q->node[*head].prev = i;
  *head = i;
}

static inline void list_remove(hd_queue *q, int32_t *head, int32_t i) {
  const hd_qnode *x = &q->node[i];
  if (x->prev >= 0)
    q->node[x->prev].next = x->next;
  else
    *head = x->next;
  if (x->next >= 0) q->node[x->next].prev = x->prev;
}

/* floor(t / w) as t * (1 / w): monotone in t, which is all the buckets need (an earlier time
 * never lands in a later bucket); clamped so that it cannot overflow. */
static inline int64_t bucket_of(const hd_queue *q, double t) {
  double b = t * q->inv_w;
  if (b >= 0.0 && b < 4e18) return (int64_t)b; /* truncation is floor here */
  b = floor(b);
  return b < 4e18 ? (b > -4e18 ? (int64_t)b : -(int64_t)4e18) : (int64_t)4e18;
}

/* Files body i (key already in t[i]) where its time says. */
static inline void insert(hd_queue *q, int32_t i) {
  double t = q->node[i].t;
  if (t == INFINITY) {
    q->node[i].where = HD_Q_NEVER;
    list_push(q, &q->never, i);
    return;
  }
  int64_t b = bucket_of(q, t);
  if (b <= q->cur) {
    heap_push(q, i);
  } else if (b < q->cur + q->nb) {
    int32_t slot = (int32_t)(b & (q->nb - 1));
    q->node[i].where = slot;
    list_push(q, &q->head[slot], i);
    q->in_buckets++;
  } else {
    q->node[i].where = HD_Q_OVERFLOW;
    list_push(q, &q->overflow, i);
  }
}

static inline void detach(hd_queue *q, int32_t i) {
  int32_t w = q->node[i].where;
  if (w == HD_Q_HEAP)
    heap_remove(q, i);
  else if (w == HD_Q_OVERFLOW)
    list_remove(q, &q->overflow, i);
  else if (w == HD_Q_NEVER)
    list_remove(q, &q->never, i);
  else {
    list_remove(q, &q->head[w], i);
    q->in_buckets--;
  }
}

/* Moves the overflow entries that now fall within the year into their buckets. */
static void redistribute(hd_queue *q) {
  int32_t i = q->overflow;
  q->overflow = -1;
  while (i >= 0) {
    int32_t nx = q->node[i].next;
    insert(q, i);
    i = nx;
  }
}

/* Passes the first entries of the two buckets after the current one to the prefetch hint. */
static void hint(hd_queue *q) {
  for (int stage = 1; stage >= 0; stage--) {
    int32_t slot = (int32_t)((q->cur + stage + 1) & (q->nb - 1)), k = 0;
    for (int32_t i = q->head[slot]; i >= 0 && k < 4; i = q->node[i].next, k++)
      q->pf(q->pf_ctx, i, stage);
  }
}

void hd_queue_set_prefetch(hd_queue *q, hd_queue_prefetch_fn fn, void *ctx) {
  q->pf = fn;
  q->pf_ctx = ctx;
}

/* Makes the next non-empty bucket current; 0 when only never-entries are left. */
static int advance(hd_queue *q) {
  if (q->in_buckets == 0) {
    if (q->overflow < 0) return 0;
    double tmin = INFINITY; /* jump straight to the earliest overflow entry */
    for (int32_t i = q->overflow; i >= 0; i = q->node[i].next)
      if (q->node[i].t < tmin) tmin = q->node[i].t;
    q->cur = bucket_of(q, tmin);
    redistribute(q);
    return 1;
  }
  q->cur++;
  if ((q->cur & (q->nb - 1)) == 0) redistribute(q); /* a new year */
  int32_t slot = (int32_t)(q->cur & (q->nb - 1));
  int32_t i = q->head[slot];
  q->head[slot] = -1;
  while (i >= 0) {
    int32_t nx = q->node[i].next;
    q->in_buckets--;
    heap_push(q, i);
    i = nx;
  }
  if (q->pf) hint(q);
  return 1;
}

int32_t hd_queue_top(hd_queue *q) {
  while (q->hn == 0)
    if (!advance(q)) return q->never;
  return q->heap[0].id;
}

void hd_queue_update(hd_queue *q, int32_t i, double t) {
  detach(q, i);
  q->node[i].t = t;
  insert(q, i);
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

void hd_queue_build(hd_queue *q, int32_t n, const double *t, int32_t stride) {
  q->n = n;
  double tmin = INFINITY;
  int64_t finite = 0;
  for (int32_t i = 0; i < n; i++) {
    double ti = t[(int64_t)i * stride];
    q->node[i].t = ti;
    if (ti < INFINITY) {
      if (ti < tmin) tmin = ti;
      finite++;
    }
  }
  /* Bucket width from the median lead time of up to 1023 sampled keys (the mean would be
   * dragged by a few slow bodies): w = 2 median / finite, about one entry per bucket, most
   * entries within a year of nb >= n buckets. */
  double sample[1023];
  int ns = 0;
  int32_t stride_s = n > 1023 ? n / 1023 : 1;
  for (int32_t i = 0; i < n && ns < 1023; i += stride_s)
    if (q->node[i].t < INFINITY) sample[ns++] = q->node[i].t - tmin;
  q->w = 1.0;
  if (ns > 2 && finite > 1) {
    qsort(sample, (size_t)ns, sizeof(double), cmp_double);
    q->w = 2.0 * sample[ns / 2] / (double)finite;
  }
  if (!(q->w > 0.0) || !isfinite(q->w) || !isfinite(1.0 / q->w)) q->w = 1.0;
  q->inv_w = 1.0 / q->w;
  q->cur = finite ? bucket_of(q, tmin) : 0;
  q->hn = 0;
  q->in_buckets = 0;
  q->overflow = q->never = -1;
  for (int32_t s = 0; s < q->nb; s++) q->head[s] = -1;
  for (int32_t i = 0; i < n; i++) insert(q, i);
}
