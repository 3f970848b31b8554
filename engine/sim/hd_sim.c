/* The event loop: hd_sim_alloc builds a simulation from a scene, hd_sim_next processes events
 * until the next collision.  Collision rules and contact times live in hd_body.c, prediction in
 * hd_predict.c, cells in hd_cells.c, the initial state in hd_init.c. */
#include <stddef.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hd_mem.h"
#include "hd_scene_species.h"
#include "hd_sim_internal.h"
#include "hd_stop.h"

/* Collisions whose |vn| is below this fraction of the thermal speed count as "slow"; this many
 * slow collisions in a row is inelastic collapse (the collision rate diverges while the
 * relative velocities vanish: an event-driven code cannot get past it). */
#define HD_SLOW_VN 1e-9
#define HD_SLOW_RUN 2000
/* Relative tolerance on the contact distance and on overlaps in verification mode. */
#define HD_VERIFY_TOL 1e-9
/* The flight, in smallest diameters, of a body at the rms speed after which the time origin is
 * rebased (rebase). */
#define HD_REBASE_TRAVEL 1e4

static const hd_wall default_walls[4] = {
    {0, 0.0, +1.0}, {0, 0.0, -1.0}, {1, 0.0, +1.0}, {1, 0.0, -1.0}};

/* Which pairs take the rough rule: beta > -1 or a species whose disks have inertia (q > 0). */
static void rough_flags(hd_sim *s) {
  for (int i = 0; i < s->nsp; i++) {
    for (int j = 0; j < s->nsp; j++)
      s->rough[i][j] = s->beta[i][j] > -1.0 || s->spin_q[i] > 0.0 || s->spin_q[j] > 0.0;
    s->wall_rough[i] = s->wall_beta > -1.0 || s->spin_q[i] > 0.0;
  }
}

/* Rough bodies (issue 29): each species' q (the disks' own inertia, hd_shape_set_q) and the
 * tangential restitutions.  A scene whose `rough` is 0 (none of its beta keys above -1, or a
 * scene filled in code with zeros) is smooth: beta = -1 everywhere. */
static int rough_setup(hd_sim *s, const hd_scene *sc, hd_error *err) {
  for (int i = 0; i < s->nsp; i++) {
    double q = i == 0   ? sc->dimer_q
               : i == 1 ? sc->disk_q
                        : sc->named[i - 2].q; /* hd_scene_species.h */
    if (hd_shape_set_q(&s->shape[i], q))
      return hd_error_set(err, HD_EINPUT, "scene: species %s: q = %g: must be in [0, 1]",
                          s->sp_name[i], q);
    s->spin_q[i] = q;
    for (int j = 0; j < s->nsp; j++) {
      double b = sc->rough ? sc->beta_pair[i][j] : -1.0;
      if (!(b >= -1.0 && b <= 1.0) || b != (sc->rough ? sc->beta_pair[j][i] : -1.0))
        return hd_error_set(err, HD_EINPUT,
                            "scene: beta of species %s with %s = %g: must be in [-1, 1] and "
                            "symmetric",
                            s->sp_name[i], s->sp_name[j], b);
      s->beta[i][j] = b;
    }
  }
  s->wall_beta = sc->rough ? sc->wall_beta : -1.0;
  if (!(s->wall_beta >= -1.0 && s->wall_beta <= 1.0))
    return hd_error_set(err, HD_EINPUT, "scene: [walls] beta = %g: must be in [-1, 1]",
                        s->wall_beta);
  rough_flags(s);
  return HD_OK;
}

/* The species table from the scene's (hd_scene_species.h: [dimers] 0, [disks] 1, then each
 * `[species NAME]` section 2, 3, ...), with the pair restitutions (hd_scene_pair_alpha).
 * HD_EINPUT for a named species
 * the engine cannot build (the scene's loader checks the same: this guards a scene filled by
 * hand). */
