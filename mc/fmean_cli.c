/* `haff mc fmean`: <f> and D_e = D/<f> for an elongation a/d (see fmean.h, docs/mc-fmean.md). */
#include <getopt.h>
#include <gsl/gsl_math.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmean.h"

int hd_mc_fmean_main(int argc, char **argv);

static void fmean_usage(FILE *out) {
  fprintf(out,
          "usage: haff mc fmean --a A [--d D] [--model heuristic|exclusion|collision|all]\n"
          "                     [--samples N | --seconds S] [--seed K] [--dim DIM]\n"
          "       haff mc fmean --scan A0:A1:STEP [same options but --a]\n"
          "       haff mc fmean --convergence [--a A [--d D]] [--seconds S] [--samples NMAX]\n"
          "                     [--seed K]\n"
          "       haff mc fmean --fig4-data --a A [--d D]\n"
          "       haff mc fmean --disks 'X Y D M; X Y D M; ...' [--model M] [--samples N |\n"
          "                     --seconds S] [--seed K] [--dim DIM]\n"
          "\n"
          "Mean orientation factor <f> of dimer-dimer collisions (Costantini et al. 2005, eq. 36)\n"
          "and the paper's effective dimension D_e = DIM/<f>, for elongation a/d = A/D.\n"
          "  --a A          bond length a > 0 (in the units of --d; required unless --scan)\n"
          "  --d D          disk diameter > 0 (default 1)\n"
          "  --model M      heuristic (paper: independent uniform angles), exclusion (uniform\n"
          "                 non-overlapping contacts), collision (contacts weighted by their\n"
          "                 entry rate in an elastic gas at equipartition), all (default)\n"
          "  --samples N    accepted samples per row, >= 2 (default 1e6); with --convergence:\n"
          "                 the largest n of the sequence, >= 1e4 (default: what --seconds\n"
          "                 allows)\n"
          "  --seconds S    sample in batches for S seconds per row instead of N samples;\n"
          "                 with --convergence: the total time budget (default 10)\n"
          "  --seed K       gsl_rng_mt19937 seed (default 1)\n"
          "  --dim DIM      D in D_e = D/<f> (default 2)\n"
          "  --scan A0:A1:STEP  one row per a = A0, A0+STEP, ..., <= A1, per model (A0 > 0,\n"
          "                 A1 >= A0, STEP > 0)\n"
          "  --convergence  heuristic MC against quadrature at n = 1e3, 1e4, ...; columns\n"
          "                 n f_mc f_stderr abs_err_vs_quadrature seconds reps rms_err, and a\n"
          "                 '# slope' line: the fitted d log(err) / d log(n) (expect -1/2)\n"
          "  --fig4-data    gnuplot data blocks of Fig. 4 (two dimers at contact, allowed range)\n"
          "  --disks SPEC   two bodies of any rigid shape instead of dimers: 1 to 8 disks, each\n"
          "                 'x y d m' (centre in the body frame, diameter, mass), separated by\n"
          "                 ';'; f = mu_eff / m_ref as the engine logs it (docs/contract.md);\n"
          "                 a_over_d is then nan\n"
          "\n"
          "Output (TSV, one header row): model a_over_d f_mean f_stderr D_e D_e_stderr samples\n"
          "seconds f_quad f_quad_abserr acceptance fvn2 D_e_energy D_e_energy_stderr\n"
          "(f_quad: heuristic by quadrature; fvn2 = <f v_n^2>_coll in T/m and D_e_energy =\n"
          "6/fvn2 the energy-balance dimension, collision model only; nan where not defined).\n");
}

/* Parses a finite double filling the whole string. */
static int parse_double(const char *s, double *x) {
  char *end;
  if (!s || !*s) return 0;
  *x = strtod(s, &end);
  return *end == '\0' && isfinite(*x);
}

/* Parses a positive integer count, allowing forms like 1e8. */
static int parse_count(const char *s, unsigned long *n) {
  double x;
  if (!parse_double(s, &x) || x < 1.0 || x > 1e15 || x != floor(x)) return 0;
  *n = (unsigned long)x;
  return 1;
}

static void print_header(void) {
  printf("model\ta_over_d\tf_mean\tf_stderr\tD_e\tD_e_stderr\tsamples\tseconds\tf_quad\t"
         "f_quad_abserr\tacceptance\tfvn2\tD_e_energy\tD_e_energy_stderr\n");
}

