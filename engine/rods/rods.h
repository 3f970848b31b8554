/* hd_rods: the 1D gas of inelastic rods of Aspelmeier, Giese and Zippelius (1998), Secs. II C
 * and IV: N point rods on a ring of length N (mean spacing 1), alternating short/long with
 * length ratio gamma and masses in the same ratio, each with a bath of N_mod vibrational modes
 * at temperature T_B.  Event driven between collisions (one event per gap i|i+1 in the engine's
 * calendar queue, hd_queue.h), Monte Carlo at collisions (eps drawn from p_beta, eps.h).
 * docs/rods.md.
 *
 * Units (paper Sec. II C): masses m_short = Gamma_1 = 1 + gamma, m_long = Gamma_2 = 1 + 1/gamma,
 * so that the reduced mass of every colliding pair is mu = Gamma_1 Gamma_2/(Gamma_1 + Gamma_2)
 * = 1 and E_kin = sum_i Gamma_i v_i^2 / 2 (eq. 33).  Rod i is short for even i, long for odd i
 * (count is even).  The initial state has E_kin = N T0 / 2 exactly, zero total momentum, uniform
 * random positions and all baths at T_B = 0. */
#ifndef HD_RODS_H
#define HD_RODS_H

#include <gsl/gsl_rng.h>
#include <stddef.h>
#include <stdint.h>

#include "eps.h"
#include "hd_error.h"
#include "hd_queue.h"

/* How eps is chosen at a collision. */
typedef enum hd_rods_model {
  HD_RODS_STOCHASTIC = 0, /* eps ~ p_beta(eps), beta = E_tr / T_B (the paper) */
  HD_RODS_CONSTANT = 1    /* eps fixed (collapses: McNamara and Young) */
} hd_rods_model;

/* Defaults of a ring's parameters: hd_rods_params_default and the [rods] keys of a scene
 * (engine/scene/hd_scene_keys.h) both take them from here.  The constant model's eps defaults to
 * gamma.
 */
#define HD_RODS_GAMMA_DEFAULT 0.8
#define HD_RODS_NMOD_DEFAULT 1000
#define HD_RODS_TEMPERATURE_DEFAULT 1.0

/* The parameters of a ring ([rods] section of a scene). */
typedef struct hd_rods_params {
  long n;                  /* rods, even, >= 2 */
  double gamma;            /* length and mass ratio short/long, in (0, 1] */
  long nmod;               /* modes per rod, >= 1 */
  hd_rods_model model;     /* stochastic or constant */
  double eps;              /* the constant model's eps, in [0, 1] */
  double damping;          /* nu >= 0: T_B(t) = T_B(t_i) exp(-nu (t - t_i)) between collisions */
  double tc;               /* >= 0: TC model (Luding and McNamara), eps = 1 when either rod had a
                              collision less than tc ago; 0 = off */
  double temperature;      /* T0 > 0: initial E_kin = N T0 / 2 */
  int table;               /* 1: eps from a tabulated p_beta (built at allocation, fixed seed) */
  int unequal;             /* 1: beta_i = E_tr / T_B(i) per rod (hd_eps_sample2); 0: mean T_B */
  unsigned long long seed; /* seeds the initial state and every eps draw (mt19937) */
  double eps_step;         /* grid step of the direct eps sampler (hd_eps_opts.step); 0 = its
                              default 0.01 */
} hd_rods_params;

/* Collapse detection.  An inelastic collapse is a pile-up of collisions in which the relative
 * motion of a cluster dies out: the pairs' relative energies E_tr fall geometrically while the
 * collisions crowd into a vanishing time.  A collision is "tiny" when it comes less than
 * HD_RODS_TINY t after the previous one (t the time now).  Tiny collisions less than
 * HD_RODS_EPISODE t after the first of them form an episode (other collisions between them do
 * not end it: a small ring's other gaps go on colliding at ordinary spacings); its tiny
 * collisions are taken in blocks of HD_RODS_TINY_RUN.  When the largest E_tr of
 * HD_RODS_TINY_LOW successive blocks has fallen below HD_RODS_TINY_FALL times that of the
 * episode's first block, the run ends with HD_ECOLLAPSE.  A pile-up at one instant (collisions
 * at one and the same double time, e.g. three rods in contact at constant eps = 0.1) is tiny
 * and cold, and is stopped by that rule within a few hundred collisions.  Collisions at one
 * double time are not a collapse by themselves: a cluster of K rods whose spacings are below
 * the clock's resolution (ulp(t) = 7e-12 at t = 4e4) is resolved at one instant, and while its
 * baths are warm this takes up to ~K^2 collisions (each pair collision at eps ~ 1 undoes about
 * one inversion of the velocity order) and ends.  A safety net only against a loop that makes
 * no progress: HD_RODS_STALL + N^2 consecutive collisions at one time also end the run
 * (HD_ECOLLAPSE; 1e8 for N = 1e4, ~1 min).  It was HD_RODS_STALL alone, and stopped the
 * paper's damped ring at t = 43929.6 (docs/rods.md).  The cluster reported is the shortest arc
 * of rods holding the pairs of the last HD_RODS_TINY_RUN tiny collisions.
 * Why energies and not the spacings (docs/rods.md): below 1e-12 t the spacing of two
 * collisions is within ~1e4 ulp of t, and the former test (a fall of the spacing by 1e6 over 64
 * tiny collisions) could only pass at 0, i.e. at two collisions rounded to the same double.  A
 * dense cluster of the damped model (10^4 rods, t = 2171) has such ties among collisions ~1e-10
 * apart while its pairs draw eps > 1 from their warm baths (beta ~ 0.6, mean eps 1.06) and their
 * E_tr does not fall: it was stopped as collapsed, and run on it dissolves.  Energies are not
 * quantised by the clock.  Criteria on speeds or gaps alone are wrong: a ring below
 * McNamara-Young's N_c cools homogeneously with speeds falling exponentially in the number of
 * collisions, and the damped model's final cluster has gaps falling like 1/t; neither is a
 * collapse, and in both the time between collisions grows (no tiny collisions).
 * Only a block of cold collisions counts as fallen: eps fixed (constant model), or drawn at
 * beta = E_tr / T_B >= HD_RODS_COLD_BETA (eps within a few % of gamma, never > 1).  A cluster
 * that collides at beta ~ 1 takes energy from its baths and gives it back (the paper, Sec. IV:
 * the damped model's clusters dissolve).  Without this the damped 10^4-rod ring was stopped at
 * t = 24243: a block at E_tr ~ 1e-18 against a first block of 9e-8 in an episode 0.0087 long,
 * when baths left alone had decayed by e^-242 (not examined further: docs/rods.md). */
