/* hd_sim: the event-driven engine.  Rigid bodies of 1 to HD_MAX_BODY_DISKS disks (the scene's
 * species: [dimers], [disks] and every [species NAME], hd_body.h's shapes) in a 2D box,
 * periodic in every direction that no wall closes.  One event per body in the event queue
 * (hd_queue.h, a calendar queue): the earliest of its predicted contacts, its wall contacts and its
 * next cell crossing.  Bodies are advanced lazily (each keeps the time of its own state) and the
 * time origin is rebased every `rebase_every` events, so precision does not decay over long runs.
 *
 * Invalidation: every velocity change bumps a body's ncoll; a pair event remembers the partner's
 * ncoll and is stale when it differs.  Cell crossings do not change velocities and invalidate
 * nothing.  The root search of a pair is made only up to the body's next cell crossing or the
 * partner's next event, whichever comes first (each is followed by that body's full prediction
 * outside pure disk scenes, which finds the pair again if they can still meet; hd_predict.c):
 * this bounds every root search. */
#ifndef HD_SIM_H
#define HD_SIM_H

#include <stdint.h>

#include <gsl/gsl_rng.h>

#include "hd_body.h"
#include "hd_error.h"
#include "hd_queue.h"
#include "hd_scene.h"

/* Event types. */
enum { HD_EV_NONE = 0, HD_EV_PAIR = 1, HD_EV_CELL = 2, HD_EV_WALL = 3 };
/* c_dir of a body that never leaves its cell but spins (a dimer with V = 0 exactly, e.g. from a
 * state file): its "crossing" is a wake-up HD_WAKE_TURNS turns ahead, which predicts it again,
 * so that contact searches with it have a finite horizon. */
enum { HD_WAKE = 4 };
#define HD_WAKE_TURNS 100

/* One body (128 bytes, two cache lines).  It carries two pending events: a contact (pair or wall,
 * `p_*`) and its next cell crossing (`c_*`); ev_t is the earlier of the two and its key in the
 * queue. */
typedef struct hd_body {
  /* first cache line: what a neighbour's prediction reads */
  double t;        /* time of the state k */
  hd_kin k;        /* centre of mass, velocity, orientation, angular velocity at t */
  int32_t species; /* index into hd_sim.shape: the scene's species (hd_scene_species.h) */
  int32_t next;    /* next body in the cell's list, -1 at the end */
  /* second cache line */
  double ev_t;       /* min(p_t, c_t): time of the next event (INFINITY if none) */
  double p_t;        /* time of the predicted contact (INFINITY if none) */
  double c_t;        /* time of the next cell crossing (INFINITY if none) */
  int32_t cell;      /* cell index (cy * ncx + cx) */
  int32_t cy;        /* the cell's row, cell / ncx (kept with cell: no division per event) */
  uint32_t ncoll;    /* velocity changes so far; invalidates partners' pair events */
  int32_t p_partner; /* PAIR: partner body; WALL: wall index */
  uint32_t p_pcount; /* PAIR: partner's ncoll when predicted */
  int16_t p_type;    /* HD_EV_PAIR, HD_EV_WALL or HD_EV_NONE */
  int16_t c_dir;     /* crossing face: 0 +x, 1 -x, 2 +y, 3 -y; HD_WAKE: no face, c_t is a
                      * wake-up that only predicts again (hd_predict.c, crossing_time) */
  int16_t p_ka;      /* touching disk of this body */
  int16_t p_kb;      /* touching disk of the partner */
  int16_t p_imx;     /* PAIR: image offset of the partner, invariant under wrapping: */
  int16_t p_imy;     /*   shift = (p_im + wrap(partner) - wrap(this)) * L, hd_image_code */
  uint32_t wx, wy;   /* times this body was wrapped through the box (+1 for x -= lx), modulo
                      * 2^32: only differences modulo 2^16 are used (hd_image_code) */
} hd_body;

