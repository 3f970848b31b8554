/* The engine with general rigid clusters of disks (issue 18): scenes whose `[species NAME]`
 * sections are filled in code (hd_scene.named, alpha_pair), as the scene loader fills them.
 * Elastic gases of linear, bent and triangular trimers and of asymmetric dimers in verification
 * mode: energy and momentum conserved to round-off, no overlap, equipartition E_tr/E_rot = 2
 * per body, and the Haff law's D_e = 3 in the limit alpha -> 1; a mixture of named species with
 * dimers and disks (body order, alpha per pair, equipartition across species); a scene without
 * named species keeps the disk and dimer fast paths; a checkpoint with named species resumes
 * bit for bit; a run with named species stores its species table, per-species samples, 'body'
 * states and body-body / body-wall collisions. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sqlite3.h>
#include <unistd.h>

#include <signal.h>
#include <time.h>

#include "hd_run.h"
#include "hd_stop.h"
#include "hd_sim_internal.h"
#include "test_sim.h"
#include "test_util.h"

/* Adds species NAME of n disks at (x, y), diameters d, masses m, count bodies, restitution
 * alpha within it and with every species before it. */
static void add_species(hd_scene *sc, const char *name, int n, const double *x, const double *y,
                        const double *d, const double *m, long count, double alpha) {
  int k = sc->n_named++;
  hd_scene_species *sp = &sc->named[k];
  memset(sp, 0, sizeof *sp);
  snprintf(sp->name, sizeof sp->name, "%s", name);
  sp->count = count;
  sp->ndisk = n;
  for (int i = 0; i < n; i++) sp->x[i] = x[i], sp->y[i] = y[i], sp->d[i] = d[i], sp->m[i] = m[i];
  sp->alpha = alpha;
  sp->line = 10 + k;
  for (int j = 0; j < 2 + k; j++) sc->alpha_pair[2 + k][j] = sc->alpha_pair[j][2 + k] = alpha;
}

/* The shapes of the tests (unit disks unless said): a linear trimer, one bent at 120 degrees at
 * its middle disk, a triangle, and an asymmetric dimer (d 1 and 0.5, m 1 and 0.3, 0.8 apart).
 * *area: the area of one body (the union of its disks). */
static void shape_of(int which, int *n, double *x, double *y, double *d, double *m, double *area) {
  const double q = M_PI / 4;
  for (int i = 0; i < 3; i++) d[i] = m[i] = 1.0, y[i] = 0.0;
  switch (which) {
  case 0: /* linear: touching disks */
    *n = 3, x[0] = 0, x[1] = 1, x[2] = 2, *area = 3 * q;
    break;
  case 1: /* bent: the outer disks 1 apart from the middle, sqrt(3) from each other */
    *n = 3, x[0] = 1, x[1] = 0, x[2] = cos(2 * M_PI / 3), y[2] = sin(2 * M_PI / 3);
    *area = 3 * q;
    break;
  case 2: /* triangle */
    *n = 3, x[0] = 0, x[1] = 1, x[2] = 0.5, y[2] = sqrt(3) / 2, *area = 3 * q;
    break;
  default: /* asymmetric dimer; the small disk overlaps the big one by a sliver (lens ~0) */
    *n = 2, x[0] = 0, x[1] = 0.8, d[1] = 0.5, m[1] = 0.3, *area = q * (1 + 0.25);
    break;
  }
}

static const char *const shape_name[] = {"linear", "bent", "triangle", "asym"};

/* A scene of count bodies of shape `which` (the only species) at area fraction eta. */
static void cluster_scene(hd_scene *sc, int which, long count, double eta, double alpha,
                          unsigned long long seed) {
  test_disk_scene(sc, 0, 0.1, alpha, seed);
  int n;
  double x[3], y[3], d[3], m[3], area;
  shape_of(which, &n, x, y, d, m, &area);
  add_species(sc, shape_name[which], n, x, y, d, m, count, alpha);
  sc->box_x = sc->box_y = sqrt((double)count * area / eta);
}

