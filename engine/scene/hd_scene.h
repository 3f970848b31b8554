/* hd_scene: scene files (INI, read with libinih) and `--set SECTION.KEY=VALUE` overrides.
 * DESIGN.md lists the sections and keys.  A section appears only when the scene needs it;
 * absent sections leave their counts at 0 and cost nothing.  Every error names the file, the
 * line and the key, and why: "scene.ini:7: [disks] alpha = 1.5: must be in [0, 1]". */
#ifndef HD_SCENE_H
#define HD_SCENE_H

#include "hd_body.h" /* HD_MAX_BODY_DISKS */
#include "hd_error.h"

#define HD_PATH_MAX 1024
#define HD_MAX_VEL_AT 64

/* Limits checked by hd_scene_load (docs/scene-keys.md explains them). */
#define HD_MAX_AREA_FRACTION 0.9069 /* `area_fraction` < this: hexagonal packing pi/(2 sqrt 3) */
#define HD_RANDOM_MAX_FRACTION                                                                     \
  0.75                          /* placement = random: covered fraction <= this; beyond            \
                                 * what random addition reaches (disks jam at 0.547) the           \
                                 * engine melts a dense lattice (pi/4 for disks) */
#define HD_MAX_COUNT 100000000L /* largest `count` of a species */
#define HD_MIN_BOND                                                                                \
  1e-9 /* [dimers] a: 0 or >= this times d.  Below ~1e-15 d the two disks                          \
        * sit within an ulp of the centre (collisions pile up); 1e-9 keeps                         \
        * the bond ~1e4 ulps long in a box of 1e3 d */
#define HD_MAX_MASS_RATIO                                                                          \
  1e12 /* [species] disks: largest mass over smallest in one body.  A light disk far from a heavy  \
        * centre of mass spins up to sqrt(n ratio) times the translational speed (rim speed =      \
        * rmax / radius of gyration); the contact search steps through the turns.  1e12 keeps it   \
        * within the 1e7 a state file allows (measured: 1e22 took 3x the time of 1e10, 1e30 made   \
        * no progress in 20 s) */
#define HD_MAX_DIAMETER_RATIO                                                                      \
  1e4 /* [species] disks: largest diameter over smallest in one body.  The contact tolerances of   \
       * a pair of bodies are relative to their smallest disk (1e-10 of it at t = 0), the          \
       * round-off of a disk's place to the body's size (~4 d_max ulps): 1e4 keeps that below the  \
       * tolerance by 25x */
#define HD_MIN_INERTIA                                                                             \
  1e-250 /* a body that turns: its moment of inertia in [this, 1 / this], so that the spin energy  \
          * and the thermal spin T / I stay within doubles (dimer 1e-155: I = 5e-311, e_rot NaN)   \
          */
#define HD_SCENE_MAX_LINE 4096 /* longest scene line, in bytes */
#define HD_FRAMES_MAX_MB 1000  /* default `frames_max_mb`: 1 GB of frames */
#define HD_FRAME_BODY_BYTES 36 /* bytes per body in a frame (db/schema.sql, table frames) */
#define HD_FRAME_ROW_BYTES                                                                         \
  40 /* SQLite's bytes per frames row besides the data: ~20 of record (dbstat) and its index       \
      * entry; a frame of a few bodies also leaves part of its page empty, not counted here */
#define HD_SCENE_MAX_BYTES (1L << 20) /* largest scene file (a scene is ~1 kB) */
#define HD_STATE_MAX_LINE 4096        /* longest line of a state CSV, in bytes */

#define HD_MAX_SPECIES 8 /* species in one scene, [dimers] and [disks] included */
#define HD_SPECIES_NAME_MAX 32

/* One `[species NAME]` section: a rigid planar cluster of disks (issue 18, docs/scene-keys.md). */
typedef struct hd_scene_species {
  char name[HD_SPECIES_NAME_MAX]; /* NAME: [A-Za-z0-9_]{1,31}, unique; "dimer", "disk",
                                   * "dimers", "disks" are reserved for the shorthand sections */
  long count;                     /* `count` [0] */
  int ndisk;                      /* disks per body, 1 .. HD_MAX_BODY_DISKS */
  double x[HD_MAX_BODY_DISKS];    /* disk centres in the body frame, as given (any origin: the */
  double y[HD_MAX_BODY_DISKS];    /*   engine moves the origin to the centre of mass) */
  double d[HD_MAX_BODY_DISKS];    /* diameters, > 0 */
  double m[HD_MAX_BODY_DISKS];    /* masses, > 0 */
  double alpha;                   /* `alpha` [1]: restitution within the species */
  double beta;                    /* `beta` [-1 = smooth]: tangential restitution within it */
  double q;                       /* `q` [0]: each disk's own inertia q m (d/2)^2 (1/2: uniform) */
  long line;                      /* line of the section header in the scene (0 from --set) */
} hd_scene_species;

