/* hd_anadb: read-only queries of the analysis programs. */
#include "hd_anadb.h"

#include "hd_db.h"
#include "hd_homog.h"
#include "hd_scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int hd_ana_open(sqlite3 **db, const char *path, hd_error *err) {
  static const char *const tables[] = {"runs", "samples", NULL};
  int rc = hd_db_open_read(path, 0, tables, db, err);
  if (!rc) sqlite3_busy_timeout(*db, 5000);
  return rc;
}

const char *hd_ana_species_name(int kind, int mixture, int walls) {
  static const char *const name[HD_NKINDS][2] = {[HD_KIND_DIMER] = {"dimers", "dimers+walls"},
                                                 [HD_KIND_DISK] = {"disks", "disks+walls"},
                                                 [HD_KIND_BODY] = {"shapes", "shapes+walls"},
                                                 [HD_KIND_ROD] = {"other", "other+walls"},
                                                 [HD_KIND_WALL] = {"other", "other+walls"}};
  if (kind == HD_KIND_DIMER && mixture) return walls ? "dimers+disks+walls" : "dimers+disks";
  return kind >= 0 && kind < HD_NKINDS ? name[kind][walls != 0] : "other";
}

/* A scene with named species (issue 18): the gas as a whole.  ri->label names the present
 * species; alpha is the restitution of every pair of them, NaN when they differ. */
static void parse_shapes(const hd_scene *sc, hd_run_info *ri) {
  long count[HD_MAX_SPECIES] = {sc->n_dimers, sc->n_disks};
  const char *name[HD_MAX_SPECIES] = {"dimers", "disks"};
  for (int k = 0; k < sc->n_named; k++) {
    count[2 + k] = sc->named[k].count, name[2 + k] = sc->named[k].name;
    if (sc->named[k].count > 0 && sc->named[k].ndisk > 1) ri->rotates = 1;
  }
  if (sc->n_dimers > 0) ri->rotates = 1;
  int ns = 2 + sc->n_named, len = snprintf(ri->label, sizeof ri->label, "shapes:");
  double lo = INFINITY, hi = -INFINITY;
  for (int i = 0; i < ns; i++) {
    if (count[i] <= 0) continue;
    ri->n += count[i];
    if (len > 0 && (size_t)len < sizeof ri->label)
      len += snprintf(ri->label + len, sizeof ri->label - (size_t)len, "%s%s",
                      ri->label[len - 1] == ':' ? "" : "+", name[i]);
    for (int j = 0; j <= i; j++) {
      if (count[j] <= 0) continue;
      double al = i == j ? (i == 0   ? sc->dimer_alpha
                            : i == 1 ? sc->disk_alpha
                                     : sc->named[i - 2].alpha)
                         : sc->alpha_pair[i][j];
      lo = fmin(lo, al), hi = fmax(hi, al);
    }
  }
  if (sc->walls && len > 0 && (size_t)len < sizeof ri->label)
    snprintf(ri->label + len, sizeof ri->label - (size_t)len, "+walls");
  ri->alpha_lo = lo, ri->alpha_hi = hi;
  ri->alpha = hi - lo <= 1e-12 ? hi : NAN;
  ri->a = 0, ri->d = ri->m = ri->mass = ri->a_over_d = NAN;
}

/* FNV-1a over the text of v to 9 significant digits (so that a value parsed twice, or a centre
 * of mass computed in another order, hashes alike; -0 as 0). */
static void key_str(uint64_t *h, const char *s) {
  for (; *s; s++) *h = (*h ^ (unsigned char)*s) * 1099511628211ULL; /* FNV-1a */
  *h = (*h ^ 0xffU) * 1099511628211ULL;                             /* a separator */
}
static void key_num(uint64_t *h, double v) {
  char b[40];
  snprintf(b, sizeof b, "%.9g", v == 0 ? 0.0 : v);
  key_str(h, b);
}

/* ri->shape_key, coll_key, rough_key, rough and wall_alpha from the bodies present in sc (issue 14
 * review: runs of rough and smooth bodies, of different shapes or wall restitutions were pooled).
 */
