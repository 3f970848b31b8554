/* Review 14, findings 3 and 5: `haff energy` averages the runs of a group at matching cpd (it
 * averaged them sample by sample, mixing runs logged at different samples_every and cutting a
 * group to its shortest run without a word), and a short window's fit prints no error it cannot
 * estimate (3 samples for 2 parameters printed D_e +- 1e-12, chi2/dof 1e-25), refuses a
 * --cpd-skip past the run's end (it was moved to the last sample), and counts in n_used the
 * samples of its window (it counted from sample 0). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "haff.h"
#include "hd_anadb.h"
#include "hd_db.h"
#include "hd_homog.h"
#include "hd_run.h"
#include "hd_runfit.h"
#include "hd_scene.h"
#include "test_cli_util.h"

/* Time at which a gas that follows Haff's law with D_e = De, nu0 = 0.3 and alpha reaches cpd:
 * tau = ln(1 + gamma nu0 t)/gamma, gamma = (1 - alpha^2)/(2 De). */
static double haff_t(double cpd, double alpha, double De) {
  double g = (1 - alpha * alpha) / (2 * De);
  return (exp(g * cpd) - 1) / (g * 0.3);
}

/* Writes a dimer run (N = 900, a = d = 1, box 100 x 100, alpha 0.9) that follows Haff's law
 * with D_e = 3 exactly (E = exp(-(1 - alpha^2) cpd / 3), e_rot = E/3), a sample every `every`
 * cpd from 0 to cpd_end; noise > 0: each sample's t is moved by noise * u and its E scaled
 * by 1 + noise * u', u and u' uniform in [-0.5, 0.5) from a fixed-seed generator (seed). */
static void add_run(hd_db *db, double every, double cpd_end, double noise, unsigned long seed) {
  const char *scene = "[system]\nbox = 100 100\n[dimers]\ncount = 900\nalpha = 0.9\na = 1\nd = 1\n";
  hd_error err;
  int64_t run;
  assert_int_equal(hd_db_run_begin(db, scene, seed, "test", &run, &err), HD_OK);
  assert_int_equal(hd_db_run_box(db, run, 100, 100, &err), HD_OK);
  double g = 1 - 0.81;
  unsigned long x = seed * 2654435761UL + 1;
  int n = (int)lround(cpd_end / every);
  for (int k = 0; k <= n; k++) {
    double cpd = every * k, E = exp(-g * cpd / 3);
    x = x * 6364136223846793005UL + 1442695040888963407UL;
    double u = (double)(x >> 11) / 9007199254740992.0 - 0.5;
    double t = haff_t(cpd, 0.9, 3) + (k > 0 ? noise * u : 0);
    x = x * 6364136223846793005UL + 1442695040888963407UL;
    E *= 1 + noise * ((double)(x >> 11) / 9007199254740992.0 - 0.5);
    hd_sample_row row = {t, (int64_t)lround(450 * cpd), cpd, E * 2 / 3, E / 3, 0.05, 0.05, 1, 1, 1,
                         1};
    assert_int_equal(hd_db_log_sample(db, run, &row, &err), HD_OK);
  }
  assert_int_equal(hd_db_run_hcs(db, run, &err), HD_OK);
  assert_int_equal(hd_db_run_status(db, run, "done", 1, 0.0, &err), HD_OK);
}

/* A new database dir/name holding the runs add_run writes: every[k], cpd_end[k]. */
static void make_db(const char *name, const double *every, const double *cpd_end, int n,
                    double noise, char *path, size_t np) {
  snprintf(path, np, "%s/%s", dir, name);
  unlink(path);
  hd_db *db;
  hd_error err;
  assert_int_equal(hd_db_open(&db, path, &err), HD_OK);
  for (int k = 0; k < n; k++) add_run(db, every[k], cpd_end[k], noise, (unsigned long)k + 1);
  assert_int_equal(hd_db_close(db, &err), HD_OK);
}

/* The text of file path in buf (at most n - 1 bytes). */
static void slurp(const char *path, char *buf, size_t n) {
  FILE *f = fopen(path, "r");
  assert_non_null(f);
  size_t k = fread(buf, 1, n - 1, f);
  buf[k] = 0;
  fclose(f);
}