/* Where the initial state comes from ([init] placement / state). */
typedef enum hd_placement {
  HD_PLACE_RANDOM = 0,  /* random non-overlapping placement (default) */
  HD_PLACE_LATTICE = 1, /* on a lattice, orientations random */
  HD_PLACE_STATE = 2    /* every body from [init] state = FILE.csv */
} hd_placement;

/* What [log] collisions = ... keeps. */
typedef enum hd_logmode {
  HD_LOG_ALL = 0,  /* every collision (default) */
  HD_LOG_NONE = 1, /* no collision rows at all */
  HD_LOG_EVERY = 2 /* every log_every-th collision */
} hd_logmode;

/* Bits of hd_scene.walls ([walls] sides = left right bottom top). */
enum { HD_WALL_LEFT = 1, HD_WALL_RIGHT = 2, HD_WALL_BOTTOM = 4, HD_WALL_TOP = 8 };

/* A parsed scene.  Defaults in brackets; 0 counts mean the section is absent. */
typedef struct hd_scene {
  char path[HD_PATH_MAX]; /* the scene file as given ("" for a string scene) */
  char dir[HD_PATH_MAX];  /* its folder, for relative paths ("." for a string scene) */
  /* [system] */
  double box_x, box_y;     /* box edges: `box = Lx Ly`, or derived from area_fraction */
  double area_fraction;    /* `area_fraction = eta` instead of box: square box [0 if box given] */
  unsigned long long seed; /* `seed` [1]; the CLI's --seed overrides it */
  char box_at[HD_PATH_MAX + 64]; /* where `box` or `area_fraction` was given, as the scene's
                                  * messages say it ("FILE:LINE", "--set system.box=20 20"),
                                  * for the engine's set-up errors about the box ("": nowhere) */
  /* [dimers] */
  long n_dimers;      /* `count` [0] */
  double dimer_d;     /* `d` [1]: disk diameter */
  double dimer_a;     /* `a` [1]: bond length */
  double dimer_m;     /* `m` [1]: mass of each disk */
  double dimer_alpha; /* `alpha` [1]: dimer-dimer restitution */
  double dimer_beta;  /* `beta` [-1 = smooth]: dimer-dimer tangential restitution */
  double dimer_q;     /* `q` [0]: each disk's own inertia q m (d/2)^2 */
  /* [disks] */
  long n_disks;            /* `count` [0] */
  double disk_sigma;       /* `sigma` [1] */
  double disk_mass;        /* `mass` [1] */
  double disk_alpha;       /* `alpha` [1]: disk-disk restitution */
  double disk_alpha_dimer; /* `alpha_dimer` [= alpha]: dimer-disk restitution */
  double disk_beta;        /* `beta` [-1 = smooth]: disk-disk tangential restitution */
  double disk_beta_dimer;  /* `beta_dimer` [= beta]: dimer-disk tangential restitution */
  double disk_q;           /* `q` [0]: the disk's own inertia q mass (sigma/2)^2 */
  /* [species NAME] sections, in the order they appear (engine species 2, 3, ...; [dimers] is
   * species 0 and [disks] species 1 as now) */
  int n_named;                                /* how many */
  hd_scene_species named[HD_MAX_SPECIES - 2]; /* the sections */
  double alpha_pair[HD_MAX_SPECIES]
                   [HD_MAX_SPECIES];                /* restitution between engine species i != j
                                                     * (symmetric); filled by the loader, with
                                                     * the defaults applied (never NaN after load) */
  double beta_pair[HD_MAX_SPECIES][HD_MAX_SPECIES]; /* tangential restitution between engine
                                                     * species i, j (i = j included; symmetric),
                                                     * filled by the loader: the smaller of the
                                                     * two `beta`s, [disks] beta_dimer, the
                                                     * beta_OTHER keys */
  int rough; /* set by the loader: 1 when some beta (pairs, walls) is above -1.  The engine reads
              * beta_pair and wall_beta only then: a scene filled in code (zeros) is smooth */
  /* [walls] */
  unsigned walls;    /* `sides`: HD_WALL_* bits [0: fully periodic] */
  double wall_alpha; /* `alpha` [1] */
  double wall_beta;  /* `beta` [-1 = smooth]: body-wall tangential restitution */
  /* [init] */
  double temperature;           /* `temperature` [1]: kT per degree of freedom (not with state) */
  hd_placement placement;       /* `placement` [random], or HD_PLACE_STATE when `state` given */
  char state_file[HD_PATH_MAX]; /* `state`: resolved against dir, made absolute (realpath) */
  /* [run] */
  double stop_time;        /* `stop_time` [0 = unset] */
  double stop_events;      /* `stop_events` [0 = unset]: collisions */
  double stop_cpd;         /* `stop_cpd` [0 = unset]; at least one stop must be set */
  int verify;              /* `verify` [0]: check no-overlap and time order at every event */
  double checkpoint_every; /* `checkpoint_every` [60]: wall-clock seconds between checkpoints */
  /* [log] */
  hd_logmode log_collisions;           /* `collisions` = all | none | every N */
  long log_every;                      /* N of `every N` [1] */
  double samples_every;                /* `samples_every` [0 = none], in cpd */
  double velocities_at[HD_MAX_VEL_AT]; /* `velocities_at` (cpd) or `velocities_at_time` (times):
                                          snapshot values, strictly ascending */
  int n_velocities_at;                 /* how many */
  int velocities_in_time;              /* 1: velocities_at holds times (`velocities_at_time`), each
                                          snapshot taken at exactly that time; 0: cpd values */
  double frames_every;      /* `frames_every` [0 = none]: a frame (positions, orientations,
                             * velocities of every body) every this many cpd */
  double frames_every_time; /* `frames_every_time` [0 = none]: a frame at t = 0, T, 2T, ...
                             * exactly (needs stop_time); not with frames_every */
  double frames_max_mb;     /* `frames_max_mb` [HD_FRAMES_MAX_MB]: cap on the frames' storage */
  /* [rods] (engine/rods/rods.h, docs/rods.md): a rods scene has no bodies, box, walls or [init] */
  long n_rods;            /* `count` [0]: rods on the ring (even, >= 2), ring length = count */
  double rod_gamma;       /* `gamma` [0.8]: length (and mass) ratio short/long, in (0, 1] */
  long rod_nmod;          /* `nmod` [1000]: vibrational modes per rod */
  int rod_model;          /* `model` = stochastic (0) | constant (1) [stochastic] */
  double rod_eps;         /* `eps` [= gamma]: the constant model's restitution, in [0, 1] */
  double rod_damping;     /* `damping` [0]: nu, bath temperatures decay as exp(-nu t) */
  double rod_tc;          /* `tc` [0 = off]: TC model, eps = 1 if a rod collided within tc */
  double rod_temperature; /* `temperature` [1]: initial <m v^2> (sets the units: 1) */
  int rod_table;          /* `table` [yes for the stochastic model with mean baths and
                           * gamma < 1, else no]: draw eps from the balanced tabulated p_beta
                           * (eps_table.c; docs/rods.md), no: the direct sampler */
  double rod_eps_step;    /* `eps_step` [0 = the sampler's 0.01]: grid step of the direct eps
                           * sampler; its sqrt(step) bias lowers the stationary E_kin by ~3 % at
                           * 0.01, ~1 % at 0.0025 (docs/rods.md) */
  int rod_unequal;        /* `baths` = mean (0) | unequal (1) [mean]: beta of each rod separately */
  char *text; /* malloc'd canonical INI of the effective scene (file + overrides), for runs.scene */
} hd_scene;

