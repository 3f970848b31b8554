/* `make scene-keys`: rewrites the key tables of docs/scene-keys.md from the scene key table
 * (engine/scene/hd_scene_keys.h, hd_scene_keys_doc in hd_scene_doc.c).  Usage: gen_scene_keys FILE
 * [--check]; with --check it writes nothing and exits 1 when FILE differs from what the table
 * gives.  tests/test_scene.c makes the same check in `make test`. */
#include <stdio.h>

#include "gen_file.h"
#include "hd_scene.h"

static int make(const char *in, char **out, char *why, size_t why_size) {
  hd_error err;
  hd_error_clear(&err);
  if (!hd_scene_keys_doc(in, out, &err)) return 0;
  snprintf(why, why_size, "%s", err.msg);
  return 1;
}

int main(int argc, char **argv) {
  const gen_file g = {"gen_scene_keys", "docs/scene-keys.md", "key table",
                      "scene-keys",     "tables rewritten",   make};
  return gen_file_main(&g, argc, argv);
}
