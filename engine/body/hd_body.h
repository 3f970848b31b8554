/* hd_body: rigid bodies in 2D — shapes, exact free flight, earliest contact and the collision
 * rules.  Pure functions of the states they are given: no global state, no allocation.
 * Conventions are those of DESIGN.md and docs/contract.md:
 *   - a body is a rigid planar cluster of n >= 1 disks (each its own diameter and mass) at fixed
 *     offsets (ox, oy) from its centre of mass in the body frame; the body frame is turned by
 *     phi (counter-clockwise), so disk k is at R + Rot(phi) (ox_k, oy_k); omega > 0 is
 *     counter-clockwise.  The disks are point masses at their centres for the moment of inertia,
 *     I = sum m_k |o_k|^2 (the paper's dimer: I = m a^2 / 2);
 *   - a dimer is the case of two equal disks at (-+a/2, 0): disk 0 at R - (a/2)(cos phi, sin phi),
 *     disk 1 at +; total mass 2m;
 *   - a disk body has one disk (index 0) at R; phi, omega unused (0) unless the disk has a
 *     moment of inertia of its own (hd_shape_set_q: a rough disk spins; its turning does not
 *     change its shape, so its contacts are still found as a disk's).
 *   - contact angle theta of a body in (-pi, pi]: signed angle from the body's outward axis at its
 *     contacting disk (unit vector from the centre of mass to that disk; for a dimer, from the
 *     partner disk to the contacting disk) to the contact normal (from its contacting disk to the
 *     other body's contacting disk).  Head-on is 0.  NaN when the contacting disk sits at the
 *     centre of mass (a disk body, the middle disk of a symmetric trimer).
 */
#ifndef HD_BODY_H
#define HD_BODY_H

#include <stdint.h>

#define HD_MAX_BODY_DISKS 8 /* disks in one rigid body (a scene species' shape too: hd_scene.h) */

/* The kind of a body: the one enumeration of kinds in every layer.  As a shape's tag (hd_shape,
 * derived by the constructors below) it is the fast path the shape takes: the paper's formulas
 * and the closed forms for disks and equal dimers, the general rigid-body code for every other
 * cluster (which gives the same results to round-off: tests/test_body.c).  As a species' kind
 * it is what the section made, stored as states.kind ('disk', 'dimer', 'body', 'rod') and in a
 * state file row (hd_state_row.kind); a pair of kinds gives a collision's kind (hd_coll_kind).
 * The values of DISK, DIMER and BODY are those of the shape tag in a checkpoint blob. */
typedef enum hd_kind {
  HD_KIND_DISK = 0,  /* one hard disk ([disks]; tag: one disk) */
  HD_KIND_DIMER = 1, /* two hard disks on a rigid bond ([dimers]; tag: two equal disks (same d,
                      * m) at (-+a/2, 0) in the body frame) */
  HD_KIND_BODY = 2,  /* any other rigid cluster of disks (a [species NAME]; tag: the general
                      * code) */
  HD_KIND_ROD = 3,   /* a rod of the 1D ring ([rods]) */
  HD_KIND_WALL = 4   /* a wall, as the partner of a collision (no body is of this kind) */
} hd_kind;
#define HD_NKINDS 5 /* kinds, HD_KIND_WALL included */

/* The text of a kind as states.kind stores it ("disk", "dimer", "body", "rod"; "wall"), or NULL
 * for another value. */
const char *hd_kind_name(int kind);

/* The kind of a collision: the pair of its partners' kinds, a * HD_NKINDS + b (body i of kind a,
 * j of kind b or HD_KIND_WALL), as hd_coll_kind_of makes it; stored as collisions.kind text,
 * "A-B" (hd_coll_kind_name). */
typedef int hd_coll_kind;

/* The collision kind of a body of kind a (i) with one of kind b (j; HD_KIND_WALL for a wall), as
 * the log keeps it: a pair with a BODY (a named species) is body-body, or body-wall; a dimer and
 * a disk are dimer-disk whichever is i; else A-B.  The kinds a pair of rods, disks or dimers give
 * the paper's names: dimer-dimer, dimer-disk, disk-disk, dimer-wall, disk-wall, rod-rod. */
