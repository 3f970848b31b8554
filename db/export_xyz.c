/* The extended XYZ writer of `haff export xyz` (cli/cmd_export.c): the states and frames
 * tables, as OVITO and ASE (ase.io.read(..., index=':')) read it.
 *
 * One frame per (label, t) of the run, in time order (at equal t: initial, frames, velocities,
 * checkpoint, final).  A frame is
 *   line 1: the number of particles, i.e. of disks (a dimer gives its 2 disks)
 *   line 2: Lattice="Lx 0 0 0 Ly 0 0 0 1" Properties=PROPS pbc="T T F" Time=t Label=label [Cpd=cpd]
 * with PROPS = species:S:1:pos:R:3:velo:R:3:masses:R:1:momenta:R:3:radius:R:1:body:I:1:phi:R:1:
 * omega:R:1:species_name:S:1, then one line per disk: species (an element per species of the
 * run, by species.idx: N for 0 [dimers], Ar for 1 [disks], O F Ne Na ... for 2, 3, ... the
 * [species NAME] sections; without a species table N for a disk of a dimer and Ar for a single
 * disk; C for a rod: chemical symbols, which ASE requires),
 * x y 0, its velocity vx vy 0 (rotation included), its mass, its momentum (what ASE reads as
 * velocities times masses), its radius, the body index, the body's orientation phi and angular
 * velocity omega (0 for a body of one disk and for a rod), and the species' name
 * (species.name; rod; dimer or disk for a file without the species table: issue 28).  A dimer's
 * disk k is at R -+ (a/2)(cos phi, sin phi) (disk 0 at -; hd_kin_disk_pos).  Numbers are written in
 * the shortest form that reads back as the same double (at most 17 digits).  Positions are not
 * wrapped into the box. pbc is F along an axis closed by [walls], and along z.
 *
 * Lx, Ly come from runs.box_x/box_y (hd_db_run_box), else from the scene's box (given, or
 * derived from area_fraction); the shapes and masses from [dimers] d, a, m and [disks] sigma,
 * mass, walls from [walls] sides: the run's stored scene read by the engine's loader
 * (hd_scene_read_stored), with its defaults; the named species' shapes from the species table.
 * Frames (table frames) take their body kinds from the run's 'initial' states.  The frames are
 * read by hd_export_frames, which the GSD writer (export_gsd.c) shares. */
#include <limits.h>
#include <stddef.h>
#include <math.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "export_xyz.h"
#include "hd_body.h"
#include "hd_db.h"
#include "hd_scene.h"

const hd_shape *hd_export_body_shape(const hd_export_geom *g, long long body, int kind) {
  for (int s = 0; s < g->nsp; s++)
    if (body >= g->first[s] && body < g->first[s + 1]) return &g->sp[s];
  return kind == HD_KIND_DIMER ? &g->dimer : &g->disk;
}

int hd_export_body_disks(const hd_export_geom *g, long long body, int kind) {
  return kind == HD_KIND_ROD ? 1 : hd_export_body_shape(g, body, kind)->n;
}

int hd_export_body_type(const hd_export_geom *g, long long body, int kind) {
  if (g->rods) return 0;
  for (int s = 0; s < g->nsp; s++)
    if (body >= g->first[s] && body < g->first[s + 1]) return s;
  return kind == HD_KIND_DIMER ? 0 : 1; /* a file without the species table: dimer, disk */
}

/* The body kind of a states.kind text. */
static int kind_of(const char *kind) {
  return !kind                    ? HD_KIND_DISK
         : !strcmp(kind, "dimer") ? HD_KIND_DIMER
         : !strcmp(kind, "rod")   ? HD_KIND_ROD
         : !strcmp(kind, "body")  ? HD_KIND_BODY
                                  : HD_KIND_DISK;
}

/* The geometry of a run's stored scene, read by the engine's own loader (hd_scene_read_stored:
 * the same keys and defaults as the run had).  HD_OK or its error. */