static int species_setup(hd_sim *s, const hd_scene *sc, hd_error *err) {
  if (sc->n_named < 0 || sc->n_named > HD_MAX_SPECIES - 2)
    return hd_error_set(err, HD_EINPUT, "scene: %d [species] sections, at most %d", sc->n_named,
                        HD_MAX_SPECIES - 2);
  s->nsp = hd_scene_nspecies(sc);
  for (int i = 0; i < s->nsp; i++) {
    hd_scene_sp sp;
    int bad = hd_scene_species_get(sc, i, &sp);
    if (sp.kind == HD_KIND_BODY &&
        (bad || sp.count < 0 || sp.count > HD_MAX_COUNT || !(sp.alpha >= 0.0 && sp.alpha <= 1.0)))
      return hd_error_set(err, HD_EINPUT,
                          "scene:%ld: [species %.31s]: count, disks or alpha out of range", sp.line,
                          sp.name);
    s->n_species[i] = (int32_t)sp.count;
    s->shape[i] = sp.shape;
    snprintf(s->sp_name[i], sizeof s->sp_name[0], "%.31s", sp.name);
    s->sp_kind[i] = sp.kind;
    s->alpha[i][i] = sp.alpha;
    for (int j = 0; j < i; j++) {
      double a = hd_scene_pair_alpha(sc, i, j);
      if (sp.kind == HD_KIND_BODY && !(a >= 0.0 && a <= 1.0))
        return hd_error_set(err, HD_EINPUT,
                            "scene:%ld: [species %.31s] alpha with species %d = %g: must be in "
                            "[0, 1]",
                            sp.line, sp.name, j, a);
      s->alpha[i][j] = s->alpha[j][i] = a;
    }
  }
  for (int i = 0; i < s->nsp; i++) {
    for (int j = 0; j < s->nsp; j++)
      s->pair_kind[i][j] = hd_coll_kind_of(s->sp_kind[i], s->sp_kind[j]);
    s->pair_kind[i][HD_MAX_SPECIES] = hd_coll_kind_of(s->sp_kind[i], HD_KIND_WALL);
  }
  int rc = rough_setup(s, sc, err);
  if (rc) return rc;
  int64_t n = 0;
  for (int i = 0; i < s->nsp; i++) n += s->n_species[i];
  for (int i = 0; i < s->nsp; i++)
    for (int j = 0; j < s->nsp; j++) s->ca_reach[i][j] = hd_ca_reach(&s->shape[i], &s->shape[j]);
  if (n > INT32_MAX)
    return hd_error_set(err, HD_EINPUT, "scene: %lld bodies: too many", (long long)n);
  return HD_OK;
}

/* Everything hd_sim_alloc and hd_sim_alloc_restore share: species, box, walls, RNG. */
static int sim_setup(hd_sim **out, const hd_scene *sc, hd_error *err) {
  *out = NULL;
  hd_sim *s = calloc(1, sizeof *s);
  if (!s) return hd_error_set(err, HD_ENOMEM, "out of memory");
  int rc = species_setup(s, sc, err);
  if (rc) {
    hd_sim_free(s);
    return rc;
  }
  s->wall_alpha = sc->wall_alpha;
  s->lx = sc->box_x;
  s->ly = sc->box_y;
  s->walls = sc->walls;
  s->zero_momentum = sc->placement != HD_PLACE_STATE; /* drawn velocities (resume: the same) */
  memcpy(s->wall, default_walls, sizeof s->wall);
  s->wall[1].pos = s->lx;
  s->wall[3].pos = s->ly;
  s->verify = sc->verify;
  s->angles = sc->log_collisions != HD_LOG_NONE; /* nobody reads them otherwise */
  s->rng = gsl_rng_alloc(gsl_rng_mt19937);
  if (!s->rng) {
    hd_sim_free(s);
    return hd_error_set(err, HD_ENOMEM, "out of memory");
  }
  gsl_rng_set(s->rng, (unsigned long)sc->seed);
  s->rebase_every = 100000;
  s->last_i = s->last_j = -1;
  s->cut_t = INFINITY;
  *out = s;
  return HD_OK;
}

/* Size of the bodies above which the event queue prefetches them (about a core's L2 cache), and
 * above which it prefetches in three stages (past the last-level cache: on the machine of
 * bench/results.md a random load took 103 ns in 16 MB (53 ns in an earlier run), 160 ns in
 * 64 MB). */
#define HD_PREFETCH_BYTES ((size_t)2 << 20)
#define HD_PREFETCH_FAR_BYTES ((size_t)32 << 20)

int hd_sim_queue_init(hd_sim *s, hd_error *err) {
  s->q = hd_queue_alloc(s->n);
  if (!s->q) return hd_error_set(err, HD_ENOMEM, "out of memory for the event queue");
  /* prefetching pays once the bodies no longer fit a core's L2 cache (bench: +25-30 % at
   * N = 1e5 and 1e6); below that its own cost wins.  Past the last level, the neighbours'
   * bodies too (+16 % at N = 1e6); within it that costs more than it saves (-8 % at 1e5). */
  size_t bytes = (size_t)s->n * sizeof(hd_body);
  if (bytes > HD_PREFETCH_FAR_BYTES)
    hd_queue_set_prefetch(s->q, hd_predict_prefetch_far, s, 3);
  else if (bytes > HD_PREFETCH_BYTES)
    hd_queue_set_prefetch(s->q, hd_predict_prefetch_near, s, 2);
  s->rebase_every = s->n > 1000 ? 100 * (int64_t)s->n : 100000;
  /* the travel criterion of rebase: (c.t v_rms)^2 > (HD_REBASE_TRAVEL dmin)^2, v_rms^2 =
   * 2 e_kin / M */
  double M = 0.0, dmin = INFINITY;
  for (int sp = 0; sp < s->nsp; sp++) {
    if (s->n_species[sp] == 0) continue;
    const hd_shape *sh = &s->shape[sp];
    M += s->n_species[sp] * hd_shape_mass(sh);
    for (int k = 0; k < sh->n; k++) dmin = sh->dk[k] < dmin ? sh->dk[k] : dmin;
  }
  s->rebase_e =
      s->n > 0 ? 0.5 * M * (HD_REBASE_TRAVEL * dmin) * (HD_REBASE_TRAVEL * dmin) : INFINITY;
  s->disks_only = 1; /* only [disks] bodies */
  for (int sp = 0; sp < s->nsp; sp++)
    if (s->sp_kind[sp] == HD_KIND_DISK)
      s->disks_d = s->shape[sp].d;
    else if (s->n_species[sp] > 0)
      s->disks_only = 0;
  s->partial_cross = s->disks_only && s->ncx >= 3 && s->ncy >= 3;
  return HD_OK;
}