static void print_row(const hd_fmean_opts *o, const hd_fmean_result *r) {
  printf("%s\t%.10g\t%.10g\t%.4g\t%.10g\t%.4g\t%lu\t%.3f\t%.12g\t%.3g\t%.6g\t%.8g\t%.8g\t%.4g\n",
         hd_fmean_model_name(o->model), o->a_over_d, r->f_mean, r->f_stderr, r->d_e, r->d_e_stderr,
         r->samples, r->seconds, r->f_quad, r->f_quad_abserr,
         r->tried ? (double)r->samples / (double)r->tried : NAN, r->fvn2, r->d_e_energy,
         r->d_e_energy_stderr);
}

/* Fig. 4 data in units of d: index 0 dimer A, 1 dimer B (example contact), 2 limiting
 * positions of B's contacting disk, 3 the allowed wedge, 4 bonds and normal as vectors. */
static void print_fig4(double a) {
  double tm = hd_fmean_theta_max(a);
  double th = 0.55 * tm; /* example contact angle of A */
  double nx = cos(th), ny = sin(th);
  /* B tilted by theta_B = -0.5 rad if that overlaps nothing, else head-on (theta_B = 0). */
  double tb = -0.5, phib = th + M_PI - tb;
  double b2x = nx - a * cos(phib), b2y = ny - a * sin(phib);
  if (hypot(b2x, b2y) < 1.0 || hypot(b2x + a, b2y) < 1.0) {
    tb = 0.0;
    b2x = (1.0 + a) * nx, b2y = (1.0 + a) * ny;
  }
  printf("# Fig. 4 data, lengths in units of d: a/d = %.6g, theta_max = %.10g rad = %.6g deg\n", a,
         tm, tm * 180.0 / M_PI);
  printf("# index 0: dimer A disks (x y r): contacting disk A1, partner A2\n");
  printf("0\t0\t0.5\n%.10g\t0\t0.5\n\n\n", -a);
  printf("# index 1: dimer B disks (B1, B2) at theta_A = %.6g rad, theta_B = %.6g rad\n", th, tb);
  printf("%.10g\t%.10g\t0.5\n%.10g\t%.10g\t0.5\n\n\n", nx, ny, b2x, b2y);
  printf("# index 2: B's contacting disk at the limits theta = +-theta_max\n");
  printf("%.10g\t%.10g\t0.5\n%.10g\t%.10g\t0.5\n\n\n", cos(tm), sin(tm), cos(tm), -sin(tm));
  printf("# index 3: allowed wedge of the contact normal (x y r start_deg end_deg)\n");
  printf("0\t0\t1.6\t%.10g\t%.10g\n\n\n", -tm * 180.0 / M_PI, tm * 180.0 / M_PI);
  printf("# index 4: vectors (x y dx dy): A's bond A2->A1, B's bond B2->B1, normal A1->B1\n");
  printf("%.10g\t0\t%.10g\t0\n", -a, a);
  printf("%.10g\t%.10g\t%.10g\t%.10g\n", b2x, b2y, nx - b2x, ny - b2y);
  printf("0\t0\t%.10g\t%.10g\n", nx, ny);
}

