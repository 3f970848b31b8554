/* `haff export xyz DB [--run ID] [--label L] [-o FILE]`: extended XYZ snapshots of the states
 * table, which OVITO and VMD open.
 *
 * One frame per (label, t) of the run, in time order (at equal t: initial, velocities,
 * checkpoint, final).  A frame is
 *   line 1: the number of particles, i.e. of disks (a dimer gives its 2 disks)
 *   line 2: Lattice="Lx 0 0 0 Ly 0 0 0 1"
 * Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1:body:I:1 Time=t Label=label [Cpd=cpd] then one
 * line per disk: species (D: disk of a dimer, S: single disk, R: rod), x y 0, vx vy 0 (the velocity
 * of that disk, rotation included), radius, body index. A dimer's disk k is at R -+ (a/2)(cos phi,
 * sin phi) (disk 0 at -), with velocity V -+ (a/2) omega (-sin phi, cos phi).  Positions are not
 * wrapped into the box.
 *
 * Lx, Ly come from runs.box_x/box_y (hd_db_run_box), else from the scene's [system] box; the
 * dimer d and a from [dimers] d, a and the disk diameter from [disks] sigma (all default 1). */
#include <getopt.h>
#include <ini.h>
#include <math.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hd_db.h"

int haff_export_main(int argc, char **argv);

/* The geometry export needs, read from the run's scene text. */
typedef struct xyz_geom {
  double lx, ly;  /* box edges, NAN until known */
  double dimer_d; /* [dimers] d */
  double dimer_a; /* [dimers] a */
  double sigma;   /* [disks] sigma */
} xyz_geom;

static int geom_handler(void *user, const char *section, const char *name, const char *value) {
  xyz_geom *g = user;
  if (!strcmp(section, "system") && !strcmp(name, "box")) {
    if (sscanf(value, "%lf %lf", &g->lx, &g->ly) != 2) g->lx = g->ly = NAN;
  } else if (!strcmp(section, "dimers") && !strcmp(name, "d")) {
    g->dimer_d = strtod(value, NULL);
  } else if (!strcmp(section, "dimers") && !strcmp(name, "a")) {
    g->dimer_a = strtod(value, NULL);
  } else if (!strcmp(section, "disks") && !strcmp(name, "sigma")) {
    g->sigma = strtod(value, NULL);
  }
  return 1; /* other keys are not ours to judge */
}

static void usage(FILE *out) {
  fprintf(out,
          "usage: haff export xyz DB [--run ID] [--label initial|final|checkpoint|velocities|all]"
          " [-o FILE]\n"
          "Writes the stored states of a run as extended XYZ (OVITO, VMD): one frame per\n"
          "(label, time), one line per disk (a dimer gives two, species D; single disks S).\n"
          "  --run ID     the run [the newest run in DB]\n"
          "  --label L    which states [all]\n"
          "  -o FILE      output file [stdout]\n");
}

/* Writes the frames of run/label to out.  Returns 0 or an exit code with one line on stderr. */
static int write_frames(hd_db *db, int64_t run, const char *label, const xyz_geom *g, FILE *out) {
  sqlite3 *h = hd_db_handle(db);
  sqlite3_stmt *frames = NULL, *bodies = NULL;
  int code = 0;
  static const char frames_sql[] =
      "SELECT label, t, max(cpd), sum(CASE kind WHEN 'dimer' THEN 2 ELSE 1 END) FROM states "
      "WHERE run = ?1 AND (?2 = 'all' OR label = ?2) GROUP BY label, t "
      "ORDER BY t, CASE label WHEN 'initial' THEN 0 WHEN 'velocities' THEN 1 "
      "WHEN 'checkpoint' THEN 2 WHEN 'final' THEN 3 ELSE 4 END, label";
  static const char bodies_sql[] = "SELECT body, kind, x, y, phi, vx, vy, omega FROM states "
                                   "WHERE run = ?1 AND label = ?2 AND t = ?3 ORDER BY body";
  if (sqlite3_prepare_v2(h, frames_sql, -1, &frames, NULL) != SQLITE_OK ||
      sqlite3_prepare_v2(h, bodies_sql, -1, &bodies, NULL) != SQLITE_OK) {
    fprintf(stderr, "haff export: %s: read states: %s\n", hd_db_path(db), sqlite3_errmsg(h));
    sqlite3_finalize(frames);
    return 1;
  }
  sqlite3_bind_int64(frames, 1, run);
  sqlite3_bind_text(frames, 2, label, -1, SQLITE_STATIC);
  long n_frames = 0;
  int s;
  while ((s = sqlite3_step(frames)) == SQLITE_ROW) {
    const char *lab = (const char *)sqlite3_column_text(frames, 0);
    double t = sqlite3_column_double(frames, 1);
    fprintf(out, "%lld\n", (long long)sqlite3_column_int64(frames, 3));
    fprintf(out,
            "Lattice=\"%.10g 0 0 0 %.10g 0 0 0 1\" "
            "Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1:body:I:1 Time=%.10g Label=%s",
            g->lx, g->ly, t, lab);
    if (sqlite3_column_type(frames, 2) != SQLITE_NULL)
      fprintf(out, " Cpd=%.10g", sqlite3_column_double(frames, 2));
    fputc('\n', out);
    sqlite3_reset(bodies);
    sqlite3_bind_int64(bodies, 1, run);
    sqlite3_bind_text(bodies, 2, lab, -1, SQLITE_TRANSIENT);
    sqlite3_bind_double(bodies, 3, t);
    int b;
    while ((b = sqlite3_step(bodies)) == SQLITE_ROW) {
      long long body = sqlite3_column_int64(bodies, 0);
      const char *kind = (const char *)sqlite3_column_text(bodies, 1);
      double x = sqlite3_column_double(bodies, 2), y = sqlite3_column_double(bodies, 3);
      double phi = sqlite3_column_double(bodies, 4);
      double vx = sqlite3_column_double(bodies, 5), vy = sqlite3_column_double(bodies, 6);
      double om = sqlite3_column_double(bodies, 7);
      if (kind && !strcmp(kind, "dimer")) {
        double h2 = 0.5 * g->dimer_a, c = cos(phi), sn = sin(phi);
        for (int k = 0; k < 2; k++) {
          double sg = k ? 1.0 : -1.0;
          fprintf(out, "D %.10g %.10g 0 %.10g %.10g 0 %.10g %lld\n", x + sg * h2 * c,
                  y + sg * h2 * sn, vx - sg * h2 * om * sn, vy + sg * h2 * om * c, 0.5 * g->dimer_d,
                  body);
        }
      } else {
        int rod = kind && !strcmp(kind, "rod");
        fprintf(out, "%s %.10g %.10g 0 %.10g %.10g 0 %.10g %lld\n", rod ? "R" : "S", x, y, vx, vy,
                0.5 * g->sigma, body);
      }
    }
    if (b != SQLITE_DONE) break;
    n_frames++;
  }
  if (s != SQLITE_DONE) {
    fprintf(stderr, "haff export: %s: read states: %s\n", hd_db_path(db), sqlite3_errmsg(h));
    code = hd_exit_code(hd_db_status_of(sqlite3_errcode(h))); /* malformed: 2 */
  } else if (n_frames == 0) {
    fprintf(stderr, "haff export: %s: run %lld has no states with label %s\n", hd_db_path(db),
            (long long)run, label);
    code = 2;
  }
  sqlite3_finalize(frames);
  sqlite3_finalize(bodies);
  return code;
}

