/* The initial state: placement (random sequential addition, a lattice, or a state file) and
 * Maxwellian velocities with zero total momentum at the scene's temperature. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>

#include "hd_scene_species.h"
#include "hd_sim_internal.h"
#include "hd_stop.h"

/* Does body i overlap any body already in the cells (or a wall)? */
static int overlaps_any(const hd_sim *s, int32_t i) {
  const hd_body *bi = &s->b[i];
  const hd_shape *si = &s->shape[bi->species];
  int nd = si->n;
  for (int a = 0; a < nd; a++) { /* inside the walls */
    double x, y;
    hd_kin_disk_pos(&bi->k, si, a, &x, &y);
    double r = 0.5 * si->dk[a];
    if (((s->walls & HD_WALL_LEFT) && x < r) || ((s->walls & HD_WALL_RIGHT) && x > s->lx - r) ||
        ((s->walls & HD_WALL_BOTTOM) && y < r) || ((s->walls & HD_WALL_TOP) && y > s->ly - r))
      return -2;
  }
  HD_FOR_NEIGHBOURS(s, bi->cell, {
    if (j == i) continue;
    const hd_body *bj = &s->b[j];
    const hd_shape *sj = &s->shape[bj->species];
    int nj = sj->n;
    hd_kin kj = bj->k;
    kj.x += sx;
    kj.y += sy;
    for (int a = 0; a < nd; a++) {
      double xa, ya;
      hd_kin_disk_pos(&bi->k, si, a, &xa, &ya);
      for (int c = 0; c < nj; c++) {
        double xb, yb, D = 0.5 * (si->dk[a] + sj->dk[c]);
        hd_kin_disk_pos(&kj, sj, c, &xb, &yb);
        if ((xb - xa) * (xb - xa) + (yb - ya) * (yb - ya) < D * D) return j;
      }
    }
  });
  return -1;
}

static double uniform_phi(gsl_rng *r) {
  return M_PI * (2.0 * gsl_rng_uniform(r) - 1.0);
}

/* Random sequential addition: each body at a uniform position and orientation, retried until it
 * overlaps nothing.  Returns 1 when some body needed more than max_tries attempts (the box is
 * too full for it: the caller then melts a lattice instead), -1 when a stop was requested (the
 * last bodies of a box past the jamming density take seconds: 6 s for 3e5 disks at 0.7). */
static int place_random(hd_sim *s) {
  const long max_tries = 20000;
  for (int32_t i = 0; i < s->n; i++) {
    if (hd_stop_requested) {
      for (int32_t j = 0; j < i; j++) hd_cells_remove(s, j);
      return -1;
    }
    hd_body *b = &s->b[i];
    long k;
    for (k = 0; k < max_tries; k++) {
      b->k.x = s->lx * gsl_rng_uniform(s->rng);
      b->k.y = s->ly * gsl_rng_uniform(s->rng);
      b->k.phi = s->shape[b->species].n > 1 ? uniform_phi(s->rng) : 0.0;
      hd_cells_insert(s, i, hd_cells_of(s, b->k.x, b->k.y));
      if (overlaps_any(s, i) == -1) break;
      hd_cells_remove(s, i);
    }
    if (k == max_tries) {
      for (int32_t j = 0; j < i; j++) hd_cells_remove(s, j);
      return 1;
    }
  }
  return 0;
}

/* The densest simple lattice for a melt: dimers all along x on an (a + d) x d grid (a dimer-only
 * scene), or a square grid of the largest body. */
