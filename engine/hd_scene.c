/* hd_scene: scene files (INI via libinih), `--set SECTION.KEY=VALUE` overrides, the canonical
 * text of a scene, and [init] state CSV files.
 *
 * Line numbers: libinih's handler is not told the line, so the scene is fed to ini_parse_stream
 * through our own reader, which hands over one physical line per call and counts them; the
 * handler then knows the line it is called for.  The reader also
 *   - strips leading blanks, so that an indented key is never taken for a libinih "multi-line
 *     continuation" of the previous key;
 *   - checks every `[section]` header itself (libinih does not report headers to the handler),
 *     so that an unknown or empty section is still an error, and text after `]` is refused;
 *   - refuses lines longer than HD_SCENE_MAX_LINE.
 * Every key is remembered with where it was set (file line or --set), so that checks made after
 * the whole scene is read still name the right line. */
#include "hd_scene.h"

#include "hd_body.h"
#include "rods.h"

#include <errno.h>
#include <float.h>
#include <ini.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

enum { S_SYSTEM, S_DIMERS, S_DISKS, S_WALLS, S_INIT, S_RUN, S_LOG, S_RODS, N_SEC };
static const char *const sec_name[N_SEC] = {"system", "dimers", "disks", "walls",
                                            "init",   "run",    "log",   "rods"};

enum {
  K_BOX,
  K_AREA,
  K_SEED,
  K_DCOUNT,
  K_DD,
  K_DA,
  K_DM,
  K_DALPHA,
  K_SCOUNT,
  K_SSIGMA,
  K_SMASS,
  K_SALPHA,
  K_SALPHAD,
  K_WSIDES,
  K_WALPHA,
  K_TEMP,
  K_PLACE,
  K_STATE,
  K_STIME,
  K_SEVENTS,
  K_SCPD,
  K_VERIFY,
  K_CKPT,
  K_LCOLL,
  K_LSAMPLES,
  K_LVEL,
  K_LFRAMES,
  K_LFRAMEST,
  K_LFRAMESMB,
  K_LVELT,
  K_RCOUNT,
  K_RGAMMA,
  K_RNMOD,
  K_RMODEL,
  K_REPS,
  K_RDAMP,
  K_RTC,
  K_RTEMP,
  K_RTABLE,
  K_RBATHS,
  K_RSTEP,
  N_KEY
};
static const struct {
  int sec;
  const char *name;
} key_def[N_KEY] = {
    {S_SYSTEM, "box"},
    {S_SYSTEM, "area_fraction"},
    {S_SYSTEM, "seed"},
    {S_DIMERS, "count"},
    {S_DIMERS, "d"},
    {S_DIMERS, "a"},
    {S_DIMERS, "m"},
    {S_DIMERS, "alpha"},
    {S_DISKS, "count"},
    {S_DISKS, "sigma"},
    {S_DISKS, "mass"},
    {S_DISKS, "alpha"},
    {S_DISKS, "alpha_dimer"},
    {S_WALLS, "sides"},
    {S_WALLS, "alpha"},
    {S_INIT, "temperature"},
    {S_INIT, "placement"},
    {S_INIT, "state"},
    {S_RUN, "stop_time"},
    {S_RUN, "stop_events"},
    {S_RUN, "stop_cpd"},
    {S_RUN, "verify"},
    {S_RUN, "checkpoint_every"},
    {S_LOG, "collisions"},
    {S_LOG, "samples_every"},
    {S_LOG, "velocities_at"},
    {S_LOG, "frames_every"},
    {S_LOG, "frames_every_time"},
    {S_LOG, "frames_max_mb"},
    {S_LOG, "velocities_at_time"},
    {S_RODS, "count"},
    {S_RODS, "gamma"},
    {S_RODS, "nmod"},
    {S_RODS, "model"},
    {S_RODS, "eps"},
    {S_RODS, "damping"},
    {S_RODS, "tc"},
    {S_RODS, "temperature"},
    {S_RODS, "table"},
    {S_RODS, "baths"},
    {S_RODS, "eps_step"},
};

static const char *const wall_name[4] = {"left", "right", "bottom", "top"};

/* Where something was set: a line of the file, or the over-th --set (1-based); 0/0 = nowhere. */
typedef struct loc {
  long line;
  int over;
} loc;

typedef struct ctx {
  hd_scene *sc;
  const char *name;        /* file name for messages */
  const char *const *over; /* the overrides */
  int n_over;              /* how many */
  hd_error *err;
  int failed;                  /* an error has been set: stop */
  int code;                    /* its hd_status */
  loc cur;                     /* where the key being handled comes from */
  loc key_at[N_KEY];           /* where each key was set */
  char key_val[N_KEY][96];     /* its value as written (shortened), for later messages */
  int present[N_SEC];          /* the section appears (header or --set) */
  loc sec_at[N_SEC];           /* its first header */
  const char *p, *end;         /* reader: rest of the text */
  long lineno;                 /* reader: lines handed out */
  char state_rel[HD_PATH_MAX]; /* `state` as written */
  int stored; /* the canonical text of a run (hd_scene_load_stored): its state file not read */
} ctx;

static int is_set(loc l) {
  return l.line > 0 || l.over > 0;
}

static void where(const ctx *c, loc l, char *buf, size_t n) {
  if (l.over)
    snprintf(buf, n, "--set %s", c->over[l.over - 1]);
  else
    snprintf(buf, n, "%s:%ld", c->name, l.line);
}

/* Records a failure: sets c->err and stops the parse.  Returns code. */
static __attribute__((format(printf, 3, 4))) int cfail(ctx *c, int code, const char *fmt, ...) {
  char msg[sizeof c->err->msg];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  c->failed = 1;
  c->code = code;
  return hd_error_set(c->err, code, "%s", msg);
}

/* Shortens a value for a message. */
static void shorten(const char *v, char *buf, size_t n) {
  size_t len = strlen(v);
  if (len < n) {
    memcpy(buf, v, len + 1);
  } else {
    memcpy(buf, v, n - 4);
    memcpy(buf + n - 4, "...", 4);
  }
}

/* "WHERE: [sec] key = value: why" (key < 0: "WHERE: [sec]: why"; val NULL: "[sec] key: why"). */
static __attribute__((format(printf, 7, 8))) int
fail(ctx *c, int code, loc l, int sec, const char *key, const char *val, const char *fmt, ...) {
  char at[600], why[400], v[96], what[200];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(why, sizeof why, fmt, ap);
  va_end(ap);
  where(c, l, at, sizeof at);
  if (!key)
    snprintf(what, sizeof what, "[%s]", sec >= 0 ? sec_name[sec] : "?");
  else if (!val)
    snprintf(what, sizeof what, "[%s] %s", sec_name[sec], key);
  else {
    shorten(val, v, sizeof v);
    snprintf(what, sizeof what, "[%s] %s = %s", sec_name[sec], key, v);
  }
  return cfail(c, code, "%s: %s: %s", at, what, why);
}

/* Error about key k where it was set, with its value. */
#define FAIL_KEY(c, k, ...)                                                                        \
  fail((c), HD_EINPUT, (c)->key_at[k], key_def[k].sec, key_def[k].name, (c)->key_val[k],           \
       __VA_ARGS__)

/* ---- value parsing ------------------------------------------------------------------------ */

/* A finite number that is the whole of s (no hex, no nan/inf). 1 on success. */
static int parse_num(const char *s, double *x) {
  if (!*s || strpbrk(s, "xX")) return 0;
  char *e;
  errno = 0;
  double v = strtod(s, &e);
  if (e == s || *e || !isfinite(v)) return 0;
  *x = v;
  return 1;
}

/* Why s is not a finite number (for messages). */
static const char *num_why(const char *s) {
  if (!*s) return "missing value: expected a number";
  double v = strtod(s, NULL);
  if (!isfinite(v)) return "must be a finite number";
  return "not a number";
}

