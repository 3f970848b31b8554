/* `haff mc rate`: the molecular-chaos collision frequency of hard dimers or any shape over
 * eq. (29)'s nu0 (mc/rate.h, docs/mc-rate.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "haff.h"
#include "hd_body.h"
#include "hd_opt.h"
#include "rate.h"

/* The options of `haff mc rate`. */
typedef struct ropts {
  double a, d, seconds; /* --a (NAN: not given), --d, --seconds (0: not given) */
  long samples, seed;   /* --samples (0: not given), --seed */
  const char *disks;    /* --disks, NULL when not given */
} ropts;

static const hd_optdef rate_opts[] = {
    HD_OPT_DBL("a", 0, ropts, a, 0, INFINITY, HD_OPTF_FINITE, "A",
               "bond length a >= 0 of the dimer (units of --d; a = 0: a disk of\n"
               "mass 2m)"),
    HD_OPT_DBL("d", 0, ropts, d, 0, INFINITY, HD_OPTF_GT | HD_OPTF_FINITE, "D",
               "disk diameter > 0 (default 1)"),
    HD_OPT_STR("disks", 0, ropts, disks, "SPEC",
               "any rigid shape instead of a dimer: 1 to 8 disks 'x y d m' separated\n"
               "by ';' (sigma = the largest diameter, M = the total mass)"),
    HD_OPT_INT("samples", 0, ropts, samples, 2, 1000000000000000LL, HD_OPTF_EXP, "N",
               "configurations to draw, >= 2 (default 1e7)"),
    HD_OPT_DBL("seconds", 0, ropts, seconds, 0, INFINITY, HD_OPTF_GT | HD_OPTF_FINITE, "S",
               "draw for S seconds instead of N configurations"),
    HD_OPT_INT("seed", 0, ropts, seed, 0, 4294967295LL, HD_OPTF_EXP, "K",
               "gsl_rng_mt19937 seed (default 1)"),
    {0}};

const hd_optspec hd_cmd_mc_rate_spec = {
    HD_OPT_SPEC("mc rate", rate_opts, 0, 0, 0, NULL),
    .head = "usage: haff mc rate --a A [--d D] [--samples N | --seconds S] [--seed K]\n"
            "       haff mc rate --disks 'X Y D M; ...' [--samples N | --seconds S] [--seed K]\n"
            "\n"
            "The low-density equilibrium collision frequency nu of hard dimers (or any shape):\n"
            "molecular chaos over the exact excluded region of two bodies, equipartition\n"
            "(translational and rotational Maxwell-Boltzmann at one T), by Monte Carlo; as a\n"
            "ratio to eq. (29)'s nu0 in haff's convention (number density of bodies, sigma =\n"
            "d, mass M = 2m, the translational T; g = 1): Table I's nu0_eff/nu0 at low density,\n"
            "recollisions and density corrections left out (docs/mc-rate.md).\n",
    .tail = "\n"
            "Output (TSV, one header row): a_over_d ratio ratio_err samples accepted seconds\n"
            "(a_over_d empty with --disks; ratio_err = sd/sqrt(samples); disks: ratio 1).\n"};

int hd_cmd_mc_rate(int argc, char **argv) {
  ropts o = {.a = NAN, .d = 1.0, .seed = 1};
  hd_optres res;
  int rc = hd_opt_parse(&hd_cmd_mc_rate_spec, argc, argv, &o, &res);
  if (rc) return rc < 0 ? 0 : rc;
  if (o.samples && o.seconds > 0) {
    fprintf(stderr, "haff mc rate: give --samples or --seconds, not both\n");
    return 2;
  }
  if (hd_opt_refuse(&hd_cmd_mc_rate_spec, &res, "disks", "a d", "with --disks")) return 2;
  if (!o.disks && isnan(o.a)) {
    fprintf(stderr, "haff mc rate: --a A is required (or --disks SPEC)\n");
    return 2;
  }
  hd_shape shape;
  if (o.disks) {
    if (hd_mc_parse_disks("mc rate", o.disks, &shape)) return 2;
  } else if (o.a > 0) {
    hd_shape_dimer(&shape, o.d, o.a, 1.0);
  } else {
    hd_shape_disk(&shape, o.d, 2.0); /* a = 0: the dimer is one disk of mass 2m */
  }
  hd_rate_opts ro = {&shape, o.samples > 0 ? (unsigned long)o.samples : 0, o.seconds,
                     (unsigned long)o.seed};
  if (!ro.samples && !(ro.seconds > 0)) ro.samples = 10000000UL;
  hd_rate_result r;
  hd_error err;
  int st = hd_rate_run(&ro, &r, &err);
  if (st) {
    fprintf(stderr, "haff mc rate: %s\n", err.msg);
    return hd_exit_code(st);
  }
  printf("a_over_d\tratio\tratio_err\tsamples\taccepted\tseconds\n");
  if (o.disks)
    printf("\t");
  else
    printf("%.10g\t", o.a / o.d);
  printf("%.8g\t%.3g\t%lu\t%lu\t%.3f\n", r.ratio, r.ratio_err, r.samples, r.accepted, r.seconds);
  return 0;
}
