/* What the two benchmark programs share: a monotonic clock, the thread's CPU clock and checked
 * command-line numbers. */
#ifndef BENCH_UTIL_H
#define BENCH_UTIL_H

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

/* Seconds on the monotonic clock (for differences only). */
static inline double bench_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* CPU seconds of the calling thread (for differences only): what a loaded machine's other
 * jobs take from the wall clock does not count. */
static inline double bench_cpu(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Parses argument `what` = s as a whole integer in [lo, hi] into *v; 0, or prints why to stderr
 * (prefixed by prog) and returns -1. */
static inline int bench_arg_long(const char *prog, const char *what, const char *s, long lo,
                                 long hi, long *v) {
  char *end;
  errno = 0;
  long x = strtol(s, &end, 10);
  if (end == s || *end || errno || x < lo || x > hi) {
    fprintf(stderr, "%s: %s = '%s': want an integer in [%ld, %ld]\n", prog, what, s, lo, hi);
    return -1;
  }
  *v = x;
  return 0;
}

/* Parses argument `what` = s as a whole number in (lo, hi] into *v; 0, or prints why and -1. */
static inline int bench_arg_double(const char *prog, const char *what, const char *s, double lo,
                                   double hi, double *v) {
  char *end;
  errno = 0;
  double x = strtod(s, &end);
  if (end == s || *end || errno || !(x > lo && x <= hi)) {
    fprintf(stderr, "%s: %s = '%s': want a number in (%g, %g]\n", prog, what, s, lo, hi);
    return -1;
  }
  *v = x;
  return 0;
}

#endif