/* Two runs that follow the same law exactly, one sampled every 0.5 cpd to cpd 60, one every
 * 1 cpd to cpd 100: the block is on the first's grid (cpd 0, 0.5, ..., 60: 121 rows, it stops
 * where the shorter run does, and the header says the longer one was cut), and every row's
 * E/E0 is the law's exp(-(1 - alpha^2) cpd / 3) to 1e-7 (printed to 8 digits; the log-linear
 * interpolation is exact for it), its t the law's at whole cpd (where both runs have a sample;
 * 1e-7 relative).  The sample-by-sample mean put run 1 at cpd k/2 beside run 2 at cpd k: its
 * rows were at cpd 0.75 k, 101 of them, and E/E0 at the last (cpd 75) 20 % off the law. */
static void energy_matching_cpd(void **state) {
  (void)state;
  char db[400], out[400];
  double every[2] = {0.5, 1}, end[2] = {60, 100};
  make_db("grid.db", every, end, 2, 0, db, sizeof db);
  snprintf(out, sizeof out, "%s/grid.tsv", dir);
  char *av[] = {"energy", db, "-o", out, NULL};
  assert_int_equal(hd_cmd_energy(4, av), 0);
  static char buf[1 << 16];
  slurp(out, buf, sizeof buf);
  char *hdr = buf, *line = strchr(buf, '\n');
  assert_non_null(line);
  *line = 0;
  printf("# %s\n", hdr);
  line = strchr(line + 1, '\n'); /* past the column header */
  assert_non_null(line);
  int rows = 0;
  double worst = 0;
  for (char *p = line + 1; *p; rows++) {
    double t, cpd, E, Er;
    assert_int_equal(sscanf(p, "%lf %lf %lf %lf", &t, &cpd, &E, &Er), 4);
    assert_true(fabs(cpd - 0.5 * rows) < 1e-12);
    double law = exp(-0.19 * cpd / 3);
    worst = fmax(worst, fabs(Er / law - 1));
    assert_true(fabs(Er / law - 1) < 1e-7);
    if (rows % 2 == 0 && rows > 0) assert_true(fabs(t / haff_t(cpd, 0.9, 3) - 1) < 1e-7);
    char *nl = strchr(p, '\n');
    p = nl ? nl + 1 : p + strlen(p);
  }
  printf("# %d rows, largest relative deviation of E/E0 from the law %.2g\n", rows, worst);
  assert_int_equal(rows, 121);
  assert_non_null(strstr(hdr, " runs=2 "));
  assert_non_null(strstr(hdr, " cpd_end=60 truncated_from=100"));
}

/* energy --by-species on a real mixture (60 dimers + 60 disks, alpha 0.9, fixed seeds 1 and
 * 2), logged every 0.5 cpd to cpd 12 and every 1 cpd to cpd 16: each block is on the 0.5 grid
 * up to cpd 12 (25 rows), its header says it was cut (truncated_from=16), and at whole cpd,
 * where both runs have samples, each row's e_tr and e_rot are the mean of the two runs' own
 * (energy --by-species --run of each; 1e-6 relative: 8 printed digits).  Sample by sample, the
 * rows were at cpd 0.75 k, 17 of them, the last mixing cpd 8 with cpd 16. */
