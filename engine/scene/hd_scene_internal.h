/* hd_scene_internal.h: what the files of engine/scene share; not part of the public API
 * (hd_scene.h is), and included by no other layer.
 *
 * Where things are:
 *   hd_scene_keys.h    every scene key, once (SCENE_KEYS): its section, type, storage, default,
 *                      range, canonical text and docs row; the table as data: hd_scene_keys.c
 *   hd_scene.c         the public entry points: hd_scene_load*, hd_scene_defaults, sizes
 *   hd_scene_parse.c   reading the text: lines, [section] headers, keys, --set overrides
 *   hd_scene_value.c   the messages (FAIL_AT, hd_scene_fail) and a value parsed by its type
 *   hd_scene_set.c     the fixed sections' keys with a syntax of their own (box, sides, state,
 *                      collisions, velocities_at...) and the [rods] checks of single keys
 *   hd_scene_shape.c   a [species NAME] body: the short forms (hd_scene_forms), d, m, disks,
 *                      the disks built and checked
 *   hd_scene_pairs.c   alpha_OTHER, beta_OTHER and the pair tables
 *   hd_scene_check.c   the checks of the whole scene after every key is read (box, placement,
 *                      state file, stops, frames, [rods])
 *   hd_scene_write.c   the canonical text (runs.scene)
 *   hd_scene_doc.c     the key tables of docs/scene-keys.md
 *   hd_scene_csv.c     [init] state CSV files
 *   hd_scene_area.c, hd_scene_species.c, hd_sweepfile.c: see their headers.
 * "Where is key X parsed": its row in hd_scene_keys.h; CUSTOM(hd_scene_set_X) names its handler,
 * any other row is parsed by its type in hd_scene_set_value (hd_scene_value.c). */
#ifndef HD_SCENE_INTERNAL_H
#define HD_SCENE_INTERNAL_H

#include "hd_scene.h"

#include <stddef.h>

/* ---- sections ------------------------------------------------------------------------------- */

/* Sections in the order of the canonical text.  S_SPECIES stands for every `[species NAME]`
 * section; a section instance `si` is a fixed section (si < N_SEC) or named species k
 * (si = N_SEC + k). */
enum { S_SYSTEM, S_DIMERS, S_DISKS, S_SPECIES, S_WALLS, S_INIT, S_RUN, S_LOG, S_RODS, N_SEC };
enum { N_SI = N_SEC + HD_MAX_SPECIES - 2 };

/* The sections' names, by S_* (hd_scene_keys.c). */
extern const char *const hd_scene_sec_name[N_SEC];

/* The [walls] sides, by bit of HD_WALL_* (hd_scene_keys.c). */
extern const char *const hd_scene_wall_name[4];

/* ---- the short forms of `shape = ...` ------------------------------------------------------- */

/* Numbers a short form takes after its name, besides the optional spacing S. */
#define HD_SCENE_FORM_MAX_PARAM 2

/* A number of a short form and its range: "NAME must be ..." when out of it. */
typedef struct hd_scene_form_param {
  const char *name;     /* as the help text and the messages write it: "A", "N", "ANGLE" */
  double lo, hi;        /* range (hi INFINITY: none above) */
  int lo_open, hi_open; /* the range excludes lo, hi */
  int whole;            /* a whole number */
  const char *note;     /* appended to the range message (NULL: nothing) */
} hd_scene_form_param;

/* One short form of `shape = NAME [numbers] [S]` of a [species NAME] section: every place that
 * knows the short forms (the parser, its messages, the canonical text, the docs' key table, the
 * body built) reads this row.  Every disk of the body has the section's `d` and `m`. */
typedef struct hd_scene_form {
  const char *name;                                   /* the first word: "bent" */
  int nparam;                                         /* numbers after the name, all required */
  hd_scene_form_param param[HD_SCENE_FORM_MAX_PARAM]; /* each, in order */
  int spacing; /* 1: an optional last number S > 0, the centre spacing (default d) */
  /* The disks' centres in the body frame, from the form's numbers v[0 .. nparam - 1] (in range)
   * and the spacing s (S, or d): fills x[], y[] and returns how many (1 .. HD_MAX_BODY_DISKS). */
  int (*build)(const double *v, double s, double *x, double *y);
  const char *help; /* one line, as docs/scene-keys.md's list of short forms gives it */
} hd_scene_form;

/* The short forms, in the order of the help text; the last row has name NULL. */
extern const hd_scene_form hd_scene_forms[];