static int geom_of_scene(const char *text, hd_export_geom *g, hd_error *err) {
  hd_scene sc;
  int rc = hd_scene_read_stored(&sc, text, "runs.scene", err);
  if (rc) return rc;
  hd_scene_free(&sc);
  if (sc.box_x > 0 && sc.box_y > 0) g->lx = sc.box_x, g->ly = sc.box_y;
  hd_shape_dimer(&g->dimer, sc.dimer_d, sc.dimer_a, sc.dimer_m);
  hd_shape_disk(&g->disk, sc.disk_sigma, sc.disk_mass);
  g->wall_x = (sc.walls & (HD_WALL_LEFT | HD_WALL_RIGHT)) != 0;
  g->wall_y = (sc.walls & (HD_WALL_BOTTOM | HD_WALL_TOP)) != 0;
  g->rods = sc.n_rods > 0;
  g->rod_gamma = sc.rod_gamma;
  return HD_OK;
}

/* Writes x in the shortest %g form that reads back as x (15 to 17 digits). */
static void put_num(FILE *out, double x) {
  char b[40];
  for (int prec = 15; prec <= 17; prec++) {
    snprintf(b, sizeof b, "%.*g", prec, x);
    if (strtod(b, NULL) == x) break;
  }
  fputs(b, out);
}

/* Writes the lines of one body (its disks): species (the type's element), pos, velo, masses,
 * momenta, radius, body, phi, omega, species_name. */
static void put_body(FILE *out, const hd_export_geom *g, long long body, int kind,
                     const hd_kin *k) {
  const hd_shape *sh = hd_export_body_shape(g, body, kind);
  int type = hd_export_body_type(g, body, kind);
  const char *species = g->type_elem[type];
  int disks = hd_export_body_disks(g, body, kind), turns = kind != HD_KIND_ROD && sh->n > 1;
  for (int j = 0; j < disks; j++) {
    double x = k->x, y = k->y, vx = k->vx, vy = k->vy, m = 0, r = 0.5;
    if (kind == HD_KIND_ROD) {
      m = hd_export_rod_mass(g, body);
    } else { /* the engine's disk positions and velocities */
      m = sh->mk[j], r = 0.5 * sh->dk[j];
      hd_kin_disk_pos(k, sh, j, &x, &y);
      hd_kin_disk_vel(k, sh, j, &vx, &vy);
    }
    double v[] = {x, y, 0, vx, vy, 0, m, m * vx, m * vy, 0, r};
    fputs(species, out);
    for (size_t c = 0; c < sizeof v / sizeof v[0]; c++) {
      fputc(' ', out);
      put_num(out, v[c]);
    }
    fprintf(out, " %lld ", body);
    put_num(out, turns ? k->phi : 0);
    fputc(' ', out);
    put_num(out, turns ? k->omega : 0);
    fputc(' ', out);
    fputs(g->type_name[type], out);
    fputc('\n', out);
  }
}

double hd_export_rod_mass(const hd_export_geom *g, long long body) {
  return body % 2 ? 1 + 1 / g->rod_gamma : 1 + g->rod_gamma; /* engine/rods/rods.c */
}

/* The kinds of the run's bodies (from its 'initial' states) into *kinds (malloc'd), *n. */
static int read_kinds(hd_db *db, int64_t run, int **kinds, long *n) {
  sqlite3 *h = hd_db_handle(db);
  sqlite3_stmt *st = NULL;
  *kinds = NULL;
  *n = 0;
  if (sqlite3_prepare_v2(h,
                         "SELECT body, kind FROM states WHERE run = ?1 AND label = 'initial' "
                         "AND t = (SELECT min(t) FROM states WHERE run = ?1 AND label = 'initial') "
                         "ORDER BY body",
                         -1, &st, NULL) != SQLITE_OK) {
    fprintf(stderr, "haff export: %s: read states: %s\n", hd_db_path(db), sqlite3_errmsg(h));
    return 1;
  }
  sqlite3_bind_int64(st, 1, run);
  long cap = 0;
  int s;
  while ((s = sqlite3_step(st)) == SQLITE_ROW) {
    long long body = sqlite3_column_int64(st, 0);
    const char *kind = (const char *)sqlite3_column_text(st, 1);
    if (body != *n) break; /* bodies are 0 .. n-1 */
    if (*n == cap) {
      cap = 2 * cap + 64;
      int *k2 = realloc(*kinds, (size_t)cap * sizeof *k2);
      if (!k2) break;
      *kinds = k2;
    }
    (*kinds)[(*n)++] = kind_of(kind);
  }
  sqlite3_finalize(st);
  if (s != SQLITE_DONE) {
    fprintf(stderr, "haff export: %s: run %lld: its initial states are not bodies 0 .. n-1\n",
            hd_db_path(db), (long long)run);
    return 1;
  }
  return 0;
}