/* A whole number in [lo, hi]; else an error on key k. */
static int get_whole(ctx *c, int k, const char *s, double lo, double hi, double *x) {
  double v;
  if (!parse_num(s, &v)) return FAIL_KEY(c, k, "%s", num_why(s));
  if (v != floor(v)) return FAIL_KEY(c, k, "must be a whole number");
  if (v < lo || v > hi) return FAIL_KEY(c, k, "must be in [%.17g, %.17g]", lo, hi);
  *x = v;
  return HD_OK;
}

/* A number checked by kind: 'p' > 0, 'n' >= 0, 'u' in [0, 1]. */
static int get_num(ctx *c, int k, const char *s, char kind, double *x) {
  double v;
  if (!parse_num(s, &v)) return FAIL_KEY(c, k, "%s", num_why(s));
  if (kind == 'p' && !(v > 0)) return FAIL_KEY(c, k, "must be > 0");
  if (kind == 'n' && !(v >= 0)) return FAIL_KEY(c, k, "must be >= 0");
  if (kind == 'u' && !(v >= 0 && v <= 1)) return FAIL_KEY(c, k, "must be in [0, 1]");
  *x = v;
  return HD_OK;
}

/* Splits s at blanks into at most max tokens copied to tok (each < 64 chars). Returns the count,
 * or -1 if there are more than max or one is too long. */
static int split(const char *s, char tok[][64], int max) {
  int n = 0;
  while (*s) {
    while (*s == ' ' || *s == '\t') s++;
    if (!*s) break;
    size_t len = strcspn(s, " \t");
    if (n == max || len >= 64) return -1;
    memcpy(tok[n], s, len);
    tok[n][len] = '\0';
    n++;
    s += len;
  }
  return n;
}

static int set_box(ctx *c, const char *v) {
  char tok[2][64];
  double lx, ly;
  if (split(v, tok, 2) != 2 || !parse_num(tok[0], &lx) || !parse_num(tok[1], &ly))
    return FAIL_KEY(c, K_BOX, "expected two finite numbers Lx Ly");
  if (!(lx > 0 && ly > 0)) return FAIL_KEY(c, K_BOX, "box edges must be > 0");
  c->sc->box_x = lx;
  c->sc->box_y = ly;
  return HD_OK;
}

static int set_seed(ctx *c, const char *v) {
  char *e;
  if (!*v || *v == '-' || *v == '+' || strpbrk(v, " \t"))
    return FAIL_KEY(c, K_SEED, "expected a whole number >= 0");
  errno = 0;
  unsigned long long s = strtoull(v, &e, 10);
  if (*e || e == v) return FAIL_KEY(c, K_SEED, "expected a whole number >= 0");
  if (errno == ERANGE) return FAIL_KEY(c, K_SEED, "too large (max %llu)", ULLONG_MAX);
  c->sc->seed = s;
  return HD_OK;
}

static int set_sides(ctx *c, const char *v) {
  char tok[5][64];
  int n = split(v, tok, 4);
  if (n < 0) return FAIL_KEY(c, K_WSIDES, "at most the four sides left right bottom top");
  if (n == 0) return FAIL_KEY(c, K_WSIDES, "missing value: list some of left right bottom top");
  unsigned w = 0;
  for (int i = 0; i < n; i++) {
    int j = 0;
    while (j < 4 && strcmp(tok[i], wall_name[j])) j++;
    if (j == 4) return FAIL_KEY(c, K_WSIDES, "unknown side '%s' (left right bottom top)", tok[i]);
    if (w & (1u << j)) return FAIL_KEY(c, K_WSIDES, "side '%s' repeated", tok[i]);
    w |= 1u << j;
  }
  /* a wall closes its axis: past it there is no periodic image, so the opposite edge must be
   * closed too (a lone wall let bodies wrap through the open edge to land behind it) */
  if (!(w & HD_WALL_LEFT) != !(w & HD_WALL_RIGHT))
    return FAIL_KEY(c, K_WSIDES, "'%s' needs '%s' too: walls close an axis at both edges",
                    w & HD_WALL_LEFT ? "left" : "right", w & HD_WALL_LEFT ? "right" : "left");
  if (!(w & HD_WALL_BOTTOM) != !(w & HD_WALL_TOP))
    return FAIL_KEY(c, K_WSIDES, "'%s' needs '%s' too: walls close an axis at both edges",
                    w & HD_WALL_BOTTOM ? "bottom" : "top", w & HD_WALL_BOTTOM ? "top" : "bottom");
  c->sc->walls = w;
  return HD_OK;
}

static int set_bool(ctx *c, int k, const char *v, int *out) {
  static const char *const yes[] = {"1", "true", "yes", "on"}, *const no[] = {"0", "false", "no",
                                                                              "off"};
  for (int i = 0; i < 4; i++) {
    if (!strcmp(v, yes[i])) return *out = 1, HD_OK;
    if (!strcmp(v, no[i])) return *out = 0, HD_OK;
  }
  return FAIL_KEY(c, k, "expected 1 or 0 (true/false, yes/no, on/off)");
}

static int set_collisions(ctx *c, const char *v) {
  hd_scene *sc = c->sc;
  if (!strcmp(v, "all")) {
    sc->log_collisions = HD_LOG_ALL;
    sc->log_every = 1;
    return HD_OK;
  }
  if (!strcmp(v, "none")) {
    sc->log_collisions = HD_LOG_NONE;
    sc->log_every = 1;
    return HD_OK;
  }
  char tok[3][64];
  double n;
  if (split(v, tok, 2) != 2 || strcmp(tok[0], "every"))
    return FAIL_KEY(c, K_LCOLL, "expected all, none or every N");
  if (!parse_num(tok[1], &n) || n != floor(n) || n < 1 || n > (double)LONG_MAX / 2)
    return FAIL_KEY(c, K_LCOLL, "every N needs a whole number N >= 1");
  sc->log_collisions = HD_LOG_EVERY;
  sc->log_every = (long)n;
  return HD_OK;
}

/* `velocities_at` (k = K_LVEL, cpd) or `velocities_at_time` (k = K_LVELT, times): the two
 * share the list, so only one of them may be given. */
static int set_vel_at(ctx *c, int k, const char *v) {
  hd_scene *sc = c->sc;
  int other = k == K_LVEL ? K_LVELT : K_LVEL;
  const char *unit = k == K_LVEL ? "cpd values" : "times";
  if (is_set(c->key_at[other]))
    return FAIL_KEY(c, k,
                    "cannot be used together with %s (one list of snapshots, in cpd or in "
                    "time)",
                    key_def[other].name);
  int n = 0;
  const char *s = v;
  while (*s) {
    while (*s == ' ' || *s == '\t') s++;
    if (!*s) break;
    size_t len = strcspn(s, " \t");
    char t[64];
    double x;
    if (len >= sizeof t) return FAIL_KEY(c, k, "not a number: '%.20s...'", s);
    memcpy(t, s, len);
    t[len] = '\0';
    s += len;
    if (!parse_num(t, &x)) return FAIL_KEY(c, k, "'%s': %s", t, num_why(t));
    if (x < 0) return FAIL_KEY(c, k, "'%s': %s must be >= 0", t, unit);
    if (n == HD_MAX_VEL_AT)
      return FAIL_KEY(c, k,
                      "more than %d values (snapshots for a movie or a trajectory: "
                      "frames_every or frames_every_time)",
                      HD_MAX_VEL_AT);
    if (n > 0 && !(x > sc->velocities_at[n - 1]))
      return FAIL_KEY(c, k, "'%s': values must be strictly ascending", t);
    sc->velocities_at[n++] = x;
  }
  if (n == 0) return FAIL_KEY(c, k, "missing value: list %s", unit);
  sc->n_velocities_at = n;
  sc->velocities_in_time = k == K_LVELT;
  return HD_OK;
}

