/* hd_scene_pairs: the restitutions of pairs of species: the `alpha_OTHER` and `beta_OTHER`
 * keys of a [species NAME] section, the tables hd_scene.alpha_pair and beta_pair they fill, and
 * their canonical text. */
#include "hd_scene_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* `alpha_OTHER` (k = K_PALPHAX) or `beta_OTHER` (K_PBETAX): recorded here, its OTHER resolved
 * when the scene is read. */
int hd_scene_set_alpha_other(ctx *c, int si, int k, const char *v) {
  (void)k;
  sp_parse *p = &c->sp[si - N_SEC];
  sp_pair *q = &p->pair[p->npair - 1]; /* the parser (handle) made it the last */
  char key[HD_SPECIES_NAME_MAX + 8];
  snprintf(key, sizeof key, "%s_%s", q->beta ? "beta" : "alpha", q->other);
  double x, lo = q->beta ? -1 : 0;
  if (!hd_scene_parse_num(v, &x))
    return hd_scene_fail(c, HD_EINPUT, q->at, si, key, v, "%s", hd_scene_num_why(v));
  if (!(x >= lo && x <= 1))
    return hd_scene_fail(c, HD_EINPUT, q->at, si, key, v, "must be in [%g, 1]", lo);
  q->v = x;
  return HD_OK;
}

/* alpha_pair (beta = 0) or beta_pair (beta = 1): each species' own alpha (beta) on the
 * diagonal, the smaller of the two off it, then [disks] alpha_dimer (beta_dimer) and the
 * alpha_OTHER (beta_OTHER) keys. */
static int fill_pairs_of(ctx *c, int beta) {
  hd_scene *sc = c->sc;
  double own[HD_MAX_SPECIES], (*pair)[HD_MAX_SPECIES] = beta ? sc->beta_pair : sc->alpha_pair;
  const char *kind = beta ? "beta" : "alpha";
  loc set_at[HD_MAX_SPECIES][HD_MAX_SPECIES];
  int set_by[HD_MAX_SPECIES][HD_MAX_SPECIES];
  memset(set_at, 0, sizeof set_at);
  for (int i = 0; i < HD_MAX_SPECIES; i++)
    own[i] = i == 0                ? (beta ? sc->dimer_beta : sc->dimer_alpha)
             : i == 1              ? (beta ? sc->disk_beta : sc->disk_alpha)
             : i - 2 < sc->n_named ? (beta ? sc->named[i - 2].beta : sc->named[i - 2].alpha)
                                   : (beta ? -1 : 1);
  for (int i = 0; i < HD_MAX_SPECIES; i++)
    for (int j = 0; j < HD_MAX_SPECIES; j++) pair[i][j] = fmin(own[i], own[j]);
  pair[0][1] = pair[1][0] = beta ? sc->disk_beta_dimer : sc->disk_alpha_dimer;
  for (int k = 0; k < sc->n_named; k++) {
    sp_parse *p = &c->sp[k];
    int si = N_SEC + k;
    for (int q = 0; q < p->npair; q++) {
      sp_pair *pr = &p->pair[q];
      if (pr->beta != beta) continue;
      char key[HD_SPECIES_NAME_MAX + 8];
      snprintf(key, sizeof key, "%s_%s", kind, pr->other);
      int o = !strcmp(pr->other, "dimers") ? 0 : !strcmp(pr->other, "disks") ? 1 : -1;
      if (o < 0 && hd_scene_find_species(c, pr->other) >= 0)
        o = hd_scene_find_species(c, pr->other) - N_SEC + 2;
      if (o == 2 + k)
        return hd_scene_fail(c, HD_EINPUT, pr->at, si, key, pr->val,
                             "the species itself: its own restitution is `%s`", kind);
      if (o < 0 || (o < 2 && !c->present[o == 0 ? S_DIMERS : S_DISKS])) {
        char known[400] = "";
        if (c->present[S_DIMERS]) strcat(known, " dimers");
        if (c->present[S_DISKS]) strcat(known, " disks");
        for (int j = 0; j < sc->n_named; j++)
          if (j != k) strcat(known, " "), strcat(known, sc->named[j].name);
        return hd_scene_fail(c, HD_EINPUT, pr->at, si, key, pr->val,
                             "no [%s%s] section in the scene (other species:%s)",
                             o < 0 ? "species " : "", pr->other, known[0] ? known : " none");
      }
      int i = 2 + k;
      if (hd_scene_is_set(set_at[i][o])) {
        char at[600];
        hd_scene_where(c, set_at[i][o], at, sizeof at);
        return hd_scene_fail(c, HD_EINPUT, pr->at, si, key, pr->val,
                             "the pair is also set by [species %s] %s_%s (%s)",
                             sc->named[set_by[i][o]].name, kind, sc->named[k].name, at);
      }
      set_at[i][o] = set_at[o][i] = pr->at;
      set_by[i][o] = set_by[o][i] = k;
      pair[i][o] = pair[o][i] = pr->v;
    }
  }
  return HD_OK;
}

/* Both pair tables, and whether the scene is rough (hd_scene.rough). */
int hd_scene_fill_pairs(ctx *c) {
  int rc = fill_pairs_of(c, 0);
  if (rc || (rc = fill_pairs_of(c, 1))) return rc;
  hd_scene *sc = c->sc;
  sc->rough = sc->wall_beta > -1;
  for (int i = 0; i < 2 + sc->n_named; i++)
    for (int j = 0; j < 2 + sc->n_named; j++) sc->rough |= sc->beta_pair[i][j] > -1;
  return HD_OK;
}

/* alpha_OTHER of every pair with a species written before this one: each pair once;
 * beta_OTHER (k = K_PBETAX) likewise, where it is not the default (the smaller `beta`) */
void hd_scene_put_pairs(const ctx *c, int si, int k, sbuf *b) {
  const hd_scene *sc = c->sc;
  int i = 2 + si - N_SEC, beta = k == K_PBETAX;
  char key[HD_SPECIES_NAME_MAX + 8];
  for (int o = 0; o < i; o++) {
    if (o < 2 && !c->present[o == 0 ? S_DIMERS : S_DISKS]) continue;
    double own_o = o == 0 ? sc->dimer_beta : o == 1 ? sc->disk_beta : sc->named[o - 2].beta;
    if (beta && sc->beta_pair[i][o] == fmin(sc->named[i - 2].beta, own_o)) continue;
    snprintf(key, sizeof key, "%s_%s", beta ? "beta" : "alpha",
             o == 0   ? "dimers"
             : o == 1 ? "disks"
                      : sc->named[o - 2].name);
    hd_scene_put_kv(b, key, beta ? sc->beta_pair[i][o] : sc->alpha_pair[i][o]);
  }
}
