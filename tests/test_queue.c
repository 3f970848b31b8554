/* The calendar event queue against a brute-force minimum: random keys, random updates (also
 * INFINITY and far-future keys that go to the overflow), the event-driven pattern "pop the
 * minimum, give it a later time", and a rebuild in the middle; the top must always be the
 * (time, index) minimum.  Fixed seed; every comparison is exact. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include "hd_queue.h"
#include "test_util.h"

static int32_t brute_min(const double *t, int32_t n) {
  int32_t b = 0;
  for (int32_t i = 1; i < n; i++)
    if (t[i] < t[b]) b = i;
  return b;
}

static void against_brute_force(void **state) {
  (void)state;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 99);
  int32_t sizes[3] = {1, 7, 3000};
  for (int z = 0; z < 3; z++) {
    int32_t n = sizes[z];
    double *t = malloc(sizeof(double) * (size_t)n);
    hd_queue *q = hd_queue_alloc(n);
    assert_non_null(q);
    for (int32_t i = 0; i < n; i++) t[i] = gsl_ran_exponential(r, 1.0);
    hd_queue_build(q, n, t, 1);
    double now = 0.0;
    long steps = test_size(200000, 10);
    for (long k = 0; k < steps; k++) {
      int32_t top = hd_queue_top(q), want = brute_min(t, n);
      if (t[want] == INFINITY) { /* only never-entries left: any of them may come up */
        assert_true(t[top] == INFINITY);
        for (int32_t i = 0; i < n; i++)
          t[i] = now + gsl_rng_uniform(r), hd_queue_update(q, i, t[i]);
        continue;
      }
      assert_int_equal(top, want);
      now = t[top];
      /* the popped body gets a later time: mostly near, sometimes far (overflow), sometimes
       * never; a few other bodies are moved too (their partners' collisions) */
      double u = gsl_rng_uniform(r);
      t[top] = u < 0.02   ? INFINITY
               : u < 0.05 ? now + 1e3 * gsl_rng_uniform(r)
               : u < 0.06 ? now /* a tie with the current time */
                          : now + gsl_ran_exponential(r, 1.0);
      hd_queue_update(q, top, t[top]);
      if (n > 1 && gsl_rng_uniform(r) < 0.3) {
        int32_t o = (int32_t)gsl_rng_uniform_int(r, (unsigned long)n);
        t[o] = now + gsl_ran_exponential(r, 0.5);
        hd_queue_update(q, o, t[o]);
      }
      if (k == steps / 2) hd_queue_build(q, n, t, 1); /* rebuild (as at a rebase) */
    }
    hd_queue_free(q);
    free(t);
  }
  gsl_rng_free(r);
}

/* Equal times come out by index. */
static void ties_by_index(void **state) {
  (void)state;
  double t[5] = {2.0, 1.0, 1.0, INFINITY, 1.0};
  hd_queue *q = hd_queue_alloc(5);
  hd_queue_build(q, 5, t, 1);
  int32_t want[4] = {1, 2, 4, 0};
  for (int k = 0; k < 4; k++) {
    int32_t i = hd_queue_top(q);
    assert_int_equal(i, want[k]);
    hd_queue_update(q, i, INFINITY);
  }
  assert_int_equal(hd_queue_top(q) >= 0, 1);
  hd_queue_free(q);
}

/* Many updates between two events (each leaves a stale entry behind, here far ahead, where no
 * event reaches it): the pool of entries fills up (3 n + 64 of them) and the queue rebuilds
 * itself from the keys, several times; the top stays the brute-force minimum throughout.
 * Also updates back to the very same time (a duplicate entry, which stands for the same
 * event). */
static void many_updates_between_events(void **state) {
  (void)state;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 7);
  enum { n = 10 };
  double t[n];
  hd_queue *q = hd_queue_alloc(n);
  assert_non_null(q);
  for (int32_t i = 0; i < n; i++) t[i] = gsl_rng_uniform(r);
  hd_queue_build(q, n, t, 1);
  double now = 0.0;
  for (int k = 0; k < 2000; k++) {
    int32_t top = hd_queue_top(q);
    assert_int_equal(top, brute_min(t, n));
    now = t[top];
    for (int u = 0; u < 50; u++) { /* 50 updates of others per event: 1000 stale entries */
      int32_t o = (int32_t)gsl_rng_uniform_int(r, n);
      if (o == top) continue;
      double v = gsl_rng_uniform(r);
      t[o] = v < 0.1 ? t[o] : now + (v < 0.5 ? 1e6 : 1.0) * gsl_rng_uniform(r);
      hd_queue_update(q, o, t[o]);
    }
    t[top] = now + gsl_rng_uniform(r);
    hd_queue_update(q, top, t[top]);
  }
  hd_queue_free(q);
  gsl_rng_free(r);
}

/* A dense cluster (a rod ring's dense phase): 50 of 2000 bodies have their events 1e-4 apart,
 * the others ~100 ahead, so the width from the keys' spread puts the whole cluster in the
 * current bucket.  The queue must narrow its buckets (wfac < 1; the heap then holds a few
 * entries, not the cluster), keep the brute-force order throughout (the order never depends
 * on the width), and widen them again once the cluster has dissolved (events at the spread of
 * the others).  Fixed seed; comparisons exact. */
static void crowded_cluster_narrows(void **state) {
  (void)state;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 5);
  enum { n = 2000, nc = 50 };
  double *t = malloc(sizeof(double) * n);
  hd_queue *q = hd_queue_alloc(n);
  assert_non_null(q);
  for (int32_t i = 0; i < n; i++)
    t[i] = i < nc ? 1e-4 * gsl_rng_uniform(r) : 100 * gsl_rng_uniform(r);
  hd_queue_build(q, n, t, 1);
  double now = 0.0;
  int32_t hmax = 0;
  for (long k = 0; k < 60000; k++) {
    int32_t top = hd_queue_top(q);
    assert_int_equal(top, brute_min(t, n));
    now = t[top];
    if (k > 20000 && q->hn > hmax) hmax = q->hn;
    /* the cluster's bodies collide again soon while k < 40000, then like the others */
    t[top] = now + (top < nc && k < 40000 ? 1e-4 : 100) * gsl_rng_uniform(r);
    hd_queue_update(q, top, t[top]);
    if (k == 30000) assert_true(q->wfac < 0.1);
  }
  assert_true(hmax < 32); /* the current bucket holds a few entries, not the 50 of the cluster */
  assert_true(q->wfac > 0.5); /* widened again (by 4 at a time, up to 1) */
  hd_queue_free(q);
  free(t);
  gsl_rng_free(r);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(against_brute_force), cmocka_unit_test(ties_by_index),
      cmocka_unit_test(many_updates_between_events), cmocka_unit_test(crowded_cluster_narrows)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