/* A frame's bodies, grown as needed. */
typedef struct frame_buf {
  long cap;
  long long *body;
  int *kind;
  hd_kin *kin;
} frame_buf;

/* Room for n bodies in fb; 0 or 1 (out of memory, said). */
static int frame_room(frame_buf *fb, long n) {
  if (n <= fb->cap) return 0;
  long cap = n + n / 2 + 64;
  long long *b = realloc(fb->body, (size_t)cap * sizeof *b);
  if (b) fb->body = b;
  int *k = b ? realloc(fb->kind, (size_t)cap * sizeof *k) : NULL;
  if (k) fb->kind = k;
  hd_kin *q = k ? realloc(fb->kin, (size_t)cap * sizeof *q) : NULL;
  if (!q) {
    fprintf(stderr, "haff export: out of memory for a frame of %ld bodies\n", n);
    return 1;
  }
  fb->kin = q;
  fb->cap = cap;
  return 0;
}

int hd_export_frames(hd_db *db, int64_t run, const char *label, const hd_export_geom *g,
                     hd_export_emit emit, void *ctx) {
  sqlite3 *h = hd_db_handle(db);
  sqlite3_stmt *frames = NULL, *bodies = NULL, *blob = NULL;
  int code = 0, *kinds = NULL;
  long nkinds = -1; /* not read yet */
  frame_buf fb = {0};
  /* states: one frame per (label, t); frames rows: one each (src 1), when the file has the
   * table (a database written before it has none, and is opened read-only: no schema added) */
#define STATES_FRAMES                                                                              \
  "SELECT label AS lab, t, max(cpd) AS cpd, count(*) AS n, "                                       \
  "0 AS src, 0 AS id FROM states WHERE run = ?1 AND (?2 = 'all' OR label = ?2) GROUP BY label, t"
#define ORDER_FRAMES                                                                               \
  " ORDER BY t, CASE lab WHEN 'initial' THEN 0 WHEN 'frames' THEN 1 WHEN 'velocities' THEN 2 "     \
  "WHEN 'checkpoint' THEN 3 WHEN 'final' THEN 4 ELSE 5 END, lab, id"
  static const char frames_sql[] = "SELECT lab, t, cpd, n, src, id FROM (" STATES_FRAMES
                                   " UNION ALL SELECT 'frames', t, cpd, n, 1, rowid FROM frames "
                                   "WHERE run = ?1 AND ?2 IN ('all', 'frames'))" ORDER_FRAMES;
  static const char states_sql[] =
      "SELECT lab, t, cpd, n, src, id FROM (" STATES_FRAMES ")" ORDER_FRAMES;
  static const char bodies_sql[] = "SELECT body, kind, x, y, phi, vx, vy, omega FROM states "
                                   "WHERE run = ?1 AND label = ?2 AND t = ?3 ORDER BY body";
  static const char blob_sql[] = "SELECT n, data FROM frames WHERE rowid = ?1";
  int has_frames = sqlite3_table_column_metadata(h, "main", "frames", "data", NULL, NULL, NULL,
                                                 NULL, NULL) == SQLITE_OK;
  if (sqlite3_prepare_v2(h, has_frames ? frames_sql : states_sql, -1, &frames, NULL) != SQLITE_OK ||
      sqlite3_prepare_v2(h, bodies_sql, -1, &bodies, NULL) != SQLITE_OK ||
      (has_frames && sqlite3_prepare_v2(h, blob_sql, -1, &blob, NULL) != SQLITE_OK)) {
    fprintf(stderr, "haff export: %s: read states: %s\n", hd_db_path(db), sqlite3_errmsg(h));
    sqlite3_finalize(frames);
    sqlite3_finalize(bodies);
    return 1;
  }
  sqlite3_bind_int64(frames, 1, run);
  sqlite3_bind_text(frames, 2, label, -1, SQLITE_STATIC);
  long n_frames = 0;
  int s, b = SQLITE_DONE;
  while ((s = sqlite3_step(frames)) == SQLITE_ROW) {
    hd_export_frame f = {(const char *)sqlite3_column_text(frames, 0),
                         sqlite3_column_double(frames, 1),
                         sqlite3_column_double(frames, 2),
                         sqlite3_column_type(frames, 2) != SQLITE_NULL,
                         0,
                         NULL,
                         NULL,
                         NULL};
    int from_frames = sqlite3_column_int(frames, 4);
    long long nb = sqlite3_column_int64(frames, 3);
    if (from_frames) { /* the bodies of a frame: their kinds from the initial states */
      if (nkinds < 0 && (code = read_kinds(db, run, &kinds, &nkinds))) break;
      sqlite3_reset(blob);
      sqlite3_bind_int64(blob, 1, sqlite3_column_int64(frames, 5));
      if (sqlite3_step(blob) != SQLITE_ROW || nb != nkinds ||
          sqlite3_column_bytes(blob, 1) != nb * HD_FRAME_BODY_BYTES) {
        fprintf(stderr,
                "haff export: %s: run %lld: the frame at t = %.17g holds %lld bodies, the run's "
                "initial states %ld\n",
                hd_db_path(db), (long long)run, f.t, nb, nkinds);
        code = 1;
        break;
      }
      const unsigned char *data = sqlite3_column_blob(blob, 1);
      if ((code = frame_room(&fb, nkinds))) break;
      for (long i = 0; i < nkinds; i++) {
        double d[3];
        float v[3];
        memcpy(d, data + (size_t)i * HD_FRAME_BODY_BYTES, sizeof d);
        memcpy(v, data + (size_t)i * HD_FRAME_BODY_BYTES + sizeof d, sizeof v);
        fb.body[i] = i;
        fb.kind[i] = kinds[i];
        fb.kin[i] = (hd_kin){d[0], d[1], v[0], v[1], d[2], v[2]};
      }
      f.n = nkinds;
    } else { /* the bodies of the states at (lab, t) */
      sqlite3_reset(bodies);
      sqlite3_bind_int64(bodies, 1, run);
      sqlite3_bind_text(bodies, 2, f.label, -1, SQLITE_TRANSIENT);
      sqlite3_bind_double(bodies, 3, f.t);
      if ((code = frame_room(&fb, (long)nb))) break;
      while ((b = sqlite3_step(bodies)) == SQLITE_ROW && f.n < nb) {
        fb.body[f.n] = sqlite3_column_int64(bodies, 0);
        fb.kind[f.n] = kind_of((const char *)sqlite3_column_text(bodies, 1));
        fb.kin[f.n] = (hd_kin){sqlite3_column_double(bodies, 2), sqlite3_column_double(bodies, 3),
                               sqlite3_column_double(bodies, 5), sqlite3_column_double(bodies, 6),
                               sqlite3_column_double(bodies, 4), sqlite3_column_double(bodies, 7)};
        f.n++;
      }
      if (b != SQLITE_DONE) break;
    }
    f.body = fb.body;
    f.kind = fb.kind;
    f.kin = fb.kin;
    if ((code = emit(ctx, g, &f))) break;
    n_frames++;
  }
  if (code) {
    /* said */
  } else if (s != SQLITE_DONE && s != SQLITE_ROW) {
    fprintf(stderr, "haff export: %s: read states: %s\n", hd_db_path(db), sqlite3_errmsg(h));
    code = 1;
  } else if (b != SQLITE_DONE) {
    fprintf(stderr, "haff export: %s: read states: %s\n", hd_db_path(db), sqlite3_errmsg(h));
    code = hd_exit_code(hd_db_status_of(sqlite3_errcode(h))); /* malformed: 2 */
  } else if (n_frames == 0) {
    if (!strcmp(label, "frames"))
      fprintf(stderr,
              "haff export: %s: run %lld has no frames (run it with [log] frames_every or "
              "frames_every_time)\n",
              hd_db_path(db), (long long)run);
    else
      fprintf(stderr, "haff export: %s: run %lld has no states with label %s\n", hd_db_path(db),
              (long long)run, label);
    code = 2;
  }
  free(kinds);
  free(fb.body);
  free(fb.kind);
  free(fb.kin);
  sqlite3_finalize(frames);
  sqlite3_finalize(bodies);
  sqlite3_finalize(blob);
  return code;
}

