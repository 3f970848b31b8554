#!/usr/bin/env bash
# plots/scripts/merge.sh OUT.db IN.db...
# Merges haff databases into one: every run of every input gets a new id (the inputs' ids
# shifted past the runs already merged) and its rows in collisions, samples, states and
# plots_runs follow it.  Checkpoints are left out (they only serve `haff resume` of the single
# run databases, which stay).  Uses the sqlite3 shell with ATTACH; the inputs are read only.
set -eu
out=$1
shift
[ $# -ge 1 ] || { echo "merge.sh: no input databases" >&2; exit 2; }
tmp=$out.tmp
rm -f "$tmp" "$tmp-journal"
# the schema of the first input (every input was made by the same bin/haff)
sqlite3 "$1" .schema | grep -v '^CREATE TABLE sqlite_' | sqlite3 "$tmp"
cols() { sqlite3 "$tmp" "SELECT group_concat(name, ',') FROM pragma_table_info('$1')"; }
exprs() { # the column list with the run id shifted
  sqlite3 "$tmp" "SELECT group_concat(CASE WHEN name = '$2' THEN name || ' + (SELECT v FROM temp.o)'
                  ELSE name END, ',') FROM pragma_table_info('$1')"; }
tables="collisions samples states"
have_pr=$(sqlite3 "$tmp" "SELECT count(*) FROM sqlite_master WHERE name = 'plots_runs'")
[ "$have_pr" = 1 ] && tables="$tables plots_runs"
# column lists, read before the writer below opens the output
declare -A C E
C[runs]=$(cols runs) E[runs]=$(exprs runs id)
for t in $tables; do C[$t]=$(cols "$t") E[$t]=$(exprs "$t" run); done
{
  echo "PRAGMA main.journal_mode = OFF; PRAGMA main.synchronous = OFF;"
  echo "CREATE TEMP TABLE o (v INTEGER);"
  for f in "$@"; do
    echo "ATTACH '$f' AS s;"
    echo "BEGIN;"
    echo "DELETE FROM temp.o; INSERT INTO temp.o SELECT coalesce(max(id), 0) FROM main.runs;"
    echo "INSERT INTO main.runs (${C[runs]}) SELECT ${E[runs]} FROM s.runs;"
    for t in $tables; do
      echo "INSERT INTO main.$t (${C[$t]}) SELECT ${E[$t]} FROM s.$t;"
    done
    echo "COMMIT;"
    echo "DETACH s;"
  done
} | sqlite3 -bail "$tmp" >/dev/null
mv "$tmp" "$out"
