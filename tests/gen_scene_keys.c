/* `make scene-keys`: rewrites the key tables of docs/scene-keys.md from the scene key table
 * (engine/scene/hd_scene_keys.h, hd_scene_keys_doc in hd_scene_doc.c).  Usage: gen_scene_keys FILE
 * [--check]; with --check it writes nothing and exits 1 when FILE differs from what the table
 * gives.  tests/test_scene.c makes the same check in `make test`. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hd_scene.h"

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: gen_scene_keys docs/scene-keys.md [--check]\n");
    return 2;
  }
  FILE *f = fopen(argv[1], "rb");
  if (!f) {
    perror(argv[1]);
    return 1;
  }
  static char in[1 << 20];
  size_t n = fread(in, 1, sizeof in - 1, f);
  fclose(f);
  in[n] = '\0';
  char *out = NULL;
  hd_error err;
  hd_error_clear(&err);
  if (hd_scene_keys_doc(in, &out, &err)) {
    fprintf(stderr, "%s: %s\n", argv[1], err.msg);
    return 1;
  }
  int same = !strcmp(in, out);
  if (argc > 2 && !strcmp(argv[2], "--check")) {
    if (!same) fprintf(stderr, "%s: not what the key table gives: run make scene-keys\n", argv[1]);
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
  printf("%s: %s\n", argv[1], same ? "up to date" : "tables rewritten");
  free(out);
  return 0;
}
