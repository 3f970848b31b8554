/* Tests of hd_scene: scene files, overrides, error messages, canonical text, state CSV.
 * Run from the repository root (test inputs under tests/data/scenes/; others go to a mkdtemp
 * folder).  Every expected value below comes from the input text or from geometry, not from the
 * code's own output. */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
// clang-format on

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gsl/gsl_rng.h>

#include "hd_body.h"
#include "hd_scene.h"

static char tmpdir[] = "/tmp/haff-test-scene-XXXXXX";

static void write_file(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  fputs(text, f);
  fclose(f);
}

static const char *tmp_path(const char *name) {
  static char buf[4][512];
  static int i;
  i = (i + 1) % 4;
  snprintf(buf[i], sizeof buf[i], "%s/%s", tmpdir, name);
  return buf[i];
}

/* Asserts that msg contains every non-NULL needle (prints msg on failure). */
static void assert_has(const char *msg, const char *a, const char *b, const char *c,
                       const char *d) {
  const char *n[4] = {a, b, c, d};
  for (int i = 0; i < 4; i++)
    if (n[i] && !strstr(msg, n[i])) {
      print_error("message \"%s\" lacks \"%s\"\n", msg, n[i]);
      fail();
    }
}

/* ---- a good scene --------------------------------------------------------------------------- */

static void good_scene_values(void **state) {
  (void)state;
  hd_scene sc;
  hd_error e;
  assert_int_equal(hd_scene_load(&sc, "tests/data/scenes/good.ini", NULL, 0, &e), HD_OK);
  assert_string_equal(e.msg, "");
  assert_string_equal(sc.path, "tests/data/scenes/good.ini");
  assert_string_equal(sc.dir, "tests/data/scenes");
  assert_true(sc.box_x == 40 && sc.box_y == 30.5);
  assert_true(sc.area_fraction == 0);
  assert_true(sc.seed == ULLONG_MAX);
  assert_int_equal(sc.n_dimers, 12);
  assert_true(sc.dimer_d == 1.25 && sc.dimer_a == 0.75 && sc.dimer_m == 2 &&
              sc.dimer_alpha == 0.95);
  assert_int_equal(sc.n_disks, 7);
  assert_true(sc.disk_sigma == 0.5 && sc.disk_mass == 3 && sc.disk_alpha == 0.8);
  assert_true(sc.disk_alpha_dimer == 0.85);
  assert_int_equal(sc.walls, HD_WALL_TOP | HD_WALL_LEFT | HD_WALL_BOTTOM | HD_WALL_RIGHT);
  assert_true(sc.wall_alpha == 0.7);
  assert_true(sc.temperature == 2.5);
  assert_int_equal(sc.placement, HD_PLACE_LATTICE);
  assert_true(sc.stop_time == 100 && sc.stop_events == 1e6 && sc.stop_cpd == 200);
  assert_int_equal(sc.verify, 1);
  assert_true(sc.checkpoint_every == 30);
  assert_int_equal(sc.log_collisions, HD_LOG_EVERY);
  assert_int_equal(sc.log_every, 10);
  assert_true(sc.samples_every == 0.5);
  assert_int_equal(sc.n_velocities_at, 4);
  assert_true(sc.velocities_at[0] == 0.1 && sc.velocities_at[3] == 100);
  assert_non_null(sc.text);
  hd_scene_free(&sc);
  assert_null(sc.text);
}

static void defaults_and_absent_sections(void **state) {
  (void)state;
  hd_scene sc;
  hd_error e;
  const char *text = "[disks]\ncount = 10\n[system]\nbox = 20 20\n[run]\nstop_events = 100\n";
  assert_int_equal(hd_scene_load_string(&sc, text, "d.ini", NULL, 0, &e), HD_OK);
  assert_int_equal(sc.n_dimers, 0);
  assert_int_equal(sc.n_disks, 10);
  assert_true(sc.seed == 1 && sc.disk_sigma == 1 && sc.disk_mass == 1 && sc.disk_alpha == 1);
  assert_true(sc.disk_alpha_dimer == 1 && sc.temperature == 1 && sc.checkpoint_every == 60);
  assert_int_equal(sc.placement, HD_PLACE_RANDOM);
  assert_int_equal(sc.walls, 0);
  assert_int_equal(sc.log_collisions, HD_LOG_ALL);
  assert_true(sc.samples_every == 0 && sc.n_velocities_at == 0);
  assert_string_equal(sc.dir, ".");
  /* absent sections stay out of the text */
  assert_null(strstr(sc.text, "[dimers]"));
  assert_null(strstr(sc.text, "[log]"));
  assert_non_null(strstr(sc.text, "[disks]"));
  hd_scene_free(&sc);
  /* alpha_dimer defaults to the disks' alpha; CRLF line ends are fine */
  text =
      "[disks]\r\ncount = 2\r\nalpha = 0.6\r\n[system]\r\nbox = 5 5\r\n[run]\r\nstop_cpd = 1\r\n";
  assert_int_equal(hd_scene_load_string(&sc, text, "crlf.ini", NULL, 0, &e), HD_OK);
  assert_true(sc.disk_alpha == 0.6 && sc.disk_alpha_dimer == 0.6);
  hd_scene_free(&sc);
}

/* ---- area fraction and the exact dimer area ------------------------------------------------- */

static void dimer_area_exact(void **state) {
  (void)state;
  /* Two unit-diameter disks (r = 1/2): one disk at a = 0, two whole disks at a >= d, and at
   * a = r the lens of two circles at distance r is r^2 (2 pi / 3 - sqrt(3) / 2) (textbook
   * circle-circle intersection).  1e-14: round-off of a few operations. */
  assert_true(fabs(hd_dimer_area(1, 0) - M_PI / 4) < 1e-14);
  assert_true(fabs(hd_dimer_area(1, 1) - M_PI / 2) < 1e-14);
  assert_true(fabs(hd_dimer_area(1, 3) - M_PI / 2) < 1e-14);
  double r = 0.5, lens = r * r * (2 * M_PI / 3 - sqrt(3) / 2);
  assert_true(fabs(hd_dimer_area(1, 0.5) - (2 * M_PI * r * r - lens)) < 1e-14);
  /* scales as d^2 */
  assert_true(fabs(hd_dimer_area(2, 1) - 4 * hd_dimer_area(1, 0.5)) < 1e-13);
  /* continuous at a = d (the lens vanishes like (d - a)^{3/2}) */
  assert_true(fabs(hd_dimer_area(1, 1 - 1e-10) - M_PI / 2) < 1e-12);
}