/* Predicts every body's events from the current state, at clock 0. */
static void start(hd_sim *s) {
  hd_sim_sort(s);
  for (int32_t i = 0; i < s->n; i++) hd_predict(s, i);
  hd_queue_build(s->q, s->n, &s->b[0].ev_t, HD_BODY_STRIDE); /* tunes it to the real times */
  s->c.next_rebase = s->rebase_every;
  double e_tr, e_rot;
  hd_sim_energy(s, -1, &e_tr, &e_rot);
  s->c.e_kin = e_tr + e_rot;
}

/* Melts a lattice (placement too dense for random addition): elastic dynamics for 20
 * collisions per body, then fresh Maxwellian velocities and the clocks back to zero. */
static int melt(hd_sim *s, const hd_scene *sc, hd_error *err) {
  double alpha[HD_MAX_SPECIES][HD_MAX_SPECIES], wall_alpha = s->wall_alpha;
  double beta[HD_MAX_SPECIES][HD_MAX_SPECIES], wall_beta = s->wall_beta;
  memcpy(alpha, s->alpha, sizeof alpha);
  memcpy(beta, s->beta, sizeof beta);
  for (int a = 0; a < HD_MAX_SPECIES; a++)
    for (int b = 0; b < HD_MAX_SPECIES; b++) s->alpha[a][b] = 1.0, s->beta[a][b] = -1.0;
  s->wall_alpha = 1.0;
  s->wall_beta = -1.0;
  rough_flags(s);
  int rc = HD_OK;
  /* 40 cpd, or until nothing moves (no event left), or a bound on events for a gas whose
   * bodies barely collide */
  for (long calls = 1;
       rc == HD_OK && hd_sim_cpd(s) < 40.0 && s->c.events <= 1000 * (int64_t)s->n + 1000; calls++) {
    hd_event_out ev;
    if ((calls & 1023) == 0 && hd_stop_requested) { /* SIGINT: 15 s for 3e5 disks */
      rc = hd_error_set(err, HD_EINTR, "interrupted while melting the lattice of the set-up");
      break;
    }
    rc = hd_sim_next(s, INFINITY, &ev, err);
    if (rc == HD_SIM_BUSY) rc = HD_OK; /* the event bound above decides */
    if (rc == HD_SIM_IDLE) {
      rc = HD_OK;
      break;
    }
  }
  memcpy(s->alpha, alpha, sizeof alpha);
  memcpy(s->beta, beta, sizeof beta);
  s->wall_alpha = wall_alpha;
  s->wall_beta = wall_beta;
  rough_flags(s);
  if (rc) return rc;
  for (int32_t i = 0; i < s->n; i++) { /* positions at the current time become time 0 */
    hd_body_sync(s, i);
    s->b[i].t = 0.0;
  }
  memset(&s->c, 0, sizeof s->c);
  hd_init_velocities(s, sc->temperature);
  s->melt = 0;
  start(s);
  return HD_OK;
}

int hd_sim_alloc(hd_sim **out, const hd_scene *sc, hd_error *err) {
  hd_sim *s;
  int rc = sim_setup(&s, sc, err);
  if (rc) return rc;
  rc = hd_init_state(s, sc, err); /* sets n, b and the cells */
  if (!rc) {
    s->id = malloc(sizeof(int32_t) * (size_t)(s->n > 0 ? s->n : 1));
    if (!s->id) rc = hd_error_set(err, HD_ENOMEM, "out of memory");
    for (int32_t i = 0; !rc && i < s->n; i++) s->id[i] = i;
  }
  if (!rc) rc = hd_sim_queue_init(s, err);
  if (rc) {
    hd_sim_free(s);
    return rc;
  }
  for (int32_t i = 0; i < s->n; i++) s->b[i].ev_t = s->b[i].p_t = s->b[i].c_t = INFINITY;
  hd_queue_build(s->q, s->n, &s->b[0].ev_t, HD_BODY_STRIDE);
  start(s);
  if (s->melt) {
    rc = melt(s, sc, err);
    if (rc) {
      hd_sim_free(s);
      return rc;
    }
  }
  *out = s;
  return HD_OK;
}

