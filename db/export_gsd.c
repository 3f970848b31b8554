/* The GSD writer of `haff export gsd` (cli/cmd_export.c): a run's states and frames as a GSD
 * file of the `hoomd` schema (HOOMD-blue's trajectory format, read by HOOMD, OVITO, freud and
 * gsd.hoomd), written from the published file-layer specification (GSD 2.x).
 *
 * File layer (all integers little-endian):
 *   header (256 bytes) at 0: magic 0x65DF65DF65DF65DF, index_location, index_allocated_entries,
 *     namelist_location, namelist_allocated_entries (64-byte segments), schema_version,
 *     gsd_version (uint32 each, 0xaaaabbbb = aaaa.bbbb), application[64], schema[64],
 *     reserved[80];
 *   the data chunks, in the order of the index;
 *   the index: one 32-byte entry per chunk (frame uint64, N uint64, location int64, M uint32,
 *     id uint16, type uint8, flags uint8 = 0), sorted by frame then id, ended by an entry of
 *     location 0 (one more entry than chunks is allocated);
 *   the namelist: the chunk names, each ended by a 0 byte, in id order, then a 0 byte (an empty
 *     name ends the list), padded with zeros to a multiple of 64 bytes.
 * The writer streams the chunks frame by frame, keeps the index in memory, and writes the index,
 * the namelist and the final header at the end, into FILE.tmp renamed to FILE on success.  The
 * chunk names are registered in one fixed order before the first frame, and each frame writes
 * them in that order, so that the ids of a frame ascend.
 *
 * The hoomd schema (1.4) as written here, for every frame (docs/python.md has the reader's view):
 *   configuration/step (uint64): the frame's index 0, 1, ...; configuration/dimensions (uint8) 2;
 *   configuration/box (float) Lx Ly 0 0 0 0 (a ring of rods: its length, and 1);
 *   particles/N, types (int8, NT x M: the names, 0-padded), typeid, mass, diameter, body,
 * moment_inertia, position, orientation, velocity, angmom, image: one particle per body, particle i
 * = body i; then, for every body of more than one disk, its disks (HOOMD's rigid-body convention:
 * the central particle has body = its own tag, the constituents body = the central particle's tag;
 * a single-disk body and a rod have body -1).  Types: the run's species (species.name in idx order;
 * 'rod'), then 'NAME_disk' for the disks of each species of more than one disk.  A central particle
 * has the body's mass, moment_inertia (0, 0, I), diameter 0, the orientation q = (cos phi/2, 0, 0,
 *   sin phi/2) and angmom p = 2 q (0, 0, 0, I omega) = (-2 sin(phi/2) I omega, 0, 0, 2 cos(phi/2)
 *   I omega), HOOMD's conjugate-quaternion momentum (the body-frame angular momentum is
 *   (q* p) / 2): I omega = (cos(phi/2) p_z - sin(phi/2) p_w) / 2.  A disk (free or constituent) has
 * its own mass, diameter, position and velocity (rotation included), the body's orientation, angmom
 * 0.  Positions are HOOMD's: the box is centred on 0, a coordinate x of haff's box [0, L) is
 * wrapped to x - i L (image i = floor(x / L)) and stored as x - i L - L/2; a rod lies on y = 0.
 *   log/haff/time, log/haff/cpd (double; cpd NaN when not stored), log/haff/label (uint8: 0
 *   initial, 1 frames, 2 velocities, 3 checkpoint, 4 final), and the exact values as doubles:
 *   log/haff/position (N x 3, haff's unwrapped coordinates), log/haff/velocity (N x 3),
 *   log/haff/phi and log/haff/omega (N: the body's; a rod's omega is its bath temperature).
 */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export_gsd.h"
#include "export_xyz.h"
#include "hd_body.h"

/* GSD's chunk types (file-layer specification). */
enum { GSD_U8 = 1, GSD_U32 = 3, GSD_U64 = 4, GSD_I8 = 5, GSD_I32 = 7, GSD_F32 = 9, GSD_F64 = 10 };

