/* Tests of db/hd_lock.c, the record locks of the run, sweep and merge locks, against its contract
 * (db/hd_lock.h): a byte another process holds is refused at once (never waited for), the holder
 * is named, and a lock goes when its process lets go of it, ends (exit or kill -9) or closes any
 * descriptor of the file.  Record locks never conflict within one process, so every "other
 * process" here is a child of fork() that takes its orders over a pipe. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "hd_lock.h"

static char dir[64], path[128];

static int setup(void **state) {
  (void)state;
  umask(022); /* the mode test below expects hd_lock_open's 0644 unmasked by a stricter umask */
  snprintf(dir, sizeof dir, "/tmp/haff-lock-XXXXXX");
  if (!mkdtemp(dir)) return -1;
  snprintf(path, sizeof path, "%s/x.lock", dir);
  return 0;
}

static int teardown(void **state) {
  (void)state;
  unlink(path);
  rmdir(dir);
  return 0;
}

/* A child process that holds bytes [start, start + len) of path and obeys one-letter orders:
 * 'r' release them, 'c' open the file again and close that second descriptor, 'x' exit; it
 * answers every order (and the lock taken) with one byte 'k'. */
typedef struct {
  pid_t pid;
  int order, answer; /* pipe ends: the parent writes orders, reads answers */
} holder;

static void child_loop(int in, int out, off_t start, off_t len) {
  int fd = hd_lock_open(path, 1);
  if (fd < 0 || hd_lock_acquire(fd, start, len) != 0) _exit(3);
  char c = 'k';
  if (write(out, &c, 1) != 1) _exit(4);
  while (read(in, &c, 1) == 1) {
    if (c == 'r' && hd_lock_release(fd, start, len) != 0) _exit(5);
    if (c == 'c') {
      int again = hd_lock_open(path, 0);
      if (again < 0) _exit(6);
      close(again);
    }
    if (c == 'x') _exit(0);
    c = 'k';
    if (write(out, &c, 1) != 1) _exit(4);
  }
  _exit(0);
}

static holder hold(off_t start, off_t len) {
  int to[2], from[2];
  assert_int_equal(pipe(to), 0);
  assert_int_equal(pipe(from), 0);
  fflush(NULL);
  holder h;
  h.pid = fork();
  assert_true(h.pid >= 0);
  if (h.pid == 0) {
    close(to[1]);
    close(from[0]);
    child_loop(to[0], from[1], start, len);
  }
  close(to[0]);
  close(from[1]);
  h.order = to[1];
  h.answer = from[0];
  char c = 0;
  assert_int_equal(read(h.answer, &c, 1), 1); /* the lock is held */
  return h;
}

static void order(holder *h, char c) {
  assert_int_equal(write(h->order, &c, 1), 1);
  char a = 0;
  assert_int_equal(read(h->answer, &a, 1), 1);
  assert_int_equal(a, 'k');
}

/* Ends the child: 'x' or kill -9; waits for it and checks how it ended. */
static void end(holder *h, int kill9) {
  int st = 0;
  if (kill9)
    assert_int_equal(kill(h->pid, SIGKILL), 0);
  else
    assert_int_equal(write(h->order, "x", 1), 1);
  assert_int_equal(waitpid(h->pid, &st, 0), h->pid);
  if (kill9)
    assert_true(WIFSIGNALED(st) && WTERMSIG(st) == SIGKILL);
  else
    assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 0);
  close(h->order);
  close(h->answer);
}

/* Whether this process is refused bytes [start, start + len) at once (checked to take less than
 * 2 s: a lock that waited would wait for the child, which waits for the next order). */
static int refused(int fd, off_t start, off_t len) {
  time_t t0 = time(NULL);
  int rc = hd_lock_acquire(fd, start, len);
  int e = errno;
  assert_true(time(NULL) - t0 < 2);
  if (rc == 0) {
    hd_lock_release(fd, start, len);
    return 0;
  }
  assert_true(e == EACCES || e == EAGAIN);
  return 1;
}

static void open_modes(void **state) {
  (void)state;
  errno = 0;
  assert_int_equal(hd_lock_open(path, 0), -1); /* read-only: never creates it */
  assert_int_equal(errno, ENOENT);
  int fd = hd_lock_open(path, 1);
  assert_true(fd >= 0);
  struct stat sb;
  assert_int_equal(stat(path, &sb), 0);
  assert_int_equal(sb.st_mode & 0777, 0644);
  int ro = hd_lock_open(path, 0);
  assert_true(ro >= 0);
  assert_int_equal(hd_lock_acquire(ro, 0, 1), -1); /* a write lock needs a writable descriptor */
  assert_int_equal(errno, EBADF);
  close(ro);
  close(fd);
}

