/* hd_path: see hd_path.h for the contract. */
#include "hd_path.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* path with its folder resolved (realpath of the folder, then the last name) into buf (size
 * PATH_MAX + NAME_MAX); NULL when the folder cannot be resolved. */
static const char *canonical(const char *path, char *buf, size_t size) {
  const char *slash = strrchr(path, '/');
  char dir[PATH_MAX], real[PATH_MAX];
  const char *name = slash ? slash + 1 : path;
  if (!slash)
    snprintf(dir, sizeof dir, ".");
  else if (slash == path)
    snprintf(dir, sizeof dir, "/");
  else
    snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path);
  if (!realpath(dir, real)) return NULL;
  int k = snprintf(buf, size, "%s/%s", strcmp(real, "/") ? real : "", name);
  return k >= 0 && (size_t)k < size ? buf : NULL;
}

/* Whether a and b name the same file: by device and inode when both exist, else (neither
 * exists: a log not made yet) by their canonical paths. */
static int same_file(const char *a, const char *b) {
  struct stat sa, sb;
  int ea = stat(a, &sa) == 0, eb = stat(b, &sb) == 0;
  if (ea && eb) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  if (ea != eb) return 0; /* one exists, the other not */
  char ca[2 * PATH_MAX], cb[2 * PATH_MAX];
  const char *pa = canonical(a, ca, sizeof ca), *pb = canonical(b, cb, sizeof cb);
  return pa && pb ? !strcmp(pa, pb) : !strcmp(a, b);
}

int hd_path_overwrites(const char *out, const char *in) {
  static const char *const side[] = {"", "-wal", "-shm", "-journal"};
  if (!out || !in || !*out || !*in) return 0;
  char real[PATH_MAX]; /* SQLite keeps the log of a linked database beside the file linked to */
  const char *names[2] = {in, realpath(in, real) ? real : in};
  for (int n = 0; n < 2; n++)
    for (size_t k = 0; k < sizeof side / sizeof *side; k++) {
      char p[PATH_MAX + 16];
      if (snprintf(p, sizeof p, "%s%s", names[n], side[k]) >= (int)sizeof p) continue;
      if (same_file(out, p)) return 1;
    }
  return 0;
}

int hd_path_folder_missing(const char *path, char *dir, size_t size) {
  if (size) dir[0] = 0;
  const char *slash = path ? strrchr(path, '/') : NULL;
  if (!slash || slash == path) return 0; /* the current folder, or / */
  size_t n = (size_t)(slash - path);
  while (n > 1 && path[n - 1] == '/') n--; /* a//b: the folder a */
  char d[PATH_MAX];
  if (n >= sizeof d) n = sizeof d - 1;
  memcpy(d, path, n);
  d[n] = 0;
  struct stat st;
  int e = stat(d, &st) == 0;
  if (e && S_ISDIR(st.st_mode)) return 0;
  if (size) snprintf(dir, size, "%s", d);
  return e ? 2 : 1;
}

int hd_path_is_sqlite(const char *path) {
  static const char magic[16] = "SQLite format 3"; /* and its NUL: the file's first 16 bytes */
  struct stat st;
  if (!path || stat(path, &st) != 0 || !S_ISREG(st.st_mode)) return 0;
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  char head[16];
  size_t k = fread(head, 1, sizeof head, f);
  fclose(f);
  return k == sizeof head && !memcmp(head, magic, sizeof head);
}