/* The chunk names in id order (every frame writes them in this order). */
enum {
  C_STEP,
  C_DIM,
  C_BOX,
  C_N,
  C_TYPES,
  C_TYPEID,
  C_MASS,
  C_DIAM,
  C_BODY,
  C_MOI,
  C_POS,
  C_ORIENT,
  C_VEL,
  C_ANGMOM,
  C_IMAGE,
  C_TIME,
  C_CPD,
  C_LABEL,
  C_XPOS,
  C_XVEL,
  C_XPHI,
  C_XOMEGA,
  C_COUNT
};
static const char *const chunk_names[C_COUNT] = {"configuration/step", "configuration/dimensions",
                                                 "configuration/box",  "particles/N",
                                                 "particles/types",    "particles/typeid",
                                                 "particles/mass",     "particles/diameter",
                                                 "particles/body",     "particles/moment_inertia",
                                                 "particles/position", "particles/orientation",
                                                 "particles/velocity", "particles/angmom",
                                                 "particles/image",    "log/haff/time",
                                                 "log/haff/cpd",       "log/haff/label",
                                                 "log/haff/position",  "log/haff/velocity",
                                                 "log/haff/phi",       "log/haff/omega"};

/* One index entry. */
typedef struct gsd_entry {
  uint64_t frame, n, location;
  uint32_t m;
  uint16_t id;
  uint8_t type;
} gsd_entry;

/* The writer and one frame's particle arrays. */
typedef struct gsd_out {
  FILE *f;
  const char *path;        /* the temporary file's name, for messages */
  const char *application; /* for the header */
  uint64_t pos;            /* bytes written */
  uint64_t frame;          /* frames written */
  gsd_entry *idx;
  size_t nidx, capidx;
  long cap; /* particles the arrays hold */
  uint32_t *typeid;
  float *mass, *diam, *moi, *pos3, *orient, *vel, *angmom;
  int32_t *body, *image;
  double *xpos, *xvel, *xphi, *xomega;
} gsd_out;

static void put_u16(unsigned char *b, uint16_t v) {
  b[0] = (unsigned char)v, b[1] = (unsigned char)(v >> 8);
}
static void put_u32(unsigned char *b, uint32_t v) {
  for (int k = 0; k < 4; k++) b[k] = (unsigned char)(v >> (8 * k));
}
static void put_u64(unsigned char *b, uint64_t v) {
  for (int k = 0; k < 8; k++) b[k] = (unsigned char)(v >> (8 * k));
}

/* Bytes of one element of a GSD type. */
static size_t type_size(int type) {
  return type == GSD_U8 || type == GSD_I8 ? 1 : type == GSD_U64 || type == GSD_F64 ? 8 : 4;
}

/* Writes n bytes at the end; 0 or 1 (said). */
static int out_write(gsd_out *w, const void *data, size_t n) {
  if (n && fwrite(data, 1, n, w->f) != n) {
    fprintf(stderr, "haff export: %s: write failed: %s\n", w->path, strerror(errno));
    return 1;
  }
  w->pos += n;
  return 0;
}

/* Writes chunk `id` of the current frame (n x m elements of `type`, in the machine's order,
 * which is little-endian on every platform haff supports: db/schema.sql's frames have the same
 * rule); 0 or 1 (said). */
static int chunk(gsd_out *w, int id, int type, uint64_t n, uint32_t m, const void *data) {
  if (w->nidx == w->capidx) {
    size_t cap = 2 * w->capidx + 256;
    gsd_entry *e = realloc(w->idx, cap * sizeof *e);
    if (!e) {
      fprintf(stderr, "haff export: out of memory for the GSD index\n");
      return 1;
    }
    w->idx = e;
    w->capidx = cap;
  }
  w->idx[w->nidx++] = (gsd_entry){w->frame, n, w->pos, m, (uint16_t)id, (uint8_t)type};
  return out_write(w, data, (size_t)(n * m) * type_size(type));
}

/* Room for n particles; 0 or 1 (said). */
static int room(gsd_out *w, long n) {
  if (n <= w->cap) return 0;
  long c = n;
#define GROW(p, k)                                                                                 \
  do {                                                                                             \
    void *q = realloc(w->p, (size_t)c * (k) * sizeof *w->p);                                       \
    if (!q) {                                                                                      \
      fprintf(stderr, "haff export: out of memory for a frame of %ld particles\n", n);             \
      return 1;                                                                                    \
    }                                                                                              \
    w->p = q;                                                                                      \
  } while (0)
  GROW(typeid, 1);
  GROW(mass, 1);
  GROW(diam, 1);
  GROW(moi, 3);
  GROW(pos3, 3);
  GROW(orient, 4);
  GROW(vel, 3);
  GROW(angmom, 4);
  GROW(body, 1);
  GROW(image, 3);
  GROW(xpos, 3);
  GROW(xvel, 3);
  GROW(xphi, 1);
  GROW(xomega, 1);
#undef GROW
  w->cap = c;
  return 0;
}

