/* hd_error: status codes and error messages shared by every haff module.
 * Library functions never exit(): they return an HD_* status and, where they can fail on
 * input or resources, fill an hd_error with one line a user can act on (file, line, key, why). */
#ifndef HD_ERROR_H
#define HD_ERROR_H

#include <stddef.h>

/* Status codes returned by library functions.  0 is success. */
enum hd_status {
  HD_OK = 0,        /* success */
  HD_EINPUT = 1,    /* bad user input: scene, CSV, command-line value (CLI exit 2) */
  HD_EIO = 2,       /* file or database failure: disk full, read-only, corrupt (CLI exit 1) */
  HD_ENOMEM = 3,    /* allocation failed (CLI exit 1) */
  HD_ECOLLAPSE = 4, /* the run ended in inelastic collapse (CLI exit 1) */
  HD_EINTR = 5,     /* the run was interrupted by a signal (CLI exit 1) */
  HD_EPHYS = 6      /* a physics invariant failed in verification mode (CLI exit 1) */
};

/* Statuses of a simulation step that are not errors (hd_sim_next, hd_rods_next, the models of
 * the runner): the next event is after the stop time; no event is left; many events passed
 * without a collision (call again).  Here, below every simulation, so that the 2D engine and
 * the rod ring share them without including each other. */
enum { HD_SIM_STOPTIME = 100, HD_SIM_IDLE = 101, HD_SIM_BUSY = 102 };

/* A one-line error message.  msg is "" when no error has been set. */
typedef struct hd_error {
  int code;       /* the hd_status of the error, HD_OK when none */
  char msg[1024]; /* human-readable, no trailing newline */
} hd_error;

/* Copies the NUL-terminated in to out (n bytes, NUL included), with every byte that is not a
 * printable ASCII or printable UTF-8 character (controls, DEL, C1 controls, invalid UTF-8)
 * written as \n, \t, \r or \xHH, so that a message stays one line and cannot drive the
 * terminal.  Idempotent (a backslash is kept as it is); cut at a whole character. */
void hd_text_escape(const char *in, char *out, size_t n);

/* Sets err (if not NULL) to code and a printf-formatted message, escaped by hd_text_escape
 * (text quoted from a file or argument stays on one line); returns code, so that
 * `return hd_error_set(err, HD_EINPUT, "...")` reads naturally. */
int hd_error_set(hd_error *err, int code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

struct option;
/* The argument getopt_long (opterr = 0) just refused, from its state (optind, optopt): "-o"
 * for a bad short option, also inside a cluster ("-qo", where argv[optind - 1] is still the
 * argument before it), else the element itself ("--bogus", "--run" without its value).
 * opts: the long options given to getopt_long; buf: room for "-c".  For messages only. */
const char *hd_opt_culprit(char *const *argv, const struct option *opts, char *buf, size_t n);

/* Clears err to HD_OK and an empty message. */
void hd_error_clear(hd_error *err);

/* The process exit code for a status: 0 for HD_OK, 2 for HD_EINPUT, 1 otherwise. */
int hd_exit_code(int status);

#endif
