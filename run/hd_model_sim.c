/* The 2D engine (hd_sim: disks and dimers) seen through hd_model_ops. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hd_model.h"
#include "hd_sim.h"
#include "rods_model.h"

static int m_alloc(void **m, const hd_scene *sc, hd_error *err) {
  return hd_sim_alloc((hd_sim **)m, sc, err);
}
static int m_alloc_restore(void **m, const hd_scene *sc, const void *blob, size_t n,
                           hd_error *err) {
  return hd_sim_alloc_restore((hd_sim **)m, sc, blob, n, err);
}
static void m_free(void *m) {
  hd_sim_free(m);
}

static int m_next(void *m, double t_stop, hd_collision_row *row, hd_error *err) {
  hd_event_out ev;
  int rc = hd_sim_next(m, t_stop, &ev, err);
  if (rc) return rc;
  const hd_sim *s = m;
  /* seq is the store's; the rod-rod columns (eps ... tb_j) are stored NULL for these kinds */
  *row = (hd_collision_row){.seq = 0,
                            .t = ev.t,
                            .kind = ev.kind,
                            .i = s->id[ev.i],
                            .j = ev.j >= 0 ? s->id[ev.j] : ev.j,
                            .disk_i = ev.ka,
                            .disk_j = ev.kb,
                            .theta_i = ev.info.theta_i,
                            .theta_j = ev.info.theta_j,
                            .f = ev.info.f,
                            .de = ev.info.de,
                            .vn = ev.info.vn,
                            .eps = NAN,
                            .e_tr = NAN,
                            .tb_i = NAN,
                            .tb_j = NAN};
  return HD_OK;
}

static int m_checkpoint(const void *m, void **blob, size_t *n, hd_error *err) {
  return hd_sim_checkpoint(m, blob, n, err);
}
static double m_time(const void *m) {
  return hd_sim_time(m);
}
static double m_cpd(const void *m) {
  return hd_sim_cpd(m);
}
static int64_t m_events(const void *m) {
  return ((const hd_sim *)m)->c.events;
}
static double m_temperature(const void *m) {
  const hd_sim *s = m;
  /* 2 translational degrees of freedom per body, 1 rotational per body with a moment of inertia
   * (a dimer of a = 0 has none and no rotational energy) */
  double dof = 2.0 * s->n;
  for (int sp = 0; sp < s->nsp; sp++)
    if (hd_shape_inertia(&s->shape[sp]) > 0) dof += s->n_species[sp];
  return 2.0 * s->c.e_kin / dof;
}

static void m_sample(const void *m, hd_sample_row *row) {
  const hd_sim *s = m;
  double e_tr, e_rot;
  hd_sim_energy(s, -1, &e_tr, &e_rot); /* each species': m_log_species_sample */
  hd_state_measures q;
  hd_sim_state(s, &q);
  *row = (hd_sample_row){.t = hd_sim_time(s),
                         .collisions = s->c.collisions,
                         .cpd = hd_sim_cpd(s),
                         .e_tr = e_tr / s->n,
                         .e_rot = e_rot / s->n,
                         .flow_frac = q.flow_frac,
                         .flow_chaos = q.flow_chaos,
                         .count_var = q.count_var,
                         .s_rho = q.s_rho,
                         .s_perp = q.s_perp,
                         .s_par = q.s_par};
}

/* states.kind of body i: its species' kind (hd_sim.sp_kind). */
static int body_kind(const hd_sim *s, int32_t i) {
  return s->sp_kind[s->b[i].species];
}

static int m_log_states(const void *m, hd_db *db, int64_t run, const char *label, hd_error *err) {
  const hd_sim *s = m;
  for (int32_t i = 0; i < s->n; i++) {
    hd_kin k;
    hd_sim_body_now(s, i, &k);
    hd_state_rec rec = {hd_sim_time(s), s->id[i],      body_kind(s, i), k.x, k.y, k.phi, k.vx, k.vy,
                        k.omega,        hd_sim_cpd(s), s->b[i].species};
    int rc = hd_db_log_state(db, run, label, &rec, err);
    if (rc) return rc;
  }
  return HD_OK;
}

static int m_states(const void *m, hd_state_rec *out, hd_error *err) {
  (void)err;
  const hd_sim *s = m;
  for (int32_t i = 0; i < s->n; i++) {
    hd_kin k;
    hd_sim_body_now(s, i, &k);
    out[i] =
        (hd_state_rec){hd_sim_time(s), s->id[i],      body_kind(s, i), k.x, k.y, k.phi, k.vx, k.vy,
                       k.omega,        hd_sim_cpd(s), s->b[i].species};
  }
  return HD_OK;
}

/* Appends x to buf (size bytes, NUL-terminated) in the shortest %g form that reads back as x. */
static void put_exact(char *buf, size_t size, double x) {
  char b[40];
  for (int prec = 15; prec <= 17; prec++) {
    snprintf(b, sizeof b, "%.*g", prec, x);
    if (strtod(b, NULL) == x) break;
  }
  size_t n = strlen(buf);
  snprintf(buf + n, size > n ? size - n : 0, "%s", b);
}

static int m_log_species(const void *m, hd_db *db, int64_t run, hd_error *err) {
  const hd_sim *s = m;
  for (int sp = 0; sp < s->nsp; sp++) {
    if (s->n_species[sp] == 0) continue;
    const hd_shape *sh = &s->shape[sp];
    char disks[HD_MAX_BODY_DISKS * 4 * 26 + 16] = "";
    for (int k = 0; k < sh->n; k++) {
      const double v[4] = {sh->ox[k], sh->oy[k], sh->dk[k], sh->mk[k]};
      for (int c = 0; c < 4; c++) {
        put_exact(disks, sizeof disks, v[c]);
        strncat(disks, c < 3 ? " " : k + 1 < sh->n ? "; " : "", sizeof disks - strlen(disks) - 1);
      }
    }
    hd_species_rec rec = {sp,       s->sp_name[sp],      disks, s->n_species[sp],
                          sh->mass, hd_shape_inertia(sh)};
    int rc = hd_db_log_species(db, run, &rec, err);
    if (rc) return rc;
  }
  return HD_OK;
}

static int m_log_species_sample(const void *m, hd_db *db, int64_t run, hd_error *err) {
  const hd_sim *s = m;
  for (int sp = 0; sp < s->nsp; sp++) {
    if (s->n_species[sp] == 0) continue;
    double et, er;
    hd_sim_energy(s, sp, &et, &er);
    hd_species_sample row = {hd_sim_time(s), sp, et / s->n_species[sp], er / s->n_species[sp]};
    int rc = hd_db_log_species_sample(db, run, &row, err);
    if (rc) return rc;
  }
  return HD_OK;
}

static void m_box(const void *m, double *lx, double *ly) {
  *lx = ((const hd_sim *)m)->lx;
  *ly = ((const hd_sim *)m)->ly;
}

const hd_model_ops hd_model_bodies2d = {
    "bodies2d", m_alloc,       m_alloc_restore, m_free,
    m_next,     m_checkpoint,  m_time,          m_cpd,
    m_events,   m_temperature, m_sample,        m_log_states,
    m_box,      m_states,      m_log_species,   m_log_species_sample};

const hd_model_ops *hd_model_for_scene(const hd_scene *sc) {
  return sc->n_rods > 0 ? &hd_model_rods : &hd_model_bodies2d;
}