static void area_fraction_box(void **state) {
  (void)state;
  hd_scene sc;
  hd_error e;
  const char *text = "[system]\narea_fraction = 0.05\n[disks]\ncount = 1000\n[run]\nstop_cpd = 1\n";
  assert_int_equal(hd_scene_load_string(&sc, text, "af.ini", NULL, 0, &e), HD_OK);
  double L = sqrt(1000 * M_PI / 4 / 0.05);
  assert_true(fabs(sc.box_x - L) < 1e-12 * L && sc.box_x == sc.box_y);
  assert_true(sc.area_fraction == 0.05);
  hd_scene_free(&sc);
  /* dimers with a = d/2 and some disks: total area over the box is eta */
  text = "[system]\narea_fraction = 0.3\n[dimers]\ncount = 100\na = 0.5\n[disks]\ncount = 50\n"
         "sigma = 2\n[run]\nstop_cpd = 1\n";
  assert_int_equal(hd_scene_load_string(&sc, text, "af2.ini", NULL, 0, &e), HD_OK);
  double rr = 0.5, dimer = 2 * M_PI * rr * rr - rr * rr * (2 * M_PI / 3 - sqrt(3) / 2);
  double area = 100 * dimer + 50 * M_PI;
  assert_true(fabs(sc.box_x * sc.box_y * 0.3 - area) < 1e-12 * area);
  assert_true(fabs(hd_scene_covered_area(&sc) - area) < 1e-12 * area);
  hd_scene_free(&sc);
}

/* ---- bad scenes ----------------------------------------------------------------------------- */

typedef struct bad_case {
  const char *text;
  const char *over; /* one override or NULL */
  int code;
  const char *at, *what, *why; /* substrings the message must hold */
} bad_case;

#define RUN "[run]\nstop_cpd = 1\n"
#define BOX "[system]\nbox = 50 50\n"

