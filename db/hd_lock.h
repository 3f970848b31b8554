/* hd_lock: POSIX record locks (fcntl F_SETLK / F_GETLK) on bytes of a lock file, the one
 * primitive of haff's three lock users: a run's lock (run/hd_run.c: byte `run` of DB.lock),
 * a study's and its points' locks (cli/cmd_sweep.c: bytes 0 and 1 + k of DIR/sweep.lock) and
 * haff merge's look at whether a run still writes (db/hd_merge.c: hd_merge_lock_held).
 *
 * The rules every caller relies on (POSIX record locks, as Linux keeps them):
 * - a lock is the process's: the kernel drops it when the process ends, however it ends
 *   (kill -9 too), so a lock is never stale;
 * - hd_lock_acquire never waits: a byte another process holds is refused at once;
 * - locks of one process never conflict with each other (taking a byte it holds again
 *   succeeds), so only another process is ever refused;
 * - any close() of any descriptor of the file in the process drops all of the process's locks
 *   in that file: the caller keeps one descriptor open for as long as it holds locks;
 * - a child of fork() holds none of its parent's locks. */
#ifndef HD_LOCK_H
#define HD_LOCK_H

#include <sys/types.h>

/* Who holds a lock that conflicts with the one asked about (hd_lock_holder). */
typedef struct {
  long pid;    /* the holder's process id; 0 when no other process holds a conflicting lock;
                  -1 when one does but the kernel gives no pid (e.g. a holder on another host
                  of a network file system) */
  off_t start; /* the first byte of the holder's lock (when pid != 0) */
  off_t len;   /* its length in bytes; 0: from start to any end of the file (when pid != 0) */
} hd_lock_who;

/* Opens the lock file path, close-on-exec: read and write, created (mode 0644) when missing,
 * when create is non-zero; else read-only (enough for hd_lock_holder, not for hd_lock_acquire),
 * and a missing file is an error (ENOENT).  Returns the descriptor, or -1 with errno set. */
int hd_lock_open(const char *path, int create);

/* Takes a write lock on the len bytes of fd from start (len 0: from start to any end of the
 * file; start, len >= 0) without waiting; fd must be open for writing.  Returns 0 when this
 * process holds them now; -1 with errno EACCES or EAGAIN when another process holds a lock on
 * one of them (refused, not waited for: hd_lock_holder names it); -1 with another errno when
 * the call fails (EBADF, ENOLCK, ...). */
int hd_lock_acquire(int fd, off_t start, off_t len);

/* Lets go of this process's locks on the len bytes of fd from start (len 0: to any end); bytes
 * it does not hold are left as they are.  0, or -1 with errno (a bad descriptor). */
int hd_lock_release(int fd, off_t start, off_t len);

/* Asks which other process holds a lock on the len bytes of fd from start (len 0: to any end)
 * that conflicts with a write lock there (write non-zero: any lock conflicts) or a read lock
 * (write 0: only a write lock conflicts).  Never takes a lock; fd may be read-only.  Fills
 * *who (who->pid 0: none does) and returns 0; -1 with errno when the kernel cannot answer,
 * *who then says none. */
int hd_lock_holder(int fd, off_t start, off_t len, int write, hd_lock_who *who);

#endif