/* S, the optional last number of a form with `spacing`. */
extern const hd_scene_form_param hd_scene_form_spacing;

/* The form's syntax as the help text writes it ("bent ANGLE [S]") into buf (n bytes). */
void hd_scene_form_syntax(const hd_scene_form *f, char *buf, size_t n);

/* Every form's syntax joined into buf (n bytes): each one `quote`d (e.g. "`" or ""), between
 * them `sep`, before the last `last_sep` ("linear N [S], triangle [S] or bent ANGLE [S]"). */
void hd_scene_forms_list(const char *quote, const char *sep, const char *last_sep, char *buf,
                         size_t n);

/* Why a value is out of the range of q, after q's name: "must be in (0, 180] degrees". */
void hd_scene_form_param_why(const hd_scene_form_param *q, char *buf, size_t n);

/* ---- the key table -------------------------------------------------------------------------- */

typedef struct ctx ctx;
typedef struct sbuf sbuf;

/* How a key's value is read, stored and written. */
typedef enum kt {
  KT_REAL,  /* a finite number in [lo, hi] (ends open per lo_open, hi_open): double */
  KT_LONG,  /* a whole number in [lo, hi]: long */
  KT_WHOLE, /* a whole number in [lo, hi]: double */
  KT_U64,   /* a whole number 0 .. 2^64 - 1: unsigned long long */
  KT_BOOL,  /* 1 0 true false yes no on off: int 0/1, written as names[0] / names[1] */
  KT_ENUM,  /* one of names: int index */
  KT_CUSTOM /* parsed by set (its fields default to zero bytes) */
} kt;

/* One scene key.  Which fields matter depends on type (above). */
typedef struct key_def {
  int sec;                  /* S_* */
  const char *name;         /* as written in the scene */
  kt type;                  /* how it is read and stored */
  size_t off;               /* offsetof(hd_scene, field), or offsetof(hd_scene_species, field)
                             * for S_SPECIES */
  double def;               /* default (not KT_CUSTOM) */
  double lo, hi;            /* range (KT_REAL, KT_LONG, KT_WHOLE) */
  int lo_open, hi_open;     /* the range excludes lo, hi */
  const char *why;          /* message when out of range, instead of the generic one */
  const char *const *names; /* KT_BOOL: written forms of 0 and 1; KT_ENUM: the values */
  int (*set)(ctx *c, int si, int k, const char *v); /* KT_CUSTOM: parses and stores */
  int (*check)(ctx *c, int si, int k);              /* further check after a generic parse */
  int if_pos;                                       /* written only when > 0 (0 means unset) */
  int if_not_def; /* KT_REAL: written only when not the default (keys added after runs were
                   * stored: their runs.scene keeps its form) */
  int (*show)(const ctx *c, int si); /* whether the canonical text writes it (NULL: yes) */
  void (*put)(const ctx *c, int si, int k, sbuf *b); /* writes it (NULL: "name = value") */
  const char *doc_key;                               /* docs: the key column (NULL: the name) */
  const char *doc_def;                               /* docs: the default column (NULL: from def) */
  const char *doc_range; /* docs: the range column (NULL: from the type and range) */
  int doc_forms;         /* docs: the range column is the short forms (hd_scene_forms), then
                          * "; " and doc_range */
  const char *doc;       /* docs: what it means */
} key_def;

#include "hd_scene_keys.h"

/* The key table, by K_* (hd_scene_keys.c). */
extern const key_def hd_scene_keys[N_KEY];

/* ---- the state of a parse ------------------------------------------------------------------- */

/* Where something was set: a line of the file, or the over-th --set (1-based); 0/0 = nowhere. */
typedef struct loc {
  long line;
  int over;
} loc;

/* An `alpha_OTHER` or `beta_OTHER` key of a [species NAME] section. */
typedef struct sp_pair {
  char other[HD_SPECIES_NAME_MAX]; /* OTHER */
  int beta;                        /* 1: beta_OTHER */
  double v;                        /* its value */
  loc at;                          /* where it was set */
  char val[96];                    /* as written */
} sp_pair;

/* What a [species NAME] section says besides its hd_scene_species fields. */
typedef struct sp_parse {
  const hd_scene_form *form;         /* its short form (NULL: `disks = ...`) */
  double v[HD_SCENE_FORM_MAX_PARAM]; /* the form's numbers */
  double s;                          /* spacing S (NAN: = d) */
  double d, m;                       /* `d`, `m` */
  int npair;                         /* alpha_OTHER and beta_OTHER keys */
  sp_pair pair[2 * HD_MAX_SPECIES];  /* (at most one of each per other species) */
} sp_parse;