/* hd_export_emit of the XYZ writer: ctx is the FILE. */
static int xyz_emit(void *ctx, const hd_export_geom *g, const hd_export_frame *f) {
  FILE *out = ctx;
  long long disks = 0;
  for (long i = 0; i < f->n; i++) disks += hd_export_body_disks(g, f->body[i], f->kind[i]);
  fprintf(out, "%lld\n", disks);
  fprintf(out,
          "Lattice=\"%.17g 0 0 0 %.17g 0 0 0 1\" Properties=species:S:1:pos:R:3:velo:R:3:"
          "masses:R:1:momenta:R:3:radius:R:1:body:I:1:phi:R:1:omega:R:1:species_name:S:1 "
          "pbc=\"%c %c F\" Time=",
          g->lx, g->ly, g->wall_x ? 'F' : 'T', g->rods || g->wall_y ? 'F' : 'T');
  put_num(out, f->t);
  fprintf(out, " Label=%s", f->label);
  if (f->has_cpd) {
    fputs(" Cpd=", out);
    put_num(out, f->cpd);
  }
  fputc('\n', out);
  for (long i = 0; i < f->n; i++) put_body(out, g, f->body[i], f->kind[i], &f->kin[i]);
  return 0;
}

/* The element symbol of species idx (species.idx): chemical symbols, since ASE looks every
 * name up in the periodic table; OVITO takes them as type names. */
