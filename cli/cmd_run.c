/* `haff run` and `haff resume`. */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "haff.h"
#include "hd_db.h"
#include "hd_merge.h"
#include "hd_opt.h"
#include "hd_run.h"
#include "hd_scene.h"

#define MAX_SET 256

/* The options of haff run and haff resume (one table: .set says which reads it). */
typedef struct run_args {
  const char *db;             /* haff run -o DB, NULL: from the scene's name */
  const char *seed;           /* --seed N (read below: any unsigned 64-bit number), or NULL */
  const char *set_v[MAX_SET]; /* the --set overrides */
  hd_optlist sets;            /* over set_v */
  long long run;              /* haff resume --run ID, 0: the newest resumable */
  int all, quiet;             /* --all (resume), --quiet */
  int force;                  /* --force: a run of a scene and seed that DB has already */
  int list_keys;              /* --list-keys: print the scene keys, run nothing */
  const char *sweep_point;    /* --sweep-point TEXT (haff sweep's points): runs.sweep_point */
  double progress;            /* --progress SECONDS, NAN when not given */
} run_args;

enum { FOR_RUN = 1, FOR_RESUME = 2 };
static const hd_optdef run_opts[] = {
    HD_OPT_PATH("o", 'o', run_args, db,
                HD_OPTF_SHORT | HD_OPTF_NOT_STDOUT | HD_OPTF_OUTPUT | HD_OPTF_DB, "DB",
                "the database [SCENE's name with .db, in the current folder]", .set = FOR_RUN),
    HD_OPT_LIST("set", 0, run_args, sets, "SECTION.KEY=VALUE", "overrides a scene key (repeatable)",
                .set = FOR_RUN),
    HD_OPT_STR("seed", 0, run_args, seed, "N", "overrides [system] seed", .flags = HD_OPTF_ONCE,
               .set = FOR_RUN),
    HD_OPT_INT("run", 0, run_args, run, 1, LLONG_MAX, HD_OPTF_ONCE, "ID",
               "the run [the newest resumable run]", .set = FOR_RESUME),
    HD_OPT_FLAG("force", 0, run_args, force,
                "run even when DB has a run of the same scene and seed", .set = FOR_RUN),
    HD_OPT_FLAG("list-keys", 0, run_args, list_keys,
                "prints every scene key as SECTION.KEY (for --set), one a line; runs nothing",
                .set = FOR_RUN),
    /* not listed: haff sweep's note of which point a run is (runs.sweep_point) */
    HD_OPT_STR("sweep-point", 0, run_args, sweep_point, "TEXT", NULL, .set = FOR_RUN),
    HD_OPT_FLAG("all", 0, run_args, all, "every resumable run, oldest first", .set = FOR_RESUME),
    HD_OPT_FLAG("quiet", 'q', run_args, quiet, "no progress, no closing line"),
    HD_OPT_DBL("progress", 0, run_args, progress, 0, 1e9, 0, "SECONDS",
               "a progress line every SECONDS when stderr is not a terminal [60] (0: none)"),
    {0}};

const hd_optspec hd_cmd_run_spec = {
    HD_OPT_SPEC("run", run_opts, FOR_RUN, 0, 1, "one scene file"),
    .head =
        "usage: haff run SCENE [-o DB] [--set SECTION.KEY=VALUE]... [--seed N] [--force]\n"
        "                [--quiet] [--progress SECONDS]\n"
        "       haff run --list-keys\n"
        "  Runs the scene file SCENE and appends one run to DB (default: SCENE's name with .db,\n"
        "  in the current folder).  --set overrides a scene key; --seed overrides [system] seed.\n"
        "  A scene and seed that DB has run already are refused (exit 2: the run would repeat\n"
        "  it, and analyses would count it twice) unless --force.  The run records the command\n"
        "  line and the build (haff -V) in runs.command, runs.git_commit ... runs.cflags.\n"
        "  Exit status: 0 done, 1 failed run (collapse, interrupted, database), 2 bad "
        "usage/input.\n"
        "  SIGINT/SIGTERM: the run is checkpointed, marked 'interrupted'; continue with haff "
        "resume.\n"
        "  Progress: redrawn on a terminal; when stderr is not one (a batch log), one line every\n"
        "  --progress SECONDS [60] (0: none).  runs.events and runs.cpd follow the run.\n"};

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

