/* hd_lock: POSIX record locks on bytes of a lock file (see hd_lock.h). */
#include "hd_lock.h"

#include <fcntl.h>
#include <string.h>

int hd_lock_open(const char *path, int create) {
  return create ? open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0644) : open(path, O_RDONLY | O_CLOEXEC);
}

/* One F_SETLK or F_GETLK on the len bytes from start with lock type type. */
static int lock_call(int fd, int cmd, int type, off_t start, off_t len, struct flock *fl) {
  memset(fl, 0, sizeof *fl);
  fl->l_type = (short)type;
  fl->l_whence = SEEK_SET;
  fl->l_start = start;
  fl->l_len = len;
  return fcntl(fd, cmd, fl);
}

int hd_lock_acquire(int fd, off_t start, off_t len) {
  struct flock fl;
  return lock_call(fd, F_SETLK, F_WRLCK, start, len, &fl);
}

int hd_lock_release(int fd, off_t start, off_t len) {
  struct flock fl;
  return lock_call(fd, F_SETLK, F_UNLCK, start, len, &fl);
}

int hd_lock_holder(int fd, off_t start, off_t len, int write, hd_lock_who *who) {
  struct flock fl;
  who->pid = 0;
  who->start = who->len = 0;
  if (lock_call(fd, F_GETLK, write ? F_WRLCK : F_RDLCK, start, len, &fl) != 0) return -1;
  if (fl.l_type == F_UNLCK) return 0;
  who->pid = fl.l_pid > 0 ? (long)fl.l_pid : -1;
  who->start = fl.l_start;
  who->len = fl.l_len;
  return 0;
}
