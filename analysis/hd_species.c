/* hd_species: per-species temperature ratios of mixtures, measured and in theory. */
#include "hd_species.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hd_mixture.h"

int hd_species_theory(const hd_ana_mix *mix, double *ratio, char *why, size_t whylen) {
  for (int i = 0; i < mix->k; i++) ratio[i] = NAN;
  why[0] = 0;
  if (mix->k == 0) return snprintf(why, whylen, "no species"), 0;
  if (mix->walls) return snprintf(why, whylen, "walls: the theory is for a periodic box"), 0;
  if (!(mix->area > 0)) return snprintf(why, whylen, "no box area"), 0;
  hd_mix_species sp[HD_MIX_MAX];
  for (int i = 0; i < mix->k; i++) {
    const hd_ana_sp *p = &mix->sp[i];
    if (p->rotates || isnan(p->sigma))
      return snprintf(why, whylen, "species %s: not a single disk (the theory is for disks)",
                      p->name),
             0;
    sp[i] = (hd_mix_species){(double)p->count / mix->area, p->sigma, p->mass};
  }
  double chi[HD_MIX_MAX * HD_MIX_MAX];
  hd_mixture_chi2d(mix->k, sp, chi);
  hd_error e;
  if (hd_mixture_hcs(mix->k, sp, mix->alpha, chi, 2, ratio, &e)) {
    for (int i = 0; i < mix->k; i++) ratio[i] = NAN;
    return snprintf(why, whylen, "%.150s", e.msg), 0;
  }
  return 1;
}

/* One run's window means of T_i/T and K_i (sums over frames), and the same over blocks. */
typedef struct run_means {
  size_t m;                                    /* frames in the window */
  double T[HD_ANA_SP_MAX], K[HD_ANA_SP_MAX];   /* window means */
  double Tb[HD_ANA_SP_MAX][HD_SPECIES_BLOCKS]; /* block means */
  double Kb[HD_ANA_SP_MAX][HD_SPECIES_BLOCKS];
  size_t nK[HD_ANA_SP_MAX]; /* frames with e_rot > 0 */
} run_means;

/* T_i / T and e_tr / e_rot of frame f of s (mix's k species; x_j = N_j / N). */
static void frame(const hd_ana_mix *mix, const hd_ana_spseries *s, size_t f, double *T, double *K) {
  size_t k = s->k;
  long N = 0;
  for (size_t j = 0; j < k; j++) N += mix->sp[j].count;
  double Tm = 0;
  for (size_t j = 0; j < k; j++) Tm += (double)mix->sp[j].count / (double)N * s->e_tr[f * k + j];
  for (size_t j = 0; j < k; j++) {
    T[j] = s->e_tr[f * k + j] / Tm;
    double er = s->e_rot[f * k + j];
    K[j] = er > 0 ? s->e_tr[f * k + j] / er : NAN;
  }
}

/* The means of run's frames with t in [t0, t1] into *r (r->m = 0 when none). */
static void window_means(const hd_ana_mix *mix, const hd_ana_spseries *s, double t0, double t1,
                         run_means *r) {
  memset(r, 0, sizeof *r);
  size_t a = 0, b;
  while (a < s->n && s->t[a] < t0) a++;
  for (b = a; b < s->n && s->t[b] <= t1; b++) {
  }
  r->m = b - a;
  size_t k = s->k;
  double T[HD_ANA_SP_MAX], K[HD_ANA_SP_MAX];
  size_t nb[HD_SPECIES_BLOCKS] = {0}, nKb[HD_ANA_SP_MAX][HD_SPECIES_BLOCKS] = {{0}};
  for (size_t f = a; f < b; f++) {
    frame(mix, s, f, T, K);
    size_t blk = (f - a) * HD_SPECIES_BLOCKS / r->m;
    nb[blk]++;
    for (size_t j = 0; j < k; j++) {
      r->T[j] += T[j], r->Tb[j][blk] += T[j];
      if (!isnan(K[j])) r->K[j] += K[j], r->Kb[j][blk] += K[j], r->nK[j]++, nKb[j][blk]++;
    }
  }
  for (size_t j = 0; j < k; j++) {
    r->T[j] = r->m ? r->T[j] / (double)r->m : NAN;
    r->K[j] = r->nK[j] ? r->K[j] / (double)r->nK[j] : NAN;
    for (int q = 0; q < HD_SPECIES_BLOCKS; q++) {
      r->Tb[j][q] = nb[q] ? r->Tb[j][q] / (double)nb[q] : NAN;
      r->Kb[j][q] = nKb[j][q] ? r->Kb[j][q] / (double)nKb[j][q] : NAN;
    }
  }
}

