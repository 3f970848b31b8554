/* `haff mc SUB ...`: dispatches to the Monte Carlo programs of mc/. */
#include <stdio.h>
#include <string.h>

int haff_mc_main(int argc, char **argv);
int hd_mc_fmean_main(int argc, char **argv);
int hd_mc_eps_main(int argc, char **argv); /* mc/eps_cli.c */

/* One `haff mc` subcommand. */
typedef struct mc_command {
  const char *name;                   /* "fmean", "eps" */
  int (*main)(int argc, char **argv); /* argv[0] == name; returns the exit code */
  const char *summary;                /* one line for `haff mc --help` */
} mc_command;

static const mc_command mc_commands[] = {
    {"fmean", hd_mc_fmean_main, "<f> and D_e = D/<f> for an elongation a/d"},
    {"eps", hd_mc_eps_main, "sample or tabulate p_beta(eps), the rods' stochastic restitution"},
    {NULL, NULL, NULL} /* sentinel; each mc program adds its line above */
};

int haff_mc_main(int argc, char **argv) {
  if (argc >= 2) {
    for (const mc_command *c = mc_commands; c->name; c++)
      if (!strcmp(argv[1], c->name)) return c->main(argc - 1, argv + 1);
  }
  int help = argc >= 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"));
  if (!help) { /* bad usage: one line (the contract), the list is in --help */
    if (argc >= 2)
      fprintf(stderr, "haff mc: unknown program '%s' (haff mc --help lists them)\n", argv[1]);
    else
      fprintf(stderr, "haff mc: expected a program (haff mc --help lists them)\n");
    return 2;
  }
  printf("usage: haff mc PROGRAM [ARGS...]\n\nprograms:\n");
  for (const mc_command *c = mc_commands; c->name; c++) printf("  %-8s %s\n", c->name, c->summary);
  return 0;
}