/* A snapshot that cannot be taken is refused at set-up: a time past stop_time, a cpd past
 * stop_cpd (a list in the other unit than the stop cannot be checked before the run; the run's
 * message says what it did not take). */
static int check_vel_at(ctx *c) {
  const hd_scene *sc = c->sc;
  if (sc->n_velocities_at == 0) return HD_OK;
  int k = sc->velocities_in_time ? K_LVELT : K_LVEL;
  double last = sc->velocities_at[sc->n_velocities_at - 1];
  double stop = sc->velocities_in_time ? sc->stop_time : sc->stop_cpd;
  if (stop > 0 && last > stop)
    return FAIL_KEY(c, k, "%.17g is past %s = %.17g: that snapshot would never be taken", last,
                    sc->velocities_in_time ? "stop_time" : "stop_cpd", stop);
  return HD_OK;
}

/* Parses the value of key k into the scene. */
static int set_value(ctx *c, int k, const char *v) {
  hd_scene *sc = c->sc;
  double x;
  int rc = HD_OK;
  switch (k) {
  case K_BOX:
    return set_box(c, v);
  case K_AREA:
    if (!parse_num(v, &x)) return FAIL_KEY(c, k, "%s", num_why(v));
    if (!(x > 0 && x < HD_MAX_AREA_FRACTION))
      return FAIL_KEY(c, k, "must be in (0, %g)", HD_MAX_AREA_FRACTION);
    sc->area_fraction = x;
    return HD_OK;
  case K_SEED:
    return set_seed(c, v);
  case K_DCOUNT:
  case K_SCOUNT:
    if ((rc = get_whole(c, k, v, 0, (double)HD_MAX_COUNT, &x))) return rc;
    *(k == K_DCOUNT ? &sc->n_dimers : &sc->n_disks) = (long)x;
    return HD_OK;
  case K_DD:
    return get_num(c, k, v, 'p', &sc->dimer_d);
  case K_DA:
    return get_num(c, k, v, 'n', &sc->dimer_a);
  case K_DM:
    return get_num(c, k, v, 'p', &sc->dimer_m);
  case K_DALPHA:
    return get_num(c, k, v, 'u', &sc->dimer_alpha);
  case K_SSIGMA:
    return get_num(c, k, v, 'p', &sc->disk_sigma);
  case K_SMASS:
    return get_num(c, k, v, 'p', &sc->disk_mass);
  case K_SALPHA:
    return get_num(c, k, v, 'u', &sc->disk_alpha);
  case K_SALPHAD:
    return get_num(c, k, v, 'u', &sc->disk_alpha_dimer);
  case K_WSIDES:
    return set_sides(c, v);
  case K_WALPHA:
    return get_num(c, k, v, 'u', &sc->wall_alpha);
  case K_TEMP:
    if (!parse_num(v, &x)) return FAIL_KEY(c, k, "%s", num_why(v));
    if (x < 0) return FAIL_KEY(c, k, "must be > 0");
    sc->temperature = x; /* 0 is refused later unless a state file gives the velocities */
    return HD_OK;
  case K_PLACE:
    if (!strcmp(v, "random"))
      sc->placement = HD_PLACE_RANDOM;
    else if (!strcmp(v, "lattice"))
      sc->placement = HD_PLACE_LATTICE;
    else
      return FAIL_KEY(c, k, "expected random or lattice");
    return HD_OK;
  case K_STATE:
    if (!*v) return FAIL_KEY(c, k, "missing value: expected a CSV file name");
    if (strlen(v) >= sizeof c->state_rel) return FAIL_KEY(c, k, "file name too long");
    strcpy(c->state_rel, v);
    return HD_OK;
  case K_STIME:
    return get_num(c, k, v, 'p', &sc->stop_time);
  case K_SEVENTS:
    if ((rc = get_whole(c, k, v, 1, 9007199254740992.0, &x))) return rc;
    sc->stop_events = x;
    return HD_OK;
  case K_SCPD:
    return get_num(c, k, v, 'p', &sc->stop_cpd);
  case K_VERIFY:
    return set_bool(c, k, v, &sc->verify);
  case K_CKPT:
    return get_num(c, k, v, 'p', &sc->checkpoint_every);
  case K_LCOLL:
    return set_collisions(c, v);
  case K_LSAMPLES:
    return get_num(c, k, v, 'n', &sc->samples_every);
  case K_LVEL:
    return set_vel_at(c, k, v);
  case K_LFRAMES:
    return get_num(c, k, v, 'n', &sc->frames_every);
  case K_LFRAMEST:
    return get_num(c, k, v, 'n', &sc->frames_every_time);
  case K_LFRAMESMB:
    return get_num(c, k, v, 'p', &sc->frames_max_mb);
  case K_LVELT:
    return set_vel_at(c, k, v);
  case K_RCOUNT:
    if ((rc = get_whole(c, k, v, 2, (double)HD_MAX_COUNT, &x))) return rc;
    if (fmod(x, 2) != 0)
      return FAIL_KEY(c, k, "must be even: the rod lengths alternate round the ring");
    sc->n_rods = (long)x;
    return HD_OK;
  case K_RGAMMA:
    if ((rc = get_num(c, k, v, 0, &x))) return rc;
    if (!(x > 0 && x <= 1)) return FAIL_KEY(c, k, "must be in (0, 1]"); /* 0 and 1.2 alike */
    sc->rod_gamma = x;
    return HD_OK;
  case K_RNMOD:
    if ((rc = get_whole(c, k, v, 1, 1e9, &x))) return rc;
    sc->rod_nmod = (long)x;
    return HD_OK;
  case K_RMODEL:
    if (!strcmp(v, "stochastic"))
      sc->rod_model = 0;
    else if (!strcmp(v, "constant"))
      sc->rod_model = 1;
    else
      return FAIL_KEY(c, k, "expected stochastic or constant");
    return HD_OK;
  case K_REPS:
    return get_num(c, k, v, 'u', &sc->rod_eps);
  case K_RDAMP:
    return get_num(c, k, v, 'n', &sc->rod_damping);
  case K_RTC:
    return get_num(c, k, v, 'n', &sc->rod_tc);
  case K_RTEMP:
    return get_num(c, k, v, 'p', &sc->rod_temperature);
  case K_RTABLE:
    return set_bool(c, k, v, &sc->rod_table);
  case K_RSTEP: {
    int got = get_num(c, k, v, 'n', &sc->rod_eps_step);
    /* 0 is the sampler's default; its grid needs ~(1 + 1/gamma)/step points, at most 5e7 / 64
     * (mc/eps.c), and 1e-300 overflowed the size check and crashed the run (SIGFPE) */
    if (!got && sc->rod_eps_step != 0 && !(sc->rod_eps_step >= 1e-5 && sc->rod_eps_step <= 0.5))
      return FAIL_KEY(c, k, "must be 0 (the default step) or in [1e-5, 0.5]");
    return got;
  }
  case K_RBATHS:
    if (!strcmp(v, "mean"))
      sc->rod_unequal = 0;
    else if (!strcmp(v, "unequal"))
      sc->rod_unequal = 1;
    else
      return FAIL_KEY(c, k, "expected mean or unequal");
    return HD_OK;
  default:
    return HD_OK;
  }
}

static int find_sec(const char *s) {
  for (int i = 0; i < N_SEC; i++)
    if (!strcmp(s, sec_name[i])) return i;
  return -1;
}

static int unknown_section(ctx *c, const char *s) {
  char at[600];
  where(c, c->cur, at, sizeof at);
  return cfail(c, HD_EINPUT,
               "%s: [%.60s]: unknown section (known: system dimers disks walls init run log rods)",
               at, s);
}

static void mark_section(ctx *c, int s) {
  if (!c->present[s]) c->sec_at[s] = c->cur;
  c->present[s] = 1;
}