static inline hd_coll_kind hd_coll_kind_of(hd_kind a, hd_kind b) {
  if (a == HD_KIND_BODY || b == HD_KIND_BODY)
    a = HD_KIND_BODY, b = b == HD_KIND_WALL ? HD_KIND_WALL : HD_KIND_BODY;
  else if (a == HD_KIND_DISK && b == HD_KIND_DIMER)
    a = HD_KIND_DIMER, b = HD_KIND_DISK;
  return (hd_coll_kind)(a * HD_NKINDS + b);
}

/* The text of a collision kind ("dimer-disk", ...), "?" for a pair hd_coll_kind_of never makes. */
const char *hd_coll_kind_name(hd_coll_kind k);

/* The shape and mass of a body species. */
typedef struct hd_shape {
  hd_kind tag; /* the fast path (derived): HD_KIND_DISK, HD_KIND_DIMER or HD_KIND_BODY */
  int n;       /* disks, 1 .. HD_MAX_BODY_DISKS */
  double d;    /* DISK, DIMER: diameter of each disk; BODY: the largest diameter */
  double a;    /* DIMER: bond length, centre to centre, >= 0; else 0 */
  double m;    /* DISK, DIMER: mass of each disk (a dimer weighs 2m); BODY: disk 0's */
  double ox[HD_MAX_BODY_DISKS], oy[HD_MAX_BODY_DISKS]; /* disk centres minus the centre of
                                                        * mass, body frame */
  double dk[HD_MAX_BODY_DISKS], mk[HD_MAX_BODY_DISKS]; /* diameters and masses of the disks */
  double mass;                                         /* total mass */
  double inertia; /* moment of inertia about the centre of mass, sum m_k |o_k|^2, plus
                   * sum q m_k (d_k/2)^2 after hd_shape_set_q */
  double radius;  /* smallest circle about the centre of mass that holds the body,
                   * max |o_k| + d_k / 2 */
  double rmax;    /* largest distance of a disk centre from the centre of mass, max |o_k| */
} hd_shape;

/* A disk body of diameter d and mass m. */
void hd_shape_disk(hd_shape *s, double d, double m);
/* The paper's dimer: two disks of diameter d and mass m, centres a apart (a >= 0). */
void hd_shape_dimer(hd_shape *s, double d, double a, double m);
/* A cluster of n disks (1 .. HD_MAX_BODY_DISKS) at (x[k], y[k]) with diameters d[k] > 0 and
 * masses m[k] > 0, in a frame of any origin: the origin is moved to the centre of mass (the body
 * frame's axes stay).  fast = 1 gives the disk or dimer tag to a shape that is one (one disk; two
 * equal disks on the x axis symmetric about the centre of mass), fast = 0 the general code in every
 * case (the tests compare the two).  Returns 0, or -1 for n or a diameter or mass out of range
 * (*s is then unchanged). */
int hd_shape_cluster(hd_shape *s, int n, const double *x, const double *y, const double *d,
                     const double *m, int fast);

/* The kinematic state of a body at some time origin. */
typedef struct hd_kin {
  double x, y;   /* centre of mass */
  double vx, vy; /* centre-of-mass velocity */
  double phi;    /* orientation of the body frame (a dimer: of the axis disk 0 -> disk 1; 0 for a
                  * disk body), kept in (-pi, pi] */
  double omega;  /* signed angular velocity (0 for a disk body) */
} hd_kin;

/* A hard wall: the line {axis coordinate == pos}; bodies live on the side `normal` points to. */
typedef struct hd_wall {
  int axis;      /* 0: the wall is x = pos; 1: the wall is y = pos */
  double pos;    /* the wall's coordinate */
  double normal; /* +1 or -1: the inward normal's sign along that axis */
} hd_wall;

/* The earliest contact found by a prediction. */
typedef struct hd_contact {
  double t; /* time of contact, measured from the common time origin of the states */
  int ka;   /* the disk of body A that touches (0 .. n - 1; 0 for a disk body) */
  int kb;   /* the disk of body B that touches (0 .. n - 1; 0 for a disk or a wall) */
} hd_contact;

