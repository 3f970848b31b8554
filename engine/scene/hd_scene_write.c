/* hd_scene_write: the canonical text of a scene (hd_scene.text, stored as runs.scene): every
 * section present, its keys in the order of SCENE_KEYS, each as its row says (.show, .put,
 * if_pos, if_not_def); numbers in the shortest form that reads back bit for bit. */
#include "hd_scene_internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

__attribute__((format(printf, 2, 3))) void hd_scene_put(sbuf *b, const char *fmt, ...) {
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

/* "key = x\n" */
void hd_scene_put_kv(sbuf *b, const char *key, double x) {
  char v[40];
  hd_scene_shortest(x, v, sizeof v);
  hd_scene_put(b, "%s = %s\n", key, v);
}

int hd_scene_show_beta_dimer(const ctx *c, int si) {
  (void)si; /* beta_dimer defaults to beta: written when either is not smooth */
  return c->sc->disk_beta > -1 || c->sc->disk_beta_dimer > -1;
}

int hd_scene_show_set(const ctx *c, int si) {
  (void)si;
  return hd_scene_key_set(c, S_SYSTEM, K_AREA);
}

int hd_scene_show_box(const ctx *c, int si) {
  (void)si;
  return hd_scene_key_set(c, S_SYSTEM, K_BOX) && !hd_scene_key_set(c, S_SYSTEM, K_AREA);
}

int hd_scene_show_not_state(const ctx *c, int si) {
  (void)si;
  return c->sc->placement != HD_PLACE_STATE;
}

int hd_scene_show_state(const ctx *c, int si) {
  return !hd_scene_show_not_state(c, si);
}

/* (always, in a scene to run: [walls] requires sides; not in one only read without them) */
int hd_scene_show_sides(const ctx *c, int si) {
  (void)si;
  return c->sc->walls != 0;
}

int hd_scene_show_vel(const ctx *c, int si) {
  (void)si;
  return c->sc->n_velocities_at > 0 && !c->sc->velocities_in_time;
}

int hd_scene_show_vel_time(const ctx *c, int si) {
  (void)si;
  return c->sc->n_velocities_at > 0 && c->sc->velocities_in_time;
}

/* only when asked for: the text of a run without frames is as before */
int hd_scene_show_frames(const ctx *c, int si) {
  (void)si;
  return c->sc->frames_every > 0 || c->sc->frames_every_time > 0;
}

int hd_scene_show_rod_eps(const ctx *c, int si) {
  (void)si;
  return c->sc->rod_model == 1;
}

void hd_scene_put_area(const ctx *c, int si, int k, sbuf *b) {
  (void)si, (void)k;
  char v1[40], v2[40];
  hd_scene_put_kv(b, "area_fraction", c->sc->area_fraction);
  hd_scene_shortest(c->sc->box_x, v1, sizeof v1);
  hd_scene_shortest(c->sc->box_y, v2, sizeof v2);
  hd_scene_put(b, "; box = %s %s (from area_fraction)\n", v1, v2);
}

void hd_scene_put_box(const ctx *c, int si, int k, sbuf *b) {
  (void)si, (void)k;
  char v1[40], v2[40];
  hd_scene_shortest(c->sc->box_x, v1, sizeof v1);
  hd_scene_shortest(c->sc->box_y, v2, sizeof v2);
  hd_scene_put(b, "box = %s %s\n", v1, v2);
}

void hd_scene_put_sides(const ctx *c, int si, int k, sbuf *b) {
  (void)si, (void)k;
  hd_scene_put(b, "sides =");
  for (int j = 0; j < 4; j++)
    if (c->sc->walls & (1u << j)) hd_scene_put(b, " %s", hd_scene_wall_name[j]);
  hd_scene_put(b, "\n");
}

void hd_scene_put_state(const ctx *c, int si, int k, sbuf *b) {
  (void)si, (void)k;
  hd_scene_put(b, "state = %s\n", c->sc->state_file);
}

void hd_scene_put_collisions(const ctx *c, int si, int k, sbuf *b) {
  (void)si, (void)k;
  const hd_scene *sc = c->sc;
  if (sc->log_collisions == HD_LOG_EVERY)
    hd_scene_put(b, "collisions = every %ld\n", sc->log_every);
  else
    hd_scene_put(b, "collisions = %s\n", sc->log_collisions == HD_LOG_NONE ? "none" : "all");
}

void hd_scene_put_vel(const ctx *c, int si, int k, sbuf *b) {
  (void)si, (void)k;
  const hd_scene *sc = c->sc;
  char v[40];
  hd_scene_put(b, "%s =", sc->velocities_in_time ? "velocities_at_time" : "velocities_at");
  for (int i = 0; i < sc->n_velocities_at; i++) {
    hd_scene_shortest(sc->velocities_at[i], v, sizeof v);
    hd_scene_put(b, " %s", v);
  }
  hd_scene_put(b, "\n");
}

/* Writes key k of section si as the canonical text has it. */
static void put_key(const ctx *c, int si, int k, sbuf *b) {
  const key_def *kd = &hd_scene_keys[k];
  const void *p = hd_scene_field(c, si, k);
  if (kd->show && !kd->show(c, si)) return;
  if (kd->if_pos && !(*(const double *)p > 0)) return;
  if (kd->if_not_def && *(const double *)p == kd->def) return;
  if (kd->put) {
    kd->put(c, si, k, b);
    return;
  }
  switch (kd->type) {
  case KT_REAL:
  case KT_WHOLE:
    hd_scene_put_kv(b, kd->name, *(const double *)p);
    break;
  case KT_LONG:
    hd_scene_put(b, "%s = %ld\n", kd->name, *(const long *)p);
    break;
  case KT_U64:
    hd_scene_put(b, "%s = %llu\n", kd->name, *(const unsigned long long *)p);
    break;
  case KT_BOOL:
  case KT_ENUM:
    hd_scene_put(b, "%s = %s\n", kd->name, kd->names[*(const int *)p]);
    break;
  case KT_CUSTOM:
    break;
  }
}

static void put_section(const ctx *c, int si, sbuf *b) {
  char label[64];
  hd_scene_sec_label(c, si, label, sizeof label);
  hd_scene_put(b, "[%s]\n", label);
  for (int k = 0; k < N_KEY; k++)
    if (hd_scene_keys[k].sec == hd_scene_sec_of(si)) put_key(c, si, k, b);
}

char *hd_scene_canonical_text(const ctx *c) {
  sbuf b = {0};
  hd_scene_put(&b, "%s", "");
  for (int s = 0; s < N_SEC; s++) {
    if (s == S_SPECIES)
      for (int j = 0; j < c->sc->n_named; j++) put_section(c, N_SEC + j, &b);
    else if (c->present[s])
      put_section(c, s, &b);
  }
  if (b.oom) {
    free(b.s);
    return NULL;
  }
  return b.s;
}