/* The second process is refused the bytes the first holds (not waited for), gets the others,
 * and is told who holds them: the run lock's and the sweep's "held by another process". */
static void second_process_refused(void **state) {
  (void)state;
  holder h = hold(3, 1);
  int fd = hd_lock_open(path, 1);
  assert_true(fd >= 0);
  assert_true(refused(fd, 3, 1));
  assert_true(refused(fd, 0, 0)); /* the whole file: byte 3 is in it */
  assert_int_equal(hd_lock_acquire(fd, 4, 1), 0);
  assert_int_equal(hd_lock_acquire(fd, 2, 1), 0);
  assert_int_equal(hd_lock_acquire(fd, 4, 1), 0); /* a process's own lock: taken again */
  hd_lock_who who;
  assert_int_equal(hd_lock_holder(fd, 3, 1, 1, &who), 0);
  assert_int_equal(who.pid, (long)h.pid);
  assert_int_equal(who.start, 3);
  assert_int_equal(who.len, 1);
  assert_int_equal(hd_lock_holder(fd, 0, 0, 0, &who), 0); /* a read lock anywhere: conflicts */
  assert_int_equal(who.pid, (long)h.pid);
  assert_int_equal(hd_lock_holder(fd, 4, 1, 1, &who), 0); /* our own byte: no other holder */
  assert_int_equal(who.pid, 0);
  end(&h, 0);
  close(fd);
}

/* A child holds byte at; this process is refused it until the child obeys order (hold's
 * letters), then takes it and sees no other holder. */
static void released_by_order(off_t at, char what) {
  holder h = hold(at, 1);
  int fd = hd_lock_open(path, 1);
  assert_true(refused(fd, at, 1));
  order(&h, what);
  assert_false(refused(fd, at, 1));
  hd_lock_who who;
  assert_int_equal(hd_lock_holder(fd, at, 1, 1, &who), 0);
  assert_int_equal(who.pid, 0);
  end(&h, 0);
  close(fd);
}

/* The holder lets go (hd_lock_release): the byte is free for the next process. */
static void released_by_release(void **state) {
  (void)state;
  released_by_order(1, 'r');
}

/* The holder ends, by exit and by kill -9: its lock goes with it (never stale). */
static void released_on_exit(void **state) {
  (void)state;
  int fd = hd_lock_open(path, 1);
  for (int kill9 = 0; kill9 <= 1; kill9++) {
    holder h = hold(0, 0); /* the whole file, as run_unlock takes it */
    assert_true(refused(fd, 7, 1));
    end(&h, kill9);
    assert_false(refused(fd, 7, 1));
    hd_lock_who who;
    assert_int_equal(hd_lock_holder(fd, 0, 0, 1, &who), 0);
    assert_int_equal(who.pid, 0);
  }
  close(fd);
}

/* The holder closes another descriptor of the file: all its locks in the file go (why the sweep
 * keeps its one descriptor open). */
static void released_on_close(void **state) {
  (void)state;
  released_by_order(2, 'c');
}

/* hd_merge_lock_held's question: a read lock asked about is refused only by a write lock, and a
 * query never takes a lock. */
static void holder_never_locks(void **state) {
  (void)state;
  int fd = hd_lock_open(path, 1);
  hd_lock_who who;
  assert_int_equal(hd_lock_holder(fd, 5, 1, 0, &who), 0);
  assert_int_equal(who.pid, 0);
  holder h = hold(5, 1); /* the child takes byte 5: the query above took nothing */
  assert_int_equal(hd_lock_holder(fd, 5, 1, 0, &who), 0);
  assert_int_equal(who.pid, (long)h.pid);
  assert_int_equal(hd_lock_holder(fd, 6, 1, 0, &who), 0);
  assert_int_equal(who.pid, 0);
  end(&h, 0);
  assert_int_equal(hd_lock_holder(-1, 6, 1, 0, &who), -1); /* the kernel cannot answer */
  assert_int_equal(errno, EBADF);
  assert_int_equal(who.pid, 0);
  close(fd);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup_teardown(open_modes, setup, teardown),
      cmocka_unit_test_setup_teardown(second_process_refused, setup, teardown),
      cmocka_unit_test_setup_teardown(released_by_release, setup, teardown),
      cmocka_unit_test_setup_teardown(released_on_exit, setup, teardown),
      cmocka_unit_test_setup_teardown(released_on_close, setup, teardown),
      cmocka_unit_test_setup_teardown(holder_never_locks, setup, teardown),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