/* HOOMD's coordinate of haff's x in a periodic box of edge l: x wrapped into [0, l) minus l/2,
 * with the image count. */
static float wrap(double x, double l, int32_t *image) {
  double i = floor(x / l);
  *image = (int32_t)i;
  return (float)(x - i * l - 0.5 * l);
}

/* Whether species type t has bodies of more than one disk (a central particle + its disks). */
static int type_rigid(const hd_export_geom *g, int t) {
  if (g->rods) return 0;
  if (g->nsp > 0) return g->sp[t].n > 1;
  return t == 0 ? g->dimer.n > 1 : g->disk.n > 1;
}

/* The constituent type of species type t (its index among the types). */
static uint32_t disk_type(const hd_export_geom *g, int t) {
  uint32_t k = (uint32_t)g->ntypes;
  for (int s = 0; s < t; s++) k += (uint32_t)type_rigid(g, s);
  return k;
}

/* Fills particle p: a disk or a central particle. */
static void particle(gsd_out *w, const hd_export_geom *g, long p, uint32_t type, double m, double d,
                     int32_t body, double inertia, double x, double y, double vx, double vy,
                     double phi, double omega, double lz) {
  w->typeid[p] = type;
  w->mass[p] = (float)m;
  w->diam[p] = (float)d;
  w->body[p] = body;
  w->moi[3 * p] = w->moi[3 * p + 1] = 0;
  w->moi[3 * p + 2] = (float)inertia;
  w->pos3[3 * p] = wrap(x, g->lx, &w->image[3 * p]);
  if (g->rods) {
    w->pos3[3 * p + 1] = 0;
    w->image[3 * p + 1] = 0;
  } else {
    w->pos3[3 * p + 1] = wrap(y, g->ly, &w->image[3 * p + 1]);
  }
  w->pos3[3 * p + 2] = 0;
  w->image[3 * p + 2] = 0;
  double c = cos(0.5 * phi), s = sin(0.5 * phi);
  float q[4] = {(float)c, 0, 0, (float)s}, a[4] = {(float)(-2 * s * lz), 0, 0, (float)(2 * c * lz)};
  memcpy(w->orient + 4 * p, q, sizeof q);
  memcpy(w->angmom + 4 * p, a, sizeof a);
  w->vel[3 * p] = (float)vx;
  w->vel[3 * p + 1] = (float)vy;
  w->vel[3 * p + 2] = 0;
  w->xpos[3 * p] = x, w->xpos[3 * p + 1] = y, w->xpos[3 * p + 2] = 0;
  w->xvel[3 * p] = vx, w->xvel[3 * p + 1] = vy, w->xvel[3 * p + 2] = 0;
  w->xphi[p] = phi;
  w->xomega[p] = omega;
}

/* The label's code in log/haff/label. */
static uint8_t label_code(const char *label) {
  static const char *const names[] = {"initial", "frames", "velocities", "checkpoint", "final"};
  for (uint8_t k = 0; k < 5; k++)
    if (!strcmp(label, names[k])) return k;
  return 255;
}