/* Elastic gas of each shape, N = 300 at area fraction 0.15, 2e5 collisions (2e4 sanitized) in
 * verification mode (contact distance at every collision, overlaps of both colliders with every
 * neighbour, time order):
 * - energy drift < 1e-9 relative and |momentum| < 1e-12 sqrt(N) (round-off; the initial total
 *   momentum is 0 to round-off);
 * - equipartition: E_tr/E_rot = 2, averaged over the second half (1000 samples of a ratio whose
 *   relative fluctuation is ~sqrt(2/N) ~ 8 %, correlated over ~N collisions: error ~1 %);
 *   tolerance 4 %;
 * - D_e at alpha -> 1: the energy lost per collision is -(1 - alpha^2) mu vn^2 / 2, so the
 *   slope of ln E against cpd is -(1 - alpha^2) <mu vn^2> / (2 dof T) with dof T = 2E/N, and
 *   D_e = 4E / (N <mu vn^2>), the mean over collisions.  Collisions happen at the rate |vn|, so
 *   for Maxwellian velocities <mu vn^2> = 2T whatever the geometry (mu vn^2 / T is a
 *   flux-weighted chi^2 of one degree of freedom, mean 2, sd 2): D_e = dof = 3 for a body that
 *   turns.  From 1e5 collisions its statistical error is ~0.5 % (sd 2 / sqrt(1e5) relative,
 *   doubled for correlations); finite N changes it by O(1/N); tolerance 3 %.
 * - the contact angle and f of every collision are finite numbers for the outer disks. */
static void elastic_clusters(void **state) {
  (void)state;
  for (int which = 0; which < 4; which++) {
    hd_scene sc;
    long N = 300;
    cluster_scene(&sc, which, N, 0.15, 1.0, 21 + (unsigned long long)which);
    sc.verify = 1;
    hd_sim *s;
    hd_error err;
    if (hd_sim_alloc(&s, &sc, &err)) fail_msg("%s", err.msg);
    assert_int_equal(s->shape[2].tag, HD_KIND_BODY); /* the first [species NAME] */
    assert_int_equal(s->n, N);
    double e0t, e0r;
    hd_sim_energy(s, -1, &e0t, &e0r);
    long n = test_size(200000, 10);
    double ksum = 0, musum = 0;
    long nk = 0, nmu = 0;
    for (long k = 0; k < n; k++) {
      hd_event_out ev;
      if (hd_sim_next(s, INFINITY, &ev, &err))
        fail_msg("%s: collision %ld: %s", shape_name[which], k, err.msg);
      assert_int_equal(ev.kind, hd_coll_kind_of(HD_KIND_BODY, HD_KIND_BODY));
      assert_true(isfinite(ev.info.f) && ev.info.f > 0 && ev.info.vn < 0);
      const hd_shape *sh = &s->shape[s->b[ev.i].species];
      musum += ev.info.f * sh->mk[ev.ka] * ev.info.vn * ev.info.vn; /* m_ref: i's disk */
      nmu++;
      if (k >= n / 2 && k % 100 == 0) {
        double et, er;
        hd_sim_energy(s, -1, &et, &er);
        ksum += et / er;
        nk++;
      }
    }
    double et, er, px, py;
    hd_sim_energy(s, -1, &et, &er);
    test_sim_momentum(s, &px, &py);
    double drift = fabs(et + er - e0t - e0r) / (e0t + e0r), K = ksum / (double)nk;
    double De = 4.0 * (et + er) / ((double)N * musum / (double)nmu);
    int32_t i, j;
    double ov = hd_sim_max_overlap(s, &i, &j);
    printf("# elastic %s: %ld collisions, drift %.3g, |p| %.3g, max overlap %.3g (now %.3g), "
           "E_tr/E_rot %.4f, D_e(alpha -> 1) %.4f\n",
           shape_name[which], n, drift, hypot(px, py), s->max_overlap, ov, K, De);
    assert_true(drift < 1e-9);
    assert_true(hypot(px, py) < 1e-12 * sqrt((double)N));
    assert_true(s->max_overlap < 1e-9 && ov < 1e-9);
    if (!test_sanitized()) {
      assert_true(fabs(K / 2 - 1) < 0.04);
      assert_true(fabs(De / 3 - 1) < 0.03);
    }
    hd_sim_free(s);
  }
}