int hd_sim_alloc_restore(hd_sim **out, const hd_scene *sc, const void *blob, size_t n,
                         hd_error *err) {
  hd_sim *s;
  int rc = sim_setup(&s, sc, err);
  if (rc) return rc;
  rc = hd_sim_restore_blob(s, blob, n, err);
  if (rc) {
    hd_sim_free(s);
    return rc;
  }
  *out = s;
  return HD_OK;
}

_Static_assert(sizeof(hd_body) == 128, "hd_body: two cache lines");
_Static_assert(offsetof(hd_body, ev_t) == 64, "hd_body: the hot fields fill the first line");

hd_body *hd_bodies_alloc(int32_t n) {
  size_t bytes = sizeof(hd_body) * (size_t)(n > 0 ? n : 1);
  hd_body *b = hd_mem_alloc(bytes);
  if (b) memset(b, 0, bytes);
  return b;
}

void hd_sim_free(hd_sim *s) {
  if (!s) return;
  hd_queue_free(s->q);
  gsl_rng_free(s->rng);
  free(s->head);
  free(s->b);
  free(s->id);
  free(s);
}

void hd_sim_body_now(const hd_sim *s, int32_t i, hd_kin *k) {
  *k = s->b[i].k;
  hd_kin_advance(k, s->c.t - s->b[i].t);
}

void hd_sim_energy(const hd_sim *s, int sp, double *e_tr, double *e_rot) {
  double tr = 0.0, rot = 0.0;
  for (int32_t i = 0; i < s->n; i++) {
    const hd_body *b = &s->b[i];
    if (sp >= 0 && b->species != sp) continue;
    const hd_shape *sh = &s->shape[b->species];
    tr += 0.5 * hd_shape_mass(sh) * (b->k.vx * b->k.vx + b->k.vy * b->k.vy);
    rot += 0.5 * hd_shape_inertia(sh) * b->k.omega * b->k.omega;
  }
  *e_tr = tr;
  *e_rot = rot;
}

/* Largest relative overlap (D - dist)/D between any disks of bodies i and j (j shifted). */
static double pair_overlap(const hd_sim *s, const hd_kin *ki, const hd_shape *si, const hd_kin *kj,
                           const hd_shape *sj) {
  double worst = -INFINITY;
  int ni = si->n, nj = sj->n;
  (void)s;
  for (int a = 0; a < ni; a++) {
    double xa, ya;
    hd_kin_disk_pos(ki, si, a, &xa, &ya);
    for (int b = 0; b < nj; b++) {
      double xb, yb, D = 0.5 * (si->dk[a] + sj->dk[b]);
      hd_kin_disk_pos(kj, sj, b, &xb, &yb);
      double dist = hypot(xb - xa, yb - ya);
      worst = fmax(worst, (D - dist) / D);
    }
  }
  return worst;
}

/* Largest overlap of body i with its neighbours at the current time. */
static double body_overlap(const hd_sim *s, int32_t i, int32_t *with) {
  hd_kin ki;
  hd_sim_body_now(s, i, &ki);
  double worst = -INFINITY;
  HD_FOR_NEIGHBOURS(s, s->b[i].cell, {
    if (j == i) continue;
    hd_kin kj;
    hd_sim_body_now(s, j, &kj);
    kj.x += sx;
    kj.y += sy;
    double o = pair_overlap(s, &ki, &s->shape[s->b[i].species], &kj, &s->shape[s->b[j].species]);
    if (o > worst) worst = o, *with = j;
  });
  return worst;
}

double hd_sim_max_overlap(const hd_sim *s, int32_t *i, int32_t *j) {
  double worst = -INFINITY;
  *i = *j = -1;
  for (int32_t k = 0; k < s->n; k++) {
    int32_t w = -1;
    double o = body_overlap(s, k, &w);
    if (o > worst) worst = o, *i = k, *j = w;
  }
  return worst;
}

/* Moves body i across the cell face of its crossing event, wrapping through the periodic box;
 * returns 1 if it wrapped. */
static int cross_cell(hd_sim *s, int32_t i) {
  hd_body *b = &s->b[i];
  int32_t cx, cy;
  hd_body_cxy(s, b, &cx, &cy);
  /* the face is random from crossing to crossing: a switch on it was mispredicted 3 times in 4,
   * so the step is looked up, and only a crossing through the box's edge branches on it */
  const int dir = b->c_dir;
  cx += hd_face_step[dir][0];
  cy += hd_face_step[dir][1];
  const int wrapped = !(((uint32_t)cx < (uint32_t)s->ncx) & ((uint32_t)cy < (uint32_t)s->ncy));
  if (__builtin_expect(wrapped, 0)) {
    switch (dir) {
    case 0:
      cx = 0, b->k.x -= s->lx, b->wx++;
      break;
    case 1:
      cx = s->ncx - 1, b->k.x += s->lx, b->wx--;
      break;
    case 2:
      cy = 0, b->k.y -= s->ly, b->wy++;
      break;
    default:
      cy = s->ncy - 1, b->k.y += s->ly, b->wy--;
      break;
    }
  }
  hd_cells_remove(s, i);
  hd_cells_insert_xy(s, i, cx, cy);
  return wrapped;
}

