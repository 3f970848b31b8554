/* hd_queue: the event queue — the earliest predicted event of each body, an O(1) calendar queue
 * in the manner of G. Paul, J. Comput. Phys. 221, 615 (2007), with lazy deletion:
 *   - time is cut into buckets of width w; bucket b holds the entries with floor(t/w) == b;
 *     the nb buckets ahead of the current one are an array of singly linked lists (a "year");
 *     entries further ahead wait in an overflow array, redistributed at each new year (an
 *     array, scanned in order, not a list: at N = 10^6 walking a list there was 10 % of the time);
 *   - only the current bucket is ordered: a small binary heap, filled when the queue reaches it;
 *   - a body whose time changes gets a new entry; the old one is left where it is and dropped
 *     when it comes up (an entry is current while its time equals the body's key).  Nothing is
 *     ever unlinked, so an update touches one bucket head and one recycled entry: no neighbour
 *     in a list, no heap position to maintain (at N = 10^6 each of those was a cache miss);
 *   - bodies with t = INFINITY have no entry.
 * Insertion is O(1), the minimum O(1) on average when w is about the mean spacing of events
 * (hd_queue_build tunes it from the keys; the engine rebuilds the queue every 100 N events; a
 * queue whose entries, current and stale, fill its pool rebuilds itself from the keys).  The
 * order is the total order (time, then body index), so the sequence of events is the same
 * whatever the bucket layout: runs are deterministic and checkpoints exact. */
#ifndef HD_QUEUE_H
#define HD_QUEUE_H

#include <stdint.h>

/* An entry of the current bucket's heap. */
typedef struct hd_qentry {
  double t;   /* event time */
  int32_t id; /* body */
  int32_t pad;
} hd_qentry;

/* An entry of a bucket. */
typedef struct hd_qitem {
  double t;     /* event time */
  int32_t id;   /* body */
  int32_t next; /* next item of the list, -1 at its end (free items: the next free one) */
} hd_qitem;

/* A hint from the queue to its user: body i's event is `stage` + 1 buckets ahead of the current
 * one (stage 1, then 0 as it comes nearer), so that what processing it will read can be
 * prefetched in steps (for example its body, then its cells).  It must not change the queue.
 * The entry may be stale (the body's time changed since): the hint is then useless, not wrong. */
typedef void (*hd_queue_prefetch_fn)(void *ctx, int32_t i, int stage);

/* The queue.  Fields are private to hd_queue.c. */
typedef struct hd_queue {
  int32_t n, cap;          /* bodies held, capacity */
  double *key;             /* key[i]: body i's time (INFINITY: no event) */
  hd_qitem *item;          /* pool of list items, icap of them */
  int32_t icap;            /* items in the pool; also the heap's capacity */
  int32_t ifree;           /* first free item (a list through next), -1 if none */
  int32_t itop;            /* items [itop, icap) have never been used */
  int32_t live;            /* items in lists plus entries in the heap */
  hd_qentry *heap;         /* the current bucket, ordered */
  int32_t hn;              /* entries in heap */
  int32_t nb;              /* buckets in a year (a power of two) */
  int32_t *head;           /* head[slot]: first item of bucket slot, -1 if empty */
  hd_qentry *ovf;          /* the overflow: entries beyond the year, icap of room */
  int32_t novf;            /* entries in it */
  int64_t in_buckets;      /* items in bucket lists */
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
/* Sets body i's time to t (any value >= the last minimum, or INFINITY). O(1) amortised. */
void hd_queue_update(hd_queue *q, int32_t i, double t);
/* The body with the earliest event (ties: lowest index); a body with t = INFINITY when nothing
 * else is left.  The queue must hold at least one body. */
int32_t hd_queue_top(hd_queue *q);

#endif
