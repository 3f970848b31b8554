/* libFuzzer harness: the scene parser (hd_scene_load_string) on arbitrary bytes.  An accepted
 * scene is freed; a refused one must leave one printable line in err.msg (no control byte:
 * hd_error_set escapes them) and no allocation.  The same for hd_scene_read_stored (the readers'
 * loader).  Built and run by `make fuzz`. */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hd_scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char *text = malloc(size + 1);
  if (!text) return 0;
  memcpy(text, data, size);
  text[size] = '\0'; /* a NUL inside ends the text, as it would a C string */
  hd_scene sc;
  hd_error err;
  hd_error_clear(&err);
  int rc = hd_scene_load_string(&sc, text, "fuzz.ini", NULL, 0, &err);
  if (rc == HD_OK) {
    if (!sc.text) abort(); /* an accepted scene has its canonical text */
    hd_scene sc2;          /* which must load again, to the same text */
    hd_error e2;
    if (hd_scene_load_stored(&sc2, sc.text, "canonical", &e2) != HD_OK) {
      /* CI keeps only the log: what failed, on the text it failed on */
      fprintf(stderr, "canonical text refused: %s\n--- text:\n%s---\n", e2.msg, sc.text);
      abort();
    }
    if (strcmp(sc.text, sc2.text)) {
      fprintf(stderr, "canonical text changed:\n%s--- reloaded:\n%s---\n", sc.text, sc2.text);
      abort();
    }
    hd_scene_free(&sc2);
    hd_scene_free(&sc);
  } else {
    if (!err.msg[0]) abort(); /* a refusal says why */
    for (const char *p = err.msg; *p; p++)
      if ((unsigned char)*p < 0x20 || *p == 0x7f) abort(); /* on one printable line */
  }
  /* the readers' loader (analysis, export): what it accepts reads back to the same text */
  hd_scene sc3, sc4;
  hd_error e3, e4;
  if (hd_scene_read_stored(&sc3, text, "fuzz.ini", &e3) == HD_OK) {
    if (hd_scene_read_stored(&sc4, sc3.text, "canonical", &e4) != HD_OK) {
      fprintf(stderr, "read_stored: canonical text refused: %s\n--- text:\n%s---\n", e4.msg,
              sc3.text);
      abort();
    }
    if (strcmp(sc3.text, sc4.text)) {
      fprintf(stderr, "read_stored: canonical text changed:\n%s--- reloaded:\n%s---\n",
              sc3.text, sc4.text);
      abort();
    }
    hd_scene_free(&sc4);
    hd_scene_free(&sc3);
  } else {
    if (!e3.msg[0]) abort();
  }
  free(text);
  return 0;
}
