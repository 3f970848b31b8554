/* `haff export xyz|gsd DB [--run ID] [--label L] [-o FILE]`: the options, the database opened
 * read-only, and the writers (db/export_xyz.c, hd_xyz_export; db/export_gsd.c, hd_gsd_export). */
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "export_gsd.h"
#include "export_xyz.h"
#include "haff.h"
#include "hd_db.h"
#include "hd_opt.h"
#include "hd_path.h"

/* The options of haff export xyz. */
typedef struct export_args {
  long long run;       /* --run ID, 0: the newest run */
  int label;           /* --label: an index of labels[] */
  const char *outpath; /* -o FILE, NULL: stdout */
} export_args;

static const char *const labels[] = {"initial",    "final",  "checkpoint",
                                     "velocities", "frames", "all"};

static const hd_optdef export_opts[] = {
    HD_OPT_INT("run", 0, export_args, run, 1, LLONG_MAX, HD_OPTF_ONCE, "ID",
               "the run [the newest run in DB]"),
    HD_OPT_ENUM("label", 0, export_args, label, "initial|final|checkpoint|velocities|frames|all",
                "L", "which states; frames: the [log] frames_every* frames [all]"),
    HD_OPT_STR("output", 'o', export_args, outpath, "FILE",
               "output file [xyz: stdout, - is stdout; gsd: DB's name with .gsd]",
               .flags = HD_OPTF_OUTPUT),
    {0}};

const hd_optspec hd_cmd_export_spec = {
    HD_OPT_SPEC("export", export_opts, 0, 1, 1, "one DB"),
    .head = "usage: haff export xyz|gsd DB [--run ID]\n"
            "       [--label initial|final|checkpoint|velocities|frames|all] [-o FILE]\n"
            "Writes the stored states and frames of a run, one frame per (label, time).\n"
            "xyz: extended XYZ (OVITO, ASE), one line per disk (a dimer gives two, element N;\n"
            "single disks Ar; rods C; named species O, F, Ne, ...) with position, velocity, mass,\n"
            "momentum, radius, body, phi, omega and species_name.\n"
            "gsd: HOOMD-blue's GSD (hoomd schema; HOOMD, OVITO, freud): 2D box, a type per\n"
            "species, a rigid body as its centre plus its disks (body ids), quaternions,\n"
            "velocities, angular momenta, and haff's exact values under log/haff/.\n"
            "\n"
            "formats:\n"
            "  xyz      extended XYZ, for OVITO, ASE and VMD\n"
            "  gsd      HOOMD-blue's GSD, for HOOMD, OVITO and freud\n"
            "\n"};

int hd_cmd_export(int argc, char **argv) {
  if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    int help = argc >= 2;
    hd_opt_help(&hd_cmd_export_spec, help ? stdout : stderr);
    return help ? 0 : 2;
  }
  int gsd = !strcmp(argv[1], "gsd");
  if (strcmp(argv[1], "xyz") && !gsd) {
    fprintf(stderr, "haff export: unknown format '%s' (xyz or gsd)\n", argv[1]);
    return 2;
  }
  export_args a = {.label = 5};
  hd_optres res; /* argv + 1: the format as the program's name */
  int prc = hd_opt_parse(&hd_cmd_export_spec, argc - 1, argv + 1, &a, &res);
  if (prc) return prc < 0 ? 0 : prc;
  long long run = a.run;
  const char *label = labels[a.label], *outpath = a.outpath;
  const char *path = res.pos[0];
  if (access(path, F_OK) != 0) {
    fprintf(stderr, "haff export: %s: no such database file\n", path);
    return 2;
  }
  char gsdpath[4096];
  if (gsd && (!outpath || !strcmp(outpath, "-"))) {
    if (outpath) {
      fprintf(stderr, "haff export: gsd cannot go to stdout (the writer seeks back to the file's "
                      "header): give -o FILE\n");
      return 2;
    }
    size_t n = strlen(path);
    if (n >= 3 && !strcmp(path + n - 3, ".db")) n -= 3;
    if (snprintf(gsdpath, sizeof gsdpath, "%.*s.gsd", (int)n, path) >= (int)sizeof gsdpath) {
      fprintf(stderr, "haff export: %s: name too long\n", path);
      return 2;
    }
    outpath = gsdpath;
    /* the derived name escapes hd_opt_parse's check of -o: the same rule here (a DB.gsd that
     * links to DB) */
    if (hd_path_overwrites(outpath, path)) {
      fprintf(stderr,
              "haff export: %s would overwrite the input %s: refused, nothing written "
              "(give -o FILE)\n",
              outpath, path);
      return 2;
    }
    if (hd_path_is_sqlite(outpath)) {
      fprintf(stderr,
              "haff export: %s is an SQLite database, which the gsd file would replace: refused, "
              "nothing written (give -o FILE)\n",
              outpath);
      return 2;
    }
  }
  hd_db *db = NULL;
  hd_error err;
  hd_error_clear(&err);
  int orc = hd_db_open_readonly(&db, path, &err);
  if (orc) {
    fprintf(stderr, "haff export: %s\n", err.msg);
    return orc == HD_EINPUT ? 2 : 1; /* not an SQLite file is bad input */
  }
  int code = gsd ? hd_gsd_export(db, (int64_t)run, label, outpath, "haff " HAFF_VERSION)
                 : hd_xyz_export(db, (int64_t)run, label, outpath);
  hd_db_close(db, NULL);
  return code;
}
