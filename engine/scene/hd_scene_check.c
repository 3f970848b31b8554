/* hd_scene_check: the checks of the whole scene once every key is read (hd_scene_check_all):
 * keys that depend on each other, the box (given or from area_fraction) and the placement, the
 * [init] state file, the thermal range, stop conditions, frames and snapshots, a [rods] ring. */
#include "hd_scene_internal.h"
#include "rods.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* A snapshot that cannot be taken is refused at set-up: a time past stop_time, a cpd past
 * stop_cpd (a list in the other unit than the stop cannot be checked before the run; the run's
 * message says what it did not take). */
static int check_vel_at(ctx *c) {
  const hd_scene *sc = c->sc;
  if (sc->n_velocities_at == 0) return HD_OK;
  int k = sc->velocities_in_time ? K_LVELT : K_LVEL;
  double last = sc->velocities_at[sc->n_velocities_at - 1];
  double stop = sc->velocities_in_time ? sc->stop_time : sc->stop_cpd;
  if (stop > 0 && last > stop)
    return FAIL_KEY(c, k, "%.17g is past %s = %.17g: that snapshot would never be taken", last,
                    sc->velocities_in_time ? "stop_time" : "stop_cpd", stop);
  return HD_OK;
}

/* Body counts of the scene (dimers, disks and each named species) summed. */
long hd_scene_body_count(const hd_scene *sc) {
  long n = sc->n_dimers + sc->n_disks;
  for (int j = 0; j < sc->n_named; j++) n += sc->named[j].count;
  return n;
}

/* Resolves, checks and counts the state file. */
static int check_state(ctx *c) {
  hd_scene *sc = c->sc;
  int any_count = hd_scene_key_set(c, S_DIMERS, K_DCOUNT) || hd_scene_key_set(c, S_DISKS, K_SCOUNT);
  for (int j = 0; j < sc->n_named; j++) any_count |= hd_scene_key_set(c, N_SEC + j, K_PCOUNT);
  if (c->mode != M_RUN) { /* the run's bodies are in its checkpoint; the counts are in the text */
    if (c->mode == M_STORED && !any_count)
      return FAIL_KEY(c, K_STATE, "a stored scene gives the counts of its bodies");
    snprintf(sc->state_file, sizeof sc->state_file, "%s", c->state_rel);
    return HD_OK;
  }
  char joined[2 * HD_PATH_MAX + 2];
  if (c->state_rel[0] == '/')
    snprintf(joined, sizeof joined, "%s", c->state_rel);
  else
    snprintf(joined, sizeof joined, "%s/%s", sc->dir, c->state_rel);
  char *real = realpath(joined, NULL);
  if (!real)
    return hd_scene_fail(c, HD_EIO, c->key_at[S_INIT][K_STATE], S_INIT, "state",
                         c->key_val[S_INIT][K_STATE], "cannot read state file '%s': %s", joined,
                         strerror(errno));
  if (strlen(real) >= sizeof sc->state_file) {
    free(real);
    return FAIL_KEY(c, K_STATE, "path too long");
  }
  struct stat stt;
  if (stat(real, &stt) == 0 && S_ISDIR(stt.st_mode)) {
    free(real);
    return FAIL_KEY(c, K_STATE, "is a directory, not a state file");
  }
  /* the run's scene text stores the path as a value: one that INI would cut short (a comment
   * after " ;" or " #", blanks at an end) could not be read back by a re-run */
  size_t rl = strlen(real);
  if (strstr(real, " ;") || strstr(real, " #") || strchr(real, '\n') || real[rl - 1] == ' ' ||
      real[rl - 1] == '\t') {
    free(real);
    return FAIL_KEY(c, K_STATE,
                    "its path holds ' ;', ' #' or a blank at its end, which a scene "
                    "cannot store: rename the file or folder");
  }
  strcpy(sc->state_file, real);
  free(real);
  hd_state_row *rows = NULL;
  long n = 0, have[HD_MAX_SPECIES] = {0};
  int rc = hd_state_csv_read_species(sc->state_file, sc, &rows, &n, c->err);
  if (rc) {
    c->failed = 1;
    c->code = rc;
    return rc;
  }
  for (long i = 0; i < n; i++) have[rows[i].species]++;
  free(rows);
  for (int j = 0; j < 2 + sc->n_named; j++) {
    int si = j == 0 ? S_DIMERS : j == 1 ? S_DISKS : N_SEC + j - 2;
    int k = j == 0 ? K_DCOUNT : j == 1 ? K_SCOUNT : K_PCOUNT;
    long *cnt = j == 0 ? &sc->n_dimers : j == 1 ? &sc->n_disks : &sc->named[j - 2].count;
    const char *kind = j == 0 ? "dimer" : j == 1 ? "disk" : sc->named[j - 2].name;
    if (hd_scene_key_set(c, si, k)) {
      if (*cnt != have[j])
        return FAIL_AT(c, si, k, "the state file %s holds %ld %s rows", c->state_rel, have[j],
                       kind);
    } else if (have[j] > 0) {
      *cnt = have[j];
      c->present[si] = 1;
    }
  }
  return HD_OK;
}