/* A parse of one scene: the scene being filled, where each key was set, the reader's place. */
struct ctx {
  hd_scene *sc;
  const char *name;        /* file name for messages */
  const char *const *over; /* the overrides */
  int n_over;              /* how many */
  hd_error *err;
  int failed;                      /* an error has been set: stop */
  int code;                        /* its hd_status */
  loc cur;                         /* where the key being handled comes from */
  int cur_si;                      /* the section of the line being read (-1: none yet) */
  loc key_at[N_SI][N_KEY];         /* where each key of each section was set */
  char key_val[N_SI][N_KEY][96];   /* its value as written (shortened), for later messages */
  int present[N_SI];               /* the section appears (header or --set) */
  loc sec_at[N_SI];                /* its first header */
  sp_parse sp[HD_MAX_SPECIES - 2]; /* the named species' sections */
  const char *p, *end;             /* reader: rest of the text */
  long lineno;                     /* reader: lines handed out */
  char state_rel[HD_PATH_MAX];     /* `state` as written */
  int mode;                        /* M_* */
};

/* What a load checks: everything (a scene to run), a run's stored text (its state file not
 * read), or a stored text only read (hd_scene_read_stored). */
enum { M_RUN, M_STORED, M_READ };

/* A growing text (the canonical text, the docs); oom is set when memory ran out. */
struct sbuf {
  char *s;
  size_t n, cap;
  int oom;
};

/* ---- messages and values (hd_scene_value.c) ------------------------------------------------- */

/* The section (S_*) of section instance si: S_SPECIES for every named species. */
int hd_scene_sec_of(int si);

/* Whether l is a place (a line of the file or a --set). */
int hd_scene_is_set(loc l);

/* Whether key k of section instance si was set (in the file or by --set). */
int hd_scene_key_set(const ctx *c, int si, int k);

/* Where key k of section instance si is stored: in c->sc, or in its named species. */
void *hd_scene_field(const ctx *c, int si, int k);

/* Section instance si as the messages name it ("dimers", "species NAME") into buf (n bytes). */
void hd_scene_sec_label(const ctx *c, int si, char *buf, size_t n);

/* Place l as the messages name it ("FILE:LINE", "--set OVERRIDE") into buf (n bytes). */
void hd_scene_where(const ctx *c, loc l, char *buf, size_t n);

/* Records a failure: c->err gets the message (code), c->failed and c->code are set, which stops
 * the parse.  Returns code. */
__attribute__((format(printf, 3, 4))) int hd_scene_cfail(ctx *c, int code, const char *fmt, ...);

/* v into buf (n bytes), cut to fit with "..." (for a message). */
void hd_scene_shorten(const char *v, char *buf, size_t n);

/* Records a failure (hd_scene_cfail) worded "WHERE: [sec] key = value: why" for place l and
 * section instance si (key NULL: "WHERE: [sec]: why"; val NULL: "WHERE: [sec] key: why", why from
 * fmt).  Returns code. */
__attribute__((format(printf, 7, 8))) int hd_scene_fail(ctx *c, int code, loc l, int si,
                                                        const char *key, const char *val,
                                                        const char *fmt, ...);

/* Error about key k of section si where it was set, with its value. */
#define FAIL_AT(c, si, k, ...)                                                                     \
  hd_scene_fail((c), HD_EINPUT, (c)->key_at[si][k], (si), hd_scene_keys[k].name,                   \
                (c)->key_val[si][k], __VA_ARGS__)
/* The same for a key of a fixed section. */
#define FAIL_KEY(c, k, ...) FAIL_AT(c, hd_scene_keys[k].sec, k, __VA_ARGS__)

/* Whether s is, whole, a finite number (no hex, no nan or inf): 1 with *x set, else 0. */
int hd_scene_parse_num(const char *s, double *x);

/* Why s, which hd_scene_parse_num refused, is not a finite number (for a message). */
const char *hd_scene_num_why(const char *s);

/* x into buf (n bytes) in the shortest of %.15g, %.16g, %.17g that reads back as exactly x. */
void hd_scene_shortest(double x, char *buf, size_t n);

/* The generic "must be ..." of kd's range (lo, hi and their ends) into buf (n bytes). */
void hd_scene_range_why(const key_def *kd, char *buf, size_t n);

