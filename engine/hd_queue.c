/* hd_queue: the calendar event queue with lazy deletion (see hd_queue.h). */
#include "hd_queue.h"

#include <math.h>
#include <stdlib.h>

#include "hd_mem.h"

static inline int before(const hd_qentry *a, const hd_qentry *b) {
  return a->t < b->t || (a->t == b->t && a->id < b->id);
}

hd_queue *hd_queue_alloc(int32_t cap) {
  hd_queue *q = calloc(1, sizeof *q);
  if (!q) return NULL;
  size_t c = (size_t)(cap > 0 ? cap : 1);
  int32_t nb = 16;
  while (nb < cap && nb < (1 << 30)) nb *= 2;
  /* entries: one per body, plus the stale ones; about one stale entry per body is typical
   * (a collision leaves the partner's old entry behind), so 3 per body rarely fill up */
  int64_t icap = 3 * (int64_t)c + 64;
  if (icap > INT32_MAX) icap = INT32_MAX;
  q->key = hd_mem_alloc(sizeof(double) * c);
  q->item = hd_mem_alloc(sizeof(hd_qitem) * (size_t)icap);
  q->heap = hd_mem_alloc(sizeof(hd_qentry) * (size_t)icap);
  q->ovf = hd_mem_alloc(sizeof(hd_qentry) * (size_t)icap);
  q->head = hd_mem_alloc(sizeof(int32_t) * (size_t)nb);
  if (!q->key || !q->item || !q->heap || !q->ovf || !q->head) {
    hd_queue_free(q);
    return NULL;
  }
  q->cap = cap;
  q->nb = nb;
  q->icap = (int32_t)icap;
  return q;
}

void hd_queue_free(hd_queue *q) {
  if (!q) return;
  free(q->key);
  free(q->item);
  free(q->heap);
  free(q->ovf);
  free(q->head);
  free(q);
}

/* ---------------------------------------------------------------------------------------- */
/* the heap of the current bucket */

static void heap_push(hd_queue *q, double t, int32_t id) {
  hd_qentry x = {t, id, 0};
  int32_t k = q->hn++;
  while (k > 0) {
    int32_t p = (k - 1) / 2;
    if (!before(&x, &q->heap[p])) break;
    q->heap[k] = q->heap[p];
    k = p;
  }
  q->heap[k] = x;
}

/* Removes the top entry. */
static void heap_pop(hd_queue *q) {
  hd_qentry x = q->heap[--q->hn];
  int32_t n = q->hn, k = 0;
  if (n == 0) return;
  for (;;) {
    int32_t c = 2 * k + 1;
    if (c >= n) break;
    if (c + 1 < n && before(&q->heap[c + 1], &q->heap[c])) c++;
    if (!before(&q->heap[c], &x)) break;
    q->heap[k] = q->heap[c];
    k = c;
  }
  q->heap[k] = x;
}

/* ---------------------------------------------------------------------------------------- */
/* lists */

static inline int64_t bucket_of(const hd_queue *q, double t) {
  double b = t * q->inv_w;
  if (b >= 0.0 && b < 4e18) return (int64_t)b; /* truncation is floor here */
  b = floor(b);
  return b < 4e18 ? (b > -4e18 ? (int64_t)b : -(int64_t)4e18) : (int64_t)4e18;
}

/* A free item (there is one: the caller checked live < icap). */
static inline int32_t item_take(hd_queue *q) {
  int32_t it = q->ifree;
  if (it >= 0) {
    q->ifree = q->item[it].next;
    return it;
  }
  return q->itop++;
}

static inline void item_give(hd_queue *q, int32_t it) {
  q->item[it].next = q->ifree;
  q->ifree = it;
}

/* Puts an entry (t, id), t finite, in bucket b, where it belongs: the heap if b is the current
 * bucket, a bucket of the year, or the overflow (live already counts it). */
static inline void place_in(hd_queue *q, double t, int32_t id, int64_t b) {
  if (b <= q->cur) {
    heap_push(q, t, id);
  } else if (b < q->cur + q->nb) {
    int32_t it = item_take(q), slot = (int32_t)(b & (q->nb - 1));
    hd_qitem *x = &q->item[it];
    x->t = t;
    x->id = id;
    x->next = q->head[slot];
    q->head[slot] = it;
    q->in_buckets++;
  } else {
    q->ovf[q->novf++] = (hd_qentry){t, id, 0};
  }
}

