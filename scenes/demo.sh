#!/usr/bin/env bash
# make demo: runs scenes/demo.ini into runs/demo.db and shows what the database holds.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p runs
db=runs/demo.db
rm -f "$db" "$db-wal" "$db-shm"
echo "== haff run scenes/demo.ini -o $db"
bin/haff run scenes/demo.ini -o "$db"
echo
echo "== the run"
sqlite3 -header -column "$db" "SELECT id, status, events, round(wall_seconds, 2) AS seconds,
  (SELECT count(*) FROM collisions) AS collisions_logged FROM runs"
echo
echo "== collisions per kind"
sqlite3 -header -column "$db" < db/queries/collisions_per_kind.sql
echo
echo "== mean orientation factor <f> of the dimer-dimer collisions (paper: 0.64 for a = d)"
sqlite3 -header -column "$db" < db/queries/mean_f_per_run.sql
echo
echo "== energy per dimer and K = E_tr/E_rot every 50 cpd (Haff: ln E falls linearly in cpd)"
sqlite3 -header -column "$db" "SELECT round(cpd, 1) AS cpd, printf('%.4g', s.t) AS time,
  printf('%.5g', e_tr + e_rot) AS energy, printf('%.4f', e_tr / e_rot) AS K
  FROM samples s WHERE abs(cpd - 50 * round(cpd / 50)) < 1e-9 ORDER BY s.t"
echo
echo "== eq. (31) fitted to this run: D_e and nu0_eff (paper, Table I: D_e ~ 3)"
bin/haff haff-fit "$db" || true
echo "(*_fit_err: the fit's formal error; runs of other seeds scatter ~10x more, and"
echo " 'haff table1' over several runs gives the standard error: docs/analysis.md)"
echo
# the tables and views the file holds, from the file itself (sqlite3 .tables lists them all)
echo "Query it yourself:  sqlite3 $db   (tables and views: $(sqlite3 "$db" \
  "SELECT group_concat(name, ' ') FROM (SELECT name FROM sqlite_schema WHERE type IN ('table', \
  'view') AND name NOT LIKE 'sqlite%' ORDER BY type, name)"); db/schema.sql documents them)"
