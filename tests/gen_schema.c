/* `make schema`: rewrites the CREATE TABLE of `collisions` in db/schema.sql from the column
 * table HD_COLLISION_COLUMNS (db/hd_db.h, hd_db_collisions_create_sql); the rest of the file
 * is left as it is.  Usage: gen_schema FILE [--check]; with --check it writes nothing and exits
 * 1 when FILE differs from what the table gives.  tests/test_db.c makes the same check in
 * `make test`. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gen_file.h"
#include "hd_db.h"

/* in with its CREATE TABLE of collisions (to the first "\n);\n" after it) made anew */
static int make(const char *in, char **out, char *why, size_t why_size) {
  const char *head = "CREATE TABLE IF NOT EXISTS collisions (\n", *end = "\n);\n";
  const char *a = strstr(in, head), *b = a ? strstr(a, end) : NULL;
  char *gen = hd_db_collisions_create_sql();
  size_t pre = a ? (size_t)(a - in) : 0, ng = gen ? strlen(gen) : 0;
  if (a && b && gen) {
    b += strlen(end);
    *out = malloc(pre + ng + strlen(b) + 1);
  }
  if (!a || !b || !gen || !*out) {
    snprintf(why, why_size, "%s",
             gen && (!a || !b) ? "no \"CREATE TABLE IF NOT EXISTS collisions (\" ... \");\" in it"
                               : "out of memory");
    free(gen);
    return 1;
  }
  memcpy(*out, in, pre);
  memcpy(*out + pre, gen, ng);
  strcpy(*out + pre + ng, b);
  free(gen);
  return 0;
}

int main(int argc, char **argv) {
  const gen_file g = {
      "gen_schema", "db/schema.sql", "column table", "schema", "collisions table rewritten", make};
  return gen_file_main(&g, argc, argv);
}