static void physics_keys(const hd_scene *sc, hd_run_info *ri) {
  uint64_t hs = 14695981039346656037ULL, hc = hs, hr = hs;
  /* species are keyed by their rank among the present ones, not by their engine index: a gas of
   * one named species of dimers keys as [dimers] alone does */
  int ns = 2 + sc->n_named, present[HD_MAX_SPECIES], rank[HD_MAX_SPECIES], np = 0;
  ri->rough = 0;
  for (int i = 0; i < ns; i++) {
    long count = i == 0 ? sc->n_dimers : i == 1 ? sc->n_disks : sc->named[i - 2].count;
    present[i] = count > 0, rank[i] = np;
    if (!present[i]) continue;
    double x[HD_MAX_BODY_DISKS], y[HD_MAX_BODY_DISKS], d[HD_MAX_BODY_DISKS], m[HD_MAX_BODY_DISKS];
    int nd;
    double q, alpha;
    if (i == 0) {
      nd = 2, q = sc->dimer_q, alpha = sc->dimer_alpha;
      x[0] = -sc->dimer_a / 2, x[1] = sc->dimer_a / 2, y[0] = y[1] = 0;
      d[0] = d[1] = sc->dimer_d, m[0] = m[1] = sc->dimer_m;
    } else if (i == 1) {
      nd = 1, q = sc->disk_q, alpha = sc->disk_alpha;
      x[0] = y[0] = 0, d[0] = sc->disk_sigma, m[0] = sc->disk_mass;
    } else {
      const hd_scene_species *sp = &sc->named[i - 2];
      nd = sp->ndisk, q = sp->q, alpha = sp->alpha;
      for (int k = 0; k < nd; k++)
        x[k] = sp->x[k], y[k] = sp->y[k], d[k] = sp->d[k], m[k] = sp->m[k];
    }
    double mt = 0, cx = 0, cy = 0;
    for (int k = 0; k < nd; k++) mt += m[k], cx += m[k] * x[k], cy += m[k] * y[k];
    key_num(&hs, (double)count);
    np++;
    key_num(&hr, rank[i]), key_num(&hr, q);
    for (int k = 0; k < nd; k++) {
      key_num(&hs, x[k] - cx / mt), key_num(&hs, y[k] - cy / mt);
      key_num(&hs, d[k]), key_num(&hs, m[k]);
    }
    for (int j = 0; j <= i; j++) {
      if (!present[j]) continue;
      double beta = sc->beta_pair[i][j];
      key_num(&hc, rank[i] * HD_MAX_SPECIES + rank[j]);
      key_num(&hr, rank[i] * HD_MAX_SPECIES + rank[j]);
      key_num(&hc, i == j ? alpha : sc->alpha_pair[i][j]), key_num(&hr, beta);
      ri->rough |= beta > -1;
    }
  }
  ri->wall_alpha = sc->walls ? sc->wall_alpha : NAN;
  key_num(&hc, sc->walls);
  if (sc->walls) {
    key_num(&hc, sc->wall_alpha), key_num(&hr, sc->wall_beta);
    ri->rough |= sc->wall_beta > -1;
  }
  ri->shape_key = hs, ri->coll_key = hc, ri->rough_key = hr;
}

int hd_ana_same_physics(const hd_run_info *a, const hd_run_info *b) {
  /* the keys hold it all: every species' q and every pair's beta (rough, beta and q follow from
   * them), the walls' alpha and beta, the shapes and counts, every pair's alpha */
  return a->shape_key == b->shape_key && a->coll_key == b->coll_key && a->rough_key == b->rough_key;
}

