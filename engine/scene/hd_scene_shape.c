/* hd_scene_shape: the body of a [species NAME]: `shape = ...` (the short forms, one row each of
 * hd_scene_forms), `d`, `m` or `disks = ...`; the canonical text of those keys; the disks built
 * from them and checked (one connected body within the engine's bounds). */
#include "hd_scene_internal.h"
#include "hd_scene_species.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* [species NAME] `d` and `m` (the short forms' disks). */
int hd_scene_set_sp_dm(ctx *c, int si, int k, const char *v) {
  double x;
  int rc = hd_scene_get_ranged(c, si, k, v, 0, &x);
  if (rc) return rc;
  *(k == K_PD ? &c->sp[si - N_SEC].d : &c->sp[si - N_SEC].m) = x;
  return HD_OK;
}

/* Each form's builder (hd_scene_form.build): its disks' centres in the body frame. */
static int build_disk(const double *v, double s, double *x, double *y) {
  (void)v, (void)s;
  x[0] = 0, y[0] = 0;
  return 1;
}

static int build_dimer(const double *v, double s, double *x, double *y) {
  (void)s;
  for (int i = 0; i < 2; i++) x[i] = i ? v[0] / 2 : -v[0] / 2, y[i] = 0;
  return 2;
}

static int build_linear(const double *v, double s, double *x, double *y) {
  int n = (int)v[0];
  for (int i = 0; i < n; i++) x[i] = (i - (n - 1) / 2.0) * s, y[i] = 0;
  return n;
}

/* side s, centroid at the origin */
static int build_triangle(const double *v, double s, double *x, double *y) {
  (void)v;
  double h = s / (2 * sqrt(3.0));
  for (int i = 0; i < 3; i++) {
    x[i] = i == 0 ? 0 : i == 1 ? -s / 2 : s / 2;
    y[i] = i == 0 ? 2 * h : -h;
  }
  return 3;
}

/* the middle disk at the origin, the arms at +-ANGLE/2 from the x axis */
static int build_bent(const double *v, double s, double *x, double *y) {
  double half = v[0] * M_PI / 360;
  for (int i = 0; i < 3; i++) {
    x[i] = i == 1 ? 0 : s * cos(half);
    y[i] = i == 1 ? 0 : i == 0 ? s * sin(half) : -s * sin(half);
  }
  return 3;
}

/* The short forms: a new one is a row here and its builder above (docs/architecture.md). */
const hd_scene_form hd_scene_forms[] = {
    {.name = "disk", .build = build_disk, .help = "one disk"},
    {.name = "dimer",
     .nparam = 1,
     .param = {{.name = "A",
                .lo = 0,
                .hi = INFINITY,
                .lo_open = 1,
                .note = " (one disk: shape = disk)"}},
     .build = build_dimer,
     .help = "two disks A apart (A > 0; A < d overlaps them, as `[dimers] a` does)"},
    {.name = "linear",
     .nparam = 1,
     .param = {{.name = "N", .lo = 1, .hi = HD_MAX_BODY_DISKS, .whole = 1}},
     .spacing = 1,
     .build = build_linear,
     .help = "N disks (1 … 8) in a row, S apart"},
    {.name = "triangle",
     .spacing = 1,
     .build = build_triangle,
     .help = "three disks at the corners of an equilateral triangle of side S"},
    {.name = "bent",
     .nparam = 1,
     .param = {{.name = "ANGLE", .lo = 0, .hi = 180, .lo_open = 1, .note = " degrees"}},
     .spacing = 1,
     .build = build_bent,
     .help = "three disks, the outer two S from the middle one, ANGLE degrees (0 < ANGLE ≤ 180) "
             "between the two arms at the middle disk"},
    {.name = NULL}};

const hd_scene_form_param hd_scene_form_spacing = {
    .name = "S", .lo = 0, .hi = INFINITY, .lo_open = 1};

void hd_scene_form_syntax(const hd_scene_form *f, char *buf, size_t n) {
  size_t at = (size_t)snprintf(buf, n, "%s", f->name);
  for (int i = 0; i < f->nparam && at < n; i++)
    at += (size_t)snprintf(buf + at, n - at, " %s", f->param[i].name);
  if (f->spacing && at < n) snprintf(buf + at, n - at, " [%s]", hd_scene_form_spacing.name);
}

