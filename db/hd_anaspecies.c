/* hd_anaspecies: a run's species and their energies, for the per-species analysis. */
#include "hd_anaspecies.h"

#include "hd_db.h"
#include "hd_scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Appends one species to mix (the pair restitutions are filled after). */
static void add_sp(hd_ana_mix *mix, int idx, const char *name, long count, double mass,
                   double sigma, int rotates) {
  hd_ana_sp *p = &mix->sp[mix->k++];
  p->idx = idx, p->count = count, p->mass = mass, p->sigma = sigma, p->rotates = rotates;
  snprintf(p->name, sizeof p->name, "%s", name);
}

/* A named species' body: its mass, its diameter when it is one disk, and whether it turns (a
 * moment of inertia sum m |x - x_cm|^2 > 0). */
static void named_body(const hd_scene_species *q, double *mass, double *sigma, int *rotates) {
  double m = 0, cx = 0, cy = 0, I = 0;
  for (int k = 0; k < q->ndisk; k++) m += q->m[k], cx += q->m[k] * q->x[k], cy += q->m[k] * q->y[k];
  cx /= m, cy /= m;
  for (int k = 0; k < q->ndisk; k++) {
    double dx = q->x[k] - cx, dy = q->y[k] - cy;
    I += q->m[k] * (dx * dx + dy * dy);
  }
  *mass = m, *sigma = q->ndisk == 1 ? q->d[0] : NAN, *rotates = I > 0;
}

int hd_ana_mix_read(sqlite3 *db, int64_t run, hd_ana_mix *mix, hd_error *err) {
  memset(mix, 0, sizeof *mix);
  sqlite3_stmt *st;
  if (sqlite3_prepare_v2(db, "SELECT scene, box_x, box_y FROM runs WHERE id = ?1", -1, &st, NULL) !=
      SQLITE_OK)
    return hd_error_set(err, hd_db_status_of(sqlite3_errcode(db)), "reading runs: %s",
                        sqlite3_errmsg(db));
  sqlite3_bind_int64(st, 1, run);
  int r = sqlite3_step(st);
  if (r != SQLITE_ROW) {
    int rc = r == SQLITE_DONE ? hd_error_set(err, HD_EINPUT, "no run with id %lld", (long long)run)
                              : hd_error_set(err, hd_db_status_of(sqlite3_errcode(db)),
                                             "reading runs: %s", sqlite3_errmsg(db));
    sqlite3_finalize(st);
    return rc;
  }
  const char *text = (const char *)sqlite3_column_text(st, 0);
  double bx = sqlite3_column_double(st, 1), by = sqlite3_column_double(st, 2);
  hd_scene sc;
  hd_error e2;
  int rc = hd_scene_read_stored(&sc, text ? text : "", "runs.scene", &e2);
  sqlite3_finalize(st);
  if (rc) return hd_error_set(err, rc, "run %lld: %.900s", (long long)run, e2.msg);
  hd_scene_free(&sc);
  mix->rods = sc.n_rods > 0;
  mix->walls = sc.walls != 0;
  mix->area = bx > 0 && by > 0 ? bx * by : sc.box_x * sc.box_y > 0 ? sc.box_x * sc.box_y : NAN;
  int eng[HD_ANA_SP_MAX];
  if (sc.n_dimers > 0) {
    eng[mix->k] = 0;
    add_sp(mix, 0, "dimers", sc.n_dimers, 2 * sc.dimer_m, sc.dimer_a == 0 ? sc.dimer_d : NAN,
           sc.dimer_a > 0);
  }
  if (sc.n_disks > 0)
    eng[mix->k] = 1, add_sp(mix, 1, "disks", sc.n_disks, sc.disk_mass, sc.disk_sigma, 0);
  for (int q = 0; q < sc.n_named && mix->k < HD_ANA_SP_MAX; q++) {
    if (sc.named[q].count <= 0) continue;
    double m, s;
    int rot;
    named_body(&sc.named[q], &m, &s, &rot);
    eng[mix->k] = 2 + q;
    add_sp(mix, 2 + q, sc.named[q].name, sc.named[q].count, m, s, rot);
  }
  for (int i = 0; i < mix->k; i++)
    for (int j = 0; j < mix->k; j++) mix->alpha[i * mix->k + j] = sc.alpha_pair[eng[i]][eng[j]];
  return HD_OK;
}

/* x and y equal to 1e-9 relative (NaN equals NaN). */
static int same(double x, double y) {
  if (isnan(x) || isnan(y)) return isnan(x) && isnan(y);
  return fabs(x - y) <= 1e-9 * fmax(fabs(x), fabs(y));
}