int hd_ana_parse_scene(const char *text, hd_run_info *ri, hd_error *err) {
  /* the engine's own loader (keys, defaults, areas), without the checks of a scene to run */
  hd_scene sc;
  int rc = hd_scene_read_stored(&sc, text, "runs.scene", err);
  if (rc) return rc;
  hd_scene_free(&sc);
  int named = 0;
  for (int k = 0; k < sc.n_named; k++) named |= sc.named[k].count > 0;
  ri->rotates = 0, ri->mixture = 0;
  ri->walls = sc.walls != 0;
  ri->beta = ri->q = NAN;
  ri->named_dimers = 0;
  if (named) {
    ri->species = HD_KIND_BODY;
    ri->n = 0;
    parse_shapes(&sc, ri);
    /* one named species of paper dimers (`shape = dimer A`: two equal disks), alone: it runs
     * bit for bit as [dimers] do, so it is analysed as dimers (the dimer analyses refused it) */
    int k = -1, nk = 0;
    for (int i = 0; i < sc.n_named; i++)
      if (sc.named[i].count > 0) k = i, nk++;
    const hd_scene_species *sp = k >= 0 ? &sc.named[k] : NULL;
    if (nk == 1 && sc.n_dimers <= 0 && sc.n_disks <= 0 && sp->ndisk == 2 && sp->d[0] == sp->d[1] &&
        sp->m[0] == sp->m[1] && hypot(sp->x[1] - sp->x[0], sp->y[1] - sp->y[0]) > 0) {
      ri->species = HD_KIND_DIMER, ri->named_dimers = 1;
      ri->alpha = ri->alpha_lo = ri->alpha_hi = sp->alpha;
      ri->a = hypot(sp->x[1] - sp->x[0], sp->y[1] - sp->y[0]), ri->d = sp->d[0];
      ri->m = sp->m[0], ri->mass = 2.0 * sp->m[0], ri->a_over_d = ri->a / ri->d;
      ri->beta = sp->beta, ri->q = sp->q;
    }
  } else if (sc.n_dimers > 0) {
    ri->species = HD_KIND_DIMER, ri->mixture = sc.n_disks > 0;
    ri->n = sc.n_dimers;
    ri->alpha = sc.dimer_alpha, ri->a = sc.dimer_a, ri->d = sc.dimer_d, ri->m = sc.dimer_m;
    ri->mass = 2.0 * sc.dimer_m;
    ri->a_over_d = sc.dimer_a / sc.dimer_d;
    ri->beta = sc.dimer_beta, ri->q = sc.dimer_q;
    ri->rotates = 1;
    ri->alpha_lo = ri->alpha_hi = ri->alpha;
    if (ri->mixture) {
      /* the gas as a whole, as the same gas of named species is (parse_shapes): every body, one
       * alpha only when the dimers', the disks' and the dimer-disk restitutions agree, and no
       * Enskog reference of one species (it used to take the dimers' alpha and N alone) */
      ri->n += sc.n_disks, ri->mass = NAN;
      ri->alpha_lo = fmin(fmin(sc.dimer_alpha, sc.disk_alpha), sc.alpha_pair[0][1]);
      ri->alpha_hi = fmax(fmax(sc.dimer_alpha, sc.disk_alpha), sc.alpha_pair[0][1]);
      ri->alpha = ri->alpha_hi - ri->alpha_lo <= 1e-12 ? ri->alpha_hi : NAN;
    }
  } else if (sc.n_disks > 0) {
    ri->species = HD_KIND_DISK;
    ri->n = sc.n_disks;
    ri->alpha = sc.disk_alpha, ri->a = 0, ri->d = sc.disk_sigma, ri->m = sc.disk_mass;
    ri->mass = sc.disk_mass;
    ri->a_over_d = 0;
    ri->beta = sc.disk_beta, ri->q = sc.disk_q;
  } else {
    ri->species = HD_KIND_ROD;
    ri->n = 0, ri->alpha = 1, ri->a = 0, ri->d = 1, ri->m = 1, ri->mass = 1, ri->a_over_d = 0;
  }
  if (ri->species != HD_KIND_BODY && !ri->named_dimers) { /* named dimers: label "shapes:NAME" */
    if (!ri->mixture) ri->alpha_lo = ri->alpha_hi = ri->alpha;
    snprintf(ri->label, sizeof ri->label, "%s",
             hd_ana_species_name(ri->species, ri->mixture, ri->walls));
  }
  /* the box as given, or derived from area_fraction over every body (hd_scene_covered_area) */
  ri->box_x = sc.box_x, ri->box_y = sc.box_y, ri->area_fraction = sc.area_fraction;
  double area = sc.box_x * sc.box_y;
  ri->density = area > 0 ? (double)ri->n / area : NAN;
  ri->eta_disk = M_PI * ri->density * ri->d * ri->d / 4;
  physics_keys(&sc, ri);
  return HD_OK;
}