/* A mixture: 150 dimers, 150 disks (sigma 0.8), 100 linear trimers and 100 triangles, elastic
 * within species, alpha 1 between them too, 2e5 collisions in verification mode: bodies
 * numbered dimers, disks, then each named species in order; every pair kind happens (the kinds
 * 0, 1, 2 and 6); energy and momentum conserved as above; every degree of freedom gets the same
 * temperature (time averages over the second half; tolerance 5 %: fewer bodies per species than
 * above).  Then the same scene with alpha = 0.5 between the two named species only: every
 * trimer-triangle collision loses -(1 - 0.25) mu vn^2 / 2 and every other collision nothing. */
static void mixture_species(void **state) {
  (void)state;
  for (int inel = 0; inel < 2; inel++) {
    hd_scene sc;
    test_disk_scene(&sc, 150, 0.1, 1.0, 31);
    sc.n_dimers = 150;
    sc.disk_sigma = 0.8;
    int n;
    double x[3], y[3], d[3], m[3], area;
    shape_of(0, &n, x, y, d, m, &area);
    add_species(&sc, "trimer", n, x, y, d, m, 100, 1.0);
    shape_of(2, &n, x, y, d, m, &area);
    add_species(&sc, "triangle", n, x, y, d, m, 100, 1.0);
    if (inel) sc.alpha_pair[2][3] = sc.alpha_pair[3][2] = 0.5;
    double tot = 150 * M_PI / 2 + 150 * M_PI / 4 * 0.64 + 200 * 3 * M_PI / 4;
    sc.box_x = sc.box_y = sqrt(tot / 0.15);
    sc.verify = 1;
    hd_sim *s;
    hd_error err;
    if (hd_sim_alloc(&s, &sc, &err)) fail_msg("%s", err.msg);
    assert_int_equal(s->nsp, 4);
    assert_int_equal(s->n, 500);
    assert_false(s->disks_only);
    assert_int_equal(s->shape[0].tag, HD_KIND_DIMER);
    assert_int_equal(s->shape[1].tag, HD_KIND_DISK);
    for (int32_t i = 0; i < s->n; i++) { /* user numbers by species, in order */
      int32_t id = s->id[i], sp = s->b[i].species;
      int32_t want = id < 150 ? 0 : id < 300 ? 1 : id < 400 ? 2 : 3;
      assert_int_equal(sp, want);
    }
    assert_true(s->alpha[2][3] == (inel ? 0.5 : 1.0) && s->alpha[0][1] == 1.0);
    double e0t, e0r;
    hd_sim_energy(s, -1, &e0t, &e0r);
    long nc = test_size(inel ? 20000 : 200000, 10), kinds[HD_NKINDS * HD_NKINDS] = {0};
    const hd_coll_kind DD = hd_coll_kind_of(HD_KIND_DIMER, HD_KIND_DIMER),
                       DK = hd_coll_kind_of(HD_KIND_DIMER, HD_KIND_DISK),
                       KK = hd_coll_kind_of(HD_KIND_DISK, HD_KIND_DISK),
                       BB = hd_coll_kind_of(HD_KIND_BODY, HD_KIND_BODY);
    double T[4][2] = {{0}}, lost = 0;
    long nT = 0;
    for (long k = 0; k < nc; k++) {
      hd_event_out ev;
      if (hd_sim_next(s, INFINITY, &ev, &err)) fail_msg("collision %ld: %s", k, err.msg);
      assert_true(ev.kind >= 0 && ev.kind < HD_NKINDS * HD_NKINDS);
      kinds[ev.kind]++;
      int si = s->b[ev.i].species, sj = s->b[ev.j].species;
      assert_true(si <= sj); /* the lower species first */
      if (si >= 2 || sj >= 2) assert_int_equal(ev.kind, BB);
      if (inel && si == 2 && sj == 3) {
        const hd_shape *sh = &s->shape[si];
        double mu = ev.info.f * sh->mk[ev.ka];
        assert_true(fabs(ev.info.de + 0.75 * mu * ev.info.vn * ev.info.vn / 2) <=
                    1e-12 * fabs(ev.info.de));
        lost += ev.info.de;
      } else if (inel) {
        assert_true(ev.info.de == 0.0);
      }
      if (!inel && k >= nc / 2 && k % 100 == 0) {
        for (int sp = 0; sp < 4; sp++) {
          double et, er;
          hd_sim_energy(s, sp, &et, &er);
          T[sp][0] += et / (double)s->n_species[sp];     /* 2 dof: T */
          T[sp][1] += 2 * er / (double)s->n_species[sp]; /* 1 dof: T */
        }
        nT++;
      }
    }
    double et, er, px, py;
    hd_sim_energy(s, -1, &et, &er);
    test_sim_momentum(s, &px, &py);
    double e0 = e0t + e0r, e1 = et + er;
    printf("# mixture%s: kinds %ld %ld %ld %ld, energy %.6g -> %.6g (booked loss %.6g)\n",
           inel ? " (alpha 0.5 between the named)" : "", kinds[DD], kinds[DK], kinds[KK], kinds[BB],
           e0, e1, lost);
    assert_true(hypot(px, py) < 1e-12 * sqrt(500.0));
    assert_true(s->max_overlap < 1e-9);
    if (inel) {
      assert_true(lost < 0 && fabs(e1 - e0 - lost) <= 1e-9 * e0);
    } else {
      assert_true(fabs(e1 - e0) < 1e-9 * e0);
      assert_true(kinds[DD] > 0 && kinds[DK] > 0 && kinds[KK] > 0 && kinds[BB] > 0);
      double T0 = T[0][0] / (double)nT;
      printf("# mixture: T dimer tr %.4f rot %.4f, disk tr %.4f, trimer tr %.4f rot %.4f, "
             "triangle tr %.4f rot %.4f\n",
             T0, T[0][1] / (double)nT, T[1][0] / (double)nT, T[2][0] / (double)nT,
             T[2][1] / (double)nT, T[3][0] / (double)nT, T[3][1] / (double)nT);
      if (!test_sanitized())
        for (int sp = 0; sp < 4; sp++)
          for (int q = 0; q < (sp == 1 ? 1 : 2); q++)
            assert_true(fabs(T[sp][q] / (double)nT / T0 - 1) < 0.05);
    }
    hd_sim_free(s);
  }
}

