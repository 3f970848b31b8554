/* `haff merge OUT.db IN.db...`: db/hd_merge.h does the work. */
#include <getopt.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "haff.h"
#include "hd_merge.h"

int haff_merge_main(int argc, char **argv);

static const char merge_usage[] =
    "usage: haff merge OUT.db IN.db... [--quiet]\n"
    "  Appends every run of the IN databases to OUT (created if missing), with new run ids;\n"
    "  their collisions, samples, states, checkpoints and provenance follow them, and the\n"
    "  provenance table records each run's source file and id, host and Slurm job and task.\n"
    "  Refused (exit 2, OUT untouched): a file given twice, a file that is not a haff database\n"
    "  or fails PRAGMA integrity_check, OUT being written by a run, a run (same scene, seed and\n"
    "  version) already in OUT.  Atomic: OUT is replaced only once the merge is whole.\n";

int haff_merge_main(int argc, char **argv) {
  static const struct option opts[] = {
      {"quiet", no_argument, 0, 'q'}, {"help", no_argument, 0, 'h'}, {0, 0, 0, 0}};
  int quiet = 0, c;
  optind = 1;
  opterr = 0;
  while ((c = getopt_long(argc, argv, "qh", opts, NULL)) != -1) {
    switch (c) {
    case 'q':
      quiet = 1;
      break;
    case 'h':
      fputs(merge_usage, stdout);
      return 0;
    default:
      fprintf(stderr, "haff merge: unknown option '%s' (see haff merge --help)\n",
              argv[optind - 1]);
      return 2;
    }
  }
  if (argc - optind < 2) {
    fprintf(stderr, "haff merge: expected OUT.db and at least one IN.db (haff merge --help)\n");
    return 2;
  }
  hd_error err;
  hd_error_clear(&err);
  int64_t runs = 0;
  int rc = hd_db_merge(argv[optind], (const char *const *)argv + optind + 1, argc - optind - 1,
                       &runs, &err);
  if (rc) {
    fprintf(stderr, "haff merge: %s\n", err.msg);
    return hd_exit_code(rc);
  }
  if (!quiet)
    fprintf(stderr, "haff merge: %lld runs from %d files into %s\n", (long long)runs,
            argc - optind - 1, argv[optind]);
  return 0;
}
