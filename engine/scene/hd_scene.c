/* hd_scene: scene files (INI via libinih), `--set SECTION.KEY=VALUE` overrides, the canonical
 * text of a scene, and [init] state CSV files.
 *
 * Every key is declared once, in SCENE_KEYS below: section, name, type, where it is stored
 * (offsetof into hd_scene or hd_scene_species, or a handler for the few keys with a syntax of
 * their own), default, range, when and how the canonical text writes it, and its row in
 * docs/scene-keys.md.  The parser, hd_scene_defaults, the canonical text (runs.scene) and the
 * key tables of docs/scene-keys.md (hd_scene_keys_doc, checked by tests/test_scene.c) all come
 * from that one table; its order is the order of the canonical text and of the docs.
 *
 * Line numbers: libinih's handler is not told the line, so the scene is fed to ini_parse_stream
 * through our own reader, which hands over one physical line per call and counts them; the
 * handler then knows the line it is called for.  The reader also
 *   - strips leading blanks, so that an indented key is never taken for a libinih "multi-line
 *     continuation" of the previous key;
 *   - checks every `[section]` header itself (libinih does not report headers to the handler),
 *     so that an unknown or empty section is still an error, and text after `]` is refused;
 *   - refuses lines longer than HD_SCENE_MAX_LINE.
 * Every key is remembered with where it was set (file line or --set), so that checks made after
 * the whole scene is read still name the right line. */
#include "hd_scene.h"

#include "hd_body.h"
#include "hd_scene_internal.h"
#include "rods.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <ini.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Sections in the order of the canonical text.  S_SPECIES stands for every `[species NAME]`
 * section; a section instance `si` is a fixed section (si < N_SEC) or named species k
 * (si = N_SEC + k). */
enum { S_SYSTEM, S_DIMERS, S_DISKS, S_SPECIES, S_WALLS, S_INIT, S_RUN, S_LOG, S_RODS, N_SEC };
enum { N_SI = N_SEC + HD_MAX_SPECIES - 2 };
static const char *const hd_scene_sec_name[N_SEC] = {
    "system", "dimers", "disks", "species", "walls", "init", "run", "log", "rods"};

static int hd_scene_sec_of(int si) {
  return si >= N_SEC ? S_SPECIES : si;
}

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

/* Handlers of the custom keys, and the predicates and writers of the canonical text. */
static int hd_scene_set_box(ctx *c, int si, int k, const char *v);
static int hd_scene_set_sides(ctx *c, int si, int k, const char *v);
static int hd_scene_set_state(ctx *c, int si, int k, const char *v);
static int hd_scene_set_collisions(ctx *c, int si, int k, const char *v);
static int hd_scene_set_vel_at(ctx *c, int si, int k, const char *v);
static int hd_scene_set_shape(ctx *c, int si, int k, const char *v);
static int hd_scene_set_disks(ctx *c, int si, int k, const char *v);
static int hd_scene_set_sp_dm(ctx *c, int si, int k, const char *v);
static int hd_scene_set_alpha_other(ctx *c, int si, int k, const char *v);
static int hd_scene_check_rod_count(ctx *c, int si, int k);
static int hd_scene_check_eps_step(ctx *c, int si, int k);
static int hd_scene_show_set(const ctx *c, int si);
static int hd_scene_show_box(const ctx *c, int si);
static int hd_scene_show_not_state(const ctx *c, int si);
static int hd_scene_show_state(const ctx *c, int si);
static int hd_scene_show_sides(const ctx *c, int si);
static int hd_scene_show_vel(const ctx *c, int si);
static int hd_scene_show_vel_time(const ctx *c, int si);
static int hd_scene_show_frames(const ctx *c, int si);
static int hd_scene_show_rod_eps(const ctx *c, int si);
static int hd_scene_show_short_shape(const ctx *c, int si);
static int hd_scene_show_explicit(const ctx *c, int si);
static int hd_scene_show_beta_dimer(const ctx *c, int si);
static void hd_scene_put_area(const ctx *c, int si, int k, sbuf *b);
static void hd_scene_put_box(const ctx *c, int si, int k, sbuf *b);
static void hd_scene_put_sides(const ctx *c, int si, int k, sbuf *b);
static void hd_scene_put_state(const ctx *c, int si, int k, sbuf *b);
static void hd_scene_put_collisions(const ctx *c, int si, int k, sbuf *b);
static void hd_scene_put_vel(const ctx *c, int si, int k, sbuf *b);
static void hd_scene_put_shape(const ctx *c, int si, int k, sbuf *b);
static void hd_scene_put_sp_dm(const ctx *c, int si, int k, sbuf *b);
static void hd_scene_put_disks(const ctx *c, int si, int k, sbuf *b);
static void hd_scene_put_pairs(const ctx *c, int si, int k, sbuf *b);

static const char *const no_yes[] = {"no", "yes", NULL};
static const char *const zero_one[] = {"0", "1", NULL};
static const char *const placements[] = {"random", "lattice", NULL};
static const char *const rod_models[] = {"stochastic", "constant", NULL};
static const char *const rod_baths[] = {"mean", "unequal", NULL};

#define F(field) .off = offsetof(hd_scene, field)
#define SPF(field) .off = offsetof(hd_scene_species, field)
#define REAL(d) .type = KT_REAL, .def = (d)
#define R_POS .lo = 0, .hi = INFINITY, .lo_open = 1
#define R_NONNEG .lo = 0, .hi = INFINITY
#define R_UNIT .lo = 0, .hi = 1
#define R_BETA .lo = -1, .hi = 1, .if_not_def = 1
#define Q_KEY(field) REAL(0), field, R_UNIT, .if_not_def = 1
#define COUNT(field, what)                                                                         \
  .type = KT_LONG, F(field), .lo = 0, .hi = (double)HD_MAX_COUNT, .doc_def = "required",           \
  .doc = "number of " what
#define CUSTOM(fn) .type = KT_CUSTOM, .set = (fn)

