/* `haff export xyz DB [--run ID] [--label L] [-o FILE]`: the options, the
 * database opened read-only, and the writer (db/export_xyz.c, hd_xyz_export). */
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "export_xyz.h"
#include "haff.h"
#include "hd_db.h"
#include "hd_opt.h"

/* The options of haff export xyz. */
typedef struct export_args {
  long long run;       /* --run ID, 0: the newest run */
  int label;           /* --label: an index of labels[] */
  const char *outpath; /* -o FILE, NULL: stdout */
} export_args;

static const char *const labels[] = {"initial",    "final",  "checkpoint",
                                     "velocities", "frames", "all"};

static const hd_optdef export_opts[] = {
    HD_OPT_INT("run", 0, export_args, run, 1, LLONG_MAX, 0, "ID", "the run [the newest run in DB]"),
    HD_OPT_ENUM("label", 0, export_args, label, "initial|final|checkpoint|velocities|frames|all",
                "L", "which states; frames: the [log] frames_every* frames [all]"),
    HD_OPT_STR("output", 'o', export_args, outpath, "FILE", "output file [stdout; - is stdout]",
               .flags = HD_OPTF_OUTPUT),
    {0}};

const hd_optspec haff_export_spec = {
    HD_OPT_SPEC("export", export_opts, 0, 1, 1, "one DB"),
    .head = "usage: haff export xyz DB [--run ID]\n"
            "       [--label initial|final|checkpoint|velocities|frames|all] [-o FILE]\n"
            "Writes the stored states and frames of a run as extended XYZ (OVITO, ASE): one frame\n"
            "per (label, time), one line per disk (a dimer gives two, species N; single disks Ar;\n"
            "rods C) with position, velocity, mass, momentum, radius, body, phi and omega.\n"
            "\n"
            "formats:\n"
            "  xyz      extended XYZ, for OVITO, ASE and VMD\n"
            "\n"};

int haff_export_main(int argc, char **argv) {
  if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    int help = argc >= 2;
    hd_opt_help(&haff_export_spec, help ? stdout : stderr);
    return help ? 0 : 2;
  }
  if (strcmp(argv[1], "xyz")) {
    fprintf(stderr, "haff export: unknown format '%s' (only xyz)\n", argv[1]);
    return 2;
  }
  export_args a = {.label = 5};
  hd_optres res; /* argv + 1: "xyz" as the program's name */
  int prc = hd_opt_parse(&haff_export_spec, argc - 1, argv + 1, &a, &res);
  if (prc) return prc < 0 ? 0 : prc;
  long long run = a.run;
  const char *label = labels[a.label], *outpath = a.outpath;
  const char *path = res.pos[0];
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
  int code = hd_xyz_export(db, (int64_t)run, label, outpath);
  hd_db_close(db, NULL);
  return code;
}
