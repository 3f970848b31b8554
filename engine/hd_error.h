/* hd_error: status codes and error messages shared by every haff module.
 * Library functions never exit(): they return an HD_* status and, where they can fail on
 * input or resources, fill an hd_error with one line a user can act on (file, line, key, why). */
#ifndef HD_ERROR_H
#define HD_ERROR_H

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

/* A one-line error message.  msg is "" when no error has been set. */
typedef struct hd_error {
  int code;       /* the hd_status of the error, HD_OK when none */
  char msg[1024]; /* human-readable, no trailing newline */
} hd_error;

/* Sets err (if not NULL) to code and a printf-formatted message; returns code, so that
 * `return hd_error_set(err, HD_EINPUT, "...")` reads naturally. */
int hd_error_set(hd_error *err, int code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Clears err to HD_OK and an empty message. */
void hd_error_clear(hd_error *err);

/* The process exit code for a status: 0 for HD_OK, 2 for HD_EINPUT, 1 otherwise. */
int hd_exit_code(int status);

#endif