#define HD_RODS_COLD_BETA 100
#define HD_RODS_TINY 1e-12
#define HD_RODS_EPISODE 1e-6
#define HD_RODS_TINY_RUN 64
#define HD_RODS_TINY_LOW 1
#define HD_RODS_TINY_FALL 1e-9
#define HD_RODS_STALL 100000

/* Size of the eps table built when params.table is set: beta in [1e-3, 1e3], 25 nodes x 129
 * quantiles x 1000 samples per node (docs/mc-eps.md: KS at the noise level; ~2 s), from an
 * mt19937 seeded with HD_RODS_TABLE_SEED so that every run of a gamma uses the same table, then
 * scaled by hd_eps_table_balance so that its detailed-balance moment D is 0. */
#define HD_RODS_TABLE_SEED 20250601UL

/* Below the table's grid (beta < 1e-3: slow pairs among hot baths, ~1e-3 of the draws in a
 * damped ring's dense clusters, but a third of its time at ~0.15 ms a direct draw) the ring
 * extends the table by HD_RODS_LOW_NODES nodes at the table's own spacing (4 per decade) down
 * to beta = 1e-6, each built when a draw first needs it as the table builds its nodes
 * (hd_eps_table_row: 1000 direct draws, their empirical quantiles) from an mt19937 seeded
 * HD_RODS_TABLE_SEED + j for node j (so a resumed run rebuilds the same node), times the
 * table's balance factor.  Below 1e-6: direct draws. */
#define HD_RODS_LOW_NODES 12

/* One collision as the ring reports it. */
typedef struct hd_rods_event {
  double t;          /* time */
  int64_t i, j;      /* rods i (left) and j = i+1 mod N (right) */
  double eps;        /* coefficient of restitution applied */
  double e_tr;       /* u^2/2: energy of the relative motion before (mu = 1) */
  double u;          /* relative velocity v_j - v_i before (< 0) */
  double tb_i, tb_j; /* bath temperatures after */
  double de;         /* kinetic energy change, -(1 - eps^2) e_tr */
} hd_rods_event;

/* The ring.  Fields are read-only for callers. */
typedef struct hd_rods {
  hd_rods_params p;
  double t;           /* current time */
  int64_t collisions; /* collisions so far */
  double *m;          /* m[i]: mass */
  double *v;          /* v[i]: velocity */
  double *tb;         /* tb[i]: bath temperature at time tl[i] */
  double *tl;         /* tl[i]: time of rod i's last collision (-inf before the first) */
  double *g;          /* g[k]: gap between rod k and rod k+1 mod N at time gt[k] */
  double *gt;         /* gt[k]: time at which g[k] holds */
  double *key;        /* key[k]: time gap k closes (INFINITY if it opens) */
  double x0, x0t;     /* position of rod 0 at time x0t, in [0, N) at the start */
  double e_lost;      /* energy removed by the damping up to the tl[] of every rod */
  int64_t resampled;  /* eps draws redrawn because the baths could not pay for eps > 1 */
  int64_t tiny_run;   /* tiny collisions in the current episode (collapse detection) */
  int64_t tiny_low;   /* successive blocks of them whose E_tr fell by HD_RODS_TINY_FALL */
  double tiny_t0;     /* time of the episode's first tiny collision */
  double tiny_e0;     /* largest E_tr of the episode's first block of HD_RODS_TINY_RUN */
  double tiny_eblk;   /* largest E_tr of the current block so far */
  int64_t tiny_warm;  /* collisions of the current block drawn from warm baths (not cold) */
  int64_t stall;      /* consecutive collisions at the same time */
  int64_t frame_next; /* collisions before which the drift is not checked again (keep_frame) */
  int64_t frames;     /* times the ring was taken to its centre-of-mass frame */
  int32_t recent[HD_RODS_TINY_RUN]; /* gaps of the last tiny collisions (ring buffer) */
  hd_queue *q;                      /* one entry per gap keyed by key[] */
  gsl_rng *rng;
  hd_eps_sampler *sampler; /* stochastic model */
  hd_eps_table *table;     /* when p.table */
  double table_scale;      /* the balance factor applied to the table (hd_eps_table_balance) */
  double *low_q;           /* HD_RODS_LOW_NODES x table->nu quantiles of the nodes below the
                            * table's grid, node j (1..) at beta_min 10^(-j/4); NULL without table */
  unsigned char *low_have; /* low_have[j - 1]: node j built */
} hd_rods;