/* Every key: X(ID, section, name, the rest of its key_def).  K_ID is its index. */
#define SCENE_KEYS(X)                                                                                \
  X(AREA, S_SYSTEM, "area_fraction", REAL(0), F(area_fraction), .lo = 0,                             \
    .hi = HD_MAX_AREA_FRACTION, .lo_open = 1, .hi_open = 1, .show = hd_scene_show_set,               \
    .put = hd_scene_put_area, .doc_key = "area_fraction = eta", .doc_def = "—",                      \
    .doc = "instead of `box`: a square box whose area makes the bodies cover eta")                   \
  X(BOX, S_SYSTEM, "box", CUSTOM(hd_scene_set_box), F(box_x), .show = hd_scene_show_box,             \
    .put = hd_scene_put_box, .doc_key = "box = Lx Ly", .doc_def = "—", .doc_range = "both > 0",      \
    .doc = "box edges; periodic in every direction no wall closes")                                  \
  X(SEED, S_SYSTEM, "seed", .type = KT_U64, F(seed), .def = 1, .doc_range = "0 … 2^64−1",            \
    .doc = "RNG seed (`haff run --seed N` is the override `--set system.seed=N`)")                   \
  X(DCOUNT, S_DIMERS, "count", COUNT(n_dimers, "dimers"))                                            \
  X(DD, S_DIMERS, "d", REAL(1), F(dimer_d), R_POS, .doc = "diameter of each disk")                   \
  X(DA, S_DIMERS, "a", REAL(1), F(dimer_a), R_NONNEG, .doc_range = "0 or ≥ 10⁻⁹ d",                  \
    .doc = "bond length, centre to centre (below 10⁻⁹ d the bond is lost in the round-off of "   \
           "the positions; `a = 0` is a disk of mass 2m)")                                           \
  X(DM, S_DIMERS, "m", REAL(1), F(dimer_m), R_POS, .doc = "mass of each disk (a dimer weighs 2m)")   \
  X(DALPHA, S_DIMERS, "alpha", REAL(1), F(dimer_alpha), R_UNIT, .doc = "dimer–dimer restitution")    \
  X(DBETA, S_DIMERS, "beta", REAL(-1), F(dimer_beta), R_BETA,                                        \
    .doc = "dimer-dimer tangential restitution at the contact point: -1 smooth (the paper's), "      \
           "1 perfectly rough (docs/analysis.md, rough bodies)")                                     \
  X(DQ, S_DIMERS, "q", Q_KEY(F(dimer_q)),                                                            \
    .doc = "each disk's own moment of inertia q m (d/2)^2, added to m a^2/2 (0: point masses, "      \
           "the paper's; 1/2: uniform disks)")                                                       \
  X(SCOUNT, S_DISKS, "count", COUNT(n_disks, "disks"))                                               \
  X(SSIGMA, S_DISKS, "sigma", REAL(1), F(disk_sigma), R_POS, .doc = "diameter")                      \
  X(SMASS, S_DISKS, "mass", REAL(1), F(disk_mass), R_POS, .doc = "mass")                             \
  X(SALPHA, S_DISKS, "alpha", REAL(1), F(disk_alpha), R_UNIT, .doc = "disk–disk restitution")        \
  X(SALPHAD, S_DISKS, "alpha_dimer", REAL(1), F(disk_alpha_dimer), R_UNIT, .doc_def = "= `alpha`",   \
    .doc = "dimer–disk restitution (eq. 21–22)")                                                     \
  X(SBETA, S_DISKS, "beta", REAL(-1), F(disk_beta), R_BETA,                                          \
    .doc = "disk-disk tangential restitution (a disk of `q` = 0 takes no torque: smooth)")           \
  X(SBETAD, S_DISKS, "beta_dimer", REAL(-1), F(disk_beta_dimer), .lo = -1, .hi = 1,                  \
    .show = hd_scene_show_beta_dimer, .doc_def = "= `beta`",                                         \
    .doc = "dimer-disk tangential restitution")                                                      \
  X(SQ, S_DISKS, "q", Q_KEY(F(disk_q)),                                                              \
    .doc = "the disk's own moment of inertia q mass (sigma/2)^2 (1/2: a uniform disk)")              \
  X(PCOUNT, S_SPECIES, "count", .type = KT_LONG, SPF(count), .lo = 0, .hi = (double)HD_MAX_COUNT,    \
    .doc_def = "required", .doc = "number of bodies")                                                \
  X(PALPHA, S_SPECIES, "alpha", REAL(1), SPF(alpha), R_UNIT,                                         \
    .doc = "restitution between two bodies of the species")                                          \
  X(PSHAPE, S_SPECIES, "shape", CUSTOM(hd_scene_set_shape), .show = hd_scene_show_short_shape,       \
    .put = hd_scene_put_shape, .doc_def = "— (or `disks`)", .doc_forms = 1,                          \
    .doc_range = "A, S ≥ 10⁻⁹ d",                                                                    \
    .doc = "a short form (below); S, the centre spacing, defaults to `d`")                           \
  X(PD, S_SPECIES, "d", CUSTOM(hd_scene_set_sp_dm), .def = 1, R_POS,                                 \
    .show = hd_scene_show_short_shape, .put = hd_scene_put_sp_dm,                                    \
    .doc = "with `shape`: the diameter of every disk")                                               \
  X(PM, S_SPECIES, "m", CUSTOM(hd_scene_set_sp_dm), .def = 1, R_POS,                                 \
    .show = hd_scene_show_short_shape, .put = hd_scene_put_sp_dm,                                    \
    .doc = "with `shape`: the mass of every disk")                                                   \
  X(PDISKS, S_SPECIES, "disks", CUSTOM(hd_scene_set_disks), .show = hd_scene_show_explicit,          \
    .put = hd_scene_put_disks, .doc_key = "disks = x y d m; x y d m; ...",                           \
    .doc_def = "— (or `shape`)",                                                                     \
    .doc_range = "1 to 8 disks, d > 0, m > 0; in one body m ≤ 10¹² × "                          \
                 "the smallest m, d ≤ 10⁴ × the smallest d, centres that "                      \
                 "span 0 or ≥ 10⁻⁹ × the largest d; no blank before `;`",                            \
    .doc = "instead of `shape`: each disk's centre in the body frame, diameter and mass")            \
  X(PALPHAX, S_SPECIES, "alpha_OTHER", CUSTOM(hd_scene_set_alpha_other),                             \
    .put = hd_scene_put_pairs, .doc_def = "the smaller of the two `alpha`s",                         \
    .doc_range = "[0, 1]",                                                                           \
    .doc = "restitution between this species and OTHER: another species' NAME, `dimers` or "         \
           "`disks` (the pair is set once, in either section)")                                      \
  X(PBETA, S_SPECIES, "beta", REAL(-1), SPF(beta), R_BETA,                                           \
    .doc = "tangential restitution between two bodies of the species")                               \
  X(PQ, S_SPECIES, "q", Q_KEY(SPF(q)),                                                               \
    .doc = "each disk's own moment of inertia q m (d/2)^2, added to the body's")                     \
  X(PBETAX, S_SPECIES, "beta_OTHER", CUSTOM(hd_scene_set_alpha_other), .put = hd_scene_put_pairs,    \
    .doc_def = "the smaller of the two `beta`s", .doc_range = "[-1, 1]",                             \
    .doc = "tangential restitution between this species and OTHER (as `alpha_OTHER`)")               \
  X(WSIDES, S_WALLS, "sides", CUSTOM(hd_scene_set_sides), F(walls), .show = hd_scene_show_sides,     \
    .put = hd_scene_put_sides, .doc_def = "required",                                                \
    .doc_range = "`left right`, `bottom top` or all four, space separated, no repeats",              \
    .doc = "flat hard walls on those box edges")                                                     \
  X(WALPHA, S_WALLS, "alpha", REAL(1), F(wall_alpha), R_UNIT,                                        \
    .doc = "body–wall restitution (eq. 24–25)")                                                      \
  X(WBETA, S_WALLS, "beta", REAL(-1), F(wall_beta), R_BETA,                                          \
    .doc = "body-wall tangential restitution")                                                       \
  X(TEMP, S_INIT, "temperature", REAL(1), F(temperature), R_NONNEG, .why = "must be > 0",            \
    .doc_range = "> 0 (≥ 0 with `state`)",                                                           \
    .doc = "kT per degree of freedom of the initial velocities; not used with `state`")              \
  X(PLACE, S_INIT, "placement", .type = KT_ENUM, F(placement), .names = placements,                  \
    .show = hd_scene_show_not_state, .doc = "how bodies are placed, orientations random")            \
  X(STATE, S_INIT, "state", CUSTOM(hd_scene_set_state), F(state_file),                               \
    .show = hd_scene_show_state, .put = hd_scene_put_state, .doc_def = "—",                          \
    .doc_range = "a CSV file",                                                                       \
    .doc = "every body given explicitly; relative to the scene file's folder")                       \
  X(STIME, S_RUN, "stop_time", REAL(0), F(stop_time), R_POS, .if_pos = 1, .doc_def = "unset",        \
    .doc = "stop at this time")                                                                      \
  X(SEVENTS, S_RUN, "stop_events", .type = KT_WHOLE, F(stop_events), .lo = 1,                        \
    .hi = 9007199254740992.0, .if_pos = 1, .doc_def = "unset", .doc_range = "whole, 1 to 2⁵³",       \
    .doc = "stop after this many collisions")                                                        \
  X(SCPD, S_RUN, "stop_cpd", REAL(0), F(stop_cpd), R_POS, .if_pos = 1, .doc_def = "unset",           \
    .doc = "stop at this many collisions per particle")                                              \
  X(VERIFY, S_RUN, "verify", .type = KT_BOOL, F(verify), .names = zero_one,                          \
    .doc = "check no-overlap and time order at every event")                                         \
  X(CKPT, S_RUN, "checkpoint_every", REAL(60), F(checkpoint_every), R_POS,                           \
    .doc = "wall-clock seconds between checkpoints")                                                 \
  X(LCOLL, S_LOG, "collisions", CUSTOM(hd_scene_set_collisions), F(log_collisions),                  \
    .put = hd_scene_put_collisions, .doc_def = "`all`",                                              \
    .doc_range = "`all` \\| `none` \\| `every N` (N whole ≥ 1)",                                     \
    .doc = "which collisions get a row")                                                             \
  X(LSAMPLES, S_LOG, "samples_every", REAL(0), F(samples_every), R_NONNEG, .doc_def = "0 (none)",    \
    .doc = "cpd between samples of E_tr, E_rot")                                                     \
  X(LVEL, S_LOG, "velocities_at", CUSTOM(hd_scene_set_vel_at), F(velocities_at),                     \
    .show = hd_scene_show_vel, .put = hd_scene_put_vel, .doc_def = "none",                           \
    .doc_range = "up to 64 cpd values ≥ 0, strictly ascending, space separated",                     \
    .doc = "when every body's velocity is stored (at the first collision at or past each value; "    \
           "values that one collision passes together give one snapshot). A value past "             \
           "`stop_cpd` is an error at set-up; values the run does not reach for another stop "       \
           "give none, and the run's message says how many")                                         \
  X(LVELT, S_LOG, "velocities_at_time", CUSTOM(hd_scene_set_vel_at), F(velocities_at),               \
    .show = hd_scene_show_vel_time, .put = hd_scene_put_vel, .doc_def = "none",                      \
    .doc_range = "up to 64 times ≥ 0, strictly ascending; not with `velocities_at`",                 \
    .doc = "the same in time: each snapshot is taken at exactly that time (the run is advanced "     \
           "to it, no collision changed). A time past `stop_time` is an error at set-up")            \
  X(LFRAMES, S_LOG, "frames_every", REAL(0), F(frames_every), R_NONNEG, .if_pos = 1,                 \
    .doc_def = "0 (none)",                                                                           \
    .doc = "a frame (position, orientation, velocity of every body, table `frames`) every this "     \
           "many cpd: at cpd 0 and at the first collision at or past each multiple, one per "        \
           "collision at most")                                                                      \
  X(LFRAMEST, S_LOG, "frames_every_time", REAL(0), F(frames_every_time), R_NONNEG, .if_pos = 1,      \
    .doc_def = "0 (none)", .doc_range = "≥ 0; needs `stop_time`; not with `frames_every`",           \
    .doc = "a frame at t = 0, T, 2T, … up to `stop_time`, at exactly those times (the engine "     \
           "stops there; the run's collisions are bit for bit those of a run without frames)")       \
  X(LFRAMESMB, S_LOG, "frames_max_mb", REAL(HD_FRAMES_MAX_MB), F(frames_max_mb), R_POS,              \
    .show = hd_scene_show_frames, .doc_range = "> 0; only with frames",                              \
    .doc = "cap on the frames' storage, in MB (10⁶ bytes)")                                          \
  X(RCOUNT, S_RODS, "count", .type = KT_LONG, F(n_rods), .lo = 2, .hi = (double)HD_MAX_COUNT,        \
    .check = hd_scene_check_rod_count, .doc_def = "required", .doc_range = "whole, even, ≥ 2",       \
    .doc = "rods on the ring (lengths alternate short/long); the ring length is `count`")            \
  X(RGAMMA, S_RODS, "gamma", REAL(HD_RODS_GAMMA_DEFAULT), F(rod_gamma), .lo = 0, .hi = 1,            \
    .lo_open = 1, .doc = "length and mass ratio short/long")                                         \
  X(RNMOD, S_RODS, "nmod", .type = KT_LONG, F(rod_nmod), .def = HD_RODS_NMOD_DEFAULT, .lo = 1,       \
    .hi = 1e9, .doc = "vibrational modes per rod")                                                   \
  X(RMODEL, S_RODS, "model", .type = KT_ENUM, F(rod_model), .names = rod_models,                     \
    .doc = "`stochastic` (ε ~ p_β) or `constant`")                                                   \
  X(REPS, S_RODS, "eps", REAL(HD_RODS_GAMMA_DEFAULT), F(rod_eps), R_UNIT,                            \
    .show = hd_scene_show_rod_eps, .doc_def = "= `gamma`",                                           \
    .doc = "the constant model's ε (only with model = constant)")                                    \
  X(RDAMP, S_RODS, "damping", REAL(0), F(rod_damping), R_NONNEG,                                     \
    .doc = "ν: bath temperatures decay as e^{−νt} between collisions")                               \
  X(RTC, S_RODS, "tc", REAL(0), F(rod_tc), R_NONNEG,                                                 \
    .doc = "TC model: ε = 1 when a rod collided less than tc ago (0 = off)")                         \
  X(RSTEP, S_RODS, "eps_step", REAL(0), F(rod_eps_step), R_NONNEG,                                   \
    .check = hd_scene_check_eps_step, .doc_def = "0 (= 0.01)", .doc_range = "0 or in [1e-5, 0.5]",   \
    .doc = "grid step of the ε sampler (the direct one, and the one the table is built from); "     \
           "the direct sampler refines it near the running maximum down to 0.01/128, which "         \
           "leaves ~ -0.3 % in the stationary E_kin at gamma 0.8 (plain grid: -3.5 %); "             \
           "see docs/mc-eps.md section 4f")                                                          \
  X(RTEMP, S_RODS, "temperature", REAL(HD_RODS_TEMPERATURE_DEFAULT), F(rod_temperature), R_POS,      \
    .doc = "initial temperature T0: E_kin(0) = N T0/2")                                              \
  X(RTABLE, S_RODS, "table", .type = KT_BOOL, F(rod_table), .names = no_yes,                         \
    .doc_def = "yes (stochastic model, baths = mean, γ < 1), else no",                               \
    .doc = "yes: ε from the balanced tabulated p_β (fast, ~3 s to build at the start; stationary " \
           "E_kin within 0.25 % of equipartition); no: the direct sampler (refined: 0.2-1.3 %, "     \
           "~10x slower per collision; not with baths = unequal). **Changed (issue 16):** "          \
           "the default was no")                                                                     \
  X(RBATHS, S_RODS, "baths", .type = KT_ENUM, F(rod_unequal), .names = rod_baths,                    \
    .doc = "`mean` (paper: β = E_tr/mean T_B) or `unequal` (β per rod)")

#define KEY_ENUM(id, ...) K_##id,
enum { SCENE_KEYS(KEY_ENUM) N_KEY };
#define KEY_DEF(id, s, n, ...) [K_##id] = {.sec = s, .name = n, __VA_ARGS__},
static const key_def hd_scene_keys[N_KEY] = {SCENE_KEYS(KEY_DEF)};

static const char *const hd_scene_wall_name[4] = {"left", "right", "bottom", "top"};

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

static int hd_scene_is_set(loc l) {
  return l.line > 0 || l.over > 0;
}

static int hd_scene_key_set(const ctx *c, int si, int k) {
  return hd_scene_is_set(c->key_at[si][k]);
}

/* Where key k of section si is stored. */
static void *hd_scene_field(const ctx *c, int si, int k) {
  char *base = si >= N_SEC ? (char *)&c->sc->named[si - N_SEC] : (char *)c->sc;
  return base + hd_scene_keys[k].off;
}

/* "dimers", or "species NAME" */
static void hd_scene_sec_label(const ctx *c, int si, char *buf, size_t n) {
  if (si >= N_SEC)
    snprintf(buf, n, "species %s", c->sc->named[si - N_SEC].name);
  else
    snprintf(buf, n, "%s", si >= 0 ? hd_scene_sec_name[si] : "?");
}

static void hd_scene_where(const ctx *c, loc l, char *buf, size_t n) {
  if (l.over)
    snprintf(buf, n, "--set %s", c->over[l.over - 1]);
  else
    snprintf(buf, n, "%s:%ld", c->name, l.line);
}

/* Records a failure: sets c->err and stops the parse.  Returns code. */
static __attribute__((format(printf, 3, 4))) int hd_scene_cfail(ctx *c, int code, const char *fmt,
                                                                ...) {
  char msg[sizeof c->err->msg];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  c->failed = 1;
  c->code = code;
  return hd_error_set(c->err, code, "%s", msg);
}

/* Shortens a value for a message. */
static void hd_scene_shorten(const char *v, char *buf, size_t n) {
  size_t len = strlen(v);
  if (len < n) {
    memcpy(buf, v, len + 1);
  } else {
    memcpy(buf, v, n - 4);
    memcpy(buf + n - 4, "...", 4);
  }
}

/* "WHERE: [sec] key = value: why" (key NULL: "WHERE: [sec]: why"; val NULL: "[sec] key: why"). */
static __attribute__((format(printf, 7, 8))) int hd_scene_fail(ctx *c, int code, loc l, int si,
                                                               const char *key, const char *val,
                                                               const char *fmt, ...) {
  char at[600], why[400], v[96], what[240], sec[64];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(why, sizeof why, fmt, ap);
  va_end(ap);
  hd_scene_where(c, l, at, sizeof at);
  hd_scene_sec_label(c, si, sec, sizeof sec);
  if (!key)
    snprintf(what, sizeof what, "[%s]", sec);
  else if (!val)
    snprintf(what, sizeof what, "[%s] %s", sec, key);
  else {
    hd_scene_shorten(val, v, sizeof v);
    snprintf(what, sizeof what, "[%s] %s = %s", sec, key, v);
  }
  return hd_scene_cfail(c, code, "%s: %s: %s", at, what, why);
}

/* Error about key k of section si where it was set, with its value. */
#define FAIL_AT(c, si, k, ...)                                                                     \
  hd_scene_fail((c), HD_EINPUT, (c)->key_at[si][k], (si), hd_scene_keys[k].name,                   \
                (c)->key_val[si][k], __VA_ARGS__)
