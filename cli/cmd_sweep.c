/* `haff sweep`: a study of many runs, one database per point, run locally or as a Slurm job
 * array, then merged (docs/contract.md, README "Studies").
 *
 * SWEEP.ini:
 *   [sweep]  scene = BASE.ini (relative to the sweep file), seeds = LIST (optional)
 *   [axes]   SECTION.KEY = LIST       one axis per key: the full grid of their values
 *   [points] point = S.K=V S.K=V ...  or a listed set of points (not both)
 * A LIST is values separated by blanks, or a range FROM:TO:STEP (TO included).  Every point is
 * also run for each seed.  A study folder DIR holds manifest.tsv (one line per point: number,
 * database, overrides), points/pNNNN.db (one run each), logs/, slurm/ and, once every point is
 * done, study.db (all runs merged, haff merge). */
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <sqlite3.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "haff.h"
#include "hd_db.h"
#include "hd_error.h"
#include "hd_lock.h"
#include "hd_merge.h"
#include "hd_opt.h"
#include "hd_scene.h"
#include "hd_sweepfile.h"

static const char sweep_usage[] =
    "usage: haff sweep SWEEP.ini [-o DIR] [--jobs N] [--progress S] [--dry-run] [--drop-points]\n"
    "       haff sweep SWEEP.ini --slurm [-o DIR] [--chunk C] [--time T] [--partition P]\n"
    "                  [--account A] [--sbatch 'OPTIONS'] [--dry-run] [--drop-points]\n"
    "       haff sweep --status DIR\n"
    "       haff sweep --resume DIR [--jobs N | --slurm ...] [--drop-points]\n"
    "       haff sweep --merge DIR [--drop-points]\n"
    "  A study: a base scene and axes of overrides (SECTION.KEY=VALUE) and seeds (SWEEP.ini) give\n"
    "  points; each point is one run in its own database DIR/points/pNNNN.db (DIR: SWEEP's\n"
    "  name without .ini, in the current folder), listed in DIR/manifest.tsv.  Locally --jobs N\n"
    "  [1] points run at once, then every run is merged into DIR/study.db.  --slurm writes\n"
    "  DIR/slurm/array-K.sh (a job array, C points per task [1]; --time, --partition,\n"
    "  --account and the options of --sbatch go to every job as #SBATCH lines) and\n"
    "  merge-K.sh (afterok on the array), and submits both (--dry-run: writes them, submits\n"
    "  nothing).  --drop-points removes the points' databases once study.db is merged and\n"
    "  verified.  One sweep at a time works on a folder (DIR/sweep.lock): a second is\n"
    "  refused, naming the first.\n"
    "  --status lists each point: done, running, interrupted, failed or missing.  --resume\n"
    "  resumes the interrupted points from their checkpoints and reruns failed or missing\n"
    "  ones, locally or as a new array.  A finished study is not run again.\n"
    "  SWEEP.ini:\n"
    "    [sweep]\n"
    "    scene = base.ini          ; relative to SWEEP.ini\n"
    "    seeds = 1:4:1             ; values, or FROM:TO:STEP (TO included)\n"
    "    [axes]                    ; the full grid (last axis fastest, seeds fastest of all)\n"
    "    disks.alpha = 0.8 0.9 0.95\n"
    "    [points]                  ; instead of [axes]: listed points\n"
    "    point = disks.alpha=0.9 disks.count=500\n"
    "  Exit status: 0 all points done, 1 a point not done, 2 bad usage or input.\n";

#define SW_MAX_AXES HD_SWEEP_MAX_AXES
#define SW_MAX_POINTS 1000000

/* A sweep file (hd_sweepfile) and the path of its base scene. */
typedef struct sweep {
  char path[PATH_MAX];  /* the sweep file as given */
  char scene[PATH_MAX]; /* the base scene, absolute */
  hd_sweepfile f;
} sweep;

/* A point: its number, the overrides (owned, NUL-separated in one string), its line. */
typedef struct point {
  int id;
  char *sets; /* "S.K=V S.K=V ...", a value with blanks in double quotes */
} point;

static void sweep_free(sweep *s) {
  hd_sweepfile_free(&s->f);
}

