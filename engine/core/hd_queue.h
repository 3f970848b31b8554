/* hd_queue: the event queue — the earliest predicted event of each body, an O(1) calendar queue
 * in the manner of G. Paul, J. Comput. Phys. 221, 615 (2007), with lazy deletion:
 *   - time is cut into buckets of width w; bucket b holds the entries with floor(t/w) == b;
 *     the nb buckets ahead of the current one (a "year") are consecutive blocks of one cache
 *     line, 4 entries each, with a chain of extension blocks for a bucket that holds more;
 *     entries further ahead wait in an overflow array, redistributed at each new year (an
 *     array, scanned in order, not a list: at N = 10^6 walking a list there was 10 % of the time);
 *   - only the current bucket is ordered: a small binary heap, filled when the queue reaches it;
 *   - a body whose time changes gets a new entry; the old one is left where it is and dropped
 *     when it comes up (an entry is current while its time equals the body's key).  Nothing is
 *     ever unlinked, so an update touches one bucket's block: no neighbour in a list, no heap
 *     position to maintain (at N = 10^6 each of those was a cache miss), and the queue walks
 *     its buckets in memory order (linked items scattered over the pool were a cache miss each
 *     at N = 10^6);
 *   - bodies with t = INFINITY have no entry.
 * Insertion is O(1), the minimum O(1) on average when w is about the mean spacing of events
 * (hd_queue_build tunes it from the keys; the engine rebuilds the queue every 100 N events; a
 * queue whose heap, overflow or extension pool fills with stale entries rebuilds itself from
 * the keys).  When the events crowd into a few bodies (a rod ring's dense clusters), the width
 * from the keys' spread is far too wide and each bucket holds hundreds of entries, ordered by
 * the heap: a queue whose buckets hold more than HD_QCROWD entries each on average narrows its
 * buckets to about two entries each and rebuilds, and widens them again (up to the rule's
 * width) when a year holds fewer than one entry per 2 buckets.  The order is the total order (time,
 * then body index), so the sequence of events is the same whatever the bucket layout: runs are
 * deterministic and checkpoints exact. */
#ifndef HD_QUEUE_H
#define HD_QUEUE_H

#include <stdint.h>

/* An entry of the current bucket's heap or of the overflow. */
typedef struct hd_qentry {
  double t;   /* event time */
  int32_t id; /* body */
  int32_t pad;
} hd_qentry;

/* Entries a bucket's block holds (one cache line: 4 times and 4 bodies). */
#define HD_QBLOCK 4

/* A bucket of the year: a block of up to HD_QBLOCK entries, and a chain of extension blocks
 * (from a pool) when more fall in it.  The buckets of a year are consecutive blocks, so the
 * queue reads its near future in memory order. */
typedef struct hd_qblock {
  double t[HD_QBLOCK];   /* event times */
  int32_t id[HD_QBLOCK]; /* bodies */
  int32_t n;             /* entries held, 0..HD_QBLOCK */
  int32_t more;          /* first extension block (ext index; only it may have room), -1: none;
                          * in the pool's free list: the next free block */
  int32_t pad[2];
} hd_qblock;

/* Entries per bucket advanced above which the queue narrows its buckets. */
#define HD_QCROWD 32

/* Updates that wait before they are written into their bucket's block (a power of two): the
 * block is prefetched when the update comes and written this many updates later. */
#define HD_QPEND 8

/* An update waiting to be written into a bucket of the year. */
typedef struct hd_qpend {
  double t;   /* event time */
  int64_t b;  /* its bucket (ahead of the current one, within the year) */
  int32_t id; /* body, -1: the slot is free */
} hd_qpend;

/* A hint from the queue to its user: body i's event is 1 (stage 0), 2 (stage 1) or, with three
 * stages, 4 (stage 2) buckets ahead of the current one; each entry is hinted at every stage,
 * the highest first, so that what processing it will read can be prefetched in steps (for
 * example its body, then its cells, then their bodies).  It must not change the queue.  The
 * entry may be stale (the body's time changed since): the hint is then useless, not wrong. */
typedef void (*hd_queue_prefetch_fn)(void *ctx, int32_t i, int stage);

/* The queue.  Fields are private to hd_queue.c. */
typedef struct hd_queue {
  int32_t n;               /* bodies held (at most the capacity given to hd_queue_alloc) */
  double *key;             /* key[i * kstride]: body i's time (INFINITY: no event), in the
                            * caller's array (hd_queue_build) */
  int64_t kstride;         /* distance between consecutive keys, in doubles */
  hd_qblock *blk;          /* blk[slot]: the bucket slot of the year, nb of them */
  hd_qblock *ext;          /* pool of extension blocks, xcap of them */
  int32_t xcap;            /* blocks in the pool */
  int32_t xfree;           /* first free extension block (a list through more), -1 if none */
  int32_t ecap;            /* room in the heap and in the overflow (each) */
  hd_qentry *heap;         /* the current bucket, ordered */
  int32_t hn;              /* entries in heap */
  int32_t nb;              /* buckets in a year (a power of two) */
  hd_qentry *ovf;          /* the overflow: entries beyond the year */
  int32_t novf;            /* entries in it */
  int64_t in_buckets;      /* entries in the buckets' blocks */
  hd_qpend pend[HD_QPEND]; /* updates waiting to be written into their blocks, a ring */
  int32_t ppos;            /* the ring's next slot */
  int32_t npend;           /* updates waiting */
  int64_t pmin;            /* no update waits for a bucket before this one (INT64_MAX: none;
                            * may be lower than the earliest, never higher) */
  int64_t cur;             /* index of the current bucket (floor(t / w)) */
  double w;                /* bucket width */
  double inv_w;            /* 1 / w: the bucket of t is floor(t * inv_w) */
  double wfac;             /* the bucket width is wfac times its rule's (rebuild): 1, lowered
                            * when the current buckets overfill (events crowded into a
                            * fraction of the bodies, as in a rod ring's dense clusters) */
  int64_t npop;            /* entries taken from the heap since the width was last checked */
  int64_t nadv;            /* buckets advanced since then */
  hd_queue_prefetch_fn pf; /* prefetch hint, or NULL */
  void *pf_ctx;            /* its context */
  int pf_stages;           /* its stages, 2 or 3 */
} hd_queue;

/* Allocates a queue for cap bodies; NULL on failure. */
hd_queue *hd_queue_alloc(int32_t cap);
/* Frees the queue (NULL allowed). */
void hd_queue_free(hd_queue *q);
/* Fills the queue with bodies 0..n-1 whose times are t[i * stride] (in doubles), choosing the
 * bucket width from their spread: O(n).  The queue keeps reading its keys there (for the engine
 * that is each body's own ev_t, on the line that the event and the prefetch hint bring in
 * anyway: no separate array to miss in): the caller changes key i only through
 * hd_queue_update (which writes it), and builds the queue again after it moves the array. */
void hd_queue_build(hd_queue *q, int32_t n, double *t, int32_t stride);
/* Sets the prefetch hint (fn NULL: none) and its stages (2 or 3, see hd_queue_prefetch_fn). */
void hd_queue_set_prefetch(hd_queue *q, hd_queue_prefetch_fn fn, void *ctx, int stages);
/* Sets body i's time to t (any value >= the last minimum, or INFINITY), writing t[i * stride]
 * of hd_queue_build's array. O(1) amortised. */
void hd_queue_update(hd_queue *q, int32_t i, double t);
/* The body with the earliest event (ties: lowest index); a body with t = INFINITY when nothing
 * else is left.  The queue must hold at least one body. */
int32_t hd_queue_top(hd_queue *q);

#endif