/* Runs scene sc as a new run of db (sc != NULL), or resumes run want of db (sc NULL; want 0:
 * the newest resumable), and says on stderr how it ended, as "haff CMD: ...": the interruption
 * with how to go on, the error, a note, or "done" unless quiet.  *run gets the run's id.
 * Returns the status (HD_EINTR: stopped by a signal). */
static int drive_run(const char *cmd, const hd_scene *sc, int64_t want, const char *db, int quiet,
                     double every, const char *cmdline, const char *sweep_point, int64_t *run) {
  hd_error err;
  hd_error_clear(&err);
  char note[256] = "";
  hd_run_opts o = {.db_path = db,
                   .quiet = quiet,
                   .version = HAFF_VERSION,
                   .command = cmdline,
                   .sweep_point = sweep_point,
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

/* Parses argv by spec into *a (its defaults set here).  Returns as hd_opt_parse; *every gets
 * --progress for hd_run_opts (0 not given, -1 none). */
static int run_parse(const hd_optspec *spec, int argc, char **argv, run_args *a, hd_optres *res,
                     double *every) {
  memset(a, 0, sizeof *a);
  a->sets = (hd_optlist){a->set_v, 0, MAX_SET};
  a->progress = NAN;
  int rc = hd_opt_parse(spec, argc, argv, a, res);
  *every = isnan(a->progress) ? 0 : a->progress == 0 ? -1.0 : a->progress;
  return rc;
}

/* --seed N into *seed: any unsigned 64-bit number (strtoull, which alone would take " -1").
 * 0, or 2 after one line. */
static int parse_seed(const char *arg, unsigned long long *seed) {
  char *end;
  errno = 0;
  *seed = strtoull(arg, &end, 10);
  if (!isdigit((unsigned char)arg[0]) || *end) {
    fprintf(stderr, "haff run: --seed %s: not a non-negative integer\n", arg);
    return 2;
  }
  if (errno == ERANGE) {
    fprintf(stderr, "haff run: --seed %s: too large (max %llu)\n", arg, ULLONG_MAX);
    return 2;
  }
  return 0;
}

/* The command line argv[0 .. argc) as one line that a POSIX shell reads back: each word
 * single-quoted when it needs it (a quote in it as '\''), blanks between; malloc'd, NULL when out
 * of memory.  A control byte (a newline) is kept inside its quotes. */
static char *command_line(int argc, char *const *argv) {
  size_t cap = 1;
  for (int k = 0; k < argc; k++) cap += 4 * strlen(argv[k]) + 3;
  char *s = malloc(cap), *p = s;
  if (!s) return NULL;
  for (int k = 0; k < argc; k++) {
    const char *w = argv[k];
    int plain = w[0] && strspn(w, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                  "0123456789._/-+=:,@%") == strlen(w);
    if (k) *p++ = ' ';
    if (!plain) *p++ = '\'';
    for (; *w; w++)
      if (*w == '\'' && !plain)
        memcpy(p, "'\\''", 4), p += 4;
      else
        *p++ = *w;
    if (!plain) *p++ = '\'';
  }
  *p = '\0';
  return s;
}

/* --list-keys: every scene key as SECTION.KEY, one a line, from the scene's key table. */
static int list_keys(void) {
  char key[96];
  for (int k = 0; hd_scene_key_name(k, key, sizeof key) == 0; k++) printf("%s\n", key);
  return 0;
}

/* Refuses (2, said) a run of scene sc into db when db has one of the same scene and seed
 * already: a second run would repeat the first bit for bit, and the analyses would count it
 * twice.  0 when db is not there yet, has no such run, or cannot be read (the run then says
 * why). */
static int refuse_same(const char *db, const hd_scene *sc) {
  if (access(db, F_OK) != 0) return 0;
  hd_error err;
  hd_error_clear(&err);
  hd_db *h = NULL;
  hd_same_run same;
  int rc = hd_db_open_readonly(&h, db, &err);
  if (!rc) rc = hd_db_find_same_run(h, sc->text ? sc->text : "", sc->seed, &same, &err);
  hd_db_close(h, NULL);
  if (rc || same.run == 0) return 0;
  int open = !strcmp(same.status, "interrupted") || !strcmp(same.status, "running") ||
             !strcmp(same.status, "failed");
  fprintf(stderr,
          "haff run: %s has run %lld of this scene and seed already (status %s, commit %.12s): "
          "not run again; --force runs it once more",
          db, (long long)same.run, same.status, same.commit);
  if (open) fprintf(stderr, "; haff resume continues that one (--run %lld)", (long long)same.run);
  fputc('\n', stderr);
  return 2;
}

int hd_cmd_run(int argc, char **argv) {
  run_args a;
  hd_optres res;
  double every;
  int rc = run_parse(&hd_cmd_run_spec, argc, argv, &a, &res, &every);
  if (rc) return rc < 0 ? 0 : rc;
  if (a.list_keys) {
    if (argc != 2) {
      fprintf(stderr, "haff run: --list-keys goes alone\n");
      return 2;
    }
    return list_keys();
  }
  if (res.npos != 1) {
    fprintf(stderr, "haff run: expected one scene file (see haff run --help)\n");
    return 2;
  }
  unsigned long long seed = 0;
  int have_seed = a.seed != NULL, quiet = a.quiet, nset = a.sets.n;
  if (have_seed && parse_seed(a.seed, &seed)) return 2;
  const char *db = a.db, **sets = a.set_v;
  const char *scene = res.pos[0];
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
  rc = hd_scene_load(&sc, scene, sets, nset, &err);
  if (rc) { /* a scene that cannot be read is bad input too */
    fprintf(stderr, "haff run: %s\n", err.msg);
    return 2;
  }
  if (!a.force && refuse_same(db, &sc)) {
    hd_scene_free(&sc);
    return 2;
  }
  /* the command line as typed (main's), else as this subcommand was called */
  char *cmdline = haff_argv ? command_line(haff_argc, haff_argv) : command_line(argc, argv);
  int64_t run = 0;
  rc = drive_run("run", &sc, 0, db, quiet, every, cmdline, a.sweep_point, &run);
  free(cmdline);
  hd_scene_free(&sc);
  return hd_exit_code(rc);
}

const hd_optspec hd_cmd_resume_spec = {
    HD_OPT_SPEC("resume", run_opts, FOR_RESUME, 1, 1, "one database"),
    .head =
        "usage: haff resume DB [--run ID | --all] [--quiet] [--progress SECONDS]\n"
        "  Continues an interrupted, killed or failed (disk full) run from its last checkpoint;\n"
        "  the result is the same as that of an uninterrupted run.  Without --run: the newest\n"
        "  resumable run; --all: every resumable run of DB in turn, oldest first (one that "
        "another\n"
        "  process is running is left to it; a signal stops the whole series).\n"};

/* Resumes run want (0: the newest resumable) of db; says how it ended.  Returns the status
 * (HD_EINTR: stopped by a signal). */
static int resume_one(const char *db, long long want, int quiet, double every) {
  int64_t run = 0;
  return drive_run("resume", NULL, (int64_t)want, db, quiet, every, NULL, NULL, &run);
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

int hd_cmd_resume(int argc, char **argv) {
  run_args a;
  hd_optres res;
  double every;
  int rc = run_parse(&hd_cmd_resume_spec, argc, argv, &a, &res, &every);
  if (rc) return rc < 0 ? 0 : rc;
  long long want = a.run;
  int quiet = a.quiet, all = a.all;
  const char *db = res.pos[0];
  if (all && want) {
    fprintf(stderr, "haff resume: --all and --run: give one\n");
    return 2;
  }
  if (!all) return hd_exit_code(resume_one(db, want, quiet, every));
  int64_t *ids;
  size_t n;
  rc = list_resumable(db, &ids, &n);
  if (rc) return hd_exit_code(rc);
  if (n == 0 && !quiet) fprintf(stderr, "haff resume: %s: no run to resume\n", db);
  int worst = 0;
  for (size_t k = 0; k < n; k++) {
    if (hd_merge_lock_held(db, ids[k])) { /* a live run ('running', its lock held) */
      if (!quiet)
        fprintf(stderr, "haff resume: %s: run %lld is being run by another process: left to it\n",
                db, (long long)ids[k]);
      continue;
    }
    int st = resume_one(db, ids[k], quiet, every);
    if (hd_exit_code(st) > worst) worst = hd_exit_code(st);
    if (st == HD_EINTR) break; /* a signal stops the series, not only this run */
  }
  free(ids);
  return worst;
}
