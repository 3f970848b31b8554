/* hd_queue: the calendar event queue with lazy deletion (see hd_queue.h). */
#include "hd_queue.h"

#include <math.h>
#include <stdlib.h>

#include "hd_mem.h"

_Static_assert(sizeof(hd_qblock) == 64, "hd_qblock: one cache line");

/* Body i's key, in the caller's array. */
static inline double key_of(const hd_queue *q, int32_t i) {
  return q->key[(int64_t)i * q->kstride];
}

static inline int before(const hd_qentry *a, const hd_qentry *b) {
  return a->t < b->t || (a->t == b->t && a->id < b->id);
}

hd_queue *hd_queue_alloc(int32_t cap) {
  hd_queue *q = calloc(1, sizeof *q);
  if (!q) return NULL;
  size_t c = (size_t)(cap > 0 ? cap : 1);
  int32_t nb = 16;
  while (nb < cap && nb < (1 << 28)) nb *= 2;
  /* the heap and the overflow: every body once, plus the stale entries that wait with them
   * (a full one rebuilds the queue from the keys, which leaves at most n entries in all) */
  int64_t ecap = 2 * (int64_t)c + 64;
  if (ecap > INT32_MAX) ecap = INT32_MAX;
  /* extension blocks: with them the buckets hold 4 nb + 4 xcap >= 6 n entries, so the n live
   * entries of a rebuilt queue always fit, however they are spread */
  int32_t xcap = nb / 2 + 16;
  q->blk = hd_mem_alloc(sizeof(hd_qblock) * (size_t)nb);
  q->ext = hd_mem_alloc(sizeof(hd_qblock) * (size_t)xcap);
  q->heap = hd_mem_alloc(sizeof(hd_qentry) * (size_t)ecap);
  q->ovf = hd_mem_alloc(sizeof(hd_qentry) * (size_t)ecap);
  if (!q->blk || !q->ext || !q->heap || !q->ovf) {
    hd_queue_free(q);
    return NULL;
  }
  q->nb = nb;
  q->wfac = 1.0;
  q->xcap = xcap;
  q->ecap = (int32_t)ecap;
  return q;
}

