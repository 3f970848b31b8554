/* Callgrind markers around a benchmark's timed loop: under `valgrind --tool=callgrind
 * --instr-atstart=no` only the timed loop is instrumented (the set-up and warm-up run at
 * near-native speed), so instruction counts per collision are exact and repeatable on a loaded
 * machine without hardware counters.  No-ops when valgrind's header is absent or the program runs
 * natively. */
#ifndef BENCH_CALLGRIND_H
#define BENCH_CALLGRIND_H
#if defined(__has_include)
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define BENCH_CG_START() CALLGRIND_START_INSTRUMENTATION
#define BENCH_CG_STOP() CALLGRIND_STOP_INSTRUMENTATION
#endif
#endif
#ifndef BENCH_CG_START
#define BENCH_CG_START() ((void)0)
#define BENCH_CG_STOP() ((void)0)
#endif
#endif