/* The number s in key k's range (whole: also a whole number) into *x: HD_OK, or the error at
 * key k of section instance si (its row's why, or the generic range message). */
int hd_scene_get_ranged(ctx *c, int si, int k, const char *s, int whole, double *x);

/* Splits s at blanks into at most max words copied to tok (each under 64 chars): their count,
 * or -1 when there are more than max or one is too long. */
int hd_scene_split(const char *s, char tok[][64], int max);

/* Parses v, the value of key k of section instance si, by the row's type (or its set handler)
 * into the scene, then runs the row's check: HD_OK or the error at the key. */
int hd_scene_set_value(ctx *c, int si, int k, const char *v);

/* ---- reading the text (hd_scene_parse.c) ---------------------------------------------------- */

/* The fixed section (S_*, not S_SPECIES) called s, or -1. */
int hd_scene_find_sec(const char *s);

/* The section instance of the named species `name`, or -1. */
int hd_scene_find_species(const ctx *c, const char *name);

/* Parses the scene text c->p .. c->end (every line, section and key): HD_OK or the error. */
int hd_scene_parse_text(ctx *c);

/* s without its leading blanks and its trailing blanks and line ends (cut in place). */
char *hd_scene_trim(char *s);

/* Applies override i of c->over ("SECTION.KEY=VALUE", "species.NAME.KEY=VALUE"): HD_OK or the
 * error naming the --set. */
int hd_scene_apply_override(ctx *c, int i);

/* ---- the keys with a syntax of their own ---------------------------------------------------- *
 * A set handler (key_def.set, CUSTOM rows) parses v, the value of key k of section instance si,
 * and stores it: HD_OK or the error at the key (FAIL_AT).  A check (key_def.check) checks a key
 * after its generic parse.  A show predicate (key_def.show) says whether the canonical text
 * writes the key of section instance si; a put writer (key_def.put) writes key k of si as the
 * canonical text has it, line end included. */

/* hd_scene_set.c: [system] box = Lx Ly (both > 0). */
int hd_scene_set_box(ctx *c, int si, int k, const char *v);
/* hd_scene_set.c: [walls] sides: left right, bottom top or all four (hd_scene.walls). */
int hd_scene_set_sides(ctx *c, int si, int k, const char *v);
/* hd_scene_set.c: [init] state = FILE (as written; resolved by hd_scene_check_all). */
int hd_scene_set_state(ctx *c, int si, int k, const char *v);
/* hd_scene_set.c: [log] collisions = all | none | every N. */
int hd_scene_set_collisions(ctx *c, int si, int k, const char *v);
/* hd_scene_set.c: [log] velocities_at (k = K_LVEL, cpd) or velocities_at_time (K_LVELT). */
int hd_scene_set_vel_at(ctx *c, int si, int k, const char *v);
/* hd_scene_set.c: [rods] count is even. */
int hd_scene_check_rod_count(ctx *c, int si, int k);
/* hd_scene_set.c: [rods] eps_step is 0 or in [1e-5, 0.5]. */
int hd_scene_check_eps_step(ctx *c, int si, int k);

/* hd_scene_shape.c: [species NAME] d (k = K_PD) and m (K_PM), the short forms' disks. */
int hd_scene_set_sp_dm(ctx *c, int si, int k, const char *v);
/* hd_scene_shape.c: [species NAME] shape = NAME [numbers] [S], a row of hd_scene_forms. */
int hd_scene_set_shape(ctx *c, int si, int k, const char *v);
/* hd_scene_shape.c: [species NAME] disks = x y d m; x y d m; ... */
int hd_scene_set_disks(ctx *c, int si, int k, const char *v);
/* hd_scene_shape.c: the species has a short form (shape, d, m are written). */
int hd_scene_show_short_shape(const ctx *c, int si);
/* hd_scene_shape.c: the species has disks = ... (written instead of shape). */
int hd_scene_show_explicit(const ctx *c, int si);
/* hd_scene_shape.c: shape = NAME [numbers] S (S always, for a form with a spacing). */
void hd_scene_put_shape(const ctx *c, int si, int k, sbuf *b);
/* hd_scene_shape.c: d or m. */
void hd_scene_put_sp_dm(const ctx *c, int si, int k, sbuf *b);
/* hd_scene_shape.c: disks = x y d m;x y d m ... (no blank before ';'). */
void hd_scene_put_disks(const ctx *c, int si, int k, sbuf *b);

