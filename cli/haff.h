/* haff command-line front end: the table of subcommands.  Each subcommand is a function
 * int NAME_main(int argc, char **argv) with argv[0] the subcommand's name; it returns the
 * process exit code (0 ok, 1 failed run, 2 bad usage or input) and never calls exit(). */
#ifndef HAFF_CLI_H
#define HAFF_CLI_H

/* One subcommand of bin/haff. */
typedef struct haff_command {
  const char *name;                   /* as typed: "run", "mc", "haff-fit", ... */
  int (*main)(int argc, char **argv); /* entry point, argv[0] == name */
  const char *summary;                /* one line for `haff --help` */
} haff_command;

/* The version string stored in runs.version. */
#define HAFF_VERSION "0.1.0"

/* True if argv holds -h or --help (anywhere after argv[0]). */
int haff_wants_help(int argc, char **argv);

#endif
