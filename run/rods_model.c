/* The ring of rods (rods.h) seen through hd_model_ops, so that `haff run` with a [rods]
 * section gets logging, samples, snapshots, checkpoints, signals and resume from hd_run.c.
 * Logged: collisions kind 'rod-rod' with t, i, j, eps, e_tr, tb_i, tb_j, de and vn = u;
 * samples e_tr = E_kin / N and e_rot = bath energy / N; states kind 'rod' with x = position,
 * vx = velocity, omega = bath temperature T_B (y, phi, vy NULL). */
#include <math.h>
#include <stdlib.h>

#include "hd_model.h"
#include "rods.h"
#include "rods_model.h"

/* The ring's parameters from a scene. */
static void params_of(const hd_scene *sc, hd_rods_params *p) {
  hd_rods_params_default(p);
  p->n = sc->n_rods;
  p->gamma = sc->rod_gamma;
  p->nmod = sc->rod_nmod;
  p->model = sc->rod_model ? HD_RODS_CONSTANT : HD_RODS_STOCHASTIC;
  p->eps = sc->rod_eps;
  p->damping = sc->rod_damping;
  p->tc = sc->rod_tc;
  p->temperature = sc->rod_temperature;
  p->table = sc->rod_table;
  p->eps_step = sc->rod_eps_step;
  p->unequal = sc->rod_unequal;
  p->seed = sc->seed;
}

static int m_alloc(void **m, const hd_scene *sc, hd_error *err) {
  hd_rods_params p;
  params_of(sc, &p);
  return hd_rods_alloc((hd_rods **)m, &p, err);
}
static int m_alloc_restore(void **m, const hd_scene *sc, const void *blob, size_t n,
                           hd_error *err) {
  hd_rods_params p;
  params_of(sc, &p);
  return hd_rods_alloc_restore((hd_rods **)m, &p, blob, n, err);
}
static void m_free(void *m) {
  hd_rods_free(m);
}

static int m_next(void *m, double t_stop, hd_collision_row *row, hd_error *err) {
  hd_rods_event ev;
  int rc = hd_rods_next(m, t_stop, &ev, err);
  if (rc) return rc;
  *row = (hd_collision_row){.seq = 0, /* the store's */
                            .t = ev.t,
                            .kind = hd_coll_kind_of(HD_KIND_ROD, HD_KIND_ROD),
                            .i = ev.i,
                            .j = ev.j,
                            .disk_i = -1,
                            .disk_j = -1,
                            .theta_i = NAN,
                            .theta_j = NAN,
                            .f = NAN,
                            .de = ev.de,
                            .vn = ev.u,
                            .eps = ev.eps,
                            .e_tr = ev.e_tr,
                            .tb_i = ev.tb_i,
                            .tb_j = ev.tb_j};
  return HD_OK;
}

static int m_checkpoint(const void *m, void **blob, size_t *n, hd_error *err) {
  return hd_rods_checkpoint(m, blob, n, err);
}
static double m_time(const void *m) {
  return ((const hd_rods *)m)->t;
}
static double m_cpd(const void *m) {
  const hd_rods *r = m;
  return 2.0 * (double)r->collisions / (double)r->p.n;
}
static int64_t m_events(const void *m) {
  return ((const hd_rods *)m)->collisions;
}
static double m_temperature(const void *m) {
  const hd_rods *r = m;
  double ek;
  hd_rods_energy(r, &ek, NULL, NULL);
  return 2 * ek / (double)r->p.n;
}

static void m_sample(const void *m, hd_sample_row *row) {
  const hd_rods *r = m;
  double ek, eb, N = (double)r->p.n;
  hd_rods_energy(r, &ek, &eb, NULL);
  *row = (hd_sample_row){.t = r->t,
                         .collisions = r->collisions,
                         .cpd = m_cpd(m),
                         .e_tr = ek / N,
                         .e_rot = eb / N,
                         .flow_frac = NAN, /* no state measures for rods */
                         .flow_chaos = NAN,
                         .count_var = NAN,
                         .s_rho = NAN,
                         .s_perp = NAN,
                         .s_par = NAN};
}

static int m_log_states(const void *m, hd_db *db, int64_t run, const char *label, hd_error *err) {
  const hd_rods *r = m;
  double *x = malloc((size_t)r->p.n * sizeof *x);
  if (!x) return hd_error_set(err, HD_ENOMEM, "rods: out of memory");
  hd_rods_positions(r, x);
  int rc = HD_OK;
  for (long i = 0; i < r->p.n && !rc; i++) {
    hd_state_rec rec = {r->t,    i,   HD_KIND_ROD,      x[i],     NAN, NAN,
                        r->v[i], NAN, hd_rods_tb(r, i), m_cpd(m), -1};
    rc = hd_db_log_state(db, run, label, &rec, err);
  }
  free(x);
  return rc;
}

static int m_states(const void *m, hd_state_rec *out, hd_error *err) {
  const hd_rods *r = m;
  double *x = malloc((size_t)r->p.n * sizeof *x);
  if (!x) return hd_error_set(err, HD_ENOMEM, "rods: out of memory");
  hd_rods_positions(r, x);
  for (long i = 0; i < r->p.n; i++)
    out[i] = (hd_state_rec){r->t,    i, HD_KIND_ROD,      x[i],     0.0, 0.0,
                            r->v[i], 0, hd_rods_tb(r, i), m_cpd(m), -1};
  free(x);
  return HD_OK;
}

static void m_box(const void *m, double *lx, double *ly) {
  *lx = (double)((const hd_rods *)m)->p.n;
  *ly = 0;
}

const hd_model_ops hd_model_rods = {
    "rods",   m_alloc,       m_alloc_restore, m_free,       m_next, m_checkpoint, m_time, m_cpd,
    m_events, m_temperature, m_sample,        m_log_states, m_box,  m_states,     NULL,   NULL};
