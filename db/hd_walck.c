/* hd_walck: the write-ahead-log checkpointer thread (see hd_walck.h).
 * A checkpoint error (a full disk, say) is not reported: the log then simply grows, the
 * writer's own COMMIT reports any real write failure, and the last connection's close (or the
 * next run) checkpoints what is left, exactly as with SQLite's automatic checkpoints, whose
 * errors SQLite ignores too. */
#include "hd_walck.h"

#include "hd_db.h"

#include <pthread.h>
#include <signal.h>
#include <stdlib.h>

struct hd_walck {
  sqlite3 *w;       /* the writing connection (its hook wakes us) */
  sqlite3 *own;     /* our connection to the same file */
  pthread_t thread; /* the checkpointer */
  pthread_mutex_t mu;
  pthread_cond_t cv;
  int wake; /* a checkpoint is wanted (under mu) */
  int busy; /* the thread is checkpointing (under mu) */
  int quit; /* the thread must end (under mu) */
};

/* sqlite3_wal_hook callback, run by w's committing thread after each commit.  The log
 * restarts from its beginning only when the writer begins a transaction after a checkpoint
 * has copied every frame; the thread's checkpoints always lag the writer by a commit or more,
 * so past HD_WALCK_RESTART frames the writer waits for the thread and checkpoints the few
 * frames left itself (which bounds the log's size). */
static int on_commit(void *ctx, sqlite3 *db, const char *name, int frames) {
  hd_walck *c = ctx;
  if (frames < HD_WALCK_FRAMES) return SQLITE_OK;
  pthread_mutex_lock(&c->mu);
  if (frames < HD_WALCK_RESTART) {
    c->wake = 1;
    pthread_cond_broadcast(&c->cv);
    pthread_mutex_unlock(&c->mu);
    return SQLITE_OK;
  }
  while (c->busy) pthread_cond_wait(&c->cv, &c->mu);
  c->wake = 0;
  pthread_mutex_unlock(&c->mu);
  sqlite3_wal_checkpoint_v2(db, name, SQLITE_CHECKPOINT_PASSIVE, NULL, NULL);
  return SQLITE_OK;
}

static void *walck_main(void *arg) {
  hd_walck *c = arg;
  sigset_t all;
  sigfillset(&all);
  pthread_sigmask(SIG_BLOCK, &all, NULL); /* signals are for the simulation's thread */
  pthread_mutex_lock(&c->mu);
  for (;;) {
    while (!c->wake && !c->quit) pthread_cond_wait(&c->cv, &c->mu);
    if (c->quit) break;
    c->wake = 0;
    c->busy = 1;
    pthread_mutex_unlock(&c->mu);
    sqlite3_wal_checkpoint_v2(c->own, "main", SQLITE_CHECKPOINT_PASSIVE, NULL, NULL);
    pthread_mutex_lock(&c->mu);
    c->busy = 0;
    pthread_cond_broadcast(&c->cv);
  }
  pthread_mutex_unlock(&c->mu);
  return NULL;
}

int hd_walck_start(hd_walck **out, sqlite3 *w, const char *path, hd_error *err) {
  *out = NULL;
  hd_walck *c = calloc(1, sizeof *c);
  if (!c) return hd_error_set(err, HD_ENOMEM, "%s: out of memory for the log checkpointer", path);
  c->w = w;
  char plain[4200]; /* the file the writer opened, not ":memory:" nor a URI */
  const char *name = hd_db_plain_name(path, plain, sizeof plain);
  if (!name || sqlite3_open_v2(name, &c->own, SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX, NULL) !=
                   SQLITE_OK) {
    hd_error_set(err, HD_EIO, "%s: open for checkpoints: %s", path,
                 c->own ? sqlite3_errmsg(c->own) : "out of memory");
    sqlite3_close(c->own);
    free(c);
    return HD_EIO;
  }
  sqlite3_wal_autocheckpoint(c->own, 0); /* its close must not checkpoint either */
  /* a first read opens the file and finds it in WAL mode (until then a checkpoint of this
   * connection is a no-op) */
  if (sqlite3_exec(c->own, "SELECT count(*) FROM sqlite_schema", NULL, NULL, NULL) != SQLITE_OK) {
    hd_error_set(err, HD_EIO, "%s: open for checkpoints: %s", path, sqlite3_errmsg(c->own));
    sqlite3_close(c->own);
    free(c);
    return HD_EIO;
  }
  if (pthread_mutex_init(&c->mu, NULL) || pthread_cond_init(&c->cv, NULL) ||
      pthread_create(&c->thread, NULL, walck_main, c)) {
    sqlite3_close(c->own);
    free(c);
    return hd_error_set(err, HD_ENOMEM, "%s: cannot start the log checkpointer", path);
  }
  sqlite3_wal_hook(w, on_commit, c); /* replaces w's automatic checkpoints */
  *out = c;
  return HD_OK;
}

void hd_walck_stop(hd_walck *c) {
  if (!c) return;
  pthread_mutex_lock(&c->mu);
  c->quit = 1;
  pthread_cond_broadcast(&c->cv);
  pthread_mutex_unlock(&c->mu);
  pthread_join(c->thread, NULL);
  sqlite3_close(c->own);
  sqlite3_wal_autocheckpoint(c->w, 1000); /* SQLite's default, and its own hook, back */
  pthread_mutex_destroy(&c->mu);
  pthread_cond_destroy(&c->cv);
  free(c);
}
