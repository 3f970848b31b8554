#!/bin/sh
# Rod ring benchmark: collisions per second and the paper's run (10^4 rods, gamma = 0.8,
# N_mod = 1000, to t = 10^5, tabulated eps).  Usage: bench/rods.sh [HAFF]  (default bin/haff)
set -e
HAFF=${1:-bin/haff}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
dir=$(dirname "$0")/../scenes
run() { # name scene-file extra --set args
  name=$1; shift
  s=$(date +%s.%N)
  "$HAFF" run "$@" -o "$tmp/$name.db" --quiet || true
  e=$(date +%s.%N)
  ev=$(sqlite3 "$tmp/$name.db" "select events from runs order by id desc limit 1")
  awk -v n="$name" -v ev="$ev" -v s="$s" -v e="$e" \
    'BEGIN { printf "%-28s %12d collisions %8.2f s %12.0f collisions/s\n", n, ev, e - s, ev / (e - s) }'
}
run paper-table "$dir/rods-paper.ini"
run paper-direct-1e6 "$dir/rods-paper.ini" --set rods.table=no --set run.stop_events=1000000
run constant-1e4-until-collapse "$dir/rods-paper.ini" --set rods.table=no --set rods.model=constant
