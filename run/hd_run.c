#include "hd_run.h"

#include <assert.h>
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "hd_build.h"
#include "hd_db.h"
#include "hd_lock.h"
#include "hd_model.h"
#include "hd_sim.h"
#include "hd_stop.h"

static void on_signal(int sig) {
  (void)sig;
  hd_stop_requested = 1;
}

/* Runner state that a checkpoint carries besides the engine's. */
typedef struct run_state {
  int64_t seq;         /* collisions so far (pair + wall): the seq of the last one */
  int64_t next_sample; /* index k of the next sample, taken when cpd >= k * samples_every */
  int32_t next_vel;    /* index of the next velocities_at snapshot */
  int32_t next_frame;  /* index k of the next frame ([log] frames_every*); was padding (0) in
                          the checkpoints of older versions, whose runs have no frames */
  double wall_seconds; /* wall-clock seconds spent before this process */
} run_state;

/* Everything one driving of a run needs. */
typedef struct runner {
  const hd_scene *sc;
  const hd_run_opts *o;
  const hd_model_ops *ops; /* the model that runs the scene */
  void *s;                 /* its state */
  hd_db *db;
  int64_t run;
  run_state st;
  double t0_wall;        /* monotonic clock at start of this process's driving */
  double last_ckpt_wall; /* monotonic time of the last checkpoint */
  double last_tick_wall; /* monotonic time of the last progress line */
  int64_t last_tick_events;
  int progress;             /* print a progress line: 1 redrawn on a terminal, 2 one per line */
  double progress_every;    /* seconds between progress lines */
  char note[200];           /* "" or what a run that ends well left undone (no event left before
                             its stop condition, velocities_at times not reached) */
  int lock_fd;              /* the run's lock (run_lock), -1 when not held */
  double last_commit_wall;  /* monotonic time of the last commit forced by the clock */
  hd_state_rec *frame_recs; /* a frame's bodies (take_frame), NULL until the first frame */
  unsigned char *frame_buf; /* the frame packed as db/schema.sql says */
  double frame_bytes;       /* bytes of frames stored for the run (hd_scene_frame_bytes each) */
  int frames_off;           /* frames_max_mb reached: no more frames */
} runner;

/* The path of run r's lock file, DB.lock. */
static void lock_path(const runner *r, char *path, size_t size) {
  snprintf(path, size, "%s.lock", r->o->db_path);
}

