/* `haff mc fmean`: <f> and D_e = D/<f> for an elongation a/d (see fmean.h, docs/mc-fmean.md). */
#include <gsl/gsl_math.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmean.h"
#include "haff.h"
#include "hd_body.h"
#include "hd_opt.h"
#include "hd_scene_species.h"

/* The options of `haff mc fmean`. */
typedef struct fopts {
  double a, d, dim, seconds; /* --a (NAN: not given), --d, --dim, --seconds (0: not given) */
  long samples, seed;        /* --samples (0: not given), --seed */
  int model;                 /* --model: an hd_fmean_model, or 3 for all */
  int conv, fig4;            /* --convergence, --fig4-data */
  const char *scan;          /* --scan A0:A1:STEP, NULL when not given */
  const char *disks;         /* --disks 'x y d m; ...', NULL when not given */
} fopts;

/* In the order of the mode checks' messages (hd_opt_refuse walks the table). */
static const hd_optdef fmean_opts[] = {
    HD_OPT_DBL("a", 0, fopts, a, 0, INFINITY, HD_OPTF_GT | HD_OPTF_FINITE, "A",
               "bond length a > 0 (in the units of --d; required unless --scan)"),
    HD_OPT_DBL("d", 0, fopts, d, 0, INFINITY, HD_OPTF_GT | HD_OPTF_FINITE, "D",
               "disk diameter > 0 (default 1)"),
    HD_OPT_ENUM("model", 0, fopts, model, "heuristic|exclusion|collision|all", "M",
                "heuristic (paper: independent uniform angles), exclusion (uniform\n"
                "non-overlapping contacts), collision (contacts weighted by their\n"
                "entry rate in an elastic gas at equipartition), all (default)"),
    HD_OPT_INT("samples", 0, fopts, samples, 2, 1000000000000000LL, HD_OPTF_EXP, "N",
               "accepted samples per row, >= 2 (default 1e6); with --convergence:\n"
               "the largest n of the sequence, >= 1e4 (default: what --seconds\n"
               "allows)"),
    HD_OPT_DBL("seconds", 0, fopts, seconds, 0, INFINITY, HD_OPTF_GT | HD_OPTF_FINITE, "S",
               "sample in batches for S seconds per row instead of N samples;\n"
               "with --convergence: the total time budget (default 10)"),
    HD_OPT_INT("seed", 0, fopts, seed, 0, 4294967295LL, HD_OPTF_EXP, "K",
               "gsl_rng_mt19937 seed (default 1)"),
    HD_OPT_STR("scan", 0, fopts, scan, "A0:A1:STEP",
               "one row per a = A0, A0+STEP, ..., <= A1, per model (A0 > 0,\n"
               "A1 >= A0, STEP > 0)"),
    HD_OPT_FLAG("convergence", 0, fopts, conv,
                "heuristic MC against quadrature at n = 1e3, 1e4, ...; columns\n"
                "n f_mc f_stderr abs_err_vs_quadrature seconds reps rms_err, and a\n"
                "'# slope' line: the fitted d log(err) / d log(n) (expect -1/2)"),
    HD_OPT_FLAG("fig4-data", 0, fopts, fig4,
                "gnuplot data blocks of Fig. 4 (two dimers at contact, allowed range)"),
    HD_OPT_DBL("dim", 0, fopts, dim, 0, INFINITY, HD_OPTF_GT | HD_OPTF_FINITE, "DIM",
               "D in D_e = D/<f> (default 2)"),
    HD_OPT_STR("disks", 0, fopts, disks, "SPEC",
               "two bodies of any rigid shape instead of dimers: 1 to 8 disks, each\n"
               "'x y d m' (centre in the body frame, diameter, mass), separated by\n"
               "';', touching or overlapping (one body); f = mu_eff / m_ref as the\n"
               "engine logs it (docs/contract.md); a_over_d is then nan"),
    {0}};