/* Scenes without named species keep their fast paths: disks only (disks_only, the closed-form
 * walk of cells) and dimers (the paper's formulas, HD_KIND_DIMER); a named species that is one
 * disk or an equal dimer on the x axis gets the fast tag too. */
static void fast_paths(void **state) {
  (void)state;
  hd_scene sc;
  hd_sim *s;
  hd_error err;
  test_disk_scene(&sc, 100, 0.2, 0.9, 1);
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  assert_true(s->disks_only && s->nsp == 2 && s->shape[1].tag == HD_KIND_DISK);
  hd_sim_free(s);
  test_disk_scene(&sc, 0, 0.2, 0.9, 1);
  sc.n_dimers = 50;
  sc.box_x = sc.box_y = 30;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  assert_true(!s->disks_only && s->shape[0].tag == HD_KIND_DIMER);
  hd_sim_free(s);
  const double x[] = {0, 1}, y[] = {0, 0}, d[] = {1, 1}, m[] = {1, 1};
  add_species(&sc, "dumbbell", 2, x, y, d, m, 10, 0.9);
  add_species(&sc, "ball", 1, x, y, d, m, 10, 0.9);
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  assert_int_equal(s->shape[2].tag, HD_KIND_DIMER);
  assert_int_equal(s->shape[3].tag, HD_KIND_DISK);
  assert_true(s->n == 70 && !s->disks_only);
  hd_sim_free(s);
  /* a species the engine cannot build: HD_EINPUT naming it */
  sc.named[1].d[0] = -1;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_EINPUT);
  assert_non_null(strstr(err.msg, "[species ball]"));
  sc.named[1].d[0] = 1;
  sc.alpha_pair[3][0] = NAN;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_EINPUT);
  assert_non_null(strstr(err.msg, "alpha"));
}