/* One eps at beta = E_tr/T_B from ring r's sampler and generator, as a collision draws it
 * before the baths' cap: from the table on its grid (p.table), from the lazily built nodes below
 * it down to 1e-6 (HD_RODS_LOW_NODES), else directly.  r must have a sampler (the stochastic
 * model, gamma < 1). */
double hd_rods_table_eps(hd_rods *r, double beta);

/* Fills p with the defaults (n = 0, gamma 0.8, nmod 1000, stochastic, eps = gamma, no damping,
 * no TC, T0 = 1, direct sampler, mean baths, seed 1). */
void hd_rods_params_default(hd_rods_params *p);

/* The options of the ring's eps sampler for eps_step (0: the sampler's default step), so that a
 * scene check (hd_eps_grid_fits) sees the sampler the ring will build. */
void hd_rods_eps_opts(double eps_step, hd_eps_opts *o);

/* Allocates a ring in its initial state.  HD_OK, HD_EINPUT (bad parameters) or HD_ENOMEM. */
int hd_rods_alloc(hd_rods **out, const hd_rods_params *p, hd_error *err);

/* Frees the ring (NULL allowed). */
void hd_rods_free(hd_rods *r);

/* Advances to the next collision, processes it and describes it in *ev.  Returns HD_OK,
 * HD_SIM_STOPTIME (hd_error.h: the next collision is after t_stop; the clock is set to t_stop),
 * HD_SIM_IDLE (no gap closes: every eps was 0 and the ring froze), or HD_ECOLLAPSE (err names
 * the time, the collisions and the cluster of rods; the state is that before the collision). */
int hd_rods_next(hd_rods *r, double t_stop, hd_rods_event *ev, hd_error *err);

/* Positions of all rods at the current time, in [0, N), into x[0..N-1] (O(N)). */
void hd_rods_positions(const hd_rods *r, double *x);

/* Bath temperature of rod i at the current time (damping applied). */
double hd_rods_tb(const hd_rods *r, long i);

/* Energies at the current time: translational sum m v^2/2, bath sum N_mod T_B and the energy
 * the damping has removed since the start (any may be NULL).  Without damping the sum of the
 * three is the initial E_kin to round-off. */
void hd_rods_energy(const hd_rods *r, double *e_kin, double *e_bath, double *e_lost);

/* Exact state as a malloc'd blob (includes the RNG state). */
int hd_rods_checkpoint(const hd_rods *r, void **blob, size_t *n, hd_error *err);

/* Allocates a ring with parameters p and the state of blob (from hd_rods_checkpoint of a ring
 * with the same p).  HD_EINPUT on a blob that does not fit. */
int hd_rods_alloc_restore(hd_rods **out, const hd_rods_params *p, const void *blob, size_t n,
                          hd_error *err);

/* ---- theory (docs/rods.md) ---------------------------------------------------------------- */

/* Stationary kinetic energy of a conservative ring of n rods with zero total momentum and
 * total energy e_tot: n - 1 translational degrees of freedom and 2 n nmod bath quadratic
 * degrees of freedom share e_tot equally, E_kin = e_tot (n-1)/(n-1 + 2 n nmod).  The paper's
 * E_kin(0)/(2 N_mod + 1) is its n -> infinity limit. */
double hd_rods_ekin_stat(long n, long nmod, double e_tot);

/* Collision rate of the 1D ideal gas of n point rods on a ring of length n at temperature T
 * (kinetic energy T/2 per translational degree of freedom, mu = 1):
 * (n - 1) sqrt(T / (2 pi)).  The paper's eq. (35) is N/(2 sqrt(pi (2 N_mod + 1))), smaller by
 * sqrt(2) at T = 1/(2 N_mod + 1). */
double hd_rods_rate_ideal(long n, double T);

/* The paper's eq. (35): n / (2 sqrt(pi (2 nmod + 1))). */
double hd_rods_rate_eq35(long n, long nmod);

/* McNamara and Young's minimum number of particles for inelastic collapse at restitution r,
 * in its asymptotic form -ln(1 - r)/(1 - r) (r < 1; +inf at r = 1). */
double hd_rods_my_ncrit(double r);

#endif