void hd_sim_sort(hd_sim *s) {
  int32_t n = s->n;
  int32_t *order = malloc(sizeof(int32_t) * (size_t)(n > 0 ? n : 1));
  int32_t *newidx = malloc(sizeof(int32_t) * (size_t)(n > 0 ? n : 1));
  int32_t *newid = malloc(sizeof(int32_t) * (size_t)(n > 0 ? n : 1));
  hd_body *nb = hd_bodies_alloc(n);
  if (!order || !newidx || !newid || !nb) { /* sorting is an optimisation: skip it */
    free(order), free(newidx), free(newid), free(nb);
    hd_queue_build(s->q, n, &s->b[0].ev_t, HD_BODY_STRIDE);
    return;
  }
  int32_t k = 0;
  for (int64_t c = 0; c < (int64_t)s->ncx * s->ncy; c++)
    for (int32_t j = s->head[c]; j >= 0; j = s->b[j].next) order[k++] = j;
  for (k = 0; k < n; k++) newidx[order[k]] = k;
  for (k = 0; k < n; k++) {
    nb[k] = s->b[order[k]];
    newid[k] = s->id[order[k]];
    if (nb[k].p_type == HD_EV_PAIR) nb[k].p_partner = newidx[nb[k].p_partner];
  }
  if (s->last_i >= 0) s->last_i = newidx[s->last_i];
  if (s->last_j >= 0) s->last_j = newidx[s->last_j];
  free(s->b);
  free(s->id);
  s->b = nb;
  s->id = newid;
  free(order);
  free(newidx);
  hd_cells_rebuild(s);
  hd_queue_build(s->q, n, &s->b[0].ev_t, HD_BODY_STRIDE);
}

/* Sets the booked kinetic energy (the running sum of every collision's de) to the bodies' own.
 * The sum's round-off is absolute, ~1e-16 of the energy it started from per collision: a gas
 * that cools by 16 decades has more error than energy, and a booked energy <= 0 made every
 * collision "slow" (check_collapse): 64 disks at alpha = 0.95 were reported as collapsed at
 * E/E0 ~ 1e-16 while colliding at the thermal speed.  Called at every rebase and before a
 * collapse is reported. */
static void rebook_energy(hd_sim *s) {
  double e_tr, e_rot;
  hd_sim_energy(s, -1, &e_tr, &e_rot);
  s->c.e_kin = e_tr + e_rot;
}

/* Whether nothing can ever happen again: every body at rest (spinning at most), none within
 * reach of another (centres farther apart than the sum of their reaches, (a + d)/2 each), and
 * no spinning body within reach of a wall (a lone dimer spinning between walls made 1.25e8
 * wake-ups in 8 s and no collision, for ever).  Then the wake-ups of the spinners (HD_WAKE)
 * would go on for ever; checked only when one of them finds no contact. */
static int frozen(const hd_sim *s) {
  for (int32_t i = 0; i < s->n; i++)
    if (s->b[i].k.vx != 0.0 || s->b[i].k.vy != 0.0) return 0;
  double reach[HD_MAX_SPECIES];
  for (int sp = 0; sp < s->nsp; sp++) reach[sp] = hd_shape_radius(&s->shape[sp]) * (1 + 1e-9);
  for (int32_t i = 0; i < s->n; i++) {
    const hd_body *bi = &s->b[i];
    int close = 0;
    HD_FOR_NEIGHBOURS(s, bi->cell, {
      if (j != i && !close) {
        const hd_body *bj = &s->b[j];
        double dx = bj->k.x + sx - bi->k.x, dy = bj->k.y + sy - bi->k.y,
               R = reach[bi->species] + reach[bj->species];
        close = dx * dx + dy * dy <= R * R;
      }
    });
    if (close) return 0;
    static const unsigned bit[4] = {HD_WALL_LEFT, HD_WALL_RIGHT, HD_WALL_BOTTOM, HD_WALL_TOP};
    for (int w = 0; w < 4 && bi->k.omega != 0.0 && s->shape[bi->species].tag != HD_KIND_DISK; w++)
      if ((s->walls & bit[w]) &&
          fabs((s->wall[w].axis ? bi->k.y : bi->k.x) - s->wall[w].pos) <= reach[bi->species])
        return 0;
  }
  return 1;
}