int hd_mc_fmean_main(int argc, char **argv) {
  static const struct option longopts[] = {
      {"a", required_argument, NULL, 'a'},       {"d", required_argument, NULL, 'd'},
      {"model", required_argument, NULL, 'm'},   {"samples", required_argument, NULL, 'n'},
      {"seconds", required_argument, NULL, 's'}, {"seed", required_argument, NULL, 'k'},
      {"scan", required_argument, NULL, 'S'},    {"convergence", no_argument, NULL, 'c'},
      {"fig4-data", no_argument, NULL, 'f'},     {"dim", required_argument, NULL, 'D'},
      {"disks", required_argument, NULL, 'B'},   {"help", no_argument, NULL, 'h'},
      {NULL, 0, NULL, 0}};
  double a = NAN, d = 1.0, seconds = 0.0, dim = 2.0, scan[3] = {0, 0, 0};
  unsigned long samples = 0, seed = 1;
  int have_scan = 0, conv = 0, fig4 = 0, all = 1, have_shape = 0;
  hd_shape shape;
  hd_fmean_model model = HD_FMEAN_HEURISTIC;
  optind = 0;
  opterr = 0;
  int c, li = -1;
  unsigned given = 0; /* bit k: option longopts[k] was given */
  while ((c = getopt_long(argc, argv, "h", longopts, &li)) != -1) {
    for (unsigned k = 0; longopts[k].name; k++)
      if (longopts[k].val == c) given |= 1u << k;
    switch (c) {
    case 'a':
      if (!parse_double(optarg, &a) || !(a > 0.0)) goto bad_value;
      break;
    case 'd':
      if (!parse_double(optarg, &d) || !(d > 0.0)) goto bad_value;
      break;
    case 'D':
      if (!parse_double(optarg, &dim) || !(dim > 0.0)) goto bad_value;
      break;
    case 'm':
      if (!strcmp(optarg, "all")) {
        all = 1;
      } else if (hd_fmean_model_parse(optarg, &model) == HD_OK) {
        all = 0;
      } else {
        goto bad_value;
      }
      break;
    case 'n':
      if (!parse_count(optarg, &samples) || samples < 2) goto bad_value;
      break;
    case 's':
      if (!parse_double(optarg, &seconds) || !(seconds > 0.0)) goto bad_value;
      break;
    case 'k': {
      double x;
      if (!parse_double(optarg, &x) || x < 0.0 || x > 4294967295.0 || x != floor(x)) goto bad_value;
      seed = (unsigned long)x;
      break;
    }
    case 'S':
      if (sscanf(optarg, "%lf:%lf:%lf", &scan[0], &scan[1], &scan[2]) != 3 || !(scan[0] > 0.0) ||
          !(scan[1] >= scan[0]) || !(scan[2] > 0.0) || !isfinite(scan[1]))
        goto bad_value;
      have_scan = 1;
      break;
    case 'c':
      conv = 1;
      break;
    case 'B': { /* x y d m; x y d m; ... */
      double x[HD_MAX_BODY_DISKS], y[HD_MAX_BODY_DISKS], dd[HD_MAX_BODY_DISKS],
          mm[HD_MAX_BODY_DISKS];
      int k = 0, used = 0;
      const char *p = optarg;
      while (*p && k < HD_MAX_BODY_DISKS &&
             sscanf(p, " %lf %lf %lf %lf %n", &x[k], &y[k], &dd[k], &mm[k], &used) == 4) {
        k++;
        p += used;
        if (*p == ';') p++;
      }
      while (*p == ' ') p++;
      if (*p || hd_shape_cluster(&shape, k, x, y, dd, mm, 0)) goto bad_value;
      have_shape = 1;
      break;
    }
    case 'f':
      fig4 = 1;
      break;
    case 'h':
      fmean_usage(stdout);
      return 0;
    case '?':
    default: {
      char buf[8];
      fprintf(stderr, "haff mc fmean: unknown option or missing value in '%s' (see --help)\n",
              hd_opt_culprit(argv, longopts, buf, sizeof buf));
    }
      return 2;
    }
  }
  if (optind < argc) {
    fprintf(stderr, "haff mc fmean: unexpected argument '%s'\n", argv[optind]);
    return 2;
  }
  if (samples && seconds > 0.0 && !conv) {
    fprintf(stderr, "haff mc fmean: give --samples or --seconds, not both\n");
    return 2;
  }
  /* each mode takes only the options it reads: one that would be ignored is an error */
  static const struct {
    int mode;            /* the mode's option ('c', 'f', 'S') */
    const char *refused; /* options it does not read */
  } modes[] = {{'c', "m S f D"}, {'f', "m n s k S c D"}, {'S', "a f c"}, {'B', "a d S c f"}};
  for (size_t q = 0; q < sizeof modes / sizeof modes[0]; q++) {
    unsigned mk = 0;
    for (unsigned k = 0; longopts[k].name; k++)
      if (longopts[k].val == modes[q].mode) mk = k;
    if (!(given & (1u << mk))) continue;
    for (unsigned k = 0; longopts[k].name; k++)
      if ((given & (1u << k)) && k != mk && strchr(modes[q].refused, longopts[k].val)) {
        fprintf(stderr, "haff mc fmean: --%s does not apply with --%s (see --help)\n",
                longopts[k].name, longopts[mk].name);
        return 2;
      }
  }
  if (conv && isnan(a) && (given & 2u)) { /* --d alone: a/d would silently be 1 */
    fprintf(stderr, "haff mc fmean: --convergence with --d needs --a\n");
    return 2;
  }
  if (conv && samples > 0 && samples < 10000) { /* it printed no row and a slope of nan */
    fprintf(stderr,
            "haff mc fmean: --convergence --samples %lu: the sequence n = 1e3, 1e4, ... "
            "needs n >= 1e4 for the two rows of a slope\n",
            (unsigned long)samples);
    return 2;
  }
  hd_error err;
  if (conv) {
    double ad = isnan(a) ? 1.0 : a / d;
    hd_fmean_conv_row rows[32];
    size_t nr;
    double slope, slope_err;
    int st = hd_fmean_convergence(ad, seed, seconds > 0.0 ? seconds : 10.0, samples, rows, 32, &nr,
                                  &slope, &slope_err, &err);
    if (st) {
      fprintf(stderr, "haff mc fmean: %s\n", err.msg);
      return hd_exit_code(st);
    }
    if (nr < 2) {
      fprintf(stderr,
              "haff mc fmean: --convergence: %zu row%s in %g s, a slope needs 2 (more "
              "--seconds)\n",
              nr, nr == 1 ? "" : "s", seconds > 0.0 ? seconds : 10.0);
      return 1;
    }
    double fq, fq_err;
    hd_fmean_quadrature(ad, &fq, &fq_err);
    printf("# heuristic model, a/d = %.10g, quadrature <f> = %.15g (abserr %.2g)\n", ad, fq,
           fq_err);
    printf("n\tf_mc\tf_stderr\tabs_err_vs_quadrature\tseconds\treps\trms_err\n");
    for (size_t i = 0; i < nr; i++)
      printf("%lu\t%.12g\t%.4g\t%.4g\t%.4f\t%lu\t%.4g\n", rows[i].n, rows[i].f_mc, rows[i].f_stderr,
             rows[i].abs_err, rows[i].seconds, rows[i].reps, rows[i].rms_err);
    printf("# slope of log(rms_err) vs log(n) (gsl_fit_wlinear): %.4f +- %.4f (1/sqrt(N) law: "
           "-0.5)\n",
           slope, slope_err);
    return 0;
  }
  if (!have_scan && !have_shape && isnan(a)) {
    fprintf(stderr, "haff mc fmean: --a A is required (or --scan A0:A1:STEP)\n");
    return 2;
  }
  if (fig4) {
    print_fig4(a / d);
    return 0;
  }
  hd_fmean_opts o;
  hd_fmean_opts_default(&o);
  o.dim = dim;
  o.seed = seed;
  if (seconds > 0.0) {
    o.samples = 0;
    o.seconds = seconds;
  } else if (samples) {
    o.samples = samples;
  }
  long n_a = 1;
  if (have_scan) {
    double cnt = floor((scan[1] - scan[0]) / scan[2] + 1e-9) + 1.0;
    if (cnt > 100000.0) {
      fprintf(stderr, "haff mc fmean: --scan gives more than 100000 rows\n");
      return 2;
    }
    n_a = (long)cnt;
  }
  print_header();
  for (long i = 0; i < n_a; i++) {
    double ai = have_scan ? scan[0] + (double)i * scan[2] : a;
    for (int m = HD_FMEAN_HEURISTIC; m <= HD_FMEAN_COLLISION; m++) {
      if (!all && m != (int)model) continue;
      hd_fmean_result r;
      o.model = (hd_fmean_model)m;
      o.a_over_d = have_shape ? NAN : ai / d;
      o.shape = have_shape ? &shape : NULL;
      int st = hd_fmean_run(&o, &r, &err);
      if (st) {
        fprintf(stderr, "haff mc fmean: %s\n", err.msg);
        return hd_exit_code(st);
      }
      print_row(&o, &r);
      fflush(stdout);
    }
  }
  return 0;

bad_value:
  fprintf(stderr, "haff mc fmean: bad value '%s' for --%s (see --help)\n", optarg,
          li >= 0 ? longopts[li].name : "?");
  return 2;
}