void hd_scene_forms_list(const char *quote, const char *sep, const char *last_sep, char *buf,
                         size_t n) {
  buf[0] = '\0';
  for (const hd_scene_form *f = hd_scene_forms; f->name; f++) {
    char syn[120];
    hd_scene_form_syntax(f, syn, sizeof syn);
    size_t at = strlen(buf);
    snprintf(buf + at, n - at, "%s%s%s%s",
             f == hd_scene_forms ? ""
             : f[1].name         ? sep
                                 : last_sep,
             quote, syn, quote);
  }
}

void hd_scene_form_param_why(const hd_scene_form_param *q, char *buf, size_t n) {
  key_def kd = {.lo = q->lo, .hi = q->hi, .lo_open = q->lo_open, .hi_open = q->hi_open};
  char why[120];
  hd_scene_range_why(&kd, why, sizeof why); /* "must be ..." */
  snprintf(buf, n, "must be %s%s%s", q->whole ? "a whole number " : "", why + strlen("must be "),
           q->note ? q->note : "");
}

/* A number of a form (the word tok) in q's range into *x; else an error naming q. */
static int form_num(ctx *c, int si, int k, const char *tok, const hd_scene_form_param *q,
                    double *x) {
  if (!hd_scene_parse_num(tok, x))
    return FAIL_AT(c, si, k, "%s '%s': %s", q->name, tok, hd_scene_num_why(tok));
  int in = (q->lo_open ? *x > q->lo : *x >= q->lo) && (q->hi_open ? *x < q->hi : *x <= q->hi);
  if ((q->whole && *x != floor(*x)) || !in) {
    char why[200];
    hd_scene_form_param_why(q, why, sizeof why);
    return FAIL_AT(c, si, k, "%s %s", q->name, why);
  }
  return HD_OK;
}

/* `shape = NAME [numbers] [S]`: a row of hd_scene_forms */
int hd_scene_set_shape(ctx *c, int si, int k, const char *v) {
  char forms[400] = "expected ";
  hd_scene_forms_list("", ", ", " or ", forms + strlen(forms), sizeof forms - strlen(forms));
  sp_parse *p = &c->sp[si - N_SEC];
  char tok[2 + HD_SCENE_FORM_MAX_PARAM][64];
  int n = hd_scene_split(v, tok, 2 + HD_SCENE_FORM_MAX_PARAM), rc;
  if (n < 1) return FAIL_AT(c, si, k, "%s", forms);
  const hd_scene_form *f = hd_scene_forms;
  while (f->name && strcmp(tok[0], f->name)) f++;
  if (!f->name || n < 1 + f->nparam || n > 1 + f->nparam + f->spacing)
    return FAIL_AT(c, si, k, "%s", forms);
  p->s = NAN;
  for (int i = 0; i < f->nparam; i++)
    if ((rc = form_num(c, si, k, tok[1 + i], &f->param[i], &p->v[i]))) return rc;
  if (f->spacing && n == 2 + f->nparam &&
      (rc = form_num(c, si, k, tok[n - 1], &hd_scene_form_spacing, &p->s)))
    return rc;
  p->form = f;
  return HD_OK;
}

/* `disks = x y d m; x y d m; ...` */
int hd_scene_set_disks(ctx *c, int si, int k, const char *v) {
  hd_scene_species *sp = &c->sc->named[si - N_SEC];
  int n = 0;
  const char *s = v;
  while (*s) {
    size_t len = strcspn(s, ";");
    char grp[256], tok[5][64];
    if (len >= sizeof grp) return FAIL_AT(c, si, k, "disk %d: too long", n + 1);
    memcpy(grp, s, len);
    grp[len] = '\0';
    s += len + (s[len] == ';');
    int nt = hd_scene_split(grp, tok, 4);
    if (nt == 0) continue; /* an empty group: "a; ; b", or a ';' at the end */
    if (n == HD_MAX_BODY_DISKS)
      return FAIL_AT(c, si, k, "more than %d disks (HD_MAX_BODY_DISKS)", HD_MAX_BODY_DISKS);
    double x[4];
    static const char *const what[4] = {"x", "y", "d", "m"};
    if (nt != 4)
      return FAIL_AT(c, si, k, "disk %d: expected x y d m (four numbers, disks separated by ';')",
                     n + 1);
    for (int j = 0; j < 4; j++)
      if (!hd_scene_parse_num(tok[j], &x[j]))
        return FAIL_AT(c, si, k, "disk %d: %s '%s': %s", n + 1, what[j], tok[j],
                       hd_scene_num_why(tok[j]));
    for (int j = 2; j < 4; j++)
      if (!(x[j] > 0)) return FAIL_AT(c, si, k, "disk %d: %s must be > 0", n + 1, what[j]);
    sp->x[n] = x[0], sp->y[n] = x[1], sp->d[n] = x[2], sp->m[n] = x[3];
    n++;
  }
  if (n == 0) return FAIL_AT(c, si, k, "missing value: expected x y d m; x y d m; ...");
  sp->ndisk = n;
  return HD_OK;
}

