/* libFuzzer harness: the sweep file parser (hd_sweepfile_parse) on arbitrary bytes, NUL bytes
 * included.  An accepted file has a scene and a line for it, [axes] or [points] (not both),
 * every axis at least one value and none twice, seeds all digits; every point splits
 * (hd_sweep_split), and every value formatted by hd_sweep_format_set splits back to itself.
 * A refused one leaves one printable line in err.msg (no control byte) and no allocation.
 * Built and run by `make fuzz`; seeds in tests/fuzz/corpus/sweep/. */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hd_sweepfile.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* value, formatted as key=value and split again, reads back as "key=value". */
static void round_trip(const char *key, const char *value) {
  size_t n = strlen(key) + strlen(value) + 8;
  char *set = malloc(n), *want = malloc(n), *buf = NULL;
  if (!set || !want) abort();
  if (hd_sweep_format_set(set, n, key, value) >= (int)n) abort();
  snprintf(want, n, "%s=%s", key, value);
  const char *w[2];
  int k = hd_sweep_split(set, &buf, w, 2);
  if (k != 1 || strcmp(w[0], want)) abort();
  free(buf);
  free(set);
  free(want);
}

static int cmp_str(const void *x, const void *y) {
  return strcmp(*(const char *const *)x, *(const char *const *)y);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  hd_sweepfile s;
  hd_error err;
  hd_error_clear(&err);
  int rc = hd_sweepfile_parse(&s, (const char *)data, size, "fuzz.ini", &err);
  if (rc == HD_OK) {
    if (!s.scene || !s.scene[0] || s.scene_line < 1) abort();
    if (s.nax && s.npoints) abort();
    for (int k = 0; k < s.nax; k++) {
      if (s.ax[k].n < 1 || !strchr(s.ax[k].key, '.')) abort();
      /* none twice: sorted copies side by side (an axis may hold HD_SWEEP_MAX_VALUES values) */
      const char **c = malloc((size_t)s.ax[k].n * sizeof *c);
      if (!c) abort();
      for (int j = 0; j < s.ax[k].n; j++) {
        if (!s.ax[k].v[j][0]) abort();
        c[j] = s.ax[k].v[j];
        if (!strchr(s.ax[k].v[j], '"')) round_trip(s.ax[k].key, s.ax[k].v[j]);
      }
      qsort(c, (size_t)s.ax[k].n, sizeof *c, cmp_str);
      for (int j = 1; j < s.ax[k].n; j++)
        if (!strcmp(c[j - 1], c[j])) abort();
      free(c);
    }
    for (int j = 0; j < s.seeds.n; j++)
      if (!s.seeds.v[j][0] || strspn(s.seeds.v[j], "0123456789") != strlen(s.seeds.v[j])) abort();
    for (int k = 0; k < s.npoints; k++) {
      char *buf = NULL;
      const char *w[64];
      if (hd_sweep_split(s.points[k], &buf, w, 64) < 1) abort();
      free(buf);
    }
    hd_sweepfile_free(&s);
  } else {
    if (!err.msg[0]) abort(); /* a refusal says why */
    for (const char *p = err.msg; *p; p++)
      if ((unsigned char)*p < 0x20 || *p == 0x7f) abort();   /* on one printable line */
    if (s.nax || s.npoints || s.scene || s.seeds.v) abort(); /* freed */
  }
  return 0;
}