void hd_queue_free(hd_queue *q) {
  if (!q) return;
  free(q->blk);
  free(q->ext);
  free(q->heap);
  free(q->ovf);
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
  q->npop++;
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
/* buckets */

static inline int64_t bucket_of(const hd_queue *q, double t) {
  double b = t * q->inv_w;
  if (b >= 0.0 && b < 4e18) return (int64_t)b; /* truncation is floor here */
  b = floor(b);
  return b < 4e18 ? (b > -4e18 ? (int64_t)b : -(int64_t)4e18) : (int64_t)4e18;
}

/* Puts an entry (t, id), t finite, in bucket b, where it belongs: the heap if b is the current
 * bucket, a bucket of the year, or the overflow.  Returns 0, or -1 when the place it needs is
 * full (the caller rebuilds the queue). */
static inline int place_in(hd_queue *q, double t, int32_t id, int64_t b) {
  if (b <= q->cur) {
    if (q->hn == q->ecap) return -1;
    heap_push(q, t, id);
  } else if (b < q->cur + q->nb) {
    hd_qblock *x = &q->blk[b & (q->nb - 1)];
    while (x->n == HD_QBLOCK) { /* full: on to its extension, or a new one in front of it */
      if (x->more < 0 || q->ext[x->more].n == HD_QBLOCK) {
        int32_t e = q->xfree;
        if (e < 0) return -1;
        q->xfree = q->ext[e].more;
        q->ext[e].n = 0;
        q->ext[e].more = x->more;
        x->more = e;
      }
      x = &q->ext[x->more];
    }
    x->t[x->n] = t;
    x->id[x->n] = id;
    x->n++;
    q->in_buckets++;
  } else {
    if (q->novf == q->ecap) return -1;
    q->ovf[q->novf++] = (hd_qentry){t, id, 0};
  }
  return 0;
}

/* Redistributes the overflow into the new year, dropping the stale entries that come into it;
 * what is still beyond it (stale or not: its key is not read) is compacted in place (the order in
 * the overflow does not matter).  -1 if a bucket or the heap is full (the overflow is then left as
 * it was: entries already placed are duplicates of ones still in the overflow, which a rebuild from
 * the keys discards anyway). */
static int redistribute(hd_queue *q) {
  int32_t n = q->novf, kept = 0;
  for (int32_t r = 0; r < n; r++) {
    /* for an entry 16 ahead that comes into the year, its key and its bucket's block (at
     * N = 10^6 a miss each, the block's read when the entry is placed): one beyond the year
     * stays without its key read (a stale one is dropped when it comes in) */
    if (r + 16 < n) {
      int64_t b16 = bucket_of(q, q->ovf[r + 16].t);
      if (b16 < q->cur + q->nb) {
        __builtin_prefetch(&q->key[(int64_t)q->ovf[r + 16].id * q->kstride]);
        __builtin_prefetch(&q->blk[b16 & (q->nb - 1)], 1);
      }
    }
    hd_qentry e = q->ovf[r];
    int64_t b = bucket_of(q, e.t);
    if (b >= q->cur + q->nb)
      q->ovf[kept++] = e;
    else if (key_of(q, e.id) != e.t)
      continue; /* stale */
    else if (place_in(q, e.t, e.id, b))
      return -1;
  }
  q->novf = kept;
  return 0;
}

/* The prefetch hint: the entries of the buckets 1, 2 (and 4) ahead of the current one, stage 0,
 * 1 (and 2); the bucket after the farthest is prefetched itself.  Buckets are consecutive
 * blocks, so this reads a few lines in order. */
static void hint(hd_queue *q) {
  static const int ahead[3] = {1, 2, 4};
  int32_t mask = q->nb - 1;
  __builtin_prefetch(&q->blk[(q->cur + ahead[q->pf_stages - 1] + 1) & mask]);
  for (int stage = q->pf_stages - 1; stage >= 0; stage--) {
    const hd_qblock *x = &q->blk[(q->cur + ahead[stage]) & mask];
    for (int32_t k = 0; k < x->n; k++)
      /* the first stage brings the key in (the engine's is on the body it prefetches); the
       * later ones skip an entry gone stale since */
      if (stage == q->pf_stages - 1 || key_of(q, x->id[k]) == x->t[k])
        q->pf(q->pf_ctx, x->id[k], stage);
  }
}

void hd_queue_set_prefetch(hd_queue *q, hd_queue_prefetch_fn fn, void *ctx, int stages) {
  q->pf = fn;
  q->pf_ctx = ctx;
  q->pf_stages = stages < 2 ? 2 : stages > 3 ? 3 : stages;
}

/* Moves the current entries of block x and of its extensions to the heap, empties them and
 * gives the extensions back. */
static void drain_block(hd_queue *q, hd_qblock *x) {
  int32_t e = x->more;
  x->more = -1;
  for (;;) {
    for (int32_t k = 0; k < x->n; k++)
      if (key_of(q, x->id[k]) == x->t[k]) heap_push(q, x->t[k], x->id[k]);
    /* else stale: its body's time has changed since */
    q->in_buckets -= x->n;
    x->n = 0;
    if (e < 0) return;
    x = &q->ext[e];
    int32_t nx = x->more;
    x->more = q->xfree;
    q->xfree = e;
    e = nx;
  }
}

static void rebuild(hd_queue *q);

/* Places the waiting entries whose bucket the queue has reached (into the heap) and sets pmin
 * to the earliest bucket of those that still wait; -1 if full. */
static int flush_due(hd_queue *q) {
  q->pmin = INT64_MAX;
  for (int k = 0; k < HD_QPEND; k++) {
    hd_qpend *p = &q->pend[k];
    if (p->id < 0) continue;
    if (p->b > q->cur) {
      if (p->b < q->pmin) q->pmin = p->b;
      continue;
    }
    q->npend--;
    int32_t id = p->id;
    p->id = -1;
    if (place_in(q, p->t, id, p->b)) return -1;
  }
  return 0;
}

/* Narrows the buckets to about two entries each (see crowded) and rebuilds. */
static int narrow(hd_queue *q) {
  if (4 * q->npop < q->n || !(q->wfac > 1e-12)) return 0;
  q->wfac *= 2.0 * (double)(q->nadv + 1) / (double)q->npop;
  if (q->wfac < 1e-12) q->wfac = 1e-12;
  rebuild(q);
  return 1;
}

/* Whether the buckets are crowded (more than HD_QCROWD entries taken per bucket advanced since
 * the last check); if so, narrows them and rebuilds.  The order of events does not depend on
 * the width, only the cost; the O(n) rebuild waits for n / 4 entries. */
static inline int crowded(hd_queue *q) {
  return q->npop > HD_QCROWD * (q->nadv + 16) && narrow(q);
}

/* Moves to the next non-empty bucket and fills the heap from it; 0 if no entry is left. */
static int advance(hd_queue *q) {
  if (q->in_buckets == 0 && q->npend == 0) {
    if (q->novf == 0) return 0;
    double tmin = INFINITY; /* jump straight to the earliest overflow entry */
    for (int32_t r = 0; r < q->novf; r++)
      if (q->ovf[r].t < tmin) tmin = q->ovf[r].t;
    q->cur = bucket_of(q, tmin);
    if (redistribute(q)) rebuild(q);
    return 1;
  }
  q->cur++;
  q->nadv++;
  if (crowded(q)) return 1;
  if ((q->cur & (q->nb - 1)) == 0) {                                  /* a new year */
    if (q->wfac < 1.0 && q->nadv >= q->nb && 2 * q->npop < q->nadv) { /* sparse: wider */
      q->wfac = q->wfac * 4.0 < 1.0 ? q->wfac * 4.0 : 1.0;
      rebuild(q);
      return 1;
    }
    if (q->nadv >= q->nb) q->npop = q->nadv = 0;
    if (redistribute(q)) {
      rebuild(q);
      return 1;
    }
  }
  if (q->pmin <= q->cur && flush_due(q)) {
    rebuild(q);
    return 1;
  }
  hd_qblock *x = &q->blk[q->cur & (q->nb - 1)];
  if (x->n > 0) drain_block(q, x);
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
    if (key_of(q, e->id) == e->t) return e->id;
    heap_pop(q);
    (void)crowded(q);
  }
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Refills the queue from the keys. */
static void rebuild(hd_queue *q) {
  int32_t n = q->n;
  double tmin = INFINITY;
  int64_t finite = 0;
  for (int32_t i = 0; i < n; i++) {
    double ti = key_of(q, i);
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
    if (key_of(q, i) < INFINITY) sample[ns++] = key_of(q, i) - tmin;
  q->w = 1.0;
  if (ns > 2 && finite > 1) {
    qsort(sample, (size_t)ns, sizeof(double), cmp_double);
    q->w = 2.0 * sample[ns / 2] / (double)finite;
  }
  q->w *= q->wfac;
  q->npop = q->nadv = 0;
  if (!(q->w > 0.0) || !isfinite(q->w) || !isfinite(1.0 / q->w)) q->w = 1.0;
  q->inv_w = 1.0 / q->w;
  q->cur = finite ? bucket_of(q, tmin) : 0;
  q->hn = 0;
  q->in_buckets = 0;
  q->novf = 0;
  for (int k = 0; k < HD_QPEND; k++) q->pend[k].id = -1;
  q->npend = 0;
  q->ppos = 0;
  q->pmin = INT64_MAX;
  for (int32_t s = 0; s < q->nb; s++) q->blk[s].n = 0, q->blk[s].more = -1;
  q->xfree = -1;
  for (int32_t e = q->xcap - 1; e >= 0; e--)
    q->ext[e].n = 0, q->ext[e].more = q->xfree, q->xfree = e;
  for (int32_t i = 0; i < n; i++) {
    double ti = key_of(q, i);
    if (ti < INFINITY) (void)place_in(q, ti, i, bucket_of(q, ti));
  }
  /* (place_in cannot fail here: the heap, the overflow and the buckets each hold >= n) */
}

void hd_queue_build(hd_queue *q, int32_t n, double *t, int32_t stride) {
  q->n = n;
  q->key = t;
  q->kstride = stride;
  rebuild(q);
}

void hd_queue_update(hd_queue *q, int32_t i, double t) {
  q->key[(int64_t)i * q->kstride] = t;
  if (t == INFINITY) return; /* no entry; the old one, if any, is stale now */
  int64_t b = bucket_of(q, t);
  if (b > q->cur && b < q->cur + q->nb) {
    /* a bucket of the year: its block (at random in memory) is prefetched now and written
     * HD_QPEND updates later, when it has arrived; the entry that was waiting in this slot
     * goes in first */
    hd_qpend *p = &q->pend[q->ppos];
    q->ppos = (q->ppos + 1) & (HD_QPEND - 1);
    if (p->id >= 0) {
      q->npend--;
      if (place_in(q, p->t, p->id, p->b)) {
        rebuild(q);
        return;
      }
    }
    __builtin_prefetch(&q->blk[b & (q->nb - 1)], 1);
    *p = (hd_qpend){t, b, i};
    q->npend++;
    if (b < q->pmin) q->pmin = b;
    return;
  }
  if (place_in(q, t, i, b)) rebuild(q); /* full of stale entries: afresh */
}