/* Fills *sc with the defaults (no bodies, no stop, text NULL): the defaults of the key table
 * (engine/scene/hd_scene.c, docs/scene-keys.md).  alpha_pair is filled by the loader, not here. */
void hd_scene_defaults(hd_scene *sc);

/* Reads scene file `path` (overwriting *sc, which must not hold a loaded scene: hd_scene_free
 * it first; HD_EINPUT for a path that is not a regular file or has more than
 * HD_SCENE_MAX_BYTES), then applies n_over overrides "SECTION.KEY=VALUE" (errors in them
 * are reported as "--set SECTION.KEY=VALUE: ..."), then checks the whole (ranges, a stop
 * condition, bodies fit in the box).  Returns HD_OK, HD_EINPUT or HD_EIO (cannot read the scene
 * or its state file).  With `state`, the state CSV is read to check it and to count its bodies:
 * an absent `count` is taken from it, a `count` that disagrees is an error.  On error *sc holds
 * no allocation (text NULL).  Not thread-safe: it sets libinih's line-length option while it
 * parses (and restores it). */
int hd_scene_load(hd_scene *sc, const char *path, const char *const *over, int n_over,
                  hd_error *err);

/* As hd_scene_load but from INI text in memory; `name` stands for the file name in messages. */
int hd_scene_load_string(hd_scene *sc, const char *text, const char *name, const char *const *over,
                         int n_over, hd_error *err);

/* As hd_scene_load_string for the canonical text of a run (runs.scene), to resume it from its
 * checkpoint: a state file is not read again (the checkpoint holds the bodies, the text their
 * counts), so a run whose CSV was moved, edited or deleted still resumes. */
