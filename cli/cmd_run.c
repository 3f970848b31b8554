/* `haff run` and `haff resume`. */
#include <ctype.h>
#include <errno.h>
#include <getopt.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "haff.h"
#include "hd_db.h"
#include "hd_run.h"
#include "hd_scene.h"

int haff_run_main(int argc, char **argv);
int haff_resume_main(int argc, char **argv);

#define MAX_SET 256

static const char run_usage[] =
    "usage: haff run SCENE [-o DB] [--set SECTION.KEY=VALUE]... [--seed N] [--quiet]\n"
    "                [--progress SECONDS]\n"
    "  Runs the scene file SCENE and appends one run to DB (default: SCENE's name with .db,\n"
    "  in the current folder).  --set overrides a scene key; --seed overrides [system] seed.\n"
    "  Exit status: 0 done, 1 failed run (collapse, interrupted, database), 2 bad usage/input.\n"
    "  SIGINT/SIGTERM: the run is checkpointed, marked 'interrupted'; continue with haff resume.\n"
    "  Progress: redrawn on a terminal; when stderr is not one (a batch log), one line every\n"
    "  --progress SECONDS [60] (0: none).  runs.events and runs.cpd follow the run.\n";

/* DB name from the scene path: dir/name.ini -> name.db */
static void default_db(const char *scene, char *out, size_t n) {
  const char *base = strrchr(scene, '/');
  base = base ? base + 1 : scene;
  snprintf(out, n, "%s", base);
  char *dot = strrchr(out, '.');
  if (dot && dot != out) *dot = '\0';
  size_t len = strlen(out);
  snprintf(out + len, n - len, ".db");
}

/* Says that cmd's run was interrupted and how to go on, for this file and run: a command to
 * paste into a POSIX shell, the path single-quoted when the shell would need it (a quote in it
 * as '\'') and led by ./ when it begins with '-'.  A path with a control byte (which no quoting
 * keeps on one line) is not echoed.  Before the run began (run 0), that nothing was written. */