int hd_scene_show_short_shape(const ctx *c, int si) {
  return c->sp[si - N_SEC].form != NULL;
}

int hd_scene_show_explicit(const ctx *c, int si) {
  return !hd_scene_show_short_shape(c, si);
}

void hd_scene_put_shape(const ctx *c, int si, int k, sbuf *b) {
  (void)k;
  const sp_parse *p = &c->sp[si - N_SEC];
  char t[40];
  hd_scene_put(b, "shape = %s", p->form->name);
  for (int i = 0; i < p->form->nparam; i++)
    hd_scene_shortest(p->v[i], t, sizeof t), hd_scene_put(b, " %s", t);
  if (p->form->spacing)
    hd_scene_shortest(isnan(p->s) ? p->d : p->s, t, sizeof t), hd_scene_put(b, " %s", t);
  hd_scene_put(b, "\n");
}

void hd_scene_put_sp_dm(const ctx *c, int si, int k, sbuf *b) {
  hd_scene_put_kv(b, hd_scene_keys[k].name, k == K_PD ? c->sp[si - N_SEC].d : c->sp[si - N_SEC].m);
}

void hd_scene_put_disks(const ctx *c, int si, int k, sbuf *b) {
  (void)k;
  const hd_scene_species *sp = &c->sc->named[si - N_SEC];
  hd_scene_put(b, "disks =");
  for (int i = 0; i < sp->ndisk; i++) {
    double v[4] = {sp->x[i], sp->y[i], sp->d[i], sp->m[i]};
    for (int j = 0; j < 4; j++) {
      char t[40];
      hd_scene_shortest(v[j], t, sizeof t);
      hd_scene_put(b, " %s", t);
    }
    if (i + 1 < sp->ndisk)
      hd_scene_put(b, ";"); /* no blank before ';': that would start a comment */
  }
  hd_scene_put(b, "\n");
}

/* Disks of one body touch or overlap when their centres are at most (d_i + d_j)/2 apart, up to
 * this relative slack (the short forms' touching disks are computed with cos and sin). */
#define HD_TOUCH_SLACK 1e-12

/* The moment of inertia of a body of species sp about its centre of mass (the engine's
 * sum m_k |o_k|^2), and its mass in *mass if not NULL. */
double hd_scene_species_inertia(const hd_scene_species *sp, double *mass) {
  double M = 0, cx = 0, cy = 0, I = 0;
  for (int a = 0; a < sp->ndisk; a++)
    M += sp->m[a], cx += sp->m[a] * sp->x[a], cy += sp->m[a] * sp->y[a];
  for (int a = 0; a < sp->ndisk; a++) {
    double ox = sp->x[a] - cx / M, oy = sp->y[a] - cy / M;
    I += sp->m[a] * (ox * ox + oy * oy);
  }
  if (mass) *mass = M;
  return I;
}

/* Why a moment of inertia must be within [HD_MIN_INERTIA, 1 / HD_MIN_INERTIA]. */
const char hd_scene_inertia_why[] =
    "the spin energy I w^2 / 2 and the thermal spin w^2 = T / I leave the range of doubles "
    "(the samples' e_rot became NaN); scale the masses or lengths";

/* The physical bounds of a body that the engine's numerics need (docs/scene-keys.md): its size
 * (the span of its disk centres: 0, a round body, or at least HD_MIN_BOND of its largest
 * diameter, as [dimers] a), the mass ratio of its disks (HD_MAX_MASS_RATIO) and their diameter
 * ratio (HD_MAX_DIAMETER_RATIO).  HD_OK or an error at `key` (shape or disks) saying why. */