const hd_optspec hd_cmd_mc_fmean_spec = {
    HD_OPT_SPEC("mc fmean", fmean_opts, 0, 0, 0, NULL),
    .head = "usage: haff mc fmean --a A [--d D] [--model heuristic|exclusion|collision|all]\n"
            "                     [--samples N | --seconds S] [--seed K] [--dim DIM]\n"
            "       haff mc fmean --scan A0:A1:STEP [same options but --a]\n"
            "       haff mc fmean --convergence [--a A [--d D]] [--seconds S] [--samples NMAX]\n"
            "                     [--seed K]\n"
            "       haff mc fmean --fig4-data --a A [--d D]\n"
            "       haff mc fmean --disks 'X Y D M; X Y D M; ...' [--model M] [--samples N |\n"
            "                     --seconds S] [--seed K] [--dim DIM]\n"
            "\n"
            "Mean orientation factor <f> of dimer-dimer collisions (Costantini et al. 2005, eq. "
            "36)\n"
            "and the paper's effective dimension D_e = DIM/<f>, for elongation a/d = A/D.\n",
    .tail = "\n"
            "Output (TSV, one header row): model a_over_d f_mean f_stderr D_e D_e_stderr samples\n"
            "seconds f_quad f_quad_abserr acceptance fvn2 D_e_energy D_e_energy_stderr\n"
            "(f_quad: heuristic by quadrature; fvn2 = <f v_n^2>_coll in T/m and D_e_energy =\n"
            "6/fvn2 the energy-balance dimension, collision model only; nan where not defined).\n"};

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

/* The options the mode does not read, each refused (an ignored option is an error), and the
 * pairs that need each other.  Returns 0 or 2 after one line. */
static int fmean_check(const hd_optres *res, const fopts *o) {
  if (o->samples && o->seconds > 0.0 && !o->conv) {
    fprintf(stderr, "haff mc fmean: give --samples or --seconds, not both\n");
    return 2;
  }
  if (hd_opt_refuse(&hd_cmd_mc_fmean_spec, res, "convergence", "model scan fig4-data dim",
                    "with --convergence") ||
      hd_opt_refuse(&hd_cmd_mc_fmean_spec, res, "fig4-data",
                    "model samples seconds seed scan convergence dim", "with --fig4-data") ||
      hd_opt_refuse(&hd_cmd_mc_fmean_spec, res, "scan", "a fig4-data convergence", "with --scan") ||
      hd_opt_refuse(&hd_cmd_mc_fmean_spec, res, "disks", "a d scan convergence fig4-data",
                    "with --disks"))
    return 2;
  if (o->conv && isnan(o->a) && res->given[hd_opt_index(&hd_cmd_mc_fmean_spec, "d")]) {
    /* --d alone: a/d would silently be 1 */
    fprintf(stderr, "haff mc fmean: --convergence with --d needs --a\n");
    return 2;
  }
  if (o->conv && o->samples > 0 && o->samples < 10000) { /* it printed no row, a slope of nan */
    fprintf(stderr,
            "haff mc fmean: --convergence --samples %lu: the sequence n = 1e3, 1e4, ... "
            "needs n >= 1e4 for the two rows of a slope\n",
            (unsigned long)o->samples);
    return 2;
  }
  return 0;
}

/* --convergence: the heuristic MC against quadrature; the exit code. */
static int fmean_convergence(const fopts *o) {
  hd_error err;
  double ad = isnan(o->a) ? 1.0 : o->a / o->d, seconds = o->seconds;
  unsigned long seed = (unsigned long)o->seed, samples = (unsigned long)o->samples;
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
  printf("# heuristic model, a/d = %.10g, quadrature <f> = %.15g (abserr %.2g)\n", ad, fq, fq_err);
  printf("n\tf_mc\tf_stderr\tabs_err_vs_quadrature\tseconds\treps\trms_err\n");
  for (size_t i = 0; i < nr; i++)
    printf("%lu\t%.12g\t%.4g\t%.4g\t%.4f\t%lu\t%.4g\n", rows[i].n, rows[i].f_mc, rows[i].f_stderr,
           rows[i].abs_err, rows[i].seconds, rows[i].reps, rows[i].rms_err);
  printf("# slope of log(rms_err) vs log(n) (gsl_fit_wlinear): %.4f +- %.4f (1/sqrt(N) law: "
         "-0.5)\n",
         slope, slope_err);
  return 0;
}