static int place_dense_lattice(hd_sim *s, hd_error *err) {
  const double eps = 1.0 + 1e-9;
  double ex, ey;
  int dimers = -1; /* the [dimers] species, if it is the only one with bodies */
  for (int sp = 0; sp < s->nsp; sp++)
    if (s->sp_kind[sp] == HD_KIND_DIMER) dimers = sp;
  for (int sp = 0; sp < s->nsp; sp++)
    if (sp != dimers && s->n_species[sp]) dimers = -2;
  if (dimers >= 0) {
    ex = (s->shape[dimers].a + s->shape[dimers].d) * eps;
    ey = s->shape[dimers].d * eps;
  } else { /* the largest body present, and the [disks] diameter in any case */
    double w = 0.0;
    for (int sp = 0; sp < s->nsp; sp++)
      if (s->sp_kind[sp] == HD_KIND_DISK)
        w = fmax(w, s->shape[sp].d);
      else if (s->n_species[sp])
        w = fmax(w, 2.0 * hd_shape_radius(&s->shape[sp]));
    ex = ey = w * eps;
  }
  /* sites along each edge, in double (box = 1 1e300 overflowed an int32 cast); a row needs
   * no more than n of them, so the casts below are exact */
  double fx = fmin(floor(s->lx / ex), (double)s->n), fy = fmin(floor(s->ly / ey), (double)s->n);
  if (fx * fy < (double)s->n)
    return hd_error_set(
        err, HD_EINPUT,
        "[system] box %g x %g: %d bodies do not fit for placement = random, not "
        "even on a dense lattice (%.0f x %.0f sites of %g x %g) to melt; enlarge it",
        s->lx, s->ly, s->n, fx, fy, ex, ey);
  int32_t nx = (int32_t)fx, ny = (int32_t)fy;
  double ax = s->lx / nx, ay = s->ly / ny;
  for (int32_t i = 0; i < s->n; i++) {
    hd_body *b = &s->b[i];
    b->k.x = (i % nx + 0.5) * ax;
    b->k.y = (i / nx + 0.5) * ay;
    b->k.phi = 0.0;
    hd_cells_insert(s, i, hd_cells_of(s, b->k.x, b->k.y));
  }
  s->melt = 1;
  return HD_OK;
}

/* A rectangular lattice with spacing >= the largest body, orientations random. */
static int place_lattice(hd_sim *s, hd_error *err) {
  double range = 0.0;
  for (int sp = 0; sp < s->nsp; sp++)
    if (s->n_species[sp] > 0) range = fmax(range, 2.0 * hd_shape_radius(&s->shape[sp]));
  /* the grid hd_scene_check.c checks: at most floor(L / range) sites along each edge (spacing
   * >= range; equal means touching), as square as the box allows */
  double fx = fmax(1.0, floor(s->lx / range)), fy = fmax(1.0, floor(s->ly / range));
  double gx = fmin(fmin(fx, (double)s->n), fmax(1.0, ceil(sqrt((double)s->n * s->lx / s->ly))));
  double gy = ceil((double)s->n / gx);
  if (gy > fy) gy = fy, gx = fmin(fx, ceil((double)s->n / gy));
  int32_t nx = (int32_t)gx, ny = (int32_t)gy;
  double ax = s->lx / nx, ay = s->ly / ny;
  if ((double)nx * ny < (double)s->n || ax < range * (1 - 1e-12) || ay < range * (1 - 1e-12))
    return hd_error_set(err, HD_EINPUT,
                        "[init] placement = lattice: %d bodies need a %d x %d lattice of spacing "
                        ">= %g, but the box %g x %g gives %g x %g; enlarge [system] box",
                        s->n, nx, ny, range, s->lx, s->ly, ax, ay);
  for (int32_t i = 0; i < s->n; i++) {
    hd_body *b = &s->b[i];
    b->k.x = (i % nx + 0.5) * ax;
    b->k.y = (i / nx + 0.5) * ay;
    b->k.phi = s->shape[b->species].n > 1 ? uniform_phi(s->rng) : 0.0;
    hd_cells_insert(s, i, hd_cells_of(s, b->k.x, b->k.y));
  }
  return HD_OK;
}

void hd_init_velocities(hd_sim *s, double T) {
  if (s->n == 0) return; /* nothing to draw (the mean momentum below would be 0 / 0) */
  double px = 0.0, py = 0.0, mtot = 0.0;
  for (int32_t i = 0; i < s->n; i++) {
    hd_body *b = &s->b[i];
    const hd_shape *sh = &s->shape[b->species];
    double m = hd_shape_mass(sh), I = hd_shape_inertia(sh);
    b->k.vx = gsl_ran_gaussian_ziggurat(s->rng, sqrt(T / m));
    b->k.vy = gsl_ran_gaussian_ziggurat(s->rng, sqrt(T / m));
    b->k.omega = I > 0.0 ? gsl_ran_gaussian_ziggurat(s->rng, sqrt(T / I)) : 0.0;
    px += m * b->k.vx;
    py += m * b->k.vy;
    mtot += m;
  }
  double ux = px / mtot, uy = py / mtot, e_tr = 0.0, e_rot = 0.0;
  long n_rot = 0;
  for (int32_t i = 0; i < s->n; i++) {
    hd_body *b = &s->b[i];
    const hd_shape *sh = &s->shape[b->species];
    b->k.vx -= ux;
    b->k.vy -= uy;
    e_tr += 0.5 * hd_shape_mass(sh) * (b->k.vx * b->k.vx + b->k.vy * b->k.vy);
    e_rot += 0.5 * hd_shape_inertia(sh) * b->k.omega * b->k.omega;
    n_rot += hd_shape_inertia(sh) > 0.0;
  }
  double ftr = s->n > 1 && e_tr > 0.0 ? sqrt(T * (double)s->n / e_tr) : 1.0;
  double frot = n_rot > 0 && e_rot > 0.0 ? sqrt(0.5 * T * (double)n_rot / e_rot) : 1.0;
  for (int32_t i = 0; i < s->n; i++) {
    s->b[i].k.vx *= ftr;
    s->b[i].k.vy *= ftr;
    s->b[i].k.omega *= frot;
  }
}