/* Takes a periodic system to its centre-of-mass frame once its drift reaches 1e-3 of the
 * thermal speed.  The total momentum is zero only to round-off (~1e-17 of the initial speeds),
 * so a gas that cools by some 30 decades in energy ends up moving as a whole at that drift:
 * its bodies then cross cells at the drift speed while they collide at the thermal one (64
 * disks at alpha = 0.95 took 1.4e5 crossings per collision at E/E0 ~ 1e-33), and the relative
 * velocities, stored as differences of the drift, lose their digits.  Galilean invariance makes
 * the boost exact physics: every body is brought to now, the drift subtracted, every event
 * predicted again (the caller rebuilds the queue).  Not with walls, which hold momentum, nor
 * for bodies from a state file, whose total momentum is the user's. */
static void remove_drift(hd_sim *s) {
  double px = 0, py = 0, M = 0, e2 = 0;
  for (int32_t i = 0; i < s->n; i++) {
    const hd_body *b = &s->b[i];
    double m = hd_shape_mass(&s->shape[b->species]);
    px += m * b->k.vx, py += m * b->k.vy, M += m;
  }
  if (!(M > 0)) return;
  double Vx = px / M, Vy = py / M;
  for (int32_t i = 0; i < s->n; i++) {
    const hd_body *b = &s->b[i];
    double m = hd_shape_mass(&s->shape[b->species]), ux = b->k.vx - Vx, uy = b->k.vy - Vy;
    e2 += m * (ux * ux + uy * uy);
  }
  if (!(Vx * Vx + Vy * Vy > 1e-6 * e2 / M)) return; /* drift below 1e-3 of the thermal speed */
  for (int32_t i = 0; i < s->n; i++) {
    hd_body_sync(s, i);
    s->b[i].k.vx -= Vx, s->b[i].k.vy -= Vy;
  }
  for (int32_t i = 0; i < s->n; i++) hd_predict(s, i);
  s->drift_removed++;
}

/* Shifts the time origin to the current time (keeps times small: precision does not decay).
 * Every rebase_every events, and also once a typical body (at the rms speed of the booked
 * energy) has flown HD_REBASE_TRAVEL of the smallest diameter since the last: the clock's
 * round-off, ~1e-16 of that flight, then stays below ~1e-12 of a diameter for bodies a few
 * times faster than the rms.  In a very dilute gas the clock used to grow unchecked before the
 * event count came (5 disks at area fraction 1e-9 failed verification at t = 4.9e7: 6.3e-9 of a
 * diameter); in gases denser than area fraction ~1e-3 a body flies less than that between
 * event-count rebases, so their runs are unchanged bit for bit. */
static void rebase(hd_sim *s) {
  double now = s->c.t;
  for (int32_t i = 0; i < s->n; i++) {
    hd_body *b = &s->b[i];
    b->t -= now; /* INFINITY stays INFINITY below */
    b->ev_t -= now;
    b->p_t -= now;
    b->c_t -= now;
  }
  s->c.t_offset += now;
  s->c.t_last -= now;
  s->c.t = 0.0;
  if (!s->walls && s->zero_momentum) remove_drift(s);
  rebook_energy(s);
  hd_sim_sort(s); /* also rebuilds the queue, whose order rounding may have changed */
}

/* The kind of a collision of i with j (j < 0: a wall): of their species (hd_sim.pair_kind). */
static hd_coll_kind collision_kind(const hd_sim *s, int32_t i, int32_t j) {
  return s->pair_kind[s->b[i].species][j < 0 ? HD_MAX_SPECIES : s->b[j].species];
}

/* Pile-up bookkeeping after any collision: HD_PILEUP collisions in a row, each less than
 * HD_PILEUP_DT of the running mean time between collisions after the previous one, is a
 * pile-up at one instant — inelastic collapse, or a body wedged in a double contact (a disk in
 * the gap of a dimer with a = 2d touches both its disks at once): the event-driven method
 * cannot get past it.  By chance (exponential gaps) such a run has probability ~1e-9^1000. */
#define HD_PILEUP 1000
#define HD_PILEUP_DT 1e-9
static int check_pileup(hd_sim *s, int32_t i, int32_t j, hd_error *err) {
  double dt = s->c.t - s->c.t_last;
  s->c.t_last = s->c.t;
  if (s->c.dt_mean > 0.0 && dt < HD_PILEUP_DT * s->c.dt_mean) {
    if (++s->c.pile_run >= HD_PILEUP)
      return hd_error_set(err, HD_ECOLLAPSE,
                          "collisions pile up at t = %.17g after %lld collisions: %d in a row "
                          "within %g of the mean time between collisions, last between bodies "
                          "%d and %d (inelastic collapse, or a body wedged in a double contact)",
                          hd_sim_time(s), (long long)(s->c.collisions + s->c.wall_hits), HD_PILEUP,
                          HD_PILEUP_DT, s->id[i], j >= 0 ? s->id[j] : j);
    return HD_OK;
  }
  s->c.pile_run = 0;
  s->c.dt_mean = s->c.dt_mean > 0.0 ? 0.999 * s->c.dt_mean + 0.001 * dt : dt;
  return HD_OK;
}