static const char *species_element(int idx) {
  static const char *const named[] = {"O", "F", "Ne", "Na", "Mg", "Al", "Si", "P", "S", "Cl"};
  return idx == 0 ? "N" : idx == 1 ? "Ar" : named[(idx - 2) % (int)(sizeof named / sizeof *named)];
}

/* The types of g (names and elements): the run's species table in idx order, else ("rod") for
 * rods, else ("dimer", "disk").  0 or an exit code (said). */
static int read_types(hd_db *db, int64_t run, hd_export_geom *g) {
  static const char *const dflt[] = {"dimer", "disk"};
  if (g->rods || g->nsp == 0) {
    g->ntypes = g->rods ? 1 : 2;
    for (int k = 0; k < g->ntypes; k++) {
      snprintf(g->type_name[k], sizeof g->type_name[k], "%s", g->rods ? "rod" : dflt[k]);
      snprintf(g->type_elem[k], sizeof g->type_elem[k], "%s", g->rods ? "C" : species_element(k));
    }
    return 0;
  }
  sqlite3 *h = hd_db_handle(db);
  sqlite3_stmt *st = NULL;
  if (sqlite3_prepare_v2(h, "SELECT idx, name FROM species WHERE run = ?1 ORDER BY idx", -1, &st,
                         NULL) != SQLITE_OK) {
    fprintf(stderr, "haff export: %s: read species: %s\n", hd_db_path(db), sqlite3_errmsg(h));
    return 1;
  }
  sqlite3_bind_int64(st, 1, run);
  int s;
  g->ntypes = 0;
  while ((s = sqlite3_step(st)) == SQLITE_ROW && g->ntypes < g->nsp) {
    const char *name = (const char *)sqlite3_column_text(st, 1);
    int k = g->ntypes++;
    snprintf(g->type_name[k], sizeof g->type_name[k], "%s", name ? name : "?");
    for (char *c = g->type_name[k]; *c; c++) /* one word in an XYZ column */
      if (*c == ' ' || *c == '\t' || *c == '"') *c = '_';
    snprintf(g->type_elem[k], sizeof g->type_elem[k], "%s",
             species_element(sqlite3_column_int(st, 0)));
  }
  sqlite3_finalize(st);
  if (g->ntypes != g->nsp) {
    fprintf(stderr, "haff export: %s: run %lld: read species: %s\n", hd_db_path(db), (long long)run,
            sqlite3_errmsg(h));
    return 1;
  }
  return 0;
}