/* Sets *err from the database's last error, as "reading WHAT: message"; returns its status. */
static int read_fail(sqlite3 *db, const char *what, hd_error *err) {
  return hd_error_set(err, hd_db_status_of(sqlite3_errcode(db)), "reading %s: %s", what,
                      sqlite3_errmsg(db));
}

/* Prepares sql into *st with run bound to ?1; on failure read_fail(what). */
static int prepare_run(sqlite3 *db, const char *sql, int64_t run, const char *what,
                       sqlite3_stmt **st, hd_error *err) {
  if (sqlite3_prepare_v2(db, sql, -1, st, NULL) != SQLITE_OK) return read_fail(db, what, err);
  sqlite3_bind_int64(*st, 1, run);
  return HD_OK;
}

/* Grows the ncol columns *cols[c] to cap doubles each; those grown before a failure keep
 * their new size.  HD_OK, or HD_ENOMEM set as "reading WHAT: out of memory". */
static int grow_cols(double **const *cols, int ncol, size_t cap, const char *what, hd_error *err) {
  for (int c = 0; c < ncol; c++) {
    double *p = realloc(*cols[c], cap * sizeof *p);
    if (!p) return hd_error_set(err, HD_ENOMEM, "reading %s: out of memory", what);
    *cols[c] = p;
  }
  return HD_OK;
}

int hd_ana_runs(sqlite3 *db, int64_t want, hd_run_info **runs, size_t *n, hd_error *err) {
  *runs = NULL, *n = 0;
  /* the stored HCS window, in files that have its columns (NULL otherwise) */
  sqlite3_stmt *st;
  int hcs =
      sqlite3_prepare_v2(db, "SELECT hcs_cpd_start FROM runs LIMIT 0", -1, &st, NULL) == SQLITE_OK;
  sqlite3_finalize(st);
  char q[400];
  snprintf(q, sizeof q, "SELECT id, scene, seed, status, box_x, box_y, %s FROM runs WHERE %s",
           hcs ? "hcs_cpd_start, hcs_cpd_end, hcs_end, hcs_s_perp, hcs_flow_excess"
               : "NULL, NULL, NULL, NULL, NULL",
           want >= 0 ? "id = ?1" : "status IN ('done','collapsed','interrupted') ORDER BY id");
  if (sqlite3_prepare_v2(db, q, -1, &st, NULL) != SQLITE_OK) return read_fail(db, "runs", err);
  if (want >= 0) sqlite3_bind_int64(st, 1, want);
  size_t cap = 0;
  int rc = HD_OK, s;
  while ((s = sqlite3_step(st)) == SQLITE_ROW) {
    if (*n == cap) {
      cap = cap ? 2 * cap : 16;
      hd_run_info *nr = realloc(*runs, cap * sizeof *nr);
      if (!nr) {
        rc = hd_error_set(err, HD_ENOMEM, "reading runs: out of memory");
        break;
      }
      *runs = nr;
    }
    hd_run_info *ri = &(*runs)[*n];
    memset(ri, 0, sizeof *ri);
    ri->id = sqlite3_column_int64(st, 0);
    const char *scene = (const char *)sqlite3_column_text(st, 1);
    ri->seed = (unsigned long long)sqlite3_column_int64(st, 2);
    const char *status = (const char *)sqlite3_column_text(st, 3);
    snprintf(ri->status, sizeof ri->status, "%s", status ? status : "");
    rc = hd_ana_parse_scene(scene ? scene : "", ri, err);
    /* the box the engine used (hd_db_run_box), which also counts every species of a mixture */
    double bx = sqlite3_column_double(st, 4), by = sqlite3_column_double(st, 5);
    if (rc == HD_OK && bx > 0 && by > 0 && isfinite(bx * by)) {
      ri->box_x = bx, ri->box_y = by;
      ri->density = (double)ri->n / (bx * by);
      ri->eta_disk = M_PI * ri->density * ri->d * ri->d / 4;
    }
    double hv[5];
    for (int c = 0; c < 5; c++)
      hv[c] = c == 2 || sqlite3_column_type(st, 6 + c) == SQLITE_NULL
                  ? NAN
                  : sqlite3_column_double(st, 6 + c); /* column 8, hcs_end, is text */
    const char *he = (const char *)sqlite3_column_text(st, 8);
    ri->hcs_stored = !isnan(hv[0]) && !isnan(hv[1]) && he;
    ri->hcs_cpd_start = hv[0], ri->hcs_cpd_end = hv[1];
    ri->hcs_end = !he                     ? HD_HCS_END_NONE
                  : !strcmp(he, "s_perp") ? HD_HCS_END_SPERP
                  : !strcmp(he, "rate")   ? HD_HCS_END_RATE
                                          : HD_HCS_END_NONE;
    ri->hcs_s_perp = hv[3], ri->hcs_flow_excess = hv[4];
    if (rc) {
      char why[1024];
      snprintf(why, sizeof why, "%s", err ? err->msg : "");
      hd_error_set(err, rc, "run %lld: %.900s", (long long)ri->id, why);
      break;
    }
    (*n)++;
  }
  if (rc == HD_OK && s != SQLITE_DONE) rc = read_fail(db, "runs", err);
  sqlite3_finalize(st);
  if (rc == HD_OK && want >= 0 && *n == 0)
    rc = hd_error_set(err, HD_EINPUT, "no run with id %lld", (long long)want);
  if (rc) free(*runs), *runs = NULL, *n = 0;
  return rc;
}