/* A run of trimers and dimers (alpha 0.9) checkpointed at 5000 collisions and restored: the next
 * 5000 collisions are bit for bit those of the run that went on; a scene whose species has
 * another shape refuses the checkpoint. */
static void checkpoint_resume(void **state) {
  (void)state;
  hd_scene sc;
  cluster_scene(&sc, 1, 200, 0.2, 0.9, 5);
  sc.n_dimers = 100;
  sc.box_x = sc.box_y = sqrt((200 * 3 * M_PI / 4 + 100 * M_PI / 2) / 0.2);
  hd_sim *a, *b;
  hd_error err;
  assert_int_equal(hd_sim_alloc(&a, &sc, &err), HD_OK);
  hd_event_out ev, ew;
  for (int k = 0; k < 5000; k++) assert_int_equal(hd_sim_next(a, INFINITY, &ev, &err), HD_OK);
  void *blob;
  size_t nb;
  assert_int_equal(hd_sim_checkpoint(a, &blob, &nb, &err), HD_OK);
  assert_int_equal(hd_sim_alloc_restore(&b, &sc, blob, nb, &err), HD_OK);
  for (int k = 0; k < 5000; k++) {
    assert_int_equal(hd_sim_next(a, INFINITY, &ev, &err), HD_OK);
    assert_int_equal(hd_sim_next(b, INFINITY, &ew, &err), HD_OK);
    assert_true(ev.t == ew.t && ev.i == ew.i && ev.j == ew.j && ev.ka == ew.ka && ev.kb == ew.kb);
    assert_true(memcmp(&ev.info, &ew.info, sizeof ev.info) == 0);
  }
  hd_sim_free(b);
  sc.named[0].d[1] = 1.01; /* another shape */
  assert_int_equal(hd_sim_alloc_restore(&b, &sc, blob, nb, &err), HD_EINPUT);
  assert_non_null(strstr(err.msg, "shape"));
  free(blob);
  hd_sim_free(a);
}

/* One integer from a query on h. */
static long long q_int(sqlite3 *h, const char *sql) {
  sqlite3_stmt *st;
  assert_int_equal(sqlite3_prepare_v2(h, sql, -1, &st, NULL), SQLITE_OK);
  assert_int_equal(sqlite3_step(st), SQLITE_ROW);
  long long v = sqlite3_column_int64(st, 0);
  sqlite3_finalize(st);
  return v;
}

/* A run (hd_run_new, verification on) of 20 dimers, 10 disks and 15 bent trimers between walls,
 * 10 cpd: the
 * species table has the three species with their counts, masses, inertias and disks (the
 * trimer: 2 - 3 |centre of mass|^2 = 5/3); every samples row has one sample_species row per
 * species, whose energies add up to the samples row's; trimers are stored as kind 'body', their
 * collisions as body-body and body-wall, with the touching disk in 0 .. 2; its frames hold every
 * body (45); `haff export xyz`
 * writes every disk of every trimer (at the engine's positions: the bent shape's distances). */