static const bad_case bad_cases[] = {
    {"[rods]\ncount = 5\n" RUN, NULL, HD_EINPUT, "bad.ini:2:", "[rods] count = 5", "even"},
    {"[rods]\n" RUN, NULL, HD_EINPUT, "bad.ini:1:", "[rods] count", "missing"},
    {"[rods]\ncount = 4\neps_step = -1\n" RUN, NULL, HD_EINPUT, "bad.ini:3:", "[rods] eps_step",
     ">= 0"},
    {RUN "stoptime = 2\n", NULL, HD_EINPUT, "bad.ini:3:", "[run] stoptime", "unknown key"},
    {RUN "stop_cpd = 2\n", NULL, HD_EINPUT, "bad.ini:3:", "[run] stop_cpd", "duplicate"},
    {RUN BOX "[dimers]\nalpha = 0.9\n", NULL, HD_EINPUT, "bad.ini:5:", "[dimers] count", "missing"},
    {RUN BOX "[walls]\nalpha = 0.9\n", NULL, HD_EINPUT, "bad.ini:5:", "[walls] sides", "missing"},
    {RUN "[dimers]\ncount = 3\n", NULL, HD_EINPUT, "bad.ini:0:", "[system] box", "missing"},
    {RUN "[dimers]\nalpha = 1.5x\n", NULL, HD_EINPUT, "bad.ini:4:", "[dimers] alpha = 1.5x",
     "not a number"},
    {RUN "[dimers]\nalpha =\n", NULL, HD_EINPUT, "bad.ini:4:", "[dimers] alpha", "missing"},
    {RUN "[dimers]\nalpha = nan\n", NULL, HD_EINPUT, "bad.ini:4:", "[dimers] alpha", "finite"},
    {RUN "[disks]\nalpha = inf\n", NULL, HD_EINPUT, "bad.ini:4:", "[disks] alpha", "finite"},
    {RUN "[disks]\nalpha = 0x1\n", NULL, HD_EINPUT, "bad.ini:4:", "[disks] alpha", "number"},
    {RUN "[dimers]\nalpha = 1.5\n", NULL, HD_EINPUT, "bad.ini:4:", "[dimers] alpha = 1.5",
     "[0, 1]"},
    {RUN "[walls]\nalpha = -0.1\n", NULL, HD_EINPUT, "bad.ini:4:", "[walls] alpha", "[0, 1]"},
    {RUN "[disks]\nalpha_dimer = 2\n", NULL, HD_EINPUT, "bad.ini:4:", "[disks] alpha_dimer",
     "[0, 1]"},
    {RUN "[dimers]\ncount = -1\n", NULL, HD_EINPUT, "bad.ini:4:", "[dimers] count", "[0,"},
    {RUN "[disks]\ncount = 2.5\n", NULL, HD_EINPUT, "bad.ini:4:", "[disks] count", "whole"},
    {RUN "[dimers]\nd = 0\n", NULL, HD_EINPUT, "bad.ini:4:", "[dimers] d", "> 0"},
    {RUN "[dimers]\nm = -2\n", NULL, HD_EINPUT, "bad.ini:4:", "[dimers] m", "> 0"},
    {RUN "[dimers]\na = -0.5\n", NULL, HD_EINPUT, "bad.ini:4:", "[dimers] a", ">= 0"},
    {RUN "[disks]\nsigma = 0\n", NULL, HD_EINPUT, "bad.ini:4:", "[disks] sigma", "> 0"},
    {RUN "[disks]\nmass = 0\n", NULL, HD_EINPUT, "bad.ini:4:", "[disks] mass", "> 0"},
    {RUN "[init]\ntemperature = 0\n", NULL, HD_EINPUT, "bad.ini:4:", "[init] temperature", "> 0"},
    {RUN "[init]\ntemperature = -1\n", NULL, HD_EINPUT, "bad.ini:4:", "[init] temperature", "> 0"},
    {RUN "[init]\nplacement = grid\n", NULL, HD_EINPUT, "bad.ini:4:", "[init] placement",
     "random or lattice"},
    {RUN "[system]\nbox = 0 10\n", NULL, HD_EINPUT, "bad.ini:4:", "[system] box", "> 0"},
    {RUN "[system]\nbox = 10\n", NULL, HD_EINPUT, "bad.ini:4:", "[system] box", "two"},
    {RUN "[system]\nseed = -1\n", NULL, HD_EINPUT, "bad.ini:4:", "[system] seed", "whole"},
    {RUN "[system]\narea_fraction = 0.95\n", NULL, HD_EINPUT,
     "bad.ini:4:", "[system] area_fraction", "(0, 0.9069)"},
    {RUN "[system]\narea_fraction = 0\n", NULL, HD_EINPUT, "bad.ini:4:", "[system] area_fraction",
     "(0, 0.9069)"},
    {RUN "[system]\nbox = 10 10\narea_fraction = 0.1\n[disks]\ncount = 1\n", NULL, HD_EINPUT,
     "bad.ini:5:", "[system] area_fraction", "not both"},
    {RUN "[log]\nsamples_every = -1\n", NULL, HD_EINPUT, "bad.ini:4:", "[log] samples_every",
     ">= 0"},
    {RUN "[log]\ncollisions = some\n", NULL, HD_EINPUT, "bad.ini:4:", "[log] collisions",
     "every N"},
    {RUN "[log]\ncollisions = every 0\n", NULL, HD_EINPUT, "bad.ini:4:", "[log] collisions",
     "N >= 1"},
    {RUN "[log]\nvelocities_at = 10 5\n", NULL, HD_EINPUT, "bad.ini:4:", "[log] velocities_at",
     "ascending"},
    {RUN "[log]\nvelocities_at = 1 x\n", NULL, HD_EINPUT, "bad.ini:4:", "[log] velocities_at",
     "not a number"},
    /* a snapshot past the stop (in the same unit) is refused at set-up (issue 16) */
    {RUN "[log]\nvelocities_at = 0.5 2\n", NULL, HD_EINPUT, "bad.ini:4:", "[log] velocities_at",
     "past stop_cpd"},
    {"[run]\nstop_time = 10\n[log]\nvelocities_at_time = 1 20\n", NULL, HD_EINPUT,
     "bad.ini:4:", "[log] velocities_at_time", "past stop_time"},
    {RUN "[log]\nvelocities_at = 0.5\nvelocities_at_time = 1\n", NULL, HD_EINPUT,
     "bad.ini:5:", "[log] velocities_at_time", "together with velocities_at"},
    {RUN "[log]\nvelocities_at_time = 2 1\n", NULL, HD_EINPUT,
     "bad.ini:4:", "[log] velocities_at_time", "ascending"},
    {RUN "[walls]\nsides = left left\n", NULL, HD_EINPUT, "bad.ini:4:", "[walls] sides",
     "repeated"},
    {RUN "[walls]\nsides = left front\n", NULL, HD_EINPUT, "bad.ini:4:", "[walls] sides",
     "unknown side"},
    {RUN "[walls]\nsides = right\n", NULL, HD_EINPUT, "bad.ini:4:", "[walls] sides",
     "'right' needs 'left'"},
    {RUN "[walls]\nsides = left right top\n", NULL, HD_EINPUT, "bad.ini:4:", "[walls] sides",
     "'top' needs 'bottom'"},
    {RUN "[run]\nverify = maybe\n", NULL, HD_EINPUT, "bad.ini:4:", "[run] verify", "expected"},
    {RUN "[run]\ncheckpoint_every = 0\n", NULL, HD_EINPUT, "bad.ini:4:", "[run] checkpoint_every",
     "> 0"},
    {"[system]\nseed = 3\n", NULL, HD_EINPUT, "bad.ini:0:", "[run]", "no stop condition"},
    {"[system]\nseed = 3\n\n[run]\nverify = 1\n", NULL, HD_EINPUT, "bad.ini:4:", "[run]",
     "no stop condition"},
    {RUN "[run]\nstop_time = 0\n", NULL, HD_EINPUT, "bad.ini:4:", "[run] stop_time", "> 0"},
    /* a bond below 1e-9 d (here d = 2: below 2e-9) is lost in round-off */
    {RUN BOX "[dimers]\ncount = 2\nd = 2\na = 1.9e-9\n", NULL, HD_EINPUT,
     "bad.ini:8:", "[dimers] a", "must be 0 or at least 1e-09 d = 2e-09"},
    /* a dimer of a + d = 2 cannot fit an edge of 1.5 */
    {RUN "[system]\nbox = 1.5 10\n[dimers]\ncount = 1\n", NULL, HD_EINPUT,
     "bad.ini:4:", "[system] box", "too small"},
    /* disks of 1e160 cover inf: the derived box was inf, and the cell grid's set-up hung */
    {RUN "[system]\narea_fraction = 0.05\n[disks]\ncount = 10\nsigma = 1e160\n", NULL, HD_EINPUT,
     "bad.ini:4:", "[system] area_fraction", "not a finite number"},
    /* 100 unit disks cover pi/4 = 0.785 of a 10 x 10 box: above the random limit 0.75 */
    {RUN "[system]\nbox = 10 10\n[disks]\ncount = 100\n", NULL, HD_EINPUT,
     "bad.ini:4:", "[system] box", "dense"},
    /* a lattice of 10 x 10 unit cells holds 100 disks, not 101 */
    {RUN "[system]\nbox = 10 10\n[disks]\ncount = 101\n[init]\nplacement = lattice\n", NULL,
     HD_EINPUT, "bad.ini:4:", "[system] box", "lattice"},
    {RUN "[init]\nplacement = random\nstate = x.csv\n", NULL, HD_EINPUT,
     "bad.ini:5:", "[init] state", "placement"},
    {RUN "seed = 1\n", NULL, HD_EINPUT, "bad.ini:3:", "[run] seed", "unknown key"},
    {"seed = 1\n" RUN, NULL, HD_EINPUT, "bad.ini:1:", "seed", "outside"},
    {RUN "stop_time\n", NULL, HD_EINPUT, "bad.ini:3:", "malformed", NULL},
    {RUN "[dimers\n", NULL, HD_EINPUT, "bad.ini:3:", "section", "]"},
    {"[dimers] count = 5\n" RUN, NULL, HD_EINPUT, "bad.ini:1:", "[section]", "own line"},
    /* overrides: the same checks, named by the --set */
    {RUN, "dimers.alpha=1.5", HD_EINPUT, "--set dimers.alpha=1.5:", "[dimers] alpha = 1.5",
     "[0, 1]"},
    {RUN, "rods.count=3", HD_EINPUT, "--set rods.count=3:", "[rods] count = 3", "even"},
    {RUN, "run.stoptime=3", HD_EINPUT, "--set run.stoptime=3:", "[run] stoptime", "unknown key"},
    {RUN, "dimersalpha=1", HD_EINPUT, "--set dimersalpha=1:", "SECTION.KEY=VALUE", NULL},
    {RUN, "dimers.alpha", HD_EINPUT, "--set dimers.alpha:", "SECTION.KEY=VALUE", NULL},
    {RUN, "log.samples_every=nan", HD_EINPUT, "--set log.samples_every=nan:", "[log] samples_every",
     "finite"},
    {"[system]\nseed = 3\n", "system.seed=4", HD_EINPUT, "bad.ini:0:", "[run]", "stop"},
};