/* Whether fd is still the file at path (run_unlock may have removed it). */
static int same_file(int fd, const char *path) {
  struct stat a, b;
  return fstat(fd, &a) == 0 && stat(path, &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

/* Takes the lock that says "this process drives run r->run": a write lock on byte r->run of
 * the file DB.lock, which the kernel drops when the process ends, however it ends (kill -9
 * too).  A resume of a run whose lock another process holds is refused: it used to take over a
 * run still going and write every row twice.  The last process to let go of the file removes it
 * (run_unlock), so a lock is only taken on the file that is at the path once it is held;
 * otherwise it is taken again on the new one. */
static int run_lock(runner *r, hd_error *err) {
  char path[4200];
  lock_path(r, path, sizeof path);
  for (int attempt = 0;; attempt++) {
    int fd = hd_lock_open(path, 1);
    if (fd < 0)
      return hd_error_set(err, HD_EIO, "%s: cannot open the run lock: %s", path, strerror(errno));
    if (hd_lock_acquire(fd, (off_t)r->run, 1) == 0) {
      if (same_file(fd, path)) {
        r->lock_fd = fd;
        return HD_OK;
      }
      close(fd); /* removed by the last holder meanwhile: the lock is on a file nobody sees */
      if (attempt < 1000) continue;
      return hd_error_set(err, HD_EIO, "%s: the run lock file keeps being replaced", path);
    }
    int e = errno;
    /* the whole file locked (start = len = 0; a run's lock is byte id >= 1): its last holder
     * removing it, for a moment; or no lock left by the time we look (none: that holder has
     * let go); then try again */
    hd_lock_who who;
    int removing = (e == EACCES || e == EAGAIN) &&
                   hd_lock_holder(fd, (off_t)r->run, 1, 1, &who) == 0 &&
                   (who.pid == 0 || (who.start == 0 && who.len == 0));
    close(fd);
    if (removing && attempt < 1000) {
      const struct timespec ms = {0, 1000000L};
      nanosleep(&ms, NULL);
      continue;
    }
    if (e == EACCES || e == EAGAIN)
      return hd_error_set(err, HD_EINPUT,
                          "run %lld of %s is being run by another process (wait for it to end, "
                          "or stop it, then resume; another run of the file: --run ID)",
                          (long long)r->run, r->o->db_path);
    return hd_error_set(err, HD_EIO, "%s: cannot lock run %lld: %s", path, (long long)r->run,
                        strerror(e));
  }
}

/* Lets go of the run's lock; removes DB.lock when no other process holds a lock in it (a
 * lock on the whole file, which fails if one does, is taken for the removal). */
static void run_unlock(runner *r) {
  if (r->lock_fd < 0) return;
  char path[4200];
  lock_path(r, path, sizeof path);
  /* start = len = 0: the whole file */
  if (hd_lock_acquire(r->lock_fd, 0, 0) == 0 && same_file(r->lock_fd, path)) unlink(path);
  close(r->lock_fd);
  r->lock_fd = -1;
}

static struct sigaction old_int, old_term;

/* SIGINT and SIGTERM set hd_stop_requested from the start of a run, set-up included (a signal
 * during the placement of many bodies used to kill the process with the run left 'running'). */
static void signals_on(void);
static void signals_off(void) {
  sigaction(SIGINT, &old_int, NULL);
  sigaction(SIGTERM, &old_term, NULL);
  hd_stop_requested = 0; /* handled: a set-up that the library's user starts next is not stopped */
}

static double now_wall(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double elapsed(const runner *r) {
  return r->st.wall_seconds + now_wall() - r->t0_wall;
}

/* Writes one states row per body at the current time under label. */
static int log_states(runner *r, const char *label, hd_error *err) {
  return r->ops->log_states(r->s, r->db, r->run, label, err);
}

static int log_sample(runner *r, hd_error *err) {
  hd_sample_row row;
  r->ops->sample(r->s, &row);
  int rc = hd_db_log_sample(r->db, r->run, &row, err);
  if (!rc && r->ops->log_species_sample) rc = r->ops->log_species_sample(r->s, r->db, r->run, err);
  return rc;
}

/* A checkpoint blob is the runner's state (run_state), the model's blob, then a trailer: the
 * magic "HAFFSUM1" and a 64-bit checksum of everything before it.  One flipped bit anywhere
 * (a damaged disk, a hand edit) is refused by resume as a damaged checkpoint; it used to crash
 * the engine, or finish "done" with wrong data.  A blob without the trailer was written before
 * it existed and is still read (the models check what they restore either way), unless its
 * model blob is of a format always stored with the trailer (hd_sim_checkpoint_needs_trailer:
 * HAFFCKP2), where a missing trailer is damage. */
#define HD_CKSUM_MAGIC 0x314d555346464148ULL /* "HAFFSUM1" */
typedef struct ckpt_trailer {
  uint64_t magic; /* HD_CKSUM_MAGIC */
  uint64_t sum;   /* ckpt_sum of the bytes before the trailer */
} ckpt_trailer;

/* The checksum of n bytes: each 8-byte word w goes in as h = (h ^ w) * K, a bijection of h for
 * a given w and of w for a given h, so any change inside one word always changes the result;
 * the final mixing spreads every bit over the whole sum. */
static uint64_t ckpt_sum(const unsigned char *p, size_t n) {
  const uint64_t K = 0x9e3779b97f4a7c15ULL; /* odd */
  uint64_t h = (uint64_t)n * K, w;
  size_t k = 0;
  for (; k + 8 <= n; k += 8) {
    memcpy(&w, p + k, 8);
    h = (h ^ w) * K;
  }
  if (k < n) {
    w = 0;
    memcpy(&w, p + k, n - k);
    h = (h ^ w) * K;
  }
  h ^= h >> 31;
  h *= 0xff51afd7ed558ccdULL;
  return h ^ (h >> 33);
}

static int checkpoint(runner *r, hd_error *err) {
  void *blob = NULL;
  size_t n = 0;
  r->st.wall_seconds = elapsed(r);
  r->t0_wall = now_wall();
  size_t hs = sizeof r->st;
  int rc = r->ops->checkpoint(r->s, &blob, &n, err);
  if (rc) return rc;
  ckpt_trailer tr = {HD_CKSUM_MAGIC, 0};
  unsigned char *all = malloc(hs + n + sizeof tr);
  if (!all) {
    free(blob);
    return hd_error_set(err, HD_ENOMEM, "out of memory for a checkpoint");
  }
  memcpy(all, &r->st, hs);
  memcpy(all + hs, blob, n);
  free(blob);
  tr.sum = ckpt_sum(all, hs + n);
  memcpy(all + hs + n, &tr, sizeof tr);
  rc = hd_db_checkpoint_save(r->db, r->run, r->st.seq, r->ops->time(r->s), all, hs + n + sizeof tr,
                             err);
  free(all);
  r->last_ckpt_wall = now_wall();
  return rc;
}

/* Stores a frame of every body at the current time (table frames), unless it would take the
 * run's frames past frames_max_mb: then frames stop, and runs.message says so. */
static int take_frame(runner *r, hd_error *err) {
  const hd_scene *sc = r->sc;
  long n = hd_scene_bodies(sc);
  size_t size = (size_t)n * HD_FRAME_BODY_BYTES;
  if (r->frame_bytes + hd_scene_frame_bytes(sc) > sc->frames_max_mb * 1e6) {
    r->frames_off = 1;
    if (!r->note[0])
      snprintf(r->note, sizeof r->note,
               "frames: frames_max_mb = %g reached at t = %.6g (cpd %.6g), later frames not taken",
               sc->frames_max_mb, r->ops->time(r->s), r->ops->cpd(r->s));
    return HD_OK;
  }
  if (!r->frame_buf) {
    r->frame_recs = malloc((size_t)n * sizeof *r->frame_recs);
    r->frame_buf = calloc(size ? size : 1, 1);
    if (!r->frame_recs || !r->frame_buf)
      return hd_error_set(err, HD_ENOMEM, "out of memory for a frame of %ld bodies", n);
  }
  int rc = r->ops->states(r->s, r->frame_recs, err);
  if (rc) return rc;
  for (long i = 0; i < n; i++) {
    const hd_state_rec *b = &r->frame_recs[i];
    assert(b->body >= 0 && b->body < n); /* the bodies are numbered 0 .. n-1 */
    double d[3] = {b->x, b->y, b->phi};
    float f[3] = {(float)b->vx, (float)b->vy, (float)b->omega};
    unsigned char *p = r->frame_buf + (size_t)b->body * HD_FRAME_BODY_BYTES;
    memcpy(p, d, sizeof d);
    memcpy(p + sizeof d, f, sizeof f);
  }
  rc = hd_db_log_frame(r->db, r->run, r->ops->time(r->s), r->ops->cpd(r->s), n, r->frame_buf, size,
                       err);
  if (!rc) r->frame_bytes += hd_scene_frame_bytes(sc);
  return rc;
}

/* Says at start what the frames will take (stderr), unless quiet. */
static void frames_estimate(const runner *r) {
  const hd_scene *sc = r->sc;
  double nf = hd_scene_frames_estimate(sc);
  if (nf == 0 || r->o->quiet) return;
  char every[64];
  if (sc->frames_every > 0)
    snprintf(every, sizeof every, "every %g cpd", sc->frames_every);
  else
    snprintf(every, sizeof every, "every %g in time", sc->frames_every_time);
  if (nf > 0)
    fprintf(stderr, "haff: frames %s: %s%.0f frames of %ld bodies, ~%.3g MB (frames_max_mb = %g)\n",
            every, sc->frames_every > 0 && sc->stop_time > 0 ? "at most " : "", nf,
            hd_scene_bodies(sc), nf * hd_scene_frame_bytes(sc) / 1e6, sc->frames_max_mb);
  else
    fprintf(stderr,
            "haff: frames %s: %.3g MB each; their count is not known before the run (no stop_cpd "
            "or stop_events): frames stop at frames_max_mb = %g\n",
            every, hd_scene_frame_bytes(sc) / 1e6, sc->frames_max_mb);
}

/* Fraction of the run done, from whichever stop condition is furthest along. */
static double fraction_done(const runner *r) {
  const hd_scene *sc = r->sc;
  double f = 0.0;
  if (sc->stop_time > 0) f = fmax(f, r->ops->time(r->s) / sc->stop_time);
  if (sc->stop_events > 0) f = fmax(f, (double)r->st.seq / sc->stop_events);
  if (sc->stop_cpd > 0) f = fmax(f, r->ops->cpd(r->s) / sc->stop_cpd);
  return fmin(f, 1.0);
}

static void tick(runner *r) {
  double w = now_wall();
  if (w - r->last_tick_wall < r->progress_every) return;
  int64_t ev = r->ops->events(r->s);
  double rate = (double)(ev - r->last_tick_events) / (w - r->last_tick_wall);
  double f = fraction_done(r), spent = elapsed(r);
  double eta = f > 0 ? spent * (1 - f) / f : NAN;
  if (r->progress == 2) /* a log: whole lines, with the run and the time spent */
    fprintf(stderr,
            "haff: %s run %lld: %lld events  %.3g ev/s  cpd %.6g  T %.4g  %.0f s  ETA %.0f s\n",
            r->o->db_path, (long long)r->run, (long long)ev, rate, r->ops->cpd(r->s),
            r->ops->temperature(r->s), spent, eta);
  else
    fprintf(stderr, "\r%12lld events  %9.3g ev/s  cpd %9.4g  T %9.3g  ETA %6.0f s   ",
            (long long)ev, rate, r->ops->cpd(r->s), r->ops->temperature(r->s), eta);
  r->last_tick_wall = w;
  r->last_tick_events = ev;
}

static int stop_reached(const runner *r) {
  const hd_scene *sc = r->sc;
  return (sc->stop_events > 0 && (double)r->st.seq >= sc->stop_events) ||
         (sc->stop_cpd > 0 && r->ops->cpd(r->s) >= sc->stop_cpd);
}

/* The velocity snapshot due when the snapshots' clock (cpd or time) reads now. */
static int snapshots(runner *r, double now, hd_error *err) {
  const hd_scene *sc = r->sc;
  if (r->st.next_vel < sc->n_velocities_at && now >= sc->velocities_at[r->st.next_vel]) {
    /* one snapshot, however many of the times this event passed: two at one event used to give
     * two sets of rows at the same t, which read (and export) as one frame of twice the bodies */
    while (r->st.next_vel < sc->n_velocities_at && now >= sc->velocities_at[r->st.next_vel])
      r->st.next_vel++;
    return log_states(r, "velocities", err);
  }
  return HD_OK;
}

/* Samples and velocity snapshots due at the current cpd (or time). */
static int observe(runner *r, hd_error *err) {
  const hd_scene *sc = r->sc;
  double cpd = r->ops->cpd(r->s);
  if (sc->samples_every > 0 && cpd >= (double)r->st.next_sample * sc->samples_every) {
    /* one sample per event, however many multiples of samples_every it passed: a tiny
     * samples_every (1e-12) wrote millions of identical rows per collision, filled the disk and
     * never came back to check for SIGINT */
    int rc = log_sample(r, err);
    if (rc) return rc;
    double k = floor(cpd / sc->samples_every) + 1.0;
    r->st.next_sample =
        k > (double)r->st.next_sample ? (int64_t)fmin(k, 9e18) : r->st.next_sample + 1;
  }
  /* the snapshots' clock: cpd, or the time (velocities_at_time; drive also stops at each) */
  int rc = snapshots(r, sc->velocities_in_time ? r->ops->time(r->s) : cpd, err);
  if (rc) return rc;
  if (sc->frames_every > 0 && !r->frames_off &&
      cpd >= (double)r->st.next_frame * sc->frames_every) {
    rc = take_frame(r, err); /* one frame per event, as for the samples */
    if (rc) return rc;
    double k = floor(cpd / sc->frames_every) + 1.0;
    r->st.next_frame =
        k > (double)r->st.next_frame ? (int32_t)fmin(k, (double)INT32_MAX) : r->st.next_frame + 1;
  }
  if (sc->frames_every_time > 0 && r->st.next_frame == 0) { /* frame 0 at t = 0; the others at
                                                               their exact times (drive) */
    rc = take_frame(r, err);
    if (rc) return rc;
    r->st.next_frame = 1;
  }
  return HD_OK;
}

/* The error of a run stopped by SIGINT or SIGTERM. */
static int interrupted(const runner *r, hd_error *err) {
  return hd_error_set(err, HD_EINTR, "interrupted at t = %.10g after %lld collisions",
                      r->ops->time(r->s), (long long)r->st.seq);
}

/* The loop: events until a stop condition, a signal, a collapse or an error. */
static int drive(runner *r, hd_error *err) {
  const hd_scene *sc = r->sc;
  double t_end = sc->stop_time > 0 ? sc->stop_time : INFINITY;
  int rc = HD_OK;
  while (rc == HD_OK && !stop_reached(r)) {
    hd_collision_row row;
    /* the engine stops at each frame's time (frames_every_time) and each snapshot's time
     * (velocities_at_time), whatever its round-off: the clock moves there, its free flight is
     * exact and no collision is changed, and the run goes on */
    double t_frame = sc->frames_every_time > 0 && !r->frames_off
                         ? (double)r->st.next_frame * sc->frames_every_time
                         : INFINITY;
    double t_snap = sc->velocities_in_time && r->st.next_vel < sc->n_velocities_at
                        ? sc->velocities_at[r->st.next_vel]
                        : INFINITY;
    double t_stop = fmin(t_end, fmin(t_frame, t_snap));
    rc = r->ops->next(r->s, t_stop, &row, err);
    if (rc == HD_SIM_STOPTIME && (t_stop == t_snap || t_stop == t_frame)) {
      rc = t_stop == t_snap ? snapshots(r, t_stop, err) : HD_OK;
      if (!rc && t_stop == t_frame) {
        rc = take_frame(r, err);
        r->st.next_frame++;
      }
      continue; /* at t_end, the next step stops at once */
    }
    if (rc == HD_SIM_IDLE && (sc->stop_events > 0 || sc->stop_cpd > 0))
      /* nothing will ever happen again: every body at rest, or cooled below the range of
       * doubles (a rod ring below its collapse size reaches t ~ 1e308) */
      snprintf(r->note, sizeof r->note,
               "no event left at t = %.6g after %lld collisions (cpd %.6g): nothing moves or "
               "collides any more, before the stop condition",
               r->ops->time(r->s), (long long)r->st.seq, r->ops->cpd(r->s));
    if (rc == HD_SIM_STOPTIME || rc == HD_SIM_IDLE) {
      rc = HD_OK;
      break;
    }
    if (rc == HD_SIM_BUSY) { /* many events, no collision: a chance to see a signal */
      rc = hd_stop_requested ? interrupted(r, err) : HD_OK;
      continue;
    }
    if (rc) break;
    row.seq = ++r->st.seq;
    if (sc->log_collisions == HD_LOG_ALL ||
        (sc->log_collisions == HD_LOG_EVERY && r->st.seq % sc->log_every == 0)) {
      rc = hd_db_log_collision(r->db, r->run, &row, err);
      if (rc) break;
    }
    rc = observe(r, err);
    if (rc) break;
    if (hd_stop_requested) {
      rc = interrupted(r, err);
      break;
    }
    if ((r->st.seq & 1023) == 0) {
      double w = now_wall();
      if (r->progress) tick(r);
      if (w - r->last_commit_wall >= 1.0) {
        /* a batch ends after 1e4 rows or 1 s: a sparsely logged run held the write lock for
         * its minutes-long batches, and a second run appending to the file timed out */
        r->last_commit_wall = w;
        rc = hd_db_commit(r->db, err);
        /* and the run's row says how far it is (runs.events, runs.cpd) */
        if (!rc)
          rc = hd_db_run_progress(r->db, r->run, r->ops->events(r->s), r->ops->cpd(r->s), err);
        if (rc) break;
      }
      if (sc->checkpoint_every > 0 && w - r->last_ckpt_wall >= sc->checkpoint_every) {
        rc = checkpoint(r, err);
        if (rc) break;
      }
    }
  }
  if (r->progress == 1) fprintf(stderr, "\n");
  return rc;
}

/* Ends the run in the database according to rc: final state and status. */
static int finish(runner *r, int rc, hd_error *err) {
  hd_error e2;
  hd_error_clear(&e2);
  const char *status = "done";
  if (rc == HD_EINTR)
    status = "interrupted";
  else if (rc == HD_ECOLLAPSE)
    status = "collapsed";
  else if (rc != HD_OK)
    status = "failed";
  int wrc = HD_OK;
  if (rc == HD_OK || rc == HD_EINTR || rc == HD_ECOLLAPSE) {
    /* the state where the run ended: 'final', or 'checkpoint' for one that can go on; the
     * engine's checkpoint only for a run that can be resumed (a done or collapsed run's is
     * deleted with its status: 150 MB at 1e6 bodies written for nothing), the rows committed
     * here all the same, so that a failed write is seen before the status is set */
    wrc = log_states(r, rc == HD_OK ? "final" : "checkpoint", &e2);
    if (!wrc) wrc = rc == HD_EINTR ? checkpoint(r, &e2) : hd_db_commit(r->db, &e2);
  }
  if (rc == HD_OK && wrc) { /* the final state or checkpoint could not be written: not done */
    status = "failed";
    hd_error_set(err, wrc, "%s", e2.msg);
    rc = wrc;
    hd_error_clear(&e2);
    wrc = HD_OK;
  }
  if (rc != HD_OK) hd_db_run_message(r->db, r->run, err->msg, &e2);
  if (rc == HD_OK && !r->note[0] && r->st.next_vel < r->sc->n_velocities_at) {
    int in_time = r->sc->velocities_in_time;
    snprintf(r->note, sizeof r->note,
             "%s: %d of %d snapshots not taken, the run ended at %s %.6g, before %g",
             in_time ? "velocities_at_time" : "velocities_at",
             r->sc->n_velocities_at - (int)r->st.next_vel, r->sc->n_velocities_at,
             in_time ? "t =" : "cpd", in_time ? r->ops->time(r->s) : r->ops->cpd(r->s),
             r->sc->velocities_at[r->st.next_vel]);
  }
  if (rc == HD_OK && r->note[0]) hd_db_run_message(r->db, r->run, r->note, &e2);
  if (r->o->note && r->o->note_size) snprintf(r->o->note, r->o->note_size, "%s", rc ? "" : r->note);
  /* the HCS window of the samples logged so far (runs.hcs_*), for the analyses; before the
   * final events and status, which a watcher takes for the run's end */
  int src = HD_OK;
  if (!wrc && (rc == HD_OK || rc == HD_EINTR || rc == HD_ECOLLAPSE))
    src = hd_db_run_hcs(r->db, r->run, &e2);
  if (!src) src = hd_db_run_progress(r->db, r->run, r->ops->events(r->s), r->ops->cpd(r->s), &e2);
  if (!src) src = hd_db_run_status(r->db, r->run, status, r->ops->events(r->s), elapsed(r), &e2);
  if (!wrc) wrc = src;
  if (!wrc && rc == HD_OK) wrc = hd_db_build_indexes(r->db, &e2);
  if (rc == HD_OK && wrc) {
    *err = e2;
    return wrc;
  }
  return rc;
}

static void signals_on(void) {
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  hd_stop_requested = 0;
  sigaction(SIGINT, &sa, &old_int);
  sigaction(SIGTERM, &sa, &old_term);
}

/* Records in the provenance table the host and the Slurm job and task the run is made in. */
static int record_origin(runner *r, hd_error *err) {
  char host[256] = "";
  if (gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
  const char *job = getenv("SLURM_ARRAY_JOB_ID");
  if (!job || !*job) job = getenv("SLURM_JOB_ID");
  return hd_db_run_origin(r->db, r->run, host, job, getenv("SLURM_ARRAY_TASK_ID"), err);
}

static int drive_and_finish(runner *r, hd_error *err) {
  r->last_ckpt_wall = r->last_tick_wall = r->last_commit_wall = now_wall();
  r->last_tick_events = r->ops->events(r->s);
  double every = r->o->progress_every == 0 ? HD_RUN_PROGRESS_EVERY : r->o->progress_every;
  r->progress = r->o->quiet ? 0 : isatty(2) ? 1 : every > 0 ? 2 : 0;
  r->progress_every = r->progress == 1 ? 0.5 : every;
  int rc = drive(r, err);
  return finish(r, rc, err);
}

/* The start of a run whose model state r->s is the scene's initial one: the box, the initial
 * states, the t = 0 sample and a first checkpoint (so that even a run killed at once can be
 * resumed). */
static int start(runner *r, hd_error *err) {
  double lx, ly;
  r->ops->box(r->s, &lx, &ly);
  int rc = hd_db_run_box(r->db, r->run, lx, ly, err);
  if (!rc && r->ops->log_species) rc = r->ops->log_species(r->s, r->db, r->run, err);
  if (!rc) rc = log_states(r, "initial", err);
  if (!rc) rc = observe(r, err); /* the t = 0 sample */
  if (!rc) rc = checkpoint(r, err);
  return rc;
}

int hd_run_new(const hd_scene *sc, const hd_run_opts *o, int64_t *run, hd_error *err) {
  runner r = {.sc = sc, .o = o, .ops = hd_model_for_scene(sc), .lock_fd = -1};
  r.t0_wall = r.last_ckpt_wall = now_wall();
  *run = 0;
  signals_on();
  int rc = HD_OK;
  if (sc->n_rods == 0 && hd_scene_bodies(sc) == 0)
    /* an empty box ran "done", and ended `failed` with a database error when it took samples
     * (NaN energies per body) */
    rc = hd_error_set(err, HD_EINPUT,
                      "%s%sno bodies: every count is 0: give [dimers], [disks] or a [species NAME] "
                      "a count > 0 (an empty box has nothing to run, and no energy per body to "
                      "sample)",
                      sc->path, sc->path[0] ? ": " : "");
  if (!rc) rc = r.ops->alloc(&r.s, sc, err); /* bad input fails here, before anything is written */
  if (rc) {
    signals_off();
    if (rc == HD_EINPUT && sc->path[0] && err->msg[0] == '[') {
      char msg[sizeof err->msg]; /* "[section] ...": a set-up the engine refused, in which file */
      snprintf(msg, sizeof msg, "%s", err->msg);
      /* about the box: where it was given (the line, or the --set), by the key the user wrote:
       * area_fraction when the box came from it */
      if (!strncmp(msg, "[system] box", 12) && sc->box_at[0] && sc->area_fraction > 0)
        hd_error_set(err, rc, "%s: [system] area_fraction = %.6g: the %s", sc->box_at,
                     sc->area_fraction, msg + 9);
      else if (!strncmp(msg, "[system] box", 12) && sc->box_at[0])
        hd_error_set(err, rc, "%s: %s", sc->box_at, msg);
      else
        hd_error_set(err, rc, "%s: %s", sc->path, msg);
    }
    return rc;
  }
  rc = hd_db_open(&r.db, o->db_path, err);
  if (!rc) rc = hd_db_run_begin(r.db, sc->text ? sc->text : "", sc->seed, o->version, &r.run, err);
  if (!rc) {
    *run = r.run;
    /* the lock before the row is committed (start commits it): a resume never finds this run
     * 'running' without its lock held, so it never takes over a run in its set-up */
    frames_estimate(&r);
    rc = run_lock(&r, err);
    if (!rc) rc = record_origin(&r, err);
    if (!rc) {
      hd_run_prov prov = {.git_commit = hd_build_commit,
                          .git_dirty = hd_build_dirty,
                          .compiler = hd_build_compiler,
                          .cflags = hd_build_cflags,
                          .command = o->command,
                          .sweep_point = o->sweep_point};
      rc = hd_db_run_provenance(r.db, r.run, &prov, err);
    }
    if (!rc) rc = start(&r, err);
    if (rc) { /* any failure of the set-up marks the run, which cannot be resumed */
      hd_error e2;
      hd_db_run_message(r.db, r.run, err->msg, &e2);
      hd_db_run_status(r.db, r.run, "failed", 0, 0.0, &e2);
    } else {
      rc = drive_and_finish(&r, err);
    }
  }
  hd_error e3;
  int crc = hd_db_close(r.db, &e3);
  if (!rc && crc) *err = e3, rc = crc;
  run_unlock(&r);
  signals_off();
  r.ops->free(r.s);
  free(r.frame_recs);
  free(r.frame_buf);
  return rc;
}

/* Restores the runner and its model from checkpoint blob (n bytes) saved at collision seq and
 * time t: the checksum, then what the runner's state holds (it indexes the scene's
 * velocities_at), then the model's own checks; the clock and the collision count must agree
 * with the row.  HD_EINPUT "DB: the checkpoint of run N is damaged (why)..." for anything
 * wrong; r->s NULL unless HD_OK. */
static int restore(runner *r, const unsigned char *blob, size_t n, int64_t seq, double t,
                   hd_error *err) {
  char why[sizeof err->msg];
  hd_error e;
  hd_error_clear(&e);
  int rc = HD_OK;
  ckpt_trailer tr = {0, 0};
  if (n >= sizeof r->st + sizeof tr) memcpy(&tr, blob + n - sizeof tr, sizeof tr);
  if (tr.magic == HD_CKSUM_MAGIC) {
    n -= sizeof tr;
    if (ckpt_sum(blob, n) != tr.sum) rc = hd_error_set(&e, HD_EINPUT, "checksum mismatch");
  } else if (n > sizeof r->st &&
             hd_sim_checkpoint_needs_trailer(blob + sizeof r->st, n - sizeof r->st)) {
    /* every HAFFCKP2 blob was stored with its trailer: one without has lost it */
    rc = hd_error_set(&e, HD_EINPUT, "its checksum trailer is missing");
  } /* else a checkpoint of an older haff (HAFFCKP1, rods), stored before the trailer */
  if (!rc && n < sizeof r->st) rc = hd_error_set(&e, HD_EINPUT, "truncated");
  if (!rc) {
    memcpy(&r->st, blob, sizeof r->st);
    const run_state *st = &r->st;
    if (st->seq != seq || st->seq < 0 || st->next_sample < 0 || st->next_vel < 0 ||
        st->next_vel > r->sc->n_velocities_at || st->next_frame < 0 ||
        !isfinite(st->wall_seconds) || st->wall_seconds < 0)
      rc = hd_error_set(&e, HD_EINPUT, "run counters out of range");
  }
  if (!rc) {
    rc = r->ops->alloc_restore(&r->s, r->sc, blob + sizeof r->st, n - sizeof r->st, &e);
    if (rc == HD_OK && r->ops->time(r->s) != t) /* the time the row says it was saved at */
      rc = hd_error_set(&e, HD_EINPUT, "its time is not the row's");
  }
  if (rc == HD_OK || rc != HD_EINPUT) {
    if (rc) *err = e;
    return rc;
  }
  if (r->s) r->ops->free(r->s);
  r->s = NULL;
  snprintf(why, sizeof why, "%s", e.msg);
  return hd_error_set(err, HD_EINPUT,
                      "%s: the checkpoint of run %lld is damaged (%s): it cannot be resumed",
                      r->o->db_path, (long long)r->run, why);
}

int hd_run_resume(int64_t want_run, const hd_run_opts *o, int64_t *run, hd_error *err) {
  runner r = {.o = o, .lock_fd = -1};
  r.t0_wall = r.last_ckpt_wall = now_wall();
  hd_scene sc;
  char *text = NULL;
  void *blob = NULL;
  size_t n = 0;
  int64_t seq = 0;
  double t = 0;
  unsigned long long seed = 0;
  *run = 0;
  /* not created by a mistyped name, nor haff's tables added to a file of someone else's */
  int rc = hd_db_open_existing(&r.db, o->db_path, err);
  if (!rc) rc = hd_db_find_resumable(r.db, want_run, &r.run, &text, &seed, err);
  if (!rc) {
    char name[64];
    snprintf(name, sizeof name, "run %lld scene", (long long)r.run);
    rc = hd_scene_load_stored(&sc, text, name, err);
    if (!rc) sc.seed = seed;
  }
  free(text);
  if (rc) {
    hd_db_close(r.db, NULL);
    return rc;
  }
  r.sc = &sc;
  r.ops = hd_model_for_scene(&sc);
  *run = r.run;
  signals_on();
  rc = run_lock(&r, err); /* before anything of the run is touched */
  int unstarted = 0;
  if (!rc) rc = hd_db_run_unstarted(r.db, r.run, &unstarted, err);
  if (!rc && unstarted) {
    /* killed in its set-up, before its first checkpoint (it is not running: we hold its lock):
     * run again from its scene and seed, the same run as one never stopped, after the rows
     * of the set-up that were committed */
    rc = hd_db_truncate_after(r.db, r.run, 0, -INFINITY, err);
    if (!rc) rc = r.ops->alloc(&r.s, &sc, err);
    if (!rc) rc = hd_db_run_message(r.db, r.run, NULL, err);
    if (!rc) rc = start(&r, err);
  } else if (!rc) {
    rc = hd_db_checkpoint_load(r.db, r.run, &blob, &n, &seq, &t, err);
    if (!rc) rc = restore(&r, blob, n, seq, t, err);
    free(blob);
    if (!rc) rc = hd_db_truncate_after(r.db, r.run, seq, t, err);
    if (!rc) /* why it stopped belongs to the stop, not to the run that now goes on */
      rc = hd_db_run_message(r.db, r.run, NULL, err);
  }
  if (!rc && (sc.frames_every > 0 || sc.frames_every_time > 0)) { /* for frames_max_mb */
    int64_t bytes = 0;
    rc = hd_db_frames_bytes(r.db, r.run, &bytes, err);
    long nb = hd_scene_bodies(&sc);
    if (nb > 0)
      r.frame_bytes =
          floor((double)bytes / ((double)nb * HD_FRAME_BODY_BYTES)) * hd_scene_frame_bytes(&sc);
  }
  if (!rc)
    rc = hd_db_run_status(r.db, r.run, "running", r.ops->events(r.s), r.st.wall_seconds, err);
  if (!rc) rc = drive_and_finish(&r, err);
  hd_error e3;
  int crc = hd_db_close(r.db, &e3);
  if (!rc && crc) *err = e3, rc = crc;
  run_unlock(&r);
  signals_off();
  if (r.s) r.ops->free(r.s);
  free(r.frame_recs);
  free(r.frame_buf);
  hd_scene_free(&sc);
  return rc;
}
