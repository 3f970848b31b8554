/* hd_scene_csv: [init] state CSV files (hd_state_csv_read_species, hd_scene.h): a header
 * kind,x,y,phi,vx,vy,omega and one row per body. */
#include "hd_scene_internal.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const char *const csv_col[7] = {"kind", "x", "y", "phi", "vx", "vy", "omega"};

static void rstrip(char *s) {
  size_t n = strlen(s);
  while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r' || s[n - 1] == '\n'))
    s[--n] = '\0';
}

/* Parses one data line (already right-stripped) into *r; `kind` may name one of sc's species
 * (sc NULL: dimer and disk only). */
static int csv_row(char *line, const char *path, long lineno, const hd_scene *sc, hd_state_row *r,
                   hd_error *err) {
  char *f[8];
  int nf = 0;
  char *p = line;
  for (;;) {
    if (nf < 8) f[nf] = p;
    nf++;
    char *comma = strchr(p, ',');
    if (!comma) break;
    *comma = '\0';
    p = comma + 1;
  }
  if (nf != 7)
    return hd_error_set(err, HD_EINPUT, "%s:%ld: expected 7 columns (%s), found %d", path, lineno,
                        "kind,x,y,phi,vx,vy,omega", nf);
  char *kind = hd_scene_trim(f[0]);
  int oriented = 0; /* phi and omega are read */
  r->species = -1;
  if (!strcmp(kind, "dimer"))
    r->kind = HD_KIND_DIMER, r->species = 0, oriented = 1;
  else if (!strcmp(kind, "disk")) /* (a rough disk, q > 0, spins: its phi and omega too) */
    r->kind = HD_KIND_DISK, r->species = 1, oriented = sc && sc->disk_q > 0;
  for (int j = 0; sc && r->species < 0 && j < sc->n_named; j++)
    if (!strcmp(kind, sc->named[j].name)) {
      r->kind = sc->named[j].ndisk >= 2 ? HD_KIND_DIMER : HD_KIND_DISK;
      oriented = sc->named[j].ndisk >= 2 || sc->named[j].q > 0;
      r->species = 2 + j;
    }
  if (r->species < 0) {
    char names[HD_MAX_SPECIES * (HD_SPECIES_NAME_MAX + 1)] = "";
    for (int j = 0; sc && j < sc->n_named; j++)
      strcat(names, " "), strcat(names, sc->named[j].name);
    return hd_error_set(err, HD_EINPUT, "%s:%ld: column 1 (kind): '%.40s' is not dimer or disk%s%s",
                        path, lineno, kind, names[0] ? ", nor a [species] of the scene:" : "",
                        names);
  }
  double v[7];
  for (int j = 1; j < 7; j++) {
    char *t = hd_scene_trim(f[j]);
    if (!hd_scene_parse_num(t, &v[j]))
      return hd_error_set(err, HD_EINPUT, "%s:%ld: column %d (%s): '%.40s': %s", path, lineno,
                          j + 1, csv_col[j], t, hd_scene_num_why(t));
  }
  r->x = v[1];
  r->y = v[2];
  r->phi = oriented ? v[3] : 0;
  r->vx = v[4];
  r->vy = v[5];
  r->omega = oriented ? v[6] : 0;
  r->line = lineno;
  return HD_OK;
}

/* One line of fp into line (room for max + 1 bytes, NUL-terminated, newline dropped): its
 * length, -1 at the end of the file, -2 when it is longer than max (the rest is not read). */
static long bounded_line(FILE *fp, char *line, long max) {
  long k = 0;
  int ch;
  while ((ch = getc_unlocked(fp)) != EOF && ch != '\n') {
    if (k == max) return -2;
    line[k++] = (char)ch;
  }
  line[k] = '\0';
  return ch == EOF && k == 0 ? -1 : k;
}

int hd_state_csv_read_species(const char *path, const hd_scene *sc, hd_state_row **rows, long *n,
                              hd_error *err) {
  *rows = NULL;
  *n = 0;
  struct stat st;
  if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) /* /dev/zero grew memory until it ran out */
    return hd_error_set(err, HD_EINPUT, "%s: cannot read state file: not a regular file", path);
  FILE *fp = fopen(path, "r");
  if (!fp)
    return hd_error_set(err, HD_EIO, "%s: cannot read state file: %s", path, strerror(errno));
  char line[HD_STATE_MAX_LINE + 1];
  long lineno = 0, nrow = 0, rcap = 0;
  hd_state_row *out = NULL;
  int rc = HD_OK;
  long got;
  while (!rc && (got = bounded_line(fp, line, HD_STATE_MAX_LINE)) != -1) {
    lineno++;
    if (got == -2) {
      rc = hd_error_set(err, HD_EINPUT, "%s:%ld: line longer than %d bytes: not a state file", path,
                        lineno, HD_STATE_MAX_LINE);
      break;
    }
    if (nrow >= 2 * HD_MAX_COUNT) {
      rc = hd_error_set(err, HD_EINPUT, "%s:%ld: more than %ld bodies", path, lineno,
                        2 * HD_MAX_COUNT);
      break;
    }
    if (memchr(line, '\0', (size_t)got)) {
      rc = hd_error_set(err, HD_EINPUT, "%s:%ld: contains a NUL byte: not a text file", path,
                        lineno);
      break;
    }
    rstrip(line);
    if (lineno == 1) {
      /* a UTF-8 byte order mark (spreadsheets write one) is skipped, as in scene files */
      if (!strncmp(line, "\xEF\xBB\xBF", 3)) memmove(line, line + 3, strlen(line + 3) + 1);
      if (strcmp(line, "kind,x,y,phi,vx,vy,omega"))
        rc = hd_error_set(err, HD_EINPUT,
                          "%s:1: missing header: expected kind,x,y,phi,vx,vy,omega, found '%.60s'",
                          path, line);
      continue;
    }
    if (!line[0]) continue; /* blank line */
    if (nrow == rcap) {
      rcap = 2 * rcap + 64;
      hd_state_row *nr = realloc(out, (size_t)rcap * sizeof *out);
      if (!nr) {
        rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", path);
        break;
      }
      out = nr;
    }
    rc = csv_row(line, path, lineno, sc, &out[nrow], err);
    if (!rc) nrow++;
  }
  if (!rc && ferror(fp)) rc = hd_error_set(err, HD_EIO, "%s: read error", path);
  if (!rc && lineno == 0)
    rc = hd_error_set(err, HD_EINPUT, "%s:1: empty file: expected header kind,x,y,phi,vx,vy,omega",
                      path);
  if (!rc && nrow == 0)
    rc = hd_error_set(err, HD_EINPUT, "%s:%ld: no bodies after the header", path, lineno);
  fclose(fp);
  if (rc) {
    free(out);
    return rc;
  }
  *rows = out;
  *n = nrow;
  hd_error_clear(err);
  return HD_OK;
}