static void bad_scenes(void **state) {
  (void)state;
  for (size_t i = 0; i < sizeof bad_cases / sizeof bad_cases[0]; i++) {
    const bad_case *b = &bad_cases[i];
    hd_scene sc;
    hd_error e;
    const char *over[1] = {b->over};
    int rc = hd_scene_load_string(&sc, b->text, "bad.ini", over, b->over ? 1 : 0, &e);
    if (rc != b->code) print_error("case %zu: rc %d, message \"%s\"\n", i, rc, e.msg);
    assert_int_equal(rc, b->code);
    assert_int_equal(e.code, b->code);
    assert_has(e.msg, b->at, b->what, b->why, NULL);
    assert_null(sc.text);
    hd_scene_free(&sc);
  }
}

/* An override mends a bad line of the file: the file's value of a key that a --set replaces is
 * not read (alpha = 1.5 stopped the run although --set disks.alpha=0.5 replaced it); the key
 * must still exist, and a bad value of another key is still an error. */
static void override_mends_a_bad_line(void **state) {
  (void)state;
  hd_scene sc;
  hd_error e;
  const char *text = RUN "[disks]\ncount = 2\nalpha = 1.5\n[system]\nbox = 5 5\n";
  const char *fix[] = {"disks.alpha=0.5"};
  assert_int_equal(hd_scene_load_string(&sc, text, "s.ini", fix, 1, &e), HD_OK);
  assert_true(sc.disk_alpha == 0.5);
  assert_non_null(strstr(sc.text, "alpha = 0.5"));
  hd_scene_free(&sc);
  assert_int_equal(hd_scene_load_string(&sc, text, "s.ini", NULL, 0, &e), HD_EINPUT);
  assert_string_equal(e.msg, "s.ini:5: [disks] alpha = 1.5: must be in [0, 1]");
  const char *other[] = {"disks.count=4"};
  assert_int_equal(hd_scene_load_string(&sc, text, "s.ini", other, 1, &e), HD_EINPUT);
  assert_string_equal(e.msg, "s.ini:5: [disks] alpha = 1.5: must be in [0, 1]");
  const char *bad[] = {"disks.alpha=2"}; /* and the override itself is checked */
  assert_int_equal(hd_scene_load_string(&sc, text, "s.ini", bad, 1, &e), HD_EINPUT);
  assert_string_equal(e.msg, "--set disks.alpha=2: [disks] alpha = 2: must be in [0, 1]");
  hd_scene_free(&sc);
}

static void override_message_exact(void **state) {
  (void)state;
  hd_scene sc;
  hd_error e;
  const char *over[] = {"dimers.alpha=1.5"};
  assert_int_equal(hd_scene_load_string(&sc, RUN, "s.ini", over, 1, &e), HD_EINPUT);
  assert_string_equal(e.msg, "--set dimers.alpha=1.5: [dimers] alpha = 1.5: must be in [0, 1]");
  /* the same error in a file */
  assert_int_equal(
      hd_scene_load_string(&sc, RUN "[dimers]\nalpha = 1.5\n", "scene.ini", NULL, 0, &e),
      HD_EINPUT);
  assert_string_equal(e.msg, "scene.ini:4: [dimers] alpha = 1.5: must be in [0, 1]");
}

static void long_line(void **state) {
  (void)state;
  size_t n = HD_SCENE_MAX_LINE + 100;
  char *text = malloc(n + 64);
  assert_non_null(text);
  strcpy(text, RUN "[log]\nvelocities_at =");
  while (strlen(text) < n) strcat(text, " 1");
  strcat(text, "\n");
  hd_scene sc;
  hd_error e;
  assert_int_equal(hd_scene_load_string(&sc, text, "long.ini", NULL, 0, &e), HD_EINPUT);
  assert_has(e.msg, "long.ini:4:", "too long", NULL, NULL);
  free(text);
}

/* A line of exactly HD_SCENE_MAX_LINE bytes followed by its newline is accepted (the newline was
 * counted, so it was refused unless it ended the file), one byte more is not. */
static void line_at_the_limit(void **state) {
  (void)state;
  for (int extra = 0; extra < 2; extra++) {
    char *text = malloc(HD_SCENE_MAX_LINE + 256);
    assert_non_null(text);
    strcpy(text, "[system]\nbox = 60 60\n[disks]\ncount = 10\n");
    size_t at = strlen(text);
    strcat(text, "alpha = 0.9");
    while (strlen(text) - at < (size_t)HD_SCENE_MAX_LINE + (size_t)extra) strcat(text, " ");
    strcat(text, "\n" RUN);
    hd_scene sc;
    hd_error e;
    int rc = hd_scene_load_string(&sc, text, "edge.ini", NULL, 0, &e);
    if (extra) {
      assert_int_equal(rc, HD_EINPUT);
      assert_has(e.msg, "edge.ini:5:", "too long", NULL, NULL);
    } else {
      assert_int_equal(rc, HD_OK);
      assert_true(sc.disk_alpha == 0.9);
      hd_scene_free(&sc);
    }
    free(text);
  }
}

/* A section line that starts with \v, \f or \r (libinih skips them, and so does the reader now)
 * is a section like any other: "\v[disks]" took effect but was missing from the canonical text,
 * so a resumed run went on without it; "\v[bogus]" was accepted.  And eps_step is 0 or in
 * [1e-5, 0.5] (1e-300 crashed the run after the database was made). */