/* What the arithmetic of a state row can resolve: an angle of at most HD_MAX_PHI radians (its
 * ulp 1.2e-10; phi = 1e300 is no angle), and a dimer's rim speed |omega| a / 2 at most
 * HD_MAX_SPIN_RATIO times the largest translational speed of the state (when it moves at all).
 * The contact search steps through the turns of a spinning dimer: its cost per unit time
 * grows as omega (two dimers at |v| ~ 1: 200 collisions in 0.13 s at omega = 1e5, 1.4 s at
 * 1e7; at 1e8 one collision in 11 s, at 1e10 2 events in 6 s). */
#define HD_MAX_PHI 1e6
#define HD_MAX_SPIN_RATIO 1e7

/* HD_EINPUT when a state row's angle or spin is beyond what the run can resolve (above). */
static int check_spins(const hd_sim *s, const hd_state_row *rows, long n, const hd_scene *sc,
                       hd_error *err) {
  double vmax = 0.0;
  for (long r = 0; r < n; r++) vmax = fmax(vmax, hypot(rows[r].vx, rows[r].vy));
  for (long r = 0; r < n; r++) {
    if (s->shape[rows[r].species].n == 1) continue; /* a disk has no angle */
    if (!(fabs(rows[r].phi) <= HD_MAX_PHI))
      return hd_error_set(err, HD_EINPUT,
                          "%s:%ld: column 4 (phi) = %g: an angle beyond +-%g rad is not resolved "
                          "(give it in (-pi, pi])",
                          sc->state_file, rows[r].line, rows[r].phi, HD_MAX_PHI);
    const hd_shape *sh = &s->shape[rows[r].species];
    double rim = fabs(rows[r].omega) *
                 (s->sp_kind[rows[r].species] == HD_KIND_DIMER ? 0.5 * sh->a : hd_shape_radius(sh));
    if (vmax > 0.0 && rim > HD_MAX_SPIN_RATIO * vmax)
      return hd_error_set(err, HD_EINPUT,
                          "%s:%ld: column 7 (omega) = %g: the rim speed |omega| a/2 = %g is more "
                          "than %g times the largest speed %g: the run would crawl through its "
                          "turns",
                          sc->state_file, rows[r].line, rows[r].omega, rim, HD_MAX_SPIN_RATIO,
                          vmax);
  }
  return HD_OK;
}