/* What a collision did, for the log. */
typedef struct hd_collision_info {
  double theta_i; /* contact angle of body A (DESIGN.md); NaN for a disk body */
  double theta_j; /* contact angle of body B; NaN for a disk body or a wall */
  double f;       /* orientation factor mu_eff / m_ref: eq. 36 for dimer-dimer; m_ref is the mass
                   * of the contacting disk of the first body of the pair that has more than one
                   * disk (A if both or neither have; a dimer's m, a disk body's mass: see
                   * hd_body_impulse.c) */
  double de;      /* kinetic energy of the pair after minus before (<= 0 for alpha <= 1), computed
                   * as -(1 - alpha^2) mu_eff vn^2 / 2 (no cancellation); 0 if not approaching */
  double vn;      /* normal relative velocity of the contact points before (< 0: approaching) */
} hd_collision_info;

/* Gives each disk of s its own moment of inertia q m_k (d_k/2)^2 (q = 1/2: uniform disks; 0:
 * the point masses of the dimer paper, s unchanged), added to s->inertia.  A dimer with q > 0
 * takes the general code (HD_KIND_BODY): the paper's formulas have I = m a^2 / 2.  Call it
 * once, after the constructor.  Returns 0, or -1 for q outside [0, 1] (s unchanged). */
int hd_shape_set_q(hd_shape *s, double q);

/* Total mass of a body of shape s. */
double hd_shape_mass(const hd_shape *s);
/* Moment of inertia about the centre of mass (m a^2 / 2 for a dimer, 0 for a disk body). */
double hd_shape_inertia(const hd_shape *s);
/* Radius of the smallest circle about the centre of mass that holds the body ((a + d) / 2 for a
 * dimer). */
double hd_shape_radius(const hd_shape *s);

/* Exact free flight of k over dt (any sign): translation, and rotation with phi wrapped to
 * (-pi, pi].  No division by omega; omega = 0 and |omega| large are exact. */
void hd_kin_advance(hd_kin *k, double dt);

/* Centre of disk `which` (0 .. n - 1) of a body in state k (at k's time origin). */
void hd_kin_disk_pos(const hd_kin *k, const hd_shape *s, int which, double *px, double *py);

/* Velocity of the centre of disk `which` of a body in state k. */
void hd_kin_disk_vel(const hd_kin *k, const hd_shape *s, int which, double *vx, double *vy);

/* What a search returns when a stop was requested (hd_stop.h) while it ran: it is unfinished,
 * and c->t is the time it reached, before which there is no contact.  Searches look at the stop
 * request every HD_CA_POLL + 1 steps (a power of two minus one: a mask of hd_ca.it); short
 * searches, nearly all of them, never do. */
#define HD_CA_CUT 3
#define HD_CA_POLL 0xffffL

/* Earliest time t in [0, tmax] at which bodies A and B, both given at a common time origin and B
 * already in A's periodic image, come into contact (some disk pair at distance (dA + dB)/2) while
 * approaching.  Returns 1 and fills *c if they do, 0 if not before tmax, HD_CA_CUT (c->t filled)
 * if a stop was requested during a long search.  A pair that overlaps by
 * round-off at t = 0 while approaching gets t = 0; one that is receding (it has just collided) is
 * ignored.  Never skips a root (see hd_body.c for the method and its tolerance). */
int hd_predict_pair(const hd_kin *A, const hd_shape *sa, const hd_kin *B, const hd_shape *sb,
                    double tmax, hd_contact *c);

/* Disk pairs a contact search handles: every disk of one body against every disk of the other. */
#define HD_CA_MAXP (HD_MAX_BODY_DISKS * HD_MAX_BODY_DISKS)

/* The moving geometry of a conservative-advancement search (hd_body.c): the "pairs", the disk
 * pairs of two bodies or the disks of one body against a wall, from a common time origin.
 * Filled and read by hd_body.c only; public so that a caller can hold an hd_ca. */