static void blank_prefixed_sections(void **state) {
  (void)state;
  hd_scene sc;
  hd_error e;
  assert_int_equal(hd_scene_load_string(&sc,
                                        "[system]\nbox = 60 60\n" RUN "[init]\n\v[disks]\n"
                                        "count = 40\nalpha = 0.99\n",
                                        "vt.ini", NULL, 0, &e),
                   HD_OK);
  assert_true(sc.n_disks == 40 && sc.disk_alpha == 0.99);
  assert_non_null(strstr(sc.text, "[disks]\ncount = 40"));
  hd_scene_free(&sc);
  assert_int_equal(
      hd_scene_load_string(&sc, "[system]\nbox = 60 60\n[disks]\ncount = 4\n" RUN "\f[bogus]\n",
                           "vt.ini", NULL, 0, &e),
      HD_EINPUT);
  printf("# %s\n", e.msg);
  assert_has(e.msg, "vt.ini:", "bogus", NULL, NULL);
  assert_int_equal(hd_scene_load_string(&sc, "[rods]\ncount = 10\neps_step = 1e-300\n" RUN,
                                        "es.ini", NULL, 0, &e),
                   HD_EINPUT);
  assert_has(e.msg, "es.ini:3:", "[rods] eps_step", "[1e-5, 0.5]", NULL);
}

/* A directory given as the scene or the state file says so (it was "read error"); a state file
 * whose path a scene cannot store (" ;" starts an INI comment) is refused at once instead of
 * making a run that cannot be re-run from its stored scene. */
static void directories_and_unstorable_paths(void **state) {
  (void)state;
  hd_scene sc;
  hd_error e;
  assert_int_equal(mkdir(tmp_path("adir"), 0755), 0);
  assert_int_equal(hd_scene_load(&sc, tmp_path("adir"), NULL, 0, &e), HD_EIO);
  assert_has(e.msg, "adir", "is a directory", NULL, NULL);
  write_file(tmp_path("d.ini"), "[system]\nbox = 30 30\n[init]\nstate = adir\n" RUN);
  assert_int_equal(hd_scene_load(&sc, tmp_path("d.ini"), NULL, 0, &e), HD_EINPUT);
  assert_has(e.msg, "d.ini:4:", "[init] state", "is a directory", NULL);
  assert_int_equal(mkdir(tmp_path("x ;y"), 0755), 0);
  write_file(tmp_path("x ;y/st.csv"),
             "kind,x,y,phi,vx,vy,omega\ndisk,1,1,0,0,0,0\ndisk,3,3,0,1,0,0\n");
  write_file(tmp_path("x ;y/s.ini"), "[system]\nbox = 30 30\n[init]\nstate = st.csv\n" RUN);
  assert_int_equal(hd_scene_load(&sc, tmp_path("x ;y/s.ini"), NULL, 0, &e), HD_EINPUT);
  assert_has(e.msg, "s.ini:4:", "cannot store", NULL, NULL);
}

static void missing_files(void **state) {
  (void)state;
  hd_scene sc;
  hd_error e;
  assert_int_equal(hd_scene_load(&sc, "tests/data/scenes/missing-state.ini", NULL, 0, &e), HD_EIO);
  assert_has(e.msg, "missing-state.ini:7:", "[init] state = nothere.csv", "cannot read",
             "tests/data/scenes/nothere.csv");
  assert_null(sc.text);
  assert_int_equal(hd_scene_load(&sc, "tests/data/scenes/no-such-scene.ini", NULL, 0, &e), HD_EIO);
  assert_has(e.msg, "no-such-scene.ini", "cannot read", NULL, NULL);
}

/* ---- overrides ------------------------------------------------------------------------------ */

static void overrides_apply(void **state) {
  (void)state;
  hd_scene sc;
  hd_error e;
  /* an override replaces a file value (no duplicate error), and may create a section */
  const char *over[] = {"dimers.alpha=0.5", " log . samples_every = 2 ", "system.seed=7",
                        "walls.sides=bottom top"};
  assert_int_equal(hd_scene_load(&sc, "tests/data/scenes/good.ini", over, 4, &e), HD_OK);
  assert_true(sc.dimer_alpha == 0.5 && sc.samples_every == 2 && sc.seed == 7);
  assert_int_equal(sc.walls, HD_WALL_BOTTOM | HD_WALL_TOP);
  assert_true(sc.disk_alpha == 0.8); /* untouched */
  hd_scene_free(&sc);

  const char *make_run[] = {"run.stop_time=5", "log.collisions=none"};
  assert_int_equal(hd_scene_load_string(&sc, "[disks]\ncount = 3\n[system]\nbox = 9 9\n", "o.ini",
                                        make_run, 2, &e),
                   HD_OK);
  assert_true(sc.stop_time == 5);
  assert_int_equal(sc.log_collisions, HD_LOG_NONE);
  assert_non_null(strstr(sc.text, "[run]\n"));
  assert_non_null(strstr(sc.text, "[log]\ncollisions = none\n"));
  hd_scene_free(&sc);

  /* the same key set twice by --set is a duplicate */
  const char *twice[] = {"run.stop_time=5", "run.stop_time=6"};
  assert_int_equal(hd_scene_load_string(&sc, RUN, "o.ini", twice, 2, &e), HD_EINPUT);
  assert_has(e.msg, "--set run.stop_time=6:", "[run] stop_time", "duplicate", "run.stop_time=5");
}

/* ---- canonical text round trip -------------------------------------------------------------- */

#define SAME(f) assert_memory_equal(&a->f, &b->f, sizeof a->f)
static void assert_same_scene(const hd_scene *a, const hd_scene *b) {
  SAME(box_x);
  SAME(box_y);
  SAME(area_fraction);
  SAME(seed);
  SAME(n_dimers);
  SAME(dimer_d);
  SAME(dimer_a);
  SAME(dimer_m);
  SAME(dimer_alpha);
  SAME(n_disks);
  SAME(disk_sigma);
  SAME(disk_mass);
  SAME(disk_alpha);
  SAME(disk_alpha_dimer);
  SAME(walls);
  SAME(wall_alpha);
  SAME(temperature);
  SAME(placement);
  assert_string_equal(a->state_file, b->state_file);
  SAME(stop_time);
  SAME(stop_events);
  SAME(stop_cpd);
  SAME(verify);
  SAME(checkpoint_every);
  SAME(log_collisions);
  SAME(log_every);
  SAME(samples_every);
  SAME(n_velocities_at);
  SAME(velocities_in_time);
  assert_memory_equal(a->velocities_at, b->velocities_at,
                      (size_t)a->n_velocities_at * sizeof a->velocities_at[0]);
  assert_string_equal(a->text, b->text);
}