static void energy_species_matching_cpd(void **state) {
  (void)state;
  char db[400], out[400], text[512];
  snprintf(db, sizeof db, "%s/mix.db", dir);
  unlink(db);
  for (int k = 0; k < 2; k++) {
    snprintf(text, sizeof text,
             "[system]\narea_fraction = 0.05\nseed = %d\n[dimers]\ncount = 60\nalpha = 0.9\n"
             "[disks]\ncount = 60\nalpha = 0.9\nalpha_dimer = 0.9\n[run]\nstop_cpd = %d\n"
             "[log]\ncollisions = none\nsamples_every = %g\n",
             k + 1, k ? 16 : 12, k ? 1.0 : 0.5);
    hd_scene sc;
    hd_error err;
    assert_int_equal(hd_scene_load_string(&sc, text, "mix.ini", NULL, 0, &err), HD_OK);
    hd_run_opts ro = {.db_path = db, .quiet = 1, .version = "test"};
    int64_t run;
    assert_int_equal(hd_run_new(&sc, &ro, &run, &err), HD_OK);
    hd_scene_free(&sc);
  }
  /* each run alone: its rows (cpd, e_tr, e_rot) of the first block (dimers) */
  static char buf[1 << 16];
  double one[2][40][3];
  int n1[2];
  for (int k = 0; k < 2; k++) {
    snprintf(out, sizeof out, "%s/mix%d.tsv", dir, k + 1);
    char id[16];
    snprintf(id, sizeof id, "%d", k + 1);
    char *av[] = {"energy", db, "--by-species", "--run", id, "-o", out, NULL};
    assert_int_equal(hd_cmd_energy(7, av), 0);
    slurp(out, buf, sizeof buf);
    char *p = strchr(strchr(buf, '\n') + 1, '\n') + 1;
    for (n1[k] = 0; *p && *p != '\n' && n1[k] < 40; n1[k]++) {
      double t;
      assert_int_equal(
          sscanf(p, "%lf %lf %lf %lf", &t, &one[k][n1[k]][0], &one[k][n1[k]][1], &one[k][n1[k]][2]),
          4);
      p = strchr(p, '\n') + 1;
    }
  }
  assert_int_equal(n1[0], 25);
  assert_int_equal(n1[1], 17);
  snprintf(out, sizeof out, "%s/mix.tsv", dir);
  char *av[] = {"energy", db, "--by-species", "-o", out, NULL};
  assert_int_equal(hd_cmd_energy(5, av), 0);
  slurp(out, buf, sizeof buf);
  char *hdr = buf, *line = strchr(buf, '\n');
  *line = 0;
  printf("# %s\n", hdr);
  char *p = strchr(line + 1, '\n') + 1;
  int rows = 0;
  for (; *p && *p != '\n'; rows++) {
    double t, cpd, et, er;
    assert_int_equal(sscanf(p, "%lf %lf %lf %lf", &t, &cpd, &et, &er), 4);
    assert_true(fabs(cpd - 0.5 * rows) < 1e-9);
    if (rows % 2 == 0) {
      int i = rows / 2; /* run 2's row at this cpd */
      assert_true(fabs(one[0][rows][0] - cpd) < 1e-9 && fabs(one[1][i][0] - cpd) < 1e-9);
      double m_et = 0.5 * (one[0][rows][1] + one[1][i][1]);
      double m_er = 0.5 * (one[0][rows][2] + one[1][i][2]);
      assert_true(fabs(et / m_et - 1) < 1e-6 && fabs(er / m_er - 1) < 1e-6);
    }
    p = strchr(p, '\n') + 1;
  }
  assert_int_equal(rows, 25);
  assert_non_null(strstr(hdr, " runs=2 species=dimers "));
  assert_non_null(strstr(hdr, " cpd_end=12 truncated_from=16"));
}

/* A window of 3 samples (cpd 5 to 6 with --cpd-max 6, a sample every 0.5 cpd; t noisy, fixed
 * seed): eq. (31) passes through all three (its first is the origin), so its D_e has no error
 * to give: D_e_err, nu0_err, chi2 NaN and haff-fit prints them empty, with n_used 3 (the
 * samples in the window; it printed 13, counted from sample 0); D_e_slope_err (a line through
 * 3 samples: the autocorrelation time is not estimated below 4) empty too.  With 5 samples
 * (--cpd-max 7) both errors are there.  Before: D_e_err ~1e-10, chi2/dof ~1e-25. */
static void short_window_errors(void **state) {
  (void)state;
  char db[400], out[400];
  double every[1] = {0.5}, end[1] = {60};
  make_db("short.db", every, end, 1, 1e-3, db, sizeof db);
  sqlite3 *h;
  hd_error err;
  assert_int_equal(hd_ana_open(&h, db, &err), HD_OK);
  hd_run_info *ri;
  size_t n;
  assert_int_equal(hd_ana_runs(h, -1, &ri, &n, &err), HD_OK);
  assert_int_equal(n, 1);
  hd_fit_opts o = hd_fit_opts_defaults();
  hd_run_fit f;
  o.cpd_max = 6;
  assert_int_equal(hd_run_fit_do(h, ri, &o, &f, &err), HD_OK);
  printf("# 3 samples: D_e %g +- %g chi2 %g, slope %g +- %g\n", f.haff.D_e, f.haff.D_e_err,
         f.haff.chi2, f.D_e_slope, f.D_e_slope_err);
  assert_int_equal(f.n_used - f.n_start, 3);
  assert_true(f.haff_ok && f.haff.D_e > 0 && f.short_window);
  assert_true(isnan(f.haff.D_e_err) && isnan(f.haff.nu0_err) && isnan(f.haff.chi2));
  assert_true(isnan(f.ratio_err) && f.slope_ok && isnan(f.D_e_slope_err));
  o.cpd_max = 7;
  assert_int_equal(hd_run_fit_do(h, ri, &o, &f, &err), HD_OK);
  printf("# 5 samples: D_e %g +- %g chi2 %g, slope %g +- %g\n", f.haff.D_e, f.haff.D_e_err,
         f.haff.chi2, f.D_e_slope, f.D_e_slope_err);
  assert_int_equal(f.n_used - f.n_start, 5);
  assert_true(f.haff.D_e_err > 0 && f.haff.chi2 > 0 && f.D_e_slope_err > 0);
  free(ri);
  sqlite3_close(h);
  /* haff-fit's row: n_used 3, the errors and chi2_dof empty */
  snprintf(out, sizeof out, "%s/short.tsv", dir);
  char *av[] = {"haff-fit", db, "--cpd-max", "6", "-o", out, NULL};
  assert_int_equal(hd_cmd_haff_fit(6, av), 0);
  char buf[4096];
  slurp(out, buf, sizeof buf);
  char *row = strchr(buf, '\n') + 1, *c[20];
  printf("# %s", row);
  c[0] = row;
  for (int k = 1; k < 20; k++) { /* split at tabs: an empty cell stays empty */
    c[k] = strchr(c[k - 1], '\t');
    assert_non_null(c[k]);
    *c[k]++ = 0;
  }
  /* run species alpha a_over_d n_used detected t_end cpd_end D_e D_e_fit_err nu0_eff
   * nu0_eff_fit_err nu0_enskog ratio ratio_fit_err chi2_dof cpd_start D_e_slope D_e_slope_err */
  assert_string_equal(c[4], "3");
  assert_string_equal(c[7], "6");
  assert_true(*c[8] != 0 && *c[10] != 0 && *c[17] != 0);
  assert_string_equal(c[9], "");
  assert_string_equal(c[11], "");
  assert_string_equal(c[14], "");
  assert_string_equal(c[15], "");
  assert_string_equal(c[16], "5");
  assert_string_equal(c[18], "");
}