typedef struct hd_ca_geom {
  int wall;              /* 0: body pair, 1: body against a wall */
  int na, nb;            /* disks of A and B (nb = 1 for a wall) */
  const hd_shape *sha;   /* general code: A's shape (its offsets, diameters); NULL: the disk and
                          * dimer fast path, with ha, hb and D */
  const hd_shape *shb;   /* general code: B's shape (NULL for a wall) */
  double dx, dy;         /* pair: R_B - R_A at t = 0; wall: (gap of A's centre, unused) */
  double dvx, dvy;       /* pair: V_B - V_A; wall: (rate of the centre's gap, unused) */
  double ha, hb;         /* half bond lengths (general code: rmax of each shape) */
  double pa, wa, pb, wb; /* orientations and angular velocities */
  double wsin;           /* wall: the axis coordinate of the offset is sin (1) or cos (0) */
  double wn;             /* wall: inward normal sign */
  double D;              /* contact distance (pair) or disk diameter (wall); general code: the
                          * smallest of the pairs', the scale of the tolerances */
  double L, K, K2u;      /* bounds on |h'|, the lower bound on h'' (-K), an upper bound on h'' */
  double vs;             /* size of the disks' own velocities, |V| + |w| a/2 of each body: their
                          * round-off widens the margin of "approaching" (HD_DISK_VROUND) */
} hd_ca_geom;

/* A contact search between two bodies that the caller advances one step at a time (hd_ca_begin,
 * hd_ca_step), so that the searches of several pairs can be interleaved, always advancing the one
 * that could touch first and stopping them all once that bound passes the earliest contact found.
 * Only t is for the caller; the other fields are private to hd_body.c. */
typedef struct hd_ca {
  double t;        /* no contact of the pair before t (from the common time origin) */
  hd_ca_geom g;    /* the geometry */
  double tend;     /* the search ends after tend (the enclosing circles part for good) */
  uint64_t ign;    /* disk pairs ignored as just collided (bit p for pair p) */
  int fresh;       /* the t = 0 contact checks are still to be made */
  long it;         /* steps taken (guard against misuse, see hd_body.c) */
  int sc0;         /* sa0, ca0 hold sin and cos of A's orientation at t = 0 */
  double sa0, ca0; /* (given to hd_ca_begin: shared by the searches of one body) */
} hd_ca;

/* sin and cos of x exactly as the contact search computes them (for hd_ca_begin's sca). */
void hd_ca_sincos(double x, double *s, double *c);

/* Starts the search for the earliest contact of A and B in [0, tmax], with the contract of
 * hd_predict_pair.  sca is NULL or {sin, cos} of A->phi from hd_ca_sincos (a caller searching
 * many partners of one dimer computes it once).  Returns 0 if there is none, 1 with *c filled if it
 * is already known (no rotation: closed form), 2 if the search is under way: then ca->t is a lower
 * bound on the contact time and hd_ca_step continues it. */
int hd_ca_begin(hd_ca *ca, const hd_kin *A, const hd_shape *sa, const hd_kin *B, const hd_shape *sb,
                double tmax, const double *sca, hd_contact *c);

/* The radius R of the window in which a search of bodies of shapes sa and sb can find a contact:
 * the centres of mass within R (the enclosing circles, widened against round-off), exactly as
 * hd_ca_begin computes it. */
double hd_ca_reach(const hd_shape *sa, const hd_shape *sb);

/* When two circles in linear relative motion part for good: with c = |dR|^2 - R^2, b = dR.dV,
 * v2 = |dV|^2 and disc = b^2 - v2 c >= 0, the larger root of |dR + dV t| = R (HUGE_VAL for v2 = 0
 * and c <= 0: they never part).  The window ends of hd_ca_begin and of its callers
 * (hd_ca_begin_in) are this one function, so that both are the same number. */
double hd_circle_exit(double c, double b, double v2, double disc);

/* hd_ca_begin for a caller that has already computed the window [t_in, t_out] in which the
 * centres are within hd_ca_reach(sa, sb) of each other, as hd_ca_begin would from A and B
 * (c = |dR|^2 - R^2, b = dR.dV, disc = b^2 - |dV|^2 c; t_in = 0 if c <= 0, else
 * c / (sqrt(disc) - b); t_out = (sqrt(disc) - b) / |dV|^2, or -c / (b + sqrt(disc)) when c <= 0
 * and b > 0), non-empty: the same search bit for bit, without computing the window again. */
int hd_ca_begin_in(hd_ca *ca, const hd_kin *A, const hd_shape *sa, const hd_kin *B,
                   const hd_shape *sb, double tmax, const double *sca, double t_in, double t_out,
                   hd_contact *c);

/* One step of a search under way (hd_ca_begin returned 2), with tmax no larger than at the start
 * (it may shrink between steps, e.g. to the earliest contact found with other bodies).  Returns 0
 * if there is no contact in [0, tmax], 1 with *c filled at the earliest contact, 2 if the search
 * is still under way (ca->t has grown: no contact before it). */
