/* gen_file.h: the main of the programs that rewrite part of a file from a table of the code
 * (tests/gen_schema.c: `make schema`; tests/gen_scene_keys.c: `make scene-keys`).  Usage:
 * PROG FILE [--check]: FILE is read whole (at most 1 MiB), gen_file.make gives its new text;
 * without --check FILE is rewritten when that differs; with --check nothing is written and
 * the exit status is 1 when it differs.  Exit 2: usage; 1: an error, said on stderr. */
#ifndef GEN_FILE_H
#define GEN_FILE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  const char *prog;      /* the program's name, for its usage line */
  const char *file;      /* the file it is made for, for its usage line */
  const char *table;     /* what the text comes from, e.g. "key table" */
  const char *target;    /* the make target that rewrites the file */
  const char *rewritten; /* what a rewrite says it did, e.g. "tables rewritten" */
  /* The new text of the file whose text is in: 0 and *out (malloc'd, the caller frees it), or
   * non-zero and why (a message of at most why_size bytes) */
  int (*make)(const char *in, char **out, char *why, size_t why_size);
} gen_file;

static inline int gen_file_main(const gen_file *g, int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s %s [--check]\n", g->prog, g->file);
    return 2;
  }
  FILE *f = fopen(argv[1], "rb");
  if (!f) {
    perror(argv[1]);
    return 1;
  }
  static char in[1 << 20];
  size_t n = fread(in, 1, sizeof in - 1, f);
  int whole = feof(f) && !ferror(f);
  fclose(f);
  if (!whole) { /* a rewrite of a cut text would lose the rest of the file */
    fprintf(stderr, "%s: not read whole (larger than %zu bytes, or a read error)\n", argv[1],
            sizeof in - 1);
    return 1;
  }
  in[n] = '\0';
  char *out = NULL, why[512] = "";
  if (g->make(in, &out, why, sizeof why)) {
    fprintf(stderr, "%s: %s\n", argv[1], why);
    return 1;
  }
  int same = !strcmp(in, out);
  if (argc > 2 && !strcmp(argv[2], "--check")) {
    if (!same)
      fprintf(stderr, "%s: not what the %s gives: run make %s\n", argv[1], g->table, g->target);
    free(out);
    return !same;
  }
  if (!same) {
    f = fopen(argv[1], "wb");
    if (!f || fputs(out, f) == EOF || fclose(f) != 0) {
      perror(argv[1]);
      free(out);
      return 1;
    }
  }
  printf("%s: %s\n", argv[1], same ? "up to date" : g->rewritten);
  free(out);
  return 0;
}

#endif
