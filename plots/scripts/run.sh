#!/usr/bin/env bash
# plots/scripts/run.sh HAFF DB SCENE [haff run options...]
# One run of `haff run SCENE ...` into a fresh database DB (written as DB.tmp, moved into place
# only when complete, so an interrupted make leaves no half-made target).  The CPU seconds of
# the run (user + sys of the haff process, from the shell's `times`) are stored in DB as the
# extra table plots_runs(run, file, cpu_seconds): runs.wall_seconds is wall-clock time, which
# on a shared machine measures the load as much as the cost.  A run that ends in inelastic
# collapse (exit status 1, runs.status = 'collapsed') is kept with a warning: its samples
# before the collapse are valid and the analysis uses them.  Any other failure fails.
set -u
haff=$1 db=$2
shift 2
tmp=$db.tmp
rm -f "$db" "$db-wal" "$db-shm" "$tmp" "$tmp-wal" "$tmp-shm"
mkdir -p "$(dirname "$db")"
"$haff" run "$@" -o "$tmp" --quiet
rc=$?
# second line of `times`: user and system time of the finished children, e.g. 0m0.380s 0m0.004s
times > "$tmp.times"   # a builtin in this shell: $(times) would run in a subshell
cpu=$(tail -n 1 "$tmp.times" | awk '{ s = 0; for (i = 1; i <= 2; i++) { split($i, p, "m");
      sub("s", "", p[2]); s += 60 * p[1] + p[2] } printf "%.4f", s }')
rm -f "$tmp.times"
if [ "$rc" -ne 0 ]; then
  status=$(sqlite3 "$tmp" "SELECT status FROM runs ORDER BY id DESC LIMIT 1" 2>/dev/null)
  if [ "$rc" -eq 1 ] && [ "$status" = collapsed ]; then
    echo "run.sh: $db: the run collapsed (kept: its samples before the collapse are valid)" >&2
  else
    echo "run.sh: $db: haff run failed (exit $rc, status '${status:-?}')" >&2
    rm -f "$tmp" "$tmp-wal" "$tmp-shm"
    exit 1
  fi
fi
sqlite3 "$tmp" "PRAGMA journal_mode = DELETE;
  CREATE TABLE IF NOT EXISTS plots_runs (run INTEGER, file TEXT, cpu_seconds REAL);
  INSERT INTO plots_runs SELECT id, '$(basename "$db")', $cpu FROM runs;" >/dev/null || exit 1
mv "$tmp" "$db"
