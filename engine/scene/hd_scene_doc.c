/* hd_scene_doc: the key tables of docs/scene-keys.md, from SCENE_KEYS (`make scene-keys`;
 * tests/test_scene.c checks the file against them). */
#include "hd_scene_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The generated table of section s. */
static void doc_table(int s, sbuf *b) {
  hd_scene_put(b, "| key | default | range | meaning |\n|---|---|---|---|\n");
  for (int k = 0; k < N_KEY; k++) {
    const key_def *kd = &hd_scene_keys[k];
    if (kd->sec != s) continue;
    char def[80], range[320];
    if (kd->doc_def)
      snprintf(def, sizeof def, "%s", kd->doc_def);
    else if (kd->type == KT_BOOL || kd->type == KT_ENUM)
      snprintf(def, sizeof def, "`%s`", kd->names[(int)kd->def]);
    else
      hd_scene_shortest(kd->def, def, sizeof def);
    if (kd->doc_forms) {
      hd_scene_forms_list("`", " \\| ", " \\| ", range, sizeof range);
      size_t at = strlen(range);
      snprintf(range + at, sizeof range - at, "; %s", kd->doc_range);
    } else if (kd->doc_range) {
      snprintf(range, sizeof range, "%s", kd->doc_range);
    } else if (kd->type == KT_BOOL) {
      snprintf(range, sizeof range, "`1 0 true false yes no on off`");
    } else if (kd->type == KT_ENUM) {
      range[0] = '\0';
      for (int j = 0; kd->names[j]; j++) {
        size_t at = strlen(range);
        snprintf(range + at, sizeof range - at, "%s`%s`", j ? " \\| " : "", kd->names[j]);
      }
    } else if (kd->type == KT_LONG || kd->type == KT_WHOLE) {
      char lo[40], hi[40];
      hd_scene_shortest(kd->lo, lo, sizeof lo);
      hd_scene_shortest(kd->hi, hi, sizeof hi);
      snprintf(range, sizeof range, "whole, %s … %s", lo, hi);
    } else {
      char why[120];
      hd_scene_range_why(kd, why, sizeof why);
      snprintf(range, sizeof range, "%s", why + strlen("must be "));
      char *ge = strstr(range, ">=");
      if (ge) memmove(ge + 3, ge + 2, strlen(ge + 2) + 1), memcpy(ge, "≥", 3);
      if (!strncmp(range, "in ", 3)) memmove(range, range + 3, strlen(range + 3) + 1);
    }
    hd_scene_put(b, "| `%s` | %s | %s | %s |\n", kd->doc_key ? kd->doc_key : kd->name, def, range,
                 kd->doc);
  }
}

int hd_scene_keys_doc(const char *in, char **out, hd_error *err) {
  static const char open_tag[] = "<!-- keys ", end_tag[] = "<!-- end keys -->";
  sbuf b = {0};
  hd_scene_put(&b, "%s", "");
  const char *p = in;
  long line = 0;
  while (*p) {
    const char *nl = strchr(p, '\n');
    size_t len = nl ? (size_t)(nl - p) + 1 : strlen(p);
    line++;
    hd_scene_put(&b, "%.*s", (int)len, p);
    if (!strncmp(p, open_tag, sizeof open_tag - 1)) {
      char name[32] = "";
      sscanf(p + sizeof open_tag - 1, "%31[a-z]", name);
      int s = !strcmp(name, "species") ? S_SPECIES : hd_scene_find_sec(name);
      if (s < 0) {
        free(b.s);
        return hd_error_set(err, HD_EINPUT, "line %ld: %s: no such section", line, name);
      }
      doc_table(s, &b);
      p += len; /* skip the old table */
      while (*p && strncmp(p, end_tag, sizeof end_tag - 1)) {
        nl = strchr(p, '\n');
        line++;
        p = nl ? nl + 1 : p + strlen(p);
      }
      if (!*p) {
        free(b.s);
        return hd_error_set(err, HD_EINPUT, "line %ld: table of [%s] not closed by %s", line, name,
                            end_tag);
      }
      continue;
    }
    p += len;
  }
  if (b.oom) {
    free(b.s);
    return hd_error_set(err, HD_ENOMEM, "out of memory");
  }
  *out = b.s;
  return HD_OK;
}