/* The shift code (-1, 0 or 1 box lengths) im + wp - wb, computed modulo 2^16: exact, since the
 * true code is -1, 0 or 1, however far the two wrap counts wp and wb have drifted apart in a
 * long run (a 16-bit difference overflowed after 32768 laps of one body more than its partner).
 * With im = ix - wp + wb it gives back the offset ix of a pair event (hd_predict.c). */
static inline int hd_image_code(int im, uint32_t wp, uint32_t wb) {
  uint32_t u = ((uint32_t)im + wp - wb) & 0xffffu;
  return u & 0x8000u ? (int)u - 0x10000 : (int)u;
}

/* Allocates n bodies, zeroed, aligned on cache lines (hd_body is two of them); NULL on
 * failure; free() releases them. */
hd_body *hd_bodies_alloc(int32_t n);

/* Counters and clocks: everything a checkpoint needs besides the bodies, cells and RNG. */
typedef struct hd_sim_clock {
  double t;            /* current time, relative to t_offset */
  double t_offset;     /* absolute time = t_offset + t */
  int64_t events;      /* events processed (collisions, crossings, stale events) */
  int64_t collisions;  /* pair collisions (cpd counts these) */
  int64_t wall_hits;   /* body-wall collisions */
  int64_t stale;       /* stale events discarded */
  int64_t next_rebase; /* events count at which the time origin is next rebased */
  double e_kin;        /* total kinetic energy, updated by each collision's de */
  int64_t slow_run;    /* consecutive collisions with |vn| tiny against the thermal speed */
  int64_t pile_run;    /* consecutive collisions with a vanishing time step (a pile-up) */
  double dt_mean;      /* running mean of the time between collisions (pile-ups excluded) */
  double t_last;       /* time of the last collision (relative, like t) */
} hd_sim_clock;

/* What one collision did, for the log. */
typedef struct hd_event_out {
  double t;               /* absolute time */
  hd_coll_kind kind;      /* of the partners' species kinds (hd_sim.sp_kind, hd_coll_kind_of) */
  int32_t i, j;           /* bodies; j = -1 - wall index for a wall */
  int ka, kb;             /* touching disks (kb = -1 for a wall) */
  hd_collision_info info; /* angles (NaN for dimers unless hd_sim.angles), f, de, vn */
} hd_event_out;