int hd_mc_parse_disks(const char *cmd, const char *spec, hd_shape *shape) {
  double x[HD_MAX_BODY_DISKS], y[HD_MAX_BODY_DISKS], dd[HD_MAX_BODY_DISKS], mm[HD_MAX_BODY_DISKS];
  int k = 0, used = 0;
  const char *p = spec;
  while (*p && k < HD_MAX_BODY_DISKS &&
         sscanf(p, " %lf %lf %lf %lf %n", &x[k], &y[k], &dd[k], &mm[k], &used) == 4) {
    k++;
    p += used;
    if (*p == ';') p++;
  }
  while (*p == ' ') p++;
  if (*p || hd_shape_cluster(shape, k, x, y, dd, mm, 0)) {
    fprintf(stderr,
            "haff %s: --disks '%s': expected 1 to %d disks 'x y d m' separated by ';' "
            "(d, m > 0)\n",
            cmd, spec, HD_MAX_BODY_DISKS);
    return 2;
  }
  int b = hd_scene_disks_unconnected(k, x, y, dd); /* the rule of a scene's [species] disks */
  if (b >= 0) {
    fprintf(stderr,
            "haff %s: --disks '%s': disk %d at (%g, %g) is not connected to disk 1: the disks of "
            "a body must touch or overlap (centres at most (d_i + d_j)/2 apart)\n",
            cmd, spec, b + 1, x[b], y[b]);
    return 2;
  }
  return 0;
}

/* The rows of <f>: one a (--a), a scan, or one shape (--disks), per model; the exit code. */
static int fmean_rows(const fopts *fo) {
  double a = fo->a, d = fo->d, seconds = fo->seconds, scan[3] = {0, 0, 0};
  int have_scan = fo->scan != NULL, all = fo->model == 3;
  hd_fmean_model model = all ? HD_FMEAN_HEURISTIC : (hd_fmean_model)fo->model;
  if (have_scan &&
      (sscanf(fo->scan, "%lf:%lf:%lf", &scan[0], &scan[1], &scan[2]) != 3 || !(scan[0] > 0.0) ||
       !(scan[1] >= scan[0]) || !(scan[2] > 0.0) || !isfinite(scan[1]))) {
    fprintf(stderr,
            "haff mc fmean: --scan '%s': expected A0:A1:STEP with A0 > 0, A1 >= A0, STEP > 0\n",
            fo->scan);
    return 2;
  }
  hd_shape shape;
  if (fo->disks && hd_mc_parse_disks("mc fmean", fo->disks, &shape)) return 2;
  hd_error err;
  hd_fmean_opts o;
  hd_fmean_opts_default(&o);
  o.dim = fo->dim;
  o.seed = (unsigned long)fo->seed;
  if (seconds > 0.0) {
    o.samples = 0;
    o.seconds = seconds;
  } else if (fo->samples) {
    o.samples = (unsigned long)fo->samples;
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
      o.a_over_d = fo->disks ? NAN : ai / d;
      o.shape = fo->disks ? &shape : NULL;
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
}

int hd_cmd_mc_fmean(int argc, char **argv) {
  fopts o = {.a = NAN, .d = 1.0, .dim = 2.0, .seed = 1, .model = 3};
  hd_optres res;
  int rc = hd_opt_parse(&hd_cmd_mc_fmean_spec, argc, argv, &o, &res);
  if (rc) return rc < 0 ? 0 : rc;
  if ((rc = fmean_check(&res, &o))) return rc;
  if (o.conv) return fmean_convergence(&o);
  if (!o.scan && !o.disks && isnan(o.a)) {
    fprintf(stderr, "haff mc fmean: --a A is required (or --scan A0:A1:STEP)\n");
    return 2;
  }
  if (o.fig4) {
    print_fig4(o.a / o.d);
    return 0;
  }
  return fmean_rows(&o);
}
