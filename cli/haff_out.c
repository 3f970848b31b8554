/* haff_out: output streams that remember why a write failed (haff.h). */
#include "haff.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

/* A stream of ours: its file descriptor and the errno of its first failed write. */
typedef struct out_cookie {
  FILE *f;
  int fd;
  int err;
} out_cookie;

enum { MAX_STREAMS = 8 };
static out_cookie cookies[MAX_STREAMS];

static ssize_t cookie_write(void *c, const char *buf, size_t n) {
  out_cookie *k = c;
  size_t done = 0;
  while (done < n) {
    ssize_t w = write(k->fd, buf + done, n - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      if (!k->err) k->err = w < 0 ? errno : EIO;
      return done ? (ssize_t)done : -1;
    }
    done += (size_t)w;
  }
  return (ssize_t)n;
}

static int cookie_close(void *c) {
  out_cookie *k = c;
  int rc = k->fd > 2 ? close(k->fd) : 0;
  if (rc && !k->err) k->err = errno;
  k->f = NULL; /* the slot is free; k->err stays readable until it is reused */
  return rc;
}

/* A stream writing to fd through a free slot, NULL when there is none (the caller falls back). */
static FILE *wrap(int fd, int line_buffered) {
  for (int s = 0; s < MAX_STREAMS; s++) {
    if (cookies[s].f) continue;
    cookies[s] = (out_cookie){NULL, fd, 0};
    cookie_io_functions_t io = {.write = cookie_write, .close = cookie_close};
    FILE *f = fopencookie(&cookies[s], "w", io);
    if (!f) return NULL;
    setvbuf(f, NULL, line_buffered ? _IOLBF : _IOFBF, BUFSIZ);
    cookies[s].f = f;
    return f;
  }
  return NULL;
}

void haff_stdout_wrap(void) {
  FILE *f = wrap(STDOUT_FILENO, isatty(STDOUT_FILENO));
  if (f) stdout = f;
}

FILE *haff_fopen_out(const char *path) {
  int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) return NULL;
  FILE *f = wrap(fd, 0);
  if (!f) {
    close(fd);
    return fopen(path, "w");
  }
  return f;
}

int haff_close_out(FILE *f, const char *cmd, const char *name) {
  int bad = ferror(f) != 0;
  errno = 0;
  int e = 0, err = 0;
  for (int s = 0; s < MAX_STREAMS; s++)
    if (cookies[s].f == f) e = s + 1;
  if (f == stdout) {
    bad |= fflush(f) != 0;
  } else {
    bad |= fclose(f) != 0;
  }
  err = errno;
  if (e && cookies[e - 1].err) err = cookies[e - 1].err;
  if (!bad) return 0;
  fprintf(stderr, "haff%s%s: %s: write error: %s\n", cmd ? " " : "", cmd ? cmd : "",
          name ? name : "stdout", err ? strerror(err) : "the reason was not reported");
  return 1;
}