/* --cpd-skip past the run's last sample is refused: hd_hcs_detect returns HD_EINPUT and says
 * where the run ends; haff-fit --run exits 2 (it fitted the last 3 samples, cpd 59 to 60, and
 * printed D_e +- 1e-12).  A run shorter than the default transient (5 cpd) keeps its window of
 * its last 3 samples, flagged short, with a note. */
static void cpd_skip_past_end(void **state) {
  (void)state;
  enum { N = 121 };
  double cpd[N], nan[N];
  for (int i = 0; i < N; i++) cpd[i] = 0.5 * i, nan[i] = NAN;
  hd_hcs_opts o = hd_hcs_defaults();
  hd_hcs hc;
  hd_error err;
  o.cpd_skip = 100;
  assert_int_equal(hd_hcs_detect(cpd, nan, nan, nan, N, &o, &hc, &err), HD_EINPUT);
  printf("# %s\n", err.msg);
  assert_non_null(strstr(err.msg, "(cpd 60)"));
  o.cpd_skip = 60; /* the last sample itself is a window start */
  assert_int_equal(hd_hcs_detect(cpd, nan, nan, nan, N, &o, &hc, &err), HD_OK);
  assert_int_equal(hc.n_start, N - 1);
  char db[400];
  double every[2] = {0.5, 0.5}, end[2] = {60, 4};
  make_db("skip.db", every, end, 2, 1e-3, db, sizeof db);
  char *av[] = {"haff-fit", db, "--run", "1", "--cpd-skip", "100", "-o", "/dev/null", NULL};
  assert_int_equal(hd_cmd_haff_fit(8, av), 2);
  /* the 4-cpd run, default options: its last 3 samples (cpd 3 to 4), short */
  sqlite3 *h;
  assert_int_equal(hd_ana_open(&h, db, &err), HD_OK);
  hd_run_info *ri;
  size_t n;
  assert_int_equal(hd_ana_runs(h, 2, &ri, &n, &err), HD_OK);
  hd_fit_opts fo = hd_fit_opts_defaults();
  hd_run_fit f;
  assert_int_equal(hd_run_fit_do(h, ri, &fo, &f, &err), HD_OK);
  printf("# 4-cpd run: cpd %g to %g, why: %s\n", f.cpd_start, f.cpd_end, f.why);
  assert_true(f.cpd_start == 3 && f.cpd_end == 4 && f.short_window && f.why[0]);
  fo.hcs.cpd_skip = 4.5; /* asked for: refused */
  assert_int_equal(hd_run_fit_do(h, ri, &fo, &f, &err), HD_EINPUT);
  assert_non_null(strstr(err.msg, "run 2: "));
  free(ri);
  sqlite3_close(h);
}

static int setup(void **state) {
  (void)state;
  return test_cli_mkdtemp("fitwin");
}

static int teardown(void **state) {
  (void)state;
  return test_cli_rmdir();
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(energy_matching_cpd),
      cmocka_unit_test(energy_species_matching_cpd),
      cmocka_unit_test(short_window_errors),
      cmocka_unit_test(cpd_skip_past_end),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