static void say_interrupted(const char *cmd, const char *msg, const char *db, int64_t run) {
  if (run == 0) {
    fprintf(stderr, "haff %s: %s, before the run began: nothing was written\n", cmd, msg);
    return;
  }
  for (const char *p = db; *p; p++)
    if ((unsigned char)*p < 0x20 || *p == 0x7f) {
      fprintf(stderr, "haff %s: %s (continue with: haff resume DB --run %lld, DB the database)\n",
              cmd, msg, (long long)run);
      return;
    }
  const char *lead = db[0] == '-' ? "./" : "";
  int plain = strspn(db, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._/-+") ==
              strlen(db);
  fprintf(stderr, "haff %s: %s (continue with: haff resume %s%s", cmd, msg, plain ? "" : "'", lead);
  for (const char *p = db; *p; p++)
    if (*p == '\'')
      fputs("'\\''", stderr);
    else
      fputc(*p, stderr);
  fprintf(stderr, "%s --run %lld)\n", plain ? "" : "'", (long long)run);
}

/* --progress SECONDS: *every gets the seconds (0 from the user means none: -1); 0 ok, else 2
 * with the message said. */
/* Runs scene sc as a new run of db (sc != NULL), or resumes run want of db (sc NULL; want 0:
 * the newest resumable), and says on stderr how it ended, as "haff CMD: ...": the interruption
 * with how to go on, the error, a note, or "done" unless quiet.  *run gets the run's id.
 * Returns the status (HD_EINTR: stopped by a signal). */
static int drive_run(const char *cmd, const hd_scene *sc, int64_t want, const char *db, int quiet,
                     double every, int64_t *run) {
  hd_error err;
  hd_error_clear(&err);
  char note[256] = "";
  hd_run_opts o = {.db_path = db,
                   .quiet = quiet,
                   .version = HAFF_VERSION,
                   .note = note,
                   .note_size = sizeof note,
                   .progress_every = every};
  *run = 0;
  int rc = sc ? hd_run_new(sc, &o, run, &err) : hd_run_resume(want, &o, run, &err);
  if (rc == HD_EINTR) {
    say_interrupted(cmd, err.msg, db, *run);
    return rc;
  }
  if (rc) {
    fprintf(stderr, "haff %s: %s\n", cmd, err.msg);
    return rc;
  }
  if (note[0]) fprintf(stderr, "haff %s: note: run %lld %s\n", cmd, (long long)*run, note);
  if (!quiet) fprintf(stderr, "haff %s: run %lld done, in %s\n", cmd, (long long)*run, db);
  return HD_OK;
}

static int parse_progress(const char *cmd, const char *arg, double *every) {
  char *end;
  errno = 0;
  double v = strtod(arg, &end);
  if (!*arg || *end || errno || !(v >= 0) || v > 1e9) {
    fprintf(stderr, "haff %s: --progress %s: not a number of seconds in [0, 1e9]\n", cmd, arg);
    return 2;
  }
  *every = v == 0 ? -1.0 : v;
  return 0;
}

/* One line for an option getopt refused (opterr = 0): the argument at fault and where help is. */
static int bad_option(const char *cmd, char **argv, const struct option *opts) {
  char buf[8];
  fprintf(stderr, "haff %s: unknown option or missing value '%s' (see haff %s --help)\n", cmd,
          hd_opt_culprit(argv, opts, buf, sizeof buf), cmd);
  return 2;
}

int haff_run_main(int argc, char **argv) {
  static const struct option opts[] = {
      {"set", required_argument, 0, 's'}, {"seed", required_argument, 0, 'S'},
      {"quiet", no_argument, 0, 'q'},     {"progress", required_argument, 0, 'P'},
      {"help", no_argument, 0, 'h'},      {0, 0, 0, 0}};
  const char *db = NULL, *sets[MAX_SET];
  int nset = 0, quiet = 0, have_seed = 0, c;
  unsigned long long seed = 0;
  double every = 0;
  optind = 1;
  opterr = 0; /* bad_option says it in one line */
  while ((c = getopt_long(argc, argv, "o:qh", opts, NULL)) != -1) {
    switch (c) {
    case 'o':
      if (!strcmp(optarg, "-")) { /* a database is a file SQLite writes in place, not a stream */
        fprintf(stderr, "haff run: -o -: a database cannot be written to stdout; give a file "
                        "name\n");
        return 2;
      }
      db = optarg;
      break;
    case 's':
      if (nset == MAX_SET) {
        fprintf(stderr, "haff run: more than %d --set options\n", MAX_SET);
        return 2;
      }
      sets[nset++] = optarg;
      break;
    case 'S': {
      char *end;
      if (have_seed) { /* as --set system.seed twice is: the first would be silently lost */
        fprintf(stderr, "haff run: --seed given twice: give one\n");
        return 2;
      }
      errno = 0;
      seed = strtoull(optarg, &end, 10);
      if (!isdigit((unsigned char)optarg[0]) || *end) { /* strtoull takes " -1" */
        fprintf(stderr, "haff run: --seed %s: not a non-negative integer\n", optarg);
        return 2;
      }
      if (errno == ERANGE) {
        fprintf(stderr, "haff run: --seed %s: too large (max %llu)\n", optarg, ULLONG_MAX);
        return 2;
      }
      have_seed = 1;
      break;
    }
    case 'q':
      quiet = 1;
      break;
    case 'P':
      if (parse_progress("run", optarg, &every)) return 2;
      break;
    case 'h':
      fputs(run_usage, stdout);
      return 0;
    default:
      return bad_option("run", argv, opts);
    }
  }
  if (optind != argc - 1) {
    fprintf(stderr, "haff run: expected one scene file (haff run --help)\n");
    return 2;
  }
  const char *scene = argv[optind];
  char seedset[64];
  for (int k = 0; have_seed && k < nset; k++)
    if (hd_scene_override_sets(sets[k], "system", "seed")) {
      fprintf(stderr, "haff run: --seed and --set %s both set [system] seed: give one\n", sets[k]);
      return 2;
    }
  if (have_seed) { /* as an override, so that runs.scene records the seed */
    if (nset == MAX_SET) {
      fprintf(stderr, "haff run: more than %d --set options\n", MAX_SET);
      return 2;
    }
    snprintf(seedset, sizeof seedset, "system.seed=%llu", seed);
    sets[nset++] = seedset;
  }
  char dbbuf[HD_PATH_MAX];
  if (!db) {
    default_db(scene, dbbuf, sizeof dbbuf);
    db = dbbuf;
  }
  hd_error err;
  hd_error_clear(&err);
  hd_scene sc;
  int rc = hd_scene_load(&sc, scene, sets, nset, &err);
  if (rc) { /* a scene that cannot be read is bad input too */
    fprintf(stderr, "haff run: %s\n", err.msg);
    return 2;
  }
  int64_t run = 0;
  rc = drive_run("run", &sc, 0, db, quiet, every, &run);
  hd_scene_free(&sc);
  return hd_exit_code(rc);
}

static const char resume_usage[] =
    "usage: haff resume DB [--run ID | --all] [--quiet] [--progress SECONDS]\n"
    "  Continues an interrupted, killed or failed (disk full) run from its last checkpoint;\n"
    "  the result is the same as that of an uninterrupted run.  Without --run: the newest\n"
    "  resumable run; --all: every resumable run of DB in turn, oldest first (one that another\n"
    "  process is running is left to it; a signal stops the whole series).\n";

/* Resumes run want (0: the newest resumable) of db; says how it ended.  Returns the status
 * (HD_EINTR: stopped by a signal). */
static int resume_one(const char *db, long long want, int quiet, double every) {
  int64_t run = 0;
  return drive_run("resume", NULL, (int64_t)want, db, quiet, every, &run);
}

/* --all: the ids of db's resumable runs, oldest first, into *ids (malloc'd); HD_OK or an error
 * said on stderr. */
static int list_resumable(const char *db, int64_t **ids, size_t *n) {
  hd_error err;
  hd_error_clear(&err);
  *ids = NULL;
  *n = 0;
  hd_db *h = NULL;
  int rc = hd_db_open_readonly(&h, db, &err);
  if (!rc) rc = hd_db_list_resumable(h, ids, n, &err);
  hd_db_close(h, NULL);
  if (rc) fprintf(stderr, "haff resume: %s\n", err.msg);
  return rc;
}

int haff_resume_main(int argc, char **argv) {
  static const struct option opts[] = {
      {"run", required_argument, 0, 'r'}, {"all", no_argument, 0, 'a'},
      {"quiet", no_argument, 0, 'q'},     {"progress", required_argument, 0, 'P'},
      {"help", no_argument, 0, 'h'},      {0, 0, 0, 0}};
  long long want = 0;
  int quiet = 0, all = 0, c;
  double every = 0;
  optind = 1;
  opterr = 0;
  while ((c = getopt_long(argc, argv, "qh", opts, NULL)) != -1) {
    switch (c) {
    case 'r': {
      char *end;
      want = strtoll(optarg, &end, 10);
      if (!*optarg || *end || want <= 0) {
        fprintf(stderr, "haff resume: --run %s: not a run id\n", optarg);
        return 2;
      }
      break;
    }
    case 'a':
      all = 1;
      break;
    case 'q':
      quiet = 1;
      break;
    case 'P':
      if (parse_progress("resume", optarg, &every)) return 2;
      break;
    case 'h':
      fputs(resume_usage, stdout);
      return 0;
    default:
      return bad_option("resume", argv, opts);
    }
  }
  if (optind != argc - 1) {
    fprintf(stderr, "haff resume: expected one database (haff resume --help)\n");
    return 2;
  }
  const char *db = argv[optind];
  if (all && want) {
    fprintf(stderr, "haff resume: --all and --run: give one\n");
    return 2;
  }
  if (!all) return hd_exit_code(resume_one(db, want, quiet, every));
  int64_t *ids;
  size_t n;
  int rc = list_resumable(db, &ids, &n);
  if (rc) return hd_exit_code(rc);
  if (n == 0 && !quiet) fprintf(stderr, "haff resume: %s: no run to resume\n", db);
  int worst = 0;
  for (size_t k = 0; k < n; k++) {
    int st = resume_one(db, ids[k], quiet, every);
    if (hd_exit_code(st) > worst) worst = hd_exit_code(st);
    if (st == HD_EINTR) break; /* a signal stops the series, not only this run */
  }
  free(ids);
  return worst;
}