/* Mean and standard error of v[0..n), NaN entries left out (se NaN with fewer than 2). */
static void mean_se(const double *v, size_t n, double *mean, double *se) {
  double s = 0, s2 = 0;
  size_t m = 0;
  for (size_t i = 0; i < n; i++)
    if (!isnan(v[i])) s += v[i], m++;
  *mean = m ? s / (double)m : NAN;
  for (size_t i = 0; i < n; i++)
    if (!isnan(v[i])) s2 += (v[i] - *mean) * (v[i] - *mean);
  *se = m >= 2 ? sqrt(s2 / (double)(m - 1) / (double)m) : NAN;
}

/* Fills g's rows from its runs. */
static int fill_group(sqlite3 *db, const hd_run_fit *fits, hd_species_group *g, hd_error *err) {
  size_t k = (size_t)g->mix.k, n = g->n;
  double *v = malloc(2 * k * (n ? n : 1) * sizeof *v), *c = malloc(2 * (n ? n : 1) * sizeof *c);
  run_means *first = malloc(sizeof *first);
  if (!v || !c || !first) {
    free(v), free(c), free(first);
    return hd_error_set(err, HD_ENOMEM, "out of memory");
  }
  int rc = HD_OK;
  for (size_t i = 0; i < n && rc == HD_OK; i++) {
    const hd_run_fit *f = &fits[g->idx[i]];
    hd_ana_spseries s;
    if ((rc = hd_ana_spseries_read(db, f->info.id, &g->mix, &s, err))) break;
    run_means r;
    window_means(&g->mix, &s, f->t_start, f->t_end, &r);
    hd_ana_spseries_free(&s);
    if (r.m == 0) continue;
    if (g->used == 0) *first = r;
    for (size_t j = 0; j < k; j++) v[j * n + g->used] = r.T[j], v[(k + j) * n + g->used] = r.K[j];
    c[g->used] = f->cpd_start, c[n + g->used] = f->cpd_end;
    g->used++;
  }
  if (rc == HD_OK) {
    double tmp;
    mean_se(c, g->used, &g->cpd_start, &tmp);
    mean_se(c + n, g->used, &g->cpd_end, &tmp);
    g->err_runs = g->used >= 2;
    for (size_t j = 0; j < k; j++) {
      hd_species_row *w = &g->row[j];
      mean_se(v + j * n, g->used, &w->T_ratio, &w->T_ratio_err);
      mean_se(v + (k + j) * n, g->used, &w->K, &w->K_err);
      if (g->used == 1) { /* one run: the spread of its window's blocks */
        mean_se(first->Tb[j], HD_SPECIES_BLOCKS, &tmp, &w->T_ratio_err);
        mean_se(first->Kb[j], HD_SPECIES_BLOCKS, &tmp, &w->K_err);
        if (first->m < 2 * HD_SPECIES_BLOCKS) w->T_ratio_err = w->K_err = NAN;
      }
      if (!g->mix.sp[j].rotates) w->K = w->K_err = NAN;
    }
  }
  free(v), free(c), free(first);
  return rc;
}

int hd_species_groups(sqlite3 *db, const hd_run_fit *fits, size_t n, hd_species_group **g,
                      size_t *ng, hd_error *err) {
  *ng = 0;
  *g = calloc(n ? n : 1, sizeof **g);
  if (!*g) return hd_error_set(err, HD_ENOMEM, "out of memory");
  int rc = HD_OK;
  for (size_t i = 0; i < n && rc == HD_OK; i++) {
    hd_ana_mix mix;
    if ((rc = hd_ana_mix_read(db, fits[i].info.id, &mix, err))) break;
    if (mix.k == 0) continue; /* rods */
    hd_species_group *q = NULL;
    for (size_t j = 0; j < *ng && !q; j++)
      if (hd_ana_mix_same(&(*g)[j].mix, &mix) &&
          hd_ana_same_physics(&fits[(*g)[j].idx[0]].info, &fits[i].info))
        q = &(*g)[j]; /* roughness, shapes, walls' alpha too (they were pooled) */
    if (!q) {
      q = &(*g)[(*ng)++];
      q->mix = mix;
      if (!(q->idx = malloc(n * sizeof *q->idx)))
        rc = hd_error_set(err, HD_ENOMEM, "out of memory");
    }
    if (q->idx) q->idx[q->n++] = i;
  }
  for (size_t j = 0; j < *ng && rc == HD_OK; j++) {
    hd_species_group *q = &(*g)[j];
    if ((rc = fill_group(db, fits, q, err))) break;
    double ratio[HD_ANA_SP_MAX];
    hd_species_theory(&q->mix, ratio, q->why, sizeof q->why);
    for (int i = 0; i < q->mix.k; i++) q->row[i].T_ratio_theory = ratio[i];
  }
  if (rc) hd_species_groups_free(*g, *ng), *g = NULL, *ng = 0;
  return rc;
}

void hd_species_groups_free(hd_species_group *g, size_t ng) {
  for (size_t i = 0; g && i < ng; i++) free(g[i].idx);
  free(g);
}
