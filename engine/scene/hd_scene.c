/* hd_scene: scene files (INI via libinih), `--set SECTION.KEY=VALUE` overrides, the canonical
 * text of a scene: the public entry points (hd_scene.h).  Loading a scene: defaults
 * (hd_scene_defaults, from SCENE_KEYS), the text parsed (hd_scene_parse.c), the overrides
 * applied, the whole checked (hd_scene_check.c), the canonical text written (hd_scene_write.c).
 * The files of the module and what each holds: hd_scene_internal.h. */
#include "hd_scene_internal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int hd_scene_key_name(int k, char *buf, size_t size) {
  if (k < 0 || k >= N_KEY) return 1;
  const key_def *kd = &hd_scene_keys[k];
  int n = snprintf(buf, size, "%s.%s%s", hd_scene_sec_name[kd->sec],
                   kd->sec == S_SPECIES ? "NAME." : "", kd->name);
  return n < 0 || (size_t)n >= size;
}

void hd_scene_defaults(hd_scene *sc) {
  memset(sc, 0, sizeof *sc);
  strcpy(sc->dir, ".");
  for (int k = 0; k < N_KEY; k++) {
    const key_def *kd = &hd_scene_keys[k];
    void *p = (char *)sc + kd->off;
    if (kd->sec == S_SPECIES) continue; /* set when the section is made */
    switch (kd->type) {
    case KT_REAL:
    case KT_WHOLE:
      *(double *)p = kd->def;
      break;
    case KT_LONG:
      *(long *)p = (long)kd->def;
      break;
    case KT_U64:
      *(unsigned long long *)p = (unsigned long long)kd->def;
      break;
    case KT_BOOL:
    case KT_ENUM:
      *(int *)p = (int)kd->def;
      break;
    case KT_CUSTOM: /* zero bytes */
      break;
    }
  }
  sc->log_every = 1; /* the N of `collisions = every N`, 1 for all (not a key of its own) */
  sc->text = NULL;
}

long hd_scene_bodies(const hd_scene *sc) {
  return sc->n_rods > 0 ? sc->n_rods : hd_scene_body_count(sc);
}

double hd_scene_frame_bytes(const hd_scene *sc) {
  return (double)hd_scene_bodies(sc) * HD_FRAME_BODY_BYTES + HD_FRAME_ROW_BYTES;
}

double hd_scene_frames_estimate(const hd_scene *sc) {
  double n = (double)hd_scene_bodies(sc), best = INFINITY;
  if (sc->frames_every_time > 0 && sc->stop_time > 0)
    best = floor(sc->stop_time / sc->frames_every_time) + 1;
  if (sc->frames_every > 0) {
    /* the run ends at the first stop reached; cpd = 2 pair collisions / N <= 2 events / N; a
     * frame after frame 0 needs cpd to grow, so a pair collision: one frame per collision at
     * most (run/hd_run.c, observe), the stop's collisions + 1 */
    if (sc->stop_cpd > 0) {
      best = fmin(best, floor(sc->stop_cpd / sc->frames_every) + 1);
      if (n > 0) best = fmin(best, ceil(sc->stop_cpd * n / 2) + 1);
    }
    if (sc->stop_events > 0 && n > 0)
      best = fmin(best,
                  fmin(floor(2 * sc->stop_events / n / sc->frames_every), (double)sc->stop_events) +
                      1);
  }
  if (!(sc->frames_every > 0 || sc->frames_every_time > 0)) return 0;
  return best < INFINITY ? best : -1;
}

double hd_scene_covered_area(const hd_scene *sc) {
  double a = (double)sc->n_dimers * hd_dimer_area(sc->dimer_d, sc->dimer_a) +
             (double)sc->n_disks * M_PI * sc->disk_sigma * sc->disk_sigma / 4;
  for (int j = 0; j < sc->n_named; j++)
    if (sc->named[j].count > 0) a += (double)sc->named[j].count * hd_species_area(&sc->named[j]);
  return a;
}

void hd_scene_free(hd_scene *sc) {
  if (!sc) return;
  free(sc->text);
  sc->text = NULL;
}

/* Parses text (len bytes) into the already-defaulted *sc. */
static int load_text(hd_scene *sc, const char *text, size_t len, const char *name,
                     const char *const *over, int n_over, int mode, hd_error *err) {
  ctx *c = calloc(1, sizeof *c);
  if (!c) return hd_error_set(err, HD_ENOMEM, "%s: out of memory", name);
  c->mode = mode;
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
  if (!rc) rc = hd_scene_parse_text(c);
  for (int i = 0; !rc && i < n_over; i++) rc = hd_scene_apply_override(c, i);
  if (!rc) rc = hd_scene_check_all(c);
  if (!rc) {
    sc->text = hd_scene_canonical_text(c);
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
  return load_text(sc, text, strlen(text), name, over, n_over, M_RUN, err);
}

int hd_scene_load_stored(hd_scene *sc, const char *text, const char *name, hd_error *err) {
  hd_scene_defaults(sc);
  if (!name) name = "<string>";
  return load_text(sc, text, strlen(text), name, NULL, 0, M_STORED, err);
}

int hd_scene_read_stored(hd_scene *sc, const char *text, const char *name, hd_error *err) {
  hd_scene_defaults(sc);
  if (!name) name = "<string>";
  return load_text(sc, text, strlen(text), name, NULL, 0, M_READ, err);
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