/* The same for a key of a fixed section. */
#define FAIL_KEY(c, k, ...) FAIL_AT(c, hd_scene_keys[k].sec, k, __VA_ARGS__)

/* ---- value parsing ------------------------------------------------------------------------ */

/* A finite number that is the whole of s (no hex, no nan/inf). 1 on success. */
static int hd_scene_parse_num(const char *s, double *x) {
  if (!*s || strpbrk(s, "xX")) return 0;
  char *e;
  errno = 0;
  double v = strtod(s, &e);
  if (e == s || *e || !isfinite(v)) return 0;
  *x = v;
  return 1;
}

/* Why s is not a finite number (for messages). */
static const char *hd_scene_num_why(const char *s) {
  if (!*s) return "missing value: expected a number";
  double v = strtod(s, NULL);
  if (!isfinite(v)) return "must be a finite number";
  return "not a number";
}

/* The shortest of %.15g, %.16g, %.17g that reads back as exactly x (so the text round-trips
 * bit for bit, and 0.95 stays "0.95" rather than "0.94999999999999996"). */
static void hd_scene_shortest(double x, char *buf, size_t n) {
  for (int prec = 15; prec <= 17; prec++) {
    snprintf(buf, n, "%.*g", prec, x);
    if (strtod(buf, NULL) == x) return;
  }
}

/* Whether x is in key k's range. */
static int in_range(const key_def *kd, double x) {
  return (kd->lo_open ? x > kd->lo : x >= kd->lo) && (kd->hi_open ? x < kd->hi : x <= kd->hi);
}

/* The generic "must be ..." of key k's range. */
static void hd_scene_range_why(const key_def *kd, char *buf, size_t n) {
  char lo[40], hi[40];
  hd_scene_shortest(kd->lo, lo, sizeof lo);
  hd_scene_shortest(kd->hi, hi, sizeof hi);
  if (kd->hi == INFINITY)
    snprintf(buf, n, "must be %s %s", kd->lo_open ? ">" : ">=", lo);
  else
    snprintf(buf, n, "must be in %c%s, %s%c", kd->lo_open ? '(' : '[', lo, hi,
             kd->hi_open ? ')' : ']');
}

/* A number in key k's range (whole: a whole number too); else an error on key k of si. */
static int hd_scene_get_ranged(ctx *c, int si, int k, const char *s, int whole, double *x) {
  const key_def *kd = &hd_scene_keys[k];
  double v;
  char why[120];
  if (!hd_scene_parse_num(s, &v)) return FAIL_AT(c, si, k, "%s", hd_scene_num_why(s));
  if (whole && v != floor(v)) return FAIL_AT(c, si, k, "must be a whole number");
  if (!in_range(kd, v)) {
    hd_scene_range_why(kd, why, sizeof why);
    return FAIL_AT(c, si, k, "%s", kd->why ? kd->why : why);
  }
  *x = v;
  return HD_OK;
}

/* Splits s at blanks into at most max tokens copied to tok (each < 64 chars). Returns the count,
 * or -1 if there are more than max or one is too long. */
static int hd_scene_split(const char *s, char tok[][64], int max) {
  int n = 0;
  while (*s) {
    while (*s == ' ' || *s == '\t') s++;
    if (!*s) break;
    size_t len = strcspn(s, " \t");
    if (n == max || len >= 64) return -1;
    memcpy(tok[n], s, len);
    tok[n][len] = '\0';
    n++;
    s += len;
  }
  return n;
}

/* Parses the value of key k of section si into the scene. */
static int hd_scene_set_value(ctx *c, int si, int k, const char *v) {
  const key_def *kd = &hd_scene_keys[k];
  void *p = hd_scene_field(c, si, k);
  double x;
  int rc = HD_OK;
  switch (kd->type) {
  case KT_CUSTOM:
    return kd->set(c, si, k, v);
  case KT_REAL:
  case KT_WHOLE:
    if ((rc = hd_scene_get_ranged(c, si, k, v, kd->type == KT_WHOLE, &x))) return rc;
    *(double *)p = x;
    break;
  case KT_LONG:
    if ((rc = hd_scene_get_ranged(c, si, k, v, 1, &x))) return rc;
    *(long *)p = (long)x;
    break;
  case KT_U64: {
    char *e;
    if (!*v || *v == '-' || *v == '+' || strpbrk(v, " \t"))
      return FAIL_AT(c, si, k, "expected a whole number >= 0");
    errno = 0;
    unsigned long long u = strtoull(v, &e, 10);
    if (*e || e == v) return FAIL_AT(c, si, k, "expected a whole number >= 0");
    if (errno == ERANGE) return FAIL_AT(c, si, k, "too large (max %llu)", ULLONG_MAX);
    *(unsigned long long *)p = u;
    break;
  }
  case KT_BOOL: {
    static const char *const yes[] = {"1", "true", "yes", "on"}, *const no[] = {"0", "false", "no",
                                                                                "off"};
    int i = 0;
    while (i < 4 && strcmp(v, yes[i]) && strcmp(v, no[i])) i++;
    if (i == 4) return FAIL_AT(c, si, k, "expected 1 or 0 (true/false, yes/no, on/off)");
    *(int *)p = !strcmp(v, yes[i]);
    break;
  }
  case KT_ENUM: {
    int i = 0;
    while (kd->names[i] && strcmp(v, kd->names[i])) i++;
    if (!kd->names[i]) {
      char list[200] = "";
      for (int j = 0; kd->names[j]; j++) {
        const char *sep = !j ? "" : kd->names[j + 1] ? ", " : " or ";
        size_t at = strlen(list);
        snprintf(list + at, sizeof list - at, "%s%s", sep, kd->names[j]);
      }
      return FAIL_AT(c, si, k, "expected %s", list);
    }
    *(int *)p = i;
    break;
  }
  }
  return kd->check ? kd->check(c, si, k) : HD_OK;
}

/* ---- the custom keys ------------------------------------------------------------------------ */

static int hd_scene_set_box(ctx *c, int si, int k, const char *v) {
  char tok[2][64];
  double lx, ly;
  if (hd_scene_split(v, tok, 2) != 2 || !hd_scene_parse_num(tok[0], &lx) ||
      !hd_scene_parse_num(tok[1], &ly))
    return FAIL_AT(c, si, k, "expected two finite numbers Lx Ly");
  if (!(lx > 0 && ly > 0)) return FAIL_AT(c, si, k, "box edges must be > 0");
  c->sc->box_x = lx;
  c->sc->box_y = ly;
  return HD_OK;
}

static int hd_scene_set_sides(ctx *c, int si, int k, const char *v) {
  char tok[5][64];
  int n = hd_scene_split(v, tok, 4);
  if (n < 0) return FAIL_AT(c, si, k, "at most the four sides left right bottom top");
  if (n == 0) return FAIL_AT(c, si, k, "missing value: list some of left right bottom top");
  unsigned w = 0;
  for (int i = 0; i < n; i++) {
    int j = 0;
    while (j < 4 && strcmp(tok[i], hd_scene_wall_name[j])) j++;
    if (j == 4) return FAIL_AT(c, si, k, "unknown side '%s' (left right bottom top)", tok[i]);
    if (w & (1u << j)) return FAIL_AT(c, si, k, "side '%s' repeated", tok[i]);
    w |= 1u << j;
  }
  /* a wall closes its axis: past it there is no periodic image, so the opposite edge must be
   * closed too (a lone wall let bodies wrap through the open edge to land behind it) */
  if (!(w & HD_WALL_LEFT) != !(w & HD_WALL_RIGHT))
    return FAIL_AT(c, si, k, "'%s' needs '%s' too: walls close an axis at both edges",
                   w & HD_WALL_LEFT ? "left" : "right", w & HD_WALL_LEFT ? "right" : "left");
  if (!(w & HD_WALL_BOTTOM) != !(w & HD_WALL_TOP))
    return FAIL_AT(c, si, k, "'%s' needs '%s' too: walls close an axis at both edges",
                   w & HD_WALL_BOTTOM ? "bottom" : "top", w & HD_WALL_BOTTOM ? "top" : "bottom");
  c->sc->walls = w;
  return HD_OK;
}

static int hd_scene_set_state(ctx *c, int si, int k, const char *v) {
  if (!*v) return FAIL_AT(c, si, k, "missing value: expected a CSV file name");
  /* the canonical text writes "state = NAME": a NAME starting with ';' would read back as an
   * inline comment (found by make fuzz through hd_scene_read_stored, which opens no file) */
  if (*v == ';') return FAIL_AT(c, si, k, "a file name cannot start with ';' (a comment)");
  if (strlen(v) >= sizeof c->state_rel) return FAIL_AT(c, si, k, "file name too long");
  strcpy(c->state_rel, v);
  return HD_OK;
}

static int hd_scene_set_collisions(ctx *c, int si, int k, const char *v) {
  hd_scene *sc = c->sc;
  if (!strcmp(v, "all") || !strcmp(v, "none")) {
    sc->log_collisions = !strcmp(v, "all") ? HD_LOG_ALL : HD_LOG_NONE;
    sc->log_every = 1;
    return HD_OK;
  }
  char tok[3][64];
  double n;
  if (hd_scene_split(v, tok, 2) != 2 || strcmp(tok[0], "every"))
    return FAIL_AT(c, si, k, "expected all, none or every N");
  if (!hd_scene_parse_num(tok[1], &n) || n != floor(n) || n < 1 || n > (double)LONG_MAX / 2)
    return FAIL_AT(c, si, k, "every N needs a whole number N >= 1");
  sc->log_collisions = HD_LOG_EVERY;
  sc->log_every = (long)n;
  return HD_OK;
}

/* `velocities_at` (k = K_LVEL, cpd) or `velocities_at_time` (k = K_LVELT, times): the two
 * share the list, so only one of them may be given. */
static int hd_scene_set_vel_at(ctx *c, int si, int k, const char *v) {
  hd_scene *sc = c->sc;
  int other = k == K_LVEL ? K_LVELT : K_LVEL;
  const char *unit = k == K_LVEL ? "cpd values" : "times";
  if (hd_scene_key_set(c, si, other))
    return FAIL_AT(c, si, k,
                   "cannot be used together with %s (one list of snapshots, in cpd or in "
                   "time)",
                   hd_scene_keys[other].name);
  int n = 0;
  const char *s = v;
  while (*s) {
    while (*s == ' ' || *s == '\t') s++;
    if (!*s) break;
    size_t len = strcspn(s, " \t");
    char t[64];
    double x;
    if (len >= sizeof t) return FAIL_AT(c, si, k, "not a number: '%.20s...'", s);
    memcpy(t, s, len);
    t[len] = '\0';
    s += len;
    if (!hd_scene_parse_num(t, &x)) return FAIL_AT(c, si, k, "'%s': %s", t, hd_scene_num_why(t));
    if (x < 0) return FAIL_AT(c, si, k, "'%s': %s must be >= 0", t, unit);
    if (n == HD_MAX_VEL_AT)
      return FAIL_AT(c, si, k,
                     "more than %d values (snapshots for a movie or a trajectory: "
                     "frames_every or frames_every_time)",
                     HD_MAX_VEL_AT);
    if (n > 0 && !(x > sc->velocities_at[n - 1]))
      return FAIL_AT(c, si, k, "'%s': values must be strictly ascending", t);
    sc->velocities_at[n++] = x;
  }
  if (n == 0) return FAIL_AT(c, si, k, "missing value: list %s", unit);
  sc->n_velocities_at = n;
  sc->velocities_in_time = k == K_LVELT;
  return HD_OK;
}

static int hd_scene_check_rod_count(ctx *c, int si, int k) {
  if (c->sc->n_rods % 2 != 0)
    return FAIL_AT(c, si, k, "must be even: the rod lengths alternate round the ring");
  return HD_OK;
}

/* 0 is the sampler's default; its grid needs ~(1 + 1/gamma)/step points, at most 5e7 / 64
 * (engine/rods/eps.c), and 1e-300 overflowed the size check and crashed the run (SIGFPE) */
static int hd_scene_check_eps_step(ctx *c, int si, int k) {
  double x = c->sc->rod_eps_step;
  if (x != 0 && !(x >= 1e-5 && x <= 0.5))
    return FAIL_AT(c, si, k, "must be 0 (the default step) or in [1e-5, 0.5]");
  return HD_OK;
}

/* [species NAME] `d` and `m` (the short forms' disks). */
static int hd_scene_set_sp_dm(ctx *c, int si, int k, const char *v) {
  double x;
  int rc = hd_scene_get_ranged(c, si, k, v, 0, &x);
  if (rc) return rc;
  *(k == K_PD ? &c->sp[si - N_SEC].d : &c->sp[si - N_SEC].m) = x;
  return HD_OK;
}

