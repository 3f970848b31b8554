/* hd_queue: the event queue — an indexed binary min-heap of bodies keyed by each body's next
 * event time.  Every body has exactly one entry (its earliest predicted event); an event is
 * invalidated cheaply by a collision counter (see hd_sim.h), so the queue never holds stale
 * duplicates.  Keys live in the heap entries themselves (16 bytes: time and body), so that a
 * sift touches the heap array only.  Ties are broken by body index, which makes the order
 * total and the run deterministic however the heap was built. */
#ifndef HD_QUEUE_H
#define HD_QUEUE_H

#include <stdint.h>

/* One heap entry. */
typedef struct hd_qentry {
  double t;   /* event time */
  int32_t id; /* body */
  int32_t pad;
} hd_qentry;

/* The heap. */
typedef struct hd_queue {
  int32_t n;     /* entries */
  int32_t cap;   /* capacity (number of bodies) */
  hd_qentry *e;  /* e[k]: entry at heap slot k */
  int32_t *slot; /* slot[i]: heap slot of body i */
} hd_queue;

/* Allocates a queue for cap bodies; NULL on failure. */
hd_queue *hd_queue_alloc(int32_t cap);
/* Frees the queue (NULL allowed). */
void hd_queue_free(hd_queue *q);
/* Builds the heap holding bodies 0..n-1 with times t[i * stride] (in doubles): O(n). */
void hd_queue_build(hd_queue *q, int32_t n, const double *t, int32_t stride);
/* Sets body i's time to t and restores the heap (up or down). */
void hd_queue_update(hd_queue *q, int32_t i, double t);
/* The body with the earliest event (the heap must not be empty). */
static inline int32_t hd_queue_top(const hd_queue *q) {
  return q->e[0].id;
}

#endif