/* hd_export_emit of the GSD writer: one frame. */
static int gsd_emit(void *ctx, const hd_export_geom *g, const hd_export_frame *f) {
  gsd_out *w = ctx;
  long n = f->n; /* particles: the bodies, then the disks of rigid ones */
  for (long i = 0; i < f->n; i++)
    if (f->kind[i] != HD_KIND_ROD && type_rigid(g, hd_export_body_type(g, f->body[i], f->kind[i])))
      n += hd_export_body_disks(g, f->body[i], f->kind[i]);
  if (n > INT32_MAX) {
    fprintf(stderr, "haff export: a frame of %ld particles is past GSD's int32 body ids\n", n);
    return 1;
  }
  if (room(w, n)) return 1;
  long c = f->n;
  for (long i = 0; i < f->n; i++) {
    const hd_kin *k = &f->kin[i];
    int kind = f->kind[i], t = hd_export_body_type(g, f->body[i], kind);
    if (kind == HD_KIND_ROD) {
      particle(w, g, i, (uint32_t)t, hd_export_rod_mass(g, f->body[i]), 1.0, -1, 0, k->x, 0, k->vx,
               0, 0, k->omega, 0);
      continue;
    }
    const hd_shape *sh = hd_export_body_shape(g, f->body[i], kind);
    if (!type_rigid(g, t)) { /* a single disk */
      double x, y, vx, vy;
      hd_kin_disk_pos(k, sh, 0, &x, &y);
      hd_kin_disk_vel(k, sh, 0, &vx, &vy);
      particle(w, g, i, (uint32_t)t, sh->mk[0], sh->dk[0], -1, 0, x, y, vx, vy, k->phi, k->omega,
               0);
      continue;
    }
    particle(w, g, i, (uint32_t)t, sh->mass, 0, (int32_t)i, sh->inertia, k->x, k->y, k->vx, k->vy,
             k->phi, k->omega, sh->inertia * k->omega);
    uint32_t dt = disk_type(g, t);
    for (int j = 0; j < sh->n; j++, c++) {
      double x, y, vx, vy;
      hd_kin_disk_pos(k, sh, j, &x, &y);
      hd_kin_disk_vel(k, sh, j, &vx, &vy);
      particle(w, g, c, dt, sh->mk[j], sh->dk[j], (int32_t)i, 0, x, y, vx, vy, k->phi, k->omega, 0);
    }
  }
  /* the types: the species, then the disks of the rigid ones, as NT x M bytes */
  char types[2 * HD_MAX_SPECIES][72];
  int nt = 0;
  size_t width = 1;
  for (int t = 0; t < g->ntypes; t++) snprintf(types[nt++], sizeof types[0], "%s", g->type_name[t]);
  for (int t = 0; t < g->ntypes; t++)
    if (type_rigid(g, t)) snprintf(types[nt++], sizeof types[0], "%s_disk", g->type_name[t]);
  for (int t = 0; t < nt; t++)
    if (strlen(types[t]) + 1 > width) width = strlen(types[t]) + 1;
  unsigned char tbuf[sizeof types];
  memset(tbuf, 0, sizeof tbuf);
  for (int t = 0; t < nt; t++) memcpy(tbuf + (size_t)t * width, types[t], strlen(types[t]));
  uint64_t step = w->frame;
  uint8_t dim = 2, label = label_code(f->label);
  float box[6] = {(float)g->lx, (float)g->ly, 0, 0, 0, 0};
  uint32_t np = (uint32_t)n;
  double t = f->t, cpd = f->has_cpd ? f->cpd : NAN;
  uint64_t un = (uint64_t)n;
  int rc =
      chunk(w, C_STEP, GSD_U64, 1, 1, &step) || chunk(w, C_DIM, GSD_U8, 1, 1, &dim) ||
      chunk(w, C_BOX, GSD_F32, 6, 1, box) || chunk(w, C_N, GSD_U32, 1, 1, &np) ||
      chunk(w, C_TYPES, GSD_I8, (uint64_t)nt, (uint32_t)width, tbuf) ||
      chunk(w, C_TYPEID, GSD_U32, un, 1, w->typeid) || chunk(w, C_MASS, GSD_F32, un, 1, w->mass) ||
      chunk(w, C_DIAM, GSD_F32, un, 1, w->diam) || chunk(w, C_BODY, GSD_I32, un, 1, w->body) ||
      chunk(w, C_MOI, GSD_F32, un, 3, w->moi) || chunk(w, C_POS, GSD_F32, un, 3, w->pos3) ||
      chunk(w, C_ORIENT, GSD_F32, un, 4, w->orient) || chunk(w, C_VEL, GSD_F32, un, 3, w->vel) ||
      chunk(w, C_ANGMOM, GSD_F32, un, 4, w->angmom) ||
      chunk(w, C_IMAGE, GSD_I32, un, 3, w->image) || chunk(w, C_TIME, GSD_F64, 1, 1, &t) ||
      chunk(w, C_CPD, GSD_F64, 1, 1, &cpd) || chunk(w, C_LABEL, GSD_U8, 1, 1, &label) ||
      chunk(w, C_XPOS, GSD_F64, un, 3, w->xpos) || chunk(w, C_XVEL, GSD_F64, un, 3, w->xvel) ||
      chunk(w, C_XPHI, GSD_F64, un, 1, w->xphi) || chunk(w, C_XOMEGA, GSD_F64, un, 1, w->xomega);
  w->frame++;
  return rc;
}

