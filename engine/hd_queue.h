/* hd_queue: the event queue — an indexed binary min-heap of bodies keyed by each body's next
 * event time.  Every body has exactly one entry (its earliest predicted event); an event is
 * invalidated cheaply by a collision counter (see hd_sim.h), so the queue never holds stale
 * duplicates.  Ties are broken by body index, which makes the order a total one and the run
 * deterministic however the heap was built. */
#ifndef HD_QUEUE_H
#define HD_QUEUE_H

#include <stdint.h>

/* The heap.  key[i] is body i's event time, owned by the caller and read through the pointer. */
typedef struct hd_queue {
  int32_t n;          /* entries in the heap */
  int32_t cap;        /* capacity (number of bodies) */
  int32_t *heap;      /* heap[k]: body at heap slot k */
  int32_t *slot;      /* slot[i]: heap slot of body i, -1 if absent */
  const double *key;  /* key[i]: event time of body i (stride: key_stride doubles) */
  int32_t key_stride; /* distance in doubles between key[i] and key[i+1] */
} hd_queue;

/* Allocates a queue for cap bodies whose keys are key[i * stride]; NULL on failure. */
hd_queue *hd_queue_alloc(int32_t cap, const double *key, int32_t stride);
/* Frees the queue (NULL allowed). */
void hd_queue_free(hd_queue *q);
/* Builds the heap from scratch holding bodies 0..n-1: O(n). */
void hd_queue_build(hd_queue *q, int32_t n);
/* Restores the heap after body i's key changed (up or down). */
void hd_queue_update(hd_queue *q, int32_t i);
/* The body with the earliest event (the heap must not be empty). */
static inline int32_t hd_queue_top(const hd_queue *q) {
  return q->heap[0];
}
/* Points the keys at a new array (after the body array moved). */
void hd_queue_rekey(hd_queue *q, const double *key);

#endif