/* Bad input in the sweep file: one line "FILE:LINE: [section] key: why" (escaped); returns 2. */
static int bad(const sweep *s, long line, const char *sec, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
static int bad(const sweep *s, long line, const char *sec, const char *key, const char *fmt, ...) {
  char why[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(why, sizeof why, fmt, ap);
  va_end(ap);
  hd_error err;
  hd_error_set(&err, HD_EINPUT, "%s:%ld: [%s]%s%s: %s", s->path, line, sec, key ? " " : "",
               key ? key : "", why);
  fprintf(stderr, "haff sweep: %s\n", err.msg);
  return 2;
}

/* Reads the sweep file (hd_sweepfile_read) and finds its base scene (relative to it).  0 or 2
 * (said). */
static int sweep_read(sweep *s, const char *path) {
  memset(s, 0, sizeof *s);
  snprintf(s->path, sizeof s->path, "%s", path);
  hd_error err;
  hd_error_clear(&err);
  int rc = hd_sweepfile_read(&s->f, path, &err);
  if (rc) {
    fprintf(stderr, "haff sweep: %s\n", err.msg);
    return rc == HD_EINPUT ? 2 : 1;
  }
  const char *val = s->f.scene;
  char rel[PATH_MAX * 2];
  if (val[0] == '/') {
    snprintf(rel, sizeof rel, "%s", val);
  } else {
    const char *slash = strrchr(path, '/');
    snprintf(rel, sizeof rel, "%.*s%s", slash ? (int)(slash - path + 1) : 0, path, val);
  }
  struct stat sb;
  if (!realpath(rel, s->scene))
    return bad(s, s->f.scene_line, "sweep", "scene", "'%s': %s", val, strerror(errno));
  if (stat(s->scene, &sb) == 0 && S_ISDIR(sb.st_mode))
    return bad(s, s->f.scene_line, "sweep", "scene", "'%s': a directory, not a scene file", val);
  return 0;
}

/* Splits "S.K=V S.K=\"V W\"" into the array sets (pointers into a copy *buf, quotes removed);
 * returns the count (0 when it cannot: an unclosed quote, which the sweep file's reader
 * refused, or out of memory). */
static int split_sets(const char *text, char **buf, const char **sets, int max) {
  int n = hd_sweep_split(text, buf, sets, max);
  return n < 0 ? 0 : n;
}

/* Loads the base scene with the overrides of text: 0 when it loads, else 1 with the reason in
 * why (the loader's message, or a malformed override). */
static int load_sets(const sweep *s, const char *text, char *why, size_t cap) {
  const char *sets[SW_MAX_AXES + 64];
  char *buf;
  int n = split_sets(text, &buf, sets, (int)(sizeof sets / sizeof sets[0]));
  for (int k = 0; k < n; k++)
    if (!strchr(sets[k], '=') || !strchr(sets[k], '.')) {
      snprintf(why, cap, "'%s': not SECTION.KEY=VALUE", sets[k]);
      free(buf);
      return 1;
    }
  hd_scene sc;
  hd_error err;
  hd_error_clear(&err);
  int rc = hd_scene_load(&sc, s->scene, sets, n, &err);
  free(buf);
  if (rc) {
    snprintf(why, cap, "%s", err.msg);
    return 1;
  }
  hd_scene_free(&sc);
  return 0;
}

/* The axis value indices of grid point b (the last axis varies fastest). */
static void grid_index(const sweep *s, int b, int *idx) {
  int rem = b;
  for (int k = s->f.nax - 1; k >= 0; k--) idx[k] = rem % s->f.ax[k].n, rem /= s->f.ax[k].n;
}

/* Says why a grid whose points in bad[] (1 = does not load, of nb) fail is refused: an axis
 * value bad in every point that has it (and bad alone) is named with the line of its axis and
 * the loader's message for it alone; else the first bad point with all its overrides.  2. */
static int grid_bad(const sweep *s, const point *p, const unsigned char *bad_pt, int nb,
                    int nseed) {
  char why[1024];
  int idx[SW_MAX_AXES];
  for (int k = 0; k < s->f.nax; k++)
    for (int j = 0; j < s->f.ax[k].n; j++) {
      int all = 1;
      for (int b = 0; b < nb && all; b++) {
        grid_index(s, b, idx);
        if (idx[k] == j && !bad_pt[b]) all = 0;
      }
      char one[4096];
      hd_sweep_format_set(one, sizeof one, s->f.ax[k].key, s->f.ax[k].v[j]);
      if (all && load_sets(s, one, why, sizeof why))
        return bad(s, s->f.ax[k].line, "axes", s->f.ax[k].key, "%s", why);
    }
  for (int b = 0; b < nb; b++)
    if (bad_pt[b]) {
      load_sets(s, p[b * nseed].sets, why, sizeof why);
      return bad(s, s->f.ax[s->f.nax - 1].line, "axes", NULL, "point %d (%s): %s", b * nseed,
                 p[b * nseed].sets, why);
    }
  return 2;
}

/* The points of the sweep, in order, each validated whole against the base scene (a value
 * can be bad alone and fine with another axis's value, as with --set).  0 or 2 (said). */
static int make_points(const sweep *s, point **out, int *np) {
  *out = NULL;
  *np = 0;
  double total = s->f.npoints ? s->f.npoints : 1;
  for (int k = 0; k < s->f.nax; k++) total *= s->f.ax[k].n;
  int nseed = s->f.seeds.n ? s->f.seeds.n : 1;
  total *= nseed;
  if (total > SW_MAX_POINTS) {
    fprintf(stderr, "haff sweep: %s: %.0f points, more than %d\n", s->path, total, SW_MAX_POINTS);
    return 2;
  }
  int n = (int)total;
  point *p = calloc((size_t)n, sizeof *p);
  int base = n / nseed;
  unsigned char *bad_pt = calloc((size_t)base + 1, 1);
  if (!p || !bad_pt) {
    free(p);
    free(bad_pt);
    return 2;
  }
  int nbad = 0;
  for (int b = 0; b < base; b++) {
    char text[8192] = "";
    size_t len = 0;
    if (s->f.npoints) {
      len = (size_t)snprintf(text, sizeof text, "%s", s->f.points[b]);
    } else {
      int idx[SW_MAX_AXES];
      grid_index(s, b, idx);
      for (int k = 0; k < s->f.nax && len < sizeof text; k++) {
        if (k) len += (size_t)snprintf(text + len, sizeof text - len, " ");
        if (len < sizeof text)
          len += (size_t)hd_sweep_format_set(text + len, sizeof text - len, s->f.ax[k].key,
                                             s->f.ax[k].v[idx[k]]);
      }
    }
    if (len >= sizeof text - 64) {
      fprintf(stderr, "haff sweep: %s: a point's overrides are too long\n", s->path);
      nbad = -1;
      break;
    }
    for (int q = 0; q < nseed; q++) {
      char full[8300];
      if (s->f.seeds.n)
        snprintf(full, sizeof full, "%s%ssystem.seed=%s", text, len ? " " : "", s->f.seeds.v[q]);
      else
        snprintf(full, sizeof full, "%s", text);
      p[b * nseed + q].id = b * nseed + q;
      p[b * nseed + q].sets = strdup(full);
    }
    /* the whole point loads */
    char why[1024];
    if (!load_sets(s, p[b * nseed].sets, why, sizeof why)) continue;
    if (s->f.npoints || !s->f.nax) {
      bad(s, s->f.npoints ? s->f.pt_line[b] : s->f.scene_line, s->f.npoints ? "points" : "sweep",
          s->f.npoints ? "point" : "scene", "%s", why);
      nbad = -1;
      break;
    }
    bad_pt[b] = 1;
    nbad++;
  }
  if (nbad > 0) grid_bad(s, p, bad_pt, base, nseed);
  free(bad_pt);
  if (nbad) {
    for (int k = 0; k < n; k++) free(p[k].sets);
    free(p);
    return 2;
  }
  *out = p;
  *np = n;
  return 0;
}

/* ------------------------------------------------------------------------------------------ */
/* the study folder */

/* A study as its manifest describes it. */
typedef struct study {
  char dir[PATH_MAX];   /* absolute */
  char scene[PATH_MAX]; /* the base scene, absolute */
  point *p;
  int n;
  int dropped; /* the points' databases were removed after a verified merge (--drop-points) */
} study;

static void study_free(study *st) {
  for (int k = 0; k < st->n; k++) free(st->p[k].sets);
  free(st->p);
  st->p = NULL;
  st->n = 0;
}

static int width(int n) {
  int w = 4;
  for (int m = 10000; m <= n - 1 && w < 9; m *= 10) w++;
  return w;
}

/* The database of point k: DIR/points/pNNNN.db. */
static void point_db(const study *st, int k, char *buf, size_t size) {
  snprintf(buf, size, "%s/points/p%0*d.db", st->dir, width(st->n), k);
}

static void point_log(const study *st, int k, char *buf, size_t size) {
  snprintf(buf, size, "%s/logs/p%0*d.log", st->dir, width(st->n), k);
}

/* DIR/points/DROPPED: written once --drop-points has removed the points' databases. */
static void dropped_path(const study *st, char *buf, size_t size) {
  snprintf(buf, size, "%s/points/DROPPED", st->dir);
}

static void study_see_dropped(study *st) {
  char path[PATH_MAX + 32];
  dropped_path(st, path, sizeof path);
  st->dropped = access(path, F_OK) == 0;
}

/* The manifest text of a study (tab-separated, one line per point). */
static char *manifest_text(const study *st) {
  size_t cap = 4096 + (size_t)st->n * 64, len = 0;
  for (int k = 0; k < st->n; k++) cap += strlen(st->p[k].sets);
  char *t = malloc(cap);
  if (!t) return NULL;
  len += (size_t)snprintf(t + len, cap - len,
                          "# haff sweep manifest: one line per point (point, database, --set "
                          "overrides of the base scene)\n# scene\t%s\npoint\tdb\tsets\n",
                          st->scene);
  for (int k = 0; k < st->n; k++) {
    char db[PATH_MAX + 64];
    /* width() is at most 9; the check tells gcc -O1 -fsanitize (the ASan build) so */
    if (snprintf(db, sizeof db, "points/p%0*d.db", width(st->n), k) >= (int)sizeof db) continue;
    len += (size_t)snprintf(t + len, cap - len, "%d\t%s\t%s\n", k, db, st->p[k].sets);
  }
  return t;
}

/* Reads DIR/manifest.tsv into *st; 0, or 2 (said). */
static int manifest_read(study *st, const char *dir) {
  memset(st, 0, sizeof *st);
  if (!realpath(dir, st->dir)) {
    fprintf(stderr, "haff sweep: %s: %s\n", dir, strerror(errno));
    return 2;
  }
  char path[PATH_MAX + 32];
  snprintf(path, sizeof path, "%s/manifest.tsv", st->dir);
  FILE *f = fopen(path, "r");
  if (!f) {
    fprintf(stderr, "haff sweep: %s: %s (not a study folder)\n", path, strerror(errno));
    return 2;
  }
  char line[16384];
  long ln = 0;
  int rc = 0, cap = 0;
  while (!rc && fgets(line, sizeof line, f)) {
    ln++;
    line[strcspn(line, "\n")] = '\0';
    if (!strncmp(line, "# scene\t", 8)) {
      snprintf(st->scene, sizeof st->scene, "%.*s", PATH_MAX - 1, line + 8);
      continue;
    }
    if (line[0] == '#' || !strncmp(line, "point\t", 6)) continue;
    char *t1 = strchr(line, '\t'), *t2 = t1 ? strchr(t1 + 1, '\t') : NULL;
    if (!t2 || atoi(line) != st->n) {
      fprintf(stderr, "haff sweep: %s:%ld: not a manifest line\n", path, ln);
      rc = 2;
      break;
    }
    if (st->n == cap) {
      cap = cap ? 2 * cap : 64;
      point *p = realloc(st->p, (size_t)cap * sizeof *p);
      if (!p) {
        rc = 2;
        break;
      }
      st->p = p;
    }
    st->p[st->n].id = st->n;
    st->p[st->n].sets = strdup(t2 + 1);
    st->n++;
  }
  fclose(f);
  if (!rc && (!st->scene[0] || st->n == 0)) {
    fprintf(stderr, "haff sweep: %s: no scene or no points\n", path);
    rc = 2;
  }
  if (rc) study_free(st);
  if (!rc) study_see_dropped(st);
  return rc;
}

/* ------------------------------------------------------------------------------------------ */
/* the study's lock: DIR/sweep.lock
 *
 * POSIX record locks (fcntl, db/hd_lock.h), which the kernel drops when the process ends however it
 * ends (kill -9 too), so a lock is never stale; the file's text only names the last holder. Byte 0:
 * the study, held (write lock, not waited for) by a local sweep, --resume and --merge for their
 * whole life: a second one on the same folder is refused, naming the holder. Byte 1 + k: point k,
 * held by the sweep process (local or a Slurm task) that runs it, from before its database is
 * looked at until its run has ended: no other sweep classes, renames or starts a point that another
 * one is running, even in the set-up before the run's own lock. Every lock of a process goes with
 * any close() of the file, so the one descriptor stays open. */

static int lock_fd = -1; /* DIR/sweep.lock, open for the process's life once opened */

/* Opens DIR/sweep.lock (created unless readonly); 0, or -1 with errno. */
static int lock_open(const study *st, int readonly) {
  if (lock_fd >= 0) return 0;
  char path[PATH_MAX + 32];
  snprintf(path, sizeof path, "%s/sweep.lock", st->dir);
  lock_fd = hd_lock_open(path, !readonly);
  return lock_fd >= 0 ? 0 : -1;
}

/* The pid of another process that holds byte at, or 0 when none does (-1: one does, its pid
 * unknown). */
static long lock_holder(off_t at) {
  hd_lock_who who;
  if (lock_fd < 0 || hd_lock_holder(lock_fd, at, 1, 1, &who) != 0) return 0;
  return who.pid;
}

/* Takes the study's lock for what (e.g. "sweep"), or refuses: 0, or 1 after one line that
 * names the holder (a sweep working on the folder is not waited for). */
static int study_lock(const study *st, const char *what) {
  if (lock_open(st, 0)) {
    fprintf(stderr, "haff sweep: %s/sweep.lock: %s\n", st->dir, strerror(errno));
    return 1;
  }
  if (hd_lock_acquire(lock_fd, 0, 1) != 0) {
    int e = errno;
    if (e != EACCES && e != EAGAIN) {
      fprintf(stderr, "haff sweep: %s/sweep.lock: cannot lock: %s\n", st->dir, strerror(e));
      return 1;
    }
    char who[256] = "";
    ssize_t n = pread(lock_fd, who, sizeof who - 1, 0);
    who[n > 0 ? n : 0] = '\0';
    who[strcspn(who, "\n")] = '\0';
    for (char *c = who; *c; c++)
      if ((unsigned char)*c < 0x20 || *c == 0x7f) *c = '?';
    long pid = lock_holder(0), said = 0;
    char holder[320];
    /* the text names the holder once it has written it: else (a moment after it took the
     * lock, or another host's pid) the pid the kernel reports */
    if (who[0] && sscanf(who, "pid %ld", &said) == 1 && (pid <= 0 || said == pid))
      snprintf(holder, sizeof holder, "%s", who);
    else
      snprintf(holder, sizeof holder, "pid %ld", pid);
    fprintf(stderr,
            "haff sweep: %s: another haff sweep works on this study (%s; lock %s/sweep.lock): "
            "refused, not waited for; when it has ended: haff sweep --status or --resume\n",
            st->dir, holder, st->dir);
    return 1;
  }
  char host[128] = "?", text[512];
  gethostname(host, sizeof host - 1);
  host[sizeof host - 1] = '\0';
  time_t now = time(NULL);
  struct tm tm;
  char when[32] = "";
  if (gmtime_r(&now, &tm)) strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &tm);
  int len = snprintf(text, sizeof text, "pid %ld on %s since %s: haff sweep %s\n", (long)getpid(),
                     host, when, what);
  if (ftruncate(lock_fd, 0) == 0 && pwrite(lock_fd, text, (size_t)len, 0) == len) {
    /* only a note: the lock is the record lock (hd_lock) */
  }
  return 0;
}

/* Claims point k for this process: 1 taken, 0 another process runs it (or no lock file). */
static int point_claim(int k) {
  return lock_fd >= 0 && hd_lock_acquire(lock_fd, (off_t)k + 1, 1) == 0;
}

static void point_release(int k) {
  if (lock_fd >= 0) hd_lock_release(lock_fd, (off_t)k + 1, 1);
}

static int mkdir_p(const char *path) {
  return mkdir(path, 0777) == 0 || errno == EEXIST ? 0 : -1;
}

/* Writes path with text via a temporary file and rename (never half written). */
static int write_atomic(const char *path, const char *text) {
  char tmp[PATH_MAX + 32];
  snprintf(tmp, sizeof tmp, "%s.tmp-%ld", path, (long)getpid());
  FILE *f = fopen(tmp, "w");
  if (!f) return -1;
  int ok = fputs(text, f) >= 0;
  ok &= fflush(f) == 0 && fsync(fileno(f)) == 0;
  ok &= fclose(f) == 0;
  if (!ok || rename(tmp, path) != 0) {
    unlink(tmp);
    return -1;
  }
  return 0;
}

/* Creates the study folder of st (or checks that the one there is this study), under the
 * study lock taken for sweep_file (named to a second sweep).  0, 1 or 2. */
static int study_create(study *st, const char *dir, const char *sweep_file) {
  if (mkdir_p(dir) || !realpath(dir, st->dir)) {
    fprintf(stderr, "haff sweep: %s: %s\n", dir, strerror(errno));
    return 1;
  }
  study_see_dropped(st);
  char *text = manifest_text(st);
  if (!text) return 1;
  char path[PATH_MAX + 32], sub[PATH_MAX + 32];
  snprintf(path, sizeof path, "%s/manifest.tsv", st->dir);
  int rc = study_lock(st, sweep_file); /* before the manifest is read or written */
  if (rc) {
    free(text);
    return rc;
  }
  FILE *f = fopen(path, "r");
  if (f) { /* a study is there: the same one, or refused */
    size_t n = strlen(text);
    char *old = malloc(n + 2);
    size_t got = old ? fread(old, 1, n + 1, f) : 0;
    fclose(f);
    if (!old || got != n || memcmp(old, text, n)) {
      fprintf(stderr,
              "haff sweep: %s: holds another study (its manifest.tsv differs from this "
              "sweep's points): give another -o DIR, or --resume %s\n",
              dir, dir);
      rc = 2;
    }
    free(old);
  } else {
    static const char *const subs[] = {"points", "logs", "slurm"};
    for (int k = 0; k < 3 && !rc; k++) {
      snprintf(sub, sizeof sub, "%s/%s", st->dir, subs[k]);
      if (mkdir_p(sub)) rc = 1;
    }
    if (!rc && write_atomic(path, text)) rc = 1;
    if (rc) fprintf(stderr, "haff sweep: %s: cannot write: %s\n", path, strerror(errno));
  }
  free(text);
  return rc;
}

/* ------------------------------------------------------------------------------------------ */
/* the state of a point */

enum { P_MISSING, P_DONE, P_RUNNING, P_INTERRUPTED, P_FAILED };
static const char *const state_name[] = {"missing", "done", "running", "interrupted", "failed"};

/* The state of point k; status gets the run's status text ("" when none), *resumable whether
 * it has a checkpoint. */
static int point_state(const study *st, int k, char *status, size_t size, int *resumable) {
  char db[PATH_MAX + 64];
  point_db(st, k, db, sizeof db);
  status[0] = '\0';
  *resumable = 0;
  /* another sweep process runs it (from before its database exists, through the run's
   * set-up), or a run's lock is held in DB.lock: being written, whatever its file says now
   * (not opened: not classed failed, not renamed, its -wal and -shm not touched) */
  if (lock_holder((off_t)k + 1)) return P_RUNNING;
  if (access(db, F_OK) != 0) {
    if (!st->dropped) return P_MISSING;
    snprintf(status, size, "dropped"); /* merged into study.db, then removed */
    return P_DONE;
  }
  if (hd_merge_lock_held(db, -1)) return P_RUNNING;
  hd_error err;
  int64_t run = 0;
  if (hd_db_newest_run(db, &run, status, size, resumable, &err)) return P_FAILED;
  if (run == 0) return P_MISSING;
  if (!strcmp(status, "done") || !strcmp(status, "collapsed")) return P_DONE;
  if (!strcmp(status, "running")) {
    /* killed (its lock is not held): from its checkpoint, or (none: killed in its set-up) run again
     * from its scene and seed by haff resume, as the same run, not a second one */
    *resumable = 1;
    return P_INTERRUPTED;
  }
  if (!strcmp(status, "interrupted")) return P_INTERRUPTED;
  return P_FAILED;
}

/* ------------------------------------------------------------------------------------------ */
/* running points */

static volatile sig_atomic_t got_signal = 0;
static void on_signal(int sig) {
  got_signal = sig;
}

/* The path of this executable (for the children and the Slurm scripts). */
static void self_exe(char *buf, size_t size) {
  ssize_t n = readlink("/proc/self/exe", buf, size - 1);
  if (n <= 0)
    n = 0, snprintf(buf, size, "haff");
  else
    buf[n] = '\0';
}

/* Starts the process that brings point k to done: `haff resume DB --all` for an interrupted
 * one (or a failed one with a checkpoint), else `haff run SCENE -o DB --set ...` (a failed
 * database without a checkpoint is first renamed DB.failed-N).  stderr appends to its log.
 * Returns the pid, 0 when there is nothing to do (done or running elsewhere), -1 on error. */
static pid_t start_point(const study *st, int k, double progress) {
  char status[32];
  int resumable;
  if (!point_claim(k)) return 0; /* another sweep process runs it */
  int s = point_state(st, k, status, sizeof status, &resumable);
  if (s == P_DONE || s == P_RUNNING) {
    point_release(k);
    return 0;
  }
  char db[PATH_MAX + 64], log[PATH_MAX + 64], exe[PATH_MAX], prog[32];
  point_db(st, k, db, sizeof db);
  point_log(st, k, log, sizeof log);
  self_exe(exe, sizeof exe);
  snprintf(prog, sizeof prog, "%g", progress);
  int resume = (s == P_INTERRUPTED || s == P_FAILED) && resumable;
  if (s == P_FAILED && !resumable) { /* kept aside, not lost */
    char aside[PATH_MAX + 96];
    for (int j = 1; j < 1000; j++) {
      snprintf(aside, sizeof aside, "%s.failed-%d", db, j);
      if (access(aside, F_OK) != 0) break;
    }
    if (rename(db, aside) != 0) {
      point_release(k);
      return -1;
    }
    /* its -wal and -shm go with it (renamed, never unlinked: they may hold its last rows) */
    static const char *const sides[] = {"-wal", "-shm"};
    for (int j = 0; j < 2; j++) {
      char from[PATH_MAX + 80], to[PATH_MAX + 120];
      snprintf(from, sizeof from, "%s%s", db, sides[j]);
      snprintf(to, sizeof to, "%s%s", aside, sides[j]);
      if (access(from, F_OK) == 0) rename(from, to);
    }
  }
  const char *argv[16 + 2 * (SW_MAX_AXES + 64)];
  int a = 0;
  char *buf = NULL, *pt = NULL;
  argv[a++] = exe;
  if (resume) {
    argv[a++] = "resume";
    argv[a++] = db;
    argv[a++] = "--all";
  } else {
    argv[a++] = "run";
    argv[a++] = st->scene;
    argv[a++] = "-o";
    argv[a++] = db;
    const char *sets[SW_MAX_AXES + 64];
    int n = split_sets(st->p[k].sets, &buf, sets, SW_MAX_AXES + 64);
    for (int j = 0; j < n; j++) argv[a++] = "--set", argv[a++] = sets[j];
    /* which point this run is, for runs.sweep_point */
    size_t pn = strlen(st->dir) + strlen(st->p[k].sets) + 32;
    if ((pt = malloc(pn))) snprintf(pt, pn, "%s point %d: %s", st->dir, k, st->p[k].sets);
    if (pt) argv[a++] = "--sweep-point", argv[a++] = pt;
  }
  argv[a++] = "--progress";
  argv[a++] = prog;
  argv[a] = NULL;
  fflush(NULL);
  pid_t pid = fork();
  if (pid == 0) {
    int fd = open(log, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd >= 0) dup2(fd, 2);
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    execv(exe, (char *const *)argv);
    _exit(127);
  }
  free(buf);
  free(pt);
  if (pid < 0) point_release(k);
  return pid;
}

/* Runs the points list[0..n) with at most jobs at once.  A SIGINT or SIGTERM is passed on to
 * the running points (they checkpoint and stop) and no new one starts.  Returns 0 when every
 * point is done, 1 otherwise. */
static int run_points(const study *st, const int *list, int n, int jobs, double progress,
                      int quiet) {
  struct sigaction sa, old_int, old_term;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  got_signal = 0;
  sigaction(SIGINT, &sa, &old_int);
  sigaction(SIGTERM, &sa, &old_term);
  pid_t *pid = calloc((size_t)(jobs > 0 ? jobs : 1), sizeof *pid);
  int *who = calloc((size_t)(jobs > 0 ? jobs : 1), sizeof *who);
  int next = 0, active = 0, failed = 0, passed = 0;
  while (pid && who && (next < n || active > 0)) {
    while (!got_signal && next < n && active < jobs) {
      int k = list[next++];
      pid_t p = start_point(st, k, progress);
      if (p < 0) {
        failed++;
        fprintf(stderr, "haff sweep: point %d: cannot start: %s\n", k, strerror(errno));
        continue;
      }
      if (p == 0) continue;
      for (int j = 0; j < jobs; j++)
        if (!pid[j]) {
          pid[j] = p, who[j] = k;
          break;
        }
      active++;
      if (!quiet) fprintf(stderr, "haff sweep: point %d started (pid %ld)\n", k, (long)p);
    }
    if (active == 0) break;
    int wst;
    pid_t w = waitpid(-1, &wst, 0);
    if (w < 0) {
      if (errno == EINTR && got_signal) {
        for (int j = 0; j < jobs; j++)
          if (pid[j]) kill(pid[j], SIGTERM);
        continue;
      }
      if (errno == EINTR) continue;
      break;
    }
    for (int j = 0; j < jobs; j++)
      if (pid[j] == w) {
        pid[j] = 0;
        active--;
        point_release(who[j]);
        /* judged by its database, not its exit status: a run that collapsed (exit 1) has
         * ended, and is a result of the study */
        char status[32];
        int r, ok = point_state(st, who[j], status, sizeof status, &r) == P_DONE;
        if (ok)
          passed++;
        else
          failed++;
        if (!quiet || !ok)
          fprintf(stderr, "haff sweep: point %d %s\n", who[j],
                  ok ? status : "not done (see its log in logs/)");
      }
  }
  free(pid);
  free(who);
  sigaction(SIGINT, &old_int, NULL);
  sigaction(SIGTERM, &old_term, NULL);
  (void)passed;
  return failed || got_signal || next < n ? 1 : 0;
}

/* The points not done (running ones too when with_running), into list; returns the count. */
static int unfinished(const study *st, int *list, int with_running) {
  int m = 0;
  for (int k = 0; k < st->n; k++) {
    char status[32];
    int r;
    int s = point_state(st, k, status, sizeof status, &r);
    if (s != P_DONE && (with_running || s != P_RUNNING)) list[m++] = k;
  }
  return m;
}

/* Merges every point into DIR/study.db (replaced).  0, 1 (a point not done) or 2. */
static int study_merge(const study *st, int quiet, int64_t *merged) {
  *merged = 0;
  if (st->dropped) { /* the points are gone: study.db is the study */
    if (!quiet)
      fprintf(stderr,
              "haff sweep: %s: the points were dropped after their merge: study.db is the "
              "study, not merged again\n",
              st->dir);
    return 0;
  }
  int *list = malloc((size_t)st->n * sizeof *list);
  if (!list) return 1;
  int m = unfinished(st, list, 1);
  if (m) {
    fprintf(stderr, "haff sweep: %s: %d of %d points not done (first: %d): not merged\n", st->dir,
            m, st->n, list[0]);
    free(list);
    return 1;
  }
  free(list);
  char **in = calloc((size_t)st->n, sizeof *in);
  char out[PATH_MAX + 32], tmp[PATH_MAX + 32];
  snprintf(out, sizeof out, "%s/study.db", st->dir);
  snprintf(tmp, sizeof tmp, "%s/study.db.new", st->dir);
  int rc = in ? 0 : 1;
  for (int k = 0; !rc && k < st->n; k++) {
    in[k] = malloc(PATH_MAX + 64);
    if (!in[k])
      rc = 1;
    else
      point_db(st, k, in[k], PATH_MAX + 64);
  }
  hd_error err;
  hd_error_clear(&err);
  int64_t runs = 0;
  unlink(tmp);
  if (!rc) rc = hd_db_merge(tmp, (const char *const *)in, st->n, &runs, &err);
  if (!rc && rename(tmp, out) != 0)
    rc = hd_error_set(&err, HD_EIO, "%s: rename: %s", tmp, strerror(errno));
  for (int k = 0; in && k < st->n; k++) free(in[k]);
  free(in);
  if (rc) {
    fprintf(stderr, "haff sweep: merge: %s\n", err.msg);
    return hd_exit_code(rc);
  }
  if (!quiet) fprintf(stderr, "haff sweep: %lld runs merged into %s\n", (long long)runs, out);
  *merged = runs;
  return 0;
}

/* --drop-points: after a merge of merged runs into DIR/study.db, checks that study.db reads
 * back with one run per point, the last of them ended (done or collapsed), then removes every
 * point's database (with its -wal, -shm and .lock) and writes DIR/points/DROPPED so that the
 * study stays done.  0, or 1 after one line (nothing removed). */
static int drop_points(study *st, int64_t merged, int quiet) {
  if (st->dropped) return 0;
  char out[PATH_MAX + 32], status[32];
  snprintf(out, sizeof out, "%s/study.db", st->dir);
  int64_t last = 0;
  int resumable = 0;
  hd_error err;
  hd_error_clear(&err);
  if (merged != st->n || hd_db_newest_run(out, &last, status, sizeof status, &resumable, &err) ||
      last != merged || (strcmp(status, "done") && strcmp(status, "collapsed"))) {
    fprintf(stderr,
            "haff sweep: %s: --drop-points: study.db does not read back as %d runs, one per "
            "point (%lld merged, %lld read%s%s): the points are kept\n",
            st->dir, st->n, (long long)merged, (long long)last, err.msg[0] ? ": " : "", err.msg);
    return 1;
  }
  char mark[PATH_MAX + 32], text[256];
  dropped_path(st, mark, sizeof mark);
  snprintf(text, sizeof text,
           "the %d point databases were removed after their merge into study.db (%lld runs)\n",
           st->n, (long long)merged);
  if (write_atomic(mark, text)) { /* first: a study never looks undone */
    fprintf(stderr, "haff sweep: %s: cannot write: %s: the points are kept\n", mark,
            strerror(errno));
    return 1;
  }
  st->dropped = 1;
  static const char *const ext[] = {"", "-wal", "-shm", ".lock"};
  for (int k = 0; k < st->n; k++) {
    char db[PATH_MAX + 64], f[PATH_MAX + 80];
    point_db(st, k, db, sizeof db);
    for (int j = 0; j < 4; j++) {
      snprintf(f, sizeof f, "%s%s", db, ext[j]);
      unlink(f);
    }
  }
  if (!quiet)
    fprintf(stderr, "haff sweep: %s: the %d point databases dropped (study.db verified)\n", st->dir,
            st->n);
  return 0;
}

/* --status: one line per point. */
static int study_status(const study *st) {
  int count[5] = {0};
  printf("point\tstate\trun_status\tdb\tsets\n");
  for (int k = 0; k < st->n; k++) {
    char status[32], db[PATH_MAX + 64];
    int r;
    int s = point_state(st, k, status, sizeof status, &r);
    count[s]++;
    point_db(st, k, db, sizeof db);
    printf("%d\t%s\t%s\tpoints/%s\t%s\n", k, state_name[s], status[0] ? status : "-",
           strrchr(db, '/') + 1, st->p[k].sets);
  }
  char out[PATH_MAX + 32];
  snprintf(out, sizeof out, "%s/study.db", st->dir);
  fprintf(stderr,
          "haff sweep: %s: %d points: %d done, %d running, %d interrupted, %d failed, "
          "%d missing; study.db %s\n",
          st->dir, st->n, count[P_DONE], count[P_RUNNING], count[P_INTERRUPTED], count[P_FAILED],
          count[P_MISSING], access(out, F_OK) == 0 ? "merged" : "not merged yet");
  return 0;
}

/* ------------------------------------------------------------------------------------------ */
/* Slurm */

typedef struct slurm_opts {
  const char *time, *partition, *account; /* --time, --partition, --account */
  const char *sbatch;                     /* --sbatch 'OPTIONS': more sbatch options */
  int chunk;                              /* --chunk */
  int dry;                                /* --dry-run: the scripts written, not submitted */
  int drop;                               /* --drop-points, given to the merge job */
} slurm_opts;

/* Whether s holds a control byte (no quoting keeps it on one #SBATCH or shell line). */
static int has_control(const char *s) {
  for (; *s; s++)
    if ((unsigned char)*s < 0x20 || *s == 0x7f) return 1;
  return 0;
}

/* Appends to buf (at *len, size) the word w as one argument of an #SBATCH line: as it is when
 * it has only plain characters, else in double quotes with \ before " and \ (sbatch reads a
 * script's #SBATCH lines so: quotes group, a backslash escapes, an unquoted # ends the line).
 * pct: with every % doubled (a file name pattern: %% is a %). */
static void sbatch_word(char *buf, size_t *len, size_t size, const char *w, int pct) {
  int plain = *w && strspn(w, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789"
                              "._/:=,+@-") == strlen(w);
  if (*len + 1 >= size) return;
  if (!plain) buf[(*len)++] = '"';
  for (; *w && *len + 4 < size; w++) {
    if (!plain && (*w == '"' || *w == '\\')) buf[(*len)++] = '\\';
    if (pct && *w == '%') buf[(*len)++] = '%';
    buf[(*len)++] = *w;
  }
  if (!plain && *len + 1 < size) buf[(*len)++] = '"';
  buf[*len] = '\0';
}

/* Splits --sbatch's text into words (blanks separate; '...' and "..." group, as a shell and
 * sbatch do) and appends them as one #SBATCH line to buf.  0, or 2 after one line. */
static int sbatch_extra(const char *text, char *buf, size_t *len, size_t size) {
  if (has_control(text)) {
    fprintf(stderr, "haff sweep: --sbatch: a control character (newline, tab...): not an #SBATCH "
                    "line\n");
    return 2;
  }
  char word[1024];
  int nw = 0;
  const char *p = text;
  *len += (size_t)snprintf(buf + *len, size - *len, "#SBATCH");
  for (;;) {
    while (*p == ' ') p++;
    if (!*p) break;
    size_t k = 0;
    char q = 0;
    for (; *p && (q || *p != ' '); p++) {
      if (q && *p == q) {
        q = 0;
      } else if (!q && (*p == '\'' || *p == '"')) {
        q = *p;
      } else if (k + 1 < sizeof word) {
        word[k++] = *p;
      }
    }
    word[k] = '\0';
    if (q) {
      fprintf(stderr, "haff sweep: --sbatch '%s': an unclosed quote\n", text);
      return 2;
    }
    if (nw == 0 && word[0] != '-') {
      fprintf(stderr, "haff sweep: --sbatch '%s': sbatch options begin with '-'\n", text);
      return 2;
    }
    if (!strcmp(word, "-a") || !strncmp(word, "--array", 7) || !strncmp(word, "--wrap", 6) ||
        (word[0] == '-' && word[1] == 'a' && isdigit((unsigned char)word[2]))) {
      fprintf(stderr, "haff sweep: --sbatch: '%s': the job array and its script are haff's\n",
              word);
      return 2;
    }
    *len += (size_t)snprintf(buf + *len, size - *len, " ");
    sbatch_word(buf, len, size, word, 0);
    nw++;
  }
  if (nw == 0) {
    fprintf(stderr, "haff sweep: --sbatch: no options\n");
    return 2;
  }
  *len += (size_t)snprintf(buf + *len, size - *len, "\n");
  return 0;
}

/* The study folder dir (absolute) can go into #SBATCH --output and the scripts' comments: 0,
 * or 2 after one line (a control byte, which no quoting keeps on its line). */
static int slurm_dir_ok(const char *dir) {
  if (!has_control(dir)) return 0;
  fprintf(stderr,
          "haff sweep: --slurm: the study folder's path holds a control character (a newline, "
          "a tab...), which no #SBATCH line can quote: give a plain -o DIR\n");
  return 2;
}

/* Runs cmd (a shell line) and reads the job id sbatch --parsable prints; 0 or -1. */
static int submit(const char *cmd, char *id, size_t size) {
  FILE *p = popen(cmd, "r");
  if (!p) return -1;
  char line[256] = "";
  if (!fgets(line, sizeof line, p)) line[0] = '\0';
  int st = pclose(p);
  line[strcspn(line, ";\n")] = '\0';
  if (st != 0 || !line[0]) return -1;
  snprintf(id, size, "%s", line);
  return 0;
}

/* Single-quotes s for the shell into buf. */
static void shq(const char *s, char *buf, size_t size) {
  size_t k = 0;
  if (size < 3) return;
  buf[k++] = '\'';
  for (; *s && k + 5 < size; s++) {
    if (*s == '\'') {
      memcpy(buf + k, "'\\''", 4);
      k += 4;
    } else {
      buf[k++] = *s;
    }
  }
  buf[k++] = '\'';
  buf[k] = '\0';
}

/* Writes and submits a job array over the points list[0..m) and a merge job after it. */
static int slurm_submit(const study *st, const int *list, int m, const slurm_opts *so,
                        double progress, int quiet) {
  if (slurm_dir_ok(st->dir)) return 2;
  char exe[PATH_MAX], qexe[PATH_MAX * 2], qdir[PATH_MAX * 2];
  self_exe(exe, sizeof exe);
  shq(exe, qexe, sizeof qexe);
  shq(st->dir, qdir, sizeof qdir);
  int sub = 1; /* the submission's number K: slurm/todo-K.txt, array-K.sh, merge-K.sh */
  char todo[PATH_MAX + 64], arr[PATH_MAX + 64], mrg[PATH_MAX + 64];
  for (;; sub++) {
    snprintf(todo, sizeof todo, "%s/slurm/todo-%d.txt", st->dir, sub);
    if (access(todo, F_OK) != 0) break;
  }
  snprintf(arr, sizeof arr, "%s/slurm/array-%d.sh", st->dir, sub);
  snprintf(mrg, sizeof mrg, "%s/slurm/merge-%d.sh", st->dir, sub);
  size_t cap = (size_t)m * 12 + 16, len = 0;
  char *t = malloc(cap);
  if (!t) return 1;
  for (int k = 0; k < m; k++) len += (size_t)snprintf(t + len, cap - len, "%d\n", list[k]);
  int rc = write_atomic(todo, t);
  free(t);
  int chunk = so->chunk > 0 ? so->chunk : 1;
  int tasks = (m + chunk - 1) / chunk;
  char opt[8192] = "";
  size_t ol = 0; /* the options checked free of blanks and quotes */
  if (so->time) ol += (size_t)snprintf(opt + ol, sizeof opt - ol, "#SBATCH --time=%s\n", so->time);
  if (so->partition)
    ol += (size_t)snprintf(opt + ol, sizeof opt - ol, "#SBATCH --partition=%s\n", so->partition);
  if (so->account)
    ol += (size_t)snprintf(opt + ol, sizeof opt - ol, "#SBATCH --account=%s\n", so->account);
  if (so->sbatch && (rc = sbatch_extra(so->sbatch, opt, &ol, sizeof opt))) return rc;
  /* #SBATCH --output=DIR/logs/...: quoted for sbatch, DIR's % doubled */
  char out_arr[PATH_MAX * 2 + 64], out_mrg[PATH_MAX * 2 + 64], w[PATH_MAX + 64];
  size_t la = 0, lm = 0;
  snprintf(w, sizeof w, "--output=%s/logs/", st->dir);
  sbatch_word(out_arr, &la, sizeof out_arr, w, 1);
  sbatch_word(out_mrg, &lm, sizeof out_mrg, w, 1);
  if (out_arr[la - 1] == '"') la--, lm--; /* the patterns inside the quotes */
  snprintf(out_arr + la, sizeof out_arr - la, "slurm-%%A_%%a.out%s", out_arr[0] == '"' ? "\"" : "");
  snprintf(out_mrg + lm, sizeof out_mrg - lm, "slurm-merge-%%j.out%s",
           out_mrg[0] == '"' ? "\"" : "");
  char script[16 * PATH_MAX];
  char qtodo[PATH_MAX * 2];
  shq(todo, qtodo, sizeof qtodo);
  snprintf(script, sizeof script,
           "#!/bin/sh\n"
           "# haff sweep: points of %s/slurm/todo-%d.txt, %d per task (written by haff sweep)\n"
           "#SBATCH --job-name=haff-sweep\n"
           "#SBATCH --array=0-%d\n"
           "#SBATCH --ntasks=1\n"
           "#SBATCH %s\n"
           "%s"
           "# srun: a job step, which `scancel --signal=TERM` and the time limit's SIGTERM reach\n"
           "# (haff checkpoints, marks the run interrupted; haff sweep --resume goes on)\n"
           "exec srun --ntasks=1 %s sweep --task %s %s --chunk %d --progress %g\n",
           st->dir, sub, chunk, tasks - 1, out_arr, opt, qexe, qdir, qtodo, chunk, progress);
  if (!rc) rc = write_atomic(arr, script);
  snprintf(script, sizeof script,
           "#!/bin/sh\n"
           "# haff sweep: merges the points of %s into study.db once the array has ended well\n"
           "#SBATCH --job-name=haff-merge\n"
           "#SBATCH --ntasks=1\n"
           "#SBATCH %s\n"
           "%s"
           "exec %s sweep --merge %s%s\n",
           st->dir, out_mrg, opt, qexe, qdir, so->drop ? " --drop-points" : "");
  if (!rc) rc = write_atomic(mrg, script);
  if (rc) {
    fprintf(stderr, "haff sweep: %s/slurm: cannot write the job scripts: %s\n", st->dir,
            strerror(errno));
    return 1;
  }
  chmod(arr, 0755);
  chmod(mrg, 0755);
  char cmd[3 * PATH_MAX], qarr[PATH_MAX * 2], qmrg[PATH_MAX * 2], job[64], mjob[64];
  shq(arr, qarr, sizeof qarr);
  shq(mrg, qmrg, sizeof qmrg);
  if (so->dry) { /* written, not submitted: the scripts' paths on stdout */
    printf("%s\t%s\n", arr, mrg);
    if (!quiet)
      fprintf(stderr,
              "haff sweep: --dry-run: wrote %s (%d tasks, %d points) and %s; nothing "
              "submitted (by hand: sbatch --parsable %s, then sbatch --dependency=afterok:JOB "
              "%s)\n",
              arr, tasks, m, mrg, qarr, qmrg);
    return 0;
  }
  snprintf(cmd, sizeof cmd, "sbatch --parsable %s", qarr);
  if (submit(cmd, job, sizeof job)) {
    fprintf(stderr, "haff sweep: sbatch %s failed (is Slurm there?)\n", arr);
    return 1;
  }
  snprintf(cmd, sizeof cmd, "sbatch --parsable --dependency=afterok:%s %s", job, qmrg);
  if (submit(cmd, mjob, sizeof mjob)) {
    fprintf(stderr, "haff sweep: sbatch %s failed; the array %s is submitted\n", mrg, job);
    return 1;
  }
  printf("%s\t%s\n", job, mjob);
  if (!quiet)
    fprintf(stderr,
            "haff sweep: submitted job array %s (%d tasks, %d points) and merge job %s "
            "(afterok); haff sweep --status %s\n",
            job, tasks, m, mjob, st->dir);
  return 0;
}

/* --task DIR TODO: the points of this array task ($SLURM_ARRAY_TASK_ID) from TODO. */
static int run_task(const study *st, const char *todo, int chunk, double progress, int quiet) {
  const char *tid = getenv("SLURM_ARRAY_TASK_ID");
  char *end;
  long task = tid ? strtol(tid, &end, 10) : -1;
  if (!tid || *end || task < 0) {
    fprintf(stderr, "haff sweep: --task: SLURM_ARRAY_TASK_ID is not set to a task number\n");
    return 2;
  }
  FILE *f = fopen(todo, "r");
  if (!f) {
    fprintf(stderr, "haff sweep: %s: %s\n", todo, strerror(errno));
    return 2;
  }
  int list[4096], m = 0, v;
  long idx = 0;
  while (fscanf(f, "%d", &v) == 1) {
    if (idx >= task * (long)chunk && idx < (task + 1) * (long)chunk && m < 4096 && v >= 0 &&
        v < st->n)
      list[m++] = v;
    idx++;
  }
  fclose(f);
  if (m == 0) {
    fprintf(stderr, "haff sweep: task %ld: no points in %s\n", task, todo);
    return 2;
  }
  return run_points(st, list, m, 1, progress, quiet);
}

/* ------------------------------------------------------------------------------------------ */

/* The options of haff sweep. */
typedef struct sweep_args {
  const char *out, *status_dir, *resume_dir, *merge_dir, *task_dir; /* -o, --status ... --task */
  slurm_opts so;                     /* --time, --partition, --account, --sbatch, --chunk */
  int jobs, slurm, dry, quiet, drop; /* --jobs, --slurm, --dry-run, --quiet, --drop-points */
  double progress;                   /* --progress S [60] */
} sweep_args;

static const hd_optdef sweep_opts[] = {
    {.name = "o",
     .letter = 'o',
     .kind = HD_ARG_PATH,
     .off = offsetof(sweep_args, out),
     .flags = HD_OPTF_SHORT | HD_OPTF_OUTPUT,
     .meta = "DIR",
     .help = "the study's folder [SWEEP's name without .ini, in the current folder]"},
    HD_OPT_INT("jobs", 'j', sweep_args, jobs, 1, 4096, 0, "N", "points run at once, locally [1]"),
    HD_OPT_FLAG("slurm", 0, sweep_args, slurm, "a Slurm job array and a merge job, submitted"),
    HD_OPT_PATH("status", 0, sweep_args, status_dir, 0, "DIR", "lists each point's state"),
    HD_OPT_PATH("resume", 0, sweep_args, resume_dir, 0, "DIR",
                "resumes or reruns the points not done"),
    HD_OPT_PATH("merge", 0, sweep_args, merge_dir, 0, "DIR", "merges the points into DIR/study.db"),
    HD_OPT_PATH("task", 0, sweep_args, task_dir, 0, "DIR",
                "DIR LIST: one Slurm task's points (the call in the array script)"),
    HD_OPT_INT("chunk", 0, sweep_args, so.chunk, 1, 4096, 0, "C", "points per Slurm task [1]"),
    HD_OPT_STR("time", 0, sweep_args, so.time, "T", "sbatch --time"),
    HD_OPT_STR("partition", 0, sweep_args, so.partition, "P", "sbatch --partition"),
    HD_OPT_STR("account", 0, sweep_args, so.account, "A", "sbatch --account"),
    HD_OPT_STR("sbatch", 0, sweep_args, so.sbatch, "'OPTIONS'",
               "more sbatch options for every job (an #SBATCH line of the scripts)"),
    HD_OPT_FLAG("drop-points", 0, sweep_args, drop,
                "removes the points' databases once study.db is merged and verified"),
    HD_OPT_DBL("progress", 0, sweep_args, progress, 0, 1e9, 0, "S",
               "a progress line of each run every S seconds [60] (0: none)"),
    HD_OPT_FLAG("dry-run", 0, sweep_args, dry,
                "prints the manifest, runs nothing; with --slurm: writes the study folder and "
                "the job scripts, submits nothing"),
    HD_OPT_FLAG("quiet", 'q', sweep_args, quiet, "no progress, no closing lines"),
    {0}};

const hd_optspec hd_cmd_sweep_spec = {HD_OPT_SPEC("sweep", sweep_opts, 0, 0, 1, "one sweep file"),
                                      .head = sweep_usage};

/* Runs the points of st that are not done (locally, jobs at a time, or as a Slurm array with
 * so) and merges them; a study done and merged is left as it is.  Returns the exit code. */
static int sweep_unfinished(study *st, int slurm, const slurm_opts *so, int jobs, double progress,
                            int quiet) {
  int rc = 0;
  int64_t merged = 0;
  int *list = malloc((size_t)st->n * sizeof *list);
  int m = list ? unfinished(st, list, 0) : 0;
  char out_db[PATH_MAX + 32];
  snprintf(out_db, sizeof out_db, "%s/study.db", st->dir);
  if (!list) {
    rc = 1;
  } else if (m == 0 && access(out_db, F_OK) == 0) {
    if (!quiet)
      fprintf(stderr, "haff sweep: %s: every point is done and merged: nothing to do\n", st->dir);
  } else if (slurm) {
    if (m == 0) { /* done, not merged: a merge job alone would do; merge here */
      rc = so->dry ? 0 : study_merge(st, quiet, &merged);
      if (!rc && so->drop && !so->dry) rc = drop_points(st, merged, quiet);
    } else {
      rc = slurm_submit(st, list, m, so, progress, quiet);
    }
  } else {
    if (!quiet && m)
      fprintf(stderr, "haff sweep: %s: %d of %d points to run, %d at a time\n", st->dir, m, st->n,
              jobs);
    rc = run_points(st, list, m, jobs, progress, quiet);
    if (!rc) rc = study_merge(st, quiet, &merged);
    if (!rc && so->drop) rc = drop_points(st, merged, quiet);
    if (rc == 1 && !merged)
      fprintf(stderr,
              "haff sweep: not every point is done: haff sweep --status %s, then "
              "--resume %s\n",
              st->dir, st->dir);
  }
  free(list);
  return rc;
}

/* The checks between sweep's options; *modes: how many of --status, --resume, --merge, --task.
 * Returns 0 or 2 after one line. */
static int sweep_check(const sweep_args *a, int *modes) {
  *modes = !!a->status_dir + !!a->resume_dir + !!a->merge_dir + !!a->task_dir;
  if (*modes > 1) {
    fprintf(stderr, "haff sweep: give one of --status, --resume, --merge, --task\n");
    return 2;
  }
  const char *given[3] = {a->so.time, a->so.partition, a->so.account};
  for (int k = 0; k < 3; k++)
    if (given[k] && (!*given[k] || strpbrk(given[k], "\n\t'\"\\ ;$`"))) {
      fprintf(stderr, "haff sweep: '%s': not a Slurm option value (empty, blanks or quotes)\n",
              given[k]);
      return 2;
    }
  if (!a->slurm && (a->so.time || a->so.partition || a->so.account || a->so.sbatch)) {
    fprintf(stderr, "haff sweep: --time, --partition, --account and --sbatch go with --slurm\n");
    return 2;
  }
  if (a->dry && (a->status_dir || a->merge_dir || a->task_dir || (a->resume_dir && !a->slurm))) {
    fprintf(stderr, "haff sweep: --dry-run goes with a sweep file, or with --resume --slurm\n");
    return 2;
  }
  if (a->drop && (a->status_dir || a->task_dir)) {
    fprintf(stderr, "haff sweep: --drop-points goes with a sweep, --resume or --merge\n");
    return 2;
  }
  return 0;
}

int hd_cmd_sweep(int argc, char **argv) {
  sweep_args a = {.so = {.chunk = 1}, .jobs = 1, .progress = 60};
  hd_optres res;
  int rc = hd_opt_parse(&hd_cmd_sweep_spec, argc, argv, &a, &res);
  if (rc) return rc < 0 ? 0 : rc;
  const char *out = a.out, *status_dir = a.status_dir, *resume_dir = a.resume_dir,
             *merge_dir = a.merge_dir, *task_dir = a.task_dir;
  slurm_opts so = a.so;
  so.dry = a.dry;
  so.drop = a.drop;
  int jobs = a.jobs, slurm = a.slurm, dry = a.dry, quiet = a.quiet;
  double progress = a.progress;
  int modes;
  if ((rc = sweep_check(&a, &modes))) return rc;
  study st;
  memset(&st, 0, sizeof st);
  if (modes) {
    if (res.npos != (task_dir ? 1 : 0)) {
      fprintf(stderr, "haff sweep: unexpected argument '%s' (haff sweep --help)\n",
              res.npos ? res.pos[0] : "");
      return 2;
    }
    const char *dir = status_dir   ? status_dir
                      : resume_dir ? resume_dir
                      : merge_dir  ? merge_dir
                                   : task_dir;
    if ((rc = manifest_read(&st, dir))) return rc;
    if (status_dir) {
      lock_open(&st, 1); /* to see the points that other sweeps run (none: no lock file) */
      rc = study_status(&st);
    } else if (merge_dir) {
      int64_t merged = 0;
      rc = study_lock(&st, "--merge");
      if (!rc) rc = study_merge(&st, quiet, &merged);
      if (!rc && a.drop) rc = drop_points(&st, merged, quiet);
    } else if (task_dir) {
      /* a Slurm task: its points' locks only (the tasks of an array run side by side) */
      if (lock_open(&st, 0)) {
        fprintf(stderr, "haff sweep: %s/sweep.lock: %s\n", st.dir, strerror(errno));
        rc = 1;
      } else {
        rc = run_task(&st, res.pos[0], so.chunk, progress, quiet);
      }
    } else {
      rc = study_lock(&st, "--resume");
    }
  } else {
    if (res.npos != 1) {
      fprintf(stderr, "haff sweep: expected one sweep file (haff sweep --help)\n");
      return 2;
    }
    sweep sw;
    rc = sweep_read(&sw, res.pos[0]);
    if (rc) {
      sweep_free(&sw);
      return rc;
    }
    if (!rc) rc = make_points(&sw, &st.p, &st.n);
    if (!rc) snprintf(st.scene, sizeof st.scene, "%s", sw.scene);
    sweep_free(&sw);
    if (rc) return rc;
    if (dry && !slurm) {
      char *t = manifest_text(&st);
      if (t) fputs(t, stdout);
      free(t);
      study_free(&st);
      return 0;
    }
    char dir[PATH_MAX];
    if (out) {
      snprintf(dir, sizeof dir, "%s", out);
    } else {
      const char *base = strrchr(res.pos[0], '/');
      snprintf(dir, sizeof dir, "%s", base ? base + 1 : res.pos[0]);
      char *dot = strrchr(dir, '.');
      if (dot && dot != dir) *dot = '\0';
    }
    rc = slurm ? slurm_dir_ok(dir) : 0;
    if (!rc) rc = study_create(&st, dir, res.pos[0]);
    if (!rc) resume_dir = dir; /* then as --resume: what is not done yet */
  }
  if (!rc && resume_dir) rc = sweep_unfinished(&st, slurm, &so, jobs, progress, quiet);
  study_free(&st);
  return rc;
}