/* The simulation. */
typedef struct hd_sim {
  int32_t n;             /* bodies */
  int64_t drift_removed; /* times the system was taken to its centre-of-mass frame (rebase) */
  int zero_momentum;     /* velocities drawn with zero total momentum (not from a state file) */
  int nsp;               /* species: 2 + the scene's named ones */
  int32_t n_species[HD_MAX_SPECIES]; /* bodies per species */
  hd_body *b;                        /* the bodies, kept sorted by cell (see hd_sim_sort) */
  int32_t *id;                       /* id[i]: the user's number of body i (dimers first, then
                                        disks, then each named species, as created); stable
                                        while b is re-sorted */
  hd_shape shape[HD_MAX_SPECIES];    /* shapes by species (HD_KIND_* tag derived) */
  char sp_name[HD_MAX_SPECIES][HD_SPECIES_NAME_MAX]; /* species names: "dimer", "disk", NAME */
  hd_kind sp_kind[HD_MAX_SPECIES]; /* the kind of each species' bodies in the log (states.kind,
                                    * collisions.kind): HD_KIND_DIMER, HD_KIND_DISK, HD_KIND_BODY
                                    * for a named species whatever its shape */
  hd_coll_kind pair_kind[HD_MAX_SPECIES]
                        [HD_MAX_SPECIES + 1];      /* [si][sj]: the kind of a collision
                                                    * of species si with sj (hd_coll_kind_of their
                                                    * sp_kind), [si]   [HD_MAX_SPECIES] with a wall */
  double alpha[HD_MAX_SPECIES][HD_MAX_SPECIES];    /* pair restitution by species */
  double ca_reach[HD_MAX_SPECIES][HD_MAX_SPECIES]; /* hd_ca_reach of each pair of species: the
                                                    * contact search's window (hd_predict.c) */
  double wall_alpha;                               /* body-wall restitution */
  double beta[HD_MAX_SPECIES][HD_MAX_SPECIES];     /* pair tangential restitution (-1: smooth) */
  double wall_beta;                                /* body-wall tangential restitution */
  unsigned char rough[HD_MAX_SPECIES][HD_MAX_SPECIES]; /* the pair takes the rough rule
                                                        * (hd_collide_rough_pair): beta > -1,
                                                        * or a species with q > 0 */
  unsigned char wall_rough[HD_MAX_SPECIES];            /* the same against a wall */
  double spin_q[HD_MAX_SPECIES];                       /* each species' q (hd_shape_set_q) */
  double lx, ly;                                       /* box */
  unsigned walls;                                      /* HD_WALL_* bits */
  hd_wall wall[4];        /* walls by index: left, right, bottom, top */
  int32_t ncx, ncy;       /* cells per direction (>= 1) */
  double cwx, cwy;        /* cell widths (>= largest body diameter) */
  int32_t *head;          /* first body of each cell, -1 if empty */
  hd_queue *q;            /* the event queue */
  gsl_rng *rng;           /* seeded generator (initial state; stochastic rules) */
  hd_sim_clock c;         /* clocks and counters */
  int64_t rebase_every;   /* events between rebases of the time origin */
  double rebase_e;        /* the origin is also rebased once c.t^2 e_kin > this: a typical
                           * body has flown HD_REBASE_TRAVEL of the smallest diameter
                           * since (hd_sim_queue_init; hd_sim.c, rebase) */
  int verify;             /* check invariants at every event (slow) */
  int angles;             /* the contact angles of hd_event_out.info are computed (1), or left
                           * NaN in smooth pair collisions of bodies of several disks (0: the
                           * scene logs no collision, [log] collisions = none; wall and rough
                           * collisions, a few per cent, have them always); set it to 1 to have
                           * them all the same */
  int disks_only;         /* only [disks] bodies: disk-disk prediction without shape dispatch */
  double disks_d;         /* the diameter of the [disks] species (HD_KIND_DISK) */
  int partial_cross;      /* pure disks, >= 3x3 cells: crossings search 3 new cells */
  int melt;               /* set-up only: the lattice placed must be melted */
  double max_overlap;     /* verification: largest relative overlap seen */
  int32_t last_i, last_j; /* bodies of the last collision (collapse report) */
  double cut_t;           /* during a prediction: the earliest time (relative to now) a contact
                           * search was cut at by a stop request (HD_CA_CUT), else INFINITY */
  int cut;                /* a prediction was cut since hd_sim_next last returned: it returns
                           * HD_SIM_BUSY after the event, so that its caller sees the stop */
} hd_sim;

/* Builds a simulation from a scene: bodies placed and given velocities (seeded by sc->seed),
 * no event processed yet.  HD_EINPUT for a scene the bodies do not fit in or a bad state file
 * (message names the file, line and key), HD_ENOMEM.  *out is NULL on failure. */
int hd_sim_alloc(hd_sim **out, const hd_scene *sc, hd_error *err);

/* Frees everything (NULL allowed). */
void hd_sim_free(hd_sim *s);

/* Status of hd_sim_next besides HD_OK (a collision happened): HD_SIM_STOPTIME, HD_SIM_IDLE,
 * HD_SIM_BUSY (hd_error.h). */
/* Events hd_sim_next processes without a collision before it returns HD_SIM_BUSY. */
#define HD_SIM_BUSY_EVENTS (1L << 22)

/* Processes events until the next collision, which it describes in *ev, and returns HD_OK; or
 * returns HD_SIM_STOPTIME when the next event is after t_stop (absolute; the clock is then at
 * t_stop), HD_SIM_IDLE when no event is left, HD_SIM_BUSY after HD_SIM_BUSY_EVENTS events
 * without a collision (call again to go on: a caller gets to check its signals even when
 * collisions are rare, e.g. one body alone, or ten disks in a box of 1e9), HD_ECOLLAPSE on
 * inelastic collapse, HD_EPHYS when verification finds an overlap or time going backwards (err
 * says which bodies). */