static void round_trip_one(const hd_scene *a) {
  hd_scene b;
  hd_error e;
  int rc = hd_scene_load_string(&b, a->text, "text", NULL, 0, &e);
  if (rc) print_error("%s\n--- text:\n%s", e.msg, a->text);
  assert_int_equal(rc, HD_OK);
  assert_same_scene(a, &b);
  hd_scene_free(&b);
}

static void text_round_trip(void **state) {
  (void)state;
  hd_scene a;
  hd_error e;
  assert_int_equal(hd_scene_load(&a, "tests/data/scenes/good.ini", NULL, 0, &e), HD_OK);
  round_trip_one(&a);
  hd_scene_free(&a);
  /* values whose decimal form is not exact, a derived box, overrides */
  const char *text = "[system]\narea_fraction = 0.1234567\nseed = 99\n[dimers]\ncount = 33\n"
                     "a = 0.3\nd = 0.7\nalpha = 0.1\n[run]\nstop_time = 0.3\n[log]\n"
                     "velocities_at = 0.1 0.2 0.30000000000000004\n";
  /* an override replacing the list is checked like the file's own line */
  const char *over[] = {
      "log.velocities_at=1e-7 0.1 0.2 0.30000000000000004 2.2250738585072014e-308",
      "init.temperature=0.7"};
  assert_int_equal(hd_scene_load_string(&a, text, "rt.ini", over, 1, &e), HD_EINPUT);
  assert_has(e.msg, "--set log.velocities_at=", "ascending", NULL, NULL);
  over[0] = "log.velocities_at=2.2250738585072014e-308 1e-7 0.1 0.2 0.30000000000000004";
  assert_int_equal(hd_scene_load_string(&a, text, "rt.ini", over, 2, &e), HD_OK);
  assert_true(a.temperature == 0.7 && a.n_velocities_at == 5);
  round_trip_one(&a);
  hd_scene_free(&a);
  /* every HD_MAX_VEL_AT values of 17 digits fit on one line */
  char big[HD_SCENE_MAX_LINE] = "log.velocities_at=";
  for (int i = 0; i < HD_MAX_VEL_AT; i++) {
    char v[40];
    snprintf(v, sizeof v, " %.17g", (i + 1) * 0.1 + 1e-3 / 3);
    strcat(big, v);
  }
  const char *bigover[] = {big};
  assert_int_equal(hd_scene_load_string(&a, "[run]\nstop_cpd = 10\n", "big.ini", bigover, 1, &e),
                   HD_OK);
  assert_int_equal(a.n_velocities_at, HD_MAX_VEL_AT);
  round_trip_one(&a);
  hd_scene_free(&a);
  /* snapshot times (velocities_at_time) keep their unit through the text */
  assert_int_equal(hd_scene_load_string(&a,
                                        "[rods]\ncount = 4\n[run]\nstop_time = 5\n[log]\n"
                                        "velocities_at_time = 0.1 5\n",
                                        "vt.ini", NULL, 0, &e),
                   HD_OK);
  assert_true(a.velocities_in_time == 1 && a.n_velocities_at == 2 && a.velocities_at[1] == 5);
  assert_non_null(strstr(a.text, "velocities_at_time = 0.1 5\n"));
  round_trip_one(&a);
  hd_scene_free(&a);
}

/* Random doubles (fixed seed) through the text: every one must come back bit for bit.  No
 * tolerance: the shortest-of-%.15g..%.17g form is exact by construction, and this checks it. */
static void text_round_trip_random(void **state) {
  (void)state;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 42);
  int n = getenv("HAFF_SANITIZE") && atoi(getenv("HAFF_SANITIZE")) ? 50 : 300;
  for (int i = 0; i < n; i++) {
    char o[4][80];
    snprintf(o[0], sizeof o[0], "dimers.alpha=%.17g", gsl_rng_uniform(r));
    snprintf(o[1], sizeof o[1], "dimers.a=%.17g", 2 * gsl_rng_uniform(r));
    snprintf(o[2], sizeof o[2], "system.area_fraction=%.17g", 0.01 + 0.4 * gsl_rng_uniform(r));
    snprintf(o[3], sizeof o[3], "run.stop_time=%.17g", exp(40 * (gsl_rng_uniform(r) - 0.5)));
    const char *over[] = {o[0], o[1], o[2], o[3], "dimers.count=50"};
    hd_scene a;
    hd_error e;
    assert_int_equal(hd_scene_load_string(&a, "", "rnd.ini", over, 5, &e), HD_OK);
    round_trip_one(&a);
    hd_scene_free(&a);
  }
  gsl_rng_free(r);
}

/* ---- state files ---------------------------------------------------------------------------- */

static void scene_with_state(void **state) {
  (void)state;
  hd_scene sc;
  hd_error e;
  /* tests/data/scenes/state.csv holds 2 dimers and 1 disk; counts come from it */
  assert_int_equal(hd_scene_load(&sc, "tests/data/scenes/state.ini", NULL, 0, &e), HD_OK);
  assert_int_equal(sc.placement, HD_PLACE_STATE);
  assert_int_equal(sc.n_dimers, 2);
  assert_int_equal(sc.n_disks, 1);
  assert_true(sc.dimer_alpha == 0.9 && sc.temperature == 0);
  assert_true(sc.state_file[0] == '/');
  const char *tail = "/tests/data/scenes/state.csv";
  assert_string_equal(sc.state_file + strlen(sc.state_file) - strlen(tail), tail);
  assert_non_null(strstr(sc.text, "[disks]\ncount = 1\n"));
  round_trip_one(&sc);
  hd_scene_free(&sc);
  /* a count that disagrees with the file */
  const char *over[] = {"dimers.count=3"};
  assert_int_equal(hd_scene_load(&sc, "tests/data/scenes/state.ini", over, 1, &e), HD_EINPUT);
  assert_has(e.msg, "--set dimers.count=3:", "[dimers] count", "2 dimer rows", NULL);
  /* a bad CSV reached through a scene: the CSV's own message */
  write_file(tmp_path("bad.csv"), "kind,x,y,phi,vx,vy,omega\ndisk,1,2,0,0,0\n");
  write_file(tmp_path("s.ini"), "[system]\nbox = 9 9\n[init]\nstate = bad.csv\n" RUN);
  assert_int_equal(hd_scene_load(&sc, tmp_path("s.ini"), NULL, 0, &e), HD_EINPUT);
  assert_has(e.msg, "bad.csv:2:", "7 columns", NULL, NULL);
}

