#!/usr/bin/env bash
# plots/scripts/merge.sh HAFF OUT.db IN.db...
# Remakes OUT.db from the per-run databases with `haff merge` (db/hd_merge.h): every run of every
# input gets a new id and its rows in collisions, samples, states, checkpoints and plots_runs
# follow it; a file given twice or a run present twice is refused.  OUT is built beside itself
# and renamed into place, so an interrupted make leaves the old OUT whole.
set -eu
haff=$1 out=$2
shift 2
[ $# -ge 1 ] || { echo "merge.sh: no input databases" >&2; exit 2; }
rm -f "$out.new"
"$haff" merge --quiet "$out.new" "$@"
mv "$out.new" "$out"