/* Collapse bookkeeping after a collision with normal relative velocity vn; a wall collision
 * (wall = 1) adds to the run of slow collisions but never ends it (the walls' fast hits would
 * hide a collapse of the pairs). */
static int check_collapse(hd_sim *s, double vn, int wall, hd_error *err) {
  double mass = 0.0;
  for (int sp = 0; sp < s->nsp; sp++) mass += s->n_species[sp] * hd_shape_mass(&s->shape[sp]);
  double vth = sqrt(2.0 * fmax(s->c.e_kin, 0.0) / mass);
  if (fabs(vn) < HD_SLOW_VN * vth || vth == 0.0) {
    if (++s->c.slow_run < HD_SLOW_RUN) return HD_OK;
    rebook_energy(s); /* judged against the bodies' energy, not the booked sum */
    vth = sqrt(2.0 * fmax(s->c.e_kin, 0.0) / mass);
    if (!(fabs(vn) < HD_SLOW_VN * vth || vth == 0.0)) {
      s->c.slow_run = 0;
      return HD_OK;
    }
    if (s->last_j < 0) /* a body held against a wall (last_j = -1 - wall) */
      return hd_error_set(err, HD_ECOLLAPSE,
                          "inelastic collapse at t = %.17g after %lld collisions and %lld wall "
                          "collisions: %d collisions in a row with |vn| < %g of the thermal "
                          "speed, last of body %d with wall %d (a lasting contact: a body "
                          "pressed or turning against a wall of low alpha)",
                          hd_sim_time(s), (long long)s->c.collisions, (long long)s->c.wall_hits,
                          HD_SLOW_RUN, HD_SLOW_VN, s->id[s->last_i], -1 - s->last_j);
    return hd_error_set(err, HD_ECOLLAPSE,
                        "inelastic collapse at t = %.17g after %lld collisions: %d collisions "
                        "in a row with |vn| < %g of the thermal speed, last between bodies %d "
                        "and %d",
                        hd_sim_time(s), (long long)s->c.collisions, HD_SLOW_RUN, HD_SLOW_VN,
                        s->id[s->last_i], s->id[s->last_j]);
  } else if (!wall) {
    s->c.slow_run = 0;
  }
  return HD_OK;
}

/* Verification of a pair collision: the touching disks are at contact distance. */
static int verify_contact(const hd_sim *s, const hd_kin *ki, const hd_kin *kj, int32_t i, int32_t j,
                          int ka, int kb, hd_error *err) {
  const hd_shape *si = &s->shape[s->b[i].species], *sj = &s->shape[s->b[j].species];
  double xa, ya, xb, yb;
  hd_kin_disk_pos(ki, si, ka, &xa, &ya);
  hd_kin_disk_pos(kj, sj, kb, &xb, &yb);
  double D = 0.5 * (si->dk[ka] + sj->dk[kb]), gap = (hypot(xb - xa, yb - ya) - D) / D;
  if (fabs(gap) > HD_VERIFY_TOL)
    return hd_error_set(err, HD_EPHYS,
                        "verification: bodies %d and %d collide at distance "
                        "%.3g of a diameter from contact, t = %.17g",
                        s->id[i], s->id[j], gap, hd_sim_time(s));
  return HD_OK;
}

/* Verification of a collision: the touching disks are at contact distance and neither body
 * overlaps anything. */
static int verify_collision(hd_sim *s, int32_t i, int32_t j, hd_error *err) {
  int32_t who = -1;
  double o = body_overlap(s, i, &who);
  if (j >= 0) {
    int32_t w2 = -1;
    double o2 = body_overlap(s, j, &w2);
    if (o2 > o) o = o2, i = j, who = w2;
  }
  if (o > s->max_overlap) s->max_overlap = o;
  if (o > HD_VERIFY_TOL)
    return hd_error_set(err, HD_EPHYS,
                        "verification: bodies %d and %d overlap by %.3g of a "
                        "diameter at t = %.17g",
                        s->id[i], who >= 0 ? s->id[who] : -1, o, hd_sim_time(s));
  return HD_OK;
}