static inline void place(hd_queue *q, double t, int32_t id) {
  place_in(q, t, id, bucket_of(q, t));
}

/* Redistributes the overflow into the new year, dropping stale entries; what is still beyond
 * it is compacted in place (the order in the overflow does not matter). */
static void redistribute(hd_queue *q) {
  int32_t n = q->novf, kept = 0;
  for (int32_t r = 0; r < n; r++) {
    hd_qentry e = q->ovf[r];
    if (q->key[e.id] != e.t) { /* stale */
      q->live--;
      continue;
    }
    int64_t b = bucket_of(q, e.t);
    if (b >= q->cur + q->nb)
      q->ovf[kept++] = e;
    else
      place_in(q, e.t, e.id, b);
  }
  q->novf = kept;
}

/* The prefetch hint for the next two buckets (a few entries of each). */
static void hint(hd_queue *q) {
  for (int stage = 1; stage >= 0; stage--) {
    int32_t slot = (int32_t)((q->cur + stage + 1) & (q->nb - 1)), k = 0;
    for (int32_t it = q->head[slot]; it >= 0 && k < 4; it = q->item[it].next, k++) {
      __builtin_prefetch(&q->key[q->item[it].id]);
      q->pf(q->pf_ctx, q->item[it].id, stage);
    }
  }
}

void hd_queue_set_prefetch(hd_queue *q, hd_queue_prefetch_fn fn, void *ctx) {
  q->pf = fn;
  q->pf_ctx = ctx;
}

/* Moves to the next non-empty bucket and fills the heap from it; 0 if no entry is left. */
static int advance(hd_queue *q) {
  if (q->in_buckets == 0) {
    if (q->novf == 0) return 0;
    double tmin = INFINITY; /* jump straight to the earliest overflow entry */
    for (int32_t r = 0; r < q->novf; r++)
      if (q->ovf[r].t < tmin) tmin = q->ovf[r].t;
    q->cur = bucket_of(q, tmin);
    redistribute(q);
    return 1;
  }
  q->cur++;
  if ((q->cur & (q->nb - 1)) == 0) redistribute(q); /* a new year */
  int32_t slot = (int32_t)(q->cur & (q->nb - 1));
  int32_t it = q->head[slot];
  q->head[slot] = -1;
  while (it >= 0) {
    const hd_qitem *x = &q->item[it];
    int32_t nx = x->next;
    q->in_buckets--;
    if (q->key[x->id] == x->t)
      heap_push(q, x->t, x->id);
    else
      q->live--; /* stale: its body's time has changed since */
    item_give(q, it);
    it = nx;
  }
  if (q->pf) hint(q);
  return 1;
}

int32_t hd_queue_top(hd_queue *q) {
  for (;;) {
    while (q->hn == 0)
      if (!advance(q)) return 0; /* no entry: every body is at INFINITY */
    const hd_qentry *e = &q->heap[0];
    /* current while its time is the body's key (two entries with the same time and body are
     * the same event: whichever comes up first stands for both) */
    if (q->key[e->id] == e->t) return e->id;
    heap_pop(q);
    q->live--;
  }
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
    q->key[i] = ti;
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
    if (q->key[i] < INFINITY) sample[ns++] = q->key[i] - tmin;
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
  q->ifree = -1;
  q->novf = 0;
  q->itop = 0;
  q->live = 0;
  for (int32_t s = 0; s < q->nb; s++) q->head[s] = -1;
  for (int32_t i = 0; i < n; i++)
    if (q->key[i] < INFINITY) {
      q->live++;
      place(q, q->key[i], i);
    }
}

void hd_queue_update(hd_queue *q, int32_t i, double t) {
  q->key[i] = t;
  if (t == INFINITY) return; /* no entry; the old one, if any, is stale now */
  if (q->live >= q->icap) {  /* the pool is full of stale entries: start afresh from the keys */
    hd_queue_build(q, q->n, q->key, 1);
    return;
  }
  q->live++;
  place(q, t, i);
}
