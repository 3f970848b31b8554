/* hd_stop: a request to stop what the process is doing, made from a signal handler (hd_run's
 * SIGINT and SIGTERM) and read by the long loops of a set-up (melting a dense lattice, seconds
 * for 10^5 bodies), which then return HD_EINTR; the event loop's own driver (hd_run) reads it
 * between events, and the contact searches (engine/body/hd_body.c, engine/sim/hd_predict.c)
 * every 65536 steps (HD_CA_POLL), cutting a search that a stiff body makes last minutes.  One
 * per process, like REBOUND's reb_sigint. */
#ifndef HD_STOP_H
#define HD_STOP_H

#include <signal.h>

/* Set to 1 to ask for a stop; cleared by whoever starts the work it stops (hd_run). */
extern volatile sig_atomic_t hd_stop_requested;

#endif
