/* hd_scene_keys.h: every scene key, once (internal to engine/scene; read through
 * hd_scene_internal.h).
 *
 * SCENE_KEYS holds a row per key: X(ID, section, name, the rest of its key_def): its type, where
 * it is stored (offsetof into hd_scene or hd_scene_species, or a handler for the few keys with a
 * syntax of their own), default, range, when and how the canonical text writes it, and its row
 * in docs/scene-keys.md.  The parser, hd_scene_defaults, the canonical text (runs.scene) and the
 * key tables of docs/scene-keys.md (hd_scene_keys_doc, checked by tests/test_scene.c) all come
 * from that one table; its order is the order of the canonical text and of the docs.  K_ID is a
 * key's index in hd_scene_keys (hd_scene_keys.c).
 *
 * Where a key is parsed: a row without CUSTOM is parsed by its type (hd_scene_set_value,
 * hd_scene_value.c); CUSTOM(hd_scene_set_X) names its handler: hd_scene_set.c for the fixed
 * sections, hd_scene_shape.c (shape, d, m, disks) and hd_scene_pairs.c (alpha_OTHER,
 * beta_OTHER) for [species NAME]. */
#ifndef HD_SCENE_KEYS_H
#define HD_SCENE_KEYS_H

/* The shorthands of the rows. */
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

#endif
