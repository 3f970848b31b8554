/* `make schema`: rewrites the CREATE TABLE of `collisions` in db/schema.sql from the column
 * table HD_COLLISION_COLUMNS (db/hd_db.h, hd_db_collisions_create_sql); the rest of the file
 * is left as it is.  Usage: gen_schema FILE [--check]; with --check it writes nothing and exits
 * 1 when FILE differs from what the table gives.  tests/test_db.c makes the same check in
 * `make test`. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hd_db.h"

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: gen_schema db/schema.sql [--check]\n");
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
  const char *head = "CREATE TABLE IF NOT EXISTS collisions (\n";
  char *a = strstr(in, head), *b = a ? strstr(a, "\n);\n") : NULL;
  char *gen = hd_db_collisions_create_sql();
  if (!a || !b || !gen) {
    fprintf(stderr, "%s: %s\n", argv[1],
            gen ? "no \"CREATE TABLE IF NOT EXISTS collisions (\" ... \");\" in it"
                : "out of memory");
    free(gen);
    return 1;
  }
  b += strlen("\n);\n");
  int same = (size_t)(b - a) == strlen(gen) && !memcmp(a, gen, strlen(gen));
  if (argc > 2 && !strcmp(argv[2], "--check")) {
    if (!same) fprintf(stderr, "%s: not what the column table gives: run make schema\n", argv[1]);
    free(gen);
    return !same;
  }
  if (!same) {
    f = fopen(argv[1], "wb");
    if (!f || fwrite(in, 1, (size_t)(a - in), f) != (size_t)(a - in) || fputs(gen, f) == EOF ||
        fputs(b, f) == EOF || fclose(f) != 0) {
      perror(argv[1]);
      free(gen);
      return 1;
    }
  }
  printf("%s: %s\n", argv[1], same ? "up to date" : "collisions table rewritten");
  free(gen);
  return 0;
}