void hd_series_free(hd_series *s) {
  free(s->t), free(s->coll), free(s->cpd), free(s->e_tr), free(s->e_rot);
  free(s->s_perp), free(s->flow_frac), free(s->flow_chaos);
  memset(s, 0, sizeof *s);
}

int hd_ana_samples(sqlite3 *db, int64_t run, hd_series *s, hd_error *err) {
  memset(s, 0, sizeof *s);
  sqlite3_stmt *st;
  /* a file of schema < 2 has no state measures: they read as NULL */
  int v2 = sqlite3_prepare_v2(db, "SELECT s_perp FROM samples LIMIT 0", -1, &st, NULL) == SQLITE_OK;
  sqlite3_finalize(st);
  int rc = prepare_run(db,
                       v2 ? "SELECT t, collisions, cpd, e_tr, e_rot, s_perp, flow_frac, "
                            "flow_chaos FROM samples WHERE run = ?1 ORDER BY t, collisions"
                          : "SELECT t, collisions, cpd, e_tr, e_rot, NULL, NULL, NULL FROM "
                            "samples WHERE run = ?1 ORDER BY t, collisions",
                       run, "samples", &st, err);
  if (rc) return rc;
  size_t cap = 0;
  int r;
  while ((r = sqlite3_step(st)) == SQLITE_ROW) {
    if (s->n == cap) {
      cap = cap ? 2 * cap : 256;
      double **const cols[8] = {&s->t,     &s->coll,   &s->cpd,       &s->e_tr,
                                &s->e_rot, &s->s_perp, &s->flow_frac, &s->flow_chaos};
      if ((rc = grow_cols(cols, 8, cap, "samples", err))) break;
    }
    s->t[s->n] = sqlite3_column_double(st, 0);
    s->coll[s->n] = sqlite3_column_double(st, 1);
    s->cpd[s->n] = sqlite3_column_double(st, 2);
    s->e_tr[s->n] = sqlite3_column_double(st, 3);
    s->e_rot[s->n] = sqlite3_column_double(st, 4);
    double *q[3] = {s->s_perp, s->flow_frac, s->flow_chaos};
    for (int c = 0; c < 3; c++)
      q[c][s->n] =
          sqlite3_column_type(st, 5 + c) == SQLITE_NULL ? NAN : sqlite3_column_double(st, 5 + c);
    s->n++;
  }
  if (rc == HD_OK && r != SQLITE_DONE) rc = read_fail(db, "samples", err);
  sqlite3_finalize(st);
  if (rc) hd_series_free(s);
  return rc;
}