/* Handles `name = value` in section `section` at c->cur. */
static int handle(ctx *c, const char *section, const char *name, const char *value) {
  char at[600], v[96];
  if (!*section) {
    where(c, c->cur, at, sizeof at);
    shorten(value, v, sizeof v);
    return cfail(c, HD_EINPUT, "%s: %.60s = %s: key outside any [section]", at, name, v);
  }
  int s = find_sec(section);
  if (s < 0) return unknown_section(c, section);
  int k = 0;
  while (k < N_KEY && !(key_def[k].sec == s && !strcmp(key_def[k].name, name))) k++;
  if (k == N_KEY) {
    char known[200] = "";
    for (int j = 0; j < N_KEY; j++)
      if (key_def[j].sec == s) {
        strcat(known, " ");
        strcat(known, key_def[j].name);
      }
    char nm[64];
    shorten(name, nm, sizeof nm);
    return fail(c, HD_EINPUT, c->cur, s, nm, value, "unknown key (keys of [%s]:%s)", sec_name[s],
                known);
  }
  loc prev = c->key_at[k];
  if (!c->cur.over && prev.line > 0)
    return fail(c, HD_EINPUT, c->cur, s, name, value, "duplicate key (first set at line %ld)",
                prev.line);
  if (c->cur.over && prev.over > 0)
    return fail(c, HD_EINPUT, c->cur, s, name, value, "duplicate key (also set by --set %s)",
                c->over[prev.over - 1]);
  c->key_at[k] = c->cur;
  shorten(value, c->key_val[k], sizeof c->key_val[k]);
  /* a file's value that a --set replaces is not read: the override mends a bad line */
  for (int i = 0; !c->cur.over && i < c->n_over; i++)
    if (hd_scene_override_sets(c->over[i], sec_name[s], key_def[k].name)) return HD_OK;
  return set_value(c, k, value);
}

static int on_key(void *user, const char *section, const char *name, const char *value) {
  ctx *c = user;
  if (c->failed) return 0;
  return handle(c, section, name, value) == HD_OK;
}

/* Checks a `[section]` line (leading blanks already gone). */
static int section_line(ctx *c, const char *line) {
  const char *close = strchr(line, ']');
  char at[600];
  where(c, c->cur, at, sizeof at);
  if (!close) {
    return cfail(c, HD_EINPUT, "%s: malformed section header: no ']'", at);
  }
  const char *r = close + 1;
  while (*r == ' ' || *r == '\t') r++;
  if (*r && *r != '\n' && *r != '\r' && *r != ';' && *r != '#') {
    return cfail(c, HD_EINPUT, "%s: text after the [section] header: put each key on its own line",
                 at);
  }
  char name[64];
  size_t len = (size_t)(close - line - 1);
  if (len >= sizeof name) len = sizeof name - 1;
  memcpy(name, line + 1, len);
  name[len] = '\0';
  int s = find_sec(name);
  if (s < 0) return unknown_section(c, name);
  mark_section(c, s);
  return HD_OK;
}