/* The largest body of the scene (the lattice's cell edge). */
static double largest_body(const hd_scene *sc) {
  double ext = 0;
  if (sc->n_dimers > 0) ext = sc->dimer_a + sc->dimer_d;
  if (sc->n_disks > 0 && sc->disk_sigma > ext) ext = sc->disk_sigma;
  for (int j = 0; j < sc->n_named; j++)
    if (sc->named[j].count > 0) ext = fmax(ext, hd_species_extent(&sc->named[j]));
  return ext;
}

/* The box: given, or derived from area_fraction; then (run is set) does everything fit. */
static int check_box(ctx *c, int run) {
  hd_scene *sc = c->sc;
  long nb = hd_scene_body_count(sc);
  int kb = hd_scene_key_set(c, S_SYSTEM, K_BOX) ? K_BOX : K_AREA;
  if (hd_scene_key_set(c, S_SYSTEM, K_BOX) && hd_scene_key_set(c, S_SYSTEM, K_AREA)) {
    loc a = c->key_at[S_SYSTEM][K_AREA], b = c->key_at[S_SYSTEM][K_BOX];
    int later = a.over > b.over || (a.over == b.over && a.line > b.line) ? K_AREA : K_BOX;
    return FAIL_KEY(c, later, "give either box or area_fraction, not both");
  }
  if (nb == 0) {
    if (run && hd_scene_key_set(c, S_SYSTEM, K_AREA))
      return FAIL_KEY(c, K_AREA, "needs bodies: a [dimers], [disks] or [species] count > 0");
    return HD_OK;
  }
  if (!hd_scene_key_set(c, S_SYSTEM, K_BOX) && !hd_scene_key_set(c, S_SYSTEM, K_AREA))
    return run ? hd_scene_fail(c, HD_EINPUT,
                               c->present[S_SYSTEM] ? c->sec_at[S_SYSTEM] : (loc){0, 0}, S_SYSTEM,
                               "box", NULL, "missing: give box = Lx Ly or area_fraction = eta")
               : HD_OK;
  hd_scene_where(c, c->key_at[S_SYSTEM][kb], sc->box_at, sizeof sc->box_at);
  double area = hd_scene_covered_area(sc);
  if (kb == K_AREA) sc->box_x = sc->box_y = sqrt(area / sc->area_fraction);
  if (!run) return HD_OK;
  if (!isfinite(sc->box_x) || !isfinite(sc->box_y)) /* the bodies' area overflowed (d ~ 1e160) */
    return FAIL_KEY(c, kb, "gives a box that is not a finite number (the bodies cover %.6g)", area);
  double ext = largest_body(sc);
  double edge = fmin(sc->box_x, sc->box_y);
  if (edge < ext)
    return FAIL_KEY(c, kb, "box too small: edge %.6g is shorter than the largest body (%.6g)", edge,
                    ext);
  if (!(sc->box_x * sc->box_y >= DBL_MIN))
    /* 1e-300 x 1e-300: the area underflows, and the covered fraction would be 0 / 0 (bodies
     * whose own area underflows cover 0 of a box that has one: that is fine) */
    return FAIL_KEY(c, kb,
                    "box %.6g x %.6g: its area is below the smallest normal double: rescale the "
                    "lengths",
                    sc->box_x, sc->box_y);
  double frac = area / (sc->box_x * sc->box_y);
  /* the lattice: one body per square cell of the largest body's extent (at most pi/8 of the box
   * for dimers of a = d, pi/4 for disks) */
  double nx = floor(sc->box_x / ext), ny = floor(sc->box_y / ext);
  const char *bigger = kb == K_AREA ? "a lower area_fraction" : "a larger box";
  if (sc->placement == HD_PLACE_RANDOM && frac > HD_RANDOM_MAX_FRACTION) {
    if (nx * ny >= (double)nb)
      return FAIL_KEY(c, kb,
                      "too dense: the bodies cover %.4g of the box, above %g for placement = "
                      "random (use placement = lattice, which holds them, or %s)",
                      frac, HD_RANDOM_MAX_FRACTION, bigger);
    return FAIL_KEY(c, kb,
                    "too dense: the bodies cover %.4g of the box, above %g for placement = random, "
                    "and placement = lattice holds only %.0f of the %ld bodies (%.0f x %.0f cells "
                    "of edge %.6g): give %s",
                    frac, HD_RANDOM_MAX_FRACTION, nx * ny, nb, nx, ny, ext, bigger);
  }
  if (sc->placement == HD_PLACE_LATTICE && nx * ny < (double)nb)
    return FAIL_KEY(c, kb,
                    "too dense for placement = lattice: %.0f x %.0f cells of edge %.6g "
                    "hold fewer than the %ld bodies: give %s",
                    nx, ny, ext, nb, bigger);
  return HD_OK;
}