/* Finds the run (newest if run <= 0) and its geometry.  Returns 0 or an exit code. */
static int read_run(hd_db *db, int64_t *run, xyz_geom *g) {
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
    *g = (xyz_geom){NAN, NAN, 1.0, 1.0, 1.0};
    const char *scene = (const char *)sqlite3_column_text(st, 1);
    if (scene && ini_parse_string(scene, geom_handler, g) < 0) {
      fprintf(stderr, "haff export: %s: run %lld: cannot parse its scene\n", hd_db_path(db),
              (long long)*run);
      code = 1;
    }
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

int haff_export_main(int argc, char **argv) {
  if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    int help = argc >= 2;
    usage(help ? stdout : stderr);
    return help ? 0 : 2;
  }
  if (strcmp(argv[1], "xyz")) {
    fprintf(stderr, "haff export: unknown format '%s' (only xyz)\n", argv[1]);
    return 2;
  }
  static const struct option opts[] = {{"run", required_argument, NULL, 'r'},
                                       {"label", required_argument, NULL, 'l'},
                                       {"output", required_argument, NULL, 'o'},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  long long run = 0;
  const char *label = "all", *outpath = NULL;
  int c;
  optind = 0; /* GNU: full re-initialisation, so the function may be called more than once;
                 parsing argv + 1 ("xyz" as the program name) */
  opterr = 0;
  while ((c = getopt_long(argc - 1, argv + 1, "o:h", opts, NULL)) != -1) {
    switch (c) {
    case 'r': {
      char *end;
      run = strtoll(optarg, &end, 10);
      if (*end || run <= 0) {
        fprintf(stderr, "haff export: --run %s: must be a positive run id\n", optarg);
        return 2;
      }
      break;
    }
    case 'l':
      label = optarg;
      if (strcmp(label, "initial") && strcmp(label, "final") && strcmp(label, "checkpoint") &&
          strcmp(label, "velocities") && strcmp(label, "all")) {
        fprintf(stderr,
                "haff export: --label %s: must be initial, final, checkpoint, "
                "velocities or all\n",
                label);
        return 2;
      }
      break;
    case 'o':
      outpath = optarg;
      break;
    case 'h':
      usage(stdout);
      return 0;
    default: {
      char buf[8];
      fprintf(stderr, "haff export: bad option '%s' (haff export --help)\n",
              hd_opt_culprit(argv + 1, opts, buf, sizeof buf));
    }
      return 2;
    }
  }
  if (optind + 1 != argc - 1) {
    fprintf(stderr, "haff export xyz: give exactly one DB (haff export --help)\n");
    return 2;
  }
  const char *path = argv[optind + 1];
  if (access(path, F_OK) != 0) {
    fprintf(stderr, "haff export: %s: no such database file\n", path);
    return 2;
  }
  hd_db *db = NULL;
  hd_error err;
  hd_error_clear(&err);
  int orc = hd_db_open_readonly(&db, path, &err);
  if (orc) {
    fprintf(stderr, "haff export: %s\n", err.msg);
    return orc == HD_EINPUT ? 2 : 1; /* not an SQLite file is bad input */
  }
  int64_t r = (int64_t)run;
  xyz_geom g;
  int code = read_run(db, &r, &g);
  FILE *out = stdout;
  if (!code && outpath && !(out = fopen(outpath, "w"))) {
    fprintf(stderr, "haff export: %s: cannot write: %m\n", outpath);
    code = 1;
  }
  if (!code) code = write_frames(db, r, label, &g, out);
  if (out && out != stdout && fclose(out) != 0 && !code) {
    fprintf(stderr, "haff export: %s: write failed: %m\n", outpath);
    code = 1;
  }
  if (out == stdout && (fflush(stdout) != 0 || ferror(stdout)) && !code) {
    fprintf(stderr, "haff export: stdout: write error: %m\n");
    code = 1;
  }
  hd_db_close(db, NULL);
  return code;
}