int hd_sim_next(hd_sim *s, double t_stop, hd_event_out *ev, hd_error *err) {
  for (long quiet = 0;; quiet++) {
    if (quiet >= HD_SIM_BUSY_EVENTS || s->cut) { /* (a cut: a stop was requested) */
      s->cut = 0;
      return HD_SIM_BUSY;
    }
    if (s->c.events >= s->c.next_rebase) {
      rebase(s);
      s->c.next_rebase += s->rebase_every;
    } else if (s->c.t * s->c.t * s->c.e_kin > s->rebase_e) {
      rebase(s); /* a dilute gas: the clock grew before the event count did */
    }
    if (s->n == 0) return HD_SIM_IDLE;
    int32_t i = hd_queue_top(s->q);
    hd_body *bi = &s->b[i];
    double te = bi->ev_t;
    double stop_rel = t_stop - s->c.t_offset;
    if (te > stop_rel || te == INFINITY) { /* (no event left: every body at rest) */
      if (stop_rel > s->c.t && stop_rel < INFINITY) s->c.t = stop_rel;
      return te == INFINITY && stop_rel == INFINITY ? HD_SIM_IDLE : HD_SIM_STOPTIME;
    }
    if (!(te >= s->c.t)) /* event times never decrease (checked in every build; NaN included) */
      return hd_error_set(err, HD_EPHYS, "event time %.17g of body %d is before the clock %.17g",
                          te + s->c.t_offset, s->id[i], hd_sim_time(s));
    s->c.t = te;
    s->c.events++;

    if (bi->c_t <= bi->p_t) { /* cell crossing */
      hd_body_sync(s, i);
      if (bi->c_dir == HD_WAKE) { /* a spinner at rest: only predicted again */
        hd_predict(s, i);
        if (bi->p_type == HD_EV_NONE && frozen(s)) return HD_SIM_IDLE;
        continue;
      }
      int wrapped = cross_cell(s, i);
      hd_predict_crossed(s, i, wrapped);
      continue;
    }
    if (bi->p_type == HD_EV_WALL) {
      hd_body_sync(s, i);
      int w = bi->p_partner, ka = bi->p_ka;
      hd_collision_info info;
      if (s->wall_rough[bi->species])
        hd_collide_rough_wall(&bi->k, &s->shape[bi->species], ka, &s->wall[w], s->wall_alpha,
                              s->wall_beta, &info);
      else
        hd_collide_wall(&bi->k, &s->shape[bi->species], ka, &s->wall[w], s->wall_alpha, &info);
      bi->ncoll++;
      s->c.wall_hits++;
      s->c.e_kin += info.de;
      *ev = (hd_event_out){hd_sim_time(s), collision_kind(s, i, -1), i, -1 - w, ka, -1, info};
      if (s->verify) {
        int rc = verify_collision(s, i, -1, err);
        if (rc) return rc;
      }
      hd_predict(s, i);
      int prc = check_pileup(s, i, -1 - w, err);
      if (prc || !(s->wall_alpha < 1.0)) return prc;
      /* a train of ever slower wall collisions (a body turning against a wall of alpha ~ 0:
       * 2e6 collisions 7e-11 apart with vn = -2.6e-13, for ever) is a collapse too */
      s->last_i = i;
      s->last_j = -1 - w;
      return check_collapse(s, info.vn, 1, err);
    }
    /* pair event */
    int32_t j = bi->p_partner;
    hd_body *bj = &s->b[j];
    if (bj->ncoll != bi->p_pcount) { /* the partner changed course: stale */
      s->c.stale++;
      hd_body_sync(s, i);
      hd_predict(s, i);
      continue;
    }
    hd_body_sync(s, i);
    hd_body_sync(s, j);
    double sx = hd_image_code(bi->p_imx, bj->wx, bi->wx) * s->lx;
    double sy = hd_image_code(bi->p_imy, bj->wy, bi->wy) * s->ly;
    hd_kin kj = bj->k;
    kj.x += sx;
    kj.y += sy;
    int ka = bi->p_ka, kb = bi->p_kb;
    if (s->rough[bi->species][bj->species])
      hd_collide_rough_pair(&bi->k, &s->shape[bi->species], &kj, &s->shape[bj->species], ka, kb,
                            s->alpha[bi->species][bj->species], s->beta[bi->species][bj->species],
                            &ev->info);
    else
      hd_collide_pair_ex(&bi->k, &s->shape[bi->species], &kj, &s->shape[bj->species], ka, kb,
                         s->alpha[bi->species][bj->species], s->angles, &ev->info);
    if (s->verify) {
      int rc = verify_contact(s, &bi->k, &kj, i, j, ka, kb, err);
      if (rc) return rc;
    }
    bj->k.vx = kj.vx;
    bj->k.vy = kj.vy;
    bj->k.omega = kj.omega;
    bi->ncoll++;
    bj->ncoll++;
    s->c.collisions++;
    s->c.e_kin += ev->info.de;
    s->last_i = i;
    s->last_j = j;
    *ev = (hd_event_out){hd_sim_time(s), collision_kind(s, i, j), i, j, ka, kb, ev->info};
    if (bi->species > bj->species) { /* the lower species first (the dimer of dimer-disk) */
      ev->i = j, ev->j = i, ev->ka = kb, ev->kb = ka;
      double th = ev->info.theta_i;
      ev->info.theta_i = ev->info.theta_j, ev->info.theta_j = th;
    }
    if (s->verify) {
      int rc = verify_collision(s, i, j, err);
      if (rc) return rc;
    }
    hd_predict_after_pair(s, i, j);
    int prc = check_pileup(s, i, j, err);
    if (prc) return prc;
    if (s->alpha[bi->species][bj->species] < 1.0) {
      int rc = check_collapse(s, ev->info.vn, 0, err);
      if (rc) return rc;
    }
    return HD_OK;
  }
}
