/* bin/haff: dispatches to the subcommands of the table haff_commands (cli/haff_commands.c). */
#include "haff.h"
#include "hd_build.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *out) {
  fprintf(out, "usage: haff COMMAND [ARGS...]   (haff COMMAND --help, or haff help COMMAND, for "
               "each)\n\ncommands:\n");
  for (const haff_command *c = haff_commands; c->name; c++)
    if (!c->group) fprintf(out, "  %-12s %s\n", c->name, c->summary);
  fprintf(
      out,
      "\noptions: -h, --help (this text), -V, --version (the version, as in runs.version, and\n"
      "the build: its git commit, compiler and flags, as runs.git_commit ... cflags store them)\n");
  fprintf(out, "\nexit status: 0 ok, 1 failed run (collapse, interrupted, resource), 2 bad usage "
               "or input\n");
}

/* `haff GROUP PROGRAM ...` (argv[0] the group): the program's main, or the group's help. */
static int group_main(const haff_command *g, int argc, char **argv) {
  if (argc >= 2)
    for (const haff_command *c = haff_commands; c->name; c++)
      if (c->group && !strcmp(c->group, g->name) && !strcmp(argv[1], c->name))
        return c->main(argc - 1, argv + 1);
  int help = argc >= 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"));
  if (!help) { /* bad usage: one line (the contract), the list is in --help */
    if (argc >= 2)
      fprintf(stderr, "haff %s: unknown program '%s' (haff %s --help lists them)\n", g->name,
              argv[1], g->name);
    else
      fprintf(stderr, "haff %s: expected a program (haff %s --help lists them)\n", g->name,
              g->name);
    return 2;
  }
  printf("usage: haff %s PROGRAM [ARGS...]\n\nprograms:\n", g->name);
  for (const haff_command *c = haff_commands; c->name; c++)
    if (c->group && !strcmp(c->group, g->name)) printf("  %-8s %s\n", c->name, c->summary);
  return 0;
}

/* The exit code of a command that returned rc, once what it wrote on stdout is out: a write
 * error (a full disk, /dev/full, a closed pipe) turns a success into 1, with one line naming the
 * command.  A command that failed already said why; its code stays. */
static int stdout_flushed(const char *cmd, int rc) {
  if (rc) { /* said why already */
    fflush(stdout);
    return rc;
  }
  return haff_close_out(stdout, cmd, NULL); /* with the reason: haff_stdout_wrap kept it */
}

int main(int argc, char **argv) {
  /* a file size limit (ulimit -f) then fails the write with EFBIG, which the run reports and
   * survives like a full disk, instead of killing the process with the run left 'running' */
  signal(SIGXFSZ, SIG_IGN);
  /* the command line as typed, for runs.command: a copy of the pointers, which getopt_long
   * permutes in argv as it parses */
  char **typed = malloc(((size_t)argc + 1) * sizeof *typed);
  if (typed) {
    memcpy(typed, argv, ((size_t)argc + 1) * sizeof *typed);
    haff_argc = argc, haff_argv = typed;
  }
  haff_stdout_wrap();
  if (argc < 2) {
    usage(stderr);
    return 2;
  }
  static char help_opt[] = "--help";
  char *hv[5];
  if (argc >= 3 && !strcmp(argv[1], "help")) { /* haff help CMD [PROGRAM]: its --help */
    hv[0] = argv[0], hv[1] = argv[2], hv[2] = argc >= 4 ? argv[3] : help_opt;
    hv[3] = argc >= 4 ? help_opt : NULL, hv[4] = NULL;
    argc = argc >= 4 ? 4 : 3, argv = hv;
  }
  if (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help") || !strcmp(argv[1], "help")) {
    usage(stdout);
    return stdout_flushed(NULL, 0);
  }
  if (!strcmp(argv[1], "--version") || !strcmp(argv[1], "-V")) {
    /* the first line is runs.version (the man page's header takes it); then the build's
     * provenance, as runs.git_commit, git_dirty, compiler and cflags store it */
    printf("haff %s\ncommit %s%s\ncompiler %s\ncflags %s\n", HAFF_VERSION, hd_build_commit,
           hd_build_dirty == 1   ? " (modified)"
           : hd_build_dirty == 0 ? ""
                                 : " (not a git build)",
           hd_build_compiler, hd_build_cflags);
    return stdout_flushed(NULL, 0);
  }
  for (const haff_command *c = haff_commands; c->name; c++)
    if (!c->group && !strcmp(argv[1], c->name))
      return stdout_flushed(c->name, c->main ? c->main(argc - 1, argv + 1)
                                             : group_main(c, argc - 1, argv + 1));
  fprintf(stderr, "haff: unknown command '%s' (haff --help lists them)\n", argv[1]);
  return 2;
}