int hd_sim_next(hd_sim *s, double t_stop, hd_event_out *ev, hd_error *err);

/* Absolute current time. */
static inline double hd_sim_time(const hd_sim *s) {
  return s->c.t_offset + s->c.t;
}

/* Collisions per particle: 2 * pair collisions / N. */
static inline double hd_sim_cpd(const hd_sim *s) {
  return s->n ? 2.0 * (double)s->c.collisions / (double)s->n : 0.0;
}

/* Renumbers the bodies in cell order (memory locality for large N); done at every rebase of the
 * time origin.  Body numbers seen by users go through s->id. */
void hd_sim_sort(hd_sim *s);

/* State of body i at the current time, without changing the simulation. */
void hd_sim_body_now(const hd_sim *s, int32_t i, hd_kin *k);

/* Kinetic energies summed over species sp (or all if sp < 0), recomputed from the bodies:
 * translational and rotational. */
void hd_sim_energy(const hd_sim *s, int sp, double *e_tr, double *e_rot);

/* O(N) measures of the state at the current time (recorded with every sample; docs/analysis.md,
 * "State measures").  Each has the value given for a gas without correlations (molecular chaos,
 * independent positions and velocities): */
typedef struct hd_state_measures {
  double flow_frac;  /* energy of the momentum field averaged on a 4 x 4 grid of the box,
                      * sum_c |P_c|^2/(2 M_c), over the translational energy */
  double flow_chaos; /* flow_frac's value without velocity correlations,
                      * sum_c (sum_{i in c} m_i^2 v_i^2)/M_c / sum_i m_i v_i^2 (about 16/N) */
  double count_var;  /* variance of the bodies' counts in the 4 x 4 cells over their mean:
                      * 1 for Poisson, S(0) of the gas (0.8 for disks at 0.05) when uncorrelated */
  double s_rho;      /* |rho_k|^2 / N at the box's 4 smallest wave vectors (mean): ~S(0);
                      * s_perp and s_par are means over those where their normalisation > 0 */
  double s_perp;     /* |p_k . t|^2 / sum m^2 (v . t)^2 there, t normal to k (shear): 1 */
  double s_par;      /* the same along k (sound): 1 */
} hd_state_measures;

/* Fills *out from the bodies at the current time (COM positions and velocities, body masses);
 * does not change the simulation.  NaN where undefined (no body, no motion). */
void hd_sim_state(const hd_sim *s, hd_state_measures *out);

/* Checks every pair of nearby bodies for overlap at the current time: returns the largest
 * relative overlap (D - |r|)/D found (<= 0 when none), with the pair in *i, *j. O(N). */
double hd_sim_max_overlap(const hd_sim *s, int32_t *i, int32_t *j);

/* Serialises the exact state (bodies, cells, clocks, RNG) into a malloc'd blob. */
int hd_sim_checkpoint(const hd_sim *s, void **blob, size_t *n, hd_error *err);

/* Whether blob (n bytes, a model blob as hd_sim_checkpoint makes it) is of a format that is
 * only ever stored with the runner's checksum trailer (run/hd_run.c): HAFFCKP2, every
 * version since the species table.  Such a blob found without its trailer has lost it (a
 * truncation, a hand edit) and is damaged; only a first-version blob (HAFFCKP1) may lack it. */
int hd_sim_checkpoint_needs_trailer(const void *blob, size_t n);

/* Builds a simulation from a scene and a blob saved by hd_sim_checkpoint for a run of that scene
 * (no placement is done, no file read): the continuation is bit-identical to the uninterrupted
 * run.  HD_EINPUT if the blob does not fit the scene or this build. */
int hd_sim_alloc_restore(hd_sim **out, const hd_scene *sc, const void *blob, size_t n,
                         hd_error *err);

#endif