void hd_snapshots_free(hd_snapshot *snaps, size_t n) {
  for (size_t i = 0; snaps && i < n; i++)
    free(snaps[i].vx), free(snaps[i].vy), free(snaps[i].omega);
  free(snaps);
}

int hd_ana_snapshots(sqlite3 *db, int64_t run, const char *label, const char *kind,
                     hd_snapshot **snaps, size_t *n, hd_error *err) {
  *snaps = NULL, *n = 0;
  sqlite3_stmt *st;
  int rc = prepare_run(db,
                       "SELECT t, cpd, vx, vy, omega FROM states WHERE run = ?1 AND "
                       "label = ?2 AND kind = ?3 ORDER BY t, body",
                       run, "states", &st, err);
  if (rc) return rc;
  sqlite3_bind_text(st, 2, label, -1, SQLITE_STATIC);
  sqlite3_bind_text(st, 3, kind, -1, SQLITE_STATIC);
  size_t cap = 0, bcap = 0;
  hd_snapshot *cur = NULL;
  int r;
  while ((r = sqlite3_step(st)) == SQLITE_ROW) {
    double t = sqlite3_column_double(st, 0);
    if (!cur || t != cur->t) {
      if (*n == cap) {
        cap = cap ? 2 * cap : 8;
        hd_snapshot *p = realloc(*snaps, cap * sizeof *p);
        if (!p) {
          rc = hd_error_set(err, HD_ENOMEM, "reading states: out of memory");
          break;
        }
        *snaps = p;
      }
      cur = &(*snaps)[(*n)++];
      memset(cur, 0, sizeof *cur);
      cur->t = t;
      cur->cpd = sqlite3_column_type(st, 1) == SQLITE_NULL ? NAN : sqlite3_column_double(st, 1);
      bcap = 0;
    }
    if (cur->n == bcap) {
      bcap = bcap ? 2 * bcap : 1024;
      double **const cols[3] = {&cur->vx, &cur->vy, &cur->omega};
      if ((rc = grow_cols(cols, 3, bcap, "states", err))) break;
    }
    cur->vx[cur->n] = sqlite3_column_double(st, 2);
    cur->vy[cur->n] = sqlite3_column_double(st, 3);
    cur->omega[cur->n] = sqlite3_column_double(st, 4);
    cur->n++;
  }
  if (rc == HD_OK && r != SQLITE_DONE) rc = read_fail(db, "states", err);
  sqlite3_finalize(st);
  if (rc) hd_snapshots_free(*snaps, *n), *snaps = NULL, *n = 0;
  return rc;
}

int hd_ana_dd_collisions(sqlite3 *db, int64_t run, int body, double **theta_i, double **theta_j,
                         double **f, size_t *n, hd_error *err) {
  *theta_i = *theta_j = *f = NULL, *n = 0;
  sqlite3_stmt *st;
  int rc = prepare_run(db,
                       "SELECT theta_i, theta_j, f FROM collisions WHERE run = ?1 AND "
                       "kind = ?2 AND theta_i IS NOT NULL AND theta_j IS NOT NULL "
                       "ORDER BY seq",
                       run, "collisions", &st, err);
  if (rc) return rc;
  sqlite3_bind_text(st, 2, body ? "body-body" : "dimer-dimer", -1, SQLITE_STATIC);
  size_t cap = 0;
  int r;
  while ((r = sqlite3_step(st)) == SQLITE_ROW) {
    if (*n == cap) {
      cap = cap ? 2 * cap : 4096;
      double **const cols[3] = {theta_i, theta_j, f};
      if ((rc = grow_cols(cols, 3, cap, "collisions", err))) break;
    }
    (*theta_i)[*n] = sqlite3_column_double(st, 0);
    (*theta_j)[*n] = sqlite3_column_double(st, 1);
    (*f)[*n] = sqlite3_column_type(st, 2) == SQLITE_NULL ? NAN : sqlite3_column_double(st, 2);
    (*n)++;
  }
  if (rc == HD_OK && r != SQLITE_DONE) rc = read_fail(db, "collisions", err);
  sqlite3_finalize(st);
  if (rc) free(*theta_i), free(*theta_j), free(*f), *theta_i = *theta_j = *f = NULL, *n = 0;
  return rc;
}

