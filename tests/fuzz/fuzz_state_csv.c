/* libFuzzer harness: the state CSV reader (hd_state_csv_read_species, no scene) on arbitrary
 * bytes, given to it as a file in memory (memfd; nothing is written to disk).  Every row it returns
 * must hold finite numbers, a known kind and an increasing line number; a refusal must say why on
 * one printable line.  Built and run by `make fuzz`. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <unistd.h>

#include "hd_body.h"
#include "hd_scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static int fd = -1;
  static char path[64];
  if (fd < 0) {
    fd = memfd_create("fuzz_state.csv", 0);
    if (fd < 0) abort();
    snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
  }
  if (ftruncate(fd, 0) || (size && pwrite(fd, data, size, 0) != (ssize_t)size)) abort();
  hd_state_row *rows = NULL;
  long n = 0;
  hd_error err;
  hd_error_clear(&err);
  int rc = hd_state_csv_read_species(path, NULL, &rows, &n, &err);
  if (rc == HD_OK) {
    if (n <= 0 || !rows) abort();
    for (long i = 0; i < n; i++) {
      const hd_state_row *r = &rows[i];
      if (r->kind != HD_KIND_DIMER && r->kind != HD_KIND_DISK) abort();
      if (!isfinite(r->x) || !isfinite(r->y) || !isfinite(r->phi) || !isfinite(r->vx) ||
          !isfinite(r->vy) || !isfinite(r->omega))
        abort();
      if (r->line < 2 || (i > 0 && r->line <= rows[i - 1].line)) abort();
    }
  } else {
    if (rows || n || !err.msg[0]) abort();
    for (const char *p = err.msg; *p; p++)
      if ((unsigned char)*p < 0x20 || *p == 0x7f) abort();
  }
  free(rows);
  return 0;
}