int hd_scene_load_stored(hd_scene *sc, const char *text, const char *name, hd_error *err);

/* As hd_scene_load_stored for the programs that only read a stored run (analysis, export): the
 * same parser, keys, ranges, defaults and [species] geometry, and the box derived from
 * area_fraction, but none of the checks of whether the run could start (a stop condition,
 * required counts, bodies that fit the box, the frames' cap, the state file). */
int hd_scene_read_stored(hd_scene *sc, const char *text, const char *name, hd_error *err);

/* Regenerates the key tables of docs/scene-keys.md from the key table: `in` is the document,
 * each table sits between a line `<!-- keys SECTION -->` and a line `<!-- end keys -->` and is
 * replaced; the rest is copied.  *out is malloc'd (free()).  HD_EINPUT for an unknown SECTION
 * or an unclosed table, HD_ENOMEM. */
int hd_scene_keys_doc(const char *in, char **out, hd_error *err);

/* The k-th scene key of the key table (k = 0, 1, ...) as an override names it, into buf:
 * "SECTION.KEY" ("system.seed"; "species.NAME.count" for a [species NAME] key, NAME and the
 * OTHER of alpha_OTHER standing for names).  Returns 0, or 1 when k is past the last key (or
 * buf too small). */
int hd_scene_key_name(int k, char *buf, size_t size);

/* Whether override `over` ("SECTION.KEY=VALUE", as hd_scene_load reads it) sets [section] key. */
int hd_scene_override_sets(const char *over, const char *section, const char *key);

/* Frees what the scene owns (text).  The struct itself is the caller's. */
void hd_scene_free(hd_scene *sc);

/* Area of one dimer: the union of two disks of diameter d whose centres are a apart (two whole
 * disks when a >= d, minus their lens-shaped overlap when a < d; one disk when a = 0). */
double hd_dimer_area(double d, double a);

/* Area of the union of n disks (centres x, y, diameters d): exact up to round-off for any
 * overlaps (Green's theorem on the arcs of the union's boundary: each circle's arcs that no other
 * disk covers, integrated in closed form), O(n^2 log n). */
double hd_disks_area(int n, const double *x, const double *y, const double *d);

/* Area one body of a named species covers: the union of its disks (hd_dimer_area for two equal
 * disks, so that `shape = dimer A` covers what a [dimers] dimer does bit for bit; hd_disks_area
 * otherwise). */
double hd_species_area(const hd_scene_species *sp);

/* Largest extent of one body of a named species: the diameter of its union of disks, max over
 * pairs of disks of centre distance + (d_i + d_j)/2.  Its width in any direction is at most
 * this, so a square cell of this edge holds the body in any orientation. */
double hd_species_extent(const hd_scene_species *sp);

/* Total area of the scene's bodies (dimers, disks and named species, overlaps within a body
 * counted once). */
double hd_scene_covered_area(const hd_scene *sc);

/* Bodies of the scene: dimers + disks + named species, or rods. */
long hd_scene_bodies(const hd_scene *sc);

/* Bytes one frame of the scene takes in the database (data and row). */
double hd_scene_frame_bytes(const hd_scene *sc);

/* How many frames the scene's run takes at most (frame 0 included): 0 when it asks for none,
 * -1 when its stops do not bound the count (frames_every with stop_time only). */
double hd_scene_frames_estimate(const hd_scene *sc);

/* One body of an [init] state CSV. */
typedef struct hd_state_row {
  int kind;         /* HD_KIND_DISK or HD_KIND_DIMER (hd_body.h); a named species' body is
                     * HD_KIND_DIMER when it has 2 or more disks (it has an orientation) */
  int species;      /* engine species index: 0 dimer, 1 disk, 2 + k for named[k] */
  double x, y, phi; /* phi (and omega) ignored (0) for disks and one-disk species, unless the
                     * scene (hd_state_csv_read_species) gives them q > 0: rough disks spin */
  double vx, vy, omega;
  long line; /* line number in the CSV, for messages */
} hd_state_row;

/* Reads a state CSV with header `kind,x,y,phi,vx,vy,omega` ([init] state): `kind` is dimer,
 * disk or the name of one of sc's [species NAME] sections (sc NULL: dimer and disk only).
 * *rows is malloc'd (free()).  Errors name file and line. Overlaps are checked by the engine,
 * which knows the shapes.  Bounded: HD_EINPUT for a path that is not a regular file (a FIFO,
 * /dev/zero), a line longer than HD_STATE_MAX_LINE or more rows than 2 HD_MAX_COUNT, before
 * memory grows with them. */
int hd_state_csv_read_species(const char *path, const hd_scene *sc, hd_state_row **rows, long *n,
                              hd_error *err);

#endif