static void run_stores_species(void **state) {
  (void)state;
  char db[] = "/tmp/haff-cluster-XXXXXX";
  int fd = mkstemp(db);
  assert_true(fd >= 0);
  close(fd);
  unlink(db);
  hd_scene sc;
  hd_error err;
  const char *text = "[system]\nbox = 30 30\nseed = 3\n[dimers]\ncount = 20\nalpha = 0.9\n"
                     "[disks]\ncount = 10\n[walls]\nsides = left right bottom top\n[run]\n"
                     "stop_cpd = 10\nverify = 1\n[log]\nsamples_every = 1\nframes_every = 5\n";
  assert_int_equal(hd_scene_load_string(&sc, text, "s.ini", NULL, 0, &err), HD_OK);
  int n;
  double x[3], y[3], d[3], m[3], area;
  shape_of(1, &n, x, y, d, m, &area);
  add_species(&sc, "bent", n, x, y, d, m, 15, 0.9);
  hd_run_opts o = {.db_path = db, .quiet = 1, .version = "test"};
  int64_t run = 0;
  if (hd_run_new(&sc, &o, &run, &err) != HD_OK) fail_msg("%s", err.msg);
  hd_scene_free(&sc);
  sqlite3 *h;
  assert_int_equal(sqlite3_open(db, &h), SQLITE_OK);
  assert_int_equal(q_int(h, "SELECT count(*) FROM species"), 3);
  assert_int_equal(q_int(h, "SELECT count FROM species WHERE idx = 2 AND name = 'bent'"), 15);
  assert_int_equal(q_int(h, "SELECT mass = 3 AND abs(inertia - 5 / 3.0) < 1e-12 FROM species WHERE "
                            "idx = 2"),
                   1);
  assert_int_equal(q_int(h, "SELECT count(*) FROM species WHERE idx = 0 AND name = 'dimer' AND "
                            "disks = '-0.5 0 1 1; 0.5 0 1 1' AND inertia = 0.5"),
                   1);
  long long ns = q_int(h, "SELECT count(*) FROM samples");
  assert_true(ns >= 10);
  assert_int_equal(q_int(h, "SELECT count(*) FROM sample_species"), 3 * ns);
  /* per body energies weighted by the counts add up to the total per body */
  assert_int_equal(q_int(h, "SELECT count(*) FROM samples AS s WHERE abs((SELECT sum(p.e_tr * "
                            "c.count) FROM sample_species AS p JOIN species AS c ON c.run = p.run "
                            "AND c.idx = p.species WHERE p.run = s.run AND p.t = s.t) / 45.0 - "
                            "s.e_tr) > 1e-12 * s.e_tr"),
                   0);
  assert_int_equal(q_int(h, "SELECT count(*) FROM states WHERE label = 'initial' AND kind = 'body' "
                            "AND body >= 30"),
                   15);
  /* each state names its body's species (states.species, schema version 4) */
  assert_int_equal(q_int(h, "SELECT count(*) FROM states WHERE species IS CASE WHEN body < 20 "
                            "THEN 0 WHEN body < 30 THEN 1 ELSE 2 END"),
                   q_int(h, "SELECT count(*) FROM states"));
  assert_int_equal(q_int(h, "SELECT count(*) FROM frames WHERE n = 45"), 3); /* cpd 0, 5, 10 */
  assert_true(q_int(h, "SELECT count(*) FROM collisions WHERE kind = 'body-body'") > 0);
  assert_true(q_int(h, "SELECT count(*) FROM collisions WHERE kind = 'body-wall'") > 0);
  assert_int_equal(q_int(h,
                         "SELECT count(*) FROM collisions WHERE kind LIKE 'body-%' AND i >= 30 AND "
                         "(j BETWEEN 0 AND 29 OR disk_i NOT BETWEEN 0 AND 2)"),
                   0);
  sqlite3_close(h);
  /* the export writes each trimer's disks where the engine has them: 1 from the middle disk */
  const char *bin = getenv("HAFF_BIN");
  if (bin) {
    char cmd[1200], xyz[300];
    snprintf(xyz, sizeof xyz, "%s.xyz", db);
    snprintf(cmd, sizeof cmd, "'%s' export xyz '%s' --label initial -o '%s'", bin, db, xyz);
    assert_int_equal(system(cmd), 0);
    FILE *f = fopen(xyz, "r");
    assert_non_null(f);
    char line[1024];
    assert_non_null(fgets(line, sizeof line, f));
    assert_int_equal(atol(line), 20 * 2 + 10 + 15 * 3);
    assert_non_null(fgets(line, sizeof line, f));
    int no = 0;
    double p[3][2];
    while (fgets(line, sizeof line, f)) {
      char sp[8];
      double px, py;
      if (sscanf(line, "%7s %lf %lf", sp, &px, &py) != 3 || strcmp(sp, "O")) continue;
      p[no % 3][0] = px, p[no % 3][1] = py;
      if (++no % 3 == 0) /* disks 0, 1, 2 of one trimer: 1, 1 and sqrt 3 apart */
        assert_true(fabs(hypot(p[0][0] - p[1][0], p[0][1] - p[1][1]) - 1) < 1e-12 &&
                    fabs(hypot(p[2][0] - p[1][0], p[2][1] - p[1][1]) - 1) < 1e-12 &&
                    fabs(hypot(p[2][0] - p[0][0], p[2][1] - p[0][1]) - sqrt(3)) < 1e-12);
    }
    fclose(f);
    assert_int_equal(no, 45);
    unlink(xyz);
  }
  unlink(db);
  char side[400];
  snprintf(side, sizeof side, "%s-wal", db), unlink(side);
  snprintf(side, sizeof side, "%s-shm", db), unlink(side);
  snprintf(side, sizeof side, "%s.lock", db), unlink(side);
}

