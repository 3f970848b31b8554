/* `haff merge OUT.db IN.db...`: db/hd_merge.h does the work. */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "haff.h"
#include "hd_merge.h"
#include "hd_opt.h"

/* The options of haff merge. */
typedef struct merge_args {
  int quiet; /* --quiet, -q */
} merge_args;

static const hd_optdef merge_opts[] = {
    HD_OPT_FLAG("quiet", 'q', merge_args, quiet, "no closing line"), {0}};

const hd_optspec hd_cmd_merge_spec = {
    HD_OPT_SPEC("merge", merge_opts, 0, 2, -1, "OUT.db and at least one IN.db"), .out_pos = 1,
    .head =
        "usage: haff merge OUT.db IN.db... [--quiet]\n"
        "  Appends every run of the IN databases to OUT (created if missing), with new run ids;\n"
        "  their collisions, samples, states, checkpoints and provenance follow them, and the\n"
        "  provenance table records each run's source file and id, host and Slurm job and task.\n"
        "  Refused (exit 2, OUT untouched): a file given twice (also as OUT, by any link), a file\n"
        "  that is not a haff database, is of a newer schema or fails PRAGMA integrity_check, OUT\n"
        "  or an input being written by a run, a write-protected OUT, OUT '-', ':memory:' or\n"
        "  'file:...' (./NAME is the file), a table of yours with a name that is not a plain\n"
        "  identifier, a run (same scene, seed and\n"
        "  commit: runs.git_commit) already in OUT.  Atomic: OUT is\n"
        "  replaced only once the merge is whole; SIGINT or SIGTERM stop it (exit 1), OUT as "
        "it was.\n"};

int hd_cmd_merge(int argc, char **argv) {
  merge_args a = {0};
  hd_optres res;
  int rc = hd_opt_parse(&hd_cmd_merge_spec, argc, argv, &a, &res);
  if (rc) return rc < 0 ? 0 : rc;
  hd_error err;
  hd_error_clear(&err);
  int64_t runs = 0;
  rc = hd_db_merge(res.pos[0], (const char *const *)res.pos + 1, res.npos - 1, &runs, &err);
  if (rc) {
    fprintf(stderr, "haff merge: %s\n", err.msg);
    return hd_exit_code(rc);
  }
  if (!a.quiet)
    fprintf(stderr, "haff merge: %lld runs from %d files into %s\n", (long long)runs, res.npos - 1,
            res.pos[0]);
  return 0;
}