/* [init] temperature against the range of doubles: the drawn speeds (v^2 ~ T / M), spins
 * (w^2 ~ T / I) and the total energy (~ N T) must stay below 1e300 (temperature = 1e300 with
 * a dimer of a = 1e-9 gave w^2 = 2e318, NaN energies that the database refused). */
static int check_thermal(ctx *c) {
  const hd_scene *sc = c->sc;
  double T = sc->temperature, worst = 0;
  const char *what = "";
  if (sc->n_dimers > 0) {
    worst = T / (2 * sc->dimer_m), what = "[dimers] v^2 ~ T / 2m";
    double I = 0.5 * sc->dimer_m * sc->dimer_a * sc->dimer_a;
    if (I > 0 && T / I > worst) worst = T / I, what = "[dimers] w^2 ~ T / I";
  }
  if (sc->n_disks > 0 && T / sc->disk_mass > worst)
    worst = T / sc->disk_mass, what = "[disks] v^2 ~ T / mass";
  for (int j = 0; j < sc->n_named; j++) {
    if (sc->named[j].count == 0) continue;
    double M, I = hd_scene_species_inertia(&sc->named[j], &M);
    if (T / M > worst) worst = T / M, what = "a [species] v^2 ~ T / M";
    if (I > 0 && T / I > worst) worst = T / I, what = "a [species] w^2 ~ T / I";
  }
  double e = T * (double)hd_scene_body_count(sc);
  if (!(worst <= 1e300 && e <= 1e300))
    return FAIL_KEY(c, K_TEMP,
                    "the drawn velocities leave the range of doubles (%s = %g, energy N T = %g; "
                    "at most 1e300): lower the temperature or scale the masses",
                    what, worst, e);
  return HD_OK;
}

