#!/usr/bin/env bash
# plots/scripts/fig1data.sh DB [LABEL] > fig1.tsv
# Every disk of the newest run's LABEL state (default: final) in DB, wrapped into the periodic
# box: columns x y r speed (speed: |V| of the dimer's centre of mass), one row per disk.
# The first line is '# box Lx Ly'.  Dimer geometry (a, d) is read from runs.scene.
set -eu
db=$1 label=${2:-final}
q() { sqlite3 -separator $'\t' "$db" "$1"; }
run=$(q "SELECT max(id) FROM runs")
scene=$(q "SELECT scene FROM runs WHERE id = $run")
key() { # value of KEY in [dimers] of the stored canonical scene, or the default $2
  awk -v k="$1" -v def="$2" '/^\[/ { s = $0 } s == "[dimers]" && $1 == k { v = $3 }
       END { print (v == "" ? def : v) }' <<< "$scene"; }
a=$(key a 1) d=$(key d 1)
read -r lx ly < <(q "SELECT box_x, box_y FROM runs WHERE id = $run" | tr '\t' ' ')
echo "# box $lx $ly"
q "WITH s AS (SELECT x, y, phi, sqrt(vx * vx + vy * vy) AS v FROM states
              WHERE run = $run AND label = '$label' AND kind = 'dimer'),
   p AS (SELECT x - 0.5 * $a * cos(phi) AS px, y - 0.5 * $a * sin(phi) AS py, v FROM s
         UNION ALL
         SELECT x + 0.5 * $a * cos(phi), y + 0.5 * $a * sin(phi), v FROM s)
   SELECT px - $lx * floor(px / $lx), py - $ly * floor(py / $ly), 0.5 * $d, v FROM p"