static void csv_good(void **state) {
  (void)state;
  const char *p = tmp_path("good.csv");
  write_file(p, "kind,x,y,phi,vx,vy,omega  \r\n"
                "dimer, 1.5 ,2,0.25,-1,1e-3,3\r\n"
                "disk,4,5,9,6,7,8\r\n"
                "\r\n");
  hd_state_row *rows;
  long n;
  hd_error e;
  assert_int_equal(hd_state_csv_read(p, &rows, &n, &e), HD_OK);
  assert_int_equal(n, 2);
  assert_int_equal(rows[0].kind, HD_KIND_DIMER);
  assert_true(rows[0].x == 1.5 && rows[0].y == 2 && rows[0].phi == 0.25);
  assert_true(rows[0].vx == -1 && rows[0].vy == 1e-3 && rows[0].omega == 3);
  assert_int_equal(rows[0].line, 2);
  assert_int_equal(rows[1].kind, HD_KIND_DISK);
  assert_true(rows[1].x == 4 && rows[1].y == 5 && rows[1].vx == 6 && rows[1].vy == 7);
  assert_true(rows[1].phi == 0 && rows[1].omega == 0); /* ignored for disks */
  assert_int_equal(rows[1].line, 3);
  free(rows);
  /* with a UTF-8 byte order mark (refused before as "missing header", the mark unprintable) */
  write_file(p, "\xEF\xBB\xBFkind,x,y,phi,vx,vy,omega\ndisk,4,5,0,6,7,0\n");
  assert_int_equal(hd_state_csv_read(p, &rows, &n, &e), HD_OK);
  assert_int_equal(n, 1);
  free(rows);
}

static void csv_bad(void **state) {
  (void)state;
  static const struct {
    const char *text, *at, *a, *b;
  } cases[] = {
      {"", ":1:", "empty", NULL},
      {"dimer,1,2,0,0,0,0\n", ":1:", "header", NULL},
      {"kind,x,y,phi,vx,vy\n", ":1:", "header", NULL},
      {"kind,x,y,phi,vx,vy,omega\n", ":1:", "no bodies", NULL},
      {"kind,x,y,phi,vx,vy,omega\ndisk,1,2,0,0,0,0\ndisk,1,2,0,0,0\n", ":3:", "7 columns",
       "found 6"},
      {"kind,x,y,phi,vx,vy,omega\ndisk,1,2,0,0,0,0,0\n", ":2:", "7 columns", "found 8"},
      {"kind,x,y,phi,vx,vy,omega\nrod,1,2,0,0,0,0\n", ":2:", "column 1 (kind)", "rod"},
      {"kind,x,y,phi,vx,vy,omega\ndisk,1,2,0,nan,0,0\n", ":2:", "column 5 (vx)", "finite"},
      {"kind,x,y,phi,vx,vy,omega\ndisk,1,1.5x,0,0,0,0\n", ":2:", "column 3 (y)", "not a number"},
      {"kind,x,y,phi,vx,vy,omega\ndimer,1,1,0,0,0,\n", ":2:", "column 7 (omega)", "missing"},
      {"kind,x,y,phi,vx,vy,omega\ndimer,1,1,inf,0,0,0\n", ":2:", "column 4 (phi)", "finite"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    const char *p = tmp_path("bad.csv");
    write_file(p, cases[i].text);
    hd_state_row *rows = (hd_state_row *)1;
    long n = -1;
    hd_error e;
    assert_int_equal(hd_state_csv_read(p, &rows, &n, &e), HD_EINPUT);
    assert_null(rows);
    assert_int_equal(n, 0);
    char at[600];
    snprintf(at, sizeof at, "%s%s", p, cases[i].at);
    assert_has(e.msg, at, cases[i].a, cases[i].b, NULL);
  }
  hd_state_row *rows;
  long n;
  hd_error e;
  assert_int_equal(hd_state_csv_read(tmp_path("none.csv"), &rows, &n, &e), HD_EIO);
  assert_has(e.msg, "none.csv", "cannot read", NULL, NULL);
}

/* ---- the example scenes --------------------------------------------------------------------- */

static void example_scenes(void **state) {
  (void)state;
  hd_scene sc;
  hd_error e;
  assert_int_equal(hd_scene_load(&sc, "scenes/disks-dilute.ini", NULL, 0, &e), HD_OK);
  assert_int_equal(sc.n_disks, 1000);
  assert_true(sc.disk_alpha == 0.9 && sc.area_fraction == 0.05 && sc.stop_cpd == 200);
  assert_true(sc.samples_every == 0.5);
  hd_scene_free(&sc);
  assert_int_equal(hd_scene_load(&sc, "scenes/disks-elastic.ini", NULL, 0, &e), HD_OK);
  assert_true(sc.disk_alpha == 1 && sc.area_fraction == 0.2 && sc.stop_events == 1e6);
  assert_int_equal(sc.log_collisions, HD_LOG_NONE);
  hd_scene_free(&sc);
}

static int setup(void **state) {
  (void)state;
  return mkdtemp(tmpdir) ? 0 : -1;
}

static int teardown(void **state) {
  (void)state;
  const char *names[] = {"good.csv", "bad.csv", "s.ini", "d.ini", "x ;y/st.csv", "x ;y/s.ini"};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) unlink(tmp_path(names[i]));
  rmdir(tmp_path("adir"));
  rmdir(tmp_path("x ;y"));
  return rmdir(tmpdir);
}

/* ---- [rods] ------------------------------------------------------------------------------- */