static int species_bounds(ctx *c, int j, int key) {
  const hd_scene_species *sp = &c->sc->named[j];
  int si = N_SEC + j;
  double span = 0, dlo = INFINITY, dhi = 0, mlo = INFINITY, mhi = 0;
  for (int a = 0; a < sp->ndisk; a++) {
    dlo = fmin(dlo, sp->d[a]), dhi = fmax(dhi, sp->d[a]);
    mlo = fmin(mlo, sp->m[a]), mhi = fmax(mhi, sp->m[a]);
    for (int b = a + 1; b < sp->ndisk; b++)
      span = fmax(span, hypot(sp->x[a] - sp->x[b], sp->y[a] - sp->y[b]));
  }
  if (span > 0 && !(span >= HD_MIN_BOND * dhi))
    return FAIL_AT(c, si, key,
                   "the disk centres span %g, less than %g of the largest diameter (%g): a body "
                   "that small is lost in the round-off of the positions (its spin runs away and "
                   "collisions pile up); disks that share one centre (span 0) make a round body",
                   span, HD_MIN_BOND, HD_MIN_BOND * dhi);
  if (!(mhi <= HD_MAX_MASS_RATIO * mlo))
    return FAIL_AT(c, si, key,
                   "masses from %g to %g, a ratio above %g: a light disk far from a heavy centre "
                   "of mass spins up to sqrt(disks x ratio) times the speed of the body, and the "
                   "contact search steps through every turn (it made no progress at 1e30)",
                   mlo, mhi, HD_MAX_MASS_RATIO);
  double I = hd_scene_species_inertia(sp, NULL);
  if (span > 0 && !(I >= HD_MIN_INERTIA && I <= 1 / HD_MIN_INERTIA))
    return FAIL_AT(c, si, key, "the moment of inertia %g is outside [%g, %g]: %s", I,
                   HD_MIN_INERTIA, 1 / HD_MIN_INERTIA, hd_scene_inertia_why);
  if (!(dhi <= HD_MAX_DIAMETER_RATIO * dlo))
    return FAIL_AT(c, si, key,
                   "diameters from %g to %g, a ratio above %g: the contact tolerances are "
                   "relative to the smallest disk (1e-10 of it), the round-off of the disks' "
                   "places to the largest",
                   dlo, dhi, HD_MAX_DIAMETER_RATIO);
  return HD_OK;
}

/* The disks of named species j from its shape, then: are they one connected body, within the
 * bounds of species_bounds. */
int hd_scene_build_species(ctx *c, int j) {
  hd_scene_species *sp = &c->sc->named[j];
  sp_parse *p = &c->sp[j];
  int si = N_SEC + j;
  int has_shape = hd_scene_key_set(c, si, K_PSHAPE), has_disks = hd_scene_key_set(c, si, K_PDISKS);
  if (has_shape && has_disks) {
    loc a = c->key_at[si][K_PSHAPE], b = c->key_at[si][K_PDISKS];
    int later = a.over > b.over || (a.over == b.over && a.line > b.line) ? K_PSHAPE : K_PDISKS;
    return FAIL_AT(c, si, later, "give either shape or disks, not both");
  }
  if (!has_shape && !has_disks) {
    char forms[400];
    hd_scene_forms_list("", " | ", " | ", forms, sizeof forms);
    return hd_scene_fail(c, HD_EINPUT, c->sec_at[si], si, "shape", NULL,
                         "missing: give shape = %s, or disks = x y d m; x y d m; ...", forms);
  }
  if (has_disks) {
    for (int k = K_PD; k <= K_PM; k++)
      if (hd_scene_key_set(c, si, k))
        return FAIL_AT(c, si, k, "not used with disks = ... (each disk gives its own d and m)");
  } else {
    sp->ndisk = p->form->build(p->v, isnan(p->s) ? p->d : p->s, sp->x, sp->y);
    for (int i = 0; i < sp->ndisk; i++) sp->d[i] = p->d, sp->m[i] = p->m;
  }
  int key = has_disks ? K_PDISKS : K_PSHAPE;
  int b = hd_scene_disks_unconnected(sp->ndisk, sp->x, sp->y, sp->d);
  if (b >= 0)
    return FAIL_AT(c, si, key,
                   "disk %d at (%g, %g) is not connected to disk 1: the disks of a body must "
                   "touch or overlap (centres at most (d_i + d_j)/2 apart)",
                   b + 1, sp->x[b], sp->y[b]);
  return species_bounds(c, j, key);
}

int hd_scene_disks_unconnected(int n, const double *x, const double *y, const double *d) {
  /* every disk reached from disk 0 through touching or overlapping pairs */
  int seen[HD_MAX_BODY_DISKS] = {1}, stack[HD_MAX_BODY_DISKS] = {0}, top = n > 0;
  if (n > HD_MAX_BODY_DISKS) return HD_MAX_BODY_DISKS;
  while (top > 0) {
    int a = stack[--top];
    for (int b = 0; b < n; b++) {
      double gap = hypot(x[a] - x[b], y[a] - y[b]);
      if (!seen[b] && gap <= (d[a] + d[b]) / 2 * (1 + HD_TOUCH_SLACK)) {
        seen[b] = 1;
        stack[top++] = b;
      }
    }
  }
  for (int b = 0; b < n; b++)
    if (!seen[b]) return b;
  return -1;
}