/* Bodies at the physical bounds of docs/scene-keys.md (issue 24), just inside each: a mass
 * ratio of 1e12 in one body, a dimer whose centres span 1e-9 d, a disk of 1e-4 d on the rim of
 * a unit disk (diameter ratio 1e4).  Elastic gases of 100 bodies at area fraction 0.15, 2e4
 * collisions (2e3 sanitized) in verification mode, the box from the sum of the disks' areas:
 * energy conserved to 1e-9 relative (round-off
 * of 2e4 collisions, ~1e-12), no overlap above 1e-9 of a diameter; and they make progress (a
 * mass ratio of 1e30 made none). */
static void bodies_at_bounds(void **state) {
  (void)state;
  static const struct {
    const char *name;
    int n;
    double x[3], d[3], m[3];
  } sh[] = {{"ratio_m", 2, {0, 1}, {1, 1}, {1, 1e12}},
            {"span", 2, {0, 1e-9}, {1, 1}, {1, 1}},
            {"ratio_d", 3, {0, 0.5, -0.5}, {1, 1e-4, 1}, {1, 1, 1}}};
  for (size_t k = 0; k < sizeof sh / sizeof sh[0]; k++) {
    hd_scene sc;
    long N = 100;
    double y[3] = {0, 0, 0};
    test_disk_scene(&sc, 0, 0.1, 1.0, 5 + k);
    add_species(&sc, sh[k].name, sh[k].n, sh[k].x, y, sh[k].d, sh[k].m, N, 1.0);
    sc.box_x = sc.box_y = sqrt((double)N * sh[k].n * M_PI / 4 / 0.15); /* (disks' areas) */
    sc.verify = 1;
    hd_sim *s;
    hd_error err;
    if (hd_sim_alloc(&s, &sc, &err)) fail_msg("%s: %s", sh[k].name, err.msg);
    double e0t, e0r, et, er;
    hd_sim_energy(s, -1, &e0t, &e0r);
    long n = test_size(20000, 10);
    for (long c = 0; c < n; c++) {
      hd_event_out ev;
      if (hd_sim_next(s, INFINITY, &ev, &err))
        fail_msg("%s: collision %ld: %s", sh[k].name, c, err.msg);
    }
    hd_sim_energy(s, -1, &et, &er);
    double drift = fabs(et + er - e0t - e0r) / (e0t + e0r);
    printf("# at the bound %s: %ld collisions, drift %.3g, max overlap %.3g\n", sh[k].name, n,
           drift, s->max_overlap);
    assert_true(drift < 1e-9);
    assert_true(s->max_overlap < 1e-9);
    hd_sim_free(s);
  }
}