int hd_ca_step(hd_ca *ca, double tmax, hd_contact *c);

/* Closed-form contact of two disks in linear relative motion (hd_predict_pair without
 * rotation; the engine's disk fast path is hd_disk.h): separation d = (dx, dy) (B - A),
 * relative velocity (dvx, dvy) (B - A), contact distance D, vs >= |vA| + |vB| (the size of the
 * velocities themselves, whose round-off the "approaching" test allows for).  Returns 1 with
 * the earliest contact time *t in [0, tmax] while approaching, 0 if none.  Same t = 0 and
 * grazing rules as hd_predict_pair. */
int hd_predict_disks(double dx, double dy, double dvx, double dvy, double D, double vs, double tmax,
                     double *t);

/* Earliest time t in [0, tmax] at which body A touches wall w while approaching it; as above
 * (HD_CA_CUT included). */
int hd_predict_wall(const hd_kin *A, const hd_shape *sa, const hd_wall *w, double tmax,
                    hd_contact *c);

/* Collision of A (disk ka) and B (disk kb), in contact now: applies the paper's rule for the
 * pair's kinds (disk-disk; dimer-disk eq. 21-22; dimer-dimer eq. 13 and 18), or for a pair with
 * a general cluster the rigid-body impulse rule (hd_body_impulse.h), with restitution
 * alpha in [0, 1] along the contact normal, updating the velocities and angular velocities of A
 * and B.  A pair whose contact points are not approaching (vn >= 0) is left unchanged.  Dimers
 * need a > 0 (a = 0 exactly moves as a disk of mass 2m).  Fills *info if not NULL.  Returns 0. */
int hd_collide_pair(hd_kin *A, const hd_shape *sa, hd_kin *B, const hd_shape *sb, int ka, int kb,
                    double alpha, hd_collision_info *info);

/* hd_collide_pair, with the contact angles of *info (theta_i, theta_j) computed only if `angles`
 * (else NaN) for bodies of more than one disk; vn, de, f and the velocities after are
 * the same bit for bit.  The engine leaves them out when no collision is logged. */
int hd_collide_pair_ex(hd_kin *A, const hd_shape *sa, hd_kin *B, const hd_shape *sb, int ka, int kb,
                       double alpha, int angles, hd_collision_info *info);

/* Collision of A (disk ka) and B (disk kb) with restitution alpha in [0, 1] along the normal
 * and tangential restitution beta in [-1, 1] at the contact point (rough bodies; the rule and
 * its derivation: hd_body_rough.c, docs/analysis.md): the relative velocity g of the contact
 * points has g'_n = -alpha g_n after, and its slip g_s (the tangential velocity a frictionless
 * impulse would leave) becomes -beta g_s (for two disks g'_t = -beta g_t).  beta = -1 is the
 * smooth rule (the same physics as hd_collide_pair, not the same round-off), beta = 1 the
 * perfectly rough one.  Rotation with each body's hd_shape_inertia (hd_shape_set_q); a body of
 * zero inertia (a disk of q = 0) takes no torque and makes the contact smooth.  Conserves
 * momentum and angular momentum about the contact point; info->de (the loss of both parts,
 * <= 0) is 0 exactly for alpha = 1 and beta = +-1.  Same contract as hd_collide_pair
 * otherwise.  Returns 0. */
int hd_collide_rough_pair(hd_kin *A, const hd_shape *sa, hd_kin *B, const hd_shape *sb, int ka,
                          int kb, double alpha, double beta, hd_collision_info *info);

/* The rough rule against wall w (infinite mass and inertia), as hd_collide_rough_pair. */
int hd_collide_rough_wall(hd_kin *A, const hd_shape *sa, int ka, const hd_wall *w, double alpha,
                          double beta, hd_collision_info *info);

/* Collision of disk ka of A with wall w (eq. 24-25 for a dimer, the rigid-body impulse rule for a
 * general cluster), restitution alpha; left unchanged
 * if the disk is not moving towards the wall.  Fills *info if not NULL.  Returns 0. */
int hd_collide_wall(hd_kin *A, const hd_shape *sa, int ka, const hd_wall *w, double alpha,
                    hd_collision_info *info);

#endif