/* hd_scene_pairs.c: [species NAME] alpha_OTHER (k = K_PALPHAX) or beta_OTHER (K_PBETAX), in the
 * pair slot that the parser made the last of the species' (OTHER resolved later). */
int hd_scene_set_alpha_other(ctx *c, int si, int k, const char *v);
/* hd_scene_pairs.c: alpha_OTHER (beta_OTHER) of every pair with a species written before this
 * one, each pair once (beta_OTHER only where not the default). */
void hd_scene_put_pairs(const ctx *c, int si, int k, sbuf *b);

/* hd_scene_write.c: the show predicates of the fixed sections' keys. */
int hd_scene_show_beta_dimer(const ctx *c, int si); /* [disks] beta_dimer: either beta set */
int hd_scene_show_set(const ctx *c, int si);        /* area_fraction: when set */
int hd_scene_show_box(const ctx *c, int si);        /* box: given, not from area_fraction */
int hd_scene_show_not_state(const ctx *c, int si);  /* placement: no state file */
int hd_scene_show_state(const ctx *c, int si);      /* state: a state file */
int hd_scene_show_sides(const ctx *c, int si);      /* sides: some walls */
int hd_scene_show_vel(const ctx *c, int si);        /* velocities_at: snapshots in cpd */
int hd_scene_show_vel_time(const ctx *c, int si);   /* velocities_at_time: in time */
int hd_scene_show_frames(const ctx *c, int si);     /* frames_max_mb: frames asked for */
int hd_scene_show_rod_eps(const ctx *c, int si);    /* [rods] eps: model = constant */

/* hd_scene_write.c: the put writers of the fixed sections' keys. */
void hd_scene_put_area(const ctx *c, int si, int k, sbuf *b); /* and "; box = ..." */
void hd_scene_put_box(const ctx *c, int si, int k, sbuf *b);
void hd_scene_put_sides(const ctx *c, int si, int k, sbuf *b);
void hd_scene_put_state(const ctx *c, int si, int k, sbuf *b); /* the resolved path */
void hd_scene_put_collisions(const ctx *c, int si, int k, sbuf *b);
void hd_scene_put_vel(const ctx *c, int si, int k, sbuf *b); /* either list */

/* ---- a species' body (hd_scene_shape.c) ----------------------------------------------------- */

/* The moment of inertia of a body of species sp about its centre of mass (the engine's
 * sum m_k |o_k|^2), and its mass in *mass if not NULL. */
double hd_scene_species_inertia(const hd_scene_species *sp, double *mass);

/* Why a moment of inertia must be within [HD_MIN_INERTIA, 1 / HD_MIN_INERTIA] (for a message). */
extern const char hd_scene_inertia_why[];

/* The disks of named species j from its shape (or disks), then checked: one connected body,
 * within the engine's bounds of size, mass ratio, inertia and diameter ratio.  HD_OK or the
 * error at its shape or disks key. */
int hd_scene_build_species(ctx *c, int j);

/* ---- pairs (hd_scene_pairs.c) --------------------------------------------------------------- */

/* hd_scene.alpha_pair and beta_pair from the species' own values, [disks] alpha_dimer and
 * beta_dimer and the alpha_OTHER and beta_OTHER keys, and hd_scene.rough: HD_OK or the error at
 * a key whose OTHER is unknown, the species itself or a pair set twice. */
int hd_scene_fill_pairs(ctx *c);

/* ---- the whole scene (hd_scene_check.c) ----------------------------------------------------- */

/* The bodies of sc: dimers, disks and each named species' count, summed. */
long hd_scene_body_count(const hd_scene *sc);

/* Checks the whole scene once every key is read (c->mode says how much: M_RUN everything, M_STORED
 * no state file read, M_READ what reading needs), fills what follows from the keys (defaults
 * that follow other keys, the species' disks, the pair tables, the box from area_fraction, the
 * counts from a state file): HD_OK or the error. */
int hd_scene_check_all(ctx *c);

/* ---- the canonical text (hd_scene_write.c) -------------------------------------------------- */

/* Appends printf-style text to b (on no memory: b->oom set, nothing more appended). */
__attribute__((format(printf, 2, 3))) void hd_scene_put(sbuf *b, const char *fmt, ...);

/* Appends "key = x\n", x in its shortest exact form. */
void hd_scene_put_kv(sbuf *b, const char *key, double x);

/* The canonical text of the parsed scene (malloc'd), or NULL when out of memory. */
char *hd_scene_canonical_text(const ctx *c);

#endif