/* A [rods] scene: a ring of count rods, nothing 2D. */
static int check_rods(ctx *c) {
  hd_scene *sc = c->sc;
  if (!hd_scene_key_set(c, S_RODS, K_RCOUNT))
    return hd_scene_fail(c, HD_EINPUT, c->sec_at[S_RODS], S_RODS, "count", NULL,
                         "missing: required in [rods]");
  static const int other[4] = {S_DIMERS, S_DISKS, S_WALLS, S_INIT};
  for (int j = 0; j < 4; j++)
    if (c->present[other[j]])
      return hd_scene_fail(
          c, HD_EINPUT, c->sec_at[other[j]], other[j], NULL, NULL,
          "cannot be combined with [rods] (the ring has its own count and temperature)");
  for (int j = 0; j < sc->n_named; j++)
    return hd_scene_fail(
        c, HD_EINPUT, c->sec_at[N_SEC + j], N_SEC + j, NULL, NULL,
        "cannot be combined with [rods] (the ring has its own count and temperature)");
  if (hd_scene_key_set(c, S_SYSTEM, K_BOX))
    return FAIL_KEY(c, K_BOX, "not used with [rods]: the ring length is the rod count");
  if (hd_scene_key_set(c, S_SYSTEM, K_AREA))
    return FAIL_KEY(c, K_AREA, "not used with [rods]: the ring length is the rod count");
  if (!hd_scene_key_set(c, S_RODS, K_REPS))
    sc->rod_eps = sc->rod_gamma;
  else if (sc->rod_model != 1)
    return FAIL_KEY(c, K_REPS, "only with model = constant");
  /* table unset: the balanced table wherever it applies (issue 16: the direct sampler then
   * lowered the stationary E_kin by ~3.5 %, the balanced table by 0.2 %; refined since issue 25,
   * the direct sampler is within ~0.3 % but ~10x slower per collision) */
  if (!hd_scene_key_set(c, S_RODS, K_RTABLE))
    sc->rod_table = sc->rod_model != 1 && !sc->rod_unequal && sc->rod_gamma < 1;
  if (sc->rod_table && sc->rod_unequal)
    return FAIL_KEY(c, K_RTABLE,
                    "the table is for equal bath temperatures: not with baths = unequal");
  if (c->mode != M_READ && sc->rod_model != 1 && sc->rod_gamma < 1) {
    /* the sampler the ring builds (rods.c) */
    hd_eps_opts o;
    hd_rods_eps_opts(sc->rod_eps_step, &o);
    if (!hd_eps_grid_fits(sc->rod_gamma, &o))
      return FAIL_KEY(c, K_RGAMMA,
                      "too small for the eps sampler's grid at eps_step %g (about (1 + 1/gamma) / "
                      "eps_step x %d points, at most 5e7): a larger gamma or eps_step",
                      o.step, o.adapt);
  }
  if (c->mode == M_READ) return HD_OK;
  if (!(sc->stop_time > 0 || sc->stop_events > 0 || sc->stop_cpd > 0))
    return hd_scene_fail(c, HD_EINPUT, c->present[S_RUN] ? c->sec_at[S_RUN] : (loc){0, 0}, S_RUN,
                         NULL, NULL, "no stop condition: set stop_time, stop_events or stop_cpd");
  return check_vel_at(c);
}

/* [log] frames_every / frames_every_time: one of them, a bounded count under the cap. */
static int check_frames(ctx *c) {
  hd_scene *sc = c->sc;
  if (sc->frames_every > 0 && sc->frames_every_time > 0)
    return FAIL_KEY(c, K_LFRAMEST, "give frames_every (cpd) or frames_every_time, not both");
  if (sc->frames_every_time > 0 && !(sc->stop_time > 0))
    return FAIL_KEY(c, K_LFRAMEST,
                    "needs [run] stop_time (frames are taken at exact times up to it; by cpd: "
                    "frames_every)");
  if (hd_scene_key_set(c, S_LOG, K_LFRAMESMB) &&
      !(sc->frames_every > 0 || sc->frames_every_time > 0))
    return FAIL_KEY(c, K_LFRAMESMB, "set without frames_every or frames_every_time");
  double nf = hd_scene_frames_estimate(sc);
  if (nf > 0) {
    double mb = nf * hd_scene_frame_bytes(sc) / 1e6;
    int k = sc->frames_every > 0 ? K_LFRAMES : K_LFRAMEST;
    /* frames by cpd in a run that stop_time may end first: a bound, not a count; the run
     * stops taking frames at the cap (hd_run.c) */
    if (mb > sc->frames_max_mb && !(sc->frames_every > 0 && sc->stop_time > 0))
      return FAIL_KEY(c, k,
                      "%.0f frames of %ld bodies take ~%.4g MB, more than frames_max_mb = %g: "
                      "take fewer frames or raise frames_max_mb",
                      nf, hd_scene_bodies(sc), mb, sc->frames_max_mb);
  }
  return HD_OK;
}

