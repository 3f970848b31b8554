#!/usr/bin/env bash
# bench/reference-ab.sh OLD_BIN NEW_BIN: the four reference runs (pure disks, pure dimers, a
# disk-dimer mixture, dimers between walls) made by two builds of haff, compared bit for bit:
# every collision row (time, kind, bodies, disks, angles, f, dE, vn: all as IEEE doubles,
# %!.17g) and the final state of every body.  Then a run of OLD_BIN interrupted (SIGINT after
# 2 s) is resumed from its checkpoint by each build: both continuations must be identical (a
# checkpoint of the older build resumes in the newer one).  Prints one line per check,
# "identical" or the first difference, and exits 1 if any differs.  Small runs (~30 s in all);
# REF_CPD scales the four runs.
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 OLD_BIN NEW_BIN" >&2; exit 2; }
old=$1 new=$2
cpd=${REF_CPD:-40}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene() { # name: the scene text
  case $1 in
  disks) printf '[system]\narea_fraction = 0.3\nseed = 11\n[disks]\ncount = 2000\nalpha = 0.9\n' ;;
  dimers) printf '[system]\narea_fraction = 0.2\nseed = 12\n[dimers]\ncount = 1000\nalpha = 0.9\n' ;;
  mixture) printf '[system]\narea_fraction = 0.2\nseed = 13\n[dimers]\ncount = 500\na = 0.7\nalpha = 0.95\n[disks]\ncount = 500\nsigma = 1.3\nmass = 0.8\nalpha = 0.9\nalpha_dimer = 0.85\n' ;;
  walls) printf '[system]\nbox = 40 40\nseed = 14\n[dimers]\ncount = 400\nalpha = 0.9\n[walls]\nsides = left right bottom top\nalpha = 0.8\n' ;;
  esac
  printf '[run]\nstop_cpd = %s\n[log]\ncollisions = all\n' "$cpd"
}
# hex of every double: a difference in the last bit shows
dump() { # db
  sqlite3 "$1" "SELECT seq, printf('%!.17g', t), kind, i, j, disk_i, disk_j,
    printf('%!.17g|%!.17g|%!.17g|%!.17g|%!.17g', theta_i, theta_j, f, de, vn)
    FROM collisions ORDER BY seq" >"$1.coll"
  sqlite3 "$1" "SELECT body, kind, printf('%!.17g|%!.17g|%!.17g|%!.17g|%!.17g|%!.17g|%!.17g', t, x, y,
    phi, vx, vy, omega) FROM states WHERE label = 'final' ORDER BY body" >"$1.final"
}
bad=0
for name in disks dimers mixture walls; do
  scene $name >"$tmp/$name.ini"
  for side in old new; do
    bin=$old
    [ $side = new ] && bin=$new
    "$bin" run "$tmp/$name.ini" -o "$tmp/$name-$side.db" --quiet >/dev/null
    dump "$tmp/$name-$side.db"
  done
  n=$(wc -l <"$tmp/$name-old.db.coll")
  if [ "$n" -eq 0 ]; then
    echo "$name: no collisions logged"; bad=1
  elif cmp -s "$tmp/$name-old.db.coll" "$tmp/$name-new.db.coll" &&
       cmp -s "$tmp/$name-old.db.final" "$tmp/$name-new.db.final"; then
    echo "$name: identical ($n collisions, $(wc -l <"$tmp/$name-old.db.final") bodies' final states)"
  else
    bad=1
    echo "$name: DIFFERENT; first differing collision rows (old, new):"
    diff "$tmp/$name-old.db.coll" "$tmp/$name-new.db.coll" | head -4 || true
    diff "$tmp/$name-old.db.final" "$tmp/$name-new.db.final" | head -4 || true
  fi
done
# a checkpoint of OLD_BIN resumed by both builds
printf '[system]\narea_fraction = 0.2\nseed = 15\n[dimers]\ncount = 2000\nalpha = 0.95\n[disks]\ncount = 500\n[run]\nstop_cpd = 1500\ncheckpoint_every = 1\n' >"$tmp/ck.ini"
timeout -s INT 2 "$old" run "$tmp/ck.ini" -o "$tmp/ck-old.db" --quiet >/dev/null 2>&1 || true
if [ "$(sqlite3 "$tmp/ck-old.db" "SELECT status FROM runs")" != interrupted ]; then
  echo "checkpoint: the run of OLD_BIN was not interrupted (too fast a machine?): not checked"
else
  cp "$tmp/ck-old.db" "$tmp/ck-new.db"
  "$old" resume "$tmp/ck-old.db" --quiet >/dev/null
  "$new" resume "$tmp/ck-new.db" --quiet >/dev/null
  for side in old new; do dump "$tmp/ck-$side.db"; done
  if cmp -s "$tmp/ck-old.db.coll" "$tmp/ck-new.db.coll" &&
     cmp -s "$tmp/ck-old.db.final" "$tmp/ck-new.db.final"; then
    echo "checkpoint of OLD_BIN resumed by each: identical ($(wc -l <"$tmp/ck-old.db.coll") collisions)"
  else
    bad=1
    echo "checkpoint of OLD_BIN resumed by each: DIFFERENT"
    diff "$tmp/ck-old.db.coll" "$tmp/ck-new.db.coll" | head -4 || true
  fi
fi
exit $bad
