/* Helpers shared by the engine tests: scenes built in code, and sizes that shrink under the
 * sanitizer build (HAFF_SANITIZE=1), where everything runs ~10x slower. */
#ifndef HD_TEST_UTIL_H
#define HD_TEST_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sqlite3.h>

#include "hd_scene.h"

/* 1 when running in the ASan+UBSan build. */
static inline int test_sanitized(void) {
  const char *s = getenv("HAFF_SANITIZE");
  return s && s[0] == '1';
}

/* n unless sanitized, else n / shrink (at least 1). */
static inline long test_size(long n, long shrink) {
  return test_sanitized() ? (n / shrink > 0 ? n / shrink : 1) : n;
}

/* A scene of n disks (sigma 1, mass 1) at area fraction eta in a square periodic box. */
static inline void test_disk_scene(hd_scene *sc, long n, double eta, double alpha,
                                   unsigned long long seed) {
  memset(sc, 0, sizeof *sc);
  sc->n_disks = n;
  sc->disk_sigma = 1.0;
  sc->disk_mass = 1.0;
  sc->disk_alpha = alpha;
  sc->disk_alpha_dimer = alpha;
  sc->dimer_d = sc->dimer_a = sc->dimer_m = 1.0;
  sc->dimer_alpha = 1.0;
  sc->wall_alpha = 1.0;
  double L = sqrt((double)n * M_PI / 4.0 / eta);
  sc->box_x = sc->box_y = L;
  sc->seed = seed;
  sc->temperature = 1.0;
  sc->placement = HD_PLACE_RANDOM; /* a melted lattice where random addition jams */
  sc->log_collisions = HD_LOG_NONE;
  sc->log_every = 1;
}

/* folder/name, in one of four rotating buffers (so that a call may take two or three). */
static inline const char *test_path_in(const char *folder, const char *name) {
  static char buf[4][512];
  static int k;
  k = (k + 1) % 4;
  snprintf(buf[k], sizeof buf[k], "%s/%s", folder, name);
  return buf[k];
}

/* Flips bit `bit` of the (first) checkpoint blob of the database at path, as a damaged file
 * would have it.  0, or -1 when the database, its checkpoint or that bit is missing or the
 * write fails. */
static inline int test_flip_checkpoint_bit(const char *path, long long bit) {
  sqlite3 *h = NULL;
  sqlite3_stmt *st = NULL;
  unsigned char *b = NULL;
  int rc = -1;
  if (sqlite3_open_v2(path, &h, SQLITE_OPEN_READWRITE, NULL) != SQLITE_OK ||
      sqlite3_prepare_v2(h, "SELECT blob FROM checkpoints", -1, &st, NULL) != SQLITE_OK ||
      sqlite3_step(st) != SQLITE_ROW)
    goto done;
  int n = sqlite3_column_bytes(st, 0);
  if (bit < 0 || bit / 8 >= n || !(b = malloc((size_t)n))) goto done;
  memcpy(b, sqlite3_column_blob(st, 0), (size_t)n);
  sqlite3_finalize(st);
  st = NULL;
  b[bit / 8] ^= (unsigned char)(1u << (bit % 8));
  if (sqlite3_prepare_v2(h, "UPDATE checkpoints SET blob = ?1", -1, &st, NULL) == SQLITE_OK &&
      sqlite3_bind_blob(st, 1, b, n, SQLITE_TRANSIENT) == SQLITE_OK &&
      sqlite3_step(st) == SQLITE_DONE)
    rc = 0;
done:
  sqlite3_finalize(st);
  sqlite3_close(h);
  free(b);
  return rc;
}

#endif