/* fgets-like reader for ini_parse_stream: one physical line per call, counted. */
static char *reader(char *str, int num, void *stream) {
  ctx *c = stream;
  if (c->failed || c->p >= c->end) return NULL;
  const char *s = c->p;
  const char *nl = memchr(s, '\n', (size_t)(c->end - s));
  const char *stop = nl ? nl + 1 : c->end;
  c->p = stop;
  c->cur.line = ++c->lineno;
  c->cur.over = 0;
  if (c->lineno == 1 && stop - s >= 3 && !memcmp(s, "\xEF\xBB\xBF", 3)) s += 3;
  /* every blank libinih skips at a line's start (\r \v \f too): "\v[disks]" was parsed as a
   * section by libinih but not seen as one here, so its keys took effect while the section was
   * left out of the canonical text (and a resume ran without them) */
  while (s < stop && (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\v' || *s == '\f')) s++;
  size_t len = (size_t)(stop - s);
  size_t body = len; /* the line without its end (\n or \r\n): what HD_SCENE_MAX_LINE bounds */
  if (body > 0 && s[body - 1] == '\n') body--;
  if (body > 0 && s[body - 1] == '\r') body--;
  if (len + 1 > (size_t)num || body > HD_SCENE_MAX_LINE) {
    char at[600];
    where(c, c->cur, at, sizeof at);
    cfail(c, HD_EINPUT, "%s: line too long (max %d bytes)", at, HD_SCENE_MAX_LINE);
    return NULL;
  }
  memcpy(str, s, len);
  str[len] = '\0';
  if (str[0] == '[' && section_line(c, str)) return NULL;
  return str;
}

/* Parses the scene text (c->p .. c->end). */
static int parse_text(ctx *c) {
  int saved = ini_max_line;
  ini_max_line = HD_SCENE_MAX_LINE + 3;
  int r = ini_parse_stream(reader, c, on_key, c);
  ini_max_line = saved;
  if (c->failed) return c->code;
  if (r != 0) {
    if (r < 0) return cfail(c, HD_ENOMEM, "%s: out of memory while parsing", c->name);
    return cfail(c, HD_EINPUT,
                 "%s:%d: malformed line: expected [section], key = value or a comment", c->name, r);
  }
  return HD_OK;
}

static char *trim(char *s) {
  while (*s == ' ' || *s == '\t') s++;
  char *e = s + strlen(s);
  while (e > s && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r' || e[-1] == '\n')) *--e = '\0';
  return s;
}

/* Splits the override in buf ("SECTION.KEY=VALUE", changed in place) into its trimmed parts;
 * 0 if it has no '=' or no '.' before it. */
static int split_override(char *buf, char **sec, char **key, char **val) {
  char *eq = strchr(buf, '=');
  char *dot = eq ? memchr(buf, '.', (size_t)(eq - buf)) : NULL;
  if (!eq || !dot) return 0;
  *dot = *eq = '\0';
  *sec = trim(buf), *key = trim(dot + 1), *val = trim(eq + 1);
  return 1;
}

int hd_scene_override_sets(const char *over, const char *section, const char *key) {
  char buf[HD_SCENE_MAX_LINE + 1], *sec, *k, *val;
  if (strlen(over) > HD_SCENE_MAX_LINE) return 0;
  strcpy(buf, over);
  return split_override(buf, &sec, &k, &val) && !strcmp(sec, section) && !strcmp(k, key);
}

/* Applies override i ("SECTION.KEY=VALUE"). */
static int apply_override(ctx *c, int i) {
  char buf[HD_SCENE_MAX_LINE + 1], at[600];
  c->cur.line = 0;
  c->cur.over = i + 1;
  where(c, c->cur, at, sizeof at);
  if (strlen(c->over[i]) > HD_SCENE_MAX_LINE) {
    return cfail(c, HD_EINPUT, "--set: value too long (max %d bytes)", HD_SCENE_MAX_LINE);
  }
  strcpy(buf, c->over[i]);
  char *sec, *key, *val;
  if (!split_override(buf, &sec, &key, &val))
    return cfail(c, HD_EINPUT, "%s: expected SECTION.KEY=VALUE", at);
  int s = find_sec(sec);
  if (s < 0) return unknown_section(c, sec);
  mark_section(c, s);
  return handle(c, sec, key, val);
}

/* ---- checks of the whole ------------------------------------------------------------------- */

double hd_dimer_area(double d, double a) {
  double r = d / 2, disk = M_PI * r * r;
  if (a >= d) return 2 * disk;
  /* lens of two circles of radius r at distance a < 2r */
  double lens = 2 * r * r * acos(a / (2 * r)) - (a / 2) * sqrt(4 * r * r - a * a);
  return 2 * disk - lens;
}

double hd_scene_covered_area(const hd_scene *sc) {
  return (double)sc->n_dimers * hd_dimer_area(sc->dimer_d, sc->dimer_a) +
         (double)sc->n_disks * M_PI * sc->disk_sigma * sc->disk_sigma / 4;
}

/* Resolves, checks and counts the state file. */
static int check_state(ctx *c) {
  hd_scene *sc = c->sc;
  if (c->stored) { /* the run's bodies are in its checkpoint; the counts are in the text */
    if (!is_set(c->key_at[K_DCOUNT]) && !is_set(c->key_at[K_SCOUNT]))
      return FAIL_KEY(c, K_STATE, "a stored scene gives the counts of its bodies");
    snprintf(sc->state_file, sizeof sc->state_file, "%s", c->state_rel);
    return HD_OK;
  }
  char joined[2 * HD_PATH_MAX + 2];
  if (c->state_rel[0] == '/')
    snprintf(joined, sizeof joined, "%s", c->state_rel);
  else
    snprintf(joined, sizeof joined, "%s/%s", sc->dir, c->state_rel);
  char *real = realpath(joined, NULL);
  if (!real)
    return fail(c, HD_EIO, c->key_at[K_STATE], S_INIT, "state", c->key_val[K_STATE],
                "cannot read state file '%s': %s", joined, strerror(errno));
  if (strlen(real) >= sizeof sc->state_file) {
    free(real);
    return FAIL_KEY(c, K_STATE, "path too long");
  }
  struct stat stt;
  if (stat(real, &stt) == 0 && S_ISDIR(stt.st_mode)) {
    free(real);
    return FAIL_KEY(c, K_STATE, "is a directory, not a state file");
  }
  /* the run's scene text stores the path as a value: one that INI would cut short (a comment
   * after " ;" or " #", blanks at an end) could not be read back by a re-run */
  size_t rl = strlen(real);
  if (strstr(real, " ;") || strstr(real, " #") || strchr(real, '\n') || real[rl - 1] == ' ' ||
      real[rl - 1] == '\t') {
    free(real);
    return FAIL_KEY(c, K_STATE,
                    "its path holds ' ;', ' #' or a blank at its end, which a scene "
                    "cannot store: rename the file or folder");
  }
  strcpy(sc->state_file, real);
  free(real);
  hd_state_row *rows = NULL;
  long n = 0, nd = 0, ns = 0;
  int rc = hd_state_csv_read(sc->state_file, &rows, &n, c->err);
  if (rc) {
    c->failed = 1;
    c->code = rc;
    return rc;
  }
  for (long i = 0; i < n; i++) *(rows[i].kind == HD_KIND_DIMER ? &nd : &ns) += 1;
  free(rows);
  static const int ck[2] = {K_DCOUNT, K_SCOUNT}, cs[2] = {S_DIMERS, S_DISKS};
  long *cnt[2] = {&sc->n_dimers, &sc->n_disks}, have[2] = {nd, ns};
  static const char *const kind[2] = {"dimer", "disk"};
  for (int j = 0; j < 2; j++) {
    if (is_set(c->key_at[ck[j]])) {
      if (*cnt[j] != have[j])
        return FAIL_KEY(c, ck[j], "the state file %s holds %ld %s rows", c->state_rel, have[j],
                        kind[j]);
    } else if (have[j] > 0) {
      *cnt[j] = have[j];
      c->present[cs[j]] = 1;
    }
  }
  return HD_OK;
}

/* The box: given, or derived from area_fraction; then does everything fit. */
static int check_box(ctx *c) {
  hd_scene *sc = c->sc;
  long nb = sc->n_dimers + sc->n_disks;
  int kb = is_set(c->key_at[K_BOX]) ? K_BOX : K_AREA;
  if (is_set(c->key_at[K_BOX]) && is_set(c->key_at[K_AREA])) {
    int later = c->key_at[K_AREA].over > c->key_at[K_BOX].over ||
                        (c->key_at[K_AREA].over == c->key_at[K_BOX].over &&
                         c->key_at[K_AREA].line > c->key_at[K_BOX].line)
                    ? K_AREA
                    : K_BOX;
    return FAIL_KEY(c, later, "give either box or area_fraction, not both");
  }
  if (nb == 0) {
    if (is_set(c->key_at[K_AREA]))
      return FAIL_KEY(c, K_AREA, "needs bodies: a [dimers] or [disks] count > 0");
    return HD_OK;
  }
  if (!is_set(c->key_at[K_BOX]) && !is_set(c->key_at[K_AREA]))
    return fail(c, HD_EINPUT, c->present[S_SYSTEM] ? c->sec_at[S_SYSTEM] : (loc){0, 0}, S_SYSTEM,
                "box", NULL, "missing: give box = Lx Ly or area_fraction = eta");
  sc->box_line = c->key_at[kb].over ? 0 : c->key_at[kb].line;
  double area = hd_scene_covered_area(sc);
  if (kb == K_AREA) sc->box_x = sc->box_y = sqrt(area / sc->area_fraction);
  if (!isfinite(sc->box_x) || !isfinite(sc->box_y)) /* the bodies' area overflowed (d ~ 1e160) */
    return FAIL_KEY(c, kb, "gives a box that is not a finite number (the bodies cover %.6g)", area);
  double ext = 0;
  if (sc->n_dimers > 0) ext = sc->dimer_a + sc->dimer_d;
  if (sc->n_disks > 0 && sc->disk_sigma > ext) ext = sc->disk_sigma;
  double edge = fmin(sc->box_x, sc->box_y);
  if (edge < ext)
    return FAIL_KEY(c, kb, "box too small: edge %.6g is shorter than the largest body (%.6g)", edge,
                    ext);
  if (!(sc->box_x * sc->box_y >= DBL_MIN))
    /* 1e-300 x 1e-300: the area underflows, and the covered fraction would be 0 / 0 (bodies
     * whose own area underflows cover 0 of a box that has one: that is fine) */
    return FAIL_KEY(c, kb,
                    "box %.6g x %.6g: its area is below the smallest normal double: rescale the "
                    "lengths",
                    sc->box_x, sc->box_y);
  double frac = area / (sc->box_x * sc->box_y);
  if (sc->placement == HD_PLACE_RANDOM && frac > HD_RANDOM_MAX_FRACTION)
    return FAIL_KEY(c, kb,
                    "box too dense: the bodies cover %.4g of it, above %g for placement = random "
                    "(use placement = lattice or a larger box)",
                    frac, HD_RANDOM_MAX_FRACTION);
  if (sc->placement == HD_PLACE_LATTICE) {
    double nx = floor(sc->box_x / ext), ny = floor(sc->box_y / ext);
    if (nx * ny < (double)nb)
      return FAIL_KEY(c, kb,
                      "box too dense for placement = lattice: %.0f x %.0f cells of edge %.6g "
                      "hold fewer than the %ld bodies",
                      nx, ny, ext, nb);
  }
  return HD_OK;
}

/* A [rods] scene: a ring of count rods, nothing 2D. */
static int check_rods(ctx *c) {
  hd_scene *sc = c->sc;
  if (!is_set(c->key_at[K_RCOUNT]))
    return fail(c, HD_EINPUT, c->sec_at[S_RODS], S_RODS, "count", NULL,
                "missing: required in [rods]");
  static const int other[4] = {S_DIMERS, S_DISKS, S_WALLS, S_INIT};
  for (int j = 0; j < 4; j++)
    if (c->present[other[j]])
      return fail(c, HD_EINPUT, c->sec_at[other[j]], other[j], NULL, NULL,
                  "cannot be combined with [rods] (the ring has its own count and temperature)");
  if (is_set(c->key_at[K_BOX]))
    return FAIL_KEY(c, K_BOX, "not used with [rods]: the ring length is the rod count");
  if (is_set(c->key_at[K_AREA]))
    return FAIL_KEY(c, K_AREA, "not used with [rods]: the ring length is the rod count");
  if (!is_set(c->key_at[K_REPS]))
    sc->rod_eps = sc->rod_gamma;
  else if (sc->rod_model != 1)
    return FAIL_KEY(c, K_REPS, "only with model = constant");
  if (sc->rod_table && sc->rod_unequal)
    return FAIL_KEY(c, K_RTABLE,
                    "the table is for equal bath temperatures: not with baths = unequal");
  if (sc->rod_model != 1 && sc->rod_gamma < 1) { /* the sampler the ring builds (rods.c) */
    hd_eps_opts o;
    hd_rods_eps_opts(sc->rod_eps_step, &o);
    if (!hd_eps_grid_fits(sc->rod_gamma, &o))
      return FAIL_KEY(c, K_RGAMMA,
                      "too small for the eps sampler's grid at eps_step %g (about (1 + 1/gamma) / "
                      "eps_step x %d points, at most 5e7): a larger gamma or eps_step",
                      o.step, o.adapt);
  }
  if (!(sc->stop_time > 0 || sc->stop_events > 0 || sc->stop_cpd > 0))
    return fail(c, HD_EINPUT, c->present[S_RUN] ? c->sec_at[S_RUN] : (loc){0, 0}, S_RUN, NULL, NULL,
                "no stop condition: set stop_time, stop_events or stop_cpd");
  return check_vel_at(c);
}

/* [log] frames_every / frames_every_time: one of them, a bounded count under the cap. */
static int check_frames(ctx *c) {
  hd_scene *sc = c->sc;
  if (sc->frames_every > 0 && sc->frames_every_time > 0)
    return FAIL_KEY(c, K_LFRAMEST, "give frames_every (cpd) or frames_every_time, not both");
  if (sc->frames_every_time > 0 && !(sc->stop_time > 0))
    return FAIL_KEY(c, K_LFRAMEST,
                    "needs [run] stop_time (frames are taken at exact times up to it; by cpd: "
                    "frames_every)");
  if (is_set(c->key_at[K_LFRAMESMB]) && !(sc->frames_every > 0 || sc->frames_every_time > 0))
    return FAIL_KEY(c, K_LFRAMESMB, "set without frames_every or frames_every_time");
  double nf = hd_scene_frames_estimate(sc);
  if (nf > 0) {
    double mb = nf * hd_scene_frame_bytes(sc) / 1e6;
    int k = sc->frames_every > 0 ? K_LFRAMES : K_LFRAMEST;
    /* frames by cpd in a run that stop_time may end first: a bound, not a count; the run
     * stops taking frames at the cap (hd_run.c) */
    if (mb > sc->frames_max_mb && !(sc->frames_every > 0 && sc->stop_time > 0))
      return FAIL_KEY(c, k,
                      "%.0f frames of %ld bodies take ~%.4g MB, more than frames_max_mb = %g: "
                      "take fewer frames or raise frames_max_mb",
                      nf, hd_scene_bodies(sc), mb, sc->frames_max_mb);
  }
  return HD_OK;
}

static int check_all(ctx *c) {
  hd_scene *sc = c->sc;
  int rc;
  if (c->present[S_RODS]) return (rc = check_rods(c)) ? rc : check_frames(c);
  if (!is_set(c->key_at[K_SALPHAD])) sc->disk_alpha_dimer = sc->disk_alpha;
  if (is_set(c->key_at[K_STATE])) {
    if (is_set(c->key_at[K_PLACE]))
      return FAIL_KEY(c, K_STATE,
                      "cannot be used together with placement (state gives every "
                      "body)");
    sc->placement = HD_PLACE_STATE;
    if ((rc = check_state(c))) return rc;
  } else if (!(sc->temperature > 0)) {
    return FAIL_KEY(c, K_TEMP, "must be > 0 (0 only with a state file)");
  }
  static const int req_sec[3] = {S_DIMERS, S_DISKS, S_WALLS};
  static const int req_key[3] = {K_DCOUNT, K_SCOUNT, K_WSIDES};
  for (int j = 0; j < 3; j++)
    if (c->present[req_sec[j]] && !is_set(c->key_at[req_key[j]]) &&
        !(req_sec[j] != S_WALLS && sc->placement == HD_PLACE_STATE))
      return fail(c, HD_EINPUT, c->sec_at[req_sec[j]], req_sec[j], key_def[req_key[j]].name, NULL,
                  "missing: required in [%s]", sec_name[req_sec[j]]);
  if (sc->n_dimers > 0 && sc->dimer_a > 0 && sc->dimer_a < HD_MIN_BOND * sc->dimer_d)
    return FAIL_KEY(c, K_DA,
                    "must be 0 or at least %g d = %g: a shorter bond is lost in the round-off of "
                    "the positions (a = 0 is a dimer without lever arm, a disk of mass 2m)",
                    HD_MIN_BOND, HD_MIN_BOND * sc->dimer_d);
  if ((rc = check_box(c))) return rc;
  if (!(sc->stop_time > 0 || sc->stop_events > 0 || sc->stop_cpd > 0))
    return fail(c, HD_EINPUT, c->present[S_RUN] ? c->sec_at[S_RUN] : (loc){0, 0}, S_RUN, NULL, NULL,
                "no stop condition: set stop_time, stop_events or stop_cpd");
  if (sc->n_dimers + sc->n_disks == 1 && !(sc->stop_time > 0) &&
      !(sc->walls && sc->stop_events > 0))
    /* it has no pair collision ever (cpd stays 0), and without walls no collision at all: the
     * run would go on for ever */
    return fail(c, HD_EINPUT, c->present[S_RUN] ? c->sec_at[S_RUN] : (loc){0, 0}, S_RUN, NULL, NULL,
                "one body alone never collides with another: stop it with stop_time (stop_events "
                "counts only its wall collisions, and a drawn velocity of one body is 0: it rests "
                "or spins in place)");
  if ((rc = check_frames(c))) return rc;
  return check_vel_at(c);
}

/* ---- canonical text ------------------------------------------------------------------------ */

typedef struct sbuf {
  char *s;
  size_t n, cap;
  int oom;
} sbuf;

static __attribute__((format(printf, 2, 3))) void put(sbuf *b, const char *fmt, ...) {
  if (b->oom) return;
  va_list ap;
  va_start(ap, fmt);
  int need = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (need < 0) return;
  if (b->n + (size_t)need + 1 > b->cap) {
    size_t cap = 2 * (b->n + (size_t)need + 1) + 256;
    char *s = realloc(b->s, cap);
    if (!s) {
      b->oom = 1;
      return;
    }
    b->s = s;
    b->cap = cap;
  }
  va_start(ap, fmt);
  vsnprintf(b->s + b->n, b->cap - b->n, fmt, ap);
  va_end(ap);
  b->n += (size_t)need;
}

/* The shortest of %.15g, %.16g, %.17g that reads back as exactly x (so the text round-trips
 * bit for bit, and 0.95 stays "0.95" rather than "0.94999999999999996"). */
static void shortest(double x, char *buf, size_t n) {
  for (int prec = 15; prec <= 17; prec++) {
    snprintf(buf, n, "%.*g", prec, x);
    if (strtod(buf, NULL) == x) return;
  }
}

/* "key = x\n" */
static void put_kv(sbuf *b, const char *key, double x) {
  char v[40];
  shortest(x, v, sizeof v);
  put(b, "%s = %s\n", key, v);
}

static char *canonical_text(const ctx *c) {
  const hd_scene *sc = c->sc;
  sbuf b = {0};
  char v1[40], v2[40];
  put(&b, "%s", "");
  if (c->present[S_SYSTEM]) {
    put(&b, "[system]\n");
    shortest(sc->box_x, v1, sizeof v1);
    shortest(sc->box_y, v2, sizeof v2);
    if (is_set(c->key_at[K_AREA])) {
      put_kv(&b, "area_fraction", sc->area_fraction);
      put(&b, "; box = %s %s (from area_fraction)\n", v1, v2);
    } else if (is_set(c->key_at[K_BOX])) {
      put(&b, "box = %s %s\n", v1, v2);
    }
    put(&b, "seed = %llu\n", sc->seed);
  }
  if (c->present[S_DIMERS]) {
    put(&b, "[dimers]\ncount = %ld\n", sc->n_dimers);
    put_kv(&b, "d", sc->dimer_d);
    put_kv(&b, "a", sc->dimer_a);
    put_kv(&b, "m", sc->dimer_m);
    put_kv(&b, "alpha", sc->dimer_alpha);
  }
  if (c->present[S_DISKS]) {
    put(&b, "[disks]\ncount = %ld\n", sc->n_disks);
    put_kv(&b, "sigma", sc->disk_sigma);
    put_kv(&b, "mass", sc->disk_mass);
    put_kv(&b, "alpha", sc->disk_alpha);
    put_kv(&b, "alpha_dimer", sc->disk_alpha_dimer);
  }
  if (c->present[S_WALLS]) {
    put(&b, "[walls]\nsides =");
    for (int j = 0; j < 4; j++)
      if (sc->walls & (1u << j)) put(&b, " %s", wall_name[j]);
    put(&b, "\n");
    put_kv(&b, "alpha", sc->wall_alpha);
  }
  if (c->present[S_INIT]) {
    put(&b, "[init]\n");
    put_kv(&b, "temperature", sc->temperature);
    if (sc->placement == HD_PLACE_STATE)
      put(&b, "state = %s\n", sc->state_file);
    else
      put(&b, "placement = %s\n", sc->placement == HD_PLACE_LATTICE ? "lattice" : "random");
  }
  if (c->present[S_RUN]) {
    put(&b, "[run]\n");
    if (sc->stop_time > 0) put_kv(&b, "stop_time", sc->stop_time);
    if (sc->stop_events > 0) put_kv(&b, "stop_events", sc->stop_events);
    if (sc->stop_cpd > 0) put_kv(&b, "stop_cpd", sc->stop_cpd);
    put(&b, "verify = %d\n", sc->verify);
    put_kv(&b, "checkpoint_every", sc->checkpoint_every);
  }
  if (c->present[S_LOG]) {
    put(&b, "[log]\n");
    if (sc->log_collisions == HD_LOG_EVERY)
      put(&b, "collisions = every %ld\n", sc->log_every);
    else
      put(&b, "collisions = %s\n", sc->log_collisions == HD_LOG_NONE ? "none" : "all");
    put_kv(&b, "samples_every", sc->samples_every);
    if (sc->n_velocities_at > 0) {
      put(&b, "%s =", sc->velocities_in_time ? "velocities_at_time" : "velocities_at");
      for (int i = 0; i < sc->n_velocities_at; i++) {
        shortest(sc->velocities_at[i], v1, sizeof v1);
        put(&b, " %s", v1);
      }
      put(&b, "\n");
    }
    /* only when asked for: the text of a run without frames is as before */
    if (sc->frames_every > 0) put_kv(&b, "frames_every", sc->frames_every);
    if (sc->frames_every_time > 0) put_kv(&b, "frames_every_time", sc->frames_every_time);
    if (sc->frames_every > 0 || sc->frames_every_time > 0)
      put_kv(&b, "frames_max_mb", sc->frames_max_mb);
  }
  if (c->present[S_RODS]) {
    put(&b, "[rods]\ncount = %ld\n", sc->n_rods);
    put_kv(&b, "gamma", sc->rod_gamma);
    put(&b, "nmod = %ld\nmodel = %s\n", sc->rod_nmod, sc->rod_model ? "constant" : "stochastic");
    if (sc->rod_model) put_kv(&b, "eps", sc->rod_eps);
    put_kv(&b, "damping", sc->rod_damping);
    put_kv(&b, "tc", sc->rod_tc);
    put_kv(&b, "eps_step", sc->rod_eps_step);
    put_kv(&b, "temperature", sc->rod_temperature);
    put(&b, "table = %s\nbaths = %s\n", sc->rod_table ? "yes" : "no",
        sc->rod_unequal ? "unequal" : "mean");
  }
  if (b.oom) {
    free(b.s);
    return NULL;
  }
  return b.s;
}

/* ---- public -------------------------------------------------------------------------------- */

void hd_scene_defaults(hd_scene *sc) {
  memset(sc, 0, sizeof *sc);
  strcpy(sc->dir, ".");
  sc->seed = 1;
  sc->dimer_d = sc->dimer_a = sc->dimer_m = sc->dimer_alpha = 1;
  sc->disk_sigma = sc->disk_mass = sc->disk_alpha = sc->disk_alpha_dimer = 1;
  sc->wall_alpha = 1;
  sc->temperature = 1;
  sc->placement = HD_PLACE_RANDOM;
  sc->checkpoint_every = 60;
  sc->log_collisions = HD_LOG_ALL;
  sc->log_every = 1;
  sc->frames_max_mb = HD_FRAMES_MAX_MB;
  sc->rod_gamma = 0.8;
  sc->rod_nmod = 1000;
  sc->rod_eps = 0.8;
  sc->rod_temperature = 1;
  sc->text = NULL;
}

long hd_scene_bodies(const hd_scene *sc) {
  long n = sc->n_dimers + sc->n_disks;
  for (int k = 0; k < sc->n_named; k++) n += sc->named[k].count; /* [species NAME] */
  return sc->n_rods > 0 ? sc->n_rods : n;
}

double hd_scene_frame_bytes(const hd_scene *sc) {
  return (double)hd_scene_bodies(sc) * HD_FRAME_BODY_BYTES + HD_FRAME_ROW_BYTES;
}

double hd_scene_frames_estimate(const hd_scene *sc) {
  double n = (double)hd_scene_bodies(sc), best = INFINITY;
  if (sc->frames_every_time > 0 && sc->stop_time > 0)
    best = floor(sc->stop_time / sc->frames_every_time) + 1;
  if (sc->frames_every > 0) {
    /* the run ends at the first stop reached; cpd = 2 pair collisions / N <= 2 events / N */
    if (sc->stop_cpd > 0) best = fmin(best, floor(sc->stop_cpd / sc->frames_every) + 1);
    if (sc->stop_events > 0 && n > 0)
      best = fmin(best, floor(2 * sc->stop_events / n / sc->frames_every) + 1);
  }
  if (!(sc->frames_every > 0 || sc->frames_every_time > 0)) return 0;
  return best < INFINITY ? best : -1;
}

void hd_scene_free(hd_scene *sc) {
  if (!sc) return;
  free(sc->text);
  sc->text = NULL;
}

/* Parses text (len bytes) into the already-defaulted *sc. */
static int load_text(hd_scene *sc, const char *text, size_t len, const char *name,
                     const char *const *over, int n_over, int stored, hd_error *err) {
  ctx *c = calloc(1, sizeof *c);
  if (!c) return hd_error_set(err, HD_ENOMEM, "%s: out of memory", name);
  c->stored = stored;
  c->sc = sc;
  c->name = name;
  c->over = over;
  c->n_over = n_over;
  c->err = err;
  c->p = text;
  c->end = text + len;
  int rc = HD_OK;
  if (memchr(text, '\0', len))
    rc = hd_error_set(err, HD_EINPUT, "%s: contains a NUL byte: not a text file", name);
  if (!rc) rc = parse_text(c);
  for (int i = 0; !rc && i < n_over; i++) rc = apply_override(c, i);
  if (!rc) rc = check_all(c);
  if (!rc) {
    sc->text = canonical_text(c);
    if (!sc->text) rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", name);
  }
  free(c);
  if (!rc) hd_error_clear(err);
  return rc;
}

int hd_scene_load_string(hd_scene *sc, const char *text, const char *name, const char *const *over,
                         int n_over, hd_error *err) {
  hd_scene_defaults(sc);
  if (!name) name = "<string>";
  return load_text(sc, text, strlen(text), name, over, n_over, 0, err);
}

int hd_scene_load_stored(hd_scene *sc, const char *text, const char *name, hd_error *err) {
  hd_scene_defaults(sc);
  if (!name) name = "<string>";
  return load_text(sc, text, strlen(text), name, NULL, 0, 1, err);
}

int hd_scene_load(hd_scene *sc, const char *path, const char *const *over, int n_over,
                  hd_error *err) {
  hd_scene_defaults(sc);
  if (strlen(path) >= sizeof sc->path)
    return hd_error_set(err, HD_EINPUT, "%.100s...: scene path too long", path);
  strcpy(sc->path, path);
  const char *slash = strrchr(path, '/');
  if (slash == path)
    strcpy(sc->dir, "/");
  else if (slash) {
    memcpy(sc->dir, path, (size_t)(slash - path));
    sc->dir[slash - path] = '\0';
  }
  struct stat stt;
  if (stat(path, &stt) == 0 && S_ISDIR(stt.st_mode))
    return hd_error_set(err, HD_EIO, "%s: cannot read scene: is a directory", path);
  if (stat(path, &stt) == 0 && !S_ISREG(stt.st_mode)) /* /dev/zero grew memory, a FIFO hung */
    return hd_error_set(err, HD_EINPUT, "%s: cannot read scene: not a regular file", path);
  FILE *f = fopen(path, "rb");
  if (!f) return hd_error_set(err, HD_EIO, "%s: cannot read scene: %s", path, strerror(errno));
  char *buf = NULL;
  size_t len = 0, cap = 0;
  for (;;) {
    if (len + 4096 + 1 > cap) {
      cap = 2 * cap + 8192;
      char *nb = realloc(buf, cap);
      if (!nb) {
        free(buf);
        fclose(f);
        return hd_error_set(err, HD_ENOMEM, "%s: out of memory", path);
      }
      buf = nb;
    }
    size_t got = fread(buf + len, 1, 4096, f);
    len += got;
    if (got < 4096) break;
    if (len > (size_t)HD_SCENE_MAX_BYTES) { /* the file grew after stat, or is not what it says */
      free(buf);
      fclose(f);
      return hd_error_set(err, HD_EINPUT, "%s: scene larger than %ld bytes: not a scene file", path,
                          HD_SCENE_MAX_BYTES);
    }
  }
  int bad = ferror(f);
  fclose(f);
  if (bad) {
    free(buf);
    return hd_error_set(err, HD_EIO, "%s: cannot read scene: read error", path);
  }
  buf[len] = '\0';
  int rc = load_text(sc, buf, len, path, over, n_over, 0, err);
  free(buf);
  return rc;
}

/* ---- state CSV ----------------------------------------------------------------------------- */

static const char *const csv_col[7] = {"kind", "x", "y", "phi", "vx", "vy", "omega"};

static void rstrip(char *s) {
  size_t n = strlen(s);
  while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r' || s[n - 1] == '\n'))
    s[--n] = '\0';
}

/* Parses one data line (already right-stripped) into *r. */
static int csv_row(char *line, const char *path, long lineno, hd_state_row *r, hd_error *err) {
  char *f[8];
  int nf = 0;
  char *p = line;
  for (;;) {
    if (nf < 8) f[nf] = p;
    nf++;
    char *comma = strchr(p, ',');
    if (!comma) break;
    *comma = '\0';
    p = comma + 1;
  }
  if (nf != 7)
    return hd_error_set(err, HD_EINPUT, "%s:%ld: expected 7 columns (%s), found %d", path, lineno,
                        "kind,x,y,phi,vx,vy,omega", nf);
  char *kind = trim(f[0]);
  if (!strcmp(kind, "dimer"))
    r->kind = HD_KIND_DIMER;
  else if (!strcmp(kind, "disk"))
    r->kind = HD_KIND_DISK;
  else
    return hd_error_set(err, HD_EINPUT, "%s:%ld: column 1 (kind): '%.40s' is not dimer or disk",
                        path, lineno, kind);
  double v[7];
  for (int j = 1; j < 7; j++) {
    char *t = trim(f[j]);
    if (!parse_num(t, &v[j]))
      return hd_error_set(err, HD_EINPUT, "%s:%ld: column %d (%s): '%.40s': %s", path, lineno,
                          j + 1, csv_col[j], t, num_why(t));
  }
  r->x = v[1];
  r->y = v[2];
  r->phi = r->kind == HD_KIND_DIMER ? v[3] : 0;
  r->vx = v[4];
  r->vy = v[5];
  r->omega = r->kind == HD_KIND_DIMER ? v[6] : 0;
  r->species = r->kind == HD_KIND_DIMER ? 0 : 1;
  r->line = lineno;
  return HD_OK;
}

/* One line of fp into line (room for max + 1 bytes, NUL-terminated, newline dropped): its
 * length, -1 at the end of the file, -2 when it is longer than max (the rest is not read). */
static long bounded_line(FILE *fp, char *line, long max) {
  long k = 0;
  int ch;
  while ((ch = getc_unlocked(fp)) != EOF && ch != '\n') {
    if (k == max) return -2;
    line[k++] = (char)ch;
  }
  line[k] = '\0';
  return ch == EOF && k == 0 ? -1 : k;
}

int hd_state_csv_read(const char *path, hd_state_row **rows, long *n, hd_error *err) {
  *rows = NULL;
  *n = 0;
  struct stat st;
  if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) /* /dev/zero grew memory until it ran out */
    return hd_error_set(err, HD_EINPUT, "%s: cannot read state file: not a regular file", path);
  FILE *fp = fopen(path, "r");
  if (!fp)
    return hd_error_set(err, HD_EIO, "%s: cannot read state file: %s", path, strerror(errno));
  char line[HD_STATE_MAX_LINE + 1];
  long lineno = 0, nrow = 0, rcap = 0;
  hd_state_row *out = NULL;
  int rc = HD_OK;
  long got;
  while (!rc && (got = bounded_line(fp, line, HD_STATE_MAX_LINE)) != -1) {
    lineno++;
    if (got == -2) {
      rc = hd_error_set(err, HD_EINPUT, "%s:%ld: line longer than %d bytes: not a state file", path,
                        lineno, HD_STATE_MAX_LINE);
      break;
    }
    if (nrow >= 2 * HD_MAX_COUNT) {
      rc = hd_error_set(err, HD_EINPUT, "%s:%ld: more than %ld bodies", path, lineno,
                        2 * HD_MAX_COUNT);
      break;
    }
    if (memchr(line, '\0', (size_t)got)) {
      rc = hd_error_set(err, HD_EINPUT, "%s:%ld: contains a NUL byte: not a text file", path,
                        lineno);
      break;
    }
    rstrip(line);
    if (lineno == 1) {
      /* a UTF-8 byte order mark (spreadsheets write one) is skipped, as in scene files */
      if (!strncmp(line, "\xEF\xBB\xBF", 3)) memmove(line, line + 3, strlen(line + 3) + 1);
      if (strcmp(line, "kind,x,y,phi,vx,vy,omega"))
        rc = hd_error_set(err, HD_EINPUT,
                          "%s:1: missing header: expected kind,x,y,phi,vx,vy,omega, found '%.60s'",
                          path, line);
      continue;
    }
    if (!line[0]) continue; /* blank line */
    if (nrow == rcap) {
      rcap = 2 * rcap + 64;
      hd_state_row *nr = realloc(out, (size_t)rcap * sizeof *out);
      if (!nr) {
        rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", path);
        break;
      }
      out = nr;
    }
    rc = csv_row(line, path, lineno, &out[nrow], err);
    if (!rc) nrow++;
  }
  if (!rc && ferror(fp)) rc = hd_error_set(err, HD_EIO, "%s: read error", path);
  if (!rc && lineno == 0)
    rc = hd_error_set(err, HD_EINPUT, "%s:1: empty file: expected header kind,x,y,phi,vx,vy,omega",
                      path);
  if (!rc && nrow == 0)
    rc = hd_error_set(err, HD_EINPUT, "%s:%ld: no bodies after the header", path, lineno);
  fclose(fp);
  if (rc) {
    free(out);
    return rc;
  }
  *rows = out;
  *n = nrow;
  hd_error_clear(err);
  return HD_OK;
}