void hd_ana_close(sqlite3 *db) {
  sqlite3_close(db);
}

int hd_ana_status(sqlite3 *db) {
  return hd_db_status_of(sqlite3_errcode(db));
}

int hd_ana_rods_run(sqlite3 *db, int64_t want, int64_t *id, char **scene, hd_error *err) {
  *id = 0;
  *scene = NULL;
  hd_error_clear(err);
  sqlite3_stmt *st;
  const char *sql = want >= 0 ? "SELECT id, scene FROM runs WHERE id = ?1"
                              : "SELECT id, scene FROM runs WHERE scene LIKE '%[rods]%' "
                                "ORDER BY id DESC LIMIT 1";
  if (sqlite3_prepare_v2(db, sql, -1, &st, NULL) != SQLITE_OK)
    return hd_error_set(err, HD_EIO, "%s", sqlite3_errmsg(db));
  if (want >= 0) sqlite3_bind_int64(st, 1, want);
  int rc = HD_EINPUT;
  if (sqlite3_step(st) == SQLITE_ROW) {
    *id = sqlite3_column_int64(st, 0);
    const char *text = (const char *)sqlite3_column_text(st, 1);
    rc = HD_OK;
    if (text && !(*scene = strdup(text)))
      rc = hd_error_set(err, HD_ENOMEM, "out of memory for the scene of run %lld", (long long)*id);
  }
  sqlite3_finalize(st);
  return rc;
}

long hd_ana_rods_times(sqlite3 *db, int64_t run, double **t) {
  sqlite3_stmt *st;
  *t = NULL;
  if (sqlite3_prepare_v2(db,
                         "SELECT DISTINCT t FROM states WHERE run = ?1 AND kind = 'rod' AND "
                         "label IN ('initial','velocities','final') ORDER BY t",
                         -1, &st, NULL) != SQLITE_OK)
    return -1;
  sqlite3_bind_int64(st, 1, run);
  long n = 0, cap = 0;
  while (sqlite3_step(st) == SQLITE_ROW) {
    if (n == cap) {
      cap = 2 * cap + 16;
      double *nt = realloc(*t, (size_t)cap * sizeof *nt);
      if (!nt) break;
      *t = nt;
    }
    (*t)[n++] = sqlite3_column_double(st, 0);
  }
  sqlite3_finalize(st);
  return n;
}

int hd_ana_rods_snapshot(sqlite3 *db, int64_t run, double t, long n, double *x, double *v,
                         double *tb, hd_error *err) {
  sqlite3_stmt *st;
  if (sqlite3_prepare_v2(db,
                         "SELECT body, x, vx, omega FROM states WHERE run = ?1 AND kind = 'rod' "
                         "AND t = ?2 AND label IN ('initial','velocities','final')",
                         -1, &st, NULL) != SQLITE_OK)
    return hd_error_set(err, HD_EIO, "%s", sqlite3_errmsg(db));
  sqlite3_bind_int64(st, 1, run);
  sqlite3_bind_double(st, 2, t);
  while (sqlite3_step(st) == SQLITE_ROW) {
    long b = (long)sqlite3_column_int64(st, 0);
    if (b < 0 || b >= n) continue;
    x[b] = sqlite3_column_double(st, 1);
    v[b] = sqlite3_column_double(st, 2);
    tb[b] = sqlite3_column_double(st, 3);
  }
  sqlite3_finalize(st);
  return HD_OK;
}