int hd_scene_check_all(ctx *c) {
  hd_scene *sc = c->sc;
  int rc, run = c->mode != M_READ;
  if (c->present[S_RODS]) return (rc = check_rods(c)) ? rc : run ? check_frames(c) : HD_OK;
  if (!hd_scene_key_set(c, S_DISKS, K_SALPHAD)) sc->disk_alpha_dimer = sc->disk_alpha;
  if (!hd_scene_key_set(c, S_DISKS, K_SBETAD)) sc->disk_beta_dimer = sc->disk_beta;
  for (int j = 0; j < sc->n_named; j++)
    if ((rc = hd_scene_build_species(c, j))) return rc;
  if ((rc = hd_scene_fill_pairs(c))) return rc;
  if (hd_scene_key_set(c, S_INIT, K_STATE)) {
    if (hd_scene_key_set(c, S_INIT, K_PLACE))
      return FAIL_KEY(c, K_STATE,
                      "cannot be used together with placement (state gives every "
                      "body)");
    sc->placement = HD_PLACE_STATE;
    if ((rc = check_state(c))) return rc;
  } else if (run && !(sc->temperature > 0)) {
    return FAIL_KEY(c, K_TEMP, "must be > 0 (0 only with a state file)");
  }
  if (!run) return check_box(c, 0);
  static const int req_sec[3] = {S_DIMERS, S_DISKS, S_WALLS};
  static const int req_key[3] = {K_DCOUNT, K_SCOUNT, K_WSIDES};
  for (int j = 0; j < 3; j++)
    if (c->present[req_sec[j]] && !hd_scene_key_set(c, req_sec[j], req_key[j]) &&
        !(req_sec[j] != S_WALLS && sc->placement == HD_PLACE_STATE))
      return hd_scene_fail(c, HD_EINPUT, c->sec_at[req_sec[j]], req_sec[j],
                           hd_scene_keys[req_key[j]].name, NULL, "missing: required in [%s]",
                           hd_scene_sec_name[req_sec[j]]);
  for (int j = 0; j < sc->n_named; j++)
    if (!hd_scene_key_set(c, N_SEC + j, K_PCOUNT) && sc->placement != HD_PLACE_STATE)
      return hd_scene_fail(c, HD_EINPUT, c->sec_at[N_SEC + j], N_SEC + j, "count", NULL,
                           "missing: required in [species %s]", sc->named[j].name);
  if (sc->n_dimers > 0 && sc->dimer_a > 0 && sc->dimer_a < HD_MIN_BOND * sc->dimer_d)
    return FAIL_KEY(c, K_DA,
                    "must be 0 or at least %g d = %g: a shorter bond is lost in the round-off of "
                    "the positions (a = 0 is a dimer without lever arm, a disk of mass 2m)",
                    HD_MIN_BOND, HD_MIN_BOND * sc->dimer_d);
  double inertia = 0.5 * sc->dimer_m * sc->dimer_a * sc->dimer_a;
  if (sc->n_dimers > 0 && sc->dimer_a > 0 &&
      !(inertia >= HD_MIN_INERTIA && inertia <= 1 / HD_MIN_INERTIA))
    return FAIL_KEY(c, K_DA, "the moment of inertia m a^2 / 2 = %g is outside [%g, %g]: %s",
                    inertia, HD_MIN_INERTIA, 1 / HD_MIN_INERTIA, hd_scene_inertia_why);
  if (sc->placement != HD_PLACE_STATE && (rc = check_thermal(c))) return rc;
  if ((rc = check_box(c, 1))) return rc;
  if (!(sc->stop_time > 0 || sc->stop_events > 0 || sc->stop_cpd > 0))
    return hd_scene_fail(c, HD_EINPUT, c->present[S_RUN] ? c->sec_at[S_RUN] : (loc){0, 0}, S_RUN,
                         NULL, NULL, "no stop condition: set stop_time, stop_events or stop_cpd");
  if (hd_scene_body_count(sc) == 1 && !(sc->stop_time > 0) && !(sc->walls && sc->stop_events > 0))
    /* it has no pair collision ever (cpd stays 0), and without walls no collision at all: the
     * run would go on for ever */
    return hd_scene_fail(
        c, HD_EINPUT, c->present[S_RUN] ? c->sec_at[S_RUN] : (loc){0, 0}, S_RUN, NULL, NULL,
        "one body alone never collides with another: stop it with stop_time (stop_events "
        "counts only its wall collisions, and a drawn velocity of one body is 0: it rests "
        "or spins in place)");
  if ((rc = check_frames(c))) return rc;
  return check_vel_at(c);
}
