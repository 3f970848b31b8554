#!/usr/bin/env bash
# tests/slurm/run.sh: `haff sweep --slurm` against a real Slurm, started here and stopped after.
#
# Starts munged, slurmctld and slurmd on this machine (one node, 127.0.0.1, configuration and
# state in a temporary folder, no systemd; the Debian packages slurm-wlm and munge are installed
# when missing and we are root), submits a sweep of 4 points as a job array with its afterok
# merge job, stops one task mid-run with `scancel --signal=TERM`, checks that the merge job did
# not run and that --status says 'interrupted', resumes with `haff sweep --resume --slurm` (a
# new array of that point alone, and a new merge job), and checks the merged study: 4 done runs,
# each with its Slurm job and task in `provenance`, the resumed one with exactly the events of
# the same point run uninterrupted.  Every wait has a timeout; a trap stops every daemon and job.
# Prints a cmocka-style summary ("[  PASSED  ] 1 test(s)." or "[  FAILED  ] 1 test(s)") that
# tests/run-tests counts.  First, `--slurm --dry-run` job scripts (a folder with a blank, a quote
# and a %, and --sbatch options) must pass `sbatch --test-only`.  HAFF_BIN: the binary (default bin/haff).
set -u
HAFF=${HAFF_BIN:-$PWD/bin/haff}
HAFF=$(readlink -f "$HAFF")
say() { echo "slurm-test: $*" >&2; }
fail() { say "FAIL: $*"; for f in "$T"/log/*.log "$T"/study/logs/*; do [ -f "$f" ] && { echo "--- $f" >&2; tail -5 "$f" >&2; }; done
         echo "[  FAILED  ] 1 test(s), listed below:"; echo "[  FAILED  ] slurm_sweep"; exit 1; }
skip() { say "skipped: $*"; echo "[  SKIPPED ] slurm_sweep"; echo "[  PASSED  ] 0 test(s)."; exit 0; }

# --- packages -------------------------------------------------------------------------------
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  [ "$(id -u)" = 0 ] || skip "slurm-wlm and munge are not installed (apt-get install slurm-wlm munge)"
  say "installing slurm-wlm munge"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null 2>&1 ||
    { apt-get update -qq >/dev/null 2>&1 && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null 2>&1; } ||
    skip "cannot install slurm-wlm munge"
fi
[ "$(id -u)" = 0 ] || skip "needs root (slurmd runs jobs as their user)"

T=$(mktemp -d /tmp/haff-slurm-XXXXXX)
PIDS=()
cleanup() {
  if [ -n "${SLURM_CONF:-}" ] && [ -f "$SLURM_CONF" ]; then
    # every job of this test cluster ends before its daemons do (slurmd would leave their
    # slurmstepd behind)
    timeout 10 scancel --quiet --full --signal=KILL --user=root >/dev/null 2>&1
    timeout 10 scancel --quiet --user=root >/dev/null 2>&1
    for _ in $(seq 100); do
      [ -z "$(timeout 5 squeue -h -o %i 2>/dev/null)" ] && break
      sleep 0.2
    done
  fi
  for p in "${PIDS[@]}"; do kill -TERM "$p" 2>/dev/null; done
  for p in "${PIDS[@]}"; do
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$p" 2>/dev/null
    wait "$p" 2>/dev/null
  done
  # job processes slurmd started and that outlived it (none expected)
  rm -rf "$T"
}
trap cleanup EXIT
trap 'exit 1' INT TERM
mkdir -p "$T/log" "$T/state" "$T/spool" "$T/munge"

# --- munge ----------------------------------------------------------------------------------
dd if=/dev/urandom of="$T/munge/munge.key" bs=1024 count=1 status=none
chmod 0400 "$T/munge/munge.key"
chmod 0755 "$T/munge"
munged --foreground --force --socket="$T/munge/sock" --key-file="$T/munge/munge.key" \
  --pid-file="$T/munge/pid" --log-file="$T/log/munged.log" --seed-file="$T/munge/seed" &
PIDS+=($!)
for i in $(seq 100); do [ -S "$T/munge/sock" ] && break; sleep 0.1; done
[ -S "$T/munge/sock" ] || fail "munged did not start"

# --- slurm ----------------------------------------------------------------------------------
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }
P1=$(free_port); P2=$(free_port)
NODE=$(hostname -s)
NCPU=$(nproc)
cat > "$T/slurm.conf" <<CONF
ClusterName=hafftest
SlurmctldHost=$NODE(127.0.0.1)
SlurmctldPort=$P1
SlurmdPort=$P2
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$T/munge/sock
CredType=cred/munge
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool/%n
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
SlurmdParameters=config_overrides
KillWait=5
MinJobAge=600
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=$NODE NodeAddr=127.0.0.1 CPUs=$NCPU State=UNKNOWN
PartitionName=debug Nodes=$NODE Default=YES MaxTime=30 State=UP
CONF
export SLURM_CONF=$T/slurm.conf
slurmctld -D -i -f "$SLURM_CONF" >"$T/log/slurmctld.out" 2>&1 &
PIDS+=($!)
slurmd -D -f "$SLURM_CONF" >"$T/log/slurmd.out" 2>&1 &
PIDS+=($!)
ok=0
for i in $(seq 300); do
  st=$(timeout 5 sinfo -h -n "$NODE" -o %T 2>/dev/null)
  case "$st" in idle*|mixed*|alloc*) ok=1; break ;; esac
  sleep 0.2
done
[ $ok = 1 ] || fail "the node did not come up (sinfo: '$st')"
say "slurm up on $NODE (ports $P1, $P2)"

# --- the sweep ------------------------------------------------------------------------------
cd "$T"
# 5e6 events (~5 s a point on an idle core): a run of 1e6 (~1 s) could end before the test saw
# its first commit (runs.events is written about once a second) and stopped it
cat > base.ini <<'INI'
[system]
area_fraction = 0.1
seed = 1
[disks]
count = 1000
alpha = 0.95
[run]
stop_events = 5000000
checkpoint_every = 0.2
[log]
collisions = none
samples_every = 5
INI
cat > sweep.ini <<'INI'
[sweep]
scene = base.ini
seeds = 1 2
[axes]
disks.alpha = 0.9 0.95
INI
# --dry-run: the scripts written, nothing submitted; sbatch --test-only takes them as they are,
# with the study folder quoted in #SBATCH --output (a blank, a quote and a %) and --sbatch's
# options (one quoted) passed through
dry=$(timeout 30 "$HAFF" sweep sweep.ini -o 'dry run "%x' --slurm --dry-run --time 5 \
  --partition debug --sbatch '--nice=5 --comment "a study, dry"' --drop-points) ||
  fail "haff sweep --slurm --dry-run failed"
[ -z "$(timeout 5 squeue -h -o %i 2>/dev/null)" ] || fail "--dry-run submitted a job"
for f in "${dry%%$'\t'*}" "${dry##*$'\t'}"; do
  [ -f "$f" ] && bash -n "$f" || fail "--dry-run: no script $f, or not sh"
  out=$(timeout 30 sbatch --test-only "$f" 2>&1) || fail "sbatch --test-only $f: $out"
  grep -q -- '--nice=5 --comment "a study, dry"' "$f" || fail "--sbatch not in $f"
done
grep -q -- ' --merge .* --drop-points$' "${dry##*$'\t'}" || fail "--drop-points not in the merge job"
[ -f 'dry run "%x/manifest.tsv' ] || fail "--dry-run wrote no manifest"
say "ok: --dry-run scripts pass sbatch --test-only"

ids=$(timeout 30 "$HAFF" sweep sweep.ini -o study --slurm --time 5 --partition debug --progress 1) ||
  fail "haff sweep --slurm failed"
JOB=${ids%%$'\t'*}; MJOB=${ids##*$'\t'}
say "array $JOB, merge job $MJOB"
grep -q -- '--time=5' study/slurm/array-1.sh && grep -q -- '--partition=debug' study/slurm/array-1.sh ||
  fail "--time/--partition not in the job script"

# task 1 (point 1) running and past its first checkpoints: stop it with SIGTERM
ok=0
for i in $(seq 300); do
  st=$("$HAFF" sweep --status study 2>/dev/null | awk -F'\t' '$1 == 1 {print $2}')
  ev=$(sqlite3 study/points/p0001.db "SELECT events FROM runs" 2>/dev/null)
  [ "$st" = running ] && [ "${ev:-0}" -gt 0 ] && { ok=1; break; }
  sleep 0.1
done
[ $ok = 1 ] || fail "point 1 never ran (state '$st')"
# (scancel may answer "Job can not be altered now" for an array task while it signals its
# step: what counts is that the point ends interrupted, checked below)
timeout 10 scancel --signal=TERM "${JOB}_1" || say "scancel --signal=TERM exited with status $?"
# every task of the array ends (the others go on to done)
ok=0
for i in $(seq 600); do
  [ -z "$(timeout 5 squeue -h -j "$JOB" -o %i 2>/dev/null)" ] && { ok=1; break; }
  sleep 0.2
done
[ $ok = 1 ] || fail "the array did not end"
status=$("$HAFF" sweep --status study 2>/dev/null)
echo "$status" | awk -F'\t' '$1 == 1 {print $2}' | grep -qx interrupted ||
  fail "point 1 is not interrupted: $(echo "$status" | sed -n 3p)"
n_done=$(echo "$status" | awk -F'\t' '$2 == "done"' | wc -l)
[ "$n_done" = 3 ] || fail "$n_done points done, 3 expected"
[ ! -e study/study.db ] || fail "the merge ran although a task failed"
mstate=$(timeout 5 squeue -h -j "$MJOB" -o %r 2>/dev/null)
say "merge job $MJOB after the failed array: '${mstate:-gone}'"
timeout 10 scancel "$MJOB" 2>/dev/null

# resume: a new array of the interrupted point, and a new merge job
ids=$(timeout 30 "$HAFF" sweep --resume study --slurm --time 5) || fail "haff sweep --resume --slurm failed"
JOB2=${ids%%$'\t'*}; MJOB2=${ids##*$'\t'}
grep -qx 1 study/slurm/todo-2.txt && [ "$(wc -l < study/slurm/todo-2.txt)" = 1 ] ||
  fail "the new array is not point 1 alone"
ok=0
for i in $(seq 900); do
  [ -z "$(timeout 5 squeue -h -j "$JOB2,$MJOB2" -o %i 2>/dev/null)" ] && [ -e study/study.db ] && { ok=1; break; }
  sleep 0.2
done
[ $ok = 1 ] || fail "the resumed array and its merge did not end"
runs=$(sqlite3 study/study.db "SELECT count(*) FROM runs WHERE status = 'done'")
[ "$runs" = 4 ] || fail "study.db holds $runs done runs, 4 expected"
prov=$(sqlite3 study/study.db "SELECT count(*) FROM provenance WHERE slurm_job IS NOT NULL AND slurm_task IS NOT NULL AND source LIKE '%/points/p%.db'")
[ "$prov" = 4 ] || fail "provenance of $prov runs, 4 expected"
# the resumed point ends exactly as the same point run without a stop
"$HAFF" run base.ini -o ref.db --set disks.alpha=0.9 --set system.seed=2 --quiet || fail "reference run"
a=$(sqlite3 study/points/p0001.db "SELECT events || ' ' || (SELECT group_concat(x || ',' || vx) FROM (SELECT x, vx FROM states WHERE label = 'final' ORDER BY body LIMIT 50)) FROM runs")
b=$(sqlite3 ref.db "SELECT events || ' ' || (SELECT group_concat(x || ',' || vx) FROM (SELECT x, vx FROM states WHERE label = 'final' ORDER BY body LIMIT 50)) FROM runs")
[ -n "$a" ] && [ "$a" = "$b" ] || fail "the resumed point differs from an uninterrupted run"
grep -q "interrupted" study/logs/p0001.log || fail "point 1's log does not say it was interrupted"
grep -q "haff: .* run 1: .* events" study/logs/p0001.log || fail "no progress line in the batch log"
say "ok: array, SIGTERM, resume as a new array, afterok merge"
echo "[  PASSED  ] 1 test(s)."