int hd_export_read_run(hd_db *db, int64_t *run, hd_export_geom *g) {
  sqlite3 *h = hd_db_handle(db);
  sqlite3_stmt *st = NULL;
  const char *sql = *run > 0 ? "SELECT id, scene, box_x, box_y FROM runs WHERE id = ?1"
                             : "SELECT id, scene, box_x, box_y FROM runs ORDER BY id DESC LIMIT 1";
  if (sqlite3_prepare_v2(h, sql, -1, &st, NULL) != SQLITE_OK) {
    fprintf(stderr, "haff export: %s: read runs: %s\n", hd_db_path(db), sqlite3_errmsg(h));
    return 1;
  }
  if (*run > 0) sqlite3_bind_int64(st, 1, *run);
  int s = sqlite3_step(st), code = 0;
  if (s == SQLITE_ROW) {
    *run = sqlite3_column_int64(st, 0);
    memset(g, 0, sizeof *g);
    g->lx = g->ly = NAN;
    g->rod_gamma = 0.8;
    hd_shape_dimer(&g->dimer, 1.0, 1.0, 1.0);
    hd_shape_disk(&g->disk, 1.0, 1.0);
    const char *scene = (const char *)sqlite3_column_text(st, 1);
    hd_error err;
    hd_error_clear(&err);
    if (scene && geom_of_scene(scene, g, &err)) {
      fprintf(stderr, "haff export: %s: run %lld: %s\n", hd_db_path(db), (long long)*run, err.msg);
      code = 1;
    }
    hd_shape_dimer(&g->dimer, g->dimer.d, g->dimer.a, g->dimer.m); /* the engine's shapes */
    hd_shape_disk(&g->disk, g->disk.d, g->disk.m);
    int64_t count[HD_MAX_SPECIES];
    hd_error e;
    if (!code && hd_db_read_species(h, *run, g->sp, count, HD_MAX_SPECIES, &g->nsp, &e)) {
      fprintf(stderr, "haff export: %s: %s\n", hd_db_path(db), e.msg);
      code = 1;
    }
    g->first[0] = 0;
    for (int k = 0; k < g->nsp; k++) g->first[k + 1] = g->first[k] + count[k];
    if (!code) code = read_types(db, *run, g);
    if (sqlite3_column_type(st, 2) != SQLITE_NULL && sqlite3_column_type(st, 3) != SQLITE_NULL) {
      g->lx = sqlite3_column_double(st, 2);
      g->ly = sqlite3_column_double(st, 3);
      if (g->lx > 0 && g->ly == 0) g->ly = 1; /* a ring of rods (1D): a strip one unit wide */
    }
    if (!code && !(g->lx > 0 && g->ly > 0)) {
      fprintf(stderr,
              "haff export: %s: run %lld: box unknown (no runs.box_x/box_y and no "
              "[system] box in its scene)\n",
              hd_db_path(db), (long long)*run);
      code = 1;
    }
  } else if (s == SQLITE_DONE) {
    if (*run > 0)
      fprintf(stderr, "haff export: %s: there is no run %lld\n", hd_db_path(db), (long long)*run);
    else
      fprintf(stderr, "haff export: %s: the database holds no run\n", hd_db_path(db));
    code = 2;
  } else {
    fprintf(stderr, "haff export: %s: read runs: %s\n", hd_db_path(db), sqlite3_errmsg(h));
    code = hd_exit_code(hd_db_status_of(sqlite3_errcode(h)));
  }
  sqlite3_finalize(st);
  return code;
}

int hd_xyz_export(hd_db *db, int64_t run, const char *label, const char *outpath) {
  int64_t r = run;
  hd_export_geom g;
  int code = hd_export_read_run(db, &r, &g);
  FILE *out = stdout;
  if (outpath && !strcmp(outpath, "-")) outpath = NULL; /* -o -: stdout */
  /* a file is written as FILE.tmp and renamed on success (a failure leaves no FILE, as in
   * export gsd); what is not a regular file (a FIFO, /dev/stdout) is written directly */
  char *tmp = NULL;
  struct stat sb;
  if (!code && outpath && !(stat(outpath, &sb) == 0 && !S_ISREG(sb.st_mode))) {
    size_t len = strlen(outpath) + 8;
    if (!(tmp = malloc(len))) return 1;
    snprintf(tmp, len, "%s.tmp", outpath);
  }
  const char *wpath = tmp ? tmp : outpath;
  if (!code && outpath && !(out = fopen(wpath, "w"))) {
    fprintf(stderr, "haff export: %s: cannot write: %m\n", wpath);
    code = 1;
  }
  if (!code) code = hd_export_frames(db, r, label, &g, xyz_emit, out);
  if (out && out != stdout && fclose(out) != 0 && !code) {
    fprintf(stderr, "haff export: %s: write failed: %m\n", wpath);
    code = 1;
  }
  if (out == stdout && (fflush(stdout) != 0 || ferror(stdout)) && !code) {
    fprintf(stderr, "haff export: stdout: write error: %m\n");
    code = 1;
  }
  if (tmp && !code && rename(tmp, outpath) != 0) {
    fprintf(stderr, "haff export: %s: cannot write: %m\n", outpath);
    code = 1;
  }
  if (tmp && code) remove(tmp);
  free(tmp);
  return code;
}
