/* plots/shapes: the data of plots/shapes.gp (`make plots`, plots/shapes.mk): cooling gases of
 * bodies of different shapes, each a scene whose one species is given in code as a
 * `[species NAME]` section would give it (hd_scene.named).
 * usage: shapes N ETA ALPHA CPD SEED   prints, per shape, TSV blocks of
 *   shape cpd x=(1-alpha^2)cpd E/E0 E_tr/E_rot
 * every 0.5 cpd, then one line per shape "# f shape <f> <f>_err collisions" with the mean of the
 * orientation factor f over its collisions (standard error from 20 batches of consecutive
 * collisions).  The shapes: disk, dimer (a = d), linear and bent (120 degrees) trimers, a
 * triangle, an asymmetric dimer (d 1 and 0.5, m 1 and 0.3, 0.8 apart); their disks are printed
 * as "# disks shape SPEC" for `haff mc fmean --disks`. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hd_sim.h"

typedef struct shape_def {
  const char *name;
  int n;
  double x[3], y[3], d[3], m[3];
  double area; /* of one body, the union of its disks */
} shape_def;

static const shape_def shapes[] = {
    {"disk", 1, {0}, {0}, {1}, {1}, M_PI / 4},
    {"dimer", 2, {0, 1}, {0, 0}, {1, 1}, {1, 1}, M_PI / 2},
    {"linear", 3, {0, 1, 2}, {0, 0, 0}, {1, 1, 1}, {1, 1, 1}, 3 * M_PI / 4},
    {"bent", 3, {1, 0, -0.5}, {0, 0, 0.86602540378443865}, {1, 1, 1}, {1, 1, 1}, 3 * M_PI / 4},
    {"triangle", 3, {0, 1, 0.5}, {0, 0, 0.86602540378443865}, {1, 1, 1}, {1, 1, 1}, 3 * M_PI / 4},
    {"asym", 2, {0, 0.8}, {0, 0}, {1, 0.5}, {1, 0.3}, M_PI / 4 * 1.25},
};

int main(int argc, char **argv) {
  if (argc != 6) {
    fprintf(stderr, "usage: shapes N ETA ALPHA CPD SEED\n");
    return 2;
  }
  long N = atol(argv[1]);
  double eta = atof(argv[2]), alpha = atof(argv[3]), cpd_end = atof(argv[4]);
  unsigned long long seed = strtoull(argv[5], NULL, 10);
  if (N < 2 || !(eta > 0 && eta < 0.5) || !(alpha >= 0 && alpha <= 1) || !(cpd_end > 0)) {
    fprintf(stderr, "shapes: bad arguments\n");
    return 2;
  }
  for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++) {
    const shape_def *sd = &shapes[k];
    hd_scene sc;
    memset(&sc, 0, sizeof sc);
    sc.dimer_d = sc.dimer_a = sc.dimer_m = sc.disk_sigma = sc.disk_mass = 1.0;
    sc.dimer_alpha = sc.disk_alpha = sc.disk_alpha_dimer = sc.wall_alpha = 1.0;
    sc.seed = seed;
    sc.temperature = 1.0;
    sc.placement = HD_PLACE_RANDOM;
    hd_scene_species *sp = &sc.named[sc.n_named++];
    snprintf(sp->name, sizeof sp->name, "%s", sd->name);
    sp->count = N;
    sp->ndisk = sd->n;
    for (int i = 0; i < sd->n; i++)
      sp->x[i] = sd->x[i], sp->y[i] = sd->y[i], sp->d[i] = sd->d[i], sp->m[i] = sd->m[i];
    sp->alpha = alpha;
    sc.alpha_pair[2][0] = sc.alpha_pair[2][1] = sc.alpha_pair[0][2] = sc.alpha_pair[1][2] = alpha;
    sc.box_x = sc.box_y = sqrt((double)N * sd->area / eta);
    hd_sim *s;
    hd_error err;
    if (hd_sim_alloc(&s, &sc, &err)) {
      fprintf(stderr, "shapes: %s: %s\n", sd->name, err.msg);
      return 1;
    }
    printf("# disks %s", sd->name);
    for (int i = 0; i < sd->n; i++)
      printf("%s%.17g %.17g %.17g %.17g", i ? "; " : " ", sd->x[i], sd->y[i], sd->d[i], sd->m[i]);
    printf("\n");
    double e0 = s->c.e_kin, next = 0.0, bsum[20] = {0};
    long bcnt[20] = {0}, ncoll = 0;
    double est = 2.0 * cpd_end * (double)N / 2.0; /* collisions expected, for the batches */
    for (;;) {
      double cpd = hd_sim_cpd(s);
      if (cpd >= next) {
        double et, er;
        hd_sim_energy(s, -1, &et, &er);
        printf("%s\t%.6g\t%.6g\t%.8g\t%.6g\n", sd->name, cpd, (1 - alpha * alpha) * cpd,
               (et + er) / e0, er > 0 ? et / er : NAN);
        next += 0.5;
      }
      if (cpd >= cpd_end) break;
      hd_event_out ev;
      int rc = hd_sim_next(s, INFINITY, &ev, &err);
      if (rc) {
        fprintf(stderr, "shapes: %s: %s\n", sd->name, err.msg);
        hd_sim_free(s);
        return 1;
      }
      int b = (int)(20.0 * (double)ncoll / est);
      if (b > 19) b = 19;
      bsum[b] += ev.info.f, bcnt[b]++, ncoll++;
    }
    double mean = 0, var = 0;
    int nb = 0;
    for (int b = 0; b < 20; b++)
      if (bcnt[b]) mean += bsum[b] / (double)bcnt[b], nb++;
    mean /= nb;
    for (int b = 0; b < 20; b++)
      if (bcnt[b]) var += pow(bsum[b] / (double)bcnt[b] - mean, 2);
    printf("# f %s %.6g %.3g %ld\n\n\n", sd->name, mean, sqrt(var / (nb * (nb - 1.0))), ncoll);
    hd_sim_free(s);
  }
  return 0;
}