/* Writes the index, the namelist and the header; 0 or 1 (said). */
static int finish(gsd_out *w) {
  uint64_t index_at = w->pos, nalloc = w->nidx + 1;
  unsigned char e[32];
  for (size_t k = 0; k < w->nidx; k++) {
    const gsd_entry *x = &w->idx[k];
    put_u64(e, x->frame);
    put_u64(e + 8, x->n);
    put_u64(e + 16, x->location);
    put_u32(e + 24, x->m);
    put_u16(e + 28, x->id);
    e[30] = x->type;
    e[31] = 0;
    if (out_write(w, e, sizeof e)) return 1;
  }
  memset(e, 0, sizeof e); /* the end of the list */
  if (out_write(w, e, sizeof e)) return 1;
  uint64_t names_at = w->pos, bytes = 1; /* the empty name that ends the list */
  for (int k = 0; k < C_COUNT; k++) bytes += strlen(chunk_names[k]) + 1;
  uint64_t segments = (bytes + 63) / 64;
  for (int k = 0; k < C_COUNT; k++)
    if (out_write(w, chunk_names[k], strlen(chunk_names[k]) + 1)) return 1;
  static const unsigned char zeros[64];
  if (out_write(w, zeros, (size_t)(segments * 64 - (bytes - 1)))) return 1;
  unsigned char h[256];
  memset(h, 0, sizeof h);
  put_u64(h, 0x65DF65DF65DF65DFull);
  put_u64(h + 8, index_at);
  put_u64(h + 16, nalloc);
  put_u64(h + 24, names_at);
  put_u64(h + 32, segments);
  put_u32(h + 40, 1u << 16 | 4u); /* schema hoomd 1.4 */
  put_u32(h + 44, 2u << 16 | 0u); /* GSD file layer 2.0 */
  snprintf((char *)h + 48, 64, "%s", w->application);
  snprintf((char *)h + 112, 64, "hoomd");
  if (fseek(w->f, 0, SEEK_SET) != 0 || fwrite(h, 1, sizeof h, w->f) != sizeof h) {
    fprintf(stderr, "haff export: %s: write failed: %s\n", w->path, strerror(errno));
    return 1;
  }
  return 0;
}

int hd_gsd_export(hd_db *db, int64_t run, const char *label, const char *outpath,
                  const char *application) {
  int64_t r = run;
  hd_export_geom g;
  int code = hd_export_read_run(db, &r, &g);
  if (code) return code;
  size_t len = strlen(outpath) + 8;
  char *tmp = malloc(len);
  if (!tmp) return 1;
  snprintf(tmp, len, "%s.tmp", outpath);
  gsd_out w = {.path = tmp, .application = application};
  if (!(w.f = fopen(tmp, "wb"))) {
    fprintf(stderr, "haff export: %s: cannot write: %s\n", tmp, strerror(errno));
    free(tmp);
    return 1;
  }
  static const unsigned char header[256]; /* written at the end */
  code = out_write(&w, header, sizeof header);
  if (!code) code = hd_export_frames(db, r, label, &g, gsd_emit, &w);
  if (!code) code = finish(&w);
  if (fclose(w.f) != 0 && !code) {
    fprintf(stderr, "haff export: %s: write failed: %s\n", tmp, strerror(errno));
    code = 1;
  }
  if (!code && rename(tmp, outpath) != 0) {
    fprintf(stderr, "haff export: %s: cannot write: %s\n", outpath, strerror(errno));
    code = 1;
  }
  if (code) remove(tmp);
  free(tmp);
  free(w.idx);
  free(w.typeid), free(w.mass), free(w.diam), free(w.moi), free(w.pos3), free(w.orient);
  free(w.vel), free(w.angmom), free(w.body), free(w.image), free(w.xpos), free(w.xvel);
  free(w.xphi), free(w.xomega);
  return code;
}
