/* hd_scene_set: the keys of the fixed sections with a syntax of their own (KT_CUSTOM rows of
 * SCENE_KEYS: [system] box, [walls] sides, [init] state, [log] collisions, velocities_at and
 * velocities_at_time) and the further checks of [rods] count and eps_step. */
#include "hd_scene_internal.h"

#include <limits.h>
#include <math.h>
#include <string.h>

int hd_scene_set_box(ctx *c, int si, int k, const char *v) {
  char tok[2][64];
  double lx, ly;
  if (hd_scene_split(v, tok, 2) != 2 || !hd_scene_parse_num(tok[0], &lx) ||
      !hd_scene_parse_num(tok[1], &ly))
    return FAIL_AT(c, si, k, "expected two finite numbers Lx Ly");
  if (!(lx > 0 && ly > 0)) return FAIL_AT(c, si, k, "box edges must be > 0");
  c->sc->box_x = lx;
  c->sc->box_y = ly;
  return HD_OK;
}

int hd_scene_set_sides(ctx *c, int si, int k, const char *v) {
  char tok[5][64];
  int n = hd_scene_split(v, tok, 4);
  if (n < 0) return FAIL_AT(c, si, k, "at most the four sides left right bottom top");
  if (n == 0) return FAIL_AT(c, si, k, "missing value: list some of left right bottom top");
  unsigned w = 0;
  for (int i = 0; i < n; i++) {
    int j = 0;
    while (j < 4 && strcmp(tok[i], hd_scene_wall_name[j])) j++;
    if (j == 4) return FAIL_AT(c, si, k, "unknown side '%s' (left right bottom top)", tok[i]);
    if (w & (1u << j)) return FAIL_AT(c, si, k, "side '%s' repeated", tok[i]);
    w |= 1u << j;
  }
  /* a wall closes its axis: past it there is no periodic image, so the opposite edge must be
   * closed too (a lone wall let bodies wrap through the open edge to land behind it) */
  if (!(w & HD_WALL_LEFT) != !(w & HD_WALL_RIGHT))
    return FAIL_AT(c, si, k, "'%s' needs '%s' too: walls close an axis at both edges",
                   w & HD_WALL_LEFT ? "left" : "right", w & HD_WALL_LEFT ? "right" : "left");
  if (!(w & HD_WALL_BOTTOM) != !(w & HD_WALL_TOP))
    return FAIL_AT(c, si, k, "'%s' needs '%s' too: walls close an axis at both edges",
                   w & HD_WALL_BOTTOM ? "bottom" : "top", w & HD_WALL_BOTTOM ? "top" : "bottom");
  c->sc->walls = w;
  return HD_OK;
}

int hd_scene_set_state(ctx *c, int si, int k, const char *v) {
  if (!*v) return FAIL_AT(c, si, k, "missing value: expected a CSV file name");
  /* the canonical text writes "state = NAME": a NAME starting with ';' would read back as an
   * inline comment (found by make fuzz through hd_scene_read_stored, which opens no file) */
  if (*v == ';') return FAIL_AT(c, si, k, "a file name cannot start with ';' (a comment)");
  if (strlen(v) >= sizeof c->state_rel) return FAIL_AT(c, si, k, "file name too long");
  strcpy(c->state_rel, v);
  return HD_OK;
}

int hd_scene_set_collisions(ctx *c, int si, int k, const char *v) {
  hd_scene *sc = c->sc;
  if (!strcmp(v, "all") || !strcmp(v, "none")) {
    sc->log_collisions = !strcmp(v, "all") ? HD_LOG_ALL : HD_LOG_NONE;
    sc->log_every = 1;
    return HD_OK;
  }
  char tok[3][64];
  double n;
  if (hd_scene_split(v, tok, 2) != 2 || strcmp(tok[0], "every"))
    return FAIL_AT(c, si, k, "expected all, none or every N");
  if (!hd_scene_parse_num(tok[1], &n) || n != floor(n) || n < 1 || n > (double)LONG_MAX / 2)
    return FAIL_AT(c, si, k, "every N needs a whole number N >= 1");
  sc->log_collisions = HD_LOG_EVERY;
  sc->log_every = (long)n;
  return HD_OK;
}

/* `velocities_at` (k = K_LVEL, cpd) or `velocities_at_time` (k = K_LVELT, times): the two
 * share the list, so only one of them may be given. */
int hd_scene_set_vel_at(ctx *c, int si, int k, const char *v) {
  hd_scene *sc = c->sc;
  int other = k == K_LVEL ? K_LVELT : K_LVEL;
  const char *unit = k == K_LVEL ? "cpd values" : "times";
  if (hd_scene_key_set(c, si, other))
    return FAIL_AT(c, si, k,
                   "cannot be used together with %s (one list of snapshots, in cpd or in "
                   "time)",
                   hd_scene_keys[other].name);
  int n = 0;
  const char *s = v;
  while (*s) {
    while (*s == ' ' || *s == '\t') s++;
    if (!*s) break;
    size_t len = strcspn(s, " \t");
    char t[64];
    double x;
    if (len >= sizeof t) return FAIL_AT(c, si, k, "not a number: '%.20s...'", s);
    memcpy(t, s, len);
    t[len] = '\0';
    s += len;
    if (!hd_scene_parse_num(t, &x)) return FAIL_AT(c, si, k, "'%s': %s", t, hd_scene_num_why(t));
    if (x < 0) return FAIL_AT(c, si, k, "'%s': %s must be >= 0", t, unit);
    if (n == HD_MAX_VEL_AT)
      return FAIL_AT(c, si, k,
                     "more than %d values (snapshots for a movie or a trajectory: "
                     "frames_every or frames_every_time)",
                     HD_MAX_VEL_AT);
    if (n > 0 && !(x > sc->velocities_at[n - 1]))
      return FAIL_AT(c, si, k, "'%s': values must be strictly ascending", t);
    sc->velocities_at[n++] = x;
  }
  if (n == 0) return FAIL_AT(c, si, k, "missing value: list %s", unit);
  sc->n_velocities_at = n;
  sc->velocities_in_time = k == K_LVELT;
  return HD_OK;
}

int hd_scene_check_rod_count(ctx *c, int si, int k) {
  if (c->sc->n_rods % 2 != 0)
    return FAIL_AT(c, si, k, "must be even: the rod lengths alternate round the ring");
  return HD_OK;
}

/* 0 is the sampler's default; its grid needs ~(1 + 1/gamma)/step points, at most 5e7 / 64
 * (engine/rods/eps.c), and 1e-300 overflowed the size check and crashed the run (SIGFPE) */
int hd_scene_check_eps_step(ctx *c, int si, int k) {
  double x = c->sc->rod_eps_step;
  if (x != 0 && !(x >= 1e-5 && x <= 0.5))
    return FAIL_AT(c, si, k, "must be 0 (the default step) or in [1e-5, 0.5]");
  return HD_OK;
}
