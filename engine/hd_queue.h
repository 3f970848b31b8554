/* hd_queue: the event queue — one entry per body (its earliest predicted event), an O(1)
 * calendar queue in the manner of G. Paul, J. Comput. Phys. 221, 615 (2007):
 *   - time is cut into buckets of width w; bucket b holds the entries with floor(t/w) == b;
 *     the nb buckets ahead of the current one are an array of linked lists (a "year");
 *     entries further ahead wait in an overflow list, redistributed at each new year;
 *   - only the current bucket is ordered: a small binary heap, filled when the queue reaches it;
 *   - entries with t = INFINITY (bodies with nothing ahead) wait in a list of their own.
 * Insertion and removal are O(1), the minimum O(1) on average when w is about the mean spacing
 * of events (hd_queue_build tunes it from the keys; the engine rebuilds the queue every 100 N
 * events).  The order is the total order (time, then body index), so the sequence of events is
 * the same whatever the bucket layout: runs are deterministic and checkpoints exact. */
#ifndef HD_QUEUE_H
#define HD_QUEUE_H

#include <stdint.h>

/* An entry of the current bucket's heap. */
typedef struct hd_qentry {
  double t;   /* event time */
  int32_t id; /* body */
  int32_t pad;
} hd_qentry;

/* Everything the queue keeps for one body, together (one cache line holds two). */
typedef struct hd_qnode {
  double t;           /* the body's key */
  int32_t where;      /* >= 0 bucket slot, or one of HD_Q_* (hd_queue.c) */
  int32_t pos;        /* in the heap: its index there */
  int32_t next, prev; /* links in a bucket, overflow or never list */
  int32_t pad[2];
} hd_qnode;

/* A hint from the queue to its user: body i's event is `stage` + 1 buckets ahead of the current
 * one (stage 1, then 0 as it comes nearer), so that what processing it will read can be
 * prefetched in steps (for example its body, then its cells).  It must not change the queue. */
typedef void (*hd_queue_prefetch_fn)(void *ctx, int32_t i, int stage);

/* The queue.  Fields are private to hd_queue.c. */
typedef struct hd_queue {
  int32_t n, cap;          /* bodies held, capacity */
  hd_qnode *node;          /* node[i]: body i */
  hd_qentry *heap;         /* the current bucket, ordered */
  int32_t hn;              /* entries in heap */
  int32_t nb;              /* buckets in a year (a power of two) */
  int32_t *head;           /* head[slot]: first body of bucket slot, -1 if empty */
  int32_t overflow, never; /* heads of the overflow and never lists */
  int64_t in_buckets;      /* bodies in bucket lists */
  int64_t cur;             /* index of the current bucket (floor(t / w)) */
  double w;                /* bucket width */
  double inv_w;            /* 1 / w: the bucket of t is floor(t * inv_w) */
  hd_queue_prefetch_fn pf; /* prefetch hint, or NULL */
  void *pf_ctx;            /* its context */
} hd_queue;

/* Allocates a queue for cap bodies; NULL on failure. */
hd_queue *hd_queue_alloc(int32_t cap);
/* Frees the queue (NULL allowed). */
void hd_queue_free(hd_queue *q);
/* Fills the queue with bodies 0..n-1 with times t[i * stride] (in doubles), choosing the bucket
 * width from their spread: O(n). */
void hd_queue_build(hd_queue *q, int32_t n, const double *t, int32_t stride);
/* Sets the prefetch hint (fn NULL: none). */
void hd_queue_set_prefetch(hd_queue *q, hd_queue_prefetch_fn fn, void *ctx);
/* Sets body i's time to t (any value >= the last minimum, or INFINITY). O(1). */
void hd_queue_update(hd_queue *q, int32_t i, double t);
/* The body with the earliest event (ties: lowest index); a body with t = INFINITY when nothing
 * else is left.  The queue must hold at least one body. */
int32_t hd_queue_top(hd_queue *q);

#endif