/* ---- the short forms of `shape = ...` ------------------------------------------------------- */

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
static int hd_scene_set_shape(ctx *c, int si, int k, const char *v) {
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
static int hd_scene_set_disks(ctx *c, int si, int k, const char *v) {
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

/* Whether s is a valid species name: [A-Za-z0-9_]{1,31}. */
static int good_name(const char *s) {
  size_t n = strlen(s);
  if (n == 0 || n >= HD_SPECIES_NAME_MAX) return 0;
  for (size_t i = 0; i < n; i++)
    if (!isalnum((unsigned char)s[i]) && s[i] != '_') return 0;
  return 1;
}

/* `alpha_OTHER` (k = K_PALPHAX) or `beta_OTHER` (K_PBETAX): recorded here, its OTHER resolved
 * when the scene is read. */
static int hd_scene_set_alpha_other(ctx *c, int si, int k, const char *v) {
  (void)k;
  sp_parse *p = &c->sp[si - N_SEC];
  sp_pair *q = &p->pair[p->npair - 1]; /* handle() made it the last */
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

/* ---- sections and keys ---------------------------------------------------------------------- */

static int hd_scene_find_sec(const char *s) {
  for (int i = 0; i < N_SEC; i++)
    if (i != S_SPECIES && !strcmp(s, hd_scene_sec_name[i])) return i;
  return -1;
}

/* The NAME of a section "species NAME" (blanks between), or NULL when s is not one. */
static const char *species_part(const char *s) {
  if (strncmp(s, "species", 7) || (s[7] != ' ' && s[7] != '\t')) return NULL;
  s += 7;
  while (*s == ' ' || *s == '\t') s++;
  return s;
}

/* The instance of named species `name`, or -1. */
static int hd_scene_find_species(const ctx *c, const char *name) {
  for (int j = 0; j < c->sc->n_named; j++)
    if (!strcmp(c->sc->named[j].name, name)) return N_SEC + j;
  return -1;
}

static int unknown_section(ctx *c, const char *s) {
  char at[600];
  hd_scene_where(c, c->cur, at, sizeof at);
  if (!strcmp(s, "species"))
    return hd_scene_cfail(c, HD_EINPUT,
                          "%s: [species]: a species section needs a name: [species NAME]", at);
  return hd_scene_cfail(
      c, HD_EINPUT,
      "%s: [%.60s]: unknown section (known: system dimers disks species NAME walls init "
      "run log rods)",
      at, s);
}

static void mark_section(ctx *c, int si) {
  if (!c->present[si]) c->sec_at[si] = c->cur;
  c->present[si] = 1;
}

/* The section instance of a [section] name (a new [species NAME] is created when `create`), or
 * -1 with the error set. */
static int section_index(ctx *c, const char *s, int create) {
  int si = hd_scene_find_sec(s);
  if (si >= 0) return si;
  const char *name = species_part(s);
  if (!name) return unknown_section(c, s), -1;
  char at[600];
  hd_scene_where(c, c->cur, at, sizeof at);
  if (!good_name(name))
    return hd_scene_cfail(c, HD_EINPUT,
                          "%s: [species %.40s]: a species name is 1 to %d letters, digits or _", at,
                          name, HD_SPECIES_NAME_MAX - 1),
           -1;
  if (!strcmp(name, "dimer") || !strcmp(name, "disk") || !strcmp(name, "dimers") ||
      !strcmp(name, "disks"))
    return hd_scene_cfail(
               c, HD_EINPUT,
               "%s: [species %s]: reserved name (the [dimers] and [disks] sections are those "
               "species)",
               at, name),
           -1;
  si = hd_scene_find_species(c, name);
  if (si >= 0 || !create) return si;
  hd_scene *sc = c->sc;
  if (sc->n_named == HD_MAX_SPECIES - 2)
    return hd_scene_cfail(
               c, HD_EINPUT,
               "%s: [species %s]: more than %d [species] sections (HD_MAX_SPECIES %d counts "
               "[dimers] and [disks])",
               at, name, HD_MAX_SPECIES - 2, HD_MAX_SPECIES),
           -1;
  si = N_SEC + sc->n_named;
  hd_scene_species *sp = &sc->named[sc->n_named++];
  memset(sp, 0, sizeof *sp);
  strcpy(sp->name, name);
  sp->line = c->cur.over ? 0 : c->cur.line;
  for (int k = 0; k < N_KEY; k++)
    if (hd_scene_keys[k].sec == S_SPECIES && hd_scene_keys[k].type == KT_REAL)
      *(double *)hd_scene_field(c, si, k) = hd_scene_keys[k].def;
  sp_parse *p = &c->sp[si - N_SEC];
  memset(p, 0, sizeof *p);
  p->d = hd_scene_keys[K_PD].def;
  p->m = hd_scene_keys[K_PM].def;
  p->s = NAN;
  return si;
}

/* Handles `name = value` in section `section` at c->cur. */
static int handle(ctx *c, const char *section, const char *name, const char *value) {
  char at[600], v[96], label[64];
  if (!*section) {
    hd_scene_where(c, c->cur, at, sizeof at);
    hd_scene_shorten(value, v, sizeof v);
    return hd_scene_cfail(c, HD_EINPUT, "%s: %.60s = %s: key outside any [section]", at, name, v);
  }
  int si = section_index(c, section, 0);
  if (si < 0) return c->failed ? c->code : unknown_section(c, section);
  int s = hd_scene_sec_of(si);
  hd_scene_sec_label(c, si, label, sizeof label);
  int k = 0;
  while (k < N_KEY && !(hd_scene_keys[k].sec == s && !strcmp(hd_scene_keys[k].name, name))) k++;
  if (k == N_KEY && s == S_SPECIES && !strncmp(name, "alpha_", 6) && name[6]) k = K_PALPHAX;
  if (k == N_KEY && s == S_SPECIES && !strncmp(name, "beta_", 5) && name[5]) k = K_PBETAX;
  if (k == N_KEY) {
    char known[300] = "";
    for (int j = 0; j < N_KEY; j++)
      if (hd_scene_keys[j].sec == s) {
        strcat(known, " ");
        strcat(known, hd_scene_keys[j].name);
      }
    char nm[64];
    hd_scene_shorten(name, nm, sizeof nm);
    return hd_scene_fail(c, HD_EINPUT, c->cur, si, nm, value, "unknown key (keys of [%s]:%s)",
                         s == S_SPECIES ? "species NAME" : hd_scene_sec_name[s], known);
  }
  loc *prev = &c->key_at[si][k];
  char *val = c->key_val[si][k];
  if (k == K_PALPHAX || k == K_PBETAX) { /* one slot per OTHER and kind */
    sp_parse *p = &c->sp[si - N_SEC];
    int beta = k == K_PBETAX, same = 0;
    const char *other = name + (beta ? 5 : 6), *kind = beta ? "beta" : "alpha";
    if (!good_name(other))
      return hd_scene_fail(c, HD_EINPUT, c->cur, si, name, value,
                           "OTHER of %s_OTHER must be a species name (letters, digits, _)", kind);
    int j = 0;
    while (j < p->npair && (strcmp(p->pair[j].other, other) || p->pair[j].beta != beta))
      same += p->pair[j++].beta == beta;
    if (j == p->npair) {
      if (same == HD_MAX_SPECIES)
        return hd_scene_fail(c, HD_EINPUT, c->cur, si, name, value,
                             "more %s_OTHER keys than species", kind);
      memset(&p->pair[j], 0, sizeof p->pair[j]);
      strcpy(p->pair[j].other, other);
      p->pair[j].beta = beta;
      p->npair++;
    } else if (j != p->npair - 1) { /* hd_scene_set_alpha_other reads the last: make it so */
      sp_pair t = p->pair[j];
      memmove(&p->pair[j], &p->pair[j + 1], (size_t)(p->npair - 1 - j) * sizeof t);
      p->pair[p->npair - 1] = t;
    }
    prev = &p->pair[p->npair - 1].at;
    val = p->pair[p->npair - 1].val;
  }
  if (!c->cur.over && prev->line > 0)
    return hd_scene_fail(c, HD_EINPUT, c->cur, si, name, value,
                         "duplicate key (first set at line %ld)", prev->line);
  if (c->cur.over && prev->over > 0)
    return hd_scene_fail(c, HD_EINPUT, c->cur, si, name, value,
                         "duplicate key (also set by --set %s)", c->over[prev->over - 1]);
  *prev = c->cur;
  hd_scene_shorten(value, val, 96);
  /* a file's value that a --set replaces is not read: the override mends a bad line */
  for (int i = 0; !c->cur.over && i < c->n_over; i++)
    if (hd_scene_override_sets(c->over[i], label, name)) return HD_OK;
  return hd_scene_set_value(c, si, k, value);
}

static int on_key(void *user, const char *section, const char *name, const char *value) {
  ctx *c = user;
  if (c->failed) return 0;
  return handle(c, section, name, value) == HD_OK;
}

/* Checks a `[section]` line (leading blanks already gone). */
static int section_line(ctx *c, const char *line) {
  const char *close = strchr(line, ']');
  char at[600];
  hd_scene_where(c, c->cur, at, sizeof at);
  if (!close) {
    return hd_scene_cfail(c, HD_EINPUT, "%s: malformed section header: no ']'", at);
  }
  const char *r = close + 1;
  while (*r == ' ' || *r == '\t') r++;
  if (*r && *r != '\n' && *r != '\r' && *r != ';' && *r != '#') {
    return hd_scene_cfail(c, HD_EINPUT,
                          "%s: text after the [section] header: put each key on its own line", at);
  }
  char name[64];
  size_t len = (size_t)(close - line - 1);
  if (len >= sizeof name) len = sizeof name - 1;
  memcpy(name, line + 1, len);
  name[len] = '\0';
  int si = section_index(c, name, 1);
  if (si < 0) return c->code;
  mark_section(c, si);
  c->cur_si = si;
  return HD_OK;
}

/* fgets-like reader for ini_parse_stream: one physical line per call, counted. */
static char *reader(char *str, int num, void *stream) {
  ctx *c = stream;
  if (c->failed || c->p >= c->end) return NULL;
  const char *s = c->p;
  const char *nl = memchr(s, '\n', (size_t)(c->end - s));
  const char *stop = nl ? nl + 1 : c->end;
  c->p = stop;
  c->cur.line = ++c->lineno;
  c->cur.over = 0;
  if (c->lineno == 1 && stop - s >= 3 && !memcmp(s, "\xEF\xBB\xBF", 3)) s += 3;
  /* every blank libinih skips at a line's start (\r \v \f too): "\v[disks]" was parsed as a
   * section by libinih but not seen as one here, so its keys took effect while the section was
   * left out of the canonical text (and a resume ran without them) */
  while (s < stop && (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\v' || *s == '\f')) s++;
  size_t len = (size_t)(stop - s);
  size_t body = len; /* the line without its end (\n or \r\n): what HD_SCENE_MAX_LINE bounds */
  if (body > 0 && s[body - 1] == '\n') body--;
  if (body > 0 && s[body - 1] == '\r') body--;
  if (len + 1 > (size_t)num || body > HD_SCENE_MAX_LINE) {
    char at[600];
    hd_scene_where(c, c->cur, at, sizeof at);
    hd_scene_cfail(c, HD_EINPUT, "%s: line too long (max %d bytes)", at, HD_SCENE_MAX_LINE);
    return NULL;
  }
  memcpy(str, s, len);
  str[len] = '\0';
  if (str[0] == '[' && section_line(c, str)) return NULL;
  /* in `disks = ...` a blank before ';' would start a libinih comment and drop the disks after
   * it without a word */
  if (c->cur_si >= N_SEC && !strncmp(str, "disks", 5) && strchr(" \t=:", str[5]) &&
      (strstr(str, " ;") || strstr(str, "\t;"))) {
    char at[600];
    hd_scene_where(c, c->cur, at, sizeof at);
    hd_scene_cfail(
        c, HD_EINPUT,
        "%s: [species %s] disks: a blank before ';' starts a comment: write x y d m; x y d m", at,
        c->sc->named[c->cur_si - N_SEC].name);
    return NULL;
  }
  return str;
}

/* Parses the scene text (c->p .. c->end). */
static int hd_scene_parse_text(ctx *c) {
  int saved = ini_max_line;
  ini_max_line = HD_SCENE_MAX_LINE + 3;
  c->cur_si = -1;
  int r = ini_parse_stream(reader, c, on_key, c);
  ini_max_line = saved;
  if (c->failed) return c->code;
  if (r != 0) {
    if (r < 0) return hd_scene_cfail(c, HD_ENOMEM, "%s: out of memory while parsing", c->name);
    return hd_scene_cfail(c, HD_EINPUT,
                          "%s:%d: malformed line: expected [section], key = value or a comment",
                          c->name, r);
  }
  return HD_OK;
}

static char *hd_scene_trim(char *s) {
  while (*s == ' ' || *s == '\t') s++;
  char *e = s + strlen(s);
  while (e > s && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r' || e[-1] == '\n')) *--e = '\0';
  return s;
}

/* Splits the override in buf ("SECTION.KEY=VALUE", changed in place) into its trimmed parts;
 * "species.NAME.KEY=VALUE" gives the section "species NAME", written to secbuf.  0 if it has no
 * '=' or no '.' before it (or, for species, no second '.'). */
static int split_override(char *buf, char *secbuf, size_t n, char **sec, char **key, char **val) {
  char *eq = strchr(buf, '=');
  char *dot = eq ? memchr(buf, '.', (size_t)(eq - buf)) : NULL;
  if (!eq || !dot) return 0;
  *dot = *eq = '\0';
  *sec = hd_scene_trim(buf), *key = hd_scene_trim(dot + 1), *val = hd_scene_trim(eq + 1);
  if (!strcmp(*sec, "species")) {
    char *dot2 = strchr(*key, '.');
    if (!dot2) return 0;
    *dot2 = '\0';
    snprintf(secbuf, n, "species %s", hd_scene_trim(*key));
    *sec = secbuf;
    *key = hd_scene_trim(dot2 + 1);
  }
  return 1;
}

int hd_scene_override_sets(const char *over, const char *section, const char *key) {
  char buf[HD_SCENE_MAX_LINE + 1], secbuf[HD_SCENE_MAX_LINE + 16], *sec, *k, *val;
  if (strlen(over) > HD_SCENE_MAX_LINE) return 0;
  strcpy(buf, over);
  return split_override(buf, secbuf, sizeof secbuf, &sec, &k, &val) && !strcmp(sec, section) &&
         !strcmp(k, key);
}

/* Applies override i ("SECTION.KEY=VALUE"). */
static int hd_scene_apply_override(ctx *c, int i) {
  char buf[HD_SCENE_MAX_LINE + 1], secbuf[HD_SCENE_MAX_LINE + 16], at[600];
  c->cur.line = 0;
  c->cur.over = i + 1;
  hd_scene_where(c, c->cur, at, sizeof at);
  if (strlen(c->over[i]) > HD_SCENE_MAX_LINE) {
    return hd_scene_cfail(c, HD_EINPUT, "--set: value too long (max %d bytes)", HD_SCENE_MAX_LINE);
  }
  strcpy(buf, c->over[i]);
  char *sec, *key, *val;
  if (!split_override(buf, secbuf, sizeof secbuf, &sec, &key, &val))
    return hd_scene_cfail(c, HD_EINPUT, "%s: expected SECTION.KEY=VALUE (species.NAME.KEY=VALUE)",
                          at);
  int si = section_index(c, sec, 1);
  if (si < 0) return c->code;
  mark_section(c, si);
  return handle(c, sec, key, val);
}

/* ---- checks of the whole ------------------------------------------------------------------- */

/* A snapshot that cannot be taken is refused at set-up: a time past stop_time, a cpd past
 * stop_cpd (a list in the other unit than the stop cannot be checked before the run; the run's
 * message says what it did not take). */
static int check_vel_at(ctx *c) {
  const hd_scene *sc = c->sc;
  if (sc->n_velocities_at == 0) return HD_OK;
  int k = sc->velocities_in_time ? K_LVELT : K_LVEL;
  double last = sc->velocities_at[sc->n_velocities_at - 1];
  double stop = sc->velocities_in_time ? sc->stop_time : sc->stop_cpd;
  if (stop > 0 && last > stop)
    return FAIL_KEY(c, k, "%.17g is past %s = %.17g: that snapshot would never be taken", last,
                    sc->velocities_in_time ? "stop_time" : "stop_cpd", stop);
  return HD_OK;
}

/* Body counts of the scene (dimers, disks and each named species) summed. */
static long hd_scene_body_count(const hd_scene *sc) {
  long n = sc->n_dimers + sc->n_disks;
  for (int j = 0; j < sc->n_named; j++) n += sc->named[j].count;
  return n;
}

/* Resolves, checks and counts the state file. */
static int check_state(ctx *c) {
  hd_scene *sc = c->sc;
  int any_count = hd_scene_key_set(c, S_DIMERS, K_DCOUNT) || hd_scene_key_set(c, S_DISKS, K_SCOUNT);
  for (int j = 0; j < sc->n_named; j++) any_count |= hd_scene_key_set(c, N_SEC + j, K_PCOUNT);
  if (c->mode != M_RUN) { /* the run's bodies are in its checkpoint; the counts are in the text */
    if (c->mode == M_STORED && !any_count)
      return FAIL_KEY(c, K_STATE, "a stored scene gives the counts of its bodies");
    snprintf(sc->state_file, sizeof sc->state_file, "%s", c->state_rel);
    return HD_OK;
  }
  char joined[2 * HD_PATH_MAX + 2];
  if (c->state_rel[0] == '/')
    snprintf(joined, sizeof joined, "%s", c->state_rel);
  else
    snprintf(joined, sizeof joined, "%s/%s", sc->dir, c->state_rel);
  char *real = realpath(joined, NULL);
  if (!real)
    return hd_scene_fail(c, HD_EIO, c->key_at[S_INIT][K_STATE], S_INIT, "state",
                         c->key_val[S_INIT][K_STATE], "cannot read state file '%s': %s", joined,
                         strerror(errno));
  if (strlen(real) >= sizeof sc->state_file) {
    free(real);
    return FAIL_KEY(c, K_STATE, "path too long");
  }
  struct stat stt;
  if (stat(real, &stt) == 0 && S_ISDIR(stt.st_mode)) {
    free(real);
    return FAIL_KEY(c, K_STATE, "is a directory, not a state file");
  }
  /* the run's scene text stores the path as a value: one that INI would cut short (a comment
   * after " ;" or " #", blanks at an end) could not be read back by a re-run */
  size_t rl = strlen(real);
  if (strstr(real, " ;") || strstr(real, " #") || strchr(real, '\n') || real[rl - 1] == ' ' ||
      real[rl - 1] == '\t') {
    free(real);
    return FAIL_KEY(c, K_STATE,
                    "its path holds ' ;', ' #' or a blank at its end, which a scene "
                    "cannot store: rename the file or folder");
  }
  strcpy(sc->state_file, real);
  free(real);
  hd_state_row *rows = NULL;
  long n = 0, have[HD_MAX_SPECIES] = {0};
  int rc = hd_state_csv_read_species(sc->state_file, sc, &rows, &n, c->err);
  if (rc) {
    c->failed = 1;
    c->code = rc;
    return rc;
  }
  for (long i = 0; i < n; i++) have[rows[i].species]++;
  free(rows);
  for (int j = 0; j < 2 + sc->n_named; j++) {
    int si = j == 0 ? S_DIMERS : j == 1 ? S_DISKS : N_SEC + j - 2;
    int k = j == 0 ? K_DCOUNT : j == 1 ? K_SCOUNT : K_PCOUNT;
    long *cnt = j == 0 ? &sc->n_dimers : j == 1 ? &sc->n_disks : &sc->named[j - 2].count;
    const char *kind = j == 0 ? "dimer" : j == 1 ? "disk" : sc->named[j - 2].name;
    if (hd_scene_key_set(c, si, k)) {
      if (*cnt != have[j])
        return FAIL_AT(c, si, k, "the state file %s holds %ld %s rows", c->state_rel, have[j],
                       kind);
    } else if (have[j] > 0) {
      *cnt = have[j];
      c->present[si] = 1;
    }
  }
  return HD_OK;
}

/* The largest body of the scene (the lattice's cell edge). */
static double largest_body(const hd_scene *sc) {
  double ext = 0;
  if (sc->n_dimers > 0) ext = sc->dimer_a + sc->dimer_d;
  if (sc->n_disks > 0 && sc->disk_sigma > ext) ext = sc->disk_sigma;
  for (int j = 0; j < sc->n_named; j++)
    if (sc->named[j].count > 0) ext = fmax(ext, hd_species_extent(&sc->named[j]));
  return ext;
}

/* The box: given, or derived from area_fraction; then (run is set) does everything fit. */
static int check_box(ctx *c, int run) {
  hd_scene *sc = c->sc;
  long nb = hd_scene_body_count(sc);
  int kb = hd_scene_key_set(c, S_SYSTEM, K_BOX) ? K_BOX : K_AREA;
  if (hd_scene_key_set(c, S_SYSTEM, K_BOX) && hd_scene_key_set(c, S_SYSTEM, K_AREA)) {
    loc a = c->key_at[S_SYSTEM][K_AREA], b = c->key_at[S_SYSTEM][K_BOX];
    int later = a.over > b.over || (a.over == b.over && a.line > b.line) ? K_AREA : K_BOX;
    return FAIL_KEY(c, later, "give either box or area_fraction, not both");
  }
  if (nb == 0) {
    if (run && hd_scene_key_set(c, S_SYSTEM, K_AREA))
      return FAIL_KEY(c, K_AREA, "needs bodies: a [dimers], [disks] or [species] count > 0");
    return HD_OK;
  }
  if (!hd_scene_key_set(c, S_SYSTEM, K_BOX) && !hd_scene_key_set(c, S_SYSTEM, K_AREA))
    return run ? hd_scene_fail(c, HD_EINPUT,
                               c->present[S_SYSTEM] ? c->sec_at[S_SYSTEM] : (loc){0, 0}, S_SYSTEM,
                               "box", NULL, "missing: give box = Lx Ly or area_fraction = eta")
               : HD_OK;
  sc->box_line = c->key_at[S_SYSTEM][kb].over ? 0 : c->key_at[S_SYSTEM][kb].line;
  double area = hd_scene_covered_area(sc);
  if (kb == K_AREA) sc->box_x = sc->box_y = sqrt(area / sc->area_fraction);
  if (!run) return HD_OK;
  if (!isfinite(sc->box_x) || !isfinite(sc->box_y)) /* the bodies' area overflowed (d ~ 1e160) */
    return FAIL_KEY(c, kb, "gives a box that is not a finite number (the bodies cover %.6g)", area);
  double ext = largest_body(sc);
  double edge = fmin(sc->box_x, sc->box_y);
  if (edge < ext)
    return FAIL_KEY(c, kb, "box too small: edge %.6g is shorter than the largest body (%.6g)", edge,
                    ext);
  if (!(sc->box_x * sc->box_y >= DBL_MIN))
    /* 1e-300 x 1e-300: the area underflows, and the covered fraction would be 0 / 0 (bodies
     * whose own area underflows cover 0 of a box that has one: that is fine) */
    return FAIL_KEY(c, kb,
                    "box %.6g x %.6g: its area is below the smallest normal double: rescale the "
                    "lengths",
                    sc->box_x, sc->box_y);
  double frac = area / (sc->box_x * sc->box_y);
  if (sc->placement == HD_PLACE_RANDOM && frac > HD_RANDOM_MAX_FRACTION)
    return FAIL_KEY(c, kb,
                    "box too dense: the bodies cover %.4g of it, above %g for placement = random "
                    "(use placement = lattice or a larger box)",
                    frac, HD_RANDOM_MAX_FRACTION);
  if (sc->placement == HD_PLACE_LATTICE) {
    double nx = floor(sc->box_x / ext), ny = floor(sc->box_y / ext);
    if (nx * ny < (double)nb)
      return FAIL_KEY(c, kb,
                      "box too dense for placement = lattice: %.0f x %.0f cells of edge %.6g "
                      "hold fewer than the %ld bodies",
                      nx, ny, ext, nb);
  }
  return HD_OK;
}

/* Disks of one body touch or overlap when their centres are at most (d_i + d_j)/2 apart, up to
 * this relative slack (the short forms' touching disks are computed with cos and sin). */
#define HD_TOUCH_SLACK 1e-12

/* The moment of inertia of a body of species sp about its centre of mass (the engine's
 * sum m_k |o_k|^2), and its mass in *mass if not NULL. */
static double hd_scene_species_inertia(const hd_scene_species *sp, double *mass) {
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

/* [init] temperature against the range of doubles: the drawn speeds (v^2 ~ T / M), spins
 * (w^2 ~ T / I) and the total energy (~ N T) must stay below 1e300 (temperature = 1e300 with
 * a dimer of a = 1e-9 gave w^2 = 2e318, NaN energies that the database refused). */
static int check_thermal(ctx *c) {
  const hd_scene *sc = c->sc;
  double T = sc->temperature, worst = 0;
  const char *what = "";
  if (sc->n_dimers > 0) {
    worst = T / (2 * sc->dimer_m), what = "[dimers] v^2 ~ T / 2m";
    double I = 0.5 * sc->dimer_m * sc->dimer_a * sc->dimer_a;
    if (I > 0 && T / I > worst) worst = T / I, what = "[dimers] w^2 ~ T / I";
  }
  if (sc->n_disks > 0 && T / sc->disk_mass > worst)
    worst = T / sc->disk_mass, what = "[disks] v^2 ~ T / mass";
  for (int j = 0; j < sc->n_named; j++) {
    if (sc->named[j].count == 0) continue;
    double M, I = hd_scene_species_inertia(&sc->named[j], &M);
    if (T / M > worst) worst = T / M, what = "a [species] v^2 ~ T / M";
    if (I > 0 && T / I > worst) worst = T / I, what = "a [species] w^2 ~ T / I";
  }
  double e = T * (double)hd_scene_body_count(sc);
  if (!(worst <= 1e300 && e <= 1e300))
    return FAIL_KEY(c, K_TEMP,
                    "the drawn velocities leave the range of doubles (%s = %g, energy N T = %g; "
                    "at most 1e300): lower the temperature or scale the masses",
                    what, worst, e);
  return HD_OK;
}

/* Why a moment of inertia must be within [HD_MIN_INERTIA, 1 / HD_MIN_INERTIA]. */
static const char hd_scene_inertia_why[] =
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
static int hd_scene_build_species(ctx *c, int j) {
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
  /* connected: every disk reached from disk 0 through touching or overlapping pairs */
  int seen[HD_MAX_BODY_DISKS] = {1}, stack[HD_MAX_BODY_DISKS] = {0}, top = 1;
  while (top > 0) {
    int a = stack[--top];
    for (int b = 0; b < sp->ndisk; b++) {
      double gap = hypot(sp->x[a] - sp->x[b], sp->y[a] - sp->y[b]);
      if (!seen[b] && gap <= (sp->d[a] + sp->d[b]) / 2 * (1 + HD_TOUCH_SLACK)) {
        seen[b] = 1;
        stack[top++] = b;
      }
    }
  }
  int key = has_disks ? K_PDISKS : K_PSHAPE;
  for (int b = 0; b < sp->ndisk; b++)
    if (!seen[b])
      return FAIL_AT(c, si, key,
                     "disk %d at (%g, %g) is not connected to disk 1: the disks of a body must "
                     "touch or overlap (centres at most (d_i + d_j)/2 apart)",
                     b + 1, sp->x[b], sp->y[b]);
  return species_bounds(c, j, key);
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
static int hd_scene_fill_pairs(ctx *c) {
  int rc = fill_pairs_of(c, 0);
  if (rc || (rc = fill_pairs_of(c, 1))) return rc;
  hd_scene *sc = c->sc;
  sc->rough = sc->wall_beta > -1;
  for (int i = 0; i < 2 + sc->n_named; i++)
    for (int j = 0; j < 2 + sc->n_named; j++) sc->rough |= sc->beta_pair[i][j] > -1;
  return HD_OK;
}

/* A [rods] scene: a ring of count rods, nothing 2D. */
static int check_rods(ctx *c) {
  hd_scene *sc = c->sc;
  if (!hd_scene_key_set(c, S_RODS, K_RCOUNT))
    return hd_scene_fail(c, HD_EINPUT, c->sec_at[S_RODS], S_RODS, "count", NULL,
                         "missing: required in [rods]");
  static const int other[4] = {S_DIMERS, S_DISKS, S_WALLS, S_INIT};
  for (int j = 0; j < 4; j++)
    if (c->present[other[j]])
      return hd_scene_fail(
          c, HD_EINPUT, c->sec_at[other[j]], other[j], NULL, NULL,
          "cannot be combined with [rods] (the ring has its own count and temperature)");
  for (int j = 0; j < sc->n_named; j++)
    return hd_scene_fail(
        c, HD_EINPUT, c->sec_at[N_SEC + j], N_SEC + j, NULL, NULL,
        "cannot be combined with [rods] (the ring has its own count and temperature)");
  if (hd_scene_key_set(c, S_SYSTEM, K_BOX))
    return FAIL_KEY(c, K_BOX, "not used with [rods]: the ring length is the rod count");
  if (hd_scene_key_set(c, S_SYSTEM, K_AREA))
    return FAIL_KEY(c, K_AREA, "not used with [rods]: the ring length is the rod count");
  if (!hd_scene_key_set(c, S_RODS, K_REPS))
    sc->rod_eps = sc->rod_gamma;
  else if (sc->rod_model != 1)
    return FAIL_KEY(c, K_REPS, "only with model = constant");
  /* table unset: the balanced table wherever it applies (issue 16: the direct sampler then
   * lowered the stationary E_kin by ~3.5 %, the balanced table by 0.2 %; refined since issue 25,
   * the direct sampler is within ~0.3 % but ~10x slower per collision) */
  if (!hd_scene_key_set(c, S_RODS, K_RTABLE))
    sc->rod_table = sc->rod_model != 1 && !sc->rod_unequal && sc->rod_gamma < 1;
  if (sc->rod_table && sc->rod_unequal)
    return FAIL_KEY(c, K_RTABLE,
                    "the table is for equal bath temperatures: not with baths = unequal");
  if (c->mode != M_READ && sc->rod_model != 1 && sc->rod_gamma < 1) {
    /* the sampler the ring builds (rods.c) */
    hd_eps_opts o;
    hd_rods_eps_opts(sc->rod_eps_step, &o);
    if (!hd_eps_grid_fits(sc->rod_gamma, &o))
      return FAIL_KEY(c, K_RGAMMA,
                      "too small for the eps sampler's grid at eps_step %g (about (1 + 1/gamma) / "
                      "eps_step x %d points, at most 5e7): a larger gamma or eps_step",
                      o.step, o.adapt);
  }
  if (c->mode == M_READ) return HD_OK;
  if (!(sc->stop_time > 0 || sc->stop_events > 0 || sc->stop_cpd > 0))
    return hd_scene_fail(c, HD_EINPUT, c->present[S_RUN] ? c->sec_at[S_RUN] : (loc){0, 0}, S_RUN,
                         NULL, NULL, "no stop condition: set stop_time, stop_events or stop_cpd");
  return check_vel_at(c);
}

/* [log] frames_every / frames_every_time: one of them, a bounded count under the cap. */
static int check_frames(ctx *c) {
  hd_scene *sc = c->sc;
  if (sc->frames_every > 0 && sc->frames_every_time > 0)
    return FAIL_KEY(c, K_LFRAMEST, "give frames_every (cpd) or frames_every_time, not both");
  if (sc->frames_every_time > 0 && !(sc->stop_time > 0))
    return FAIL_KEY(c, K_LFRAMEST,
                    "needs [run] stop_time (frames are taken at exact times up to it; by cpd: "
                    "frames_every)");
  if (hd_scene_key_set(c, S_LOG, K_LFRAMESMB) &&
      !(sc->frames_every > 0 || sc->frames_every_time > 0))
    return FAIL_KEY(c, K_LFRAMESMB, "set without frames_every or frames_every_time");
  double nf = hd_scene_frames_estimate(sc);
  if (nf > 0) {
    double mb = nf * hd_scene_frame_bytes(sc) / 1e6;
    int k = sc->frames_every > 0 ? K_LFRAMES : K_LFRAMEST;
    /* frames by cpd in a run that stop_time may end first: a bound, not a count; the run
     * stops taking frames at the cap (hd_run.c) */
    if (mb > sc->frames_max_mb && !(sc->frames_every > 0 && sc->stop_time > 0))
      return FAIL_KEY(c, k,
                      "%.0f frames of %ld bodies take ~%.4g MB, more than frames_max_mb = %g: "
                      "take fewer frames or raise frames_max_mb",
                      nf, hd_scene_bodies(sc), mb, sc->frames_max_mb);
  }
  return HD_OK;
}

static int hd_scene_check_all(ctx *c) {
  hd_scene *sc = c->sc;
  int rc, run = c->mode != M_READ;
  if (c->present[S_RODS]) return (rc = check_rods(c)) ? rc : run ? check_frames(c) : HD_OK;
  if (!hd_scene_key_set(c, S_DISKS, K_SALPHAD)) sc->disk_alpha_dimer = sc->disk_alpha;
  if (!hd_scene_key_set(c, S_DISKS, K_SBETAD)) sc->disk_beta_dimer = sc->disk_beta;
  for (int j = 0; j < sc->n_named; j++)
    if ((rc = hd_scene_build_species(c, j))) return rc;
  if ((rc = hd_scene_fill_pairs(c))) return rc;
  if (hd_scene_key_set(c, S_INIT, K_STATE)) {
    if (hd_scene_key_set(c, S_INIT, K_PLACE))
      return FAIL_KEY(c, K_STATE,
                      "cannot be used together with placement (state gives every "
                      "body)");
    sc->placement = HD_PLACE_STATE;
    if ((rc = check_state(c))) return rc;
  } else if (run && !(sc->temperature > 0)) {
    return FAIL_KEY(c, K_TEMP, "must be > 0 (0 only with a state file)");
  }
  if (!run) return check_box(c, 0);
  static const int req_sec[3] = {S_DIMERS, S_DISKS, S_WALLS};
  static const int req_key[3] = {K_DCOUNT, K_SCOUNT, K_WSIDES};
  for (int j = 0; j < 3; j++)
    if (c->present[req_sec[j]] && !hd_scene_key_set(c, req_sec[j], req_key[j]) &&
        !(req_sec[j] != S_WALLS && sc->placement == HD_PLACE_STATE))
      return hd_scene_fail(c, HD_EINPUT, c->sec_at[req_sec[j]], req_sec[j],
                           hd_scene_keys[req_key[j]].name, NULL, "missing: required in [%s]",
                           hd_scene_sec_name[req_sec[j]]);
  for (int j = 0; j < sc->n_named; j++)
    if (!hd_scene_key_set(c, N_SEC + j, K_PCOUNT) && sc->placement != HD_PLACE_STATE)
      return hd_scene_fail(c, HD_EINPUT, c->sec_at[N_SEC + j], N_SEC + j, "count", NULL,
                           "missing: required in [species %s]", sc->named[j].name);
  if (sc->n_dimers > 0 && sc->dimer_a > 0 && sc->dimer_a < HD_MIN_BOND * sc->dimer_d)
    return FAIL_KEY(c, K_DA,
                    "must be 0 or at least %g d = %g: a shorter bond is lost in the round-off of "
                    "the positions (a = 0 is a dimer without lever arm, a disk of mass 2m)",
                    HD_MIN_BOND, HD_MIN_BOND * sc->dimer_d);
  double inertia = 0.5 * sc->dimer_m * sc->dimer_a * sc->dimer_a;
  if (sc->n_dimers > 0 && sc->dimer_a > 0 &&
      !(inertia >= HD_MIN_INERTIA && inertia <= 1 / HD_MIN_INERTIA))
    return FAIL_KEY(c, K_DA, "the moment of inertia m a^2 / 2 = %g is outside [%g, %g]: %s",
                    inertia, HD_MIN_INERTIA, 1 / HD_MIN_INERTIA, hd_scene_inertia_why);
  if (sc->placement != HD_PLACE_STATE && (rc = check_thermal(c))) return rc;
  if ((rc = check_box(c, 1))) return rc;
  if (!(sc->stop_time > 0 || sc->stop_events > 0 || sc->stop_cpd > 0))
    return hd_scene_fail(c, HD_EINPUT, c->present[S_RUN] ? c->sec_at[S_RUN] : (loc){0, 0}, S_RUN,
                         NULL, NULL, "no stop condition: set stop_time, stop_events or stop_cpd");
  if (hd_scene_body_count(sc) == 1 && !(sc->stop_time > 0) && !(sc->walls && sc->stop_events > 0))
    /* it has no pair collision ever (cpd stays 0), and without walls no collision at all: the
     * run would go on for ever */
    return hd_scene_fail(
        c, HD_EINPUT, c->present[S_RUN] ? c->sec_at[S_RUN] : (loc){0, 0}, S_RUN, NULL, NULL,
        "one body alone never collides with another: stop it with stop_time (stop_events "
        "counts only its wall collisions, and a drawn velocity of one body is 0: it rests "
        "or spins in place)");
  if ((rc = check_frames(c))) return rc;
  return check_vel_at(c);
}

/* ---- canonical text ------------------------------------------------------------------------ */

struct sbuf {
  char *s;
  size_t n, cap;
  int oom;
};

static __attribute__((format(printf, 2, 3))) void hd_scene_put(sbuf *b, const char *fmt, ...) {
  if (b->oom) return;
  va_list ap;
  va_start(ap, fmt);
  int need = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (need < 0) return;
  if (b->n + (size_t)need + 1 > b->cap) {
    size_t cap = 2 * (b->n + (size_t)need + 1) + 256;
    char *s = realloc(b->s, cap);
    if (!s) {
      b->oom = 1;
      return;
    }
    b->s = s;
    b->cap = cap;
  }
  va_start(ap, fmt);
  vsnprintf(b->s + b->n, b->cap - b->n, fmt, ap);
  va_end(ap);
  b->n += (size_t)need;
}

/* "key = x\n" */
static void hd_scene_put_kv(sbuf *b, const char *key, double x) {
  char v[40];
  hd_scene_shortest(x, v, sizeof v);
  hd_scene_put(b, "%s = %s\n", key, v);
}

static int hd_scene_show_beta_dimer(const ctx *c, int si) {
  (void)si; /* beta_dimer defaults to beta: written when either is not smooth */
  return c->sc->disk_beta > -1 || c->sc->disk_beta_dimer > -1;
}
static int hd_scene_show_set(const ctx *c, int si) {
  (void)si;
  return hd_scene_key_set(c, S_SYSTEM, K_AREA);
}
static int hd_scene_show_box(const ctx *c, int si) {
  (void)si;
  return hd_scene_key_set(c, S_SYSTEM, K_BOX) && !hd_scene_key_set(c, S_SYSTEM, K_AREA);
}
static int hd_scene_show_not_state(const ctx *c, int si) {
  (void)si;
  return c->sc->placement != HD_PLACE_STATE;
}
static int hd_scene_show_state(const ctx *c, int si) {
  return !hd_scene_show_not_state(c, si);
}
/* (always, in a scene to run: [walls] requires sides; not in one only read without them) */
static int hd_scene_show_sides(const ctx *c, int si) {
  (void)si;
  return c->sc->walls != 0;
}
static int hd_scene_show_vel(const ctx *c, int si) {
  (void)si;
  return c->sc->n_velocities_at > 0 && !c->sc->velocities_in_time;
}
static int hd_scene_show_vel_time(const ctx *c, int si) {
  (void)si;
  return c->sc->n_velocities_at > 0 && c->sc->velocities_in_time;
}
/* only when asked for: the text of a run without frames is as before */
static int hd_scene_show_frames(const ctx *c, int si) {
  (void)si;
  return c->sc->frames_every > 0 || c->sc->frames_every_time > 0;
}
static int hd_scene_show_rod_eps(const ctx *c, int si) {
  (void)si;
  return c->sc->rod_model == 1;
}
static int hd_scene_show_short_shape(const ctx *c, int si) {
  return c->sp[si - N_SEC].form != NULL;
}
static int hd_scene_show_explicit(const ctx *c, int si) {
  return !hd_scene_show_short_shape(c, si);
}

static void hd_scene_put_area(const ctx *c, int si, int k, sbuf *b) {
  (void)si, (void)k;
  char v1[40], v2[40];
  hd_scene_put_kv(b, "area_fraction", c->sc->area_fraction);
  hd_scene_shortest(c->sc->box_x, v1, sizeof v1);
  hd_scene_shortest(c->sc->box_y, v2, sizeof v2);
  hd_scene_put(b, "; box = %s %s (from area_fraction)\n", v1, v2);
}
static void hd_scene_put_box(const ctx *c, int si, int k, sbuf *b) {
  (void)si, (void)k;
  char v1[40], v2[40];
  hd_scene_shortest(c->sc->box_x, v1, sizeof v1);
  hd_scene_shortest(c->sc->box_y, v2, sizeof v2);
  hd_scene_put(b, "box = %s %s\n", v1, v2);
}
static void hd_scene_put_sides(const ctx *c, int si, int k, sbuf *b) {
  (void)si, (void)k;
  hd_scene_put(b, "sides =");
  for (int j = 0; j < 4; j++)
    if (c->sc->walls & (1u << j)) hd_scene_put(b, " %s", hd_scene_wall_name[j]);
  hd_scene_put(b, "\n");
}
static void hd_scene_put_state(const ctx *c, int si, int k, sbuf *b) {
  (void)si, (void)k;
  hd_scene_put(b, "state = %s\n", c->sc->state_file);
}
static void hd_scene_put_collisions(const ctx *c, int si, int k, sbuf *b) {
  (void)si, (void)k;
  const hd_scene *sc = c->sc;
  if (sc->log_collisions == HD_LOG_EVERY)
    hd_scene_put(b, "collisions = every %ld\n", sc->log_every);
  else
    hd_scene_put(b, "collisions = %s\n", sc->log_collisions == HD_LOG_NONE ? "none" : "all");
}
static void hd_scene_put_vel(const ctx *c, int si, int k, sbuf *b) {
  (void)si, (void)k;
  const hd_scene *sc = c->sc;
  char v[40];
  hd_scene_put(b, "%s =", sc->velocities_in_time ? "velocities_at_time" : "velocities_at");
  for (int i = 0; i < sc->n_velocities_at; i++) {
    hd_scene_shortest(sc->velocities_at[i], v, sizeof v);
    hd_scene_put(b, " %s", v);
  }
  hd_scene_put(b, "\n");
}
static void hd_scene_put_shape(const ctx *c, int si, int k, sbuf *b) {
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
static void hd_scene_put_sp_dm(const ctx *c, int si, int k, sbuf *b) {
  hd_scene_put_kv(b, hd_scene_keys[k].name, k == K_PD ? c->sp[si - N_SEC].d : c->sp[si - N_SEC].m);
}
static void hd_scene_put_disks(const ctx *c, int si, int k, sbuf *b) {
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
/* alpha_OTHER of every pair with a species written before this one: each pair once;
 * beta_OTHER (k = K_PBETAX) likewise, where it is not the default (the smaller `beta`) */
static void hd_scene_put_pairs(const ctx *c, int si, int k, sbuf *b) {
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

/* Writes key k of section si as the canonical text has it. */
static void put_key(const ctx *c, int si, int k, sbuf *b) {
  const key_def *kd = &hd_scene_keys[k];
  const void *p = hd_scene_field(c, si, k);
  if (kd->show && !kd->show(c, si)) return;
  if (kd->if_pos && !(*(const double *)p > 0)) return;
  if (kd->if_not_def && *(const double *)p == kd->def) return;
  if (kd->put) {
    kd->put(c, si, k, b);
    return;
  }
  switch (kd->type) {
  case KT_REAL:
  case KT_WHOLE:
    hd_scene_put_kv(b, kd->name, *(const double *)p);
    break;
  case KT_LONG:
    hd_scene_put(b, "%s = %ld\n", kd->name, *(const long *)p);
    break;
  case KT_U64:
    hd_scene_put(b, "%s = %llu\n", kd->name, *(const unsigned long long *)p);
    break;
  case KT_BOOL:
  case KT_ENUM:
    hd_scene_put(b, "%s = %s\n", kd->name, kd->names[*(const int *)p]);
    break;
  case KT_CUSTOM:
    break;
  }
}

static void put_section(const ctx *c, int si, sbuf *b) {
  char label[64];
  hd_scene_sec_label(c, si, label, sizeof label);
  hd_scene_put(b, "[%s]\n", label);
  for (int k = 0; k < N_KEY; k++)
    if (hd_scene_keys[k].sec == hd_scene_sec_of(si)) put_key(c, si, k, b);
}

static char *hd_scene_canonical_text(const ctx *c) {
  sbuf b = {0};
  hd_scene_put(&b, "%s", "");
  for (int s = 0; s < N_SEC; s++) {
    if (s == S_SPECIES)
      for (int j = 0; j < c->sc->n_named; j++) put_section(c, N_SEC + j, &b);
    else if (c->present[s])
      put_section(c, s, &b);
  }
  if (b.oom) {
    free(b.s);
    return NULL;
  }
  return b.s;
}

/* ---- docs/scene-keys.md -------------------------------------------------------------------- */

/* The generated table of section s. */
static void doc_table(int s, sbuf *b) {
  hd_scene_put(b, "| key | default | range | meaning |\n|---|---|---|---|\n");
  for (int k = 0; k < N_KEY; k++) {
    const key_def *kd = &hd_scene_keys[k];
    if (kd->sec != s) continue;
    char def[80], range[320];
    if (kd->doc_def)
      snprintf(def, sizeof def, "%s", kd->doc_def);
    else if (kd->type == KT_BOOL || kd->type == KT_ENUM)
      snprintf(def, sizeof def, "`%s`", kd->names[(int)kd->def]);
    else
      hd_scene_shortest(kd->def, def, sizeof def);
    if (kd->doc_forms) {
      hd_scene_forms_list("`", " \\| ", " \\| ", range, sizeof range);
      size_t at = strlen(range);
      snprintf(range + at, sizeof range - at, "; %s", kd->doc_range);
    } else if (kd->doc_range) {
      snprintf(range, sizeof range, "%s", kd->doc_range);
    } else if (kd->type == KT_BOOL) {
      snprintf(range, sizeof range, "`1 0 true false yes no on off`");
    } else if (kd->type == KT_ENUM) {
      range[0] = '\0';
      for (int j = 0; kd->names[j]; j++) {
        size_t at = strlen(range);
        snprintf(range + at, sizeof range - at, "%s`%s`", j ? " \\| " : "", kd->names[j]);
      }
    } else if (kd->type == KT_LONG || kd->type == KT_WHOLE) {
      char lo[40], hi[40];
      hd_scene_shortest(kd->lo, lo, sizeof lo);
      hd_scene_shortest(kd->hi, hi, sizeof hi);
      snprintf(range, sizeof range, "whole, %s … %s", lo, hi);
    } else {
      char why[120];
      hd_scene_range_why(kd, why, sizeof why);
      snprintf(range, sizeof range, "%s", why + strlen("must be "));
      char *ge = strstr(range, ">=");
      if (ge) memmove(ge + 3, ge + 2, strlen(ge + 2) + 1), memcpy(ge, "≥", 3);
      if (!strncmp(range, "in ", 3)) memmove(range, range + 3, strlen(range + 3) + 1);
    }
    hd_scene_put(b, "| `%s` | %s | %s | %s |\n", kd->doc_key ? kd->doc_key : kd->name, def, range,
                 kd->doc);
  }
}

int hd_scene_keys_doc(const char *in, char **out, hd_error *err) {
  static const char open_tag[] = "<!-- keys ", end_tag[] = "<!-- end keys -->";
  sbuf b = {0};
  hd_scene_put(&b, "%s", "");
  const char *p = in;
  long line = 0;
  while (*p) {
    const char *nl = strchr(p, '\n');
    size_t len = nl ? (size_t)(nl - p) + 1 : strlen(p);
    line++;
    hd_scene_put(&b, "%.*s", (int)len, p);
    if (!strncmp(p, open_tag, sizeof open_tag - 1)) {
      char name[32] = "";
      sscanf(p + sizeof open_tag - 1, "%31[a-z]", name);
      int s = !strcmp(name, "species") ? S_SPECIES : hd_scene_find_sec(name);
      if (s < 0) {
        free(b.s);
        return hd_error_set(err, HD_EINPUT, "line %ld: %s: no such section", line, name);
      }
      doc_table(s, &b);
      p += len; /* skip the old table */
      while (*p && strncmp(p, end_tag, sizeof end_tag - 1)) {
        nl = strchr(p, '\n');
        line++;
        p = nl ? nl + 1 : p + strlen(p);
      }
      if (!*p) {
        free(b.s);
        return hd_error_set(err, HD_EINPUT, "line %ld: table of [%s] not closed by %s", line, name,
                            end_tag);
      }
      continue;
    }
    p += len;
  }
  if (b.oom) {
    free(b.s);
    return hd_error_set(err, HD_ENOMEM, "out of memory");
  }
  *out = b.s;
  return HD_OK;
}

/* ---- public -------------------------------------------------------------------------------- */

int hd_scene_key_name(int k, char *buf, size_t size) {
  if (k < 0 || k >= N_KEY) return 1;
  const key_def *kd = &hd_scene_keys[k];
  int n = snprintf(buf, size, "%s.%s%s", hd_scene_sec_name[kd->sec],
                   kd->sec == S_SPECIES ? "NAME." : "", kd->name);
  return n < 0 || (size_t)n >= size;
}

void hd_scene_defaults(hd_scene *sc) {
  memset(sc, 0, sizeof *sc);
  strcpy(sc->dir, ".");
  for (int k = 0; k < N_KEY; k++) {
    const key_def *kd = &hd_scene_keys[k];
    void *p = (char *)sc + kd->off;
    if (kd->sec == S_SPECIES) continue; /* set when the section is made */
    switch (kd->type) {
    case KT_REAL:
    case KT_WHOLE:
      *(double *)p = kd->def;
      break;
    case KT_LONG:
      *(long *)p = (long)kd->def;
      break;
    case KT_U64:
      *(unsigned long long *)p = (unsigned long long)kd->def;
      break;
    case KT_BOOL:
    case KT_ENUM:
      *(int *)p = (int)kd->def;
      break;
    case KT_CUSTOM: /* zero bytes */
      break;
    }
  }
  sc->log_every = 1; /* the N of `collisions = every N`, 1 for all (not a key of its own) */
  sc->text = NULL;
}

long hd_scene_bodies(const hd_scene *sc) {
  return sc->n_rods > 0 ? sc->n_rods : hd_scene_body_count(sc);
}

double hd_scene_frame_bytes(const hd_scene *sc) {
  return (double)hd_scene_bodies(sc) * HD_FRAME_BODY_BYTES + HD_FRAME_ROW_BYTES;
}

double hd_scene_frames_estimate(const hd_scene *sc) {
  double n = (double)hd_scene_bodies(sc), best = INFINITY;
  if (sc->frames_every_time > 0 && sc->stop_time > 0)
    best = floor(sc->stop_time / sc->frames_every_time) + 1;
  if (sc->frames_every > 0) {
    /* the run ends at the first stop reached; cpd = 2 pair collisions / N <= 2 events / N */
    if (sc->stop_cpd > 0) best = fmin(best, floor(sc->stop_cpd / sc->frames_every) + 1);
    if (sc->stop_events > 0 && n > 0)
      best = fmin(best, floor(2 * sc->stop_events / n / sc->frames_every) + 1);
  }
  if (!(sc->frames_every > 0 || sc->frames_every_time > 0)) return 0;
  return best < INFINITY ? best : -1;
}

double hd_scene_covered_area(const hd_scene *sc) {
  double a = (double)sc->n_dimers * hd_dimer_area(sc->dimer_d, sc->dimer_a) +
             (double)sc->n_disks * M_PI * sc->disk_sigma * sc->disk_sigma / 4;
  for (int j = 0; j < sc->n_named; j++)
    if (sc->named[j].count > 0) a += (double)sc->named[j].count * hd_species_area(&sc->named[j]);
  return a;
}

void hd_scene_free(hd_scene *sc) {
  if (!sc) return;
  free(sc->text);
  sc->text = NULL;
}

/* Parses text (len bytes) into the already-defaulted *sc. */
static int load_text(hd_scene *sc, const char *text, size_t len, const char *name,
                     const char *const *over, int n_over, int mode, hd_error *err) {
  ctx *c = calloc(1, sizeof *c);
  if (!c) return hd_error_set(err, HD_ENOMEM, "%s: out of memory", name);
  c->mode = mode;
  c->sc = sc;
  c->name = name;
  c->over = over;
  c->n_over = n_over;
  c->err = err;
  c->p = text;
  c->end = text + len;
  int rc = HD_OK;
  if (memchr(text, '\0', len))
    rc = hd_error_set(err, HD_EINPUT, "%s: contains a NUL byte: not a text file", name);
  if (!rc) rc = hd_scene_parse_text(c);
  for (int i = 0; !rc && i < n_over; i++) rc = hd_scene_apply_override(c, i);
  if (!rc) rc = hd_scene_check_all(c);
  if (!rc) {
    sc->text = hd_scene_canonical_text(c);
    if (!sc->text) rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", name);
  }
  free(c);
  if (!rc) hd_error_clear(err);
  return rc;
}

int hd_scene_load_string(hd_scene *sc, const char *text, const char *name, const char *const *over,
                         int n_over, hd_error *err) {
  hd_scene_defaults(sc);
  if (!name) name = "<string>";
  return load_text(sc, text, strlen(text), name, over, n_over, M_RUN, err);
}

int hd_scene_load_stored(hd_scene *sc, const char *text, const char *name, hd_error *err) {
  hd_scene_defaults(sc);
  if (!name) name = "<string>";
  return load_text(sc, text, strlen(text), name, NULL, 0, M_STORED, err);
}

int hd_scene_read_stored(hd_scene *sc, const char *text, const char *name, hd_error *err) {
  hd_scene_defaults(sc);
  if (!name) name = "<string>";
  return load_text(sc, text, strlen(text), name, NULL, 0, M_READ, err);
}

int hd_scene_load(hd_scene *sc, const char *path, const char *const *over, int n_over,
                  hd_error *err) {
  hd_scene_defaults(sc);
  if (strlen(path) >= sizeof sc->path)
    return hd_error_set(err, HD_EINPUT, "%.100s...: scene path too long", path);
  strcpy(sc->path, path);
  const char *slash = strrchr(path, '/');
  if (slash == path)
    strcpy(sc->dir, "/");
  else if (slash) {
    memcpy(sc->dir, path, (size_t)(slash - path));
    sc->dir[slash - path] = '\0';
  }
  struct stat stt;
  if (stat(path, &stt) == 0 && S_ISDIR(stt.st_mode))
    return hd_error_set(err, HD_EIO, "%s: cannot read scene: is a directory", path);
  if (stat(path, &stt) == 0 && !S_ISREG(stt.st_mode)) /* /dev/zero grew memory, a FIFO hung */
    return hd_error_set(err, HD_EINPUT, "%s: cannot read scene: not a regular file", path);
  FILE *f = fopen(path, "rb");
  if (!f) return hd_error_set(err, HD_EIO, "%s: cannot read scene: %s", path, strerror(errno));
  char *buf = NULL;
  size_t len = 0, cap = 0;
  for (;;) {
    if (len + 4096 + 1 > cap) {
      cap = 2 * cap + 8192;
      char *nb = realloc(buf, cap);
      if (!nb) {
        free(buf);
        fclose(f);
        return hd_error_set(err, HD_ENOMEM, "%s: out of memory", path);
      }
      buf = nb;
    }
    size_t got = fread(buf + len, 1, 4096, f);
    len += got;
    if (got < 4096) break;
    if (len > (size_t)HD_SCENE_MAX_BYTES) { /* the file grew after stat, or is not what it says */
      free(buf);
      fclose(f);
      return hd_error_set(err, HD_EINPUT, "%s: scene larger than %ld bytes: not a scene file", path,
                          HD_SCENE_MAX_BYTES);
    }
  }
  int bad = ferror(f);
  fclose(f);
  if (bad) {
    free(buf);
    return hd_error_set(err, HD_EIO, "%s: cannot read scene: read error", path);
  }
  buf[len] = '\0';
  int rc = load_text(sc, buf, len, path, over, n_over, 0, err);
  free(buf);
  return rc;
}

/* ---- state CSV ----------------------------------------------------------------------------- */

static const char *const csv_col[7] = {"kind", "x", "y", "phi", "vx", "vy", "omega"};

static void rstrip(char *s) {
  size_t n = strlen(s);
  while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r' || s[n - 1] == '\n'))
    s[--n] = '\0';
}

/* Parses one data line (already right-stripped) into *r; `kind` may name one of sc's species
 * (sc NULL: dimer and disk only). */
static int csv_row(char *line, const char *path, long lineno, const hd_scene *sc, hd_state_row *r,
                   hd_error *err) {
  char *f[8];
  int nf = 0;
  char *p = line;
  for (;;) {
    if (nf < 8) f[nf] = p;
    nf++;
    char *comma = strchr(p, ',');
    if (!comma) break;
    *comma = '\0';
    p = comma + 1;
  }
  if (nf != 7)
    return hd_error_set(err, HD_EINPUT, "%s:%ld: expected 7 columns (%s), found %d", path, lineno,
                        "kind,x,y,phi,vx,vy,omega", nf);
  char *kind = hd_scene_trim(f[0]);
  int oriented = 0; /* phi and omega are read */
  r->species = -1;
  if (!strcmp(kind, "dimer"))
    r->kind = HD_KIND_DIMER, r->species = 0, oriented = 1;
  else if (!strcmp(kind, "disk")) /* (a rough disk, q > 0, spins: its phi and omega too) */
    r->kind = HD_KIND_DISK, r->species = 1, oriented = sc && sc->disk_q > 0;
  for (int j = 0; sc && r->species < 0 && j < sc->n_named; j++)
    if (!strcmp(kind, sc->named[j].name)) {
      r->kind = sc->named[j].ndisk >= 2 ? HD_KIND_DIMER : HD_KIND_DISK;
      oriented = sc->named[j].ndisk >= 2 || sc->named[j].q > 0;
      r->species = 2 + j;
    }
  if (r->species < 0) {
    char names[HD_MAX_SPECIES * (HD_SPECIES_NAME_MAX + 1)] = "";
    for (int j = 0; sc && j < sc->n_named; j++)
      strcat(names, " "), strcat(names, sc->named[j].name);
    return hd_error_set(err, HD_EINPUT, "%s:%ld: column 1 (kind): '%.40s' is not dimer or disk%s%s",
                        path, lineno, kind, names[0] ? ", nor a [species] of the scene:" : "",
                        names);
  }
  double v[7];
  for (int j = 1; j < 7; j++) {
    char *t = hd_scene_trim(f[j]);
    if (!hd_scene_parse_num(t, &v[j]))
      return hd_error_set(err, HD_EINPUT, "%s:%ld: column %d (%s): '%.40s': %s", path, lineno,
                          j + 1, csv_col[j], t, hd_scene_num_why(t));
  }
  r->x = v[1];
  r->y = v[2];
  r->phi = oriented ? v[3] : 0;
  r->vx = v[4];
  r->vy = v[5];
  r->omega = oriented ? v[6] : 0;
  r->line = lineno;
  return HD_OK;
}

/* One line of fp into line (room for max + 1 bytes, NUL-terminated, newline dropped): its
 * length, -1 at the end of the file, -2 when it is longer than max (the rest is not read). */
static long bounded_line(FILE *fp, char *line, long max) {
  long k = 0;
  int ch;
  while ((ch = getc_unlocked(fp)) != EOF && ch != '\n') {
    if (k == max) return -2;
    line[k++] = (char)ch;
  }
  line[k] = '\0';
  return ch == EOF && k == 0 ? -1 : k;
}

int hd_state_csv_read_species(const char *path, const hd_scene *sc, hd_state_row **rows, long *n,
                              hd_error *err) {
  *rows = NULL;
  *n = 0;
  struct stat st;
  if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) /* /dev/zero grew memory until it ran out */
    return hd_error_set(err, HD_EINPUT, "%s: cannot read state file: not a regular file", path);
  FILE *fp = fopen(path, "r");
  if (!fp)
    return hd_error_set(err, HD_EIO, "%s: cannot read state file: %s", path, strerror(errno));
  char line[HD_STATE_MAX_LINE + 1];
  long lineno = 0, nrow = 0, rcap = 0;
  hd_state_row *out = NULL;
  int rc = HD_OK;
  long got;
  while (!rc && (got = bounded_line(fp, line, HD_STATE_MAX_LINE)) != -1) {
    lineno++;
    if (got == -2) {
      rc = hd_error_set(err, HD_EINPUT, "%s:%ld: line longer than %d bytes: not a state file", path,
                        lineno, HD_STATE_MAX_LINE);
      break;
    }
    if (nrow >= 2 * HD_MAX_COUNT) {
      rc = hd_error_set(err, HD_EINPUT, "%s:%ld: more than %ld bodies", path, lineno,
                        2 * HD_MAX_COUNT);
      break;
    }
    if (memchr(line, '\0', (size_t)got)) {
      rc = hd_error_set(err, HD_EINPUT, "%s:%ld: contains a NUL byte: not a text file", path,
                        lineno);
      break;
    }
    rstrip(line);
    if (lineno == 1) {
      /* a UTF-8 byte order mark (spreadsheets write one) is skipped, as in scene files */
      if (!strncmp(line, "\xEF\xBB\xBF", 3)) memmove(line, line + 3, strlen(line + 3) + 1);
      if (strcmp(line, "kind,x,y,phi,vx,vy,omega"))
        rc = hd_error_set(err, HD_EINPUT,
                          "%s:1: missing header: expected kind,x,y,phi,vx,vy,omega, found '%.60s'",
                          path, line);
      continue;
    }
    if (!line[0]) continue; /* blank line */
    if (nrow == rcap) {
      rcap = 2 * rcap + 64;
      hd_state_row *nr = realloc(out, (size_t)rcap * sizeof *out);
      if (!nr) {
        rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", path);
        break;
      }
      out = nr;
    }
    rc = csv_row(line, path, lineno, sc, &out[nrow], err);
    if (!rc) nrow++;
  }
  if (!rc && ferror(fp)) rc = hd_error_set(err, HD_EIO, "%s: read error", path);
  if (!rc && lineno == 0)
    rc = hd_error_set(err, HD_EINPUT, "%s:1: empty file: expected header kind,x,y,phi,vx,vy,omega",
                      path);
  if (!rc && nrow == 0)
    rc = hd_error_set(err, HD_EINPUT, "%s:%ld: no bodies after the header", path, lineno);
  fclose(fp);
  if (rc) {
    free(out);
    return rc;
  }
  *rows = out;
  *n = nrow;
  hd_error_clear(err);
  return HD_OK;
}