int hd_ana_mix_same(const hd_ana_mix *a, const hd_ana_mix *b) {
  if (a->k != b->k || a->walls != b->walls || a->rods != b->rods || !same(a->area, b->area))
    return 0;
  for (int i = 0; i < a->k; i++) {
    const hd_ana_sp *p = &a->sp[i], *q = &b->sp[i];
    if (p->idx != q->idx || strcmp(p->name, q->name) || p->count != q->count ||
        !same(p->mass, q->mass) || !same(p->sigma, q->sigma) || p->rotates != q->rotates)
      return 0;
  }
  for (int i = 0; i < a->k * a->k; i++)
    if (!same(a->alpha[i], b->alpha[i])) return 0;
  return 1;
}

void hd_ana_spseries_free(hd_ana_spseries *s) {
  free(s->t), free(s->e_tr), free(s->e_rot);
  memset(s, 0, sizeof *s);
}

/* Runs sql (run bound to ?1; rows t, species, e_tr, e_rot ordered by t) into s: one frame per
 * time at which every species of mix has a row. */
static int read_rows(sqlite3 *db, const char *sql, int64_t run, const hd_ana_mix *mix,
                     hd_ana_spseries *s, hd_error *err) {
  sqlite3_stmt *st;
  if (sqlite3_prepare_v2(db, sql, -1, &st, NULL) != SQLITE_OK)
    return hd_error_set(err, hd_db_status_of(sqlite3_errcode(db)), "reading sample_species: %s",
                        sqlite3_errmsg(db));
  sqlite3_bind_int64(st, 1, run);
  size_t k = (size_t)mix->k, cap = 0;
  int have[HD_ANA_SP_MAX] = {0}, rc = HD_OK, r;
  double tcur = NAN;
  s->k = k;
  /* frame s->n is being filled while its t is tcur; it is kept when every species had a row */
  while ((r = sqlite3_step(st)) == SQLITE_ROW) {
    double t = sqlite3_column_double(st, 0);
    int idx = sqlite3_column_int(st, 1);
    if (t != tcur) {
      int full = !isnan(tcur);
      for (size_t j = 0; j < k && full; j++) full = have[j];
      if (full) s->n++;
      memset(have, 0, sizeof have);
      tcur = t;
      if (s->n == cap) {
        cap = cap ? 2 * cap : 256;
        double *a = realloc(s->t, cap * sizeof *a),
               *b = a ? realloc(s->e_tr, cap * k * sizeof *b) : NULL;
        if (a) s->t = a;
        if (b) s->e_tr = b;
        double *c = b ? realloc(s->e_rot, cap * k * sizeof *c) : NULL;
        if (c) s->e_rot = c;
        if (!c) {
          rc = hd_error_set(err, HD_ENOMEM, "reading sample_species: out of memory");
          break;
        }
      }
      s->t[s->n] = t;
    }
    for (size_t j = 0; j < k; j++)
      if (mix->sp[j].idx == idx) {
        s->e_tr[s->n * k + j] = sqlite3_column_double(st, 2);
        s->e_rot[s->n * k + j] = sqlite3_column_double(st, 3);
        have[j] = 1;
      }
  }
  if (rc == HD_OK && r != SQLITE_DONE)
    rc = hd_error_set(err, hd_db_status_of(sqlite3_errcode(db)), "reading sample_species: %s",
                      sqlite3_errmsg(db));
  if (rc == HD_OK && !isnan(tcur)) {
    int full = 1;
    for (size_t j = 0; j < k && full; j++) full = have[j];
    if (full) s->n++;
  }
  sqlite3_finalize(st);
  return rc;
}

int hd_ana_spseries_read(sqlite3 *db, int64_t run, const hd_ana_mix *mix, hd_ana_spseries *s,
                         hd_error *err) {
  memset(s, 0, sizeof *s);
  if (mix->k == 0) return HD_OK;
  sqlite3_stmt *st;
  int has = sqlite3_prepare_v2(db, "SELECT 1 FROM sample_species WHERE run = ?1 LIMIT 1", -1, &st,
                               NULL) == SQLITE_OK;
  if (has) {
    sqlite3_bind_int64(st, 1, run);
    has = sqlite3_step(st) == SQLITE_ROW;
  }
  sqlite3_finalize(st);
  int rc;
  if (has)
    rc = read_rows(db,
                   "SELECT t, species, e_tr, e_rot FROM sample_species WHERE run = ?1 "
                   "ORDER BY t, species",
                   run, mix, s, err);
  else if (mix->k == 1) {
    char sql[128];
    snprintf(sql, sizeof sql, "SELECT t, %d, e_tr, e_rot FROM samples WHERE run = ?1 ORDER BY t",
             mix->sp[0].idx);
    rc = read_rows(db, sql, run, mix, s, err);
  } else
    rc = read_rows(db,
                   "SELECT t, 0, e_tr_dimer, e_rot_dimer FROM samples WHERE run = ?1 AND "
                   "e_tr_dimer IS NOT NULL UNION ALL SELECT t, 1, e_tr_disk, 0 FROM samples "
                   "WHERE run = ?1 AND e_tr_disk IS NOT NULL ORDER BY 1, 2",
                   run, mix, s, err);
  if (rc) hd_ana_spseries_free(s);
  return rc;
}