static double test_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void too_slow(int sig) {
  (void)sig;
  static const char msg[] = "stop_cuts_long_searches: no answer to the stop request in 20 s\n";
  if (write(2, msg, sizeof msg - 1) < 0) _exit(1);
  _exit(1);
}

/* A stop request cuts a contact search that would run for minutes (issue 24: SIGTERM took 27 s
 * to 6 min): every body of a gas of dimers is given omega = 1e12 (a checkpoint with a huge
 * omega, or a stiff body), and each is predicted again with the stop requested.  Each search
 * is cut within HD_CA_POLL + 1 steps (milliseconds): the whole takes well under 2 s (before, one
 * search ran 1e8 steps, seconds, and then reported no contact; a guard ends the test after
 * 20 s); a cut body wakes up later to be predicted again (HD_WAKE at or after now), hd_sim_next
 * returns at once, and the state is a valid checkpoint (restored and checked). */
static void stop_cuts_long_searches(void **state) {
  (void)state;
  hd_scene sc;
  long N = 64;
  double x[2] = {0, 1}, y[2] = {0, 0}, d[2] = {1, 1}, m[2] = {1, 1};
  test_disk_scene(&sc, 0, 0.1, 1.0, 9);
  add_species(&sc, "spinner", 2, x, y, d, m, N, 1.0);
  sc.box_x = sc.box_y = sqrt((double)N * 2 * M_PI / 4 / 0.3);
  hd_sim *s;
  hd_error err;
  if (hd_sim_alloc(&s, &sc, &err)) fail_msg("%s", err.msg);
  for (int32_t i = 0; i < s->n; i++) s->b[i].k.omega = i % 2 ? 1e12 : -1e12;
  signal(SIGALRM, too_slow);
  alarm(20);
  hd_stop_requested = 1;
  double t0 = test_now();
  for (int32_t i = 0; i < s->n; i++) hd_predict(s, i);
  double dt = test_now() - t0;
  int woken = 0;
  for (int32_t i = 0; i < s->n; i++) {
    woken += s->b[i].c_dir == HD_WAKE;
    assert_true(s->b[i].ev_t >= s->c.t);
  }
  hd_event_out ev;
  t0 = test_now();
  int rc = hd_sim_next(s, INFINITY, &ev, &err);
  double dt2 = test_now() - t0;
  hd_stop_requested = 0;
  alarm(0);
  printf("# stop: %d of %ld bodies cut, predictions %.3f s, next %.3f s (rc %d)\n", woken, N, dt,
         dt2, rc);
  assert_true(woken > 0);
  assert_true(dt < 2.0 && dt2 < 1.0);
  assert_true(rc == HD_SIM_BUSY || rc == HD_OK);
  void *blob;
  size_t nb;
  assert_int_equal(hd_sim_checkpoint(s, &blob, &nb, &err), HD_OK);
  hd_sim *r;
  if (hd_sim_alloc_restore(&r, &sc, blob, nb, &err)) fail_msg("restore: %s", err.msg);
  free(blob);
  hd_sim_free(r);
  hd_sim_free(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(fast_paths),
      cmocka_unit_test(checkpoint_resume),
      cmocka_unit_test(run_stores_species),
      cmocka_unit_test(mixture_species),
      cmocka_unit_test(elastic_clusters),
      cmocka_unit_test(bodies_at_bounds),
      cmocka_unit_test(stop_cuts_long_searches),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