/* A rods-only scene needs no box; values and defaults as written; text round trip. */
static void rods_scene(void **state) {
  (void)state;
  hd_scene sc, sc2;
  hd_error e;
  const char *txt = "[system]\nseed = 7\n[rods]\ncount = 50\ngamma = 0.5\nnmod = 20\n"
                    "model = constant\neps = 0.3\ndamping = 0.01\ntc = 0.001\ntable = no\n"
                    "eps_step = 0.0025\n[run]\nstop_time = 10\n";
  assert_int_equal(hd_scene_load_string(&sc, txt, "r.ini", NULL, 0, &e), HD_OK);
  assert_int_equal(sc.n_rods, 50);
  assert_true(sc.rod_gamma == 0.5 && sc.rod_nmod == 20 && sc.rod_model == 1);
  assert_true(sc.rod_eps == 0.3 && sc.rod_damping == 0.01 && sc.rod_tc == 0.001);
  assert_true(sc.rod_temperature == 1 && sc.rod_table == 0 && sc.rod_unequal == 0);
  assert_true(sc.rod_eps_step == 0.0025);
  assert_true(sc.n_dimers == 0 && sc.n_disks == 0);
  assert_int_equal(hd_scene_load_string(&sc2, sc.text, "canon", NULL, 0, &e), HD_OK);
  assert_string_equal(sc.text, sc2.text);
  hd_scene_free(&sc);
  hd_scene_free(&sc2);
  /* defaults: gamma 0.8, nmod 1000, stochastic, eps = gamma */
  assert_int_equal(hd_scene_load_string(&sc, "[rods]\ncount = 4\n[run]\nstop_events = 5\n", "d.ini",
                                        NULL, 0, &e),
                   HD_OK);
  assert_true(sc.rod_gamma == 0.8 && sc.rod_nmod == 1000 && sc.rod_model == 0);
  assert_true(sc.rod_eps == 0.8);
  hd_scene_free(&sc);
  const char *over[] = {"rods.baths=unequal", "rods.count=8"};
  assert_int_equal(hd_scene_load_string(&sc, "[rods]\ncount = 4\n[run]\nstop_events = 5\n", "d.ini",
                                        over, 2, &e),
                   HD_OK);
  assert_true(sc.rod_unequal == 1 && sc.n_rods == 8);
  hd_scene_free(&sc);
}

/* Each bad [rods] scene fails with file:line, the key and why. */
static void rods_bad(void **state) {
  (void)state;
  static const struct {
    const char *text, *a, *b, *c;
  } cases[] = {
      {"[rods]\ncount = 5\n[run]\nstop_time = 1\n", "r.ini:2", "[rods] count = 5", "even"},
      {"[rods]\ncount = 0\n[run]\nstop_time = 1\n", "r.ini:2", "[rods] count = 0", "["},
      {"[rods]\ncount = 4\ngamma = 1.5\n[run]\nstop_time = 1\n", "r.ini:3", "gamma = 1.5",
       "(0, 1]"},
      {"[rods]\ncount = 4\ngamma = 0\n[run]\nstop_time = 1\n", "r.ini:3", "gamma = 0", "(0, 1]"},
      {"[rods]\ncount = 4\nmodel = fixed\n[run]\nstop_time = 1\n", "r.ini:3", "model = fixed",
       "stochastic or constant"},
      {"[rods]\ncount = 4\neps = 0.5\n[run]\nstop_time = 1\n", "r.ini:3", "eps = 0.5",
       "model = constant"},
      {"[rods]\ncount = 4\nnmod = 0\n[run]\nstop_time = 1\n", "r.ini:3", "nmod = 0", "["},
      {"[rods]\ncount = 4\ndamping = -1\n[run]\nstop_time = 1\n", "r.ini:3", "damping = -1",
       ">= 0"},
      {"[rods]\ncount = 4\ntable = maybe\n[run]\nstop_time = 1\n", "r.ini:3", "table = maybe",
       "yes/no"},
      {"[rods]\ncount = 4\nbaths = hot\n[run]\nstop_time = 1\n", "r.ini:3", "baths = hot",
       "mean or unequal"},
      {"[rods]\ncount = 4\ntable = yes\nbaths = unequal\n[run]\nstop_time = 1\n", "r.ini:3",
       "table = yes", "equal"},
      {"[rods]\ncount = 4\nlength = 2\n[run]\nstop_time = 1\n", "r.ini:3", "[rods] length",
       "unknown key"},
      {"[rods]\ngamma = 0.5\n[run]\nstop_time = 1\n", "r.ini:1", "[rods] count", "missing"},
      {"[rods]\ncount = 4\n[disks]\ncount = 3\n[run]\nstop_time = 1\n", "r.ini:3", "[disks]",
       "cannot be combined"},
      {"[system]\nbox = 5 5\n[rods]\ncount = 4\n[run]\nstop_time = 1\n", "r.ini:2", "box = 5 5",
       "ring length"},
      {"[rods]\ncount = 4\n", "r.ini", "no stop condition", NULL},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    hd_scene sc;
    hd_error e;
    assert_int_equal(hd_scene_load_string(&sc, cases[i].text, "r.ini", NULL, 0, &e), HD_EINPUT);
    assert_has(e.msg, cases[i].a, cases[i].b, cases[i].c, NULL);
    assert_null(sc.text);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(good_scene_values),
      cmocka_unit_test(defaults_and_absent_sections),
      cmocka_unit_test(dimer_area_exact),
      cmocka_unit_test(area_fraction_box),
      cmocka_unit_test(bad_scenes),
      cmocka_unit_test(override_message_exact),
      cmocka_unit_test(override_mends_a_bad_line),
      cmocka_unit_test(long_line),
      cmocka_unit_test(line_at_the_limit),
      cmocka_unit_test(blank_prefixed_sections),
      cmocka_unit_test(directories_and_unstorable_paths),
      cmocka_unit_test(missing_files),
      cmocka_unit_test(overrides_apply),
      cmocka_unit_test(text_round_trip),
      cmocka_unit_test(text_round_trip_random),
      cmocka_unit_test(scene_with_state),
      cmocka_unit_test(csv_good),
      cmocka_unit_test(csv_bad),
      cmocka_unit_test(example_scenes),
      cmocka_unit_test(rods_scene),
      cmocka_unit_test(rods_bad),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