/* Bodies from a state CSV; the counts must agree with the scene's where the scene gives them. */
static int place_from_file(hd_sim *s, const hd_scene *sc, hd_error *err) {
  hd_state_row *rows = NULL;
  long n = 0;
  int rc = hd_state_csv_read_species(sc->state_file, sc, &rows, &n, err);
  for (long r = 0; !rc && r < n; r++)
    if (rows[r].species < 0 || rows[r].species >= s->nsp)
      rc = hd_error_set(err, HD_EINPUT, "%s:%ld: column 1 (kind): species %d is not in the scene",
                        sc->state_file, rows[r].line, rows[r].species);
  if (!rc) rc = check_spins(s, rows, n, sc, err);
  if (rc) {
    free(rows);
    return rc;
  }
  int32_t cnt[HD_MAX_SPECIES] = {0};
  for (long r = 0; r < n; r++) cnt[rows[r].species]++;
  if ((sc->n_dimers && sc->n_dimers != cnt[0]) || (sc->n_disks && sc->n_disks != cnt[1])) {
    free(rows);
    return hd_error_set(err, HD_EINPUT,
                        "%s: holds %d dimers and %d disks but the scene's "
                        "[dimers]/[disks] count say %ld and %ld",
                        sc->state_file, cnt[0], cnt[1], sc->n_dimers, sc->n_disks);
  }
  for (int sp = 0; sp < s->nsp; sp++)
    if (s->sp_kind[sp] == HD_KIND_BODY) {
      hd_scene_sp q;
      hd_scene_species_get(sc, sp, &q);
      if (q.count && q.count != cnt[sp]) {
        free(rows);
        return hd_error_set(err, HD_EINPUT,
                            "%s: holds %d bodies of species %s but its [species] count says %ld",
                            sc->state_file, cnt[sp], s->sp_name[sp], q.count);
      }
    }
  s->n = 0;
  for (int sp = 0; sp < s->nsp; sp++) s->n_species[sp] = cnt[sp], s->n += cnt[sp];
  free(s->b);
  s->b = hd_bodies_alloc(s->n);
  if (!s->b) {
    free(rows);
    return hd_error_set(err, HD_ENOMEM, "out of memory");
  }
  rc = hd_cells_alloc(s, err);
  int32_t next[HD_MAX_SPECIES] = {0};
  for (int sp = 1; sp < s->nsp; sp++) next[sp] = next[sp - 1] + cnt[sp - 1];
  long *line = malloc(sizeof(long) * (size_t)(s->n > 0 ? s->n : 1));
  for (long r = 0; rc == HD_OK && r < n; r++) {
    int sp = rows[r].species, turns = s->shape[sp].n > 1 || s->shape[sp].inertia > 0.0;
    int32_t i = next[sp]++;
    hd_body *b = &s->b[i];
    b->species = sp;
    b->next = -1;
    b->k = (hd_kin){rows[r].x,
                    rows[r].y,
                    rows[r].vx,
                    rows[r].vy,
                    turns ? remainder(rows[r].phi, 2 * M_PI) : 0.0,
                    turns ? rows[r].omega : 0.0};
    if (line) line[i] = rows[r].line;
    if (b->k.x < 0 || b->k.x >= s->lx || b->k.y < 0 || b->k.y >= s->ly) {
      rc = hd_error_set(err, HD_EINPUT, "%s:%ld: body at (%g, %g) is outside the box %g x %g",
                        sc->state_file, rows[r].line, b->k.x, b->k.y, s->lx, s->ly);
      break;
    }
    /* a speed whose square overflows (|v| ~ 1e160) gave inf energies and a run that crossed
     * cells for ever without a collision; 16 v^2 bounds the squares of relative velocities */
    double v2 = b->k.vx * b->k.vx + b->k.vy * b->k.vy, w2 = b->k.omega * b->k.omega;
    double e = 0.5 * hd_shape_mass(&s->shape[sp]) * v2 + 0.5 * hd_shape_inertia(&s->shape[sp]) * w2;
    if (!isfinite(16 * v2) || !isfinite(16 * w2) || !isfinite(e)) {
      rc = hd_error_set(err, HD_EINPUT,
                        "%s:%ld: velocity (%g, %g) or omega %g too large: its square is not a "
                        "finite number",
                        sc->state_file, rows[r].line, b->k.vx, b->k.vy, b->k.omega);
      break;
    }
    hd_cells_insert(s, i, hd_cells_of(s, b->k.x, b->k.y));
    int o = overlaps_any(s, i);
    if (o == -2)
      rc =
          hd_error_set(err, HD_EINPUT, "%s:%ld: body crosses a wall", sc->state_file, rows[r].line);
    else if (o >= 0)
      rc = hd_error_set(err, HD_EINPUT, "%s:%ld: body overlaps the body on line %ld",
                        sc->state_file, rows[r].line, line ? line[o] : -1L);
  }
  free(line);
  free(rows);
  return rc;
}

int hd_init_state(hd_sim *s, const hd_scene *sc, hd_error *err) {
  if (sc->placement == HD_PLACE_STATE) return place_from_file(s, sc, err);
  s->n = 0;
  for (int sp = 0; sp < s->nsp; sp++) s->n += s->n_species[sp];
  s->b = hd_bodies_alloc(s->n);
  if (!s->b) return hd_error_set(err, HD_ENOMEM, "out of memory for %d bodies", s->n);
  int rc = hd_cells_alloc(s, err);
  if (rc) return rc;
  for (int32_t i = 0, sp = 0, left = s->n_species[0]; i < s->n; i++) {
    while (left == 0) left = s->n_species[++sp]; /* dimers, disks, then each named species */
    s->b[i].species = sp;
    s->b[i].next = -1;
    left--;
  }
  if (s->n == 0) /* a scene without bodies: no grid to size (0 / 0 sites per row) */
    rc = HD_OK;
  else if (sc->placement == HD_PLACE_LATTICE)
    rc = place_lattice(s, err);
  else if ((rc = place_random(s)) < 0)
    rc = hd_error_set(err, HD_EINTR, "interrupted while placing the bodies of the set-up");
  else if (rc)
    rc = place_dense_lattice(s, err); /* too dense for random addition: melt a lattice */
  if (rc) return rc;
  hd_init_velocities(s, sc->temperature);
  return HD_OK;
}
