#!/usr/bin/env bash
# plots/scripts/fig1data.sh DB [LABEL] > fig1.tsv
# Every disk of the newest run's LABEL state (default: final) in DB, wrapped into the periodic
# box: columns x y r speed (speed: |V| of the dimer's centre of mass), one row per disk, and
# again at each periodic image within r of the box (a disk over an edge shows on both sides).
# The first line is '# box Lx Ly cpd C t T N n' (the state's cpd and time, the dimers).
# Dimer geometry (a, d) is read from runs.scene.
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
read -r cpd t n < <(q "SELECT round(cpd, 2), t, count(*) FROM states WHERE run = $run AND
  label = '$label' AND kind = 'dimer'" | tr '\t' ' ')
echo "# box $lx $ly cpd $cpd t $t N $n"
q "WITH s AS (SELECT x, y, phi, sqrt(vx * vx + vy * vy) AS v FROM states
              WHERE run = $run AND label = '$label' AND kind = 'dimer'),
   p AS (SELECT x - 0.5 * $a * cos(phi) AS px, y - 0.5 * $a * sin(phi) AS py, v FROM s
         UNION ALL
         SELECT x + 0.5 * $a * cos(phi), y + 0.5 * $a * sin(phi), v FROM s),
   w AS (SELECT px - $lx * floor(px / $lx) AS x, py - $ly * floor(py / $ly) AS y, v FROM p),
   i(dx, dy) AS (VALUES (0, 0), (1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (1, -1), (-1, 1),
                        (-1, -1))
   SELECT x + dx * $lx, y + dy * $ly, 0.5 * $d, v FROM w, i
   WHERE x + dx * $lx > -0.5 * $d AND x + dx * $lx < $lx + 0.5 * $d
     AND y + dy * $ly > -0.5 * $d AND y + dy * $ly < $ly + 0.5 * $d"
